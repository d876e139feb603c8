//! Small models through the macro: they compile (a normal test build, not trybuild: building
//! and running a pass case in trybuild would codegen every dependency of the runtime again in
//! trybuild's own target folder, which dominated CI time).

use wrinkle_runtime::{EnergyModel, QuadratureRule};

wrinkle_macros::energy_model! {
    /// A beam on an elastic foundation, with a reduced-integration shear-like term.
    model Beam as "beam" {
        fields: w;
        parameters: bending "EI (N m^2)", foundation;
        energy curvature = 0.5 * bending * w.x^2;
        energy support [reduced] = 0.5 * foundation * w^2;
    }
}

wrinkle_macros::energy_model! {
    /// No parameters at all.
    model Quartic as "quartic" {
        fields: w;
        parameters: ;
        energy e = -w^2 + w^4 / 4;
    }
}

/// Models without parameters, with reduced quadrature and a rational density compile and run.
#[test]
fn minimal_models_compile_and_evaluate() {
    let beam = Beam::new(2.0, 3.0);
    assert_eq!(Beam::SPEC.terms[1].quadrature, QuadratureRule::Reduced);
    assert_eq!(beam.parameter_values(), vec![2.0, 3.0]);
    let jet = [0.5, 0.25];
    assert_eq!(beam.energy::<f64>(0, &jet[1..]), 0.25 * 0.25);
    let quartic = Quartic::from_parameters(&[]);
    let mut out = [0.0];
    quartic.residual::<f64>(0, &[2.0], &mut out);
    assert_eq!(out[0], -4.0 + 8.0);
}
