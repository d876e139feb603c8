//! Shared set-up of the envelope-model verification tests (`complex_envelope_reduction.rs`,
//! `pure_membrane_example1.rs`): the paper's example 1 for any model, by field roles, and the
//! closed forms of THEORY.md §8 it is checked against.
//!
//! Example 1 (THEORY.md §9): `L_X = 400`, `L_Y = 200`, `h = 0.05` mm, `E = 70000` MPa,
//! `ν = 0.3`, `N_Y = 10` N/mm on `bottom`/`top`, `N_X = −λ` on `left`/`right` (proportional);
//! `u = v = 0` at `centre`, `v = 0` at `right_middle` (`src/setup.rs`, `biaxial`), every
//! transverse field (deflections, rotations, envelopes) zero on every edge. The pre-buckling
//! membrane state is exactly uniform: $`N_X = -\lambda`$, $`N_Y = N_Y`$, $`N_{XY} = 0`$.

#![allow(dead_code)]

use std::f64::consts::PI;
use std::sync::Arc;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::{BodyLoad, DirichletCondition, EdgeTraction, Loads, Mesh};
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::{LinearBuckling, LinearBucklingOptions, linear_buckling};

/// Young's modulus (MPa).
pub const YOUNG: f64 = 70000.0;
/// Poisson ratio.
pub const POISSON: f64 = 0.3;
/// Thickness (mm).
pub const THICKNESS: f64 = 0.05;
/// Length along X (mm).
pub const LX: f64 = 400.0;
/// Width along Y (mm).
pub const LY: f64 = 200.0;
/// Tension $`N_Y`$ on the Y edges (N/mm).
pub const TENSION: f64 = 10.0;

/// $`D = Eh^3/(12(1-\nu^2))`$.
pub fn bending_stiffness() -> f64 {
    YOUNG * THICKNESS.powi(3) / (12.0 * (1.0 - POISSON * POISSON))
}

/// Neutral curve (42): $`\lambda(Q) = [6DQ^2\pi^2/L_X^2 + (2DQ^2 + N_Y)\pi^2/L_Y^2 + DQ^4] /
/// (Q^2 + \pi^2/L_X^2)`$, the exact eigenvalue of the linearised reference envelope equation
/// (32) on the clamped rectangle (mode $`\sin(\pi X/L_X)\sin(\pi Y/L_Y)`$).
pub fn neutral_curve(q: f64) -> f64 {
    let d = bending_stiffness();
    let (cx, cy) = (PI * PI / (LX * LX), PI * PI / (LY * LY));
    (6.0 * d * q * q * cx + (2.0 * d * q * q + TENSION) * cy + d * q.powi(4)) / (q * q + cx)
}

/// Minimiser of (42) in closed form: with $`s = Q^2`$, $`\lambda = (Ds^2 + as + b)/(s + c)`$,
/// $`a = 6D\pi^2/L_X^2 + 2D\pi^2/L_Y^2`$, $`b = N_Y\pi^2/L_Y^2`$, $`c = \pi^2/L_X^2`$, and
/// $`d\lambda/ds = 0`$ at $`s^* = -c + \sqrt{c^2 + (b - ac)/D}`$. Returns $`Q^* = \sqrt{s^*}`$.
pub fn optimal_wavenumber() -> f64 {
    let d = bending_stiffness();
    let (cx, cy) = (PI * PI / (LX * LX), PI * PI / (LY * LY));
    let a = 6.0 * d * cx + 2.0 * d * cy;
    let b = TENSION * cy;
    let excess = (b - a * cx) / d;
    (excess / (cx + (cx * cx + excess).sqrt())).sqrt()
}

/// Approximate wavenumber (44): $`Q_{wr} = (12\pi^2(1-\nu^2))^{1/4}(hL_Y)^{-1/2}(\sigma_Y/E)^{1/4}`$.
pub fn approximate_wavenumber() -> f64 {
    let stress_y = TENSION / THICKNESS;
    (12.0 * PI * PI * (1.0 - POISSON * POISSON)).powf(0.25) / (THICKNESS * LY).sqrt()
        * (stress_y / YOUNG).powf(0.25)
}

/// A model with `young`, `poisson`, `thickness`, `wavenumber` = `q` and `direction` = 0.
pub fn envelope_model<M: EnergyModel>(q: f64) -> M {
    let mut m = M::from_parameters(&vec![0.0; M::SPEC.parameters.len()]);
    for (name, value) in [
        ("young", YOUNG),
        ("poisson", POISSON),
        ("thickness", THICKNESS),
        ("wavenumber", q),
        ("direction", 0.0),
    ] {
        m.set_parameter(name, value).unwrap();
    }
    m
}

fn fixed(edge: &str, field: usize) -> DirichletCondition {
    DirichletCondition::fixed(edge, field)
}

/// Example 1 on a uniform `nx × ny` Q8 mesh (see the module documentation).
pub fn example1<M: EnergyModel>(model: M, nx: usize, ny: usize) -> Problem<M> {
    example1_with_body_loads(model, nx, ny, &[])
}

/// [`example1`] with `body_loads` (e.g. the paper's uniform load on the envelope, an
/// imperfection).
pub fn example1_with_body_loads<M: EnergyModel>(
    model: M,
    nx: usize,
    ny: usize,
    body_loads: &[BodyLoad],
) -> Problem<M> {
    let spec = M::SPEC;
    let (u, v) = (
        spec.field_index("u").unwrap(),
        spec.field_index("v").unwrap(),
    );
    let mut conditions = vec![
        fixed("centre", u),
        fixed("centre", v),
        fixed("right_middle", v),
    ];
    for (field, role) in spec.field_roles.iter().enumerate() {
        if role.is_transverse() {
            for edge in ["left", "right", "bottom", "top"] {
                conditions.push(fixed(edge, field));
            }
        }
    }
    let tractions: Vec<EdgeTraction> = [
        ("left", [1.0, 0.0], true),
        ("right", [-1.0, 0.0], true),
        ("bottom", [0.0, -TENSION], false),
        ("top", [0.0, TENSION], false),
    ]
    .into_iter()
    .map(|(edge, traction, proportional)| EdgeTraction {
        edge: edge.into(),
        fields: [u, v],
        traction,
        proportional,
    })
    .collect();
    let mesh = Arc::new(Mesh::rectangle(LX, LY, nx, ny, 1.0).unwrap());
    let loads = Loads {
        tractions,
        body_loads: body_loads.to_vec(),
        ..Loads::default()
    };
    Problem::new(model, mesh, &conditions, &loads).unwrap()
}

/// Linear buckling about λ = 0, first (distinct) mode. Pre-buckling Newton tolerance 1e-6 as
/// in `fvk_plate_support::buckle` (at λ = 0 the `u` residual is measured against a floor; the
/// state is linear in the load and reached in one iteration to round-off).
pub fn buckle<M: EnergyModel>(problem: &Problem<M>) -> LinearBuckling {
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut options = LinearBucklingOptions::default();
    options.newton.tolerance = 1e-6;
    linear_buckling(problem, &mut factor, &options).unwrap()
}

/// The state on the linear pre-buckling path at load `load`: $`U_0 + \lambda\dot U`$.
pub fn prebuckling_state(buckling: &LinearBuckling, load: f64) -> Vec<f64> {
    buckling
        .prebuckling
        .iter()
        .zip(&buckling.prebuckling_rate)
        .map(|(u, r)| u + load * r)
        .collect()
}

/// Largest magnitude of each field's entries in a free-dof vector.
pub fn field_magnitudes<M: EnergyModel>(problem: &Problem<M>, free: &[f64]) -> Vec<f64> {
    let nf = problem.dofs().field_count;
    let mut largest = vec![0.0_f64; nf];
    for (i, x) in free.iter().enumerate() {
        let field = problem.dofs().global_of_free(i) % nf;
        largest[field] = largest[field].max(x.abs());
    }
    largest
}
