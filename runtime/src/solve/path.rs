//! Types shared by the path-following solvers ([`anm`](super::anm), [`riks`](super::riks)).
//!
//! A solver traces $`R(U,\lambda) = 0`$ from a start point and reports every accepted point to
//! an observer, which decides whether to go on (stop criteria that depend on the physics, such
//! as the envelope amplitude, live with the caller; the solver knows only the residual).

use super::error::SolveError;

/// A point $`(U, \lambda)`$ of the path.
#[derive(Clone, Debug, PartialEq)]
pub struct PathState {
    /// Free dof values.
    pub displacement: Vec<f64>,
    /// Load parameter.
    pub load: f64,
}

/// One accepted point as reported to the observer.
#[derive(Clone, Debug)]
pub struct PathEvent<'a> {
    /// Step index (0 = the start point).
    pub step: usize,
    /// `true` for a point inside a step (dense output from the series), `false` for a step's
    /// end point (or the start point).
    pub interior: bool,
    /// The point.
    pub state: &'a PathState,
    /// Relative residual $`\|R\|/\text{scale}`$ at the point.
    pub relative_residual: f64,
    /// Predicted bifurcation load from the tangent at this step's start, when computed.
    pub predicted_bifurcation: Option<f64>,
    /// Where the point lies on its step's own approximant, when it does (the ANM's dense output
    /// and uncorrected step ends; not Riks' points, the start, or a landed point): the
    /// observer can evaluate the path between it and the point reported before it.
    pub on_step: Option<OnStep<'a>>,
}

/// A point's place on the approximant of the ANM step it belongs to ([`PathEvent::on_step`]):
/// every point of the step between `previous` and `parameter` is `evaluate(a)`, as the step
/// evaluated its own points. An observer lands on a value of its own measure there
/// ([`landing::parameter_on_step`](super::landing::parameter_on_step)) without a correction.
#[derive(Clone, Copy)]
pub struct OnStep<'a> {
    /// The point's path parameter $`a`$ in its step.
    pub parameter: f64,
    /// The path parameter of the point reported before it in the same step (0: the step's
    /// start, which is the previous step's end).
    pub previous: f64,
    /// The step's point at a path parameter.
    pub evaluate: &'a dyn Fn(f64) -> PathState,
}

impl std::fmt::Debug for OnStep<'_> {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        formatter
            .debug_struct("OnStep")
            .field("parameter", &self.parameter)
            .field("previous", &self.previous)
            .finish_non_exhaustive()
    }
}

/// What the observer wants after an event.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathControl {
    /// Go on.
    Continue,
    /// Stop after this point (the caller's criterion was met).
    Stop,
}

/// Why a path ended.
#[derive(Debug)]
pub enum PathStop {
    /// The observer asked to stop.
    Observer,
    /// The maximum load was reached.
    MaxLoad,
    /// The step budget was used up.
    MaxSteps,
    /// A failure; every point before it was reported and is kept.
    Failed(SolveError),
}

impl PathStop {
    /// Human-readable reason.
    pub fn describe(&self) -> String {
        match self {
            PathStop::Observer => "stop criterion reached".into(),
            PathStop::MaxLoad => "maximum load reached".into(),
            PathStop::MaxSteps => "maximum number of steps reached".into(),
            PathStop::Failed(e) => format!("failed: {e}"),
        }
    }
    /// Whether the path ended by a failure.
    pub fn is_failure(&self) -> bool {
        matches!(self, PathStop::Failed(_))
    }
}

/// Work counters and timings of a path.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PathStatistics {
    /// Accepted steps.
    pub steps: usize,
    /// Numeric factorisations of the tangent.
    pub factorizations: usize,
    /// Of `factorizations`, those of the bifurcation predictions and of locating a crossed
    /// critical point (a shifted tangent, or the tangent at an earlier point): timed in
    /// `bifurcation_seconds`, not in `factorization_seconds`, whose mean is over the others.
    pub prediction_factorizations: usize,
    /// Tangent assemblies.
    pub tangent_assemblies: usize,
    /// `f64` residual assemblies.
    pub residual_assemblies: usize,
    /// Series-residual assemblies (ANM right-hand sides).
    pub series_assemblies: usize,
    /// Newton corrections applied (ANM) / Newton iterations (Riks).
    pub corrections: usize,
    /// Rejected step-end attempts: ends halved or shortened towards the series' range, and
    /// steps redone after jumping over a critical point (ANM); halved steps (Riks).
    pub rejected_steps: usize,
    /// Seconds in tangent assembly.
    pub assembly_seconds: f64,
    /// Seconds in numeric factorisation.
    pub factorization_seconds: f64,
    /// Seconds computing series terms (ANM) including their solves.
    pub series_seconds: f64,
    /// Of `series_seconds`, the forward and backward solves with the factorised tangent (one
    /// per order); the rest is the Taylor-mode right-hand sides.
    pub series_solve_seconds: f64,
    /// Seconds evaluating `f64` residuals: the check of every candidate step end and interior
    /// point (ANM), and the residuals of corrector iterations.
    pub residual_seconds: f64,
    /// Seconds in bifurcation prediction (eigen-solves).
    pub bifurcation_seconds: f64,
    /// Wall time of the whole path.
    pub total_seconds: f64,
    /// Bytes of the Taylor tape of the ANM's series (`None` for Riks): what the recurrences
    /// keep per quadrature point, for every order of a step.
    pub tape_bytes: Option<usize>,
    /// Entries of the factor of the tangent (fill-in included), after the last factorisation.
    pub factor_nonzeros: Option<usize>,
}

impl PathStatistics {
    /// Runs one `f64` residual evaluation, counting it in `residual_assemblies` and its time in
    /// `residual_seconds` (every solver's residual checks go through here).
    pub fn time_residual<T>(&mut self, evaluate: impl FnOnce() -> T) -> T {
        let clock = std::time::Instant::now();
        let residual = evaluate();
        self.residual_assemblies += 1;
        self.residual_seconds += clock.elapsed().as_secs_f64();
        residual
    }

    /// Adds the linear-algebra work counted in `work` — factorisations, tangent and residual
    /// assemblies and their times — but not its steps, corrections or rejections (e.g. an
    /// arc-length correction's Newton iterations inside an ANM step).
    pub fn add_linear_work(&mut self, work: &PathStatistics) {
        self.factorizations += work.factorizations;
        self.prediction_factorizations += work.prediction_factorizations;
        self.tangent_assemblies += work.tangent_assemblies;
        self.residual_assemblies += work.residual_assemblies;
        self.residual_seconds += work.residual_seconds;
        self.assembly_seconds += work.assembly_seconds;
        self.factorization_seconds += work.factorization_seconds;
    }
}

/// The outcome of a path-following run: whatever was computed, and why it ended.
#[derive(Debug)]
pub struct PathResult {
    /// Last accepted point.
    pub last: PathState,
    /// Counters and timings.
    pub statistics: PathStatistics,
    /// Why it ended.
    pub stop: PathStop,
    /// Bifurcation detected along the path: load, and the step at which it was detected.
    pub bifurcation: Option<(f64, usize)>,
    /// Diagnostics that did not stop the path (e.g. a failed eigen-solve while locating a
    /// bifurcation), each saying where and why.
    pub warnings: Vec<String>,
}
