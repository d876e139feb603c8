//! The path as an application asks for it: one entry point, [`follow_path`], that traces
//! $`R(U, \lambda) = 0`$ from a start point with the chosen method (the ANM, with or without
//! Padé, or Newton–Riks) and lands the last point on the target the path stopped at.
//!
//! The application sees the path only through a [`PathObserver`]: every accepted point, its
//! own measure of a point (the amplitude its target is set in, e.g. the largest physical
//! deflection over the thickness, which only it knows how to compute from the model's
//! fields), and the landed point that replaces the overshooting one. Its stop criteria stay its
//! own: it stops the path by returning [`PathControl::Stop`].
//!
//! **Landings** ([`landing`](super::landing)). The path stops at its first computed point past
//! the target: Riks' step end (up to half a thickness past an amplitude target), the ANM's next
//! dense-output point (2.6 % past it on the default scene). When the observer stopped the path
//! and wants the landing ([`PathObserver::wants_landing`]), the last point is moved back onto
//! [`FollowOptions::amplitude_target`]; a Riks path stopped by its `max_load` lands on that
//! load the same way (the ANM evaluates its series there exactly). If no correction lands, the
//! path is left as it was.

use std::time::Instant;

use super::anm::{AnmOptions, AnmStep, StepTail, follow_path_anm_to_tail};
use super::arc_length::ArcCorrectorOptions;
use super::landing::{LandingTarget, land, land_on_step};
use super::linearization::{Linearization, Workspace};
use super::path::{PathControl, PathEvent, PathResult, PathState, PathStop};
use super::riks::{RiksOptions, follow_path_riks};
use crate::linear::factor::SparseFactorization;
use crate::model::EnergyModel;
use crate::problem::Problem;

/// The path-following method and its settings.
#[derive(Clone, Debug)]
pub enum FollowMethod {
    /// The Asymptotic Numerical Method ([`follow_path_anm`]; Padé by [`AnmOptions::pade`]).
    Anm(AnmOptions),
    /// Newton–Riks arc-length continuation ([`follow_path_riks`]).
    Riks(RiksOptions),
}

/// Settings of [`follow_path`].
#[derive(Clone, Debug)]
pub struct FollowOptions {
    /// The method.
    pub method: FollowMethod,
    /// The amplitude (in [`PathObserver::amplitude`]'s measure) the last point lands on when
    /// the observer stopped the path past it; `None`: no amplitude landing.
    pub amplitude_target: Option<f64>,
    /// The arc-length corrector of the landings.
    pub landing_corrector: ArcCorrectorOptions,
}

/// What a path is followed for: the application's side of [`follow_path`].
pub trait PathObserver {
    /// An accepted point; [`PathControl::Stop`] ends the path after it.
    fn observe(&mut self, event: &PathEvent) -> PathControl;

    /// The measure of `state` that [`FollowOptions::amplitude_target`] is set in.
    fn amplitude(&self, state: &PathState) -> f64;

    /// Whether a path this observer stopped should land on its target (e.g. not when the user
    /// interrupted it).
    fn wants_landing(&self) -> bool {
        true
    }

    /// The last observed point overshot the target and is replaced by `landed`, a point
    /// between it and `kept` (the point observed before it, which stays).
    fn replace_last(&mut self, kept: &PathState, landed: &PathEvent);
}

/// The outcome of [`follow_path`].
#[derive(Debug)]
pub struct FollowedPath {
    /// The path: its last point (the landed one after a landing), statistics (the landing's
    /// work included), why it stopped.
    pub result: PathResult,
    /// The ANM's step log (empty for Riks).
    pub anm_steps: Vec<AnmStep>,
}

/// Follows the path from `start` with `options.method`, reporting every accepted point to
/// `observer`, then lands the last point on its target (see the [module](self)). `factor`
/// must have been analysed for the problem's tangent pattern.
pub fn follow_path<M: EnergyModel>(
    problem: &Problem<M>,
    start: PathState,
    factor: &mut SparseFactorization,
    options: &FollowOptions,
    observer: &mut dyn PathObserver,
) -> FollowedPath {
    follow_path_in_workspace(problem, (start, None), factor, options, observer)
}

/// [`follow_path`] in the [`Workspace`] made for the path, when given: the ANM assembles and
/// checks its step ends in its buffers, and keeps the factorisation it holds for the first
/// step when the start's tangent is the one factorised there ([`Workspace::newton`]). Riks does
/// not use it.
pub fn follow_path_in_workspace<M: EnergyModel>(
    problem: &Problem<M>,
    (start, workspace): (PathState, Option<Workspace>),
    factor: &mut SparseFactorization,
    options: &FollowOptions,
    observer: &mut dyn PathObserver,
) -> FollowedPath {
    let mut recent = RecentPoints::default();
    let mut anm_steps = Vec::new();
    let (mut result, tail) = {
        let mut watch = |event: &PathEvent| {
            recent.record(event);
            observer.observe(event)
        };
        match &options.method {
            FollowMethod::Anm(anm) => follow_path_anm_to_tail(
                problem,
                (start, workspace),
                factor,
                anm,
                &mut watch,
                &mut anm_steps,
            ),
            FollowMethod::Riks(riks) => (
                follow_path_riks(problem, start, factor, riks, &mut watch),
                None,
            ),
        }
    };
    if let Some(target) = landing_target(&result.stop, options)
        && observer.wants_landing()
    {
        land_last_point(
            problem,
            factor,
            options,
            target,
            (recent, tail),
            observer,
            &mut result,
        );
    }
    FollowedPath { result, anm_steps }
}

/// What a path that stopped with `stop` lands on: the amplitude target when the observer
/// stopped it, Riks' `max_load` when that did.
fn landing_target(stop: &PathStop, options: &FollowOptions) -> Option<LandingTarget> {
    match (stop, &options.method) {
        (PathStop::Observer, _) => options.amplitude_target.map(LandingTarget::Amplitude),
        (PathStop::MaxLoad, FollowMethod::Riks(riks)) => riks.max_load.map(LandingTarget::Load),
        _ => None,
    }
}

/// Lands the last of the `recent` points on `target` — on the ANM step the path stopped in
/// when there is one ([`land_on_step`]: no correction), else by correcting chords ([`land`]);
/// a landed point replaces it in the observer and in `result`, whose statistics receive the
/// landing's work and time.
fn land_last_point<M: EnergyModel>(
    problem: &Problem<M>,
    factor: &mut SparseFactorization,
    options: &FollowOptions,
    target: LandingTarget,
    (recent, tail): (RecentPoints, Option<StepTail>),
    observer: &mut dyn PathObserver,
    result: &mut PathResult,
) {
    let (Some(below), Some((step, above))) = (recent.penultimate, recent.last) else {
        return;
    };
    let clock = Instant::now();
    let mut linearization = Linearization::new(problem, factor);
    let landed = {
        let measure = |state: &PathState| match target {
            LandingTarget::Amplitude(_) => observer.amplitude(state),
            LandingTarget::Load(_) => state.load,
        };
        let tolerance = options.landing_corrector.tolerance;
        tail.and_then(|tail| land_on_step(&mut linearization, &tail, target, &measure, tolerance))
            .or_else(|| {
                land(
                    &mut linearization,
                    &below,
                    &above,
                    target,
                    &measure,
                    &options.landing_corrector,
                )
            })
    };
    result.statistics.add_linear_work(&linearization.statistics);
    let Some(landed) = landed else {
        result.statistics.total_seconds += clock.elapsed().as_secs_f64();
        return;
    };
    let event = PathEvent {
        step,
        interior: false,
        state: &landed.state,
        relative_residual: landed.relative_residual,
        predicted_bifurcation: None,
        on_step: None,
    };
    // The observer records the landed point (its recording time is part of the path's).
    observer.replace_last(&below, &event);
    result.last = landed.state;
    result.statistics.total_seconds += clock.elapsed().as_secs_f64();
}

/// The last two points reported to the observer (the step of the last one too).
#[derive(Default)]
struct RecentPoints {
    penultimate: Option<PathState>,
    last: Option<(usize, PathState)>,
}

impl RecentPoints {
    fn record(&mut self, event: &PathEvent) {
        let last = self.last.replace((event.step, event.state.clone()));
        self.penultimate = last.map(|(_, state)| state);
    }
}
