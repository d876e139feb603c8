//! Sparse factorisations of symmetric matrices with the symbolic analysis done once per pattern.
//!
//! The symbolic phase (fill-reducing ordering, elimination tree, structure of the factor) only
//! depends on the [`SparsityPattern`]; it is computed by [`SparseFactorization::analyze`] and
//! reused by every [`SparseFactorization::factorize`] (and shared by the factorisations
//! [`SparseFactorization::same_analysis`] makes). The ordering is faer's approximate minimum
//! degree or, from [`DISSECTION_FROM`] unknowns, the project's nested dissection
//! ([`super::ordering`]) when its factor costs less ([`factorization_work`]): on the plate's
//! elongated Q8 meshes it does (example 1 at 128 × 32: 44 % less work), on square grids it
//! does not. The numeric phase tries, in order,
//! 1. $`A = L L^\top`$ (Cholesky), which succeeds iff $`A`$ is numerically positive definite;
//! 2. $`A = L D L^\top`$ without pivoting on the same symbolic structure, accepted when no pivot
//!    $`d_k`$ is tiny relative to the scale of its column (and none grew excessively); the signs
//!    of $`d_k`$ give the inertia of $`A`$ (Sylvester's law);
//! 3. $`P A Q = L U`$ with partial pivoting (simplicial, COLAMD column ordering computed on first
//!    use and then reused), which also detects numerical singularity through its pivots.
//!
//! Solves with a supernodal $`LL^\top`$ or $`LDL^\top`$ factor of
//! [`super::split_solve::SPLIT_SOLVE_FROM`] unknowns or more substitute two halves of its
//! elimination tree on two cores ([`super::split_solve`]; the same bits on any number of
//! threads); smaller ones, and LU, use faer's sequential solve.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::cholesky::ldlt::factor::LdltRegularization;
use faer::linalg::cholesky::llt::factor::{LltError as DenseLltError, LltRegularization};
use faer::perm::PermRef;
use faer::sparse::linalg::LuError;
pub use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LdltRef, LltRef, SymbolicCholesky, SymbolicCholeskyRaw,
    SymmetricOrdering, factorize_symbolic_cholesky, supernodal::SupernodalLdltRef,
};
use faer::sparse::linalg::lu::{LuSymbolicParams, factorize_symbolic_lu, simplicial};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side};

pub use super::error::LinearError;
use super::pattern::{SparseMatrix, SparsityPattern};
use super::split_solve::{Diagonal, SPLIT_SOLVE_FROM, SolveSplit};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Pivots of $`L D L^\top`$ with $`|d_k| \le`$ this times the largest absolute entry of their
/// column are considered a breakdown of the pivot-free factorisation (fall back to LU).
const LDLT_TINY_PIVOT_RELATIVE: f64 = 1e-12;
/// Pivots of $`L D L^\top`$ with $`|d_k| \ge`$ this times their column scale signal harmful
/// element growth (fall back to LU).
const LDLT_GROWTH_RELATIVE: f64 = 1e10;
/// LU pivots with $`|u_{kk}| \le`$ this times the largest absolute entry of their column make the
/// matrix numerically singular.
const LU_SINGULAR_PIVOT_RELATIVE: f64 = 1e-13;

/// Which factorisation the last successful [`SparseFactorization::factorize`] produced.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FactorizationKind {
    /// $`A = L L^\top`$: $`A`$ is positive definite.
    Cholesky,
    /// $`A = L D L^\top`$ without pivoting: $`A`$ is symmetric indefinite (and not singular).
    SymmetricIndefinite,
    /// $`P A Q = L U`$ with partial pivoting.
    Lu,
}

/// State of the LU fallback: column ordering (computed on first use) and numeric factors.
struct LuFactors {
    col_perm_fwd: Vec<usize>,
    col_perm_inv: Vec<usize>,
    row_perm_fwd: Vec<usize>,
    row_perm_inv: Vec<usize>,
    numeric: simplicial::SimplicialLu<usize, f64>,
}

/// Sparse factorisation of a symmetric matrix with a reusable symbolic analysis.
///
/// Typical use: `analyze` once per pattern, then `factorize` + `solve_in_place` for each new
/// matrix on that pattern (Newton iterations, continuation steps).
pub struct SparseFactorization {
    dimension: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    /// Shared with the factorisations made from this one ([`SparseFactorization::same_analysis`]).
    symbolic: Option<std::sync::Arc<SymbolicCholesky<usize>>>,
    factor_values: Vec<f64>,
    factor_scratch: MemBuffer,
    lu: Option<LuFactors>,
    kind: Option<FactorizationKind>,
    negative_pivots: Option<usize>,
    /// Copy of the matrix values, kept for one step of iterative refinement after
    /// $`L D L^\top`$ solves.
    refinement_values: Vec<f64>,
    /// Wall time spent in [`SparseFactorization::solve_in_place`] since the analysis, in
    /// nanoseconds (atomic: solves take `&self`).
    solve_nanos: AtomicU64,
    /// The two-core substitution of a supernodal factor ([`super::split_solve`]), from
    /// [`super::split_solve::SPLIT_SOLVE_FROM`] unknowns; shared like the analysis.
    split: Option<std::sync::Arc<SolveSplit>>,
}

impl std::fmt::Debug for SparseFactorization {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        formatter
            .debug_struct("SparseFactorization")
            .field("dimension", &self.dimension)
            .field("factor_len", &self.factor_values.len())
            .field("kind", &self.kind)
            .field("negative_pivots", &self.negative_pivots)
            .finish_non_exhaustive()
    }
}

fn backend(error: impl std::fmt::Debug) -> LinearError {
    LinearError::Backend(format!("{error:?}"))
}

/// Which fill-reducing ordering an analysis uses ([`SparseFactorization::analyze`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OrderingChoice {
    /// The cheaper of the two below by the estimated factorisation work (the default).
    Cheaper,
    /// Approximate minimum degree (faer's).
    Amd,
    /// Nested dissection ([`super::ordering::nested_dissection`]).
    NestedDissection,
}

/// Floating-point operations of a numeric Cholesky factorisation with this structure, estimated
/// from its columns: $`\sum_j c_j^2`$ with $`c_j`$ the entries of column $`j`$ of $`L`$ below
/// the diagonal (one multiply–add per entry pair of the column's outer-product update).
pub fn factorization_work(symbolic: &SymbolicCholesky<usize>) -> f64 {
    match symbolic.raw() {
        SymbolicCholeskyRaw::Simplicial(simplicial) => simplicial
            .col_ptr()
            .windows(2)
            .map(|w| ((w[1] - w[0]) as f64).powi(2))
            .sum(),
        SymbolicCholeskyRaw::Supernodal(supernodal) => {
            let begin = supernodal.supernode_begin();
            let end = supernodal.supernode_end();
            let rows = supernodal.col_ptr_for_row_idx();
            (0..supernodal.n_supernodes())
                .map(|s| {
                    let width = (end[s] - begin[s]) as f64;
                    let below = (rows[s + 1] - rows[s]) as f64;
                    // Column k of the supernode has (width − k − 1) + below entries below
                    // its diagonal: Σ_k (width − k − 1 + below)².
                    (0..end[s] - begin[s])
                        .map(|k| (width - k as f64 - 1.0 + below).powi(2))
                        .sum::<f64>()
                })
                .sum()
        }
    }
}

/// The symbolic Cholesky analysis of `structure` with the ordering `choice`.
fn symbolic_with(
    pattern: &SparsityPattern,
    structure: SymbolicSparseColMatRef<'_, usize>,
    params: CholeskySymbolicParams<'_>,
    choice: OrderingChoice,
) -> Result<SymbolicCholesky<usize>, LinearError> {
    match choice {
        OrderingChoice::Amd | OrderingChoice::Cheaper => {
            factorize_symbolic_cholesky(structure, Side::Upper, SymmetricOrdering::Amd, params)
                .map_err(backend)
        }
        OrderingChoice::NestedDissection => {
            let forward = super::ordering::nested_dissection(pattern);
            let mut inverse = vec![0; forward.len()];
            for (new, &old) in forward.iter().enumerate() {
                inverse[old] = new;
            }
            let permutation = PermRef::new_checked(&forward, &inverse, forward.len());
            factorize_symbolic_cholesky(
                structure,
                Side::Upper,
                SymmetricOrdering::Custom(permutation),
                params,
            )
            .map_err(backend)
        }
    }
}

/// Scratch of one numeric factorisation, $`LL^\top`$ or $`LDL^\top`$, with this structure.
fn numeric_scratch(symbolic: &SymbolicCholesky<usize>) -> StackReq {
    StackReq::or(
        symbolic.factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default()),
        symbolic.factorize_numeric_ldlt_scratch::<f64>(Par::Seq, Default::default()),
    )
}

/// Below this many unknowns the analysis keeps AMD without trying nested dissection (its
/// factor is small either way, and the dissection's search would cost more than it saves).
pub const DISSECTION_FROM: usize = 20_000;

/// The symbolic analysis with the ordering `choice`; for [`OrderingChoice::Cheaper`], the one of
/// least [`factorization_work`] among AMD and nested dissection (AMD alone below
/// [`DISSECTION_FROM`] unknowns).
fn ordered_analysis(
    pattern: &SparsityPattern,
    structure: SymbolicSparseColMatRef<'_, usize>,
    params: CholeskySymbolicParams<'_>,
    choice: OrderingChoice,
) -> Result<SymbolicCholesky<usize>, LinearError> {
    if choice != OrderingChoice::Cheaper {
        return symbolic_with(pattern, structure, params, choice);
    }
    if pattern.dimension() < DISSECTION_FROM {
        return symbolic_with(pattern, structure, params, OrderingChoice::Amd);
    }
    // Two independent sequential analyses, one per core (each gives the same structure on any
    // number of threads, and the choice between them is by their work alone).
    let (amd, dissection) = rayon::join(
        || symbolic_with(pattern, structure, params, OrderingChoice::Amd),
        || symbolic_with(pattern, structure, params, OrderingChoice::NestedDissection),
    );
    let (amd, dissection) = (amd?, dissection?);
    Ok(
        if factorization_work(&dissection) < factorization_work(&amd) {
            dissection
        } else {
            amd
        },
    )
}

/// The ordering of [`SparseFactorization::analyze`]: [`OrderingChoice::Cheaper`], unless the
/// environment variable `WRINKLE_ORDERING` is `amd` or `nd` (to measure one against the other
/// on a whole run, docs/benchmarks.md; results agree to rounding).
pub fn default_ordering() -> OrderingChoice {
    match std::env::var("WRINKLE_ORDERING").as_deref() {
        Ok("amd") => OrderingChoice::Amd,
        Ok("nd") => OrderingChoice::NestedDissection,
        _ => OrderingChoice::Cheaper,
    }
}

impl SparseFactorization {
    /// Symbolic analysis of `pattern`: fill-reducing ordering ([`default_ordering`]: the
    /// cheaper of AMD and nested dissection), elimination tree and structure of the Cholesky
    /// factor (simplicial or supernodal, chosen by faer).
    pub fn analyze(pattern: &SparsityPattern) -> Result<Self, LinearError> {
        Self::analyze_with(pattern, SupernodalThreshold::AUTO, default_ordering())
    }

    /// As [`SparseFactorization::analyze`], with an explicit choice between the simplicial and
    /// supernodal Cholesky structures (for tests and tuning).
    pub fn analyze_with_threshold(
        pattern: &SparsityPattern,
        threshold: SupernodalThreshold,
    ) -> Result<Self, LinearError> {
        Self::analyze_with(pattern, threshold, default_ordering())
    }

    /// As [`SparseFactorization::analyze`], with the supernodal threshold and the ordering given.
    pub fn analyze_with(
        pattern: &SparsityPattern,
        threshold: SupernodalThreshold,
        ordering: OrderingChoice,
    ) -> Result<Self, LinearError> {
        let dimension = pattern.dimension();
        let mut factorization = Self {
            dimension,
            col_ptr: pattern.col_ptr().to_vec(),
            row_idx: pattern.row_idx().to_vec(),
            symbolic: None,
            factor_values: Vec::new(),
            factor_scratch: MemBuffer::new(StackReq::empty()),
            lu: None,
            kind: None,
            negative_pivots: None,
            refinement_values: Vec::new(),
            solve_nanos: AtomicU64::new(0),
            split: None,
        };
        if dimension == 0 {
            return Ok(factorization);
        }
        let structure = SymbolicSparseColMatRef::new_checked(
            dimension,
            dimension,
            pattern.col_ptr(),
            None,
            pattern.row_idx(),
        );
        let params = CholeskySymbolicParams {
            supernodal_flop_ratio_threshold: threshold,
            ..Default::default()
        };
        let symbolic = ordered_analysis(pattern, structure, params, ordering)?;
        factorization.factor_scratch =
            MemBuffer::try_new(numeric_scratch(&symbolic)).map_err(backend)?;
        factorization.factor_values = vec![0.0; symbolic.len_val()];
        factorization.symbolic = Some(std::sync::Arc::new(symbolic));
        if dimension >= SPLIT_SOLVE_FROM {
            factorization.set_split_solve(true);
        }
        Ok(factorization)
    }

    /// Factor entries of the split solve's top and two groups, when it is on.
    pub fn split_entries(&self) -> Option<[usize; 3]> {
        self.split.as_deref().map(SolveSplit::entries)
    }

    /// Whether solves with a supernodal factor substitute two halves of its elimination tree
    /// side by side ([`super::split_solve`]; the default from
    /// [`super::split_solve::SPLIT_SOLVE_FROM`] unknowns) or use faer's sequential solve. The
    /// split is kept only where it pays (a balanced one exists); returns whether it is on.
    pub fn set_split_solve(&mut self, enabled: bool) -> bool {
        self.split = match (enabled, self.symbolic.as_deref().map(SymbolicCholesky::raw)) {
            (true, Some(SymbolicCholeskyRaw::Supernodal(supernodal))) => {
                SolveSplit::new(supernodal).map(std::sync::Arc::new)
            }
            _ => None,
        };
        self.split.is_some()
    }

    /// A new, unfactorised factorisation of the same pattern sharing this one's symbolic
    /// analysis (ordering and factor structure): what [`SparseFactorization::analyze`] of the
    /// same pattern gives, without repeating the analysis.
    pub fn same_analysis(&self) -> Result<Self, LinearError> {
        Ok(Self {
            dimension: self.dimension,
            col_ptr: self.col_ptr.clone(),
            row_idx: self.row_idx.clone(),
            symbolic: self.symbolic.clone(),
            factor_values: vec![0.0; self.factor_values.len()],
            factor_scratch: MemBuffer::try_new(
                self.symbolic
                    .as_deref()
                    .map_or(StackReq::empty(), numeric_scratch),
            )
            .map_err(backend)?,
            lu: None,
            kind: None,
            negative_pivots: None,
            refinement_values: Vec::new(),
            solve_nanos: AtomicU64::new(0),
            split: self.split.clone(),
        })
    }

    /// Whether `other` shares this factorisation's symbolic analysis (made by
    /// [`Self::same_analysis`] of it, or it of `other`): the same ordering and factor structure.
    pub fn shares_analysis(&self, other: &Self) -> bool {
        match (&self.symbolic, &other.symbolic) {
            (Some(a), Some(b)) => std::sync::Arc::ptr_eq(a, b),
            _ => false,
        }
    }

    /// Estimated operations of one numeric factorisation ([`factorization_work`]; 0 before an
    /// analysis).
    pub fn work(&self) -> f64 {
        self.symbolic.as_deref().map_or(0.0, factorization_work)
    }

    /// Dimension of the analysed pattern.
    pub fn dimension(&self) -> usize {
        self.dimension
    }

    /// Seconds spent in [`SparseFactorization::solve_in_place`] since the analysis (all
    /// factorisations of this pattern together): a solver reads it before and after a phase
    /// to split that phase's time into solves and the rest.
    pub fn solve_seconds(&self) -> f64 {
        self.solve_nanos.load(Ordering::Relaxed) as f64 * 1e-9
    }

    /// Number of non-zeros of the Cholesky / $`L D L^\top`$ factor (fill-in included).
    pub fn factor_nnz(&self) -> usize {
        self.factor_values.len()
    }

    /// Numeric factorisation of `matrix`, which must have the analysed pattern: $`L L^\top`$
    /// first, $`L D L^\top`$ if $`A`$ is not positive definite, LU as the last fallback. Returns
    /// which factorisation succeeded, or [`LinearError::Singular`] naming the dof where it broke
    /// down.
    pub fn factorize(&mut self, matrix: &SparseMatrix) -> Result<FactorizationKind, LinearError> {
        self.kind = None;
        self.negative_pivots = None;
        let pattern = &matrix.pattern;
        if pattern.dimension() != self.dimension
            || pattern.col_ptr() != self.col_ptr
            || pattern.row_idx() != self.row_idx
        {
            return Err(LinearError::PatternMismatch);
        }
        if matrix.values.len() != pattern.nnz() {
            return Err(LinearError::DimensionMismatch {
                what: "matrix values".to_owned(),
                expected: pattern.nnz(),
                found: matrix.values.len(),
            });
        }
        if let Some(slot) = matrix.values.iter().position(|value| !value.is_finite()) {
            let column = self.col_ptr.partition_point(|&start| start <= slot) - 1;
            return Err(LinearError::NonFinite {
                what: format!(
                    "matrix entry ({}, {column}) = {}",
                    self.row_idx[slot], matrix.values[slot]
                ),
            });
        }
        let Some(symbolic) = self.symbolic.as_ref() else {
            self.kind = Some(FactorizationKind::Cholesky);
            self.negative_pivots = Some(0);
            return Ok(FactorizationKind::Cholesky);
        };
        let structure = SymbolicSparseColMatRef::new_checked(
            self.dimension,
            self.dimension,
            &self.col_ptr,
            None,
            &self.row_idx,
        );
        let a = SparseColMatRef::new(structure, &matrix.values);
        let stack = MemStack::new(&mut self.factor_scratch);
        let llt = symbolic.factorize_numeric_llt(
            &mut self.factor_values,
            a,
            Side::Upper,
            LltRegularization::default(),
            Par::Seq,
            stack,
            Default::default(),
        );
        match llt {
            Ok(_) => {
                self.kind = Some(FactorizationKind::Cholesky);
                self.negative_pivots = Some(0);
                return Ok(FactorizationKind::Cholesky);
            }
            Err(DenseLltError::NonPositivePivot { .. }) => {}
        }
        let column_scale = matrix.column_max_abs();
        let stack = MemStack::new(&mut self.factor_scratch);
        let ldlt = symbolic.factorize_numeric_ldlt(
            &mut self.factor_values,
            a,
            Side::Upper,
            LdltRegularization::default(),
            Par::Seq,
            stack,
            Default::default(),
        );
        if ldlt.is_ok()
            && let Some(negative) = self.accept_ldlt_pivots(&column_scale)
        {
            self.kind = Some(FactorizationKind::SymmetricIndefinite);
            self.negative_pivots = Some(negative);
            self.refinement_values.clone_from(&matrix.values);
            return Ok(FactorizationKind::SymmetricIndefinite);
        }
        self.factorize_lu(&matrix.values, &column_scale)?;
        self.kind = Some(FactorizationKind::Lu);
        Ok(FactorizationKind::Lu)
    }

    /// Pivots $`d_k`$ of the $`L D L^\top`$ factor in elimination order.
    fn ldlt_pivots(&self) -> Vec<f64> {
        let Some(symbolic) = self.symbolic.as_ref() else {
            return Vec::new();
        };
        match symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(simplicial_symbolic) => {
                let col_ptr = simplicial_symbolic.col_ptr();
                (0..self.dimension)
                    .map(|k| self.factor_values[col_ptr[k]])
                    .collect()
            }
            SymbolicCholeskyRaw::Supernodal(supernodal_symbolic) => {
                let factor = SupernodalLdltRef::new(supernodal_symbolic, &self.factor_values);
                let mut pivots = Vec::with_capacity(self.dimension);
                for supernode in 0..supernodal_symbolic.n_supernodes() {
                    let values = factor.supernode(supernode).val();
                    pivots.extend((0..values.ncols()).map(|j| values[(j, j)]));
                }
                pivots
            }
        }
    }

    /// Checks the $`L D L^\top`$ pivots; returns the number of negative ones when acceptable.
    fn accept_ldlt_pivots(&self, column_scale: &[f64]) -> Option<usize> {
        let symbolic = self.symbolic.as_ref()?;
        let pivots = self.ldlt_pivots();
        let forward = symbolic.perm().map(|perm| perm.arrays().0);
        let mut negative = 0;
        for (k, pivot) in pivots.iter().enumerate() {
            let column = forward.map_or(k, |forward| forward[k]);
            let scale = column_scale[column];
            let magnitude = pivot.abs();
            if !pivot.is_finite()
                || magnitude <= LDLT_TINY_PIVOT_RELATIVE * scale
                || magnitude >= LDLT_GROWTH_RELATIVE * scale
            {
                return None;
            }
            if *pivot < 0.0 {
                negative += 1;
            }
        }
        Some(negative)
    }

    fn factorize_lu(&mut self, values: &[f64], column_scale: &[f64]) -> Result<(), LinearError> {
        let n = self.dimension;
        let structure =
            SymbolicSparseColMatRef::new_checked(n, n, &self.col_ptr, None, &self.row_idx);
        let a = SparseColMatRef::new(structure, values);
        if self.lu.is_none() {
            let params = LuSymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SIMPLICIAL,
                ..Default::default()
            };
            let symbolic = factorize_symbolic_lu(a.symbolic(), params).map_err(backend)?;
            let (forward, inverse) = symbolic.col_perm().arrays();
            self.lu = Some(LuFactors {
                col_perm_fwd: forward.to_vec(),
                col_perm_inv: inverse.to_vec(),
                row_perm_fwd: vec![0; n],
                row_perm_inv: vec![0; n],
                numeric: simplicial::SimplicialLu::new(),
            });
        }
        let Some(lu) = self.lu.as_mut() else {
            return Err(LinearError::NotFactorized);
        };
        let mut buffer = MemBuffer::try_new(simplicial::factorize_simplicial_numeric_lu_scratch::<
            usize,
            f64,
        >(n, n))
        .map_err(backend)?;
        let col_perm = PermRef::new_checked(&lu.col_perm_fwd, &lu.col_perm_inv, n);
        let result = simplicial::factorize_simplicial_numeric_lu(
            &mut lu.row_perm_fwd,
            &mut lu.row_perm_inv,
            &mut lu.numeric,
            a,
            col_perm,
            MemStack::new(&mut buffer),
        );
        match result {
            Ok(()) => {}
            Err(LuError::SymbolicSingular { index }) => {
                return Err(LinearError::Singular {
                    column: lu.col_perm_fwd[index],
                    pivot: 0.0,
                });
            }
            Err(LuError::Generic(error)) => return Err(backend(error)),
        }
        let upper = lu.numeric.u_factor_unsorted();
        for step in 0..n {
            let rows = upper.symbolic().row_idx_of_col_raw(step);
            let values = upper.val_of_col(step);
            let pivot = rows
                .iter()
                .zip(values)
                .find(|(row, _)| **row == step)
                .map_or(0.0, |(_, value)| *value);
            let column = lu.col_perm_fwd[step];
            if !pivot.is_finite()
                || pivot.abs() <= LU_SINGULAR_PIVOT_RELATIVE * column_scale[column]
            {
                return Err(LinearError::Singular { column, pivot });
            }
        }
        Ok(())
    }

    /// Solves $`A x = b`$ in place (`rhs` holds $`b`$ on entry and $`x`$ on exit), after a
    /// successful [`SparseFactorization::factorize`]. After $`L D L^\top`$ one step of iterative
    /// refinement is applied.
    pub fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), LinearError> {
        let clock = Instant::now();
        let result = self.solve_untimed(rhs);
        let nanos = u64::try_from(clock.elapsed().as_nanos()).unwrap_or(u64::MAX);
        self.solve_nanos.fetch_add(nanos, Ordering::Relaxed);
        result
    }

    fn solve_untimed(&self, rhs: &mut [f64]) -> Result<(), LinearError> {
        let n = self.dimension;
        if rhs.len() != n {
            return Err(LinearError::DimensionMismatch {
                what: "right-hand side".to_owned(),
                expected: n,
                found: rhs.len(),
            });
        }
        let Some(kind) = self.kind else {
            return Err(LinearError::NotFactorized);
        };
        if rhs.iter().any(|value| !value.is_finite()) {
            return Err(LinearError::NonFinite {
                what: "right-hand side".to_owned(),
            });
        }
        if n == 0 {
            return Ok(());
        }
        if kind == FactorizationKind::SymmetricIndefinite {
            let original = rhs.to_vec();
            self.raw_solve(kind, rhs)?;
            let mut residual = vec![0.0; n];
            self.refinement_residual(&original, rhs, &mut residual);
            self.raw_solve(kind, &mut residual)?;
            for (value, correction) in rhs.iter_mut().zip(&residual) {
                *value += correction;
            }
        } else {
            self.raw_solve(kind, rhs)?;
        }
        if rhs.iter().any(|value| !value.is_finite()) {
            return Err(LinearError::NonFinite {
                what: "solution of the linear system".to_owned(),
            });
        }
        Ok(())
    }

    /// $`r = b - A x`$ with the stored copy of the matrix values.
    fn refinement_residual(&self, b: &[f64], x: &[f64], residual: &mut [f64]) {
        residual.copy_from_slice(b);
        for (column, &x_column) in x.iter().enumerate() {
            let range = self.col_ptr[column]..self.col_ptr[column + 1];
            for (&row, &value) in self.row_idx[range.clone()]
                .iter()
                .zip(&self.refinement_values[range])
            {
                residual[row] -= value * x_column;
            }
        }
    }

    fn raw_solve(&self, kind: FactorizationKind, rhs: &mut [f64]) -> Result<(), LinearError> {
        let n = self.dimension;
        match kind {
            FactorizationKind::Cholesky | FactorizationKind::SymmetricIndefinite => {
                let Some(symbolic) = self.symbolic.as_ref() else {
                    return Err(LinearError::NotFactorized);
                };
                if let (Some(split), SymbolicCholeskyRaw::Supernodal(supernodal)) =
                    (self.split.as_deref(), symbolic.raw())
                {
                    let diagonal = if kind == FactorizationKind::Cholesky {
                        Diagonal::Cholesky
                    } else {
                        Diagonal::Pivots
                    };
                    let mut permuted = match symbolic.perm() {
                        Some(permutation) => {
                            permutation.arrays().0.iter().map(|&old| rhs[old]).collect()
                        }
                        None => rhs.to_vec(),
                    };
                    split.solve_in_place(supernodal, &self.factor_values, diagonal, &mut permuted);
                    match symbolic.perm() {
                        Some(permutation) => {
                            for (value, &new) in rhs.iter_mut().zip(permutation.arrays().1) {
                                *value = permuted[new];
                            }
                        }
                        None => rhs.copy_from_slice(&permuted),
                    }
                    return Ok(());
                }
                let rhs_matrix = MatMut::from_column_major_slice_mut(rhs, n, 1);
                let mut buffer =
                    MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq))
                        .map_err(backend)?;
                let stack = MemStack::new(&mut buffer);
                if kind == FactorizationKind::Cholesky {
                    LltRef::new(symbolic, &self.factor_values).solve_in_place_with_conj(
                        Conj::No,
                        rhs_matrix,
                        Par::Seq,
                        stack,
                    );
                } else {
                    LdltRef::new(symbolic, &self.factor_values).solve_in_place_with_conj(
                        Conj::No,
                        rhs_matrix,
                        Par::Seq,
                        stack,
                    );
                }
            }
            FactorizationKind::Lu => {
                let Some(lu) = self.lu.as_ref() else {
                    return Err(LinearError::NotFactorized);
                };
                let rhs_matrix = MatMut::from_column_major_slice_mut(rhs, n, 1);
                let mut buffer = MemBuffer::try_new(
                    simplicial::solve_in_place_scratch::<usize, f64>(n, 1, Par::Seq),
                )
                .map_err(backend)?;
                lu.numeric.solve_in_place_with_conj(
                    PermRef::new_checked(&lu.row_perm_fwd, &lu.row_perm_inv, n),
                    PermRef::new_checked(&lu.col_perm_fwd, &lu.col_perm_inv, n),
                    Conj::No,
                    rhs_matrix,
                    Par::Seq,
                    MemStack::new(&mut buffer),
                );
            }
        }
        Ok(())
    }

    /// Kind of the last successful factorisation (`None` before one or after a failure).
    pub fn kind(&self) -> Option<FactorizationKind> {
        self.kind
    }

    /// Number of negative eigenvalues of $`A`$ (Sylvester inertia) when known: 0 after a
    /// successful $`L L^\top`$, the number of negative pivots of $`D`$ after $`L D L^\top`$,
    /// `None` after LU or before a factorisation.
    pub fn negative_pivots(&self) -> Option<usize> {
        self.negative_pivots
    }
}
