//! Nonlinear and scalar solvers.

pub mod brent;
pub mod buckling;
pub mod error;
pub mod newton;

pub use error::SolveError;
pub mod anm;
pub mod ellipticity;
pub mod path;
pub mod riks;
pub mod wavenumber;
