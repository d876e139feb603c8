//! Truncated power series in the path parameter $`a`$ of the Asymptotic Numerical Method (ANM).
//!
//! * [`Series`]: a scalar truncated Taylor series $`x(a) = \sum_{k=0}^{n-1} x_k a^k`$ that
//!   implements [`Scalar`](crate::Scalar), so the generated model kernels run on it and return
//!   the Taylor coefficients of energies and residuals along the path.
//! * [`PathSeries`]: the vector series $`(U(a), \lambda(a))`$ of one ANM step, with the
//!   classical step length [`series_step_length`] and the bifurcation indicator
//!   [`geometric_ratio`].
//! * [`recurrence`]: the order-$`k`$ rules (product, quotient, reciprocal) that the generated
//!   Taylor-mode kernels apply to their per-point tapes.
//! * [`PadeApproximant`]: rational approximants with a common denominator that extend the
//!   validity range of a step ([`PadeApproximant::pade_step_length`]).
//! * [`ExponentialMap`]: the series re-expanded in $`s = \ln(1 + a/R)`$, which removes a
//!   singularity behind the step at $`a = -R`$ ([`singularity_behind`]).

mod mapped;
mod pade;
pub mod recurrence;
mod scalar_series;
mod vector_series;

pub use mapped::{ALTERNATING_COSINE_THRESHOLD, ExponentialMap, singularity_behind};
pub use pade::{GramSchmidt, PADE_POLE_SAFETY_FACTOR, PadeApproximant, SPURIOUS_RESIDUE};
pub use scalar_series::{MAX_SERIES_LEN, Series};
pub use vector_series::{
    GEOMETRIC_COSINE_THRESHOLD, GEOMETRIC_RATIO_TOLERANCE, PathSeries, geometric_ratio,
    series_step_length,
};

/// Errors of the series utilities (bad lengths, inconsistent vector series).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SeriesError {
    /// A scalar series length outside $`1..=`$ [`MAX_SERIES_LEN`].
    #[error("series length {requested} is outside the supported range 1..={maximum}")]
    LengthOutOfRange {
        /// The requested number of coefficients.
        requested: usize,
        /// The capacity [`MAX_SERIES_LEN`].
        maximum: usize,
    },
    /// A coefficient index at or beyond the live length of a scalar series.
    #[error("coefficient index {index} is out of range for a series of length {len}")]
    CoefficientOutOfRange {
        /// The requested coefficient index.
        index: usize,
        /// The live length of the series.
        len: usize,
    },
    /// A vector series without any coefficient (not even $`U_0`$).
    #[error("the path series has no coefficient (U_0 is missing)")]
    EmptySeries,
    /// Different numbers of displacement and load coefficients.
    #[error(
        "the path series has {displacement_orders} displacement coefficients but {load_orders} load coefficients"
    )]
    InconsistentOrders {
        /// Number of displacement vectors $`U_0, \dots, U_N`$.
        displacement_orders: usize,
        /// Number of load coefficients $`\lambda_0, \dots, \lambda_N`$.
        load_orders: usize,
    },
    /// A displacement coefficient whose dimension differs from that of $`U_0`$.
    #[error("displacement coefficient of order {order} has dimension {found}, expected {expected}")]
    DimensionMismatch {
        /// The order $`k`$ of the offending $`U_k`$.
        order: usize,
        /// Dimension of $`U_0`$.
        expected: usize,
        /// Dimension of $`U_k`$.
        found: usize,
    },
    /// Too few orders for the requested construction.
    #[error("at least {required} orders are required, the series has {found}")]
    TooFewOrders {
        /// Minimal truncation order $`N`$.
        required: usize,
        /// Truncation order $`N`$ of the series.
        found: usize,
    },
    /// A non-finite coefficient (NaN or infinity) in a vector series.
    #[error("the coefficient of order {order} contains a non-finite value")]
    NonFinite {
        /// The order $`k`$ of the offending coefficient.
        order: usize,
    },
}
