//! Prescribed values $`f = g_0 + \lambda g_1`$ on a boundary set (displacement control),
//! against loads and against Newton.
//!
//! * **Bar stretched by its end, linear.** Plane stress, $`E h = 1000`$ N/mm, $`\nu = 0.3`$, the
//!   plate $`[0, 4] \times [0, 2]`$ mm (4 × 2 Q8), $`u = 0`$ on `left`, $`v = 0`$ at
//!   `left_middle`. A traction $`(\lambda T, 0)`$ on `right` and the prescribed end displacement
//!   $`u = \lambda\,TL/(Eh)`$ on `right` both give the uniaxial state
//!   $`u = TX/(Eh)`$, $`v = -\nu T (Y - 1)/(Eh)`$, which Q8 represents exactly: every nodal
//!   value agrees with it to round-off, with $`g_0 \neq 0`$ too.
//! * **Clamped membrane stretched and sheared, geometrically nonlinear** (Saint-Venant–Kirchhoff
//!   plane stress, Green–Lagrange strains): $`u = v = 0`$ on `left`, $`u = \lambda`$ and
//!   $`v = -0.05`$ mm (constant) on `right`. The ANM path (with Padé) from the Newton solution at
//!   $`\lambda = 0`$ to $`\lambda = 0.6`$ agrees with Newton at its own loads to $`10^{-6}`$ of the
//!   displacement.

use std::sync::Arc;

use wrinkle_runtime::fem::{DirichletCondition, EdgeTraction, Loads, Mesh};
use wrinkle_runtime::linear::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::anm::{AnmOptions, follow_path_anm};
use wrinkle_runtime::solve::newton::{NewtonOptions, newton};
use wrinkle_runtime::solve::path::{PathControl, PathState, PathStop};

wrinkle_macros::energy_model! {
    /// Linear plane-stress membrane.
    model LinearMembrane as "test-linear-membrane" {
        fields: u [displacement_x], v [displacement_y];
        parameters: young, poisson, thickness;
        let c = young * thickness / (1 - poisson^2);
        let gxy = u.y + v.x;
        energy membrane = 0.5 * c * (u.x^2 + v.y^2 + 2 * poisson * u.x * v.y
            + 0.5 * (1 - poisson) * gxy^2);
    }
}

#[path = "support/svk_membrane.rs"]
mod svk_membrane;
use svk_membrane::SvkMembrane;

const YOUNG: f64 = 1000.0;
const POISSON: f64 = 0.3;
const THICKNESS: f64 = 1.0;
const LENGTH: f64 = 4.0;
const WIDTH: f64 = 2.0;
const TRACTION: f64 = 2.5;

fn plate() -> Arc<Mesh> {
    Arc::new(Mesh::rectangle(LENGTH, WIDTH, 4, 2, 1.0).unwrap())
}

/// Newton from zero at `load` (one iteration for a linear problem, then round-off), as global
/// nodal values.
fn solve_global<M: wrinkle_runtime::EnergyModel>(problem: &Problem<M>, load: f64) -> Vec<f64> {
    let mut matrix = problem.new_matrix();
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let options = NewtonOptions {
        tolerance: 1e-10,
        max_iterations: 10,
    };
    let zero = vec![0.0; problem.free_count()];
    let solution = newton(problem, zero, load, &mut factor, &mut matrix, &options).unwrap();
    problem.dofs().expand(&solution.solution, load)
}

fn assert_uniaxial(mesh: &Mesh, global: &[f64], what: &str) {
    let strain = TRACTION / (YOUNG * THICKNESS);
    for (node, &[x, y]) in mesh.nodes.iter().enumerate() {
        let exact = [strain * x, -POISSON * strain * (y - 0.5 * WIDTH)];
        for (field, expected) in exact.iter().enumerate() {
            let value = global[node * 2 + field];
            assert!(
                (value - expected).abs() <= 1e-13,
                "{what}: field {field} at node {node} ({x}, {y}): {value} vs {expected}"
            );
        }
    }
}

#[test]
fn bar_stretched_by_a_prescribed_end_displacement_equals_the_traction_loaded_bar() {
    let model = || LinearMembrane::new(YOUNG, POISSON, THICKNESS);
    let support = [
        DirichletCondition::fixed("left", 0),
        DirichletCondition::fixed("left_middle", 1),
    ];
    let traction = Loads {
        tractions: vec![EdgeTraction {
            edge: "right".into(),
            fields: [0, 1],
            traction: [TRACTION, 0.0],
            proportional: true,
        }],
        ..Loads::default()
    };
    let by_traction = Problem::new(model(), plate(), &support, &traction).unwrap();
    assert_uniaxial(
        &plate(),
        &solve_global(&by_traction, 1.0),
        "traction λT at λ = 1",
    );

    let end = TRACTION * LENGTH / (YOUNG * THICKNESS);
    let mut controlled = support.to_vec();
    controlled.push(DirichletCondition::prescribed("right", 0, 0.0, end));
    let by_displacement = Problem::new(model(), plate(), &controlled, &Loads::default()).unwrap();
    assert_eq!(
        by_displacement.free_count() + plate().boundary_nodes("right").unwrap().len(),
        by_traction.free_count()
    );
    assert_uniaxial(
        &plate(),
        &solve_global(&by_displacement, 1.0),
        "u = λ TL/(Eh) at λ = 1",
    );
    // Constant plus rate: u = g₀ + λ g₁ with g₀ = end/4, g₁ = end/2, at λ = 3/2.
    controlled.pop();
    controlled.push(DirichletCondition::prescribed(
        "right",
        0,
        0.25 * end,
        0.5 * end,
    ));
    let affine = Problem::new(model(), plate(), &controlled, &Loads::default()).unwrap();
    assert_uniaxial(
        &plate(),
        &solve_global(&affine, 1.5),
        "u = g₀ + λ g₁ at λ = 3/2",
    );
}

/// The clamped membrane's supports: $`u = v = 0`$ on `left`, $`u = \lambda`$ and
/// $`v = -0.05`$ mm on `right`.
fn clamped_stretched_and_sheared() -> [DirichletCondition; 4] {
    [
        DirichletCondition::fixed("left", 0),
        DirichletCondition::fixed("left", 1),
        DirichletCondition::prescribed("right", 0, 0.0, 1.0),
        DirichletCondition::prescribed("right", 1, -0.05, 0.0),
    ]
}

#[test]
fn anm_path_under_a_prescribed_displacement_matches_newton() {
    let conditions = clamped_stretched_and_sheared();
    let problem = Problem::new(
        SvkMembrane::new(YOUNG, POISSON, THICKNESS),
        plate(),
        &conditions,
        &Loads::default(),
    )
    .unwrap();
    let start_global = solve_global(&problem, 0.0);
    let start = PathState {
        displacement: problem.dofs().restrict(&start_global),
        load: 0.0,
    };
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let options = AnmOptions {
        max_load: Some(0.6),
        predict_bifurcation: false,
        ..AnmOptions::default()
    };
    let mut points = Vec::new();
    let mut observer = |event: &wrinkle_runtime::solve::path::PathEvent| {
        points.push(event.state.clone());
        PathControl::Continue
    };
    let result = follow_path_anm(
        &problem,
        start,
        &mut factor,
        &options,
        &mut observer,
        &mut Vec::new(),
    );
    assert!(
        matches!(result.stop, PathStop::MaxLoad),
        "{}",
        result.stop.describe()
    );
    let last = points.last().unwrap().load;
    assert!((last - 0.6).abs() < 1e-9, "last load {last}");
    let checked: Vec<&PathState> = points.iter().filter(|p| p.load > 0.05).step_by(3).collect();
    assert!(checked.len() >= 3, "{} points", points.len());
    for state in checked {
        let path = problem.dofs().expand(&state.displacement, state.load);
        let exact = solve_global(&problem, state.load);
        let size = exact.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let error = path
            .iter()
            .zip(&exact)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(
            error <= 1e-6 * size,
            "λ = {}: ANM off Newton by {error} (size {size})",
            state.load
        );
    }
}

/// The load derivative $`\partial R/\partial\lambda`$ of the clamped membrane stretched by its
/// `right` edge ($`u = \lambda`$) and pulled on `top` by a proportional traction, at a deformed
/// state: over the two elements on `right` only (of 4 × 2) it has the values of the
/// dual-number residual over every element, entry for entry, and matches the residual's central
/// difference in $`\lambda`$. Under force control alone no element carries the load.
#[test]
fn load_derivative_over_the_loaded_edge_equals_the_whole_element_loop() {
    use num_dual::Dual64;
    let conditions = clamped_stretched_and_sheared();
    let pull = Loads {
        tractions: vec![EdgeTraction {
            edge: "top".into(),
            fields: [0, 1],
            traction: [0.5, 2.0],
            proportional: true,
        }],
        ..Loads::default()
    };
    let model = || SvkMembrane::new(YOUNG, POISSON, THICKNESS);
    let problem = Problem::new(model(), plate(), &conditions, &pull).unwrap();
    let loaded: Vec<usize> = (0..problem.load_elements().len())
        .filter(|&e| problem.load_elements()[e])
        .collect();
    assert_eq!(loaded.len(), 2, "the elements on `right`: {loaded:?}");

    let free: Vec<f64> = (0..problem.free_count())
        .map(|i| 0.02 * (0.7 * i as f64).sin())
        .collect();
    let load = 0.3;
    let derivative = problem.load_derivative(&free, load);
    let dual_free: Vec<Dual64> = free.iter().map(|&u| Dual64::from_re(u)).collect();
    let whole: Vec<f64> = problem
        .residual(&dual_free, Dual64::new(load, 1.0))
        .iter()
        .map(|r| r.eps)
        .collect();
    assert_eq!(derivative, whole, "skipped elements changed a value");
    let largest = whole.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    assert!(largest > 1.0, "a derivative worth testing: {largest}");

    let h = 1e-6;
    let above = problem.residual(&free, load + h);
    let below = problem.residual(&free, load - h);
    for (i, &d) in derivative.iter().enumerate() {
        let difference = (above[i] - below[i]) / (2.0 * h);
        assert!(
            (d - difference).abs() <= 1e-6 * largest,
            "dof {i}: {d} against the central difference {difference}"
        );
    }

    let support = [
        DirichletCondition::fixed("left", 0),
        DirichletCondition::fixed("left", 1),
    ];
    let forced = Problem::new(model(), plate(), &support, &pull).unwrap();
    assert!(forced.load_elements().iter().all(|&e| !e));
    let minus_pull: Vec<f64> = forced.loads.proportional.iter().map(|p| -p).collect();
    let free: Vec<f64> = (0..forced.free_count())
        .map(|i| 0.02 * (0.7 * i as f64).sin())
        .collect();
    assert_eq!(forced.load_derivative(&free, load), minus_pull);
}
