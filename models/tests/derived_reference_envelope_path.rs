//! The derived reference envelope model on the default scene (issue 29, "done means"): the same
//! critical load and the same path as the hand-written `reference-envelope`.
//!
//! Source: THEORY.md §9 (example 1, the default scene), `envelope_support` for the scene; the
//! models `models/src/reference_envelope.rs` and `models/src/derived_reference_envelope.rs`.
//! Parameters: $`E = 70000`$ MPa, $`\nu = 0.3`$, $`h = 0.05`$ mm, $`L_X \times L_Y = 400 \times
//! 200`$ mm, $`N_Y = 10`$ N/mm, the closed-form optimum $`Q = 0.2354346`$ /mm of (42).
//!
//! * `derived_reference_envelope_buckles_at_the_reference_load`: linear buckling on the default
//!   mesh (32 × 16 Q8): $`\lambda_c = 0.08952133`$ N/mm for both, relative difference below
//!   1e-9 (measured 3.6e-15).
//! * `derived_reference_envelope_follows_the_reference_path`: on the same mesh, the path with
//!   the paper's imperfection (a uniform load $`f = 10^{-6}`$ N/mm² on the envelope), traced by
//!   Newton at the loads $`\lambda = k\,\lambda_c/20`$, $`k = 0 … 25`$ (to $`1.25\lambda_c`$,
//!   where the wrinkles reach 4.1 thicknesses), each solve started from the secant
//!   extrapolation of the two previous points and converged to round-off: at every load the
//!   states of the two models (every free dof, max norm) differ by less than 1e-9 relative
//!   (measured at worst 9.7e-15). About 5 s in a test build.
//!
//! Why Newton at fixed loads and not the ANM of `wrinkle run`: the two models' kernels are
//! different expressions of the same density (the derived one is emitted from the normal form),
//! so they differ in round-off, and the ANM's step length
//! $`(\varepsilon\|u_1\|/\|u_n\|)^{1/(n-1)}`$ reads the highest-order series coefficient, which
//! on the nearly linear first step is round-off itself: `wrinkle run` and `wrinkle run --set
//! model.name=derived-reference-envelope` give the same critical load (relative 2.4e-15) and
//! points of one curve, but at loads that differ by 2e-3 relative from the first step on. The
//! path compared at the same loads is the path itself.

mod envelope_support;

use envelope_support::*;
use wrinkle_models::{DerivedReferenceEnvelope, ReferenceEnvelope};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::BodyLoad;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::newton::{NewtonOptions, newton};

/// The imperfection: a uniform load density on the envelope (N/mm²), not scaled by λ.
const IMPERFECTION: f64 = 1e-6;

/// Loads of the path, in units of $`\lambda_c/20`$: $`0, \lambda_c/20, …, 1.25\lambda_c`$.
const LOAD_STEPS: usize = 25;

/// Example 1 with the imperfection on the field of role `envelope`.
fn imperfect_example1<M: EnergyModel>(model: M, nx: usize, ny: usize) -> Problem<M> {
    let envelope = M::SPEC.field_index("w").unwrap();
    let imperfection = BodyLoad {
        field: envelope,
        value: IMPERFECTION,
        proportional: false,
    };
    example1_with_body_loads(model, nx, ny, &[imperfection])
}

/// The equilibrium states at the loads `loads`, each converged to round-off by Newton from
/// the secant extrapolation of the two previous ones (zero for the first).
fn path<M: EnergyModel>(problem: &Problem<M>, loads: &[f64]) -> Vec<Vec<f64>> {
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut matrix = problem.new_matrix();
    let options = NewtonOptions {
        tolerance: 1e-10,
        max_iterations: 40,
    };
    let mut states: Vec<Vec<f64>> = Vec::new();
    for &load in loads {
        let guess = match states.as_slice() {
            [] => vec![0.0; problem.free_count()],
            [only] => only.clone(),
            [.., before, last] => last.iter().zip(before).map(|(l, b)| 2.0 * l - b).collect(),
        };
        let solution = newton(problem, guess, load, &mut factor, &mut matrix, &options)
            .unwrap_or_else(|error| panic!("{}: Newton at λ = {load}: {error}", M::SPEC.name));
        states.push(solution.solution);
    }
    states
}

/// Max-norm relative difference.
fn relative_difference(value: &[f64], truth: &[f64]) -> f64 {
    let scale = truth.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let difference = value
        .iter()
        .zip(truth)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    difference / scale
}

/// Both models' paths on an `nx × ny` mesh agree state by state to 1e-9.
fn compare_paths(nx: usize, ny: usize) {
    let q = optimal_wavenumber();
    let hand_written = imperfect_example1(envelope_model::<ReferenceEnvelope>(q), nx, ny);
    let derived = imperfect_example1(envelope_model::<DerivedReferenceEnvelope>(q), nx, ny);
    let critical =
        buckle(&example1(envelope_model::<ReferenceEnvelope>(q), nx, ny)).critical_loads[0];
    let loads: Vec<f64> = (0..=LOAD_STEPS)
        .map(|k| k as f64 * critical / 20.0)
        .collect();
    let (hand_written_path, derived_path) = (path(&hand_written, &loads), path(&derived, &loads));
    let envelope = ReferenceEnvelope::SPEC.field_index("w").unwrap();
    let mut worst = 0.0_f64;
    for ((load, truth), value) in loads.iter().zip(&hand_written_path).zip(&derived_path) {
        let difference = relative_difference(value, truth);
        let amplitude = field_magnitudes(&hand_written, truth)[envelope];
        println!(
            "λ/λ_c = {:.2}: envelope amplitude max|w|/h = {:.6e}, relative difference {difference:.2e}",
            load / critical,
            2.0 * amplitude / THICKNESS
        );
        worst = worst.max(difference);
    }
    println!("{nx} × {ny}: worst relative difference over the path {worst:.2e}");
    assert!(worst < 1e-9, "{worst:e}");
}

#[test]
fn derived_reference_envelope_buckles_at_the_reference_load() {
    let q = optimal_wavenumber();
    let hand_written =
        buckle(&example1(envelope_model::<ReferenceEnvelope>(q), 32, 16)).critical_loads[0];
    let derived = buckle(&example1(
        envelope_model::<DerivedReferenceEnvelope>(q),
        32,
        16,
    ))
    .critical_loads[0];
    let difference = (derived - hand_written).abs() / hand_written;
    println!(
        "reference-envelope λ_c = {hand_written:.15e}, derived-reference-envelope λ_c = {derived:.15e}, relative difference {difference:.2e}"
    );
    assert!(difference < 1e-9, "{difference:e}");
}

#[test]
fn derived_reference_envelope_follows_the_reference_path() {
    compare_paths(32, 16);
}
