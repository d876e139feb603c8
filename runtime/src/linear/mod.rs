//! Sparse linear algebra: a symmetric sparsity pattern shared by every matrix of a problem,
//! factorisations whose symbolic analysis is reused across numeric refactorisations, and the
//! shift-invert Lanczos solver of the linear buckling eigenproblem, and the dense vector kernels
//! ([`vector`]: dot product, norm, axpy) every solver shares.

pub mod eigen;
pub mod error;
pub mod factor;
pub mod ordering;
pub mod pattern;
pub mod split_solve;
pub mod vector;

pub use eigen::{BucklingMode, BucklingOptions, BucklingSolution, smallest_positive_buckling};
pub use factor::{FactorizationKind, LinearError, SparseFactorization};
pub use pattern::{SparseMatrix, SparsityPattern};
