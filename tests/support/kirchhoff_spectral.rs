//! Independent Kirchhoff-plate reference for the linear buckling of a clamped rectangle:
//! a Legendre spectral Galerkin (Rayleigh–Ritz) solver that shares no code with the project.
//!
//! Problem (`../shared/THEORY.md` §2, §8–9): the rectangle $`[0, L_X]\times[0, L_Y]`$, clamped
//! ($`w = \partial_n w = 0`$) on all four edges, carries the uniform membrane state
//! $`N_X = T_X - \lambda c_X`$, $`N_Y = T_Y - \lambda c_Y`$, $`N_{XY} = 0`$. The critical load is
//! $$`\lambda_c = \min_w \frac{\int D\,[(\Delta w)^2 - 2(1-\nu)(w_{XX}w_{YY} - w_{XY}^2)]
//!   + T_X \int w_X^2 + T_Y \int w_Y^2}{c_X \int w_X^2 + c_Y \int w_Y^2}.`$$
//! The paper's example 1 is $`T_X = 0`$, $`T_Y = T`$, $`c_X = 1`$, $`c_Y = 0`$.
//!
//! Discretisation:
//! * along each side, mapped to $`\xi\in[-1, 1]`$, Shen's clamped Legendre functions
//!   $`\phi_k = (L_k - \tfrac{2(2k+5)}{2k+7} L_{k+2} + \tfrac{2k+3}{2k+7} L_{k+4})/\sqrt{d_k}`$,
//!   $`d_k = 2(2k+3)^2(2k+5)`$, $`k = 0..=p-4`$ for the polynomial degree $`p`$ (J. Shen, SIAM J.
//!   Sci. Comput. 15 (1994) 1489–1505): $`\phi_k(\pm1) = \phi_k'(\pm1) = 0`$ exactly and
//!   $`\int\phi_j''\phi_k'' = \delta_{jk}`$. The spaces are nested in $`p`$, so the computed
//!   $`\lambda_c`$ decreases monotonically to the exact value (Rayleigh–Ritz);
//! * the 1-D matrices are computed by Gauss–Legendre quadrature with $`p + 4`$ points (exact);
//! * $`\phi_k`$ has the parity of $`k`$, so the four symmetry classes (even/odd about the centre
//!   in X and in Y) decouple and are solved one by one;
//! * conditioning: each 1-D basis is replaced by the discrete clamped-beam modes — along X the
//!   buckling modes normalised by $`\int w_X^2`$, along Y the vibration modes normalised by
//!   $`\int w^2`$ — obtained from symmetric eigenproblems of well-conditioned matrices (the
//!   span, hence the Ritz value, is unchanged; on example 1 at degrees 100 × 100 the raw Shen
//!   basis gives the same λ_c to 1e-15, so this is a safety margin, not a necessity);
//! * the pencil $`K\varphi = \lambda G\varphi`$ (K symmetric positive definite) is solved by a
//!   Cholesky factorisation $`K = LL^T`$ and Lanczos with full reorthogonalisation for the
//!   largest eigenvalue $`\mu = 1/\lambda_c`$ of $`L^{-1} G L^{-T}`$.

// Each test binary (and the example) that includes this module uses a different part of it.
#![allow(dead_code)]

use nalgebra::{Cholesky, DMatrix, DVector, SymmetricEigen};
use std::f64::consts::PI;

// ------------------------------------------------------------------------------------------
// Quadrature and Legendre polynomials
// ------------------------------------------------------------------------------------------

/// Gauss–Legendre rule with `count` points on [−1, 1] (nodes ascending, exactly symmetric);
/// exact for polynomials of degree ≤ 2 `count` − 1. Newton iteration on $`P_n`$.
pub fn gauss_legendre(count: usize) -> (Vec<f64>, Vec<f64>) {
    let n = count;
    let mut nodes = vec![0.0; n];
    let mut weights = vec![0.0; n];
    for i in 0..n.div_ceil(2) {
        let mut x = (PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        for _ in 0..100 {
            let (value, derivative) = legendre_and_slope(n, x);
            let step = value / derivative;
            x -= step;
            if step.abs() <= 1e-15 {
                break;
            }
        }
        if 2 * i + 1 == n {
            x = 0.0;
        }
        let slope = legendre_and_slope(n, x).1;
        let weight = 2.0 / ((1.0 - x * x) * slope * slope);
        nodes[i] = -x;
        nodes[n - 1 - i] = x;
        weights[i] = weight;
        weights[n - 1 - i] = weight;
    }
    (nodes, weights)
}

/// $`(P_n(x), P_n'(x))`$ by the three-term recurrence, for |x| < 1.
fn legendre_and_slope(n: usize, x: f64) -> (f64, f64) {
    let (mut previous, mut current) = (1.0, x);
    if n == 0 {
        return (1.0, 0.0);
    }
    for k in 1..n {
        let next = ((2 * k + 1) as f64 * x * current - k as f64 * previous) / (k + 1) as f64;
        previous = current;
        current = next;
    }
    (current, n as f64 * (x * current - previous) / (x * x - 1.0))
}

/// $`P_n, P_n', P_n''`$ for $`n = 0..=`$`max_degree` at `x` (valid on the closed interval):
/// $`P_{n+1}^{(r)} = P_{n-1}^{(r)} + (2n+1) P_n^{(r-1)}`$ for the derivatives.
pub fn legendre_with_derivatives(max_degree: usize, x: f64) -> [Vec<f64>; 3] {
    let size = max_degree + 1;
    let (mut value, mut first, mut second) = (vec![0.0; size], vec![0.0; size], vec![0.0; size]);
    value[0] = 1.0;
    if size > 1 {
        value[1] = x;
        first[1] = 1.0;
    }
    for n in 1..max_degree {
        let m = n as f64;
        value[n + 1] = ((2.0 * m + 1.0) * x * value[n] - m * value[n - 1]) / (m + 1.0);
        first[n + 1] = first[n - 1] + (2.0 * m + 1.0) * value[n];
        second[n + 1] = second[n - 1] + (2.0 * m + 1.0) * first[n];
    }
    [value, first, second]
}

// ------------------------------------------------------------------------------------------
// Shen's clamped Legendre basis on [−1, 1]
// ------------------------------------------------------------------------------------------

/// Number of clamped basis functions of polynomial degree ≤ `degree`: `degree − 3`.
pub fn clamped_basis_count(degree: usize) -> usize {
    degree.saturating_sub(3)
}

/// Coefficients $`(1, a_k, b_k)/\sqrt{d_k}`$ of $`L_k, L_{k+2}, L_{k+4}`$ in $`\phi_k`$.
fn shen_coefficients(k: usize) -> [f64; 3] {
    let kf = k as f64;
    let scale = 1.0 / (2.0 * (2.0 * kf + 3.0).powi(2) * (2.0 * kf + 5.0)).sqrt();
    let a = -2.0 * (2.0 * kf + 5.0) / (2.0 * kf + 7.0);
    let b = (2.0 * kf + 3.0) / (2.0 * kf + 7.0);
    [scale, a * scale, b * scale]
}

/// Values, first and second derivatives (in ξ) of $`\phi_k`$, `k` in `indices`, at `xi`.
pub fn clamped_basis_values(degree: usize, indices: &[usize], xi: f64) -> [Vec<f64>; 3] {
    let legendre = legendre_with_derivatives(degree, xi);
    let mut out = [
        vec![0.0; indices.len()],
        vec![0.0; indices.len()],
        vec![0.0; indices.len()],
    ];
    for (slot, &k) in indices.iter().enumerate() {
        let [c0, c2, c4] = shen_coefficients(k);
        for order in 0..3 {
            let p = &legendre[order];
            out[order][slot] = c0 * p[k] + c2 * p[k + 2] + c4 * p[k + 4];
        }
    }
    out
}

/// Parity about the centre of a side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Parity {
    /// $`f(-\xi) = f(\xi)`$.
    Even,
    /// $`f(-\xi) = -f(\xi)`$.
    Odd,
}

impl Parity {
    /// The basis indices `k ≤ degree − 4` with this parity.
    pub fn indices(self, degree: usize) -> Vec<usize> {
        let start = match self {
            Parity::Even => 0,
            Parity::Odd => 1,
        };
        (start..clamped_basis_count(degree)).step_by(2).collect()
    }
}

/// Symmetry class of a mode about the plate's centre lines.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Symmetry {
    /// Parity in X about $`X = L_X/2`$.
    pub x: Parity,
    /// Parity in Y about $`Y = L_Y/2`$.
    pub y: Parity,
}

impl Symmetry {
    /// The four classes.
    pub const ALL: [Symmetry; 4] = [
        Symmetry {
            x: Parity::Even,
            y: Parity::Even,
        },
        Symmetry {
            x: Parity::Odd,
            y: Parity::Even,
        },
        Symmetry {
            x: Parity::Even,
            y: Parity::Odd,
        },
        Symmetry {
            x: Parity::Odd,
            y: Parity::Odd,
        },
    ];
}

impl std::fmt::Display for Symmetry {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let name = |p: Parity| match p {
            Parity::Even => "even",
            Parity::Odd => "odd",
        };
        write!(f, "{}-X/{}-Y", name(self.x), name(self.y))
    }
}

// ------------------------------------------------------------------------------------------
// One-dimensional matrices
// ------------------------------------------------------------------------------------------

/// Physical 1-D integrals over $`[0, L]`$ of the clamped functions of one parity
/// ($`X = \tfrac L2 (1 + \xi)`$, derivatives in X).
#[derive(Clone, Debug)]
pub struct LineMatrices {
    /// $`\int f_i f_j`$.
    pub value: DMatrix<f64>,
    /// $`\int f_i' f_j'`$.
    pub slope: DMatrix<f64>,
    /// $`\int f_i'' f_j''`$.
    pub curvature: DMatrix<f64>,
    /// $`\int f_i'' f_j`$ (not assumed symmetric: it is $`-\int f_i' f_j'`$ only through the
    /// clamped conditions).
    pub curvature_value: DMatrix<f64>,
}

impl LineMatrices {
    /// Gauss–Legendre assembly with `degree + 4` points (exact for these polynomials).
    pub fn assemble(degree: usize, indices: &[usize], length: f64) -> Self {
        let n = indices.len();
        let half = 0.5 * length;
        let mut m = [
            DMatrix::zeros(n, n),
            DMatrix::zeros(n, n),
            DMatrix::zeros(n, n),
        ];
        let mut curvature_value = DMatrix::zeros(n, n);
        let (nodes, weights) = gauss_legendre(degree + 4);
        for (&xi, &weight) in nodes.iter().zip(&weights) {
            let [v, d1, d2] = clamped_basis_values(degree, indices, xi);
            let (v, d1, d2) = (
                DVector::from_vec(v),
                DVector::from_vec(d1),
                DVector::from_vec(d2),
            );
            m[0].ger(weight, &v, &v, 1.0);
            m[1].ger(weight, &d1, &d1, 1.0);
            m[2].ger(weight, &d2, &d2, 1.0);
            curvature_value.ger(weight, &d2, &v, 1.0);
        }
        let [value, slope, curvature] = m;
        LineMatrices {
            value: value * half,
            slope: slope / half,
            curvature: curvature / half.powi(3),
            curvature_value: curvature_value / half,
        }
    }

    /// The same integrals in the basis $`g_j = \sum_i T_{ij} f_i`$.
    pub fn transformed(&self, t: &DMatrix<f64>) -> Self {
        let congruence = |m: &DMatrix<f64>| t.transpose() * m * t;
        LineMatrices {
            value: congruence(&self.value),
            slope: congruence(&self.slope),
            curvature: congruence(&self.curvature),
            curvature_value: congruence(&self.curvature_value),
        }
    }
}

/// `T` with $`T^T N T = I`$ and $`T^T S T`$ diagonal (ascending), for SPD `norm` = N and
/// symmetric `other` = S: Cholesky of N, then the symmetric eigenproblem of
/// $`R^{-1} S R^{-T}`$. Returns `T` and the diagonal.
fn simultaneous_diagonalisation(
    norm: &DMatrix<f64>,
    other: &DMatrix<f64>,
) -> (DMatrix<f64>, Vec<f64>) {
    let r = Cholesky::new(symmetrised(norm))
        .expect("norm matrix is SPD")
        .unpack();
    let r_inv_s = r.solve_lower_triangular(other).expect("triangular");
    let c = r
        .solve_lower_triangular(&r_inv_s.transpose())
        .expect("triangular");
    let eigen = SymmetricEigen::new(symmetrised(&c));
    let mut order: Vec<usize> = (0..eigen.eigenvalues.len()).collect();
    order.sort_by(|&i, &j| eigen.eigenvalues[i].total_cmp(&eigen.eigenvalues[j]));
    let q = DMatrix::from_fn(c.nrows(), order.len(), |i, j| {
        eigen.eigenvectors[(i, order[j])]
    });
    let t = r
        .transpose()
        .solve_upper_triangular(&q)
        .expect("triangular");
    (t, order.iter().map(|&i| eigen.eigenvalues[i]).collect())
}

fn symmetrised(m: &DMatrix<f64>) -> DMatrix<f64> {
    (m + m.transpose()) * 0.5
}

/// How each 1-D basis is conditioned before the 2-D assembly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LineBasis {
    /// Shen's functions as they are ($`\int\phi''\phi'' = I`$).
    Shen,
    /// Discrete clamped-beam modes: along X buckling modes with $`\int g'g' = I`$, along Y
    /// vibration modes with $`\int g g = I`$ (the default).
    BeamModes,
}

/// Which 1-D integral the beam modes of a side are orthonormal for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Normalisation {
    /// $`\int g_i' g_j' = \delta_{ij}`$ (buckling modes: the loaded direction X).
    Slope,
    /// $`\int g_i g_j = \delta_{ij}`$ (vibration modes: the transverse direction Y).
    Value,
}

/// The 1-D matrices of one side and the change of basis from Shen's functions.
struct Line {
    matrices: LineMatrices,
    to_shen: DMatrix<f64>,
    indices: Vec<usize>,
}

impl Line {
    fn new(
        degree: usize,
        parity: Parity,
        length: f64,
        basis: LineBasis,
        normalisation: Normalisation,
    ) -> Self {
        let indices = parity.indices(degree);
        let shen = LineMatrices::assemble(degree, &indices, length);
        let to_shen = match basis {
            LineBasis::Shen => DMatrix::identity(indices.len(), indices.len()),
            LineBasis::BeamModes => {
                let other = match normalisation {
                    Normalisation::Slope => &shen.slope,
                    Normalisation::Value => &shen.value,
                };
                let (t, diagonal) = simultaneous_diagonalisation(&shen.curvature, other);
                let scale = DMatrix::from_diagonal(&DVector::from_iterator(
                    diagonal.len(),
                    diagonal.iter().map(|d| 1.0 / d.sqrt()),
                ));
                t * scale
            }
        };
        let matrices = shen.transformed(&to_shen);
        Line {
            matrices,
            to_shen,
            indices,
        }
    }
}

// ------------------------------------------------------------------------------------------
// Problem definition and 2-D assembly
// ------------------------------------------------------------------------------------------

/// Plate geometry and bending stiffness.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClampedPlate {
    /// $`L_X`$ (mm).
    pub length_x: f64,
    /// $`L_Y`$ (mm).
    pub length_y: f64,
    /// $`D = E h^3 / (12(1-\nu^2))`$ (N·mm).
    pub bending_stiffness: f64,
    /// $`\nu`$.
    pub poisson_ratio: f64,
}

impl ClampedPlate {
    /// From thickness, Young's modulus and Poisson's ratio.
    pub fn new(
        length_x: f64,
        length_y: f64,
        thickness: f64,
        young: f64,
        poisson_ratio: f64,
    ) -> Self {
        let bending_stiffness =
            young * thickness.powi(3) / (12.0 * (1.0 - poisson_ratio * poisson_ratio));
        ClampedPlate {
            length_x,
            length_y,
            bending_stiffness,
            poisson_ratio,
        }
    }
}

/// Membrane state $`N_X = T_X - \lambda c_X`$, $`N_Y = T_Y - \lambda c_Y`$, $`N_{XY} = 0`$.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MembraneLoading {
    /// $`T_X \ge 0`$ (N/mm), fixed tension along X.
    pub tension_x: f64,
    /// $`T_Y \ge 0`$ (N/mm), fixed tension along Y.
    pub tension_y: f64,
    /// $`c_X \ge 0`$, compression along X per unit load.
    pub compression_x: f64,
    /// $`c_Y \ge 0`$, compression along Y per unit load.
    pub compression_y: f64,
}

impl MembraneLoading {
    /// The paper's example 1: $`N_X = -\lambda`$, $`N_Y = T`$.
    pub fn tension_compression(tension_y: f64) -> Self {
        MembraneLoading {
            tension_x: 0.0,
            tension_y,
            compression_x: 1.0,
            compression_y: 0.0,
        }
    }
}

/// Polynomial degrees along X and Y (the basis has `degree − 3` functions per side).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Degrees {
    /// Along X.
    pub x: usize,
    /// Along Y.
    pub y: usize,
}

/// Sum of $`c\,(A\otimes B)`$ terms; index of $`f_i(X) g_j(Y)`$ is `i · ny + j`.
struct KroneckerSum {
    terms: Vec<(f64, DMatrix<f64>, DMatrix<f64>)>,
    nx: usize,
    ny: usize,
}

impl KroneckerSum {
    fn new(nx: usize, ny: usize) -> Self {
        KroneckerSum {
            terms: Vec::new(),
            nx,
            ny,
        }
    }

    fn add(&mut self, coefficient: f64, x: &DMatrix<f64>, y: &DMatrix<f64>) {
        if coefficient != 0.0 {
            self.terms.push((coefficient, x.clone(), y.clone()));
        }
    }

    /// Symmetric part $`\tfrac c2 (A\otimes B + A^T\otimes B^T)`$.
    fn add_symmetrised(&mut self, coefficient: f64, x: &DMatrix<f64>, y: &DMatrix<f64>) {
        self.add(0.5 * coefficient, x, y);
        self.add(0.5 * coefficient, &x.transpose(), &y.transpose());
    }

    fn dense(&self) -> DMatrix<f64> {
        let (nx, ny) = (self.nx, self.ny);
        let mut out = DMatrix::zeros(nx * ny, nx * ny);
        for (c, a, b) in &self.terms {
            for k in 0..nx {
                for l in 0..ny {
                    for i in 0..nx {
                        let factor = c * a[(i, k)];
                        if factor == 0.0 {
                            continue;
                        }
                        for j in 0..ny {
                            out[(i * ny + j, k * ny + l)] += factor * b[(j, l)];
                        }
                    }
                }
            }
        }
        out
    }

    /// $`\sum c\,(A\otimes B)v`$ as $`\sum c\, B V A^T`$ with `V` the ny × nx reshape of `v`.
    fn apply(&self, v: &DVector<f64>) -> DVector<f64> {
        let matrix = DMatrix::from_column_slice(self.ny, self.nx, v.as_slice());
        let mut out = DMatrix::zeros(self.ny, self.nx);
        for (c, a, b) in &self.terms {
            out += (b * &matrix * a.transpose()) * *c;
        }
        DVector::from_column_slice(out.as_slice())
    }

    fn quadratic_form(&self, v: &DVector<f64>) -> f64 {
        v.dot(&self.apply(v))
    }
}

/// The bending, Gaussian-curvature, stiffness and load operators of one symmetry class.
struct ClassOperators {
    /// $`\int D[w_{XX}^2 + w_{YY}^2 + 2\nu w_{XX}w_{YY} + 2(1-\nu)w_{XY}^2]`$.
    bending: KroneckerSum,
    /// $`\int (w_{XX}w_{YY} - w_{XY}^2)`$ (zero for clamped edges).
    gaussian: KroneckerSum,
    /// Bending plus $`T_X\int w_X^2 + T_Y\int w_Y^2`$.
    stiffness: KroneckerSum,
    /// $`c_X\int w_X^2 + c_Y\int w_Y^2`$.
    load: KroneckerSum,
}

fn class_operators(
    plate: &ClampedPlate,
    loading: &MembraneLoading,
    x: &LineMatrices,
    y: &LineMatrices,
) -> ClassOperators {
    let (nx, ny) = (x.value.nrows(), y.value.nrows());
    let (d, nu) = (plate.bending_stiffness, plate.poisson_ratio);
    let cross_y = y.curvature_value.transpose();
    let mut bending = KroneckerSum::new(nx, ny);
    bending.add(d, &x.curvature, &y.value);
    bending.add(d, &x.value, &y.curvature);
    bending.add_symmetrised(2.0 * nu * d, &x.curvature_value, &cross_y);
    bending.add(2.0 * (1.0 - nu) * d, &x.slope, &y.slope);
    let mut gaussian = KroneckerSum::new(nx, ny);
    gaussian.add_symmetrised(1.0, &x.curvature_value, &cross_y);
    gaussian.add(-1.0, &x.slope, &y.slope);
    let mut stiffness = KroneckerSum::new(nx, ny);
    stiffness.terms = bending.terms.clone();
    stiffness.add(loading.tension_x, &x.slope, &y.value);
    stiffness.add(loading.tension_y, &x.value, &y.slope);
    let mut load = KroneckerSum::new(nx, ny);
    load.add(loading.compression_x, &x.slope, &y.value);
    load.add(loading.compression_y, &x.value, &y.slope);
    ClassOperators {
        bending,
        gaussian,
        stiffness,
        load,
    }
}

// ------------------------------------------------------------------------------------------
// Dense linear algebra
// ------------------------------------------------------------------------------------------

/// Block size of [`blocked_cholesky`].
const CHOLESKY_BLOCK: usize = 96;

/// Lower Cholesky factor `L` ($`A = LL^T`$) of the symmetric positive definite `a` (its lower
/// triangle is read), right-looking by blocks so that most of the work is matrix products;
/// `None` if `a` is not numerically positive definite.
pub fn blocked_cholesky(mut a: DMatrix<f64>) -> Option<DMatrix<f64>> {
    let n = a.nrows();
    let mut k = 0;
    while k < n {
        let b = CHOLESKY_BLOCK.min(n - k);
        let diagonal = Cholesky::new(a.view((k, k), (b, b)).clone_owned())?.unpack();
        a.view_mut((k, k), (b, b)).copy_from(&diagonal);
        let rest = n - k - b;
        if rest > 0 {
            let panel_transposed = a.view((k + b, k), (rest, b)).transpose();
            let panel = diagonal
                .solve_lower_triangular(&panel_transposed)?
                .transpose();
            a.view_mut((k + b, k), (rest, b)).copy_from(&panel);
            subtract_lower_product(&mut a, k + b, &panel);
        }
        k += b;
    }
    a.fill_upper_triangle(0.0, 1);
    Some(a)
}

/// `a[start.., start..] −= panel · panelᵀ` on the lower triangle (by column blocks).
fn subtract_lower_product(a: &mut DMatrix<f64>, start: usize, panel: &DMatrix<f64>) {
    let rest = panel.nrows();
    let mut j = 0;
    while j < rest {
        let width = CHOLESKY_BLOCK.min(rest - j);
        let left = panel.rows(j, rest - j);
        let right = panel.rows(j, width).transpose();
        let mut target = a.view_mut((start + j, start + j), (rest - j, width));
        target.gemm(-1.0, &left, &right, 1.0);
        j += width;
    }
}

// ------------------------------------------------------------------------------------------
// Largest eigenpair by Lanczos
// ------------------------------------------------------------------------------------------

/// Result of [`largest_eigenpair`].
#[derive(Clone, Debug)]
pub struct LanczosResult {
    /// Largest eigenvalue μ.
    pub value: f64,
    /// Unit eigenvector.
    pub vector: DVector<f64>,
    /// Number of operator applications.
    pub steps: usize,
    /// $`\|Cv - \mu v\|/\mu`$ (from the Lanczos recurrence).
    pub relative_residual: f64,
}

/// Largest eigenpair of the symmetric positive semi-definite operator `apply` on ℝⁿ: Lanczos with
/// full (twice repeated) reorthogonalisation, explicit restarts from the Ritz vector every
/// `restart_length` steps, stopping when the relative residual is below `tolerance`.
pub fn largest_eigenpair(
    dimension: usize,
    mut apply: impl FnMut(&DVector<f64>) -> DVector<f64>,
    tolerance: f64,
) -> LanczosResult {
    let restart_length = dimension.min(300);
    let mut start = pseudo_random_vector(dimension);
    let mut steps = 0;
    loop {
        let (basis, alphas, betas) =
            lanczos_run(&mut apply, &start, restart_length, tolerance, &mut steps);
        let (value, ritz, residual) = top_ritz_pair(&alphas, &betas);
        let mut vector = DVector::zeros(dimension);
        for (q, s) in basis.iter().zip(ritz.iter()) {
            vector.axpy(*s, q, 1.0);
        }
        vector.normalize_mut();
        let relative_residual = residual / value;
        if relative_residual <= tolerance
            || basis.len() == dimension
            || steps >= 50 * dimension.max(20)
        {
            return LanczosResult {
                value,
                vector,
                steps,
                relative_residual,
            };
        }
        start = vector;
    }
}

type LanczosRun = (Vec<DVector<f64>>, Vec<f64>, Vec<f64>);

/// Up to `length` Lanczos steps from `start`; checks convergence every 10 steps.
fn lanczos_run(
    apply: &mut impl FnMut(&DVector<f64>) -> DVector<f64>,
    start: &DVector<f64>,
    length: usize,
    tolerance: f64,
    steps: &mut usize,
) -> LanczosRun {
    let mut basis = vec![start.normalize()];
    let (mut alphas, mut betas) = (Vec::new(), Vec::new());
    loop {
        let j = basis.len() - 1;
        let mut w = apply(&basis[j]);
        *steps += 1;
        alphas.push(basis[j].dot(&w));
        for _ in 0..2 {
            for q in &basis {
                let projection = q.dot(&w);
                w.axpy(-projection, q, 1.0);
            }
        }
        let beta = w.norm();
        betas.push(beta);
        let scale = alphas.iter().fold(0.0_f64, |m, a| m.max(a.abs()));
        let full = basis.len() == length || beta <= 1e-14 * scale;
        if full || basis.len() % 10 == 0 {
            let (value, _, residual) = top_ritz_pair(&alphas, &betas);
            if full || residual <= tolerance * value {
                return (basis, alphas, betas);
            }
        }
        basis.push(w / beta);
    }
}

/// Largest eigenpair of the Lanczos tridiagonal matrix and the residual estimate
/// $`|\beta_m s_m|`$.
fn top_ritz_pair(alphas: &[f64], betas: &[f64]) -> (f64, DVector<f64>, f64) {
    let m = alphas.len();
    let t = DMatrix::from_fn(m, m, |i, j| {
        if i == j {
            alphas[i]
        } else if i + 1 == j || j + 1 == i {
            betas[i.min(j)]
        } else {
            0.0
        }
    });
    let eigen = SymmetricEigen::new(t);
    let top = eigen.eigenvalues.imax();
    let s = eigen.eigenvectors.column(top).into_owned();
    let residual = (betas[m - 1] * s[m - 1]).abs();
    (eigen.eigenvalues[top], s, residual)
}

/// Deterministic start vector (xorshift), so runs are reproducible.
fn pseudo_random_vector(dimension: usize) -> DVector<f64> {
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    DVector::from_fn(dimension, |_, _| {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    })
}

// ------------------------------------------------------------------------------------------
// One symmetry class
// ------------------------------------------------------------------------------------------

/// A buckling mode: $`w = \sum_{ij} C_{ij}\,\phi_{k_i}(\xi)\,\phi_{m_j}(\eta)`$ with Shen's
/// functions, $`\xi = 2X/L_X - 1`$, $`\eta = 2Y/L_Y - 1`$.
#[derive(Clone, Debug)]
pub struct Mode {
    /// Symmetry class.
    pub symmetry: Symmetry,
    /// Polynomial degrees.
    pub degrees: Degrees,
    /// Shen indices $`k_i`$ along X.
    pub indices_x: Vec<usize>,
    /// Shen indices $`m_j`$ along Y.
    pub indices_y: Vec<usize>,
    /// Coefficients `C` (rows along X, columns along Y).
    pub coefficients: DMatrix<f64>,
    /// $`L_X`$, $`L_Y`$.
    pub lengths: (f64, f64),
}

impl Mode {
    /// $`w(X, Y)`$.
    pub fn w_at(&self, x: f64, y: f64) -> f64 {
        self.grid(&[x], &[y])[(0, 0)]
    }

    /// $`w`$ on the tensor grid `xs` × `ys` (rows along X).
    pub fn grid(&self, xs: &[f64], ys: &[f64]) -> DMatrix<f64> {
        let phi_x = basis_matrix(self.degrees.x, &self.indices_x, xs, self.lengths.0);
        let phi_y = basis_matrix(self.degrees.y, &self.indices_y, ys, self.lengths.1);
        phi_x * &self.coefficients * phi_y.transpose()
    }
}

/// Rows: points; columns: basis functions.
fn basis_matrix(degree: usize, indices: &[usize], points: &[f64], length: f64) -> DMatrix<f64> {
    let mut out = DMatrix::zeros(points.len(), indices.len());
    for (row, &p) in points.iter().enumerate() {
        let xi = (2.0 * p / length - 1.0).clamp(-1.0, 1.0);
        let [v, _, _] = clamped_basis_values(degree, indices, xi);
        for (column, value) in v.into_iter().enumerate() {
            out[(row, column)] = value;
        }
    }
    out
}

/// Lowest eigenpair of one symmetry class.
#[derive(Clone, Debug)]
pub struct ClassSolution {
    /// $`\lambda_c`$ of the class (N/mm for unit $`c`$).
    pub critical_load: f64,
    /// The mode.
    pub mode: Mode,
    /// Number of unknowns of the class.
    pub unknowns: usize,
    /// Lanczos operator applications.
    pub lanczos_steps: usize,
    /// Lanczos relative residual.
    pub relative_residual: f64,
    /// Rayleigh quotient of the mode recomputed from the operators (check of the eigensolver).
    pub rayleigh_quotient: f64,
    /// $`\int(w_{XX}w_{YY} - w_{XY}^2) / \int[(\Delta w)^2 + \ldots]`$ for the mode: zero up to
    /// round-off for clamped edges.
    pub gaussian_ratio: f64,
}

/// Solves one symmetry class.
pub fn solve_class(
    plate: &ClampedPlate,
    loading: &MembraneLoading,
    degrees: Degrees,
    symmetry: Symmetry,
    basis: LineBasis,
) -> ClassSolution {
    let line_x = Line::new(
        degrees.x,
        symmetry.x,
        plate.length_x,
        basis,
        Normalisation::Slope,
    );
    let line_y = Line::new(
        degrees.y,
        symmetry.y,
        plate.length_y,
        basis,
        Normalisation::Value,
    );
    let operators = class_operators(plate, loading, &line_x.matrices, &line_y.matrices);
    let unknowns = line_x.indices.len() * line_y.indices.len();
    let l = blocked_cholesky(operators.stiffness.dense()).expect("stiffness is SPD");
    let apply = |v: &DVector<f64>| {
        let mut z = v.clone();
        l.tr_solve_lower_triangular_mut(&mut z);
        let mut out = operators.load.apply(&z);
        l.solve_lower_triangular_mut(&mut out);
        out
    };
    let eigen = largest_eigenpair(unknowns, apply, 1e-11);
    assert!(
        eigen.relative_residual <= 1e-8,
        "Lanczos did not converge: residual {:e} after {} steps",
        eigen.relative_residual,
        eigen.steps
    );
    let mut phi = eigen.vector.clone();
    l.tr_solve_lower_triangular_mut(&mut phi);
    let stiffness = operators.stiffness.quadratic_form(&phi);
    let rayleigh_quotient = stiffness / operators.load.quadratic_form(&phi);
    let gaussian_ratio = operators.gaussian.quadratic_form(&phi) * plate.bending_stiffness
        / operators.bending.quadratic_form(&phi);
    let psi =
        DMatrix::from_column_slice(line_y.indices.len(), line_x.indices.len(), phi.as_slice());
    let coefficients = &line_x.to_shen * psi.transpose() * line_y.to_shen.transpose();
    let mode = Mode {
        symmetry,
        degrees,
        indices_x: line_x.indices,
        indices_y: line_y.indices,
        coefficients,
        lengths: (plate.length_x, plate.length_y),
    };
    ClassSolution {
        critical_load: 1.0 / eigen.value,
        mode,
        unknowns,
        lanczos_steps: eigen.steps,
        relative_residual: eigen.relative_residual,
        rayleigh_quotient,
        gaussian_ratio,
    }
}

// ------------------------------------------------------------------------------------------
// Whole plate: all classes, mode analysis
// ------------------------------------------------------------------------------------------

/// Relative amplitude below which samples of the line count as zero when half-waves are counted
/// (this drops the tiny tails next to the clamped ends).
pub const HALF_WAVE_THRESHOLD: f64 = 1e-3;

/// Linear buckling of the clamped rectangle.
#[derive(Clone, Debug)]
pub struct SpectralBuckling {
    /// $`\lambda_c`$: smallest over the four classes.
    pub critical_load: f64,
    /// Class of the critical mode.
    pub symmetry: Symmetry,
    /// Number of half-waves along the line $`Y`$ = [`Self::line_y`]: lobes of one sign whose
    /// samples exceed [`HALF_WAVE_THRESHOLD`] × the line's maximum.
    pub half_waves_midline: usize,
    /// Carrier wavelength: twice the mean spacing of the zero crossings of $`w`$ in the central
    /// half $`L_X/4 \le X \le 3L_X/4`$ of the line; `None` with fewer than two crossings.
    pub wavelength: Option<f64>,
    /// Line used: $`L_Y/2`$ when the mode is even in Y, else the Y of largest |w|.
    pub line_y: f64,
    /// $`\lambda_c`$ of every class.
    pub class_loads: Vec<(Symmetry, f64)>,
    /// Critical class's solution (mode normalised to max |w| = 1 on the line, positive there).
    pub critical: ClassSolution,
}

impl SpectralBuckling {
    /// Deflection of the normalised critical mode.
    pub fn w_at(&self, x: f64, y: f64) -> f64 {
        self.critical.mode.w_at(x, y)
    }
}

/// All four classes for a general loading.
pub fn plate_buckling(
    plate: &ClampedPlate,
    loading: &MembraneLoading,
    degrees: Degrees,
) -> SpectralBuckling {
    let mut solutions: Vec<ClassSolution> = Symmetry::ALL
        .iter()
        .map(|&s| solve_class(plate, loading, degrees, s, LineBasis::BeamModes))
        .collect();
    let class_loads = solutions
        .iter()
        .map(|s| (s.mode.symmetry, s.critical_load))
        .collect();
    let best = (0..solutions.len())
        .min_by(|&i, &j| {
            solutions[i]
                .critical_load
                .total_cmp(&solutions[j].critical_load)
        })
        .expect("four classes");
    let critical = solutions.swap_remove(best);
    analyse(plate, critical, class_loads)
}

/// The brief's entry point: $`N_X = -\lambda`$, $`N_Y = T`$ = `tension`, clamped edges.
#[allow(clippy::too_many_arguments)]
pub fn clamped_rectangle_buckling(
    lx: f64,
    ly: f64,
    h: f64,
    e: f64,
    nu: f64,
    tension: f64,
    degree_x: usize,
    degree_y: usize,
) -> SpectralBuckling {
    let plate = ClampedPlate::new(lx, ly, h, e, nu);
    let loading = MembraneLoading::tension_compression(tension);
    plate_buckling(
        &plate,
        &loading,
        Degrees {
            x: degree_x,
            y: degree_y,
        },
    )
}

fn analyse(
    plate: &ClampedPlate,
    mut critical: ClassSolution,
    class_loads: Vec<(Symmetry, f64)>,
) -> SpectralBuckling {
    let samples = (20 * critical.mode.degrees.x).max(4000);
    let xs: Vec<f64> = (0..=samples)
        .map(|i| plate.length_x * i as f64 / samples as f64)
        .collect();
    let line_y = match critical.mode.symmetry.y {
        Parity::Even => 0.5 * plate.length_y,
        Parity::Odd => line_of_largest_deflection(&critical.mode, &xs, plate.length_y),
    };
    let line = critical.mode.grid(&xs, &[line_y]).column(0).into_owned();
    let peak = line.iamax();
    let scale = line[peak];
    critical.mode.coefficients /= scale;
    let line = line / scale;
    let half_waves_midline = count_half_waves(line.as_slice(), HALF_WAVE_THRESHOLD);
    let wavelength =
        central_wavelength(&critical.mode, &xs, line.as_slice(), line_y, plate.length_x);
    SpectralBuckling {
        critical_load: critical.critical_load,
        symmetry: critical.mode.symmetry,
        half_waves_midline,
        wavelength,
        line_y,
        class_loads,
        critical,
    }
}

fn line_of_largest_deflection(mode: &Mode, xs: &[f64], length_y: f64) -> f64 {
    let ys: Vec<f64> = (0..=400).map(|j| length_y * j as f64 / 400.0).collect();
    let grid = mode.grid(xs, &ys);
    let (_, column) = grid.iamax_full();
    ys[column]
}

/// Lobes of one sign among the samples above `threshold` × max |w|.
pub fn count_half_waves(values: &[f64], threshold: f64) -> usize {
    let cut = threshold * values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let mut lobes = 0;
    let mut last_sign = 0.0;
    for &v in values.iter().filter(|v| v.abs() > cut) {
        if v.signum() != last_sign {
            lobes += 1;
            last_sign = v.signum();
        }
    }
    lobes
}

/// Twice the mean spacing of the zero crossings (refined by bisection) in the central half.
/// Samples that are exactly zero (a node on a symmetry line) are stepped over.
fn central_wavelength(
    mode: &Mode,
    xs: &[f64],
    line: &[f64],
    line_y: f64,
    length_x: f64,
) -> Option<f64> {
    let (low, high) = (0.25 * length_x, 0.75 * length_x);
    let signed: Vec<usize> = (0..line.len()).filter(|&i| line[i] != 0.0).collect();
    let mut crossings = Vec::new();
    for pair in signed.windows(2) {
        let (i, j) = (pair[0], pair[1]);
        if xs[i] >= low && xs[j] <= high && line[i] * line[j] < 0.0 {
            crossings.push(bisect_zero(|x| mode.w_at(x, line_y), xs[i], xs[j]));
        }
    }
    if crossings.len() < 2 {
        return None;
    }
    let span = crossings[crossings.len() - 1] - crossings[0];
    Some(2.0 * span / (crossings.len() - 1) as f64)
}

fn bisect_zero(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64) -> f64 {
    let fa = f(a);
    for _ in 0..60 {
        let m = 0.5 * (a + b);
        if f(m) * fa > 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    0.5 * (a + b)
}
