//! Sparse linear algebra: a symmetric sparsity pattern shared by every matrix of a problem,
//! factorisations whose symbolic analysis is reused across numeric refactorisations, and the
//! shift-invert Lanczos solver of the linear buckling eigenproblem.

pub mod eigen;
pub mod error;
pub mod factor;
pub mod pattern;

pub use eigen::{BucklingMode, BucklingOptions, BucklingSolution, smallest_positive_buckling};
pub use factor::{FactorizationKind, LinearError, SparseFactorization};
pub use pattern::{SparseMatrix, SparsityPattern};
