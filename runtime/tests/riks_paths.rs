//! Newton–Riks on a strip in uniaxial tension with a hand-written nonlinear-spring energy
//! $`\psi(\varepsilon) = \tfrac12 k\varepsilon^2 - \tfrac13 b\varepsilon^3 + \tfrac14 c\varepsilon^4`$,
//! $`\varepsilon = \partial u/\partial X`$.
//!
//! With $`u = 0`$ on `left` and a traction $`\lambda`$ on `right`, the exact solution is the
//! uniform strain $`u = \varepsilon X`$ with $`\lambda = \sigma(\varepsilon) = k\varepsilon - b\varepsilon^2 + c\varepsilon^3`$
//! (representable exactly by the Q8 element), which every path point must satisfy.

use std::sync::Arc;

use wrinkle_runtime::fem::{DirichletCondition, EdgeTraction, Loads, Mesh};
use wrinkle_runtime::linear::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::SolveError;
use wrinkle_runtime::solve::path::{PathControl, PathEvent, PathState, PathStop};
use wrinkle_runtime::solve::riks::{
    AmplitudeControl, ArcLengthConstraint, RiksOptions, follow_path_riks,
};
use wrinkle_runtime::{
    Derivative, EnergyModel, FieldRole, JetEntry, ModelSpec, QuadratureRule, Scalar, TermSpec,
};

/// One field `u`, one term depending on $`\partial u/\partial X`$.
static TERMS: [TermSpec; 1] = [TermSpec {
    name: "spring",
    quadrature: QuadratureRule::Full,
    jet: &[0],
    tangent_pattern: &[(0, 0)],
    taylor_slots: 1,
    linear_residual: false,
}];

static SPEC: ModelSpec = ModelSpec {
    name: "test-nonlinear-spring",
    description: "1-field nonlinear spring ½kε² − ⅓bε³ + ¼cε⁴ of ε = ∂u/∂X",
    fields: &["u"],
    field_roles: &[FieldRole::DisplacementX],
    parameters: &["k", "b", "c"],
    varying_parameters: &[],
    jet: &[JetEntry {
        field: 0,
        derivative: Derivative::X,
    }],
    terms: &TERMS,
    simplification_report: "hand-written",
    derivation: None,
};

#[derive(Clone, Debug)]
struct NonlinearSpring {
    k: f64,
    b: f64,
    c: f64,
}

impl NonlinearSpring {
    /// Exact stress $`\sigma(\varepsilon)`$ (= the load on the path).
    fn stress(&self, strain: f64) -> f64 {
        self.k * strain - self.b * strain * strain + self.c * strain.powi(3)
    }
}

impl EnergyModel for NonlinearSpring {
    const SPEC: &'static ModelSpec = &SPEC;

    fn from_parameters(values: &[f64]) -> Self {
        NonlinearSpring {
            k: values[0],
            b: values[1],
            c: values[2],
        }
    }

    fn parameter_values(&self) -> Vec<f64> {
        vec![self.k, self.b, self.c]
    }

    fn energy<S: Scalar>(&self, _term: usize, jet: &[S]) -> S {
        let e = jet[0];
        e * e * (0.5 * self.k) - e.powi(3) * (self.b / 3.0) + e.powi(4) * (0.25 * self.c)
    }

    fn residual<S: Scalar>(&self, _term: usize, jet: &[S], out: &mut [S]) {
        let e = jet[0];
        out[0] = e * self.k - e * e * self.b + e.powi(3) * self.c;
    }

    fn tangent<S: Scalar>(&self, _term: usize, jet: &[S], out: &mut [S]) {
        let e = jet[0];
        out[0] = -(e * (2.0 * self.b)) + e * e * (3.0 * self.c) + self.k;
    }
}

const LENGTH: f64 = 2.0;

/// Strip `[0, 2] × [0, 1]` of `elements` Q8 elements, `u = 0` on `left`, traction $`\lambda`$
/// on `right` (X component on field 0, zero Y component also on field 0).
fn strip_problem(model: NonlinearSpring, elements: usize) -> Problem<NonlinearSpring> {
    let mesh = Mesh::rectangle(LENGTH, 1.0, elements, 1, 1.0).unwrap();
    let conditions = [DirichletCondition::fixed("left", 0)];
    let tractions = [EdgeTraction {
        edge: "right".into(),
        fields: [0, 0],
        traction: [1.0, 0.0],
        proportional: true,
    }];
    let loads = Loads {
        tractions: tractions.to_vec(),
        ..Loads::default()
    };
    Problem::new(model, Arc::new(mesh), &conditions, &loads).unwrap()
}

/// X coordinate of every free dof.
fn free_positions(problem: &Problem<NonlinearSpring>) -> Vec<f64> {
    let mesh = problem.assembler.mesh();
    (0..problem.free_count())
        .map(|i| mesh.nodes[problem.dofs().global_of_free(i)][0])
        .collect()
}

/// Checks that `state` is the uniform strain $`u = \varepsilon X`$ with
/// $`\lambda = \sigma(\varepsilon)`$ to `1e-8`, and returns $`\varepsilon`$.
fn assert_on_exact_path(
    problem: &Problem<NonlinearSpring>,
    positions: &[f64],
    state: &PathState,
) -> f64 {
    let (index, x_max) =
        positions.iter().enumerate().fold(
            (0, 0.0),
            |best, (i, &x)| if x > best.1 { (i, x) } else { best },
        );
    let strain = state.displacement[index] / x_max;
    for (u, x) in state.displacement.iter().zip(positions) {
        assert!(
            (u - strain * x).abs() <= 1e-8 * (1.0 + strain.abs()),
            "non-uniform strain: u = {u}, expected {} at X = {x}",
            strain * x
        );
    }
    let exact = problem.assembler.model().stress(strain);
    assert!(
        (state.load - exact).abs() <= 1e-8 * (1.0 + exact.abs()),
        "load {} off the exact path σ(ε = {strain}) = {exact}",
        state.load
    );
    strain
}

/// Euclidean norm $`\|\Delta U\|`$ of the displacement increment from `a` to `b`.
fn displacement_distance(a: &PathState, b: &PathState) -> f64 {
    a.displacement
        .iter()
        .zip(&b.displacement)
        .map(|(x, y)| (y - x) * (y - x))
        .sum::<f64>()
        .sqrt()
}

/// Runs Riks and collects every reported point.
fn run(
    problem: &Problem<NonlinearSpring>,
    options: &RiksOptions,
) -> (
    wrinkle_runtime::solve::path::PathResult,
    Vec<(usize, PathState)>,
) {
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let start = PathState {
        displacement: vec![0.0; problem.free_count()],
        load: 0.0,
    };
    let mut points = Vec::new();
    let mut observer = |event: &PathEvent| {
        assert!(!event.interior);
        assert!(event.relative_residual <= 1e-10);
        points.push((event.step, event.state.clone()));
        PathControl::Continue
    };
    let result = follow_path_riks(problem, start, &mut factor, options, &mut observer);
    (result, points)
}

#[test]
fn hardening_spring_path_is_exact_for_both_constraints() {
    let model = NonlinearSpring {
        k: 2.0,
        b: 0.0,
        c: 1.5,
    };
    for constraint in [
        ArcLengthConstraint::Spherical,
        ArcLengthConstraint::Linearized,
    ] {
        let problem = strip_problem(model.clone(), 4);
        let positions = free_positions(&problem);
        let options = RiksOptions {
            initial_arc_length: 0.2,
            max_arc_length: 0.5,
            max_load: Some(6.0),
            constraint,
            ..RiksOptions::default()
        };
        let (result, points) = run(&problem, &options);
        assert!(
            matches!(result.stop, PathStop::MaxLoad),
            "{}",
            result.stop.describe()
        );
        assert_eq!(points[0].0, 0);
        assert_eq!(points[0].1.load, 0.0);
        assert_eq!(points.len(), result.statistics.steps + 1);
        let mut previous_strain = -1.0;
        for (index, (step, state)) in points.iter().enumerate() {
            assert_eq!(*step, index);
            let strain = assert_on_exact_path(&problem, &positions, state);
            assert!(
                strain > previous_strain,
                "strain must grow along a hardening path"
            );
            previous_strain = strain;
        }
        // Each accepted point lies on the arc-length sphere around the previous one
        // (unless the step was shortened, which it is not on this smooth path).
        assert_eq!(result.statistics.rejected_steps, 0);
        let last = &points.last().unwrap().1;
        assert!(last.load >= 6.0);
        assert_eq!(result.last, *last);
        // The start's tangent, each accepted point's (the next step's predictor and the
        // crossing guard's inertia), and one per Newton iteration.
        let statistics = &result.statistics;
        assert_eq!(
            statistics.factorizations,
            1 + statistics.steps + statistics.corrections
        );
        assert_eq!(statistics.tangent_assemblies, statistics.factorizations);
        assert!(statistics.corrections >= statistics.steps);
        assert!(statistics.total_seconds > 0.0);
    }
}

#[test]
fn step_lengths_satisfy_the_arc_length_equation() {
    let model = NonlinearSpring {
        k: 1.0,
        b: 0.0,
        c: 4.0,
    };
    let problem = strip_problem(model, 3);
    let load_scale = 0.7;
    // Fixed arc length (min = initial = max) so every step must have exactly this length.
    let arc = 0.3;
    for constraint in [
        ArcLengthConstraint::Spherical,
        ArcLengthConstraint::Linearized,
    ] {
        let options = RiksOptions {
            initial_arc_length: arc,
            min_arc_length: arc,
            max_arc_length: arc,
            load_scale,
            max_steps: 6,
            constraint,
            ..RiksOptions::default()
        };
        let (result, points) = run(&problem, &options);
        assert!(
            matches!(result.stop, PathStop::MaxSteps),
            "{}",
            result.stop.describe()
        );
        assert_eq!(points.len(), 7);
        for pair in points.windows(2) {
            let (a, b) = (&pair[0].1, &pair[1].1);
            let squared = displacement_distance(a, b).powi(2)
                + load_scale * load_scale * (b.load - a.load).powi(2);
            // The linearised constraint is only converged along with the residual.
            assert!(
                (squared.sqrt() - arc).abs() <= 1e-6 * arc,
                "{constraint:?}: step length {} instead of {arc}",
                squared.sqrt()
            );
            assert!(b.load > a.load);
        }
    }
}

/// With `reference_load` the arc length is dimensionless: on the uniform strain
/// $`u = \varepsilon X`$, $`\|\Delta U\|/s = k\,|\Delta\varepsilon|/\lambda_\text{ref}`$ whatever
/// the mesh (both norms run over the same free nodes), so 3 and 24 elements take the same
/// steps to round-off, each of length exactly $`\ell`$ in
/// $`\|\Delta U\|^2/s^2 + \Delta\lambda^2/\lambda_\text{ref}^2`$. With the Euclidean norm of
/// `load_scale` the finer mesh takes shorter load steps.
#[test]
fn dimensionless_arc_length_takes_the_same_steps_on_every_mesh() {
    let model = NonlinearSpring {
        k: 2.0,
        b: 0.0,
        c: 3.0,
    };
    let (arc, reference) = (0.4, 1.5);
    let loads = |elements: usize, reference_load: Option<f64>| {
        let problem = strip_problem(model.clone(), elements);
        let positions = free_positions(&problem);
        let options = RiksOptions {
            initial_arc_length: arc,
            min_arc_length: arc,
            max_arc_length: arc,
            reference_load,
            max_steps: 5,
            ..RiksOptions::default()
        };
        let (result, points) = run(&problem, &options);
        assert!(matches!(result.stop, PathStop::MaxSteps));
        // s = λ_ref ‖δU_F‖ with δU_F = X / k at the unstrained start.
        let scale = reference * positions.iter().map(|x| x * x).sum::<f64>().sqrt() / model.k;
        for pair in points.windows(2) {
            let (a, b) = (&pair[0].1, &pair[1].1);
            let displacement = displacement_distance(a, b);
            let length = if reference_load.is_some() {
                (displacement / scale).hypot((b.load - a.load) / reference)
            } else {
                displacement.hypot(b.load - a.load)
            };
            assert!((length - arc).abs() <= 1e-6 * arc, "step length {length}");
            assert_on_exact_path(&problem, &positions, b);
        }
        points.iter().map(|(_, s)| s.load).collect::<Vec<_>>()
    };
    let (coarse, fine) = (loads(3, Some(reference)), loads(24, Some(reference)));
    for (a, b) in coarse.iter().zip(&fine) {
        assert!(
            (a - b).abs() <= 1e-9 * (1.0 + a.abs()),
            "{coarse:?} vs {fine:?}"
        );
    }
    let (coarse, fine) = (loads(3, None), loads(24, None));
    assert!(fine[5] < 0.7 * coarse[5], "{coarse:?} vs {fine:?}");
}

/// A zero or non-finite reference load is refused before any step.
#[test]
fn a_zero_reference_load_is_rejected() {
    let problem = strip_problem(
        NonlinearSpring {
            k: 1.0,
            b: 0.0,
            c: 1.0,
        },
        2,
    );
    for reference in [0.0, f64::INFINITY] {
        let options = RiksOptions {
            reference_load: Some(reference),
            ..RiksOptions::default()
        };
        let (result, points) = run(&problem, &options);
        assert!(points.is_empty());
        let PathStop::Failed(error) = &result.stop else {
            panic!("{}", result.stop.describe());
        };
        assert!(error.to_string().contains("reference_load"), "{error}");
    }
}

#[test]
fn snap_through_passes_both_limit_points() {
    // σ(ε) = ε − 3ε² + 2.5ε³: local maximum at ε = (6 − √6)/15, minimum at (6 + √6)/15.
    let model = NonlinearSpring {
        k: 1.0,
        b: 3.0,
        c: 2.5,
    };
    let strain_at_maximum = (6.0 - 6.0_f64.sqrt()) / 15.0;
    let strain_at_minimum = (6.0 + 6.0_f64.sqrt()) / 15.0;
    let load_maximum = model.stress(strain_at_maximum);
    let load_minimum = model.stress(strain_at_minimum);
    for constraint in [
        ArcLengthConstraint::Spherical,
        ArcLengthConstraint::Linearized,
    ] {
        let problem = strip_problem(model.clone(), 3);
        let positions = free_positions(&problem);
        let options = RiksOptions {
            initial_arc_length: 0.05,
            max_arc_length: 0.2,
            max_load: Some(0.3),
            constraint,
            ..RiksOptions::default()
        };
        let (result, points) = run(&problem, &options);
        assert!(
            matches!(result.stop, PathStop::MaxLoad),
            "{}",
            result.stop.describe()
        );
        // The step that passes the maximum from a stable start ends with negative pivots, but
        // the load turns back there: a limit point of the path, which the crossing guard keeps
        // at once (it halves only steps that jump over a bifurcation with the load still rising).
        assert_eq!(result.statistics.rejected_steps, 0, "{constraint:?}");
        let strains: Vec<f64> = points
            .iter()
            .map(|(_, state)| assert_on_exact_path(&problem, &positions, state))
            .collect();
        let loads: Vec<f64> = points.iter().map(|(_, state)| state.load).collect();
        // The strain grows monotonically along the whole path; the load rises, falls, rises.
        assert!(strains.windows(2).all(|w| w[1] > w[0]));
        let signs: Vec<bool> = loads.windows(2).map(|w| w[1] > w[0]).collect();
        let changes = signs.windows(2).filter(|w| w[0] != w[1]).count();
        assert_eq!(changes, 2, "{constraint:?}: loads {loads:?}");
        assert!(signs[0], "the load must rise first");
        assert!(*signs.last().unwrap());
        // Points on the unstable (softening) branch were found, below the maximum.
        let softening: Vec<usize> = (0..strains.len())
            .filter(|&i| {
                strains[i] > strain_at_maximum + 0.02 && strains[i] < strain_at_minimum - 0.02
            })
            .collect();
        assert!(!softening.is_empty());
        for &i in &softening {
            assert!(loads[i] < load_maximum && loads[i] > load_minimum);
        }
        // There the tangent is negative definite (every pivot negative): an unstable
        // equilibrium that load-controlled Newton cannot follow.
        let state = &points[softening[0]].1;
        let mut matrix = problem.new_matrix();
        problem.tangent_into(&state.displacement, state.load, &mut matrix);
        let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
        factor.factorize(&matrix).unwrap();
        assert_eq!(factor.negative_pivots(), Some(problem.free_count()));
        // Beyond the minimum the path comes back above the maximum load.
        assert!(*strains.last().unwrap() > strain_at_minimum);
        assert!(*loads.last().unwrap() >= 0.3);
    }
}

#[test]
fn zero_stiffness_fails_with_a_singular_tangent_after_reporting_the_start() {
    let problem = strip_problem(
        NonlinearSpring {
            k: 0.0,
            b: 0.0,
            c: 0.0,
        },
        2,
    );
    let (result, points) = run(&problem, &RiksOptions::default());
    assert_eq!(points.len(), 1);
    assert_eq!(points[0].0, 0);
    assert_eq!(result.statistics.steps, 0);
    assert_eq!(result.last.load, 0.0);
    match &result.stop {
        PathStop::Failed(error) => {
            let message = error.to_string();
            assert!(message.contains("singular"), "{message}");
            assert!(message.contains("load 0.000000e0"), "{message}");
        }
        other => panic!("expected a failure, got {}", other.describe()),
    }
    assert!(result.stop.is_failure());
}

#[test]
fn invalid_options_and_start_point_are_rejected_without_events() {
    let problem = strip_problem(
        NonlinearSpring {
            k: 1.0,
            b: 0.0,
            c: 0.0,
        },
        2,
    );
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let zero = PathState {
        displacement: vec![0.0; problem.free_count()],
        load: 0.0,
    };
    let bad_options = [
        RiksOptions {
            min_arc_length: 1.0,
            initial_arc_length: 0.5,
            ..RiksOptions::default()
        },
        RiksOptions {
            tolerance: -1.0,
            ..RiksOptions::default()
        },
        RiksOptions {
            load_scale: f64::NAN,
            ..RiksOptions::default()
        },
        RiksOptions {
            max_iterations: 0,
            ..RiksOptions::default()
        },
        RiksOptions {
            amplitude: Some(AmplitudeControl {
                dofs: vec![0],
                max_change: 0.0,
            }),
            ..RiksOptions::default()
        },
        RiksOptions {
            amplitude: Some(AmplitudeControl {
                dofs: vec![problem.free_count()],
                max_change: 1.0,
            }),
            ..RiksOptions::default()
        },
    ];
    for options in &bad_options {
        let mut events = 0;
        let mut observer = |_: &PathEvent| {
            events += 1;
            PathControl::Continue
        };
        let result = follow_path_riks(&problem, zero.clone(), &mut factor, options, &mut observer);
        assert_eq!(events, 0);
        match result.stop {
            PathStop::Failed(SolveError::Path { message, .. }) => {
                assert!(message.contains("invalid option"), "{message}")
            }
            other => panic!("expected a failure, got {}", other.describe()),
        }
    }
    let short = PathState {
        displacement: vec![0.0; 3],
        load: 0.0,
    };
    let mut observer = |_: &PathEvent| PathControl::Continue;
    let result = follow_path_riks(
        &problem,
        short,
        &mut factor,
        &RiksOptions::default(),
        &mut observer,
    );
    match result.stop {
        PathStop::Failed(error) => assert!(error.to_string().contains("free dofs")),
        other => panic!("expected a failure, got {}", other.describe()),
    }
}

#[test]
fn observer_stops_the_path() {
    let model = NonlinearSpring {
        k: 1.0,
        b: 0.0,
        c: 1.0,
    };
    let problem = strip_problem(model, 2);
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let start = PathState {
        displacement: vec![0.0; problem.free_count()],
        load: 0.0,
    };
    let mut steps = Vec::new();
    let mut observer = |event: &PathEvent| {
        steps.push(event.step);
        if event.step == 3 {
            PathControl::Stop
        } else {
            PathControl::Continue
        }
    };
    let result = follow_path_riks(
        &problem,
        start,
        &mut factor,
        &RiksOptions::default(),
        &mut observer,
    );
    assert!(matches!(result.stop, PathStop::Observer));
    assert_eq!(steps, vec![0, 1, 2, 3]);
    assert_eq!(result.statistics.steps, 3);
    let positions = free_positions(&problem);
    assert_on_exact_path(&problem, &positions, &result.last);
}

/// Largest change of the free dofs `dofs` between consecutive reported points.
fn largest_step_change(points: &[(usize, PathState)], dofs: &[usize]) -> f64 {
    points
        .windows(2)
        .flat_map(|pair| {
            dofs.iter()
                .map(|&i| (pair[1].1.displacement[i] - pair[0].1.displacement[i]).abs())
        })
        .fold(0.0, f64::max)
}

/// The amplitude control bounds every step's change of the monitored dofs (here the last
/// node's displacement), where the arc length alone lets a step move it four times as far;
/// the points stay on the exact path and reach the same load.
#[test]
fn amplitude_control_bounds_each_steps_change_of_the_monitored_dofs() {
    let model = NonlinearSpring {
        k: 2.0,
        b: 0.0,
        c: 1.5,
    };
    let problem = strip_problem(model, 4);
    let positions = free_positions(&problem);
    let end: Vec<usize> = (0..positions.len())
        .filter(|&i| positions[i] == LENGTH)
        .collect();
    let free = RiksOptions {
        initial_arc_length: 0.2,
        max_arc_length: 0.5,
        max_load: Some(6.0),
        ..RiksOptions::default()
    };
    let (_, free_points) = run(&problem, &free);
    let unbounded = largest_step_change(&free_points, &end);
    let max_change = unbounded / 4.0;
    let bounded = RiksOptions {
        amplitude: Some(AmplitudeControl {
            dofs: end.clone(),
            max_change,
        }),
        ..free
    };
    let (result, points) = run(&problem, &bounded);
    assert!(
        matches!(result.stop, PathStop::MaxLoad),
        "{}",
        result.stop.describe()
    );
    let largest = largest_step_change(&points, &end);
    assert!(
        largest <= max_change * (1.0 + 1e-12),
        "{largest} > {max_change}"
    );
    assert!(points.len() > free_points.len());
    for (_, state) in &points {
        assert_on_exact_path(&problem, &positions, state);
    }
}

#[test]
fn oversized_steps_are_halved_and_the_path_stays_exact() {
    // A very stiff cubic term with a huge first arc length and few iterations allowed: the
    // first attempts fail and are retried with half the arc length.
    let model = NonlinearSpring {
        k: 1.0,
        b: 0.0,
        c: 50.0,
    };
    let problem = strip_problem(model, 2);
    let positions = free_positions(&problem);
    let options = RiksOptions {
        initial_arc_length: 40.0,
        max_arc_length: 40.0,
        max_iterations: 4,
        max_steps: 5,
        ..RiksOptions::default()
    };
    let (result, points) = run(&problem, &options);
    assert!(
        matches!(result.stop, PathStop::MaxSteps),
        "{}",
        result.stop.describe()
    );
    assert!(result.statistics.rejected_steps > 0);
    for (_, state) in &points {
        assert_on_exact_path(&problem, &positions, state);
    }
}

#[test]
fn displacement_control_uses_the_load_derivative_of_prescribed_values() {
    // u = 0 on `left`, u = λ on `right`, no traction: ε = λ / L on the whole path.
    let model = NonlinearSpring {
        k: 1.0,
        b: 0.0,
        c: 3.0,
    };
    let mesh = Mesh::rectangle(LENGTH, 1.0, 3, 1, 1.0).unwrap();
    let conditions = [
        DirichletCondition::fixed("left", 0),
        DirichletCondition {
            value_per_load: 1.0,
            ..DirichletCondition::fixed("right", 0)
        },
    ];
    let problem = Problem::new(model, Arc::new(mesh), &conditions, &Loads::default()).unwrap();
    let positions = free_positions(&problem);
    let options = RiksOptions {
        max_load: Some(1.0),
        ..RiksOptions::default()
    };
    let (result, points) = run(&problem, &options);
    assert!(
        matches!(result.stop, PathStop::MaxLoad),
        "{}",
        result.stop.describe()
    );
    assert!(points.len() > 3);
    for (_, state) in &points {
        for (u, x) in state.displacement.iter().zip(&positions) {
            assert!((u - state.load * x / LENGTH).abs() <= 1e-9);
        }
    }
}

/// A state that overflowed (as a diverging step end can) must never read as converged: the
/// relative residual is NaN, not the 0 that `f64::max` would leave after dropping the NaN.
#[test]
fn overflowed_state_has_a_nan_relative_residual_not_zero() {
    let problem = strip_problem(
        NonlinearSpring {
            k: 1.0,
            b: 0.5,
            c: 0.2,
        },
        2,
    );
    let positions = free_positions(&problem);
    let exact: Vec<f64> = positions.iter().map(|x| 0.01 * x).collect();
    let load = problem.assembler.model().stress(0.01);
    assert!(problem.relative_residual(&exact, load) < 1e-12);
    let overflowed: Vec<f64> = positions.iter().map(|x| 1e300 * x).collect();
    let residual = problem.relative_residual(&overflowed, 1e300);
    assert!(residual.is_nan(), "{residual}");
}
