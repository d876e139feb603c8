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
//! * **Corrector**: full Newton on the bordered system
//!   $$`\begin{pmatrix} K_t & \partial_\lambda R \\ 2\Delta U^\top & 2\psi^2\Delta\lambda\end{pmatrix}
//!   \begin{pmatrix}\delta U\\ \delta\lambda\end{pmatrix} = -\begin{pmatrix} R \\ g\end{pmatrix},
//!   \qquad g = \|\Delta U\|^2 + \psi^2\Delta\lambda^2 - \ell^2,`$$
//!   solved by the two-solve (Batoz–Dhatt) trick with the factorised $`K_t`$ only:
//!   $`\delta U = \delta U_R + \delta\lambda\,\delta U_F`$ with $`K_t\,\delta U_R = -R`$ and
//!   $`K_t\,\delta U_F = -\partial_\lambda R`$, and $`\delta\lambda`$ from the linearised constraint
//!   ([`ArcLengthConstraint::Linearized`]) or from the exact sphere
//!   ([`ArcLengthConstraint::Spherical`], Crisfield: the root closest in angle to the current
//!   increment). The tangent is reassembled and refactorised every iteration.
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

use std::time::Instant;

use super::error::SolveError;
use super::path::{PathControl, PathEvent, PathResult, PathState, PathStatistics, PathStop};
use crate::linear::LinearError;
use crate::linear::factor::SparseFactorization;
use crate::linear::pattern::SparseMatrix;
use crate::linear::vector::dot;
use crate::model::EnergyModel;
use crate::problem::Problem;

/// Which arc-length equation the corrector enforces.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ArcLengthConstraint {
    /// Newton on the constraint: $`\delta\lambda`$ from its linearisation at the current
    /// iterate (Riks–Wempner). Always solvable unless the bordered system is singular; the
    /// converged point lies on the sphere.
    Linearized,
    /// Crisfield's spherical constraint: $`\delta\lambda`$ solves the quadratic
    /// $`\|\Delta U + \delta U_R + \delta\lambda\,\delta U_F\|^2 + \psi^2(\Delta\lambda + \delta\lambda)^2 = \ell^2`$
    /// exactly (a step without real root is rejected).
    Spherical,
}

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

/// Why one step attempt failed.
enum StepFailure {
    /// The corrector did not reach the tolerance.
    NoConvergence { iterations: usize, residual: f64 },
    /// The tangent could not be factorised (or solved with).
    Singular {
        load: f64,
        iteration: usize,
        source: LinearError,
    },
    /// NaN or infinity appeared.
    NonFinite { location: String },
    /// The spherical constraint has no real root, or the bordered system is singular.
    Constraint { message: String },
}

impl StepFailure {
    fn describe(&self, tolerance: f64) -> String {
        match self {
            StepFailure::NoConvergence {
                iterations,
                residual,
            } => format!(
                "no convergence after {iterations} iterations (relative residual {residual:.3e}, \
                 tolerance {tolerance:.1e})"
            ),
            StepFailure::Singular {
                load,
                iteration,
                source,
            } => format!("singular tangent at load {load:.6e}, iteration {iteration}: {source}"),
            StepFailure::NonFinite { location } => {
                format!("non-finite values (NaN or infinity) in {location}")
            }
            StepFailure::Constraint { message } => message.clone(),
        }
    }
}

/// Arc-length norm squared $`\|a\|^2 + \psi^2 b^2`$ style inner product.
fn arc_dot(u: &[f64], load_u: f64, v: &[f64], load_v: f64, load_scale: f64) -> f64 {
    dot(u, v) + load_scale * load_scale * load_u * load_v
}

/// Tangent assembly + factorisation + solves, with the work counters.
struct Linearization<'a, M: EnergyModel> {
    problem: &'a Problem<M>,
    factor: &'a mut SparseFactorization,
    matrix: SparseMatrix,
    statistics: PathStatistics,
}

impl<M: EnergyModel> Linearization<'_, M> {
    /// Assembles and factorises $`K_t(U, \lambda)`$.
    fn factorize(&mut self, displacement: &[f64], load: f64) -> Result<(), LinearError> {
        let clock = Instant::now();
        self.problem
            .tangent_into(displacement, load, &mut self.matrix);
        self.statistics.tangent_assemblies += 1;
        self.statistics.assembly_seconds += clock.elapsed().as_secs_f64();
        let clock = Instant::now();
        let result = self.factor.factorize(&self.matrix);
        self.statistics.factorizations += 1;
        self.statistics.factorization_seconds += clock.elapsed().as_secs_f64();
        result.map(|_| ())
    }

    /// $`\delta U_F = -K_t^{-1}\,\partial R/\partial\lambda`$ with the current factorisation.
    fn load_tangent(&mut self, displacement: &[f64], load: f64) -> Result<Vec<f64>, LinearError> {
        let mut derivative = self.problem.load_derivative(displacement, load);
        self.statistics.residual_assemblies += 1;
        for value in derivative.iter_mut() {
            *value = -*value;
        }
        self.factor.solve_in_place(&mut derivative)?;
        Ok(derivative)
    }

    /// $`(R, \|R\|/\text{scale})`$ at a point.
    fn residual(&mut self, displacement: &[f64], load: f64) -> (Vec<f64>, f64) {
        let problem = self.problem;
        self.statistics
            .time_residual(|| problem.residual_with_relative(displacement, load))
    }
}

/// A converged step.
struct Corrected {
    state: PathState,
    iterations: usize,
    relative_residual: f64,
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
    let mut linearization = Linearization {
        problem,
        factor,
        matrix: problem.new_matrix(),
        statistics: PathStatistics::default(),
    };
    let (stop, last) = trace(&mut linearization, start, options, observer);
    let mut statistics = linearization.statistics;
    statistics.total_seconds = clock.elapsed().as_secs_f64();
    statistics.factor_nonzeros = Some(linearization.factor.factor_nnz());
    PathResult {
        last,
        statistics,
        stop,
        bifurcation: None,
        warnings: Vec::new(),
    }
}

/// The path loop; returns why it ended and the last accepted point.
fn trace<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    start: PathState,
    options: &RiksOptions,
    observer: &mut dyn FnMut(&PathEvent) -> PathControl,
) -> (PathStop, PathState) {
    let failed = |load: f64, message: String| PathStop::Failed(SolveError::Path { load, message });
    if let Err(message) = options.validate() {
        let load = start.load;
        return (
            failed(load, format!("Newton–Riks: invalid option: {message}")),
            start,
        );
    }
    let free_count = linearization.problem.free_count();
    if start.displacement.len() != free_count {
        let message = format!(
            "Newton–Riks: the start point has {} displacement values, the problem has {free_count} \
             free dofs",
            start.displacement.len()
        );
        return (failed(start.load, message), start);
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
        return (failed(start.load, message), start);
    }
    if !start.load.is_finite() || start.displacement.iter().any(|u| !u.is_finite()) {
        let location = "the start point of the Newton–Riks path".to_string();
        return (PathStop::Failed(SolveError::NonFinite { location }), start);
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
    };
    if observer(&event) == PathControl::Stop {
        return (PathStop::Observer, start);
    }
    if let Some(max_load) = options.max_load
        && start.load >= max_load
    {
        return (PathStop::MaxLoad, start);
    }

    // Whether the factorisation in hand is the tangent at `current` (the start's, or the
    // previous step's end check), so that the step does not factorise it again.
    let mut start_factorized = false;
    // The load tangent at the start when the arc-length scale has solved for it already.
    let mut start_tangent = None;
    let normalized;
    let options = match options.reference_load {
        None => options,
        Some(reference) => {
            let response = linearization
                .factorize(&start.displacement, start.load)
                .and_then(|()| linearization.load_tangent(&start.displacement, start.load));
            let scale = match response {
                Ok(tangent) => {
                    let scale = reference.abs() * dot(&tangent, &tangent).sqrt();
                    start_tangent = Some(tangent);
                    scale
                }
                Err(source) => {
                    let context = format!(
                        "Newton–Riks at load {:.6e}: singular tangent at the start point (no \
                         arc-length scale)",
                        start.load
                    );
                    return (
                        PathStop::Failed(SolveError::Linear { context, source }),
                        start,
                    );
                }
            };
            if !(scale > 0.0 && scale.is_finite()) {
                let message = format!(
                    "Newton–Riks: the linear response to the reference load {reference:e} has \
                     norm {scale:e}; the dimensionless arc length needs a load that moves the \
                     displacements"
                );
                return (failed(start.load, message), start);
            }
            start_factorized = true;
            normalized = RiksOptions {
                initial_arc_length: options.initial_arc_length * scale,
                min_arc_length: options.min_arc_length * scale,
                max_arc_length: options.max_arc_length * scale,
                load_scale: scale / reference.abs(),
                reference_load: None,
                ..options.clone()
            };
            &normalized
        }
    };
    let load_scale = options.load_scale;
    let mut current = start;
    let mut arc_length = options.initial_arc_length;
    // Increment (ΔU, Δλ) of the last accepted step.
    let mut previous: Option<(Vec<f64>, f64)> = None;
    let mut step = 0;
    loop {
        if step == options.max_steps {
            return (PathStop::MaxSteps, current);
        }
        step += 1;
        // Unit predictor direction (in the arc-length metric).
        let factorized = if std::mem::take(&mut start_factorized) {
            Ok(())
        } else {
            linearization.factorize(&current.displacement, current.load)
        };
        // Negative pivots of the start's tangent, for the crossing guard.
        let start_pivots = factorized
            .as_ref()
            .ok()
            .and_then(|()| linearization.factor.negative_pivots());
        let tangent = match start_tangent.take() {
            Some(tangent) => Ok(tangent),
            None => factorized
                .and_then(|()| linearization.load_tangent(&current.displacement, current.load)),
        };
        let (mut direction, mut load_direction) = match (tangent, &previous) {
            (Ok(mut displacement_tangent), _) => {
                let sign = previous
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
                return (
                    PathStop::Failed(SolveError::Linear { context, source }),
                    current,
                );
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
            return (failed(current.load, message), current);
        }
        for value in direction.iter_mut() {
            *value /= length;
        }
        load_direction /= length;

        let mut halvings = 0;
        let mut shrinks = 0;
        // Largest change of the monitored dofs over the accepted step.
        let mut amplitude_change = None;
        let corrected = loop {
            match correct(
                linearization,
                &current,
                &direction,
                load_direction,
                arc_length,
                options,
            ) {
                Ok(corrected) => {
                    if let Some(control) = &options.amplitude {
                        let change = largest_change(&control.dofs, &current, &corrected.state);
                        let shorter =
                            arc_length * (AMPLITUDE_TARGET * control.max_change / change).max(0.1);
                        if change > control.max_change
                            && shrinks < MAX_AMPLITUDE_SHRINKS
                            && shorter >= options.min_arc_length
                        {
                            shrinks += 1;
                            linearization.statistics.rejected_steps += 1;
                            arc_length = shorter;
                            continue;
                        }
                        amplitude_change = Some((change, control.max_change));
                    }
                    // The end's tangent is the next step's: factorising it here costs nothing
                    // when the end is kept, and its inertia tells whether the step crossed a
                    // critical point (see `MAX_CROSSING_HALVINGS`).
                    let end = &corrected.state;
                    let factorized = linearization.factorize(&end.displacement, end.load);
                    let crossed = start_pivots == Some(0)
                        && match (&factorized, linearization.factor.negative_pivots()) {
                            (Err(_), _) => true,
                            (Ok(()), Some(after)) => {
                                after > 0
                                    && load_keeps_its_direction(
                                        linearization,
                                        &current,
                                        end,
                                        load_direction,
                                        load_scale,
                                    )
                            }
                            (Ok(()), None) => false,
                        };
                    if crossed
                        && halvings < MAX_CROSSING_HALVINGS
                        && 0.5 * arc_length >= options.min_arc_length
                    {
                        halvings += 1;
                        linearization.statistics.rejected_steps += 1;
                        arc_length *= 0.5;
                        continue;
                    }
                    start_factorized = factorized.is_ok();
                    break corrected;
                }
                Err(failure) => {
                    linearization.statistics.rejected_steps += 1;
                    arc_length *= 0.5;
                    if arc_length < options.min_arc_length {
                        let message = format!(
                            "Newton–Riks step {step}: {}; arc length reduced to {arc_length:.3e}, \
                             below the minimum {:.3e}",
                            failure.describe(options.tolerance),
                            options.min_arc_length
                        );
                        return (failed(current.load, message), current);
                    }
                }
            }
        };

        previous = Some(increment(&current, &corrected.state));
        current = corrected.state;
        linearization.statistics.steps += 1;
        let factor =
            (options.desired_iterations as f64 / corrected.iterations.max(1) as f64).sqrt();
        let mut next = arc_length * factor;
        if let Some((change, max_change)) = amplitude_change
            && change > 0.0
        {
            next = next.min(arc_length * AMPLITUDE_TARGET * max_change / change);
        }
        arc_length = next.clamp(options.min_arc_length, options.max_arc_length);

        let event = PathEvent {
            step,
            interior: false,
            state: &current,
            relative_residual: corrected.relative_residual,
            predicted_bifurcation: None,
        };
        if observer(&event) == PathControl::Stop {
            return (PathStop::Observer, current);
        }
        if let Some(max_load) = options.max_load
            && current.load >= max_load
        {
            return (PathStop::MaxLoad, current);
        }
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

/// The increment $`(\Delta U, \Delta\lambda)`$ from `from` to `to`.
fn increment(from: &PathState, to: &PathState) -> (Vec<f64>, f64) {
    let displacement = to
        .displacement
        .iter()
        .zip(&from.displacement)
        .map(|(new, old)| new - old)
        .collect();
    (displacement, to.load - from.load)
}

/// $`\pm 1`$: the sign that orients the path tangent $`(\delta U_F, 1)`$ along the increment
/// $`(\Delta U, \Delta\lambda)`$ in the arc-length metric (+1 when they are orthogonal).
fn orientation(increment: &[f64], load_increment: f64, tangent: &[f64], load_scale: f64) -> f64 {
    if arc_dot(increment, load_increment, tangent, 1.0, load_scale) < 0.0 {
        -1.0
    } else {
        1.0
    }
}

/// One step attempt: predictor of length `arc_length` along the unit direction
/// `(direction, load_direction)`, then full Newton on the bordered system.
fn correct<M: EnergyModel>(
    linearization: &mut Linearization<'_, M>,
    origin: &PathState,
    direction: &[f64],
    load_direction: f64,
    arc_length: f64,
    options: &RiksOptions,
) -> Result<Corrected, StepFailure> {
    let load_scale = options.load_scale;
    let weight = load_scale * load_scale;
    let mut increment: Vec<f64> = direction.iter().map(|d| arc_length * d).collect();
    let mut load_increment = arc_length * load_direction;
    let mut displacement: Vec<f64> = origin
        .displacement
        .iter()
        .zip(&increment)
        .map(|(u, d)| u + d)
        .collect();
    let mut load = origin.load + load_increment;
    let mut iterations = 0;
    loop {
        let (mut residual, relative) = linearization.residual(&displacement, load);
        if !relative.is_finite() {
            return Err(StepFailure::NonFinite {
                location: format!("the residual at load {load:.6e}, iteration {iterations}"),
            });
        }
        if relative <= options.tolerance {
            return Ok(Corrected {
                state: PathState { displacement, load },
                iterations,
                relative_residual: relative,
            });
        }
        if iterations == options.max_iterations {
            return Err(StepFailure::NoConvergence {
                iterations,
                residual: relative,
            });
        }
        let singular = |source| StepFailure::Singular {
            load,
            iteration: iterations,
            source,
        };
        linearization
            .factorize(&displacement, load)
            .map_err(singular)?;
        for value in residual.iter_mut() {
            *value = -*value;
        }
        linearization
            .factor
            .solve_in_place(&mut residual)
            .map_err(singular)?;
        let residual_correction = residual;
        let load_correction_direction = linearization
            .load_tangent(&displacement, load)
            .map_err(singular)?;

        let load_correction = match options.constraint {
            ArcLengthConstraint::Linearized => {
                let mismatch = arc_dot(
                    &increment,
                    load_increment,
                    &increment,
                    load_increment,
                    load_scale,
                ) - arc_length * arc_length;
                let numerator = -0.5 * mismatch - dot(&increment, &residual_correction);
                let denominator =
                    dot(&increment, &load_correction_direction) + weight * load_increment;
                let correction = numerator / denominator;
                if !correction.is_finite() {
                    return Err(StepFailure::Constraint {
                        message: format!(
                            "singular bordered system at load {load:.6e} (constraint row \
                             {denominator:.3e} against the load tangent)"
                        ),
                    });
                }
                correction
            }
            ArcLengthConstraint::Spherical => {
                let shifted: Vec<f64> = increment
                    .iter()
                    .zip(&residual_correction)
                    .map(|(a, b)| a + b)
                    .collect();
                let a = dot(&load_correction_direction, &load_correction_direction) + weight;
                let b = 2.0 * (dot(&shifted, &load_correction_direction) + weight * load_increment);
                let c = dot(&shifted, &shifted) + weight * load_increment * load_increment
                    - arc_length * arc_length;
                spherical_root(
                    a,
                    b,
                    c,
                    &increment,
                    load_increment,
                    &shifted,
                    &load_correction_direction,
                    load_scale,
                )
                .map_err(|message| StepFailure::Constraint {
                    message: format!("{message} at load {load:.6e}, iteration {iterations}"),
                })?
            }
        };
        for ((u, delta), (r, f)) in displacement
            .iter_mut()
            .zip(increment.iter_mut())
            .zip(residual_correction.iter().zip(&load_correction_direction))
        {
            let change = r + load_correction * f;
            *u += change;
            *delta += change;
        }
        load += load_correction;
        load_increment += load_correction;
        iterations += 1;
        linearization.statistics.corrections += 1;
        if !load.is_finite() || displacement.iter().any(|u| !u.is_finite()) {
            return Err(StepFailure::NonFinite {
                location: format!("the corrector iterate {iterations}"),
            });
        }
    }
}

/// Root $`\delta\lambda`$ of $`a\,\delta\lambda^2 + b\,\delta\lambda + c = 0`$ whose new
/// increment $`(s + \delta\lambda f, \Delta\lambda + \delta\lambda)`$ makes the smallest angle
/// with the current increment $`(\Delta U, \Delta\lambda)`$ (Crisfield's choice).
#[allow(clippy::too_many_arguments)]
fn spherical_root(
    a: f64,
    b: f64,
    c: f64,
    increment: &[f64],
    load_increment: f64,
    shifted: &[f64],
    load_correction_direction: &[f64],
    load_scale: f64,
) -> Result<f64, String> {
    let discriminant = b * b - 4.0 * a * c;
    if !discriminant.is_finite() || !a.is_finite() {
        return Err("non-finite coefficients of the spherical constraint".into());
    }
    if discriminant < 0.0 {
        return Err(format!(
            "the spherical arc-length constraint has no real root (discriminant {discriminant:.3e})"
        ));
    }
    if a == 0.0 {
        // Linear constraint (no load weight and no load tangent).
        let root = -c / b;
        return if root.is_finite() {
            Ok(root)
        } else {
            Err("degenerate spherical arc-length constraint".into())
        };
    }
    // Numerically stable pair of roots.
    let q = -0.5 * (b + b.signum() * discriminant.sqrt());
    let roots = if q == 0.0 { [0.0, 0.0] } else { [q / a, c / q] };
    let alignment = |root: f64| {
        let moved: f64 = increment
            .iter()
            .zip(shifted.iter().zip(load_correction_direction))
            .map(|(d, (s, f))| d * (s + root * f))
            .sum();
        moved + load_scale * load_scale * load_increment * (load_increment + root)
    };
    let chosen = if alignment(roots[0]) >= alignment(roots[1]) {
        roots[0]
    } else {
        roots[1]
    };
    if chosen.is_finite() {
        Ok(chosen)
    } else {
        Err("degenerate spherical arc-length constraint".into())
    }
}

/// Result of [`correct_on_arc`].
#[derive(Clone, Debug)]
pub struct ArcCorrection {
    /// The corrected equilibrium point.
    pub state: PathState,
    /// Newton iterations (= tangent factorisations) used.
    pub iterations: usize,
    /// Relative residual reached.
    pub relative_residual: f64,
}

/// Riks corrector for a predicted point, e.g. the end of an ANM step: Newton on the bordered
/// system with the arc-length constraint (of radius $`\|(\Delta U, \psi\Delta\lambda)\|`$ about
/// `origin`) passing through `predicted`. Unlike Newton at fixed load it converges through limit
/// points. `options` supplies the tolerance, iteration cap, load scale $`\psi`$ and constraint;
/// the work done is added to `statistics`.
pub fn correct_on_arc<M: EnergyModel>(
    problem: &Problem<M>,
    factor: &mut SparseFactorization,
    origin: &PathState,
    predicted: &PathState,
    options: &RiksOptions,
    statistics: &mut PathStatistics,
) -> Result<ArcCorrection, SolveError> {
    let (increment, load_increment) = increment(origin, predicted);
    let arc_length = arc_dot(
        &increment,
        load_increment,
        &increment,
        load_increment,
        options.load_scale,
    )
    .sqrt();
    if !(arc_length > 0.0 && arc_length.is_finite()) {
        return Err(SolveError::Path {
            load: origin.load,
            message: format!("arc-length correction: degenerate increment (length {arc_length:e})"),
        });
    }
    let direction: Vec<f64> = increment.iter().map(|d| d / arc_length).collect();
    let mut linearization = Linearization {
        problem,
        factor,
        matrix: problem.new_matrix(),
        statistics: PathStatistics::default(),
    };
    let result = correct(
        &mut linearization,
        origin,
        &direction,
        load_increment / arc_length,
        arc_length,
        options,
    );
    let work = &linearization.statistics;
    statistics.factorizations += work.factorizations;
    statistics.tangent_assemblies += work.tangent_assemblies;
    statistics.residual_assemblies += work.residual_assemblies;
    statistics.residual_seconds += work.residual_seconds;
    statistics.assembly_seconds += work.assembly_seconds;
    statistics.factorization_seconds += work.factorization_seconds;
    match result {
        Ok(c) => Ok(ArcCorrection {
            state: c.state,
            iterations: c.iterations,
            relative_residual: c.relative_residual,
        }),
        Err(failure) => Err(SolveError::Path {
            load: predicted.load,
            message: format!(
                "arc-length correction: {}",
                failure.describe(options.tolerance)
            ),
        }),
    }
}
