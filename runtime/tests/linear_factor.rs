//! Sparse factorisations against dense nalgebra references.

use std::sync::Arc;

use nalgebra::{DVector, SymmetricEigen};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_runtime::linear::{
    FactorizationKind, LinearError, SparseFactorization, SparseMatrix, SparsityPattern,
};

/// Random symmetric pattern: each column couples to `per_column` random other columns.
fn random_pattern(n: usize, per_column: usize, rng: &mut StdRng) -> Arc<SparsityPattern> {
    let mut entries = Vec::new();
    for column in 0..n {
        for _ in 0..per_column {
            entries.push((rng.random_range(0..n), column));
        }
    }
    Arc::new(SparsityPattern::from_symmetric_entries(n, entries).unwrap())
}

/// Symmetric matrix on `pattern` with random off-diagonal entries in [-1, 1] and diagonal
/// $`\pm(\sum_j |a_{ij}| + \mathrm{margin})`$, the sign chosen by `negative(i)`.
fn dominant_matrix(
    pattern: &Arc<SparsityPattern>,
    rng: &mut StdRng,
    margin: f64,
    negative: impl Fn(usize) -> bool,
) -> SparseMatrix {
    let n = pattern.dimension();
    let mut matrix = SparseMatrix::zeros(pattern.clone());
    for column in 0..n {
        for &row in pattern.rows_of_column(column) {
            if row < column {
                let value = rng.random_range(-1.0..1.0);
                matrix.add_to(row, column, value).unwrap();
                matrix.add_to(column, row, value).unwrap();
            }
        }
    }
    let dense = matrix.to_dense();
    for i in 0..n {
        let off_diagonal: f64 = dense.row(i).iter().map(|value| value.abs()).sum();
        let sign = if negative(i) { -1.0 } else { 1.0 };
        matrix.add_to(i, i, sign * (off_diagonal + margin)).unwrap();
    }
    matrix
}

fn random_vector(n: usize, rng: &mut StdRng) -> Vec<f64> {
    (0..n).map(|_| rng.random_range(-1.0..1.0)).collect()
}

/// Solves with the sparse factorisation and compares with nalgebra's dense LU.
fn assert_solution_matches_dense(
    factorization: &SparseFactorization,
    matrix: &SparseMatrix,
    rhs: &[f64],
) {
    let dense = matrix.to_dense();
    let reference = dense
        .clone()
        .lu()
        .solve(&DVector::from_column_slice(rhs))
        .expect("dense reference is regular");
    let mut solution = rhs.to_vec();
    factorization.solve_in_place(&mut solution).unwrap();
    let error = (DVector::from_column_slice(&solution) - &reference).norm() / reference.norm();
    assert!(error < 1e-10, "relative error {error:e}");
}

fn dense_negative_eigenvalues(matrix: &SparseMatrix) -> usize {
    SymmetricEigen::new(matrix.to_dense())
        .eigenvalues
        .iter()
        .filter(|value| **value < 0.0)
        .count()
}

#[test]
fn cholesky_solves_random_spd_matrices_like_dense_lu() {
    let mut rng = StdRng::seed_from_u64(11);
    for n in [1, 7, 60, 150] {
        let pattern = random_pattern(n, 3, &mut rng);
        let matrix = dominant_matrix(&pattern, &mut rng, 0.5, |_| false);
        let mut factorization = SparseFactorization::analyze(&pattern).unwrap();
        assert_eq!(factorization.kind(), None);
        assert_eq!(
            factorization.factorize(&matrix).unwrap(),
            FactorizationKind::Cholesky
        );
        assert_eq!(factorization.kind(), Some(FactorizationKind::Cholesky));
        assert_eq!(factorization.negative_pivots(), Some(0));
        assert!(factorization.factor_nnz() >= n);
        let rhs = random_vector(n, &mut rng);
        assert_solution_matches_dense(&factorization, &matrix, &rhs);
    }
}

#[test]
fn indefinite_matrices_use_ldlt_with_correct_inertia() {
    let mut rng = StdRng::seed_from_u64(12);
    for (n, threshold) in [
        (
            50,
            faer::sparse::linalg::SupernodalThreshold::FORCE_SIMPLICIAL,
        ),
        (
            120,
            faer::sparse::linalg::SupernodalThreshold::FORCE_SIMPLICIAL,
        ),
        (
            120,
            faer::sparse::linalg::SupernodalThreshold::FORCE_SUPERNODAL,
        ),
        (
            300,
            faer::sparse::linalg::SupernodalThreshold::FORCE_SUPERNODAL,
        ),
    ] {
        let pattern = random_pattern(n, 4, &mut rng);
        // Strong diagonal dominance with mixed signs: pivots stay far from zero without pivoting.
        let matrix = dominant_matrix(&pattern, &mut rng, 1.0, |i| i % 3 == 1);
        let mut factorization =
            SparseFactorization::analyze_with_threshold(&pattern, threshold).unwrap();
        assert_eq!(
            factorization.factorize(&matrix).unwrap(),
            FactorizationKind::SymmetricIndefinite
        );
        let expected = dense_negative_eigenvalues(&matrix);
        assert!(expected > 0);
        assert_eq!(factorization.negative_pivots(), Some(expected));
        let rhs = random_vector(n, &mut rng);
        assert_solution_matches_dense(&factorization, &matrix, &rhs);
    }
}

#[test]
fn weakly_dominant_indefinite_matrix_is_solved_accurately() {
    // Margins near zero make some pivots small; either LDLᵀ (with refinement) or the LU fallback
    // must deliver dense-LU accuracy, and the inertia, when reported, must be right.
    let mut rng = StdRng::seed_from_u64(13);
    let pattern = random_pattern(80, 4, &mut rng);
    let mut matrix = dominant_matrix(&pattern, &mut rng, 0.0, |i| i % 2 == 0);
    for value in matrix.values.iter_mut() {
        *value *= 1.0 + 0.3 * rng.random_range(-1.0..1.0);
    }
    // Re-symmetrise after the perturbation.
    let dense = matrix.to_dense();
    for column in 0..80 {
        for &row in pattern.rows_of_column(column) {
            let slot = pattern.slot(row, column).unwrap();
            matrix.values[slot] = 0.5 * (dense[(row, column)] + dense[(column, row)]);
        }
    }
    let mut factorization = SparseFactorization::analyze(&pattern).unwrap();
    let kind = factorization.factorize(&matrix).unwrap();
    assert_ne!(kind, FactorizationKind::Cholesky);
    if let Some(negative) = factorization.negative_pivots() {
        assert_eq!(negative, dense_negative_eigenvalues(&matrix));
    }
    let rhs = random_vector(80, &mut rng);
    assert_solution_matches_dense(&factorization, &matrix, &rhs);
}

#[test]
fn zero_diagonal_saddle_blocks_fall_back_to_lu() {
    // Blocks [[0, a], [a, 0]] coupled weakly: every diagonal entry is zero, so LLᵀ and LDLᵀ
    // without pivoting break down at the first pivot whatever the ordering.
    let blocks = 20;
    let n = 2 * blocks;
    let mut rng = StdRng::seed_from_u64(14);
    let mut entries = Vec::new();
    for block in 0..blocks {
        entries.push((2 * block + 1, 2 * block));
        if block + 1 < blocks {
            entries.push((2 * block + 2, 2 * block + 1));
        }
    }
    let pattern = Arc::new(SparsityPattern::from_symmetric_entries(n, entries).unwrap());
    let mut matrix = SparseMatrix::zeros(pattern.clone());
    for block in 0..blocks {
        let a = 1.0 + rng.random_range(0.0..1.0);
        matrix.add_to(2 * block + 1, 2 * block, a).unwrap();
        matrix.add_to(2 * block, 2 * block + 1, a).unwrap();
        if block + 1 < blocks {
            let coupling = 0.1 * rng.random_range(-1.0..1.0);
            matrix
                .add_to(2 * block + 2, 2 * block + 1, coupling)
                .unwrap();
            matrix
                .add_to(2 * block + 1, 2 * block + 2, coupling)
                .unwrap();
        }
    }
    let mut factorization = SparseFactorization::analyze(&pattern).unwrap();
    assert_eq!(
        factorization.factorize(&matrix).unwrap(),
        FactorizationKind::Lu
    );
    assert_eq!(factorization.negative_pivots(), None);
    let rhs = random_vector(n, &mut rng);
    assert_solution_matches_dense(&factorization, &matrix, &rhs);
}

#[test]
fn refactorisation_reuses_the_symbolic_analysis() {
    let mut rng = StdRng::seed_from_u64(15);
    let pattern = random_pattern(90, 3, &mut rng);
    let mut factorization = SparseFactorization::analyze(&pattern).unwrap();
    let factor_nnz = factorization.factor_nnz();
    let kinds = [
        (0, FactorizationKind::Cholesky),
        (4, FactorizationKind::SymmetricIndefinite),
        (0, FactorizationKind::Cholesky),
        (2, FactorizationKind::SymmetricIndefinite),
    ];
    for (period, expected_kind) in kinds {
        let matrix = dominant_matrix(&pattern, &mut rng, 0.7, |i| period > 0 && i % period == 0);
        assert_eq!(factorization.factorize(&matrix).unwrap(), expected_kind);
        assert_eq!(factorization.factor_nnz(), factor_nnz);
        let rhs = random_vector(90, &mut rng);
        assert_solution_matches_dense(&factorization, &matrix, &rhs);
        if period > 0 {
            assert_eq!(
                factorization.negative_pivots(),
                Some(dense_negative_eigenvalues(&matrix))
            );
        }
    }
    // A matrix on another pattern is rejected.
    let other = random_pattern(90, 3, &mut rng);
    let foreign = dominant_matrix(&other, &mut rng, 1.0, |_| false);
    assert_eq!(
        factorization.factorize(&foreign),
        Err(LinearError::PatternMismatch)
    );
    assert_eq!(factorization.kind(), None);
    let mut rhs = vec![1.0; 90];
    assert_eq!(
        factorization.solve_in_place(&mut rhs),
        Err(LinearError::NotFactorized)
    );
}

/// Tridiagonal pattern of dimension n.
fn chain_pattern(n: usize) -> Arc<SparsityPattern> {
    Arc::new(SparsityPattern::from_symmetric_entries(n, (1..n).map(|i| (i, i - 1))).unwrap())
}

#[test]
fn zero_column_is_reported_as_singular_at_that_dof() {
    let n = 25;
    let pattern = chain_pattern(n);
    let mut matrix = SparseMatrix::zeros(pattern.clone());
    for i in 0..n {
        matrix.add_to(i, i, 2.0).unwrap();
        if i > 0 {
            matrix.add_to(i, i - 1, -1.0).unwrap();
            matrix.add_to(i - 1, i, -1.0).unwrap();
        }
    }
    // Dof 7 is "forgotten": its row and column are zero (an unconstrained, unloaded dof).
    let dead = 7;
    for column in 0..n {
        for &row in pattern.rows_of_column(column) {
            if row == dead || column == dead {
                let slot = pattern.slot(row, column).unwrap();
                matrix.values[slot] = 0.0;
            }
        }
    }
    let mut factorization = SparseFactorization::analyze(&pattern).unwrap();
    match factorization.factorize(&matrix) {
        Err(LinearError::Singular { column, pivot }) => {
            assert_eq!(column, dead);
            assert_eq!(pivot, 0.0);
        }
        other => panic!("expected a singular error, got {other:?}"),
    }
    assert!(
        LinearError::Singular {
            column: dead,
            pivot: 0.0
        }
        .to_string()
        .contains("dof (column) 7")
    );
}

#[test]
fn free_floating_chain_is_singular() {
    // 1-D Laplacian with free ends (Neumann): constant vectors are in the kernel.
    let n = 30;
    let pattern = chain_pattern(n);
    let mut matrix = SparseMatrix::zeros(pattern.clone());
    for i in 1..n {
        for (row, column, value) in [
            (i, i, 1.0),
            (i - 1, i - 1, 1.0),
            (i, i - 1, -1.0),
            (i - 1, i, -1.0),
        ] {
            matrix.add_to(row, column, value).unwrap();
        }
    }
    let mut factorization = SparseFactorization::analyze(&pattern).unwrap();
    match factorization.factorize(&matrix) {
        Err(LinearError::Singular { column, pivot }) => {
            assert!(column < n);
            assert!(pivot.abs() < 1e-12, "pivot {pivot:e}");
        }
        other => panic!("expected a singular error, got {other:?}"),
    }
}

#[test]
fn bad_inputs_give_errors() {
    let pattern = chain_pattern(4);
    let mut matrix = SparseMatrix::zeros(pattern.clone());
    for i in 0..4 {
        matrix.add_to(i, i, 1.0).unwrap();
    }
    matrix.add_to(2, 1, f64::NAN).unwrap();
    let mut factorization = SparseFactorization::analyze(&pattern).unwrap();
    assert!(matches!(
        factorization.factorize(&matrix),
        Err(LinearError::NonFinite { what }) if what.contains("(2, 1)")
    ));
    matrix.values.iter_mut().for_each(|value| *value = 0.0);
    for i in 0..4 {
        matrix.add_to(i, i, 1.0).unwrap();
    }
    factorization.factorize(&matrix).unwrap();
    let mut short = vec![1.0; 3];
    assert!(matches!(
        factorization.solve_in_place(&mut short),
        Err(LinearError::DimensionMismatch {
            expected: 4,
            found: 3,
            ..
        })
    ));
    let mut infinite = vec![1.0, f64::INFINITY, 0.0, 0.0];
    assert!(matches!(
        factorization.solve_in_place(&mut infinite),
        Err(LinearError::NonFinite { .. })
    ));
}

/// The 5-point Laplacian on a 100 × 100 grid (10⁴ dofs): the solve's residual (no dense
/// reference), and a fill-reducing ordering, judged by the factor's size and work rather than by
/// a wall time. On a `k × k` grid ($`n = k^2`$) nested dissection fills
/// $`\tfrac{31}{4} n \log_2 k + O(n)`$ entries with $`\tfrac{829}{84} n^{3/2} + O(n \log n)`$
/// multiplications (George 1973), where the natural (banded) ordering fills $`n k`$ with
/// $`n k^2`$; a factor within George's bounds is one of order $`n \log n`$ fill.
#[test]
fn large_grid_laplacian_factor_has_nested_dissection_fill() {
    let side = 100;
    let n = side * side;
    let index = |i: usize, j: usize| i * side + j;
    let mut entries = Vec::new();
    for i in 0..side {
        for j in 0..side {
            if i + 1 < side {
                entries.push((index(i + 1, j), index(i, j)));
            }
            if j + 1 < side {
                entries.push((index(i, j + 1), index(i, j)));
            }
        }
    }
    let pattern = Arc::new(SparsityPattern::from_symmetric_entries(n, entries.clone()).unwrap());
    let mut matrix = SparseMatrix::zeros(pattern.clone());
    for k in 0..n {
        matrix.add_to(k, k, 4.0).unwrap();
    }
    for (row, column) in entries {
        matrix.add_to(row, column, -1.0).unwrap();
        matrix.add_to(column, row, -1.0).unwrap();
    }
    let mut factorization = SparseFactorization::analyze(&pattern).unwrap();
    assert_eq!(
        factorization.factorize(&matrix).unwrap(),
        FactorizationKind::Cholesky
    );
    let mut rng = StdRng::seed_from_u64(16);
    let rhs = random_vector(n, &mut rng);
    let mut solution = rhs.clone();
    factorization.solve_in_place(&mut solution).unwrap();
    let mut product = vec![0.0; n];
    matrix.multiply_into(&solution, &mut product);
    let residual: f64 = product
        .iter()
        .zip(&rhs)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt();
    let rhs_norm = rhs.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(residual < 1e-12 * rhs_norm, "residual {residual:e}");
    // Fill and work within George's nested-dissection counts, far below the band's (n k =
    // 10⁶ entries, n k² = 10⁸ operations): 2.06e5 entries and 1.21e7 operations here.
    let (n, k) = (n as f64, side as f64);
    let fill = factorization.factor_nnz() as f64;
    let work = factorization.work();
    assert!(fill <= 31.0 / 4.0 * n * k.log2(), "fill {fill:e}");
    // `work` counts Σ c_j², a multiply–add per entry pair of a column: twice George's
    // multiplications (½ Σ c_j² to leading order).
    assert!(0.5 * work <= 829.0 / 84.0 * n.powf(1.5), "work {work:e}");
    assert!(fill <= 0.25 * n * k && work <= 0.25 * n * k * k);
}

/// The pattern of a `ex × ey` grid of 8-node quadrilaterals with `dofs` unknowns per node (the
/// plate's element).
fn serendipity_grid(ex: usize, ey: usize, dofs: usize) -> Arc<SparsityPattern> {
    let columns = 2 * ex + 1;
    let mut number = vec![usize::MAX; columns * (2 * ey + 1)];
    let mut nodes = 0;
    for i in 0..=2 * ey {
        for j in 0..columns {
            if i % 2 == 0 || j % 2 == 0 {
                number[i * columns + j] = nodes;
                nodes += 1;
            }
        }
    }
    let node = |i: usize, j: usize| number[i * columns + j];
    let mut elements = Vec::new();
    for a in 0..ey {
        for b in 0..ex {
            let (i, j) = (2 * a, 2 * b);
            let corners = [
                node(i, j),
                node(i, j + 1),
                node(i, j + 2),
                node(i + 1, j),
                node(i + 1, j + 2),
                node(i + 2, j),
                node(i + 2, j + 1),
                node(i + 2, j + 2),
            ];
            let list: Vec<Option<usize>> = corners
                .iter()
                .flat_map(|&n| (0..dofs).map(move |d| Some(n * dofs + d)))
                .collect();
            elements.push(list);
        }
    }
    Arc::new(SparsityPattern::from_element_dofs(
        nodes * dofs,
        elements.iter().map(Vec::as_slice),
    ))
}

/// The two-core substitution (`set_split_solve`, on by default from 20 000 unknowns) on a plate
/// pattern, forced on a small one: it solves positive definite ($`LL^\top`$) and indefinite
/// ($`LDL^\top`$) systems as faer's sequential solve does, to rounding, and gives the same bits
/// on one thread and on two.
#[test]
fn split_solve_matches_the_sequential_solve_and_is_the_same_on_one_and_two_threads() {
    use wrinkle_runtime::linear::factor::SupernodalThreshold;
    let pattern = serendipity_grid(48, 12, 3);
    let n = pattern.dimension();
    let mut rng = StdRng::seed_from_u64(30);
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    for (negative_every, kind) in [
        (0, FactorizationKind::Cholesky),
        (7, FactorizationKind::SymmetricIndefinite),
    ] {
        let matrix = dominant_matrix(&pattern, &mut rng, 0.5, |i| {
            negative_every > 0 && i % negative_every == 0
        });
        let mut split = SparseFactorization::analyze_with_threshold(
            &pattern,
            SupernodalThreshold::FORCE_SUPERNODAL,
        )
        .unwrap();
        let mut sequential = split.same_analysis().unwrap();
        assert!(
            split.set_split_solve(true),
            "a split exists on a 48 × 12 grid"
        );
        assert!(!sequential.set_split_solve(false));
        let [top, first, second] = split.split_entries().unwrap();
        assert!(
            top < first.min(second),
            "top {top}, groups {first}, {second}"
        );
        assert!(
            first.abs_diff(second) * 5 < first.max(second),
            "{first} vs {second}"
        );
        assert_eq!(split.factorize(&matrix).unwrap(), kind);
        assert_eq!(sequential.factorize(&matrix).unwrap(), kind);

        let rhs = random_vector(n, &mut rng);
        let mut reference = rhs.clone();
        sequential.solve_in_place(&mut reference).unwrap();
        let mut on_one = rhs.clone();
        one.install(|| split.solve_in_place(&mut on_one)).unwrap();
        let mut on_two = rhs.clone();
        two.install(|| split.solve_in_place(&mut on_two)).unwrap();
        assert_eq!(on_one, on_two, "{kind:?}: bits depend on the thread count");
        let scale = reference.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        let difference = reference
            .iter()
            .zip(&on_two)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(
            difference < 1e-12 * scale,
            "{kind:?}: {difference:e} of {scale:e}"
        );
        let mut product = vec![0.0; n];
        matrix.multiply_into(&on_two, &mut product);
        let residual = product
            .iter()
            .zip(&rhs)
            .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
        assert!(residual < 1e-12, "{kind:?}: residual {residual:e}");
    }
}
