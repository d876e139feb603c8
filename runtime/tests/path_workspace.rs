//! A path in a [`Workspace`]: the start's Newton iterations assemble into the path's own
//! matrix, and the ANM's first step keeps their last factorisation when the tangent at the
//! start is the one factorised ([`Linearization::factorize_unless_held`]), on the nonlinear
//! spring of `support` ($`\sigma = 2\varepsilon + 1.5\varepsilon^3`$).
//!
//! Expected: the same path as without the workspace (every point within $`10^{-12}`$ of it, the
//! tangents differing only by Newton's last correction; on the exact path to the ANM's residual
//! tolerance), with one factorisation fewer; a held
//! tangent that is not the start's is refactorised (the path bit for bit the plain one's, the
//! same count); [`same_tangent`] tells a rounding-level difference from a real one.
//!
//! [`Linearization::factorize_unless_held`]:
//! wrinkle_runtime::solve::linearization::Linearization::factorize_unless_held

mod support;

use support::{NonlinearSpring, assert_on_exact_path, strain, strip_problem};
use wrinkle_runtime::linear::{SparseFactorization, SparseMatrix};
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::anm::AnmOptions;
use wrinkle_runtime::solve::arc_length::{ArcCorrectorOptions, ArcLengthConstraint};
use wrinkle_runtime::solve::follow::{
    FollowMethod, FollowOptions, FollowedPath, PathObserver, follow_path_in_workspace,
};
use wrinkle_runtime::solve::linearization::{HELD_TANGENT_TOLERANCE, Workspace, same_tangent};
use wrinkle_runtime::solve::newton::{NewtonOptions, newton};
use wrinkle_runtime::solve::path::{PathControl, PathEvent, PathState};

const HARDENING: NonlinearSpring = NonlinearSpring {
    k: 2.0,
    b: 0.0,
    c: 1.5,
};

const TARGET_STRAIN: f64 = 0.8;

/// Records the points and stops at the target strain.
struct Recorder<'a> {
    problem: &'a Problem<NonlinearSpring>,
    points: Vec<PathState>,
}

impl PathObserver for Recorder<'_> {
    fn observe(&mut self, event: &PathEvent) -> PathControl {
        self.points.push(event.state.clone());
        if strain(self.problem, event.state) >= TARGET_STRAIN {
            PathControl::Stop
        } else {
            PathControl::Continue
        }
    }

    fn amplitude(&self, state: &PathState) -> f64 {
        strain(self.problem, state)
    }

    fn wants_landing(&self) -> bool {
        false
    }

    fn replace_last(&mut self, _: &PathState, _: &PathEvent) {}
}

/// How the path's start and first factorisation are come by.
enum Start {
    /// The plain path from the Newton start, without a workspace.
    Plain,
    /// Newton assembles into the workspace, which holds its last factorisation.
    Held,
    /// The workspace's Newton ran at another load, then the start's Newton outside it: the
    /// workspace holds a tangent that is not the start's.
    HeldElsewhere,
}

/// The spring's path from the equilibrium at zero load found by Newton from a strained guess.
fn follow(problem: &Problem<NonlinearSpring>, start: Start) -> (FollowedPath, Vec<PathState>) {
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut workspace = Workspace::new(problem, &factor).unwrap();
    let guess = vec![0.05; problem.free_count()];
    let newton_options = NewtonOptions::default();
    if let Start::HeldElsewhere = start {
        // The workspace's Newton at another load: it holds the tangent there.
        let solution = workspace.newton(problem, guess.clone(), 0.5, &mut factor, &newton_options);
        assert!(solution.unwrap().iterations >= 1);
    }
    let solution = match start {
        Start::Plain | Start::HeldElsewhere => {
            let mut plain = problem.new_matrix();
            newton(
                problem,
                guess,
                0.0,
                &mut factor,
                &mut plain,
                &newton_options,
            )
        }
        Start::Held => workspace.newton(problem, guess, 0.0, &mut factor, &newton_options),
    }
    .unwrap();
    assert!(solution.iterations >= 2, "Newton iterated");
    let state = PathState {
        displacement: solution.solution,
        load: 0.0,
    };
    let workspace = match start {
        Start::Plain => None,
        Start::Held | Start::HeldElsewhere => Some(workspace),
    };
    let options = FollowOptions {
        method: FollowMethod::Anm(AnmOptions {
            order: 12,
            ..AnmOptions::default()
        }),
        amplitude_target: Some(TARGET_STRAIN),
        landing_corrector: ArcCorrectorOptions {
            tolerance: 1e-10,
            max_iterations: 15,
            load_scale: 1.0,
            constraint: ArcLengthConstraint::Spherical,
        },
    };
    let mut recorder = Recorder {
        problem,
        points: Vec::new(),
    };
    let followed = follow_path_in_workspace(
        problem,
        (state, workspace),
        &mut factor,
        &options,
        &mut recorder,
    );
    (followed, recorder.points)
}

#[test]
fn the_first_step_keeps_the_start_newtons_factorisation_and_the_path_is_the_same() {
    let problem = strip_problem(HARDENING, 4);
    let (plain, plain_points) = follow(&problem, Start::Plain);
    let (held, held_points) = follow(&problem, Start::Held);
    let (plain, held) = (&plain.result.statistics, &held.result.statistics);
    assert!(plain.steps >= 2, "{plain:?}");
    assert_eq!(held.steps, plain.steps);
    assert_eq!(held.factorizations + 1, plain.factorizations);
    assert_eq!(held.tangent_assemblies, plain.tangent_assemblies);
    assert_eq!(held_points.len(), plain_points.len());
    // The start (Newton's, at rest) on the exact path; every point within the ANM's residual
    // tolerance of it.
    assert_on_exact_path(&problem, &held_points[0]);
    for point in &held_points {
        let exact = problem.assembler.model().stress(strain(&problem, point));
        let off = (point.load - exact).abs();
        assert!(
            off <= 1e-6 * (1.0 + exact.abs()),
            "{point:?} off σ = {exact}"
        );
    }
    for (a, b) in held_points.iter().zip(&plain_points) {
        let scale = 1.0 + b.load.abs();
        assert!(
            (a.load - b.load).abs() <= 1e-12 * scale,
            "{a:?} against {b:?}"
        );
        for (x, y) in a.displacement.iter().zip(&b.displacement) {
            assert!((x - y).abs() <= 1e-12 * (1.0 + y.abs()), "{x} against {y}");
        }
    }
}

#[test]
fn a_held_factorisation_of_another_tangent_is_refactorised() {
    let problem = strip_problem(HARDENING, 4);
    let (plain, plain_points) = follow(&problem, Start::Plain);
    let (elsewhere, elsewhere_points) = follow(&problem, Start::HeldElsewhere);
    let (plain, elsewhere) = (&plain.result.statistics, &elsewhere.result.statistics);
    assert_eq!(elsewhere.factorizations, plain.factorizations);
    assert_eq!(elsewhere_points, plain_points);
}

#[test]
fn same_tangent_tells_rounding_from_a_change() {
    let problem = strip_problem(HARDENING, 4);
    let mut held = problem.new_matrix();
    problem.tangent_into(&vec![0.1; problem.free_count()], 0.0, &mut held);
    let largest = held.values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let perturbed = |relative: f64| {
        let mut matrix: SparseMatrix = held.clone();
        matrix.values[0] += relative * largest;
        matrix
    };
    assert!(same_tangent(&held, &held.clone()));
    assert!(same_tangent(
        &held,
        &perturbed(0.5 * HELD_TANGENT_TOLERANCE)
    ));
    assert!(!same_tangent(
        &held,
        &perturbed(2.0 * HELD_TANGENT_TOLERANCE)
    ));
    assert!(!same_tangent(&held, &perturbed(f64::NAN)));
    let mut other = problem.new_matrix();
    problem.tangent_into(&vec![0.2; problem.free_count()], 0.0, &mut other);
    assert!(!same_tangent(&held, &other));
    // Another pattern (a longer strip) never matches.
    let longer = strip_problem(HARDENING, 5);
    assert!(!same_tangent(&held, &longer.new_matrix()));
}
