//! Buckling eigen-solver against closed forms and dense references.

use std::f64::consts::PI;
use std::sync::Arc;

use nalgebra::{DMatrix, SymmetricEigen};
use wrinkle_runtime::linear::{
    BucklingOptions, FactorizationKind, LinearError, SparseFactorization, SparseMatrix,
    SparsityPattern, smallest_positive_buckling,
};

/// Grid Laplacian $`-\Delta_h`$ (5-point, unit spacing, Dirichlet) on `nx × ny` nodes, or the 1-D
/// second difference when `ny == 1`.
fn grid_laplacian(nx: usize, ny: usize) -> SparseMatrix {
    let n = nx * ny;
    let index = |i: usize, j: usize| j * nx + i;
    let mut entries = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            if i + 1 < nx {
                entries.push((index(i + 1, j), index(i, j)));
            }
            if j + 1 < ny {
                entries.push((index(i, j + 1), index(i, j)));
            }
        }
    }
    let pattern = Arc::new(SparsityPattern::from_symmetric_entries(n, entries.clone()).unwrap());
    let mut matrix = SparseMatrix::zeros(pattern);
    let diagonal = if ny == 1 { 2.0 } else { 4.0 };
    for k in 0..n {
        matrix.add_to(k, k, diagonal).unwrap();
    }
    for (row, column) in entries {
        matrix.add_to(row, column, -1.0).unwrap();
        matrix.add_to(column, row, -1.0).unwrap();
    }
    matrix
}

/// Diagonal matrix $`-\mathrm{diag}(d)`$ on the pattern of `like`.
fn negative_diagonal(like: &SparseMatrix, diagonal: impl Fn(usize) -> f64) -> SparseMatrix {
    let mut matrix = SparseMatrix::zeros(like.pattern.clone());
    for k in 0..like.dimension() {
        matrix.add_to(k, k, -diagonal(k)).unwrap();
    }
    matrix
}

/// $`k`$-th eigenvalue of tridiag(−1, 2, −1) of order $`n`$, $`2 - 2\cos(k\pi/(n+1))`$,
/// written as $`4\sin^2(k\pi/(2(n+1)))`$ to avoid cancellation for small $`k`$.
fn second_difference_eigenvalue(k: usize, n: usize) -> f64 {
    (4.0 * (k as f64 * PI / (2.0 * (n as f64 + 1.0))).sin().powi(2)).max(0.0)
}

fn factorize(a: &SparseMatrix) -> SparseFactorization {
    let mut factorization = SparseFactorization::analyze(&a.pattern).unwrap();
    assert_eq!(
        factorization.factorize(a).unwrap(),
        FactorizationKind::Cholesky
    );
    factorization
}

fn assert_load_factors(computed: &[f64], expected: &[f64], tolerance: f64) {
    assert_eq!(
        computed.len(),
        expected.len(),
        "{computed:?} vs {expected:?}"
    );
    for (value, reference) in computed.iter().zip(expected) {
        let error = (value - reference).abs() / reference.abs();
        assert!(
            error < tolerance,
            "λ = {value} vs {reference}: relative error {error:e}"
        );
    }
}

/// Checks $`(A + \lambda B)\varphi \approx 0`$ and $`\varphi^\top A \varphi = 1`$ independently.
fn assert_modes_satisfy_equation(
    a: &SparseMatrix,
    b: &SparseMatrix,
    modes: &[wrinkle_runtime::linear::BucklingMode],
) {
    let n = a.dimension();
    for mode in modes {
        let mut av = vec![0.0; n];
        let mut bv = vec![0.0; n];
        a.multiply_into(&mode.vector, &mut av);
        b.multiply_into(&mode.vector, &mut bv);
        let a_norm: f64 = mode.vector.iter().zip(&av).map(|(x, y)| x * y).sum();
        assert!((a_norm - 1.0).abs() < 1e-12);
        let residual: f64 = av
            .iter()
            .zip(&bv)
            .map(|(x, y)| (x + mode.load_factor * y).powi(2))
            .sum::<f64>()
            .sqrt()
            / av.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!(residual < 1e-9, "residual {residual:e}");
        assert!((residual - mode.residual).abs() < 1e-12);
    }
}

#[test]
fn one_dimensional_laplacian_with_identity_load() {
    let n = 200;
    let a = grid_laplacian(n, 1);
    let b = negative_diagonal(&a, |_| 1.0);
    let factor = factorize(&a);
    let options = BucklingOptions {
        modes: 4,
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    assert!(solution.converged);
    let expected: Vec<f64> = (1..=4)
        .map(|k| second_difference_eigenvalue(k, n))
        .collect();
    let computed: Vec<f64> = solution.modes.iter().map(|mode| mode.load_factor).collect();
    assert_load_factors(&computed, &expected, 1e-11);
    assert_modes_satisfy_equation(&a, &b, &solution.modes);
    // The first mode is the half sine sin(kπ i/(n+1)), positive with our sign convention.
    let first = &solution.modes[0].vector;
    let sine: Vec<f64> = (0..n)
        .map(|i| ((i + 1) as f64 * PI / (n as f64 + 1.0)).sin())
        .collect();
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
    let scale = dot(first, &sine) / dot(&sine, &sine);
    assert!(scale > 0.0);
    let deviation: f64 = first
        .iter()
        .zip(&sine)
        .map(|(value, s)| (value - scale * s).powi(2))
        .sum::<f64>()
        .sqrt();
    assert!(
        deviation < 1e-8 * dot(first, first).sqrt(),
        "deviation {deviation:e}"
    );
}

#[test]
fn small_problem_exhausting_the_space_is_exact() {
    let n = 6;
    let a = grid_laplacian(n, 1);
    let b = negative_diagonal(&a, |_| 1.0);
    let factor = factorize(&a);
    let options = BucklingOptions {
        modes: 3,
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    let expected: Vec<f64> = (1..=3)
        .map(|k| second_difference_eigenvalue(k, n))
        .collect();
    let computed: Vec<f64> = solution.modes.iter().map(|mode| mode.load_factor).collect();
    assert_load_factors(&computed, &expected, 1e-12);
}

#[test]
fn lumped_mass_finite_elements_approach_continuum_frequencies() {
    // Bar on [0, 1], linear elements: A = (1/h) tridiag(−1, 2, −1), lumped mass M = h I.
    // Discrete λ_k = (2 − 2 cos(kπh))/h², which tends to (kπ)².
    let n = 399;
    let h = 1.0 / (n as f64 + 1.0);
    let mut a = grid_laplacian(n, 1);
    a.values.iter_mut().for_each(|value| *value /= h);
    let b = negative_diagonal(&a, |_| h);
    let factor = factorize(&a);
    let options = BucklingOptions {
        modes: 3,
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    let expected: Vec<f64> = (1..=3)
        .map(|k| second_difference_eigenvalue(k, n) / (h * h))
        .collect();
    let computed: Vec<f64> = solution.modes.iter().map(|mode| mode.load_factor).collect();
    assert_load_factors(&computed, &expected, 1e-10);
    assert!((computed[0] - PI * PI).abs() < 1e-4 * PI * PI);
    assert_modes_satisfy_equation(&a, &b, &solution.modes);
}

/// Dense reference: eigenvalues $`\mu`$ of $`L^{-1} B L^{-\top}`$ ($`A = L L^\top`$), giving
/// $`\lambda = -1/\mu`$ for $`\mu < 0`$, ascending.
fn dense_positive_load_factors(a: &SparseMatrix, b: &SparseMatrix, count: usize) -> Vec<f64> {
    let cholesky = a.to_dense().cholesky().unwrap();
    let l = cholesky.l();
    let l_inverse = l.clone().try_inverse().unwrap();
    let reduced: DMatrix<f64> = &l_inverse * b.to_dense() * l_inverse.transpose();
    let reduced = 0.5 * (&reduced + reduced.transpose());
    let mut factors: Vec<f64> = SymmetricEigen::new(reduced)
        .eigenvalues
        .iter()
        .filter(|mu| **mu < 0.0)
        .map(|mu| -1.0 / mu)
        .collect();
    factors.sort_by(f64::total_cmp);
    factors.truncate(count);
    factors
}

#[test]
fn variable_mass_matches_dense_generalised_eigenvalues() {
    let n = 120;
    let a = grid_laplacian(n, 1);
    let b = negative_diagonal(&a, |k| 1.0 + 0.5 * (0.37 * k as f64).sin());
    let factor = factorize(&a);
    let options = BucklingOptions {
        modes: 4,
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    let computed: Vec<f64> = solution.modes.iter().map(|mode| mode.load_factor).collect();
    assert_load_factors(&computed, &dense_positive_load_factors(&a, &b, 4), 1e-10);
    assert_modes_satisfy_equation(&a, &b, &solution.modes);
}

#[test]
fn indefinite_load_stiffness_matches_dense_reference() {
    // Compression in the middle, tension near the ends: B has both signs.
    let n = 150;
    let a = grid_laplacian(n, 1);
    let b = negative_diagonal(&a, |k| {
        -(2.0 * PI * (k as f64 + 0.5) / n as f64).cos() + 0.2
    });
    let factor = factorize(&a);
    let options = BucklingOptions {
        modes: 3,
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    let computed: Vec<f64> = solution.modes.iter().map(|mode| mode.load_factor).collect();
    assert_load_factors(&computed, &dense_positive_load_factors(&a, &b, 3), 1e-10);
    assert_modes_satisfy_equation(&a, &b, &solution.modes);
}

#[test]
fn two_dimensional_grid_of_ten_thousand_dofs() {
    let (nx, ny) = (125, 80);
    let a = grid_laplacian(nx, ny);
    assert_eq!(a.dimension(), 10_000);
    let b = negative_diagonal(&a, |_| 1.0);
    let factor = factorize(&a);
    let options = BucklingOptions {
        modes: 3,
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    let eigenvalue = |j: usize, k: usize| {
        second_difference_eigenvalue(j, nx) + second_difference_eigenvalue(k, ny)
    };
    let mut expected: Vec<f64> = (1..=4)
        .flat_map(|j| (1..=4).map(move |k| (j, k)))
        .map(|(j, k)| eigenvalue(j, k))
        .collect();
    expected.sort_by(f64::total_cmp);
    expected.truncate(3);
    let computed: Vec<f64> = solution.modes.iter().map(|mode| mode.load_factor).collect();
    assert_load_factors(&computed, &expected, 1e-11);
    assert_modes_satisfy_equation(&a, &b, &solution.modes);
    // Its cost as work, not wall time: with the thick restarts, the three wanted load factors
    // (the fourth only 7 % above the third: 2.13e-3, 3.99e-3, 6.64e-3, 7.10e-3) take a few
    // dozen solves with the factor (26 here), not hundreds.
    assert!(solution.iterations <= 40, "{} solves", solution.iterations);
}

#[test]
fn positive_semidefinite_load_has_no_positive_load_factor() {
    let n = 50;
    let a = grid_laplacian(n, 1);
    // B ⪰ 0 (tension and unloaded dofs): A + λB is positive definite for every λ > 0.
    let b = negative_diagonal(&a, |k| if k % 3 == 0 { 0.0 } else { -1.0 });
    let factor = factorize(&a);
    let error =
        smallest_positive_buckling(&a, &factor, &b, &BucklingOptions::default()).unwrap_err();
    assert!(
        matches!(error, LinearError::NoPositiveLoadFactor { .. }),
        "{error}"
    );
    assert!(
        error
            .to_string()
            .contains("no positive buckling load factor")
    );
    let zero = SparseMatrix::zeros(a.pattern.clone());
    assert!(matches!(
        smallest_positive_buckling(&a, &factor, &zero, &BucklingOptions::default()),
        Err(LinearError::NoPositiveLoadFactor { .. })
    ));
}

#[test]
fn invalid_inputs_are_rejected() {
    let a = grid_laplacian(20, 1);
    let b = negative_diagonal(&a, |_| 1.0);
    let factor = factorize(&a);
    let no_modes = BucklingOptions {
        modes: 0,
        ..Default::default()
    };
    assert!(matches!(
        smallest_positive_buckling(&a, &factor, &b, &no_modes),
        Err(LinearError::InvalidOption { .. })
    ));
    // A indefinite: the A-inner product does not exist.
    let mut shifted = a.clone();
    for k in 0..20 {
        shifted.add_to(k, k, -0.7).unwrap();
    }
    let mut indefinite = SparseFactorization::analyze(&shifted.pattern).unwrap();
    indefinite.factorize(&shifted).unwrap();
    assert!(matches!(
        smallest_positive_buckling(&shifted, &indefinite, &b, &BucklingOptions::default()),
        Err(LinearError::InvalidOption { what }) if what.contains("positive definite")
    ));
    // A factorisation of another matrix.
    assert!(matches!(
        smallest_positive_buckling(&shifted, &factor, &b, &BucklingOptions::default()),
        Err(LinearError::InvalidOption { what }) if what.contains("not a factorisation")
    ));
    // Too strict a budget: one restart of a small basis cannot reach 1e-14.
    let starved = BucklingOptions {
        modes: 1,
        tolerance: 1e-14,
        max_krylov: 3,
        max_restarts: 1,
        ..Default::default()
    };
    let big = grid_laplacian(400, 1);
    let big_b = negative_diagonal(&big, |_| 1.0);
    let big_factor = factorize(&big);
    let error = smallest_positive_buckling(&big, &big_factor, &big_b, &starved).unwrap_err();
    assert!(matches!(error, LinearError::NotConverged { .. }), "{error}");
    let accepted = smallest_positive_buckling(
        &big,
        &big_factor,
        &big_b,
        &BucklingOptions {
            accept_unconverged: true,
            ..starved
        },
    )
    .unwrap();
    assert!(!accepted.converged);
    assert_eq!(accepted.modes.len(), 1);
}

#[test]
fn stiff_fourth_order_operator_keeps_accuracy() {
    // Beam-like pencil: A = D² (κ(A) ≈ 1.6·10⁹), B = −D with D = tridiag(−1, 2, −1) of order
    // 200, so (A + λB)φ = D(D − λ)φ = 0 and λ_k are the eigenvalues of D.
    let n = 200;
    let d = grid_laplacian(n, 1);
    let mut entries = Vec::new();
    for i in 1..n {
        entries.push((i, i - 1));
        if i >= 2 {
            entries.push((i, i - 2));
        }
    }
    let pattern = Arc::new(SparsityPattern::from_symmetric_entries(n, entries).unwrap());
    let mut a = SparseMatrix::zeros(pattern.clone());
    let mut b = SparseMatrix::zeros(pattern);
    for row in 0..n {
        for column in row.saturating_sub(2)..(row + 3).min(n) {
            let square: f64 = (row.saturating_sub(1)..(row + 2).min(n))
                .map(|k| d.get(row, k) * d.get(k, column))
                .sum();
            a.add_to(row, column, square).unwrap();
            b.add_to(row, column, -d.get(row, column)).unwrap();
        }
    }
    let factor = factorize(&a);
    let options = BucklingOptions {
        modes: 2,
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    let expected: Vec<f64> = (1..=2)
        .map(|k| second_difference_eigenvalue(k, n))
        .collect();
    let computed: Vec<f64> = solution.modes.iter().map(|mode| mode.load_factor).collect();
    // Rounding in A φ for such smooth modes limits the accuracy to about ε κ(A)^{1/2}.
    assert_load_factors(&computed, &expected, 1e-9);
}

/// The half-sine modes $`\sin(k\pi (i+1)/(n+1))`$ of the 1-D second difference.
fn sine_mode(k: usize, n: usize) -> Vec<f64> {
    (0..n)
        .map(|i| (k as f64 * (i + 1) as f64 * PI / (n as f64 + 1.0)).sin())
        .collect()
}

#[test]
fn warm_start_near_the_mode_converges_before_the_basis_is_full() {
    // The eigen-solver checks convergence as its basis grows: started near the first mode it
    // stops long before filling the 40-vector basis, at the closed-form load factor.
    let n = 400;
    let a = grid_laplacian(n, 1);
    let b = negative_diagonal(&a, |_| 1.0);
    let factor = factorize(&a);
    let (first, second) = (sine_mode(1, n), sine_mode(2, n));
    let start: Vec<f64> = first
        .iter()
        .zip(&second)
        .map(|(x, y)| x + 1e-2 * y)
        .collect();
    let options = BucklingOptions {
        start: Some(start),
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    assert!(solution.converged);
    assert!(
        solution.iterations < options.max_krylov,
        "{} operator applications",
        solution.iterations
    );
    assert_load_factors(
        &[solution.modes[0].load_factor],
        &[second_difference_eigenvalue(1, n)],
        1e-11,
    );
}

#[test]
fn warm_start_orthogonal_to_the_first_mode_still_finds_it() {
    // A neighbour's mode can be exactly orthogonal to the wanted one (a symmetric mode there,
    // an antisymmetric one here): a Krylov space built on it alone never contains the first
    // mode. Here A = I and B = −diag(d) with the largest d first, so A⁻¹B is diagonal and keeps
    // a zero first component exactly zero, rounding included: only the solver's pseudo-random
    // admixture to every start vector can find λ₁ = 1/d₀ (without it the answer is 1/d₁).
    let n = 400;
    let pattern = grid_laplacian(n, 1);
    let a = negative_diagonal(&pattern, |_| -1.0);
    let d = |k: usize| {
        if k == 0 {
            4.0
        } else {
            2.0 - k as f64 / n as f64
        }
    };
    let b = negative_diagonal(&pattern, d);
    let factor = factorize(&a);
    let mut start = vec![1.0; n];
    start[0] = 0.0;
    let options = BucklingOptions {
        start: Some(start),
        ..Default::default()
    };
    let solution = smallest_positive_buckling(&a, &factor, &b, &options).unwrap();
    assert!(solution.converged);
    assert_load_factors(&[solution.modes[0].load_factor], &[1.0 / d(0)], 1e-11);
}
