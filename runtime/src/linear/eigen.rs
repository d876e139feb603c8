//! Linear buckling eigenproblem $`(A + \lambda B)\varphi = 0`$ by shift-invert Lanczos in the
//! $`A`$-inner product.
//!
//! With $`A`$ symmetric positive definite and $`B`$ symmetric (indefinite), the problem is
//! equivalent to $`C \varphi = \mu \varphi`$ with $`C = A^{-1} B`$ and $`\mu = -1/\lambda`$.
//! $`C`$ is self-adjoint for $`\langle x, y \rangle_A = x^\top A y`$, since
//! $`\langle x, C y \rangle_A = x^\top B y`$. The smallest positive $`\lambda`$ are the most
//! negative $`\mu`$, an extreme (and, after the shift-invert, well separated) end of the spectrum
//! of $`C`$, which Lanczos finds fast.
//!
//! The basis $`V`$ is kept $`A`$-orthonormal by full re-orthogonalisation (classical Gram–Schmidt
//! applied twice); the projected matrix $`T = V^\top B V`$ is diagonalised by nalgebra's
//! `SymmetricEigen` (Rayleigh–Ritz), and the iteration is restarted thickly (Krylov–Schur
//! style): the wanted Ritz vectors are kept together with the residual direction
//! $`(I - V V^\top A) C v_m`$, shared by all Ritz residuals. Alongside $`V`$ the products
//! $`A V`$, $`B V`$ and $`C V`$ are kept, so that restarts need no new solves and residuals
//! $`r = C y - \theta y`$ are computed exactly: $`\|r\|_A^2 = r^\top (B V s - \theta A V s)`$.
//!
//! Repeated eigenvalues: a single-vector Krylov method resolves one vector per distinct eigenvalue
//! (a double $`\lambda`$ is reported once, with one of its modes); the load factors returned are
//! the distinct smallest ones.

use nalgebra::{DMatrix, SymmetricEigen};

use super::factor::{FactorizationKind, LinearError, SparseFactorization};
use super::pattern::SparseMatrix;
use super::vector::{axpy, dot, norm};

/// Settings of [`smallest_positive_buckling`].
#[derive(Clone, Debug, PartialEq)]
pub struct BucklingOptions {
    /// Number of buckling modes wanted (smallest positive load factors), at least 1.
    pub modes: usize,
    /// Relative residual $`\|C y - \theta y\|_A / |\theta|`$ at which a Ritz pair is converged.
    /// The load factor error is of the order of the square of this residual. When rounding
    /// prevents reaching it, a residual stagnating below $`\sqrt{\mathrm{tolerance}}`$ is
    /// accepted (the load factor is then still accurate to about `tolerance`).
    pub tolerance: f64,
    /// Maximum dimension of the Krylov basis (clamped to the problem dimension).
    pub max_krylov: usize,
    /// Maximum number of thick restarts.
    pub max_restarts: usize,
    /// When the iteration does not converge: return the best approximations with
    /// `converged = false` instead of [`LinearError::NotConverged`].
    pub accept_unconverged: bool,
    /// Seed of the deterministic pseudo-random start vector.
    pub seed: u64,
    /// A start vector (warm start, e.g. the mode of a nearby problem); a pseudo-random one when
    /// `None` or when it does not fit.
    pub start: Option<Vec<f64>>,
    /// When set: a wanted residual below $`\sqrt{\mathrm{tolerance}}`$ that has not halved over
    /// the last this many operator applications, judged at every check (not only at full bases),
    /// is taken as the rounding floor and accepted. `None`: stagnation is judged over
    /// restarts only (three of them, about 60 applications at the default basis size). Large
    /// plate meshes reach their floor ($`10^{-10}`$–$`10^{-9}`$, above the default tolerance)
    /// in a few tens of applications after a close shift and would otherwise spend 60 more.
    pub stagnation_applications: Option<usize>,
}

impl Default for BucklingOptions {
    fn default() -> Self {
        Self {
            modes: 1,
            tolerance: 1e-12,
            max_krylov: 40,
            max_restarts: 300,
            accept_unconverged: false,
            seed: 0x5eed_0fb0_c1a5,
            start: None,
            stagnation_applications: None,
        }
    }
}

/// One buckling mode.
#[derive(Clone, Debug, PartialEq)]
pub struct BucklingMode {
    /// Load factor $`\lambda > 0`$ with $`(A + \lambda B)\varphi = 0`$, computed as the Rayleigh
    /// quotient $`-\varphi^\top A \varphi / \varphi^\top B \varphi`$.
    pub load_factor: f64,
    /// Mode $`\varphi`$, normalised so that $`\varphi^\top A \varphi = 1`$, with its
    /// largest-magnitude component positive.
    pub vector: Vec<f64>,
    /// Relative residual $`\|(A + \lambda B)\varphi\|_2 / \|A\varphi\|_2`$.
    pub residual: f64,
}

/// Result of [`smallest_positive_buckling`].
#[derive(Clone, Debug, PartialEq)]
pub struct BucklingSolution {
    /// Modes sorted by ascending load factor (fewer than asked for when the explored subspace
    /// holds fewer positive load factors).
    pub modes: Vec<BucklingMode>,
    /// Applications of the operator $`A^{-1} B`$ (one sparse solve each).
    pub iterations: usize,
    /// Whether every returned mode reached the tolerance (always `true` unless
    /// [`BucklingOptions::accept_unconverged`] is set).
    pub converged: bool,
}

/// Relative size below which a negative Ritz value is considered rounding noise.
const NEGATIVE_NOISE_RELATIVE: f64 = 1e-9;
/// Restarts without halving of the residual after which it is considered stagnant.
const STAGNATION_WINDOW: usize = 3;
/// Restarts without halving of the residual after which the iteration gives up.
const HOPELESS_WINDOW: usize = 12;
/// Basis vectors beyond the number of wanted modes at the first convergence check.
const EARLY_CHECK_MARGIN: usize = 5;
/// Vectors appended between two convergence checks before the basis is full.
const EARLY_CHECK_STRIDE: usize = 2;
/// Relative size (root mean square against that of the start vector) of the pseudo-random part
/// added to a warm start.
const WARM_START_RANDOM: f64 = 1e-3;
/// Relative $`A`$-norm below which an orthogonalised vector signals an invariant subspace.
const BREAKDOWN_RELATIVE: f64 = 1e-10;

/// Deterministic pseudo-random numbers (SplitMix64) for start and breakdown vectors.
struct SplitMix64(u64);

impl SplitMix64 {
    fn next_unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        // 53 random bits mapped to [-1, 1).
        (z >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }

    fn vector(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.next_unit()).collect()
    }
}

/// $`\sum_j s_j X_j`$.
fn combine(vectors: &[Vec<f64>], coefficients: impl Iterator<Item = f64>, n: usize) -> Vec<f64> {
    let mut result = vec![0.0; n];
    for (vector, coefficient) in vectors.iter().zip(coefficients) {
        axpy(coefficient, vector, &mut result);
    }
    result
}

/// The $`A`$-orthonormal basis with the images needed for Rayleigh–Ritz and residuals.
struct Basis {
    /// $`v_j`$, $`A`$-orthonormal.
    vectors: Vec<Vec<f64>>,
    /// $`A v_j`$.
    a_vectors: Vec<Vec<f64>>,
    /// $`B v_j`$.
    b_vectors: Vec<Vec<f64>>,
    /// $`C v_j = A^{-1} B v_j`$.
    c_vectors: Vec<Vec<f64>>,
    /// Lower triangle of the projected matrix
    /// $`T_{ij} = \tfrac12 (v_i^\top A C v_j + v_j^\top A C v_i)`$, row by row, extended as
    /// vectors are appended (so that a Rayleigh–Ritz check costs no product of length $`n`$).
    projected: Vec<Vec<f64>>,
}

struct Operator<'a> {
    a: &'a SparseMatrix,
    a_factor: &'a SparseFactorization,
    b: &'a SparseMatrix,
    applications: usize,
}

impl Operator<'_> {
    /// Returns $`(B x, A^{-1} B x)`$.
    fn apply(&mut self, x: &[f64]) -> Result<(Vec<f64>, Vec<f64>), LinearError> {
        let mut bx = vec![0.0; x.len()];
        self.b.try_multiply_symmetric_into(x, &mut bx)?;
        let mut cx = bx.clone();
        self.a_factor.solve_in_place(&mut cx)?;
        self.applications += 1;
        Ok((bx, cx))
    }

    fn apply_a(&self, x: &[f64]) -> Result<Vec<f64>, LinearError> {
        let mut ax = vec![0.0; x.len()];
        self.a.try_multiply_symmetric_into(x, &mut ax)?;
        Ok(ax)
    }
}

impl Basis {
    fn len(&self) -> usize {
        self.vectors.len()
    }

    /// Removes from `x` its $`A`$-projection on the basis (classical Gram–Schmidt, twice).
    fn orthogonalize(&self, x: &mut [f64]) {
        for _ in 0..2 {
            let coefficients: Vec<f64> = self.a_vectors.iter().map(|av| dot(av, x)).collect();
            for (vector, coefficient) in self.vectors.iter().zip(coefficients) {
                axpy(-coefficient, vector, x);
            }
        }
    }

    /// Orthogonalises `x` (of $`A`$-norm `reference_norm` before) against the basis and appends
    /// it normalised, applying the operator. Returns `false` (basis unchanged) when `x` lies in the
    /// span of the basis to working precision.
    fn try_push(
        &mut self,
        mut x: Vec<f64>,
        reference_norm: f64,
        operator: &mut Operator<'_>,
    ) -> Result<bool, LinearError> {
        self.orthogonalize(&mut x);
        let mut ax = operator.apply_a(&x)?;
        let a_norm_squared = dot(&x, &ax);
        if !a_norm_squared.is_finite()
            || a_norm_squared <= 0.0
            || a_norm_squared.sqrt() <= BREAKDOWN_RELATIVE * reference_norm
        {
            return Ok(false);
        }
        let scale = 1.0 / a_norm_squared.sqrt();
        x.iter_mut().for_each(|value| *value *= scale);
        ax.iter_mut().for_each(|value| *value *= scale);
        let (bx, cx) = operator.apply(&x)?;
        self.vectors.push(x);
        self.a_vectors.push(ax);
        self.b_vectors.push(bx);
        self.c_vectors.push(cx);
        self.extend_projected();
        Ok(true)
    }

    /// Appends the row of the last vector to the projected matrix.
    fn extend_projected(&mut self) {
        let k = self.len() - 1;
        let (a_k, c_k) = (&self.a_vectors[k], &self.c_vectors[k]);
        let row = (0..=k)
            .map(|j| 0.5 * (dot(a_k, &self.c_vectors[j]) + dot(&self.a_vectors[j], c_k)))
            .collect();
        self.projected.push(row);
    }

    /// A basis from the given vectors and their images, with its projected matrix.
    fn from_columns(
        vectors: Vec<Vec<f64>>,
        a_vectors: Vec<Vec<f64>>,
        b_vectors: Vec<Vec<f64>>,
        c_vectors: Vec<Vec<f64>>,
    ) -> Basis {
        let mut basis = Basis {
            vectors: Vec::with_capacity(vectors.len()),
            a_vectors: Vec::with_capacity(vectors.len()),
            b_vectors: Vec::with_capacity(vectors.len()),
            c_vectors: Vec::with_capacity(vectors.len()),
            projected: Vec::with_capacity(vectors.len()),
        };
        for (((v, av), bv), cv) in vectors
            .into_iter()
            .zip(a_vectors)
            .zip(b_vectors)
            .zip(c_vectors)
        {
            basis.vectors.push(v);
            basis.a_vectors.push(av);
            basis.b_vectors.push(bv);
            basis.c_vectors.push(cv);
            basis.extend_projected();
        }
        basis
    }

    /// Appends a new direction: the orthogonalised image of the last vector, or a random vector
    /// when the image lies in the span (invariant subspace). Returns `false` when the basis spans
    /// the whole space.
    fn expand(
        &mut self,
        operator: &mut Operator<'_>,
        random: &mut SplitMix64,
    ) -> Result<bool, LinearError> {
        let n = operator.a.dimension();
        if self.len() >= n {
            return Ok(false);
        }
        if let (Some(last_c), Some(last_b)) = (self.c_vectors.last(), self.b_vectors.last()) {
            // ‖C v‖_A² = (C v)ᵀ A C v = (C v)ᵀ B v.
            let reference = dot(last_c, last_b).abs().sqrt();
            if self.try_push(last_c.clone(), reference, operator)? {
                return Ok(true);
            }
        }
        for _ in 0..3 {
            let candidate = random.vector(n);
            let reference = dot(&candidate, &operator.apply_a(&candidate)?).abs().sqrt();
            if self.try_push(candidate, reference, operator)? {
                return Ok(true);
            }
        }
        Ok(false)
    }
}

/// A Ritz pair of the current basis with its relative residual.
struct RitzPair {
    value: f64,
    coefficients: Vec<f64>,
    relative_residual: f64,
}

/// Ritz pairs of the basis in ascending order; residuals are computed for the first
/// `with_residual` pairs only (the others get `f64::INFINITY`).
fn rayleigh_ritz(basis: &Basis, n: usize, with_residual: usize) -> Vec<RitzPair> {
    let m = basis.len();
    let projected = DMatrix::from_fn(m, m, |i, j| {
        if j <= i {
            basis.projected[i][j]
        } else {
            basis.projected[j][i]
        }
    });
    let eigen = SymmetricEigen::new(projected);
    let mut order: Vec<usize> = (0..m).collect();
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    order
        .into_iter()
        .enumerate()
        .map(|(rank, index)| {
            let value = eigen.eigenvalues[index];
            let coefficients: Vec<f64> = eigen.eigenvectors.column(index).iter().copied().collect();
            if rank >= with_residual {
                return RitzPair {
                    value,
                    coefficients,
                    relative_residual: f64::INFINITY,
                };
            }
            // r = C y − θ y and A r = B y − θ A y, so ‖r‖²_A = rᵀ A r.
            let mut residual = combine(&basis.c_vectors, coefficients.iter().copied(), n);
            let mut a_residual = combine(&basis.b_vectors, coefficients.iter().copied(), n);
            for (j, coefficient) in coefficients.iter().enumerate() {
                axpy(-value * coefficient, &basis.vectors[j], &mut residual);
                axpy(-value * coefficient, &basis.a_vectors[j], &mut a_residual);
            }
            let residual_norm = dot(&residual, &a_residual).abs().sqrt();
            RitzPair {
                value,
                coefficients,
                relative_residual: residual_norm / value.abs().max(f64::MIN_POSITIVE),
            }
        })
        .collect()
}

fn validate(
    a: &SparseMatrix,
    a_factor: &SparseFactorization,
    b: &SparseMatrix,
    options: &BucklingOptions,
) -> Result<(), LinearError> {
    let n = a.dimension();
    for (what, found) in [
        ("load stiffness B", b.dimension()),
        ("factorisation of A", a_factor.dimension()),
    ] {
        if found != n {
            return Err(LinearError::DimensionMismatch {
                what: what.to_owned(),
                expected: n,
                found,
            });
        }
    }
    for (what, matrix) in [("A", a), ("B", b)] {
        if matrix.values.len() != matrix.pattern.nnz() {
            return Err(LinearError::DimensionMismatch {
                what: format!("values of {what}"),
                expected: matrix.pattern.nnz(),
                found: matrix.values.len(),
            });
        }
        if matrix.values.iter().any(|value| !value.is_finite()) {
            return Err(LinearError::NonFinite {
                what: format!("buckling matrix {what}"),
            });
        }
    }
    if options.modes == 0 {
        return Err(LinearError::InvalidOption {
            what: "at least one buckling mode must be requested".to_owned(),
        });
    }
    if !(options.tolerance > 0.0 && options.tolerance < 1.0) {
        return Err(LinearError::InvalidOption {
            what: format!(
                "eigen-solver tolerance must lie in (0, 1), got {}",
                options.tolerance
            ),
        });
    }
    if options.max_krylov < options.modes + 2 && options.max_krylov < n {
        return Err(LinearError::InvalidOption {
            what: format!(
                "max_krylov = {} must be at least modes + 2 = {}",
                options.max_krylov,
                options.modes + 2
            ),
        });
    }
    match a_factor.kind() {
        Some(FactorizationKind::Cholesky) => Ok(()),
        None => Err(LinearError::NotFactorized),
        Some(kind) => Err(LinearError::InvalidOption {
            what: format!(
                "the buckling eigen-solver needs A positive definite (Cholesky factorisation), \
                 but A was factorised as {kind:?} with {} negative pivots: the reference state is \
                 already beyond a critical point",
                a_factor
                    .negative_pivots()
                    .map_or_else(|| "unknown".to_owned(), |count| count.to_string())
            ),
        }),
    }
}

/// Smallest positive load factors $`\lambda`$ of the linear buckling problem
/// $`(A + \lambda B)\varphi = 0`$, with $`A`$ symmetric positive definite (given with its
/// Cholesky factorisation `a_factor`) and $`B`$ symmetric, possibly indefinite.
///
/// Returns the `options.modes` smallest positive $`\lambda`$ in ascending order (each with its
/// $`A`$-normalised mode and residual $`\|(A+\lambda B)\varphi\| / \|A\varphi\|`$), or
/// [`LinearError::NoPositiveLoadFactor`] when $`B \succeq 0`$ (no compression), or
/// [`LinearError::NotConverged`] stating the residual reached.
pub fn smallest_positive_buckling(
    a: &SparseMatrix,
    a_factor: &SparseFactorization,
    b: &SparseMatrix,
    options: &BucklingOptions,
) -> Result<BucklingSolution, LinearError> {
    validate(a, a_factor, b, options)?;
    let n = a.dimension();
    if n == 0 {
        return Err(LinearError::NoPositiveLoadFactor {
            most_negative_ritz_value: 0.0,
        });
    }
    let krylov_dimension = options.max_krylov.min(n);
    let mut operator = Operator {
        a,
        a_factor,
        b,
        applications: 0,
    };
    let mut random = SplitMix64(options.seed);
    let mut basis = start_basis(&mut operator, &mut random, options)?;
    check_factorization(&operator, &basis)?;
    let mut history: Vec<f64> = Vec::new();
    let mut checks: Vec<(usize, f64)> = Vec::new();
    let mut restarts = 0;
    loop {
        let full = grow_to_next_check(
            &mut basis,
            &mut operator,
            &mut random,
            options.modes,
            krylov_dimension,
        )?;
        let ritz = rayleigh_ritz(&basis, n, options.modes);
        let progress = Progress {
            full,
            exhausted: basis.len() >= n,
            restarts,
            applications: operator.applications,
        };
        match verdict(&ritz, &mut history, &mut checks, &progress, options) {
            Verdict::Expand => continue,
            Verdict::Restart => {}
            Verdict::Solved { wanted, converged } => {
                return solution(&basis, &wanted, &operator, n, converged);
            }
            Verdict::Failed(error) => return Err(error),
        }
        restarts += 1;
        basis = thick_restart(
            &basis,
            &ritz,
            options.modes,
            krylov_dimension,
            &mut operator,
            &mut random,
        )?;
    }
}

/// The first basis vector: the warm start of `options` with a small pseudo-random admixture
/// when it fits, else a pseudo-random vector.
fn start_basis(
    operator: &mut Operator<'_>,
    random: &mut SplitMix64,
    options: &BucklingOptions,
) -> Result<Basis, LinearError> {
    let n = operator.a.dimension();
    let mut basis = Basis::from_columns(Vec::new(), Vec::new(), Vec::new(), Vec::new());
    let warm = match &options.start {
        Some(start) if start.len() == n && start.iter().all(|v| v.is_finite()) => {
            // A small pseudo-random admixture: a warm start that is exactly orthogonal to the
            // wanted mode (a symmetric mode of the neighbouring problem, an antisymmetric one
            // here) would otherwise leave it outside the Krylov space for good.
            let scale = WARM_START_RANDOM * norm(start) / (n as f64).sqrt();
            let mut start = start.clone();
            for value in start.iter_mut() {
                *value += scale * random.next_unit();
            }
            let reference = dot(&start, &operator.apply_a(&start)?).abs().sqrt();
            basis.try_push(start, reference, operator)?
        }
        _ => false,
    };
    if !warm && !basis.expand(operator, random)? {
        return Err(LinearError::NoPositiveLoadFactor {
            most_negative_ritz_value: 0.0,
        });
    }
    Ok(basis)
}

/// Checks that the factorisation belongs to $`A`$: $`A (A^{-1} B v) = B v`$ for the first
/// basis vector.
fn check_factorization(operator: &Operator<'_>, basis: &Basis) -> Result<(), LinearError> {
    let check = operator.apply_a(&basis.c_vectors[0])?;
    let mismatch: f64 = check
        .iter()
        .zip(&basis.b_vectors[0])
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt();
    let scale = norm(&basis.b_vectors[0]);
    if mismatch > 1e-6 * scale {
        return Err(LinearError::InvalidOption {
            what: format!(
                "a_factor is not a factorisation of A (‖A A⁻¹ B v − B v‖ / ‖B v‖ = {:e})",
                mismatch / scale
            ),
        });
    }
    Ok(())
}

/// Expands the basis to the next check: every other vector once it holds a few more vectors
/// than modes wanted (a warm-started analysis often converges long before the basis is full),
/// and at the full dimension. Returns whether the basis is full (or could not grow).
fn grow_to_next_check(
    basis: &mut Basis,
    operator: &mut Operator<'_>,
    random: &mut SplitMix64,
    modes: usize,
    krylov_dimension: usize,
) -> Result<bool, LinearError> {
    let first_check = (modes + EARLY_CHECK_MARGIN).min(krylov_dimension);
    let target = if basis.len() < first_check {
        first_check
    } else {
        (basis.len() + EARLY_CHECK_STRIDE).min(krylov_dimension)
    };
    let mut grew = false;
    while basis.len() < target {
        if !basis.expand(operator, random)? {
            break;
        }
        grew = true;
    }
    Ok(basis.len() >= krylov_dimension || !grew)
}

/// Where the iteration stands at a check.
struct Progress {
    /// The basis is full (or could not grow).
    full: bool,
    /// The basis spans the whole space.
    exhausted: bool,
    restarts: usize,
    /// Operator applications so far.
    applications: usize,
}

/// What a check decides.
enum Verdict<'r> {
    /// Grow the basis further before the next check.
    Expand,
    /// Restart thickly.
    Restart,
    /// Return these pairs' modes.
    Solved {
        wanted: Vec<&'r RitzPair>,
        converged: bool,
    },
    /// Give up.
    Failed(LinearError),
}

/// The decision at a check from the Ritz pairs (ascending), the history of the worst wanted
/// residual at full checks and that at every check with its operator applications (both
/// extended here), and the iteration's progress.
fn verdict<'r>(
    ritz: &'r [RitzPair],
    history: &mut Vec<f64>,
    checks: &mut Vec<(usize, f64)>,
    progress: &Progress,
    options: &BucklingOptions,
) -> Verdict<'r> {
    let spectral_scale = ritz
        .iter()
        .fold(0.0_f64, |max, pair| max.max(pair.value.abs()));
    let noise = NEGATIVE_NOISE_RELATIVE * spectral_scale;
    let wanted: Vec<&RitzPair> = ritz
        .iter()
        .take(options.modes)
        .take_while(|pair| pair.value < -noise)
        .collect();
    let growing = !progress.full && !progress.exhausted;
    if wanted.is_empty() {
        // No negative Ritz value yet. A small negative end of the spectrum can hide behind a
        // large positive one (a strip in tension: the compressed zone is small), so the
        // iteration goes on, restarted on the leftmost Ritz vectors, until the leftmost
        // Ritz pair itself has converged (then there is no positive load factor) or the
        // restart budget is spent.
        let leftmost = ritz.first();
        let settled = leftmost
            .is_none_or(|pair| pair.relative_residual <= options.tolerance.sqrt())
            || progress.exhausted
            || progress.restarts >= options.max_restarts;
        return if growing {
            Verdict::Expand
        } else if settled {
            Verdict::Failed(LinearError::NoPositiveLoadFactor {
                most_negative_ritz_value: leftmost.map_or(0.0, |pair| pair.value),
            })
        } else {
            Verdict::Restart
        };
    }
    let worst = wanted
        .iter()
        .fold(0.0_f64, |max, pair| max.max(pair.relative_residual));
    checks.push((progress.applications, worst));
    if wanted.len() == options.modes && at_floor(checks, options) {
        return Verdict::Solved {
            wanted,
            converged: true,
        };
    }
    if growing {
        let all_found = wanted.len() == options.modes;
        return if all_found && worst <= options.tolerance {
            Verdict::Solved {
                wanted,
                converged: true,
            }
        } else {
            Verdict::Expand
        };
    }
    history.push(worst);
    full_check_verdict(wanted, worst, history, progress, options)
}

/// Whether the last worst residual of `checks` lies below $`\sqrt{\mathrm{tolerance}}`$ and
/// has not halved since the last check at least [`BucklingOptions::stagnation_applications`]
/// operator applications earlier (never when that option is `None`).
fn at_floor(checks: &[(usize, f64)], options: &BucklingOptions) -> bool {
    let (Some(window), Some(&(applications, worst))) =
        (options.stagnation_applications, checks.last())
    else {
        return false;
    };
    let earlier = checks
        .iter()
        .rev()
        .find(|(at, _)| *at + window <= applications);
    worst <= options.tolerance.sqrt()
        && earlier.is_some_and(|&(_, residual)| worst > 0.5 * residual)
}

/// [`verdict`] at a full basis with wanted pairs, `worst` their largest residual (the last
/// entry of `history`).
///
/// Rounding limits the attainable residual (about $`\epsilon\,\kappa(A)`$ for smooth modes of
/// stiff operators): a residual that no longer halves is accepted below
/// $`\sqrt{\text{tolerance}}`$ (the load factor error being of the order of its square), and
/// ends the iteration otherwise.
fn full_check_verdict<'r>(
    wanted: Vec<&'r RitzPair>,
    worst: f64,
    history: &[f64],
    progress: &Progress,
    options: &BucklingOptions,
) -> Verdict<'r> {
    let improving_over = |window: usize| {
        history.len() <= window || worst <= 0.5 * history[history.len() - 1 - window]
    };
    let stagnated = !improving_over(STAGNATION_WINDOW);
    let converged = worst <= options.tolerance
        || progress.exhausted
        || (stagnated && worst <= options.tolerance.sqrt());
    let hopeless = !improving_over(HOPELESS_WINDOW);
    if !(converged || hopeless || progress.restarts >= options.max_restarts) {
        return Verdict::Restart;
    }
    if !converged && !options.accept_unconverged {
        return Verdict::Failed(LinearError::NotConverged {
            restarts: progress.restarts,
            iterations: progress.applications,
            residual: worst,
            tolerance: options.tolerance,
        });
    }
    Verdict::Solved { wanted, converged }
}

/// Thick restart: a basis of the most negative Ritz vectors and the common residual direction
/// (or, when that lies in their span, a new direction).
fn thick_restart(
    basis: &Basis,
    ritz: &[RitzPair],
    modes: usize,
    krylov_dimension: usize,
    operator: &mut Operator<'_>,
    random: &mut SplitMix64,
) -> Result<Basis, LinearError> {
    let n = operator.a.dimension();
    let keep = (modes + (krylov_dimension - modes) / 2)
        .min(krylov_dimension.saturating_sub(2))
        .max(modes)
        .min(ritz.len());
    let last_c = basis.c_vectors.last().cloned().unwrap_or_default();
    let last_b = basis.b_vectors.last().cloned().unwrap_or_default();
    let mut continuation = last_c.clone();
    basis.orthogonalize(&mut continuation);
    let transform = |vectors: &[Vec<f64>]| -> Vec<Vec<f64>> {
        ritz[..keep]
            .iter()
            .map(|pair| combine(vectors, pair.coefficients.iter().copied(), n))
            .collect()
    };
    let mut restarted = Basis::from_columns(
        transform(&basis.vectors),
        transform(&basis.a_vectors),
        transform(&basis.b_vectors),
        transform(&basis.c_vectors),
    );
    let reference = dot(&last_c, &last_b).abs().sqrt();
    if !restarted.try_push(continuation, reference, operator)? {
        restarted.expand(operator, random)?;
    }
    Ok(restarted)
}

/// The returned solution: the modes of the `wanted` Ritz pairs, by ascending load factor.
fn solution(
    basis: &Basis,
    wanted: &[&RitzPair],
    operator: &Operator<'_>,
    n: usize,
    converged: bool,
) -> Result<BucklingSolution, LinearError> {
    let mut modes = wanted
        .iter()
        .map(|pair| finish_mode(basis, pair, operator, n))
        .collect::<Result<Vec<_>, _>>()?;
    modes.sort_by(|x, y| x.load_factor.total_cmp(&y.load_factor));
    Ok(BucklingSolution {
        modes,
        iterations: operator.applications,
        converged,
    })
}

/// Builds the returned mode from a converged Ritz pair: explicit $`A`$-normalisation, Rayleigh
/// quotient and residual with the original matrices.
fn finish_mode(
    basis: &Basis,
    pair: &RitzPair,
    operator: &Operator<'_>,
    n: usize,
) -> Result<BucklingMode, LinearError> {
    let (a, a_factor, b) = (operator.a, operator.a_factor, operator.b);
    let mut vector = combine(&basis.vectors, pair.coefficients.iter().copied(), n);
    let mut av = vec![0.0; n];
    let mut bv = vec![0.0; n];
    a.try_multiply_symmetric_into(&vector, &mut av)?;
    b.try_multiply_symmetric_into(&vector, &mut bv)?;
    let a_norm_squared = dot(&vector, &av);
    let b_quotient = dot(&vector, &bv);
    // λ = −1/θ with θ the Rayleigh quotient of C = A⁻¹B in the B-form,
    // θ = (Bφ)ᵀ A⁻¹ (Bφ) / φᵀBφ: stationary at eigenvectors like the A-form quotient
    // −φᵀAφ/φᵀBφ, but free of the cancellation of Aφ for smooth modes of stiff operators.
    let mut cv = bv.clone();
    a_factor.solve_in_place(&mut cv)?;
    let c_quotient = dot(&bv, &cv);
    let load_factor = -b_quotient / c_quotient;
    if !(load_factor.is_finite() && load_factor > 0.0 && a_norm_squared > 0.0) {
        return Err(LinearError::NonFinite {
            what: format!(
                "buckling load factor (vᵀAv = {a_norm_squared:e}, vᵀBv = {b_quotient:e})"
            ),
        });
    }
    let residual_vector: Vec<f64> = av
        .iter()
        .zip(&bv)
        .map(|(ax, bx)| ax + load_factor * bx)
        .collect();
    let residual = norm(&residual_vector) / norm(&av);
    let mut scale = 1.0 / a_norm_squared.sqrt();
    let largest = vector.iter().copied().fold(0.0_f64, |best, value| {
        if value.abs() > best.abs() {
            value
        } else {
            best
        }
    });
    if largest < 0.0 {
        scale = -scale;
    }
    vector.iter_mut().for_each(|value| *value *= scale);
    Ok(BucklingMode {
        load_factor,
        vector,
        residual,
    })
}
