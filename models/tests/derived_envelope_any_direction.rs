//! The wave direction of the derived envelope models (issue 29, (ii)): any direction
//! $`\mathbf e = (\cos\theta, \sin\theta)`$, checked by rotating the problem.
//!
//! Source: THEORY.md §4 (the direction-general reference model is a rotation of the model along
//! X) and §9 (example 1); `envelope_support` for the scene.
//!
//! * `derived_energy_is_rotation_covariant` (kernels): for random jets of
//!   `derived-reference-envelope` at $`\theta = 0`$, the energy of every term equals the energy at
//!   $`\theta`$ = 0.3, 1.1 and 2.5 rad of the jet rotated by $`\theta`$ — the envelope's gradient
//!   $`R\nabla w`$, the displacement gradient $`R\,\nabla\mathbf u\,R^T`$ — to 1e-12 relative.
//! * `rotated_example1_buckles_at_the_same_load` (runtime): example 1 turned by 90°
//!   ($`L_X = 200`$, $`L_Y = 400`$ mm, tension 10 N/mm on the X edges, compression on the Y
//!   edges, 16 × 32 Q8) with the wave along Y ($`\theta = \pi/2`$) buckles at the load of the
//!   unrotated example 1 (32 × 16, $`\theta = 0`$) with the hand-written reference model, at
//!   the reference optimum $`Q = 0.2354346`$ /mm: relative difference below 1e-9 (measured
//!   3.7e-13). The rotated mesh is the unrotated one turned, node for node.

mod envelope_support;

use std::sync::Arc;

use envelope_support::*;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_models::{DerivedReferenceEnvelope, ReferenceEnvelope};
use wrinkle_runtime::fem::{DirichletCondition, EdgeTraction, Loads, Mesh};
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::{Derivative, EnergyModel};

/// Value of `(field, derivative)` in a jet laid out as `M::SPEC.jet`.
fn index<M: EnergyModel>(field: &str, derivative: Derivative) -> usize {
    let f = M::SPEC.field_index(field).unwrap();
    M::SPEC
        .jet
        .iter()
        .position(|e| e.field == f && e.derivative == derivative)
        .unwrap()
}

/// The jet of the fields turned by `angle`: $`\nabla' w = R\nabla w`$,
/// $`\nabla'\mathbf u' = R\,\nabla\mathbf u\,R^T`$.
fn rotated<M: EnergyModel>(jet: &[f64], angle: f64) -> Vec<f64> {
    let (c, s) = (angle.cos(), angle.sin());
    let at = |f: &str, d: Derivative| jet[index::<M>(f, d)];
    let (x, y) = (Derivative::X, Derivative::Y);
    let gradient = [[at("u", x), at("u", y)], [at("v", x), at("v", y)]];
    let r = [[c, -s], [s, c]];
    let mut turned = [[0.0; 2]; 2];
    for (i, row) in turned.iter_mut().enumerate() {
        for (j, entry) in row.iter_mut().enumerate() {
            *entry = (0..2)
                .flat_map(|k| (0..2).map(move |l| (k, l)))
                .map(|(k, l)| r[i][k] * gradient[k][l] * r[j][l])
                .sum();
        }
    }
    let (wx, wy) = (at("w", x), at("w", y));
    let mut out = jet.to_vec();
    out[index::<M>("u", x)] = turned[0][0];
    out[index::<M>("u", y)] = turned[0][1];
    out[index::<M>("v", x)] = turned[1][0];
    out[index::<M>("v", y)] = turned[1][1];
    out[index::<M>("w", x)] = c * wx - s * wy;
    out[index::<M>("w", y)] = s * wx + c * wy;
    out
}

fn energies<M: EnergyModel>(model: &M, jet: &[f64]) -> Vec<f64> {
    M::SPEC
        .terms
        .iter()
        .enumerate()
        .map(|(t, term)| {
            let local: Vec<f64> = term.jet.iter().map(|&i| jet[i]).collect();
            model.energy(t, &local)
        })
        .collect()
}

#[test]
fn derived_energy_is_rotation_covariant() {
    type Derived = DerivedReferenceEnvelope;
    let along_x: Derived = envelope_model(0.23);
    let mut random = StdRng::seed_from_u64(90);
    for angle in [0.3, 1.1, 2.5] {
        let mut turned: Derived = envelope_model(0.23);
        turned.set_parameter("direction", angle).unwrap();
        for _ in 0..20 {
            let jet: Vec<f64> = Derived::SPEC
                .jet
                .iter()
                .map(|e| match (e.field, e.derivative) {
                    (2, Derivative::Value) => 0.1,
                    (2, _) => 5e-3,
                    _ => 1e-3,
                } * random.random_range(-1.0..1.0))
                .collect();
            let expected = energies(&along_x, &jet);
            let found = energies(&turned, &rotated::<Derived>(&jet, angle));
            for (a, b) in found.iter().zip(&expected) {
                assert!(
                    (a - b).abs() <= 1e-12 * b.abs(),
                    "angle {angle}: {a} vs {b}"
                );
            }
        }
    }
}

fn fixed(edge: &str, field: usize) -> DirichletCondition {
    DirichletCondition::fixed(edge, field)
}

/// Example 1 turned by 90°: compression along Y, tension along X (module documentation).
fn rotated_example1<M: EnergyModel>(model: M, nx: usize, ny: usize) -> Problem<M> {
    let (u, v) = (
        M::SPEC.field_index("u").unwrap(),
        M::SPEC.field_index("v").unwrap(),
    );
    let mut conditions = vec![
        fixed("centre", u),
        fixed("centre", v),
        fixed("top_middle", u),
    ];
    for (field, role) in M::SPEC.field_roles.iter().enumerate() {
        if role.is_transverse() {
            for edge in ["left", "right", "bottom", "top"] {
                conditions.push(fixed(edge, field));
            }
        }
    }
    let tractions: Vec<EdgeTraction> = [
        ("bottom", [0.0, 1.0], true),
        ("top", [0.0, -1.0], true),
        ("left", [-TENSION, 0.0], false),
        ("right", [TENSION, 0.0], false),
    ]
    .into_iter()
    .map(|(edge, traction, proportional)| EdgeTraction {
        edge: edge.into(),
        fields: [u, v],
        traction,
        proportional,
    })
    .collect();
    let mesh = Arc::new(Mesh::rectangle(LY, LX, nx, ny, 1.0).unwrap());
    let loads = Loads {
        tractions,
        ..Loads::default()
    };
    Problem::new(model, mesh, &conditions, &loads).unwrap()
}

#[test]
fn rotated_example1_buckles_at_the_same_load() {
    let q = optimal_wavenumber();
    let unrotated =
        buckle(&example1(envelope_model::<ReferenceEnvelope>(q), 32, 16)).critical_loads[0];
    let mut model: DerivedReferenceEnvelope = envelope_model(q);
    model
        .set_parameter("direction", std::f64::consts::FRAC_PI_2)
        .unwrap();
    let turned = buckle(&rotated_example1(model, 16, 32)).critical_loads[0];
    let difference = (turned - unrotated).abs() / unrotated;
    println!(
        "example 1: {unrotated:.12e}; turned by 90° (derived, θ = π/2): {turned:.12e}; relative difference {difference:.2e}"
    );
    assert!(difference < 1e-9, "{difference:e}");
}
