//! The path as an application asks for it ([`follow_path`]): the ANM (with and without Padé)
//! and Riks on the nonlinear spring of `support` (exact path $`\lambda = \sigma(\varepsilon)`$,
//! $`\sigma = 2\varepsilon + 1.5\varepsilon^3`$ here), landed on an amplitude target (the
//! observer's measure: the strain $`\varepsilon`$) or on Riks' `max_load`.
//!
//! Expected: the last point lies in the target's window — $`[t, t(1 + 10^{-3})]`$ for the
//! amplitude, $`[t, t(1 + 10^{-9})]`$ for the load — on the exact path, reported to the
//! observer as the replacement of the overshooting point (whose predecessor is kept).

mod support;

use support::{NonlinearSpring, assert_on_exact_path, strain, strip_problem};
use wrinkle_runtime::linear::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::anm::AnmOptions;
use wrinkle_runtime::solve::arc_length::{ArcCorrectorOptions, ArcLengthConstraint};
use wrinkle_runtime::solve::follow::{
    FollowMethod, FollowOptions, FollowedPath, PathObserver, follow_path,
};
use wrinkle_runtime::solve::landing::{AMPLITUDE_LANDING_TOLERANCE, LOAD_LANDING_TOLERANCE};
use wrinkle_runtime::solve::path::{PathControl, PathEvent, PathState, PathStop};
use wrinkle_runtime::solve::riks::RiksOptions;

const HARDENING: NonlinearSpring = NonlinearSpring {
    k: 2.0,
    b: 0.0,
    c: 1.5,
};

/// Records the points, stops at `target` strain, and counts the landings.
struct Recorder<'a> {
    problem: &'a Problem<NonlinearSpring>,
    target: f64,
    landing: bool,
    points: Vec<PathState>,
    replaced: Vec<(PathState, PathState)>,
}

impl PathObserver for Recorder<'_> {
    fn observe(&mut self, event: &PathEvent) -> PathControl {
        self.points.push(event.state.clone());
        if strain(self.problem, event.state) >= self.target {
            PathControl::Stop
        } else {
            PathControl::Continue
        }
    }

    fn amplitude(&self, state: &PathState) -> f64 {
        strain(self.problem, state)
    }

    fn wants_landing(&self) -> bool {
        self.landing
    }

    fn replace_last(&mut self, kept: &PathState, landed: &PathEvent) {
        let overshooting = self.points.pop().expect("a point to replace");
        assert_eq!(self.points.last(), Some(kept));
        self.replaced.push((overshooting, landed.state.clone()));
        self.points.push(landed.state.clone());
    }
}

/// Follows the spring's path from rest with `method`, landing on `target` strain.
fn follow(
    problem: &Problem<NonlinearSpring>,
    method: FollowMethod,
    target: f64,
    landing: bool,
) -> (FollowedPath, Recorder<'_>) {
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let start = PathState {
        displacement: vec![0.0; problem.free_count()],
        load: 0.0,
    };
    let options = FollowOptions {
        method,
        amplitude_target: Some(target),
        landing_corrector: ArcCorrectorOptions {
            tolerance: 1e-10,
            max_iterations: 15,
            load_scale: 1.0,
            constraint: ArcLengthConstraint::Spherical,
        },
    };
    let mut recorder = Recorder {
        problem,
        target,
        landing,
        points: Vec::new(),
        replaced: Vec::new(),
    };
    let followed = follow_path(problem, start, &mut factor, &options, &mut recorder);
    (followed, recorder)
}

fn methods() -> Vec<(&'static str, FollowMethod)> {
    let anm = |pade| AnmOptions {
        order: 12,
        pade,
        ..AnmOptions::default()
    };
    vec![
        ("ANM", FollowMethod::Anm(anm(false))),
        ("ANM + Padé", FollowMethod::Anm(anm(true))),
        (
            "Riks",
            FollowMethod::Riks(RiksOptions {
                initial_arc_length: 0.3,
                max_arc_length: 0.6,
                ..RiksOptions::default()
            }),
        ),
    ]
}

#[test]
fn every_method_lands_on_the_amplitude_target() {
    let problem = strip_problem(HARDENING, 4);
    let target = 0.8;
    for (name, method) in methods() {
        let (followed, recorder) = follow(&problem, method, target, true);
        let result = &followed.result;
        assert!(
            matches!(result.stop, PathStop::Observer),
            "{name}: {}",
            result.stop.describe()
        );
        assert_eq!(recorder.replaced.len(), 1, "{name}: one landing");
        let (overshooting, landed) = &recorder.replaced[0];
        assert!(strain(&problem, overshooting) > target * (1.0 + AMPLITUDE_LANDING_TOLERANCE));
        let reached = strain(&problem, landed);
        assert!(
            reached >= target && reached <= target * (1.0 + AMPLITUDE_LANDING_TOLERANCE),
            "{name}: landed at strain {reached}, target {target}"
        );
        assert_eq!(result.last, *landed);
        assert_eq!(recorder.points.last(), Some(landed));
        assert_on_exact_path(&problem, landed);
    }
}

/// The ANM lands inside the step it stopped in, on the step's own approximant: no
/// factorisation more than the same path without a landing, when its points meet the landing
/// corrector's tolerance (as in `wrinkle run`, where both are `solver.tolerance`; the landed
/// point is on the exact path by the test above); Riks corrects a chord and refactorises.
#[test]
fn the_anm_lands_along_its_last_step_without_a_factorisation() {
    let problem = strip_problem(HARDENING, 4);
    let target = 0.8;
    for (name, mut method) in methods() {
        if let FollowMethod::Anm(anm) = &mut method {
            // The landing corrector's tolerance (`follow`).
            anm.residual_tolerance = 1e-10;
        }
        let (landed, recorder) = follow(&problem, method.clone(), target, true);
        let (kept, _) = follow(&problem, method, target, false);
        assert_eq!(recorder.replaced.len(), 1, "{name}: one landing");
        let landing =
            landed.result.statistics.factorizations - kept.result.statistics.factorizations;
        if name == "Riks" {
            assert!(landing >= 1, "{name}: {landing} factorisations to land");
        } else {
            assert_eq!(landing, 0, "{name}: {landing} factorisations to land");
        }
    }
}

#[test]
fn an_observer_that_declines_the_landing_keeps_the_overshooting_point() {
    let problem = strip_problem(HARDENING, 4);
    let target = 0.8;
    for (name, method) in methods() {
        let (followed, recorder) = follow(&problem, method, target, false);
        assert!(recorder.replaced.is_empty(), "{name}");
        assert_eq!(recorder.points.last(), Some(&followed.result.last));
        assert!(
            strain(&problem, &followed.result.last) > target * 1.001,
            "{name}"
        );
    }
}

#[test]
fn riks_stopped_by_max_load_lands_on_it() {
    let problem = strip_problem(HARDENING, 4);
    let max_load = 3.0;
    let riks = RiksOptions {
        initial_arc_length: 0.3,
        max_arc_length: 0.6,
        max_load: Some(max_load),
        ..RiksOptions::default()
    };
    let (followed, recorder) = follow(&problem, FollowMethod::Riks(riks), 10.0, true);
    let result = &followed.result;
    assert!(
        matches!(result.stop, PathStop::MaxLoad),
        "{}",
        result.stop.describe()
    );
    assert_eq!(recorder.replaced.len(), 1);
    assert!(recorder.replaced[0].0.load > max_load * (1.0 + LOAD_LANDING_TOLERANCE));
    let load = result.last.load;
    assert!(
        load >= max_load && load <= max_load * (1.0 + LOAD_LANDING_TOLERANCE),
        "landed at {load}"
    );
    assert_on_exact_path(&problem, &result.last);
    assert!(followed.anm_steps.is_empty());
}

#[test]
fn the_anm_meets_max_load_without_a_landing() {
    let problem = strip_problem(HARDENING, 4);
    let max_load = 3.0;
    let anm = AnmOptions {
        order: 12,
        max_load: Some(max_load),
        ..AnmOptions::default()
    };
    let (followed, recorder) = follow(&problem, FollowMethod::Anm(anm), 10.0, true);
    let result = &followed.result;
    assert!(
        matches!(result.stop, PathStop::MaxLoad),
        "{}",
        result.stop.describe()
    );
    assert!(recorder.replaced.is_empty());
    assert!((result.last.load - max_load).abs() <= 1e-12 * max_load);
    assert!(!followed.anm_steps.is_empty());
}
