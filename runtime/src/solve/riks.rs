//! Newton–Riks arc-length path following: the classical baseline beside the ANM.
//!
//! The path $`R(U,\lambda) = 0`$ is traced by steps of prescribed arc length $`\ell`$,
//! $$`\|\Delta U\|^2 + \psi^2 \Delta\lambda^2 = \ell^2,`$$
//! where $`(\Delta U, \Delta\lambda)`$ is the increment from the last accepted point and
//! $`\psi`$ ([`RiksOptions::load_scale`]) weighs the load parameter against the displacements.
//! With [`RiksOptions::reference_load`] the arc length is dimensionless instead:
//! $`\|\Delta U\|^2/s^2 + \Delta\lambda^2/\lambda_\text{ref}^2 = \ell^2`$, with $`s`$ the norm of the
//! linear response to $`\lambda_\text{ref}`$ at the start, so that the same arc lengths take the
//! same steps on every mesh.
//!
//! * **Predictor**: the tangent $`(\delta U_F, 1)`$ with $`K_t\,\delta U_F = -\partial R/\partial\lambda`$,
//!   scaled to length $`\ell`$; its orientation follows the previous increment (sign of the dot
//!   product in the arc-length metric), the first step increases $`\lambda`$. When the tangent at
//!   the accepted point cannot be factorised, the previous increment (secant) is used instead.
//! * **Corrector**: full Newton on the bordered system of the arc-length constraint
//!   ([`arc_length`](super::arc_length): the two-solve trick, the linearised or spherical
//!   constraint of [`RiksOptions::constraint`]). The tangent is reassembled and refactorised
//!   every iteration.
//! * **Crossing guard**: the tangent at each accepted point is factorised at once (it is the
//!   next step's predictor tangent, so this costs nothing when the point is kept). When it has
//!   negative pivots after a stable start (none) and the path tangent there still moves the load
//!   the way the step's predictor did, the step converged past a bifurcation — near a nearly
//!   perfect one, onto the unstable fundamental branch beyond the sharp turn of the imperfect
//!   path — and is redone with half the arc length, up to [`MAX_CROSSING_HALVINGS`] times,
//!   after which the crossing is the path's own (a perfect bifurcation) and the step is kept.
//!   Where the load turns back the critical point is a limit point, which the path passes as it
//!   should. Without the guard, arc lengths of 0.3 (in the dimensionless metric) ended
//!   example 1 at 1.9 λ_c on another branch, or stayed on the fundamental branch to 600 λ_c
//!   with a 1e-6 imperfection.
//! * **Step control**: a failed step (no convergence, singular tangent, NaN, no real root) is
//!   retried with $`\ell/2`$; below [`RiksOptions::min_arc_length`] the path ends with
//!   [`PathStop::Failed`]. After an accepted step,
//!   $`\ell \leftarrow \ell\sqrt{n_\text{desired}/n_\text{used}}`$, clamped to
//!   $`[\ell_\text{min}, \ell_\text{max}]`$.
//! * **Amplitude control** ([`RiksOptions::amplitude`]): a converged step that changes one of
//!   the monitored dofs by more than $`\Delta_\text{max}`$ is redone with the arc length
//!   scaled by $`0.9\,\Delta_\text{max}/\Delta`$, and after an accepted step the next arc
//!   length is capped the same way, so that the knee of a response whose wrinkles are small
//!   beside the in-plane displacements (which dominate the arc length) is resolved.

use std::borrow::Cow;
use std::time::Instant;

pub use super::arc_length::ArcLengthConstraint;
use super::arc_length::{
    ArcCorrection, ArcCorrectorOptions, arc_dot, correct, increment, orientation,
};
use super::error::SolveError;
use super::linearization::Linearization;
use super::path::{PathControl, PathEvent, PathResult, PathState, PathStop};
use crate::linear::factor::SparseFactorization;
use crate::linear::vector::norm;
use crate::model::EnergyModel;
use crate::problem::Problem;

/// Halvings of a step that jumped over a bifurcation (negative pivots at its end after a
/// stable start, the load still moving the same way) before the crossing is taken as the
/// path's own.
///
/// Near a nearly perfect bifurcation the imperfect path turns sharply at $`\lambda_c`$, within
/// a load range that shrinks with the imperfection, and a step can converge past the turn onto
/// the unstable fundamental branch (one negative pivot): the end's tangent, factorised anyway
/// as the next step's, shows it. Such a step is redone with half the arc length. 12 halvings
/// (a factor 4096) resolve the turn of example 1 with a 1e-6 imperfection, where 4 did not;
/// a crossing that survives them is a perfect bifurcation of the path itself, and the step is
/// kept (as it is when a halving would go below `RiksOptions::min_arc_length`). As in the
/// ANM's guard, only a start without negative pivot is kept stable.
pub const MAX_CROSSING_HALVINGS: usize = 12;

/// Shrinks of one step whose monitored change exceeds [`AmplitudeControl::max_change`] before
/// the step is kept as it is (each shrink scales the arc length by at most 0.9).
pub const MAX_AMPLITUDE_SHRINKS: usize = 12;

/// Fraction of [`AmplitudeControl::max_change`] a shortened step aims at.
const AMPLITUDE_TARGET: f64 = 0.9;

/// A bound on the change of some dofs in one step ([`RiksOptions::amplitude`]).
#[derive(Clone, Debug, PartialEq)]
pub struct AmplitudeControl {
    /// Free dof numbers, e.g. every free dof of the deflection (or envelope) fields.
    pub dofs: Vec<usize>,
    /// The largest change $`\Delta_\text{max} = \max_i |\Delta U_i|`$ over `dofs` one step
    /// may make, in the dofs' own unit.
    pub max_change: f64,
}

/// Settings of [`follow_path_riks`].
#[derive(Clone, Debug, PartialEq)]
pub struct RiksOptions {
    /// Arc length $`\ell`$ of the first step.
    pub initial_arc_length: f64,
    /// Smallest arc length tried before the path is declared failed.
    pub min_arc_length: f64,
    /// Largest arc length the adaptation may reach.
    pub max_arc_length: f64,
    /// Accept a corrector iterate when $`\|R\| \le`$ `tolerance` × [`Problem::residual_scale`]
    /// (as in [`newton`](super::newton::newton)).
    pub tolerance: f64,
    /// Newton iterations allowed per step attempt.
    pub max_iterations: usize,
    /// Target iteration count of the arc-length adaptation
    /// $`\ell_{k+1} = \ell_k\sqrt{n_\text{desired}/n_\text{used}}`$.
    pub desired_iterations: usize,
    /// Accepted steps after which the path stops ([`PathStop::MaxSteps`]).
    pub max_steps: usize,
    /// Stop ([`PathStop::MaxLoad`]) at the first accepted point with $`\lambda \ge`$ this.
    pub max_load: Option<f64>,
    /// Weight $`\psi`$ of the load parameter in the arc length (0 = displacements only).
    /// Unused with [`RiksOptions::reference_load`].
    pub load_scale: f64,
    /// `Some(λ_ref)`: a dimensionless arc length,
    /// $`\ell^2 = \|\Delta U\|^2/s^2 + \Delta\lambda^2/\lambda_\text{ref}^2`$ with
    /// $`s = |\lambda_\text{ref}|\,\|\delta U_F\|`$ the norm of the linear response to the load
    /// $`\lambda_\text{ref}`$ at the start point ($`K_t\,\delta U_F = -\partial R/\partial\lambda`$).
    /// The three arc lengths are then fractions of that response, on the fundamental branch a
    /// step of $`\ell`$ moves the load by about $`\ell\lambda_\text{ref}/\sqrt2`$, and the number
    /// of steps does not grow with the mesh (a Euclidean $`\|\Delta U\|`$ grows as the square
    /// root of the number of unknowns). `None`: the metric of `load_scale`, displacements in
    /// their own unit.
    pub reference_load: Option<f64>,
    /// Constraint used by the corrector.
    pub constraint: ArcLengthConstraint,
    /// `Some`: no step changes the monitored dofs by more than
    /// [`AmplitudeControl::max_change`] (a step that does is redone shorter, up to
    /// [`MAX_AMPLITUDE_SHRINKS`] times, and the next arc length is capped). The arc length is
    /// a norm over all unknowns, in which wrinkles that are small beside the in-plane
    /// displacements barely count: on the long strip at 16 × 8 one step of 0.3 (dimensionless)
    /// took the physical amplitude from 0.02 to 1.49 thicknesses — right points, an
    /// unresolved knee between them.
    pub amplitude: Option<AmplitudeControl>,
}

impl Default for RiksOptions {
    fn default() -> Self {
        RiksOptions {
            initial_arc_length: 0.1,
            min_arc_length: 1e-8,
            max_arc_length: 1.0,
            tolerance: 1e-10,
            max_iterations: 15,
            desired_iterations: 4,
            max_steps: 200,
            max_load: None,
            load_scale: 1.0,
            reference_load: None,
            constraint: ArcLengthConstraint::Spherical,
            amplitude: None,
        }
    }
}

impl RiksOptions {
    /// Checks the settings; the error says which one is wrong.
    pub fn validate(&self) -> Result<(), String> {
        let positive = [
            ("initial_arc_length", self.initial_arc_length),
            ("min_arc_length", self.min_arc_length),
            ("max_arc_length", self.max_arc_length),
            ("tolerance", self.tolerance),
        ];
        for (name, value) in positive {
            if !(value > 0.0 && value.is_finite()) {
                return Err(format!("{name} must be positive and finite, got {value}"));
            }
        }
        if !(self.min_arc_length <= self.initial_arc_length
            && self.initial_arc_length <= self.max_arc_length)
        {
            return Err(format!(
                "arc lengths must satisfy min <= initial <= max, got {} <= {} <= {}",
                self.min_arc_length, self.initial_arc_length, self.max_arc_length
            ));
        }
        if let Some(reference) = self.reference_load
            && !(reference != 0.0 && reference.is_finite())
        {
            return Err(format!(
                "reference_load must be non-zero and finite, got {reference}"
            ));
        }
        if let Some(amplitude) = &self.amplitude
            && !(amplitude.max_change > 0.0 && amplitude.max_change.is_finite())
        {
            return Err(format!(
                "amplitude.max_change must be positive and finite, got {}",
                amplitude.max_change
            ));
        }
        if self.max_iterations == 0 {
            return Err("max_iterations must be at least 1".into());
        }
        if self.desired_iterations == 0 {
            return Err("desired_iterations must be at least 1".into());
        }
        if !(self.load_scale >= 0.0 && self.load_scale.is_finite()) {
            return Err(format!(
                "load_scale must be non-negative and finite, got {}",
                self.load_scale
            ));
        }
        if let Some(max_load) = self.max_load
            && max_load.is_nan()
        {
            return Err("max_load must not be NaN".into());
        }
        Ok(())
    }
}

impl RiksOptions {
    /// The settings of the arc-length corrector of each step: the tolerance, iteration cap,
    /// load weight $`\psi`$ and constraint. Also the corrector of `wrinkle run`'s landing.
    pub fn corrector(&self) -> ArcCorrectorOptions {
        ArcCorrectorOptions {
            tolerance: self.tolerance,
            max_iterations: self.max_iterations,
            load_scale: self.load_scale,
            constraint: self.constraint,
        }
    }
}

/// Traces $`R(U, \lambda) = 0`$ from `start` with Newton–Riks (see the [module](self) for the
/// method).
///
/// Every accepted point, starting with `start` itself (step 0), is reported to `observer` with
/// `interior = false`; returning [`PathControl::Stop`] ends the path with [`PathStop::Observer`].
/// The path also ends at [`RiksOptions::max_load`], after [`RiksOptions::max_steps`] steps, or
/// with [`PathStop::Failed`] carrying a [`SolveError`] that says at which load and why (no
/// convergence, singular tangent, NaN, invalid options) — every point before the failure was
/// reported and the last one is [`PathResult::last`].
///
/// `factor` must have been analysed for the problem's tangent pattern. Counters:
/// `factorizations`, `tangent_assemblies`, `residual_assemblies` (the residual, its scale and
/// the dual-number $`\partial R/\partial\lambda`$ each count one), `corrections` (Newton
/// iterations), `rejected_steps`; timings of assembly and factorisation and the total.
pub fn follow_path_riks<M: EnergyModel>(
    problem: &Problem<M>,
    start: PathState,
    factor: &mut SparseFactorization,
    options: &RiksOptions,
    observer: &mut dyn FnMut(&PathEvent) -> PathControl,
) -> PathResult {
    let clock = Instant::now();
    let mut linearization = Linearization::new(problem, factor);
    let (stop, last) = trace(&mut linearization, start, options, observer);
    let factor_nonzeros = linearization.factor().factor_nnz();
    let mut statistics = linearization.statistics;
    statistics.total_seconds = clock.elapsed().as_secs_f64();
    statistics.factor_nonzeros = Some(factor_nonzeros);
    PathResult {
        last,
        statistics,
        stop,
        bifurcation: None,
        warnings: Vec::new(),
    }
}

/// A failure of the path at `load`.
fn failed(load: f64, message: String) -> PathStop {
    PathStop::Failed(SolveError::Path { load, message })
}

/// The path: checks and reports the start, sets up the arc-length metric, then steps until a
/// stop; returns why it ended and the last accepted point.
fn trace<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    start: PathState,
    options: &RiksOptions,
    observer: &mut dyn FnMut(&PathEvent) -> PathControl,
) -> (PathStop, PathState) {
    if let Err(stop) = check_start(linearization.problem().free_count(), &start, options) {
        return (stop, start);
    }
    let (_, start_residual) = linearization.residual(&start.displacement, start.load);
    if !start_residual.is_finite() {
        let location = format!(
            "the residual at the start point of the Newton–Riks path (load {:.6e})",
            start.load
        );
        return (PathStop::Failed(SolveError::NonFinite { location }), start);
    }
    let event = PathEvent {
        step: 0,
        interior: false,
        state: &start,
        relative_residual: start_residual,
        predicted_bifurcation: None,
        on_step: None,
    };
    if observer(&event) == PathControl::Stop {
        return (PathStop::Observer, start);
    }
    if let Some(max_load) = options.max_load
        && start.load >= max_load
    {
        return (PathStop::MaxLoad, start);
    }
    let metric = match ArcMetric::at_start(linearization, &start, options) {
        Ok(metric) => metric,
        Err(stop) => return (stop, start),
    };
    let path = RiksPath {
        arc_length: metric.options.initial_arc_length,
        options: metric.options,
        linearization,
        current: start,
        previous: None,
        start_factorized: metric.start_factorized,
        start_tangent: metric.start_tangent,
    };
    path.run(observer)
}

/// The options and start point checked before any work: an invalid option, a start point of
/// the wrong size or with non-finite values, or a monitored dof out of range.
fn check_start(
    free_count: usize,
    start: &PathState,
    options: &RiksOptions,
) -> Result<(), PathStop> {
    if let Err(message) = options.validate() {
        return Err(failed(
            start.load,
            format!("Newton–Riks: invalid option: {message}"),
        ));
    }
    if start.displacement.len() != free_count {
        let message = format!(
            "Newton–Riks: the start point has {} displacement values, the problem has {free_count} \
             free dofs",
            start.displacement.len()
        );
        return Err(failed(start.load, message));
    }
    if let Some(dof) = options
        .amplitude
        .iter()
        .flat_map(|a| &a.dofs)
        .find(|&&dof| dof >= free_count)
    {
        let message = format!(
            "Newton–Riks: invalid option: amplitude dof {dof} out of range ({free_count} free \
             dofs)"
        );
        return Err(failed(start.load, message));
    }
    if !start.load.is_finite() || start.displacement.iter().any(|u| !u.is_finite()) {
        let location = "the start point of the Newton–Riks path".to_string();
        return Err(PathStop::Failed(SolveError::NonFinite { location }));
    }
    Ok(())
}

/// The arc-length metric of a path: the options in the units the steps take (the
/// dimensionless arc length of [`RiksOptions::reference_load`] turned into displacement
/// units), and what computing it left at the start.
struct ArcMetric<'o> {
    options: Cow<'o, RiksOptions>,
    /// The tangent at the start is factorised already.
    start_factorized: bool,
    /// The load tangent at the start, when the scale solved for it.
    start_tangent: Option<Vec<f64>>,
}

impl<'o> ArcMetric<'o> {
    /// Without a reference load, `options` as they are; with one, the scale
    /// $`s = |\lambda_\text{ref}|\,\|\delta U_F\|`$ from the tangent at the start, which
    /// multiplies the three arc lengths and sets $`\psi = s/|\lambda_\text{ref}|`$.
    fn at_start<M: EnergyModel>(
        linearization: &mut Linearization<'_, M>,
        start: &PathState,
        options: &'o RiksOptions,
    ) -> Result<Self, PathStop> {
        let Some(reference) = options.reference_load else {
            return Ok(ArcMetric {
                options: Cow::Borrowed(options),
                start_factorized: false,
                start_tangent: None,
            });
        };
        let response = linearization
            .factorize(&start.displacement, start.load)
            .and_then(|()| linearization.load_tangent(&start.displacement, start.load));
        let tangent = response.map_err(|source| {
            let context = format!(
                "Newton–Riks at load {:.6e}: singular tangent at the start point (no \
                 arc-length scale)",
                start.load
            );
            PathStop::Failed(SolveError::Linear { context, source })
        })?;
        let scale = reference.abs() * norm(&tangent);
        if !(scale > 0.0 && scale.is_finite()) {
            let message = format!(
                "Newton–Riks: the linear response to the reference load {reference:e} has \
                 norm {scale:e}; the dimensionless arc length needs a load that moves the \
                 displacements"
            );
            return Err(failed(start.load, message));
        }
        Ok(ArcMetric {
            options: Cow::Owned(RiksOptions {
                initial_arc_length: options.initial_arc_length * scale,
                min_arc_length: options.min_arc_length * scale,
                max_arc_length: options.max_arc_length * scale,
                load_scale: scale / reference.abs(),
                reference_load: None,
                ..options.clone()
            }),
            start_factorized: true,
            start_tangent: Some(tangent),
        })
    }
}

/// The state of a Newton–Riks path between steps.
struct RiksPath<'p, 'a, 'o, M: EnergyModel> {
    linearization: &'p mut Linearization<'a, M>,
    /// The options in the units of the steps ([`ArcMetric`]).
    options: Cow<'o, RiksOptions>,
    /// The last accepted point.
    current: PathState,
    /// The arc length of the next step attempt.
    arc_length: f64,
    /// Increment $`(\Delta U, \Delta\lambda)`$ of the last accepted step.
    previous: Option<(Vec<f64>, f64)>,
    /// Whether the factorisation in hand is the tangent at `current` (the start's, or the
    /// previous step's end check), so that the step does not factorise it again.
    start_factorized: bool,
    /// The load tangent at the start when the arc-length scale has solved for it already.
    start_tangent: Option<Vec<f64>>,
}

/// A step's unit predictor direction in the arc-length metric.
struct Predictor {
    direction: Vec<f64>,
    load_direction: f64,
    /// Negative pivots of the tangent at the step's start, for the crossing guard.
    start_pivots: Option<usize>,
}

/// What the amplitude control makes of a converged step end.
enum AmplitudeVerdict {
    /// The monitored dofs changed too much: redo the step with the shortened arc length.
    Redo,
    /// Keep the end; the largest change of the monitored dofs and its bound (`None` without
    /// amplitude control).
    Keep(Option<(f64, f64)>),
}

/// A step's converged end, with the largest change of the monitored dofs and its bound.
struct AcceptedStep {
    corrected: ArcCorrection,
    amplitude_change: Option<(f64, f64)>,
}

impl<M: EnergyModel> RiksPath<'_, '_, '_, M> {
    /// Steps until a stop: predictor, converged step, arc-length adaptation, report.
    fn run(mut self, observer: &mut dyn FnMut(&PathEvent) -> PathControl) -> (PathStop, PathState) {
        let mut step = 0;
        loop {
            if step == self.options.max_steps {
                return (PathStop::MaxSteps, self.current);
            }
            step += 1;
            let accepted = match self
                .predictor(step)
                .and_then(|predictor| self.converge(step, &predictor))
            {
                Ok(accepted) => accepted,
                Err(stop) => return (stop, self.current),
            };
            let relative_residual = accepted.corrected.relative_residual;
            self.accept(accepted);
            let event = PathEvent {
                step,
                interior: false,
                state: &self.current,
                relative_residual,
                predicted_bifurcation: None,
                on_step: None,
            };
            if observer(&event) == PathControl::Stop {
                return (PathStop::Observer, self.current);
            }
            if let Some(max_load) = self.options.max_load
                && self.current.load >= max_load
            {
                return (PathStop::MaxLoad, self.current);
            }
        }
    }

    /// The unit predictor at the current point: the load tangent oriented along the previous
    /// increment, or that increment (secant) when the tangent cannot be factorised.
    fn predictor(&mut self, step: usize) -> Result<Predictor, PathStop> {
        let linearization = &mut *self.linearization;
        let current = &self.current;
        let factorized = if std::mem::take(&mut self.start_factorized) {
            Ok(())
        } else {
            linearization.factorize(&current.displacement, current.load)
        };
        let start_pivots = factorized
            .as_ref()
            .ok()
            .and_then(|()| linearization.negative_pivots());
        let tangent = match self.start_tangent.take() {
            Some(tangent) => Ok(tangent),
            None => factorized
                .and_then(|()| linearization.load_tangent(&current.displacement, current.load)),
        };
        let load_scale = self.options.load_scale;
        let (mut direction, mut load_direction) = match (tangent, &self.previous) {
            (Ok(mut displacement_tangent), _) => {
                let sign = self
                    .previous
                    .as_ref()
                    .map_or(1.0, |(increment, load_increment)| {
                        orientation(
                            increment,
                            *load_increment,
                            &displacement_tangent,
                            load_scale,
                        )
                    });
                for value in displacement_tangent.iter_mut() {
                    *value *= sign;
                }
                (displacement_tangent, sign)
            }
            // No tangent at this point: continue along the previous increment (secant).
            (Err(_), Some((increment, load_increment))) => (increment.clone(), *load_increment),
            (Err(source), None) => {
                let context = format!(
                    "Newton–Riks at load {:.6e}: singular tangent at the start point (no \
                     predictor)",
                    current.load
                );
                return Err(PathStop::Failed(SolveError::Linear { context, source }));
            }
        };
        let length = arc_dot(
            &direction,
            load_direction,
            &direction,
            load_direction,
            load_scale,
        )
        .sqrt();
        if !(length > 0.0 && length.is_finite()) {
            let message = format!(
                "Newton–Riks step {step}: degenerate predictor (arc-length norm {length:.3e}); \
                 with load_scale = 0 the load must move the displacements"
            );
            return Err(failed(current.load, message));
        }
        for value in direction.iter_mut() {
            *value /= length;
        }
        load_direction /= length;
        Ok(Predictor {
            direction,
            load_direction,
            start_pivots,
        })
    }

    /// Corrects the step along `predictor` until its end is kept: a failed correction is
    /// retried with half the arc length (the path fails below the minimum), an end that
    /// changes the monitored dofs too much is redone shorter, one that jumped over a
    /// bifurcation is redone with half the arc length.
    fn converge(&mut self, step: usize, predictor: &Predictor) -> Result<AcceptedStep, PathStop> {
        let corrector = self.options.corrector();
        let min_arc_length = self.options.min_arc_length;
        let mut halvings = 0;
        let mut shrinks = 0;
        loop {
            let attempt = correct(
                self.linearization,
                &self.current,
                &predictor.direction,
                predictor.load_direction,
                self.arc_length,
                &corrector,
            );
            let corrected = match attempt {
                Ok(corrected) => corrected,
                Err(failure) => {
                    self.linearization.statistics.rejected_steps += 1;
                    self.arc_length *= 0.5;
                    if self.arc_length < min_arc_length {
                        let message = format!(
                            "Newton–Riks step {step}: {}; arc length reduced to {:.3e}, \
                             below the minimum {min_arc_length:.3e}",
                            failure.describe(corrector.tolerance),
                            self.arc_length,
                        );
                        return Err(failed(self.current.load, message));
                    }
                    continue;
                }
            };
            let amplitude_change = match self.amplitude_check(&corrected.state, &mut shrinks) {
                AmplitudeVerdict::Redo => continue,
                AmplitudeVerdict::Keep(change) => change,
            };
            // The end's tangent is the next step's: factorising it here costs nothing when
            // the end is kept, and its inertia tells whether the step crossed a critical
            // point (see `MAX_CROSSING_HALVINGS`).
            let (crossed, end_factorized) = self.end_check(&corrected.state, predictor);
            if crossed
                && halvings < MAX_CROSSING_HALVINGS
                && 0.5 * self.arc_length >= min_arc_length
            {
                halvings += 1;
                self.linearization.statistics.rejected_steps += 1;
                self.arc_length *= 0.5;
                continue;
            }
            self.start_factorized = end_factorized;
            return Ok(AcceptedStep {
                corrected,
                amplitude_change,
            });
        }
    }

    /// The amplitude control of a converged end ([`RiksOptions::amplitude`]): redo the step
    /// (the arc length is shortened), or keep it.
    fn amplitude_check(&mut self, end: &PathState, shrinks: &mut usize) -> AmplitudeVerdict {
        let Some(control) = &self.options.amplitude else {
            return AmplitudeVerdict::Keep(None);
        };
        let change = largest_change(&control.dofs, &self.current, end);
        let shorter = self.arc_length * (AMPLITUDE_TARGET * control.max_change / change).max(0.1);
        if change > control.max_change
            && *shrinks < MAX_AMPLITUDE_SHRINKS
            && shorter >= self.options.min_arc_length
        {
            *shrinks += 1;
            self.linearization.statistics.rejected_steps += 1;
            self.arc_length = shorter;
            return AmplitudeVerdict::Redo;
        }
        AmplitudeVerdict::Keep(Some((change, control.max_change)))
    }

    /// Factorises the tangent at a converged `end` and tells whether the step crossed a
    /// bifurcation: negative pivots after a stable start, with the load still moving the way
    /// of the predictor (a failed factorisation counts as a crossing). Returns that and
    /// whether the factorisation succeeded.
    fn end_check(&mut self, end: &PathState, predictor: &Predictor) -> (bool, bool) {
        let linearization = &mut *self.linearization;
        let factorized = linearization.factorize(&end.displacement, end.load);
        let crossed = predictor.start_pivots == Some(0)
            && match (&factorized, linearization.negative_pivots()) {
                (Err(_), _) => true,
                (Ok(()), Some(after)) => {
                    after > 0
                        && load_keeps_its_direction(
                            linearization,
                            &self.current,
                            end,
                            predictor.load_direction,
                            self.options.load_scale,
                        )
                }
                (Ok(()), None) => false,
            };
        (crossed, factorized.is_ok())
    }

    /// Moves to the accepted end and adapts the arc length:
    /// $`\ell \leftarrow \ell\sqrt{n_\text{desired}/n_\text{used}}`$, capped by the amplitude
    /// control, clamped to $`[\ell_\text{min}, \ell_\text{max}]`$.
    fn accept(&mut self, accepted: AcceptedStep) {
        let AcceptedStep {
            corrected,
            amplitude_change,
        } = accepted;
        self.previous = Some(increment(&self.current, &corrected.state));
        self.current = corrected.state;
        self.linearization.statistics.steps += 1;
        let arc_length = self.arc_length;
        let factor =
            (self.options.desired_iterations as f64 / corrected.iterations.max(1) as f64).sqrt();
        let mut next = arc_length * factor;
        if let Some((change, max_change)) = amplitude_change
            && change > 0.0
        {
            next = next.min(arc_length * AMPLITUDE_TARGET * max_change / change);
        }
        self.arc_length = next.clamp(self.options.min_arc_length, self.options.max_arc_length);
    }
}

/// Whether the path tangent at `end`, oriented along the step's increment from `start`, still
/// moves the load in the sense of the step's predictor (`load_direction`), with the tangent at
/// `end` factorised. A critical point crossed with the load still moving the same way is a
/// bifurcation jumped over; at a limit point the load turns back. A singular solve counts as
/// a jump.
fn load_keeps_its_direction<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    start: &PathState,
    end: &PathState,
    load_direction: f64,
    load_scale: f64,
) -> bool {
    let Ok(tangent) = linearization.load_tangent(&end.displacement, end.load) else {
        return true;
    };
    let (step, load_step) = increment(start, end);
    // The oriented tangent is ±(δU_F, 1): its load component is the orientation's sign.
    orientation(&step, load_step, &tangent, load_scale) == load_direction.signum()
}

/// $`\max_i |U_i(\text{to}) - U_i(\text{from})|`$ over `dofs`.
fn largest_change(dofs: &[usize], from: &PathState, to: &PathState) -> f64 {
    dofs.iter()
        .map(|&i| (to.displacement[i] - from.displacement[i]).abs())
        .fold(0.0, f64::max)
}
