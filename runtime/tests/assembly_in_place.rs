//! The tangent assembled in place, its directional derivative without a dual-number matrix, and
//! the matrices a problem recycles.
//!
//! * **In place, the same sums.** On a Saint-Venant–Kirchhoff membrane (the plate
//!   $`[0, 4] \times [0, 2]`$ mm, 4 × 2 Q8, clamped on `left`) at a deformed state,
//!   [`Problem::tangent_into`] over a matrix holding other values gives the tangent of
//!   [`Assembler::tangent_values`] bit for bit.
//! * **The directional derivative.** [`Problem::tangent_derivative_into`] gives, bit for bit, the
//!   dual parts of the tangent assembled on dual numbers (the dual parts of a sum are the sums of
//!   the dual parts), and agrees with the central difference of the tangent along the same
//!   direction to $`10^{-7}`$ of the largest entry (the membrane's tangent is quadratic in
//!   $`U`$: the difference is exact to rounding).
//! * **Recycled matrices.** A matrix handed back ([`Problem::recycle_matrix`]) is the next
//!   [`Problem::new_matrix`]'s memory, zeroed; at most [`MAX_RECYCLED_MATRICES`] are kept, and a
//!   matrix on another problem's pattern is not.
//!
//! [`Assembler::tangent_values`]: wrinkle_runtime::fem::assembly::Assembler::tangent_values

use std::sync::Arc;

use num_dual::Dual64;
use wrinkle_runtime::fem::{DirichletCondition, Loads, Mesh};
use wrinkle_runtime::problem::{MAX_RECYCLED_MATRICES, Problem};

#[path = "support/svk_membrane.rs"]
mod svk_membrane;
use svk_membrane::SvkMembrane;

fn membrane(nx: usize, ny: usize) -> Problem<SvkMembrane> {
    let mesh = Arc::new(Mesh::rectangle(4.0, 2.0, nx, ny, 1.0).unwrap());
    let support = [
        DirichletCondition::fixed("left", 0),
        DirichletCondition::fixed("left", 1),
    ];
    Problem::new(
        SvkMembrane::new(1000.0, 0.3, 1.0),
        mesh,
        &support,
        &Loads::default(),
    )
    .unwrap()
}

/// A deformed state with every free dof moved (a smooth, deterministic pattern).
fn deformed(n: usize, scale: f64) -> Vec<f64> {
    (0..n)
        .map(|i| scale * ((0.37 * i as f64).sin() + 0.5 * (1.3 * i as f64).cos()))
        .collect()
}

#[test]
fn svk_membrane_tangent_assembled_in_place_over_other_values_is_the_assembled_tangent() {
    let problem = membrane(4, 2);
    let free = deformed(problem.free_count(), 0.05);
    let global = problem.dofs().expand(&free, 0.0);
    let expected = problem.assembler.tangent_values(&global);
    let mut matrix = problem.new_matrix();
    matrix.values.fill(7.5);
    problem.tangent_into(&free, 0.0, &mut matrix);
    assert!(expected.iter().any(|v| *v != 0.0));
    for (slot, (got, want)) in matrix.values.iter().zip(&expected).enumerate() {
        assert_eq!(
            got.to_bits(),
            want.to_bits(),
            "slot {slot}: {got} vs {want}"
        );
    }
}

#[test]
fn svk_membrane_tangent_derivative_is_the_dual_tangent_and_its_central_difference() {
    let problem = membrane(4, 2);
    let n = problem.free_count();
    let free = deformed(n, 0.05);
    let direction = deformed(n, 1.0)
        .into_iter()
        .rev()
        .map(|d| 0.3 * d)
        .collect::<Vec<_>>();
    let mut derivative = problem.new_matrix();
    derivative.values.fill(-3.0);
    problem.tangent_derivative_into(&free, 0.0, &direction, 0.0, &mut derivative);

    // Bit for bit the dual parts of the tangent on dual numbers.
    let dual: Vec<Dual64> = free
        .iter()
        .zip(&direction)
        .map(|(&u, &d)| Dual64::new(u, d))
        .collect();
    let global = problem.dofs().expand(&dual, Dual64::from_re(0.0));
    let on_duals = problem.assembler.tangent_values(&global);
    for (slot, (got, want)) in derivative.values.iter().zip(&on_duals).enumerate() {
        assert_eq!(got.to_bits(), want.eps.to_bits(), "slot {slot}");
    }

    // The central difference of the tangent along the direction.
    let h = 1e-3;
    let shifted = |sign: f64| {
        let moved: Vec<f64> = free
            .iter()
            .zip(&direction)
            .map(|(u, d)| u + sign * h * d)
            .collect();
        let mut matrix = problem.new_matrix();
        problem.tangent_into(&moved, 0.0, &mut matrix);
        matrix.values
    };
    let (plus, minus) = (shifted(1.0), shifted(-1.0));
    let largest = derivative.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(largest > 0.0);
    for (slot, ((p, m), d)) in plus.iter().zip(&minus).zip(&derivative.values).enumerate() {
        let difference = (p - m) / (2.0 * h);
        assert!(
            (difference - d).abs() <= 1e-7 * largest,
            "slot {slot}: central difference {difference} vs {d}"
        );
    }
}

#[test]
fn a_recycled_matrix_is_the_next_new_matrix_zeroed_and_at_most_two_are_kept() {
    let problem = membrane(4, 2);
    let dirty = |value: f64| {
        let mut matrix = problem.new_matrix();
        matrix.values.fill(value);
        matrix
    };
    let held: Vec<_> = (0..MAX_RECYCLED_MATRICES + 1)
        .map(|k| dirty(k as f64 + 1.0))
        .collect();
    let addresses: Vec<usize> = held.iter().map(|m| m.values.as_ptr() as usize).collect();
    for matrix in held {
        problem.recycle_matrix(matrix);
    }
    assert_eq!(problem.recycled_matrices(), MAX_RECYCLED_MATRICES);
    // The kept ones come back, last in first out, zeroed.
    let again: Vec<_> = (0..MAX_RECYCLED_MATRICES)
        .map(|_| problem.new_matrix())
        .collect();
    assert_eq!(problem.recycled_matrices(), 0);
    for (k, matrix) in again.iter().enumerate() {
        assert_eq!(
            matrix.values.as_ptr() as usize,
            addresses[MAX_RECYCLED_MATRICES - 1 - k]
        );
        assert!(matrix.values.iter().all(|v| v.to_bits() == 0));
        assert_eq!(matrix.values.len(), problem.assembler.pattern().nnz());
    }
    assert!(problem.new_matrix().values.iter().all(|v| v.to_bits() == 0));

    // Another problem's pattern, even of the same size, is not kept.
    let other = membrane(4, 2);
    problem.recycle_matrix(other.new_matrix());
    assert_eq!(problem.recycled_matrices(), 0);
    problem.recycle_matrix(problem.new_matrix());
    assert_eq!(problem.recycled_matrices(), 1);
}
