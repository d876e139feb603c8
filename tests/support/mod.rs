//! Test-support code shared by integration tests (each test file compiles its own copy).

pub mod kirchhoff_spectral;
