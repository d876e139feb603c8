//! A foundation stiffness that varies along the beam, $`c(X)`$: the parameter `foundation`,
//! declared `[varying]` by the three beam models, given a piecewise-linear profile
//! ([`ParameterProfile`]) that the assembler evaluates at every quadrature point.
//!
//! Checked on the assembled problem (the kernels themselves are checked by
//! `every_model_kernels.rs`; what is new is which model instance each point uses):
//! * a one-point (constant) profile gives the same residual and tangent, bit for bit, as the
//!   constant parameter;
//! * with a varying profile the triad stays consistent: the residual is the central
//!   difference of the potential energy, the tangent the difference of the residual;
//! * the Taylor-mode right-hand side of order 2 along $`U_0 + aU_1`$ equals the order-2
//!   coefficient of the residual evaluated on truncated series;
//! * the winkler energy of a known state is $`\int \tfrac12 c(X) v^2\,dX`$ (quadrature exact);
//! * a profile on a parameter the model does not declare `[varying]` is refused, naming it.
//!
//! Parameters: `beam_support` ($`EI = c = 1`$, $`ES = 1200`$), $`L = 20`$, $`c(X)`$ through
//! $`(0, 0.5), (8, 1.5), (20, 1)`$, states $`\sin`$ combinations of amplitude 0.1.

mod beam_support;

use beam_support::*;
use wrinkle_models::{BeamEnvelope, BeamFull};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::{
    DirichletCondition, ElementKind, Loads, Mesh, ParameterProfile, ProfileAxis,
};
use wrinkle_runtime::problem::{Problem, ProblemError};
use wrinkle_runtime::series::Series;

const LENGTH: f64 = 20.0;

fn ramp() -> ParameterProfile {
    ParameterProfile::new(ProfileAxis::X, vec![[0.0, 0.5], [8.0, 1.5], [20.0, 1.0]]).unwrap()
}

fn profiled<M: EnergyModel>(mut problem: Problem<M>, profile: ParameterProfile) -> Problem<M> {
    problem
        .set_parameter_profiles(vec![("foundation".to_string(), profile)])
        .unwrap();
    problem
}

/// A smooth state of every free dof: `amplitude · sin(1.3 i + phase)`.
fn state(count: usize, amplitude: f64, phase: f64) -> Vec<f64> {
    (0..count)
        .map(|i| amplitude * (1.3 * i as f64 + phase).sin())
        .collect()
}

fn assert_close(label: &str, found: &[f64], expected: &[f64], tolerance: f64) {
    let scale = expected.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let worst = found
        .iter()
        .zip(expected)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    println!("{label}: largest difference {worst:.3e} of scale {scale:.3e}");
    assert!(
        worst <= tolerance * scale,
        "{label}: {worst:e} > {tolerance:e} · {scale:e}"
    );
}

/// Residual against the central difference of the potential energy, and the tangent times a
/// direction against the central difference of the residual.
fn check_triad<M: EnergyModel>(label: &str, problem: &Problem<M>) {
    let n = problem.free_count();
    let (u, direction) = (state(n, 0.1, 0.2), state(n, 1.0, 0.7));
    let load = 1.7;
    let step = 1e-6;
    let shifted = |sign: f64| -> Vec<f64> {
        u.iter()
            .zip(&direction)
            .map(|(a, d)| a + sign * step * d)
            .collect()
    };
    let residual = problem.residual(&u, load);
    let projected: f64 = residual.iter().zip(&direction).map(|(r, d)| r * d).sum();
    let difference = (problem.potential_energy(&shifted(1.0), load)
        - problem.potential_energy(&shifted(-1.0), load))
        / (2.0 * step);
    assert_close(
        &format!("{label}: residual"),
        &[projected],
        &[difference],
        1e-6,
    );
    let mut tangent = problem.new_matrix();
    problem.tangent_into(&u, load, &mut tangent);
    let mut product = vec![0.0; n];
    tangent.multiply_into(&direction, &mut product);
    let (plus, minus) = (
        problem.residual(&shifted(1.0), load),
        problem.residual(&shifted(-1.0), load),
    );
    let difference: Vec<f64> = plus
        .iter()
        .zip(&minus)
        .map(|(p, m)| (p - m) / (2.0 * step))
        .collect();
    assert_close(&format!("{label}: tangent"), &product, &difference, 1e-6);
}

/// The order-2 Taylor right-hand side along $`U_0 + aU_1`$, $`\lambda_0 + a\lambda_1`$,
/// against the residual on series.
fn check_taylor<M: EnergyModel>(label: &str, problem: &Problem<M>) {
    let n = problem.free_count();
    let (u0, u1) = (state(n, 0.1, 0.2), state(n, 0.05, 1.1));
    let (load0, load1) = (1.7, 0.3);
    let mut tape = problem.assembler.taylor_tape(2);
    problem.taylor_start(&u0, load0, &mut tape);
    problem.taylor_commit(1, &u1, load1, &mut tape);
    let taylor = problem.taylor_residual(2, &mut tape);
    let series: Vec<Series> = u0
        .iter()
        .zip(&u1)
        .map(|(&a, &b)| Series::from_coefficients(&[a, b, 0.0]).unwrap())
        .collect();
    let load = Series::from_coefficients(&[load0, load1, 0.0]).unwrap();
    let expected: Vec<f64> = problem
        .residual(&series, load)
        .iter()
        .map(|r| r.coefficient(2))
        .collect();
    assert_close(
        &format!("{label}: Taylor order 2"),
        &taylor,
        &expected,
        1e-12,
    );
}

#[test]
fn a_constant_profile_is_the_constant_parameter_bit_for_bit() {
    let plain = full(LENGTH, 40, 2.0, Ends::Clamped);
    let constant = ParameterProfile::new(ProfileAxis::X, vec![[3.0, C]]).unwrap();
    let with_profile = profiled(full(LENGTH, 40, 2.0, Ends::Clamped), constant);
    let u = state(plain.free_count(), 0.1, 0.2);
    assert_eq!(plain.residual(&u, 1.5), with_profile.residual(&u, 1.5));
    let (mut a, mut b) = (plain.new_matrix(), with_profile.new_matrix());
    plain.tangent_into(&u, 1.5, &mut a);
    with_profile.tangent_into(&u, 1.5, &mut b);
    assert_eq!(a.values, b.values);
}

#[test]
fn a_varying_foundation_keeps_energy_residual_tangent_and_taylor_consistent() {
    let full = profiled(full(LENGTH, 40, 2.0, Ends::Clamped), ramp());
    check_triad("beam-full", &full);
    check_taylor("beam-full", &full);
    let envelope = profiled(envelope(LENGTH, 12, 2.0), ramp());
    check_triad("beam-envelope", &envelope);
    check_taylor("beam-envelope", &envelope);
    let complex = profiled(complex_envelope(LENGTH, 12, -0.5), ramp());
    check_triad("beam-complex-envelope", &complex);
    check_taylor("beam-complex-envelope", &complex);
}

/// $`v = 1`$, $`u = 0`$ on a free beam with only the foundation: the energy is
/// $`\int_0^L \tfrac12 c(X)\,dX`$, the area under the profile (exact: the rule integrates the
/// linear pieces exactly on elements whose ends are the table's points).
#[test]
fn the_foundation_energy_integrates_the_profile() {
    let kind = ElementKind::Line3;
    let mesh = std::sync::Arc::new(Mesh::line(LENGTH, 20, 1.0, kind).unwrap());
    let model = BeamEnvelope::new(0.0, 0.0, 1.0, 0.0, 1.0);
    let conditions = [DirichletCondition::fixed("left", 0)];
    let mut problem = Problem::new(model, mesh, &conditions, &Loads::default()).unwrap();
    problem
        .set_parameter_profiles(vec![("foundation".to_string(), ramp())])
        .unwrap();
    let dofs = problem.dofs();
    let mut free = vec![0.0; problem.free_count()];
    for node in 0..problem.assembler.mesh().nodes.len() {
        if let Some(i) = dofs.free(node, 1) {
            free[i] = 1.0;
        }
    }
    // beam-envelope's foundation energy is c v₁² (the period mean of ½ c v² with v = 2 v₁ cos).
    let area = 0.5 * (0.5 + 1.5) * 8.0 + 0.5 * (1.5 + 1.0) * 12.0;
    let energy = problem.potential_energy(&free, 0.0);
    assert!(
        (energy - area).abs() < 1e-12 * area,
        "{energy} against {area}"
    );
}

#[test]
fn a_profile_on_a_parameter_that_cannot_vary_is_refused() {
    let mut problem = full(LENGTH, 10, 0.0, Ends::SimplySupported);
    let error = problem
        .set_parameter_profiles(vec![("bending_stiffness".to_string(), ramp())])
        .unwrap_err();
    assert!(matches!(error, ProblemError::ParameterNotVarying { .. }));
    let text = error.to_string();
    assert!(
        text.contains("bending_stiffness") && text.contains("foundation"),
        "{text}"
    );
    assert_eq!(BeamFull::SPEC.varying_parameters, &["foundation"]);
}
