//! Errors of the nonlinear and eigen solvers: each says where and why.

use crate::linear::LinearError;

/// A solver failure.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// A factorisation or linear solve failed.
    #[error("{context}: {source}")]
    Linear {
        /// What the solver was doing.
        context: String,
        /// The linear-algebra error (with the pivot's location).
        #[source]
        source: LinearError,
    },
    /// Newton did not reach the tolerance.
    #[error(
        "Newton at load {load:.6e}: no convergence after {iterations} iterations (relative residual {residual:.3e}, tolerance {tolerance:.1e})"
    )]
    NewtonDiverged {
        /// Load parameter.
        load: f64,
        /// Iterations made.
        iterations: usize,
        /// Last relative residual.
        residual: f64,
        /// Target.
        tolerance: f64,
    },
    /// NaN or infinity appeared.
    #[error("non-finite values in {location}")]
    NonFinite {
        /// Where.
        location: String,
    },
    /// The ANM series or step failed.
    #[error("path following at load {load:.6e}: {message}")]
    Path {
        /// Last accepted load.
        load: f64,
        /// Why.
        message: String,
    },
    /// No buckling load found.
    #[error("linear buckling: {0}")]
    Buckling(String),
}

impl SolveError {
    /// Wraps a linear-algebra error with context.
    pub fn linear(context: impl Into<String>) -> impl FnOnce(LinearError) -> SolveError {
        let context = context.into();
        move |source| SolveError::Linear { context, source }
    }
}
