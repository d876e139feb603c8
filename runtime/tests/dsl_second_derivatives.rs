//! Second derivatives in the energy DSL: `w.xx`, `w.xy` and `w.yy` parse, enter the model's jet
//! with the contract's [`Derivative`] values, and are differentiated like any jet entry; a mesh
//! whose element cannot supply them refuses the model before any work.
//!
//! The density is the Kirchhoff bending energy of a plate (THEORY.md §2) with a spring,
//! $$`\psi = \tfrac12 k w^2 +
//! \tfrac12 D\left[(w_{,XX} + w_{,YY})^2 - 2(1-\nu)(w_{,XX}w_{,YY} - w_{,XY}^2)\right]`$$,
//! whose residual and tangent are written out below by hand.

use std::sync::Arc;

use wrinkle_runtime::fem::Mesh;
use wrinkle_runtime::problem::{Problem, ProblemError};
use wrinkle_runtime::{Derivative, EnergyModel, JetEntry};

wrinkle_macros::energy_model! {
    /// Kirchhoff bending of `w` on a spring foundation.
    model KirchhoffSpring as "kirchhoff-spring" {
        fields: w [deflection];
        parameters: d, nu, k;
        energy bending = 0.5 * d * ((w.xx + w.yy)^2 - 2 * (1 - nu) * (w.xx * w.yy - w.xy^2));
        energy spring = 0.5 * k * w^2;
    }
}

const D: f64 = 2.5;
const NU: f64 = 0.3;
const K: f64 = 7.0;

#[test]
fn w_xx_xy_yy_enter_the_jet_sorted_after_the_first_derivatives() {
    let entry = |derivative| JetEntry {
        field: 0,
        derivative,
    };
    assert_eq!(
        KirchhoffSpring::SPEC.jet,
        [
            entry(Derivative::Value),
            entry(Derivative::XX),
            entry(Derivative::XY),
            entry(Derivative::YY),
        ]
    );
    // The bending term reads the three second derivatives, the spring the value.
    assert_eq!(KirchhoffSpring::SPEC.terms[0].jet, [1, 2, 3]);
    assert_eq!(KirchhoffSpring::SPEC.terms[1].jet, [0]);
}

#[test]
fn w_xx_xy_yy_are_differentiated_like_any_jet_entry() {
    let model = KirchhoffSpring::new(D, NU, K);
    let (xx, xy, yy): (f64, f64, f64) = (0.7, -0.4, 1.3);
    let jet = [xx, xy, yy];
    let energy = 0.5 * D * ((xx + yy).powi(2) - 2.0 * (1.0 - NU) * (xx * yy - xy * xy));
    assert!((model.energy::<f64>(0, &jet) - energy).abs() < 1e-14);
    // ∂ψ/∂(w_XX, w_XY, w_YY) = D (w_XX + ν w_YY, 2(1 − ν) w_XY, w_YY + ν w_XX).
    let mut residual = [0.0; 3];
    model.residual::<f64>(0, &jet, &mut residual);
    let expected = [
        D * (xx + NU * yy),
        2.0 * D * (1.0 - NU) * xy,
        D * (yy + NU * xx),
    ];
    for (got, want) in residual.iter().zip(expected) {
        assert!((got - want).abs() < 1e-14, "{residual:?} vs {expected:?}");
    }
    // Hessian D [[1, 0, ν], [0, 2(1 − ν), 0], [ν, 0, 1]] on the published pattern.
    let hessian = |i: usize, j: usize| match (i, j) {
        (0, 0) | (2, 2) => D,
        (1, 1) => 2.0 * D * (1.0 - NU),
        (0, 2) | (2, 0) => D * NU,
        _ => 0.0,
    };
    let pattern = KirchhoffSpring::SPEC.terms[0].tangent_pattern;
    let mut tangent = vec![0.0; pattern.len()];
    model.tangent::<f64>(0, &jet, &mut tangent);
    for (&(i, j), value) in pattern.iter().zip(&tangent) {
        assert!((value - hessian(i, j)).abs() < 1e-14, "({i}, {j}): {value}");
    }
    for (i, j) in [(0, 0), (1, 1), (2, 2), (0, 2)] {
        assert!(
            pattern.contains(&(i, j)),
            "({i}, {j}) missing from {pattern:?}"
        );
    }
}

#[test]
fn q8_refuses_a_model_asking_for_w_xx() {
    let mesh = Arc::new(Mesh::rectangle(2.0, 1.0, 2, 1, 1.0).unwrap());
    let error = Problem::new(
        KirchhoffSpring::new(D, NU, K),
        mesh,
        &[],
        &Default::default(),
    )
    .unwrap_err();
    assert!(
        matches!(
            error,
            ProblemError::UnsupportedDerivative {
                field: "w",
                derivative: Derivative::XX,
                ..
            }
        ),
        "{error:?}"
    );
    let message = error.to_string();
    assert!(
        message.contains("Q8") && message.contains("`w.xx`"),
        "{message}"
    );
}
