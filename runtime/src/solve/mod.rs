//! Solvers: Newton at a fixed load, linear buckling and the wavelength search, and path
//! following (the ANM and Newton–Riks) with the path tools they share.
//!
//! Layout (each module imports only the ones listed before it, besides `error` and `path`):
//! * [`error`]: [`SolveError`], what every solver returns on failure, saying where and why.
//! * [`path`]: the types of a path — points, events reported to an observer, why a path
//!   stopped, work counters ([`path::PathStatistics`]).
//! * [`linearization`]: the tangent assembled, factorised and counted, and the load tangent
//!   $`-K_t^{-1}\partial R/\partial\lambda`$ — used by Newton, buckling, the ANM and Riks.
//! * [`newton`]: Newton–Raphson at a fixed load.
//! * [`brent`]: scalar minimisers (Brent, successive parabolic interpolation).
//! * [`ellipticity`]: the Legendre–Hadamard check of a state.
//! * [`buckling`]: linear buckling about the pre-buckling state (Newton, then the eigen-solver).
//! * [`wavenumber`]: the critical load minimised over a model parameter (buckling, Brent).
//! * [`arc_length`]: the arc-length corrector and its geometry (chord, orientation, metric).
//! * [`landing`]: landing the last point of a path on an amplitude or load target
//!   (arc-length corrections), and the ANM's bisection onto `max_load` inside a step.
//! * [`riks`]: Newton–Riks path following (arc length, linearisation).
//! * [`anm`]: the Asymptotic Numerical Method (series, Padé; arc length, landing,
//!   linearisation, and the shift of `wavenumber` for its bifurcation prediction).
//! * [`follow`]: the one entry point an application calls — a path with the chosen method,
//!   landed on its target (ANM or Riks, landing).
//!
//! The solvers never print or write files: they return results and diagnostics and talk to the
//! application through path events.

pub mod error;
pub mod path;

pub mod linearization;
pub mod newton;

pub mod brent;
pub mod buckling;
pub mod ellipticity;
pub mod wavenumber;

pub mod arc_length;
pub mod landing;

pub mod anm;
pub mod follow;
pub mod riks;

pub use error::SolveError;
