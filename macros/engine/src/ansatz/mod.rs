//! Envelope models derived from a microscopic energy: the method of Fourier series with slowly
//! variable coefficients (THEORY.md §3, the paper's (6)–(8), (14), (20)–(27), (63)–(64)),
//! automated.

pub mod coefficient;
pub mod polynomial;
pub mod rational;
