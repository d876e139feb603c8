//! Multi-term Galerkin solution of the second-order stress-function problem (55), of which the
//! one-term closed form $`C(\alpha)`$ of (62) is the truncation to one basis function.
//!
//! # The problem
//! At order $`a^2`$ of the post-bifurcation expansion (45) the membrane stress is
//! $`N^{(2)} = -\lambda^{(2)} e_X\otimes e_X + \operatorname{curl}\operatorname{curl}\psi`$
//! ($`N_X = \psi_{YY}`$, $`N_Y = \psi_{XX}`$, $`N_{XY} = -\psi_{XY}`$, (52)), and compatibility
//! of the strain (53) with the wrinkling strain of the mode
//! $`w^{(1)} = \sin(\pi X/L_X)\sin(\pi Y/L_Y)`$ gives (54); dropping its Föppl–von Kármán term
//! (order $`1/L^4`$ against $`Q^2/L^2`$, as the paper does) leaves the clamped biharmonic problem (55)
//! $$`\frac{1}{Eh}\Delta^2\psi = Q^2\,\partial_{YY}\big(w^{(1)}\big)^2 \text{ in } \omega,\qquad
//!   \psi = \partial_n\psi = 0 \text{ on } \partial\omega`$$
//! (zero boundary tractions: the load increment $`\lambda^{(2)}`$ is carried by
//! $`-\lambda^{(2)}Y^2/2`$). On $`[-1, 1]^2`$ ($`X = (1+r)L_X/2`$, $`Y = (1+s)L_Y/2`$,
//! $`\alpha = L_Y/L_X`$) this is the paper's
//! $$`(\alpha^2\partial_{rr} + \partial_{ss})^2\psi = \kappa f,\qquad
//!   \kappa = \frac{\pi^2 E h Q^2 L_Y^2}{16},\qquad f(r, s) = [1 - \cos\pi(1+r)]\cos\pi(1+s).`$$
//! The solvability condition of order 3, reduced as in the paper to
//! $`\iint N_X^{(2)}(w^{(1)})^2 = 0`$, with $`N_X^{(2)} = -\lambda^{(2)} + (4/L_Y^2)\psi_{ss}`$, gives
//! $$`\lambda^{(2)} = \frac{\pi^2}{4} E h Q^2\,\frac{J}{I_3},\qquad
//!   J = \frac{1}{\kappa}\iint \psi_{ss}\,(w^{(1)})^2\,dr\,ds.`$$
//!
//! # Galerkin
//! With $`\psi = \kappa\sum_i c_i\varphi_i`$ for clamped basis functions $`\varphi_i`$ (zero value
//! and slope on the boundary), the weak form of the biharmonic problem is the symmetric positive
//! definite system
//! $$`A c = b,\quad A_{ij} = \iint L\varphi_i\,L\varphi_j,\quad b_i = \iint f\varphi_i,\quad
//!   L = \alpha^2\partial_{rr} + \partial_{ss},`$$
//! and $`J = d^\top c`$ with $`d_i = \iint \partial_{ss}\varphi_i\,(w^{(1)})^2`$. The amplitude
//! coefficient follows as in (62) with $`I_2 I_4/I_1`$ replaced by $`J`$:
//! $$`C = \sqrt{\frac{2 I_3}{3\pi^2(1-\nu^2)\,J}}.`$$
//! For the single function $`\varphi_1 = W = (1-r^2)^2(1-s^2)^2`$ the system is
//! $`I_1 c = I_2`$ and $`d = I_4`$, so $`J = I_2 I_4/I_1`$ and $`C`$ is exactly (62): the closed
//! form is the one-term truncation. Integrating by parts twice in $`s`$,
//! $`d_i = \iint\varphi_i\,\partial_{ss}(w^{(1)})^2 = (\pi^2/4)\,b_i`$, so
//! $`J = (\pi^2/4)\,b^\top A^{-1} b`$ is a compliance: Galerkin solutions on nested spaces increase
//! it monotonically towards the exact value, and $`C`$ decreases towards its converged value.
//!
//! # Basis
//! The source $`f`$ is even in $`r`$ and in $`s`$, so $`\psi`$ is too. The space with $`K`$
//! functions per direction is $`\{(1-r^2)^2(1-s^2)^2\,p(r)\,q(s)\}`$ with $`p, q`$ even of degree
//! $`\le 2K - 2`$, i.e. the span of $`W\,P_{2m}(r)P_{2n}(s)`$, $`m, n < K`$ ($`K^2`$ terms: 1, 4,
//! 9, 16, …; $`K = 1`$ is the paper's $`W`$). For conditioning it is spanned by the
//! equivalent functions $`g_m(r)g_n(s)`$ with
//! $$`g_m = \frac{P_{2m} - \frac{2(4m+5)}{4m+7}P_{2m+2} + \frac{4m+3}{4m+7}P_{2m+4}}{(4m+3)(4m+5)},
//!   \qquad g_m'' = P_{2m+2},\qquad g_m(\pm1) = g_m'(\pm1) = 0`$$
//! (Shen's biharmonic basis; $`g_0 = (1-x^2)^2/8`$): second derivatives are orthogonal, so the
//! $`\alpha^4`$ and $`1`$ blocks of $`A`$ are nearly diagonal. All integrals factor into
//! one-dimensional ones, evaluated by Gauss–Legendre quadrature (exact for the polynomial products,
//! spectrally accurate for the cosines). $`A`$ is Jacobi-scaled and factorised by the runtime's
//! Cholesky.

use super::gauss_legendre;
use std::f64::consts::PI;
use std::sync::Arc;
use wrinkle_runtime::linear::{
    FactorizationKind, LinearError, SparseFactorization, SparseMatrix, SparsityPattern,
};

/// Default largest number of basis functions per direction in [`converge`] (576 terms).
pub const DEFAULT_MAX_TERMS_PER_DIRECTION: usize = 24;
/// Default relative change of $`C`$ below which [`converge`] stops (two changes in a row). The
/// tail of the sequence decays roughly geometrically (ratio ~1/2 per step from $`K \approx 10`$),
/// so the remaining error is of the order of the last change.
pub const DEFAULT_RELATIVE_TOLERANCE: f64 = 1e-12;

/// One Galerkin solution of (55) with $`K^2`$ basis functions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StressFunctionSolution {
    /// $`K`$, basis functions per direction.
    pub terms_per_direction: usize,
    /// $`K^2`$, basis functions in all.
    pub terms: usize,
    /// $`J = d^\top A^{-1} b`$, which replaces $`I_2 I_4/I_1`$ in (60)–(62).
    pub load_integral: f64,
    /// $`C = \sqrt{2 I_3/(3\pi^2(1-\nu^2) J)}`$: envelope amplitude $`a/h`$ per
    /// $`\sqrt{\lambda/\lambda_c - 1}`$.
    pub amplitude_coefficient: f64,
}

/// Why [`converge`] stopped.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ConvergenceStop {
    /// Two consecutive relative changes of $`C`$ were below the tolerance.
    Converged,
    /// The largest basis was reached first.
    TermLimit,
}

impl ConvergenceStop {
    /// A short name: `converged` or `term limit`.
    pub fn as_str(self) -> &'static str {
        match self {
            ConvergenceStop::Converged => "converged",
            ConvergenceStop::TermLimit => "term limit",
        }
    }
}

/// The sequence of Galerkin solutions with $`K = 1, 2, \ldots`$ terms per direction.
#[derive(Clone, Debug, PartialEq)]
pub struct StressFunctionConvergence {
    /// Solutions in order of increasing $`K`$ (at least one).
    pub solutions: Vec<StressFunctionSolution>,
    /// Why the sequence stopped.
    pub stop: ConvergenceStop,
    /// Relative tolerance it was run with.
    pub relative_tolerance: f64,
}

impl StressFunctionConvergence {
    /// The richest solution.
    pub fn converged(&self) -> &StressFunctionSolution {
        self.solutions.last().expect("at least one solution")
    }

    /// Relative change of $`C`$ between the last two solutions (`None` with one solution).
    pub fn last_relative_change(&self) -> Option<f64> {
        relative_changes(&self.solutions).last().copied()
    }
}

/// Relative changes $`|C_K - C_{K-1}|/C_K`$ of consecutive solutions.
pub fn relative_changes(solutions: &[StressFunctionSolution]) -> Vec<f64> {
    solutions
        .windows(2)
        .map(|pair| {
            ((pair[1].amplitude_coefficient - pair[0].amplitude_coefficient)
                / pair[1].amplitude_coefficient)
                .abs()
        })
        .collect()
}

/// Solves (55) with $`K`$ = `terms_per_direction` basis functions per direction (see the module
/// documentation). Fails (with a message) only if the Galerkin matrix is not numerically positive
/// definite.
///
/// # Example
/// The one-term solution is the closed form (62); 16 terms move $`C(1)`$ from 1.6509 to 1.5790.
/// ```
/// use wrinkle::closed_form::{amplitude_coefficient, stress_function};
/// let one_term = stress_function::solve(1.0, 0.3, 1).unwrap();
/// assert!((one_term.amplitude_coefficient - amplitude_coefficient(1.0, 0.3)).abs() < 1e-14);
/// let sixteen_terms = stress_function::solve(1.0, 0.3, 4).unwrap();
/// assert!((sixteen_terms.amplitude_coefficient - 1.579_022_025).abs() < 1e-9);
/// ```
///
/// # Panics
/// If `terms_per_direction` is 0.
pub fn solve(
    aspect_ratio: f64,
    poisson_ratio: f64,
    terms_per_direction: usize,
) -> Result<StressFunctionSolution, String> {
    assert!(terms_per_direction > 0, "at least one term per direction");
    let moments = OneDimensionalMoments::new(terms_per_direction);
    let (matrix, source, load) = moments.galerkin_system(aspect_ratio);
    let coefficients = solve_positive_definite(&matrix, &source).map_err(|error| {
        format!("Galerkin system of (55) with {terms_per_direction}² terms: {error}")
    })?;
    let load_integral: f64 = coefficients.iter().zip(&load).map(|(c, d)| c * d).sum();
    let i3 = super::galerkin_integrals(aspect_ratio).i3;
    let amplitude_coefficient =
        (2.0 * i3 / (3.0 * PI * PI * (1.0 - poisson_ratio * poisson_ratio) * load_integral)).sqrt();
    Ok(StressFunctionSolution {
        terms_per_direction,
        terms: terms_per_direction * terms_per_direction,
        load_integral,
        amplitude_coefficient,
    })
}

/// Solves (55) with $`K = 1, 2, \ldots`$ terms per direction until two consecutive relative
/// changes of $`C`$ are at most `relative_tolerance`, or $`K`$ = `max_terms_per_direction`.
pub fn converge(
    aspect_ratio: f64,
    poisson_ratio: f64,
    max_terms_per_direction: usize,
    relative_tolerance: f64,
) -> Result<StressFunctionConvergence, String> {
    let mut solutions = Vec::new();
    for terms_per_direction in 1..=max_terms_per_direction.max(1) {
        solutions.push(solve(aspect_ratio, poisson_ratio, terms_per_direction)?);
        let changes = relative_changes(&solutions);
        if changes.len() >= 2
            && changes[changes.len() - 2..]
                .iter()
                .all(|change| *change <= relative_tolerance)
        {
            return Ok(StressFunctionConvergence {
                solutions,
                stop: ConvergenceStop::Converged,
                relative_tolerance,
            });
        }
    }
    Ok(StressFunctionConvergence {
        solutions,
        stop: ConvergenceStop::TermLimit,
        relative_tolerance,
    })
}

/// One-dimensional integrals of the basis $`g_0, \ldots, g_{K-1}`$ on $`[-1, 1]`$.
struct OneDimensionalMoments {
    /// $`\int g_m g_p`$.
    mass: Vec<Vec<f64>>,
    /// $`\int g_m'' g_p`$.
    mixed: Vec<Vec<f64>>,
    /// $`\int g_m'' g_p''`$.
    stiffness: Vec<Vec<f64>>,
    /// $`\int [1 - \cos\pi(1+x)]\,g_m = \int (1 + \cos\pi x)\,g_m`$.
    source_r: Vec<f64>,
    /// $`\int \cos\pi(1+x)\,g_m = -\int \cos\pi x\,g_m`$.
    source_s: Vec<f64>,
    /// $`\int g_m\cos^2(\pi x/2)`$.
    mode_r: Vec<f64>,
    /// $`\int g_m''\cos^2(\pi x/2)`$.
    mode_s: Vec<f64>,
}

impl OneDimensionalMoments {
    fn new(terms: usize) -> Self {
        // g_m g_p has degree ≤ 4K + 4: 2K + 3 points are exact; the margin resolves the cosines.
        let (nodes, weights) = gauss_legendre(2 * terms + 48);
        let mut values = vec![Vec::with_capacity(nodes.len()); terms];
        let mut second = vec![Vec::with_capacity(nodes.len()); terms];
        for &x in &nodes {
            let legendre = legendre_values(2 * terms + 2, x);
            for m in 0..terms {
                let k = 4.0 * m as f64;
                let combination = legendre[2 * m]
                    - 2.0 * (k + 5.0) / (k + 7.0) * legendre[2 * m + 2]
                    + (k + 3.0) / (k + 7.0) * legendre[2 * m + 4];
                values[m].push(combination / ((k + 3.0) * (k + 5.0)));
                second[m].push(legendre[2 * m + 2]);
            }
        }
        let integrate = |first: &[f64], other: &dyn Fn(usize) -> f64| -> f64 {
            weights
                .iter()
                .enumerate()
                .map(|(q, weight)| weight * first[q] * other(q))
                .sum()
        };
        let table = |left: &[Vec<f64>], right: &[Vec<f64>]| -> Vec<Vec<f64>> {
            left.iter()
                .map(|l| right.iter().map(|r| integrate(l, &|q| r[q])).collect())
                .collect()
        };
        let cosine = |q: usize| (PI * nodes[q]).cos();
        let half_cosine_squared = |q: usize| (1.0 + cosine(q)) / 2.0;
        OneDimensionalMoments {
            mass: table(&values, &values),
            mixed: table(&second, &values),
            stiffness: table(&second, &second),
            source_r: values
                .iter()
                .map(|g| integrate(g, &|q| 1.0 + cosine(q)))
                .collect(),
            source_s: values
                .iter()
                .map(|g| integrate(g, &|q| -cosine(q)))
                .collect(),
            mode_r: values
                .iter()
                .map(|g| integrate(g, &half_cosine_squared))
                .collect(),
            mode_s: second
                .iter()
                .map(|g| integrate(g, &half_cosine_squared))
                .collect(),
        }
    }

    /// $`(A, b, d)`$ for the tensor basis $`\varphi_{mK+n} = g_m(r) g_n(s)`$.
    fn galerkin_system(&self, aspect_ratio: f64) -> (Vec<Vec<f64>>, Vec<f64>, Vec<f64>) {
        let terms = self.source_r.len();
        let alpha_squared = aspect_ratio * aspect_ratio;
        let index = |m: usize, n: usize| m * terms + n;
        let size = terms * terms;
        let mut matrix = vec![vec![0.0; size]; size];
        let mut source = vec![0.0; size];
        let mut load = vec![0.0; size];
        for (m, n) in (0..terms).flat_map(|m| (0..terms).map(move |n| (m, n))) {
            source[index(m, n)] = self.source_r[m] * self.source_s[n];
            load[index(m, n)] = self.mode_r[m] * self.mode_s[n];
            for (p, q) in (0..terms).flat_map(|p| (0..terms).map(move |q| (p, q))) {
                // ∫∫ (α² g_m'' g_n + g_m g_n'') (α² g_p'' g_q + g_p g_q'').
                matrix[index(m, n)][index(p, q)] =
                    alpha_squared * alpha_squared * self.stiffness[m][p] * self.mass[n][q]
                        + alpha_squared
                            * (self.mixed[m][p] * self.mixed[q][n]
                                + self.mixed[p][m] * self.mixed[n][q])
                        + self.mass[m][p] * self.stiffness[n][q];
            }
        }
        (matrix, source, load)
    }
}

/// $`P_0(x), \ldots, P_{n+2}(x)`$ by the three-term recurrence.
fn legendre_values(degree: usize, x: f64) -> Vec<f64> {
    let mut values = vec![1.0, x];
    for k in 2..=degree + 2 {
        let k = k as f64;
        let next = ((2.0 * k - 1.0) * x * values[values.len() - 1]
            - (k - 1.0) * values[values.len() - 2])
            / k;
        values.push(next);
    }
    values
}

/// Solves the dense symmetric positive definite system $`A c = b`$: Jacobi scaling, then the
/// runtime's Cholesky on a full pattern. Fails if $`A`$ is not numerically positive definite.
fn solve_positive_definite(matrix: &[Vec<f64>], source: &[f64]) -> Result<Vec<f64>, String> {
    let size = source.len();
    let scale: Vec<f64> = (0..size).map(|i| 1.0 / matrix[i][i].sqrt()).collect();
    let linear = |error: LinearError| error.to_string();
    let pattern = Arc::new(
        SparsityPattern::from_symmetric_entries(
            size,
            (0..size).flat_map(|j| (0..j).map(move |i| (i, j))),
        )
        .map_err(linear)?,
    );
    let mut scaled = SparseMatrix::zeros(Arc::clone(&pattern));
    for (i, row) in matrix.iter().enumerate() {
        for (j, value) in row.iter().enumerate() {
            scaled
                .add_to(i, j, scale[i] * value * scale[j])
                .map_err(linear)?;
        }
    }
    let mut factorization = SparseFactorization::analyze(&pattern).map_err(linear)?;
    let kind = factorization.factorize(&scaled).map_err(linear)?;
    if kind != FactorizationKind::Cholesky {
        return Err(format!(
            "the matrix is not numerically positive definite (factorised by {kind:?})"
        ));
    }
    let mut solution: Vec<f64> = source.iter().zip(&scale).map(|(b, s)| b * s).collect();
    factorization
        .solve_in_place(&mut solution)
        .map_err(linear)?;
    Ok(solution.iter().zip(&scale).map(|(y, s)| y * s).collect())
}
