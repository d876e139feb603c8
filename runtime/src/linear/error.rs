//! Errors of the sparse linear algebra, shared by the pattern, the factorisations and the
//! eigen-solver (its own module so that `pattern` and `factor` do not import each other).

/// Errors of the sparse linear algebra.
#[derive(thiserror::Error, Debug, Clone, PartialEq)]
pub enum LinearError {
    /// The matrix is (numerically) singular: the factorisation broke down at dof (column)
    /// `column`, where the pivot was `pivot`.
    #[error(
        "singular matrix: factorisation broke down at dof (column) {column} with pivot {pivot:e} \
         (is a rigid-body mode left unconstrained?)"
    )]
    Singular {
        /// Dof (column of the original matrix) at which the factorisation broke down.
        column: usize,
        /// Pivot value found there.
        pivot: f64,
    },
    /// A NaN or infinite value was found.
    #[error("non-finite value (NaN or infinity) in {what}")]
    NonFinite {
        /// Where the value was found.
        what: String,
    },
    /// An argument has the wrong length.
    #[error("dimension mismatch for {what}: expected {expected}, found {found}")]
    DimensionMismatch {
        /// Which argument.
        what: String,
        /// Expected length.
        expected: usize,
        /// Actual length.
        found: usize,
    },
    /// An index is not below the dimension.
    #[error("index {index} out of range for a matrix of dimension {dimension}")]
    IndexOutOfRange {
        /// The offending index.
        index: usize,
        /// Matrix dimension.
        dimension: usize,
    },
    /// An entry outside the sparsity pattern was written.
    #[error("entry ({row}, {column}) is not in the sparsity pattern")]
    StructuralZero {
        /// Row of the entry.
        row: usize,
        /// Column of the entry.
        column: usize,
    },
    /// The matrix does not have the pattern the factorisation was analysed for.
    #[error("the matrix does not have the sparsity pattern the factorisation was analysed for")]
    PatternMismatch,
    /// A solve was requested before a successful numeric factorisation.
    #[error("solve requested before a successful numeric factorisation")]
    NotFactorized,
    /// The buckling problem has no positive load factor.
    #[error(
        "no positive buckling load factor: the load stiffness B is positive semidefinite on the \
         explored subspace (most negative Ritz value of A⁻¹B was {most_negative_ritz_value:e}); \
         the load does not compress the structure"
    )]
    NoPositiveLoadFactor {
        /// Most negative Ritz value $`\mu`$ of $`A^{-1} B`$ found (non-negative up to noise).
        most_negative_ritz_value: f64,
    },
    /// The buckling eigen-solver did not reach the tolerance.
    #[error(
        "buckling eigen-solver did not converge: after {restarts} restarts ({iterations} operator \
         applications) the worst relative residual of the wanted modes is {residual:e}, above the \
         tolerance {tolerance:e}"
    )]
    NotConverged {
        /// Restarts performed.
        restarts: usize,
        /// Applications of $`A^{-1} B`$.
        iterations: usize,
        /// Worst relative residual reached.
        residual: f64,
        /// Requested tolerance.
        tolerance: f64,
    },
    /// Invalid solver option.
    #[error("invalid option: {what}")]
    InvalidOption {
        /// Description of the problem.
        what: String,
    },
    /// Failure inside faer (allocation, index overflow).
    #[error("sparse backend failure: {0}")]
    Backend(String),
}
