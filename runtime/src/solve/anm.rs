//! Asymptotic Numerical Method (ANM): path following by truncated power series (THEORY.md §10).
//!
//! From a regular point $`(U_0,\lambda_0)`$ the branch is expanded as
//! $`U(a) = U_0 + \sum_{n=1}^N a^n U_n`$, $`\lambda(a) = \lambda_0 + \sum_{n=1}^N a^n\lambda_n`$ in
//! the path parameter $`a = \langle U - U_0, U_1\rangle + (\lambda-\lambda_0)\lambda_1`$.
//! With $`K_t = \partial R/\partial U(U_0,\lambda_0)`$ factorised **once per step** and
//! $`F = -\partial R/\partial\lambda`$:
//! * order 1: $`K_t\hat U = F`$, $`\lambda_1 = \pm(1 + \|\hat U\|^2)^{-1/2}`$, $`U_1 = \lambda_1\hat U`$;
//! * order $`n\ge2`$: $`K_t\hat U_n = F^{nl}_n`$ with $`F^{nl}_n`$ minus the $`a^n`$ coefficient of
//!   $`R(\sum_{k<n} a^kU_k, \sum_{k<n}a^k\lambda_k)`$ — obtained from the model's generated
//!   Taylor-mode kernels ([`compute_series`]: $`O(k)`$ per product at order $`k`$ from a
//!   per-point tape; the generic kernels on truncated [`Series`] are the reference,
//!   [`compute_series_generic`]); no model-specific code — then
//!   $`\lambda_n = -\lambda_1\langle\hat U_n, U_1\rangle`$ and $`U_n = \lambda_n\hat U + \hat U_n`$.
//!
//! Step length $`a_{\max} = (\epsilon\|U_1\|/\|U_N\|)^{1/(N-1)}`$ or, optionally, the Padé
//! approximants' longer range, or that of the series re-expanded in $`s = \ln(1 + a/R)`$ when
//! its last orders show a singularity behind the step at $`a = -R`$
//! ([`ExponentialMap`]). The residual is checked at the end of
//! every step; a Riks (arc-length) correction brings it back under the tolerance when needed
//! (or the step is halved).
//!
//! Each step is oriented with the path tangent at the end of the previous one.
//!
//! **The mode as path parameter** ([`AnmOptions::mode_parameter`]). Given the buckling mode
//! $`\varphi`$ the imperfection selects, a step from a stable start (no negative pivot) whose
//! load tangent has a part along it
//! ($`|\langle\hat U,\varphi\rangle| \ge`$ [`MODE_PARAMETER_COSINE`]$`\,\|\hat U\|\|\varphi\|`$)
//! is expanded in the change of the mode's amplitude instead,
//! $`a = \langle U - U_0, \varphi\rangle/\langle\varphi,\varphi\rangle`$: order 1 then has
//! $`\lambda_1 = \langle\varphi,\varphi\rangle/\langle\hat U,\varphi\rangle`$, order $`n\ge2`$
//! $`\lambda_n = -\langle\hat U_n,\varphi\rangle/\langle\hat U,\varphi\rangle`$ (the same one solve
//! an order). Through the knee of an imperfect path $`\lambda(\xi)`$ is nearly
//! $`\lambda_c(\xi + c\xi^3)/(\xi + \varepsilon)`$ in the amplitude $`\xi`$, whose only nearby
//! singularity, the pole at $`\xi = -\varepsilon`$ behind the step, is what the exponential map
//! removes; in the pseudo arc length the turn of the path adds branch points of its own.
//!
//! **Crossing guard.** The tangent at each step's end is factorised (it is the next step's
//! tangent, so this costs nothing when the end is kept). When it has more negative pivots than
//! the start's, the step crossed a critical point: near a nearly perfect bifurcation a step can
//! run along the fundamental branch past $`\lambda_c`$ onto the unstable branch of the imperfect
//! problem. Such a step is redone — with the series' own range after a Padé step, with half its
//! length after a series step from a stable start (no negative pivot), up to
//! `MAX_CROSSING_HALVINGS` times, after which the crossing is taken as the path's own and located
//! at the next step.
//!
//! Bifurcations, without an eigen-solve at every step: the factorisation of each step's tangent
//! gives its inertia (negative pivots of $`LDL^\top`$; none after $`LL^\top`$). When it changes, a
//! critical point was crossed in the previous step and is located by linear buckling about that
//! step's start along its path tangent. On a path that stays stable — the imperfect path that
//! turns smoothly onto the wrinkled branch — the first step whose series shows a geometric tail
//! (the ANM signature of a nearby singularity) predicts the bifurcation load by one such analysis
//! with its own factorised tangent, on a thread of its own beside the next step's series; the
//! bifurcation is reported at the step whose end passes it. An eigen-solver failure never stops
//! the path and is never swallowed: it is kept in [`PathResult::warnings`].

use super::arc_length::{ArcCorrectorOptions, ArcLengthConstraint, correct_on_arc};
use super::error::SolveError;
use super::landing::parameter_at_load;
use super::linearization::{
    Linearization, SpareTangent, Workspace, factorize_tangent, load_tangent,
};
use super::newton::NewtonOptions;
use super::path::{OnStep, PathControl, PathEvent, PathResult, PathState, PathStop};
use super::wavenumber::LOCAL_SHIFT;
use crate::fem::TaylorTape;
use crate::linear::eigen::{BucklingOptions, smallest_positive_buckling};
use crate::linear::factor::SparseFactorization;
use crate::linear::pattern::SparseMatrix;
use crate::linear::vector::{axpy, dot};
use crate::model::EnergyModel;
use crate::problem::Problem;
use crate::series::{
    ExponentialMap, GramSchmidt, MAX_SERIES_LEN, PadeApproximant, PathSeries, Series,
    geometric_ratio, series_step_length, singularity_behind,
};
use std::time::Instant;

/// Settings of [`follow_path_anm`].
#[derive(Clone, Debug)]
pub struct AnmOptions {
    /// Truncation order $`N`$ (2 ≤ N ≤ 40).
    pub order: usize,
    /// $`\epsilon`$ of the step-length rule.
    pub series_tolerance: f64,
    /// Largest accepted relative residual at a step end.
    pub residual_tolerance: f64,
    /// Step budget.
    pub max_steps: usize,
    /// Stop at this load (`None`: no limit).
    pub max_load: Option<f64>,
    /// Use Padé approximants (common denominator) for the step range and evaluation beyond
    /// the plain series' range (default: on). A Padé-extended step whose end gained negative
    /// pivots (it jumped over a critical point) is redone with the series' range; one whose end
    /// misses the residual tolerance is halved towards that range, not corrected.
    pub pade: bool,
    /// Re-expand the series in $`s = \ln(1 + a/R)`$ when its last orders show a singularity
    /// behind the step at $`a = -R`$ ([`ExponentialMap`], default: on): past the knee of an
    /// imperfect path, where that singularity (the imperfect bifurcation left behind) limits
    /// the series and Padé alike to a fraction of the distance travelled. The step takes the
    /// longer of this range and Padé's. An end on the map must meet a tenth of
    /// `residual_tolerance` (`MAPPED_END_RESIDUAL_FRACTION`); one that misses it is halved
    /// like a Padé end, or gives way to Padé's range once that reaches further.
    pub exponential_map: bool,
    /// Points evaluated inside each step (dense output).
    pub interior_points: usize,
    /// Iteration cap of the corrector (a Riks correction on the arc through the step's end
    /// point, to `residual_tolerance / 100`); its tolerance field is not used.
    pub corrector: NewtonOptions,
    /// Watch for bifurcations: a change of the tangent's inertia between steps is located by
    /// linear buckling about the previous step's start; on a stable (e.g. imperfect) path, the
    /// first step whose series shows a geometric tail predicts the bifurcation load by one
    /// linear buckling analysis about its start. No eigen-solve at other steps.
    pub predict_bifurcation: bool,
    /// Warm start of those eigen-solves (e.g. the critical mode of a linear buckling analysis).
    pub bifurcation_mode_guess: Option<Vec<f64>>,
    /// A guess of the bifurcation load ahead (e.g. the linear buckling threshold): the
    /// prediction's eigen-solve is then shifted towards it (see `predict_bifurcation`).
    pub bifurcation_load_guess: Option<f64>,
    /// Cap on the path parameter of one step; when the series is exactly polynomial (no
    /// finite range) the step uses this value, or 1 if it is infinite.
    pub max_step_length: f64,
    /// The mode $`\varphi`$ (free unknowns) whose amplitude parametrises the steps whose load
    /// tangent has a part along it (see the [module](self)); `None`: every step in the pseudo
    /// arc length. `wrinkle run` gives the buckling mode that shapes the imperfection.
    pub mode_parameter: Option<Vec<f64>>,
}

/// A step is parametrised by the mode's amplitude ([`AnmOptions::mode_parameter`]) when the
/// cosine between its load tangent $`\hat U`$ and the mode is at least this; else by the
/// pseudo arc length. Below it the mode's amplitude hardly moves along the path (the sheet's
/// in-plane response to the load dominates, or the path turns in the mode's amplitude) and
/// would be a poor parameter.
pub const MODE_PARAMETER_COSINE: f64 = 1e-3;

/// How a step's series is oriented and parametrised.
#[derive(Clone, Copy, Debug, Default)]
pub struct StepOrientation<'a> {
    /// The path tangent $`(dU/da, d\lambda/da)`$ at the end of the previous step, which the step
    /// continues (else $`\lambda_1 > 0`$ in the arc length).
    pub previous_direction: Option<(&'a [f64], f64)>,
    /// The mode whose amplitude is the step's parameter where the load tangent has a part
    /// along it ([`AnmOptions::mode_parameter`]); `None`: the pseudo arc length.
    pub mode: Option<&'a [f64]>,
}

/// One step's series ([`AnmRun::series`]).
struct StepSeries {
    series: PathSeries,
    /// $`\hat U = K_t^{-1}F`$.
    u_hat: Vec<f64>,
    /// The series' coefficients orthogonalised for Padé, when on.
    orthogonalized: Option<GramSchmidt>,
    /// Parametrised by the mode's amplitude ([`StepParameter::Mode`]).
    by_mode: bool,
}

/// How one step's path parameter $`a`$ is defined.
#[derive(Clone, Copy, Debug)]
enum StepParameter<'p> {
    /// $`a = \langle U - U_0, U_1\rangle + (\lambda-\lambda_0)\lambda_1`$ with
    /// $`\|U_1\|^2 + \lambda_1^2 = 1`$.
    ArcLength,
    /// $`a = \langle U - U_0, \varphi\rangle/\langle\varphi,\varphi\rangle`$, with
    /// $`\langle\hat U,\varphi\rangle`$.
    Mode { mode: &'p [f64], projection: f64 },
}

impl Default for AnmOptions {
    fn default() -> Self {
        AnmOptions {
            order: 20,
            series_tolerance: 1e-7,
            residual_tolerance: 1e-6,
            max_steps: 200,
            max_load: None,
            pade: true,
            exponential_map: true,
            interior_points: 10,
            corrector: NewtonOptions {
                tolerance: 1e-9,
                max_iterations: 12,
            },
            predict_bifurcation: true,
            bifurcation_mode_guess: None,
            bifurcation_load_guess: None,
            max_step_length: f64::INFINITY,
            mode_parameter: None,
        }
    }
}

/// The ranges the extensions of a step's series offered, and the distance of the singularity
/// behind its start the series showed ([`AnmRun::approximant`]).
#[derive(Clone, Copy, Debug)]
struct Offered {
    pade: Option<f64>,
    map: Option<f64>,
    behind: Option<f64>,
}

/// Per-step diagnostics kept by the solver.
#[derive(Clone, Debug, PartialEq)]
pub struct AnmStep {
    /// Step index.
    pub step: usize,
    /// Load at the start and end.
    pub load_range: (f64, f64),
    /// Path-parameter range used.
    pub step_length: f64,
    /// Range the plain series allowed (for comparison with Padé).
    pub series_step_length: f64,
    /// Range Padé allowed (when enabled). The step used it when `step_length` exceeds
    /// `series_step_length`; a Padé range longer than `step_length` means the Padé end missed
    /// the residual tolerance and was shortened towards the series' range, or jumped over a
    /// critical point and the step was redone with the series' range (`crossings_redone`).
    pub pade_step_length: Option<f64>,
    /// Range the exponential map offered ([`ExponentialMap`]: when enabled and the series
    /// showed a singularity behind the step, at [`AnmStep::singularity_behind`]). The step
    /// used it when it was the longest range offered and `step_length` exceeds
    /// `series_step_length`.
    pub mapped_step_length: Option<f64>,
    /// Distance of a singularity behind the step's start detected in the series' last orders
    /// ([`singularity_behind`]), if any.
    pub singularity_behind: Option<f64>,
    /// Relative residual at the accepted end point (after the correction, if any).
    pub end_residual: f64,
    /// Newton iterations of the correction (0 = none needed).
    pub correction_iterations: usize,
    /// Times the step was redone because its end had more negative pivots than its start (it
    /// jumped over a critical point): with the series' range after a Padé end, with half its
    /// length after a series end.
    pub crossings_redone: usize,
    /// Radius of convergence estimated from a geometric tail of the series, if any.
    pub geometric_radius: Option<f64>,
    /// Bifurcation load predicted by linear buckling about the step's start (only at the step
    /// where it was computed).
    pub predicted_bifurcation: Option<f64>,
    /// Negative eigenvalues of the tangent at the step's start (`None` when the factorisation
    /// gives no inertia, i.e. after LU).
    pub negative_pivots: Option<usize>,
    /// `false` for a last step the stop criterion ended at one of its interior points: its
    /// `load_range` ends there, and `steps` of the path statistics counts it.
    pub completed: bool,
    /// The step's path parameter (and its lengths above) is the mode's amplitude
    /// ([`AnmOptions::mode_parameter`]); `false`: the pseudo arc length.
    pub mode_parameter: bool,
}

/// Order 1 of a step: $`\hat U = K_t^{-1}F`$, and $`\lambda_1 = \pm(1+\|\hat U\|^2)^{-1/2}`$ in
/// the pseudo arc length, or $`\pm\langle\varphi,\varphi\rangle/\langle\hat U,\varphi\rangle`$ in
/// the amplitude of `mode` when $`\hat U`$ has a part along it ([`MODE_PARAMETER_COSINE`]); the
/// sign chosen so that $`(U_1, \lambda_1) = \lambda_1(\hat U, 1)`$ continues
/// `previous_direction` (the path tangent at the end of the previous step), else as computed.
/// Returns $`(\hat U, \lambda_1)`$ and the step's parameter.
fn first_order<'p, M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    factor: &SparseFactorization,
    previous_direction: Option<(&[f64], f64)>,
    mode: Option<&'p [f64]>,
) -> Result<(Vec<f64>, f64, StepParameter<'p>), SolveError> {
    let u_hat = load_tangent(problem, factor, &state.displacement, state.load).map_err(
        SolveError::linear(format!("ANM order 1 at load {:.6e}", state.load)),
    )?;
    let norm2 = dot(&u_hat, &u_hat);
    let mut lambda1 = 1.0 / (1.0 + norm2).sqrt();
    let mut parameter = StepParameter::ArcLength;
    if let Some(mode) = mode {
        let projection = dot(&u_hat, mode);
        let mode_norm2 = dot(mode, mode);
        if projection.abs() >= MODE_PARAMETER_COSINE * (norm2 * mode_norm2).sqrt()
            && projection.is_finite()
            && mode_norm2 > 0.0
        {
            lambda1 = mode_norm2 / projection;
            parameter = StepParameter::Mode { mode, projection };
        }
    }
    if let Some((u_prev, l_prev)) = previous_direction
        && lambda1 * (dot(&u_hat, u_prev) + l_prev) < 0.0
    {
        lambda1 = -lambda1;
    }
    Ok((u_hat, lambda1, parameter))
}

/// Order $`k \ge 2`$ from its right-hand side $`F^{nl}_k`$ (overwritten): solve
/// $`K_t\hat U_k = F^{nl}_k`$, then $`\lambda_k = -\lambda_1\langle\hat U_k, U_1\rangle`$ in the
/// pseudo arc length, $`\lambda_k = -\langle\hat U_k,\varphi\rangle/\langle\hat U,\varphi\rangle`$
/// in the mode's amplitude ($`\langle U_k, \varphi\rangle = 0`$), and
/// $`U_k = \hat U_k + \lambda_k\hat U`$.
#[allow(clippy::too_many_arguments)]
fn higher_order(
    factor: &SparseFactorization,
    mut rhs: Vec<f64>,
    u_hat: &[f64],
    u1: &[f64],
    lambda1: f64,
    parameter: StepParameter<'_>,
    k: usize,
    load: f64,
) -> Result<(Vec<f64>, f64), SolveError> {
    if rhs.iter().any(|v| !v.is_finite()) {
        return Err(SolveError::NonFinite {
            location: format!("ANM right-hand side of order {k} at load {load:.6e}"),
        });
    }
    factor
        .solve_in_place(&mut rhs)
        .map_err(SolveError::linear(format!(
            "ANM order {k} at load {load:.6e}"
        )))?;
    let lambda_k = match parameter {
        StepParameter::ArcLength => -lambda1 * dot(&rhs, u1),
        StepParameter::Mode { mode, projection } => -dot(&rhs, mode) / projection,
    };
    axpy(lambda_k, u_hat, &mut rhs);
    Ok((rhs, lambda_k))
}

/// Computes the series of one step at `state`, whose tangent `factor` holds, with the models'
/// Taylor-mode kernels: per order one solve and one sweep over the tape that commits the
/// previous order and predicts the right-hand side of this one ($`O(k)`$ per product at every
/// quadrature point). The last order is not committed (the tape is restarted at the next step).
/// `tape` must hold at least `order` orders.
/// Returns the path series (orders 0..=N) and $`\hat U`$.
pub fn compute_series<M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    factor: &SparseFactorization,
    order: usize,
    previous_direction: Option<(&[f64], f64)>,
    tape: &mut TaylorTape,
) -> Result<(PathSeries, Vec<f64>), SolveError> {
    compute_series_in_mode(
        problem,
        state,
        factor,
        order,
        StepOrientation {
            previous_direction,
            mode: None,
        },
        tape,
    )
    .map(|(series, u_hat, _)| (series, u_hat))
}

/// [`compute_series`] with the step parametrised by the amplitude of `mode` when given,
/// $`a = \langle U - U_0, \varphi\rangle/\langle\varphi,\varphi\rangle`$, and the load tangent
/// has a part along it ([`AnmOptions::mode_parameter`], [`MODE_PARAMETER_COSINE`]); the
/// returned flag says whether it has (else the series is the arc length's).
pub fn compute_series_in_mode<M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    factor: &SparseFactorization,
    order: usize,
    orientation: StepOrientation<'_>,
    tape: &mut TaylorTape,
) -> Result<(PathSeries, Vec<f64>, bool), SolveError> {
    start_tape(problem, state, tape);
    series_with(problem, state, factor, order, orientation, tape, None)
}

/// Starts the tape at `state` for a series there: order 0, then the order-1 prediction (zero:
/// every coefficient of order 1 is linear in $`U_1`$, but the kernels record their partial
/// sums).
fn start_tape<M: EnergyModel>(problem: &Problem<M>, state: &PathState, tape: &mut TaylorTape) {
    problem.taylor_start(&state.displacement, state.load, tape);
    problem.taylor_residual(1, tape);
}

/// [`compute_series`], pushing its coefficients into `orthogonalized` when given, for the Padé
/// approximants ([`PadeApproximant::orthogonalized`]): each $`V_{k-1}`$ is orthogonalised while
/// the order-$`k`$ solve runs, on the core the solve leaves idle (the approximant's
/// construction took 0.06 of a step's floor on the reference envelope at 128 × 64, after the
/// series). The tape must have been started at `state` ([`start_tape`]). The step is oriented
/// along `previous_direction` and parametrised by the amplitude of `mode` when given and the
/// load tangent has a part along it ([`first_order`]); the returned flag says whether it is.
fn series_with<M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    factor: &SparseFactorization,
    order: usize,
    orientation: StepOrientation<'_>,
    tape: &mut TaylorTape,
    mut orthogonalized: Option<&mut GramSchmidt>,
) -> Result<(PathSeries, Vec<f64>, bool), SolveError> {
    let order = order.clamp(2, tape.highest_order());
    let StepOrientation {
        previous_direction,
        mode,
    } = orientation;
    let (u_hat, lambda1, parameter) =
        first_order(problem, state, factor, previous_direction, mode)?;
    let u1: Vec<f64> = u_hat.iter().map(|v| v * lambda1).collect();
    let mut displacement = vec![state.displacement.clone(), u1];
    let mut load = vec![state.load, lambda1];
    for k in 2..=order {
        let rhs: Vec<f64> = problem
            .taylor_commit_then_residual(k - 1, &displacement[k - 1], load[k - 1], tape)
            .iter()
            .map(|r| -r)
            .collect();
        // The solve runs on one core; the previous coefficient's Gram–Schmidt on the other.
        let (solved, ()) = rayon::join(
            || {
                higher_order(
                    factor,
                    rhs,
                    &u_hat,
                    &displacement[1],
                    lambda1,
                    parameter,
                    k,
                    state.load,
                )
            },
            || {
                if let Some(orthogonalized) = orthogonalized.as_deref_mut() {
                    orthogonalized.push(&displacement[k - 1], load[k - 1]);
                }
            },
        );
        let (u_k, lambda_k) = solved?;
        displacement.push(u_k);
        load.push(lambda_k);
    }
    if let Some(orthogonalized) = orthogonalized {
        orthogonalized.push(&displacement[order], load[order]);
    }
    let series = PathSeries::new(displacement, load).map_err(|e| SolveError::Path {
        load: state.load,
        message: format!("series: {e}"),
    })?;
    let by_mode = matches!(parameter, StepParameter::Mode { .. });
    Ok((series, u_hat, by_mode))
}

/// [`compute_series`] through the generic kernels on truncated [`Series`]: the residual of
/// $`\sum_{j<k} a^j U_j`$ evaluated to order $`k`$ at every order ($`O(N^3)`$ per step). Kept
/// as the reference the Taylor-mode kernels are tested against.
pub fn compute_series_generic<M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    factor: &SparseFactorization,
    order: usize,
    previous_direction: Option<(&[f64], f64)>,
) -> Result<(PathSeries, Vec<f64>), SolveError> {
    let n = problem.free_count();
    let order = order.clamp(2, MAX_SERIES_LEN - 2);
    let (u_hat, lambda1, parameter) =
        first_order(problem, state, factor, previous_direction, None)?;
    let u1: Vec<f64> = u_hat.iter().map(|v| v * lambda1).collect();
    let mut displacement = vec![state.displacement.clone(), u1];
    let mut load = vec![state.load, lambda1];
    for k in 2..=order {
        // Series of the unknowns truncated at order k−1, evaluated to order k.
        let mut free = vec![Series::zeros(k + 1); n];
        for (i, s) in free.iter_mut().enumerate() {
            let c = s.coefficients_mut();
            for (j, u) in displacement.iter().enumerate() {
                c[j] = u[i];
            }
        }
        let mut load_series = Series::zeros(k + 1);
        load_series.coefficients_mut()[..k].copy_from_slice(&load);
        let residual = problem.residual(&free, load_series);
        let rhs: Vec<f64> = residual.iter().map(|r| -r.coefficient(k)).collect();
        let (u_k, lambda_k) = higher_order(
            factor,
            rhs,
            &u_hat,
            &displacement[1],
            lambda1,
            parameter,
            k,
            state.load,
        )?;
        displacement.push(u_k);
        load.push(lambda_k);
    }
    let series = PathSeries::new(displacement, load).map_err(|e| SolveError::Path {
        load: state.load,
        message: format!("series: {e}"),
    })?;
    Ok((series, u_hat))
}

/// What lengthens a step beyond the plain series' range.
#[derive(Clone, Debug)]
enum Extension {
    /// The Padé approximants' common-denominator form ([`PadeApproximant`]).
    Pade(PadeApproximant),
    /// The series re-expanded in $`s = \ln(1 + a/R)`$ past a singularity behind the step
    /// ([`ExponentialMap`]).
    Map(ExponentialMap),
}

impl Extension {
    fn evaluate(&self, a: f64) -> (Vec<f64>, f64) {
        match self {
            Extension::Pade(pade) => pade.evaluate(a),
            Extension::Map(map) => map.evaluate(a),
        }
    }

    fn evaluate_derivative(&self, a: f64) -> (Vec<f64>, f64) {
        match self {
            Extension::Pade(pade) => pade.evaluate_derivative(a),
            Extension::Map(map) => map.evaluate_derivative(a),
        }
    }
}

/// What one step evaluates: its truncated series up to the series' own range, and beyond it
/// the extension (Padé approximant or exponential map) when that allows a finite, longer step.
struct StepApproximant<'s> {
    series: &'s PathSeries,
    /// The plain series' range.
    plain: f64,
    /// The extension and its range, when it lengthens the step.
    extension: Option<(Extension, f64)>,
    /// The other extension, with a shorter range that still lengthens the step: the step
    /// falls back on it when an end on the exponential map misses its residual tolerance
    /// ([`AnmRun::accept_end`]).
    fallback: Option<(Extension, f64)>,
}

impl StepApproximant<'_> {
    /// The range the step tries first.
    fn range(&self) -> f64 {
        self.extension
            .as_ref()
            .map_or(self.plain, |&(_, range)| range)
    }

    /// The extension when it is what the step evaluates at `a`.
    fn extension_at(&self, a: f64) -> Option<&Extension> {
        self.extension
            .as_ref()
            .filter(|_| a > self.plain)
            .map(|(extension, _)| extension)
    }

    fn evaluate(&self, a: f64) -> PathState {
        evaluate_approximant(self.series, self.plain, self.extension.as_ref(), a)
    }

    /// The series' range and the extension with its range, without the series borrowed.
    fn into_parts(self) -> (f64, Option<(Extension, f64)>) {
        (self.plain, self.extension)
    }

    /// The path tangent at `a`, from the approximant evaluated there: beyond the series' range
    /// its own derivative is meaningless and can point backwards.
    fn derivative(&self, a: f64) -> (Vec<f64>, f64) {
        match self.extension_at(a) {
            Some(extension) => extension.evaluate_derivative(a),
            None => self.series.evaluate_derivative(a),
        }
    }
}

/// A step's approximant at `a`: the extension beyond the series' range `plain` when there is
/// one, else the series.
fn evaluate_approximant(
    series: &PathSeries,
    plain: f64,
    extension: Option<&(Extension, f64)>,
    a: f64,
) -> PathState {
    let (displacement, load) = match extension.filter(|_| a > plain) {
        Some((extension, _)) => extension.evaluate(a),
        None => series.evaluate(a),
    };
    PathState { displacement, load }
}

/// The approximant of the step a path stopped in (the observer stopped it at a point of that
/// step), with the path parameters of the last two points it reported: a landing on a target
/// between them evaluates the step there instead of correcting a chord
/// ([`land_on_step`](super::landing::land_on_step)).
pub struct StepTail {
    series: PathSeries,
    plain: f64,
    extension: Option<(Extension, f64)>,
    /// Parameters $`a`$ of the point reported before the stop and of the stop.
    pub bracket: (f64, f64),
}

impl StepTail {
    /// The tail of the step with `series` and its approximant's
    /// [`parts`](StepApproximant::into_parts), stopped between the parameters `bracket`.
    fn new(
        series: PathSeries,
        (plain, extension): (f64, Option<(Extension, f64)>),
        bracket: (f64, f64),
    ) -> Self {
        Self {
            series,
            plain,
            extension,
            bracket,
        }
    }

    /// The step's point at parameter `a` (as the step evaluated its own points).
    pub fn evaluate(&self, a: f64) -> PathState {
        evaluate_approximant(&self.series, self.plain, self.extension.as_ref(), a)
    }
}

/// The first end a step tries, in multiples of the series' own range, when the Padé
/// approximant's criterion ([`PadeApproximant::pade_step_length`]) holds without bound (its
/// range is infinite: $`P_N`$ and $`P_{N-1}`$ agree to $`\varepsilon`$ as far as it looks, and
/// no pole bounds the step). The end is then shortened towards the series' range, halving,
/// until its residual passes ([`AnmRun::accept_end`]): at most 10 residual checks, not a step.
///
/// Before, such a step took the plain series' range: on the long strip's plate (example 2, at
/// 112 × 64) the path's first four steps grew by only a factor of 2 each (the series' radius
/// is proportional to the distance from the unloaded start, where the imperfection's response
/// is a cubic membrane law), and 7 of its 21 steps went to reach 0.18 mm; with this bound the
/// second step ends at 0.76 mm, and the path takes 16 steps (docs/benchmarks.md, "Round
/// four").
const UNBOUNDED_PADE_RANGE: f64 = 1024.0;

/// The fraction of the residual tolerance an end on the exponential map must meet
/// ([`ExponentialMap`]); a longer end is shortened towards the series' range. Its range comes
/// from the mapped coefficients' decay, which says less about the end's accuracy than the plain
/// series' does: on the strip's plate (example 2, 112 × 64) past the knee, mapped ends accepted
/// at the full tolerance (relative residuals 9.5e-7 and 5.8e-7) moved the load at a/h = 2 by
/// 1.3e-4 (17.15166 against 17.14951 at a tolerance of 1e-8), where series and Padé ends
/// (1e-8 to 2e-7) kept it within 2e-6.
const MAPPED_END_RESIDUAL_FRACTION: f64 = 0.1;

/// Halvings of a series step whose end crossed a critical point before the crossing is taken
/// as the path's own (a limit point or a perfect bifurcation, located at the next step).
const MAX_CROSSING_HALVINGS: usize = 4;

/// Halvings of a step end (each after a failed residual check and corrector) before the step
/// fails.
const MAX_END_HALVINGS: usize = 12;

/// Traces the path from `start` with the ANM; every accepted point (step ends and the
/// `interior_points` inside each step) goes to `observer`. Never panics on a numerical failure:
/// the result keeps the last accepted point and says why it stopped.
pub fn follow_path_anm<M: EnergyModel>(
    problem: &Problem<M>,
    start: PathState,
    factor: &mut SparseFactorization,
    options: &AnmOptions,
    observer: &mut dyn FnMut(&PathEvent) -> PathControl,
    steps_log: &mut Vec<AnmStep>,
) -> PathResult {
    let path = (start, None);
    follow_path_anm_to_tail(problem, path, factor, options, observer, steps_log).0
}

/// [`follow_path_anm`], with the approximant of the step the observer stopped the path in, if
/// it did ([`StepTail`]), from `start` in the [`Workspace`] made for it, if any (its spare
/// serves only a `factor` of the same analysis, [`Workspace::fits`]).
pub fn follow_path_anm_to_tail<M: EnergyModel>(
    problem: &Problem<M>,
    start: (PathState, Option<Workspace>),
    factor: &mut SparseFactorization,
    options: &AnmOptions,
    observer: &mut dyn FnMut(&PathEvent) -> PathControl,
    steps_log: &mut Vec<AnmStep>,
) -> (PathResult, Option<StepTail>) {
    std::thread::scope(|scope| {
        follow_path_in(scope, problem, start, factor, options, observer, steps_log)
    })
}

/// [`follow_path_anm`] inside the scope its bifurcation prediction may run in
/// ([`AnmRun::watch_bifurcation`]).
fn follow_path_in<'scope, 'a: 'scope, M: EnergyModel>(
    scope: &'scope std::thread::Scope<'scope, 'a>,
    problem: &'a Problem<M>,
    (start, workspace): (PathState, Option<Workspace>),
    factor: &'a mut SparseFactorization,
    options: &'a AnmOptions,
    observer: &mut dyn FnMut(&PathEvent) -> PathControl,
    steps_log: &mut Vec<AnmStep>,
) -> (PathResult, Option<StepTail>) {
    let (matrix, end_check, start_held) = match workspace.filter(|w| w.fits(factor)) {
        Some(workspace) => {
            let (matrix, spare, held) = workspace.into_parts();
            (matrix, Some(spare), held)
        }
        None => (problem.new_matrix(), None, false),
    };
    let mut run = AnmRun {
        scope,
        pending: None,
        linearization: Linearization::with_matrix(problem, factor, matrix),
        options,
        begin: Instant::now(),
        tape: problem
            .assembler
            .taylor_tape(options.order.clamp(2, MAX_SERIES_LEN - 2)),
        state: start,
        previous_direction: None,
        previous_start: None,
        negative_pivots: None,
        prediction: None,
        bifurcation: None,
        warnings: Vec::new(),
        end_check,
        start_factorized: false,
        start_held,
        tape_started_at: None,
        tail: None,
    };
    run.linearization.statistics.tape_bytes = Some(run.tape.bytes());
    let start_residual = run
        .linearization
        .relative_residual(&run.state.displacement, run.state.load);
    let event = PathEvent {
        step: 0,
        interior: false,
        state: &run.state,
        relative_residual: start_residual,
        predicted_bifurcation: None,
        on_step: None,
    };
    if observer(&event) == PathControl::Stop {
        return run.finish(PathStop::Observer, steps_log);
    }
    for step in 1..=options.max_steps {
        match run.step(step, observer, steps_log) {
            Ok(None) => {}
            Ok(Some(stop)) => return run.finish(stop, steps_log),
            Err(error) => return run.finish(PathStop::Failed(error), steps_log),
        }
    }
    run.finish(PathStop::MaxSteps, steps_log)
}

/// What a bifurcation prediction gives back from its thread.
struct PredictionOutcome {
    load: Result<f64, SolveError>,
    factorizations: usize,
}

/// A bifurcation prediction running on a thread of its own beside the path
/// ([`AnmRun::watch_bifurcation`]).
struct PendingPrediction<'scope> {
    /// The step about whose start it predicts.
    step: usize,
    /// Where that step's record goes in the steps' log.
    record: usize,
    /// The load at that start (for the warning when it fails).
    load: f64,
    handle: std::thread::ScopedJoinHandle<'scope, PredictionOutcome>,
}

/// The state of one ANM path.
struct AnmRun<'scope, 'a: 'scope, M: EnergyModel> {
    /// Where a bifurcation prediction runs beside the path.
    scope: &'scope std::thread::Scope<'scope, 'a>,
    /// The bifurcation prediction under way, if any.
    pending: Option<PendingPrediction<'scope>>,
    /// The tangent at the step's start, its factorisation and the path's work counters.
    linearization: Linearization<'a, M>,
    options: &'a AnmOptions,
    begin: Instant,
    tape: TaylorTape,
    state: PathState,
    /// Path tangent $`(dU/da, d\lambda/da)`$ at the end of the previous step.
    previous_direction: Option<(Vec<f64>, f64)>,
    /// Start point and $`\hat U`$ of the previous step (to locate a critical point crossed in it).
    previous_start: Option<(PathState, Vec<f64>)>,
    /// Negative eigenvalues of the tangent at the previous step's start.
    negative_pivots: Option<usize>,
    /// Bifurcation load predicted by linear buckling about the path, when computed.
    prediction: Option<f64>,
    bifurcation: Option<(f64, usize)>,
    warnings: Vec<String>,
    /// A second tangent and factorisation for the end of a step,
    /// where its inertia is checked (see [`AnmRun::jumped_over_critical_point`]).
    end_check: Option<SpareTangent>,
    /// The tangent at the current start is already assembled and factorised (by the end check
    /// of the previous step).
    start_factorized: bool,
    /// The factorisation holds that of the current matrix, assembled before the path (the
    /// start's Newton, [`Workspace::newton`]): the first step keeps it when the tangent at the
    /// start is the same ([`Linearization::factorize_unless_held`]).
    start_held: bool,
    /// The load of the step end the tape was last started at (beside that end's
    /// factorisation, [`Self::jumped_over_critical_point`]); the next series skips the start
    /// when it is the current start's.
    tape_started_at: Option<f64>,
    /// The step the observer stopped the path in.
    tail: Option<StepTail>,
}

/// How a step's end point was accepted.
struct AcceptedEnd {
    state: PathState,
    residual: f64,
    corrections: usize,
    step_length: f64,
    hit_max_load: bool,
}

impl<'scope, 'a: 'scope, M: EnergyModel> AnmRun<'scope, 'a, M> {
    fn finish(
        mut self,
        stop: PathStop,
        steps_log: &mut [AnmStep],
    ) -> (PathResult, Option<StepTail>) {
        self.collect_prediction(steps_log);
        let factor_nonzeros = self.linearization.factor().factor_nnz();
        let mut statistics = self.linearization.statistics;
        statistics.total_seconds = self.begin.elapsed().as_secs_f64();
        statistics.factor_nonzeros = Some(factor_nonzeros);
        let result = PathResult {
            last: self.state,
            statistics,
            stop,
            bifurcation: self.bifurcation,
            warnings: self.warnings,
        };
        (result, self.tail)
    }

    /// One step: factorise, series, bifurcation bookkeeping, step length, end point, dense
    /// output. `Ok(Some(stop))` ends the path.
    fn step(
        &mut self,
        step: usize,
        observer: &mut dyn FnMut(&PathEvent) -> PathControl,
        steps_log: &mut Vec<AnmStep>,
    ) -> Result<Option<PathStop>, SolveError> {
        self.factorize_tangent(step, steps_log)?;
        let StepSeries {
            series,
            u_hat,
            orthogonalized,
            by_mode,
        } = self.series()?;
        // One started at an earlier step has had this series beside it.
        self.collect_prediction(steps_log);
        let predicted = self.watch_bifurcation(step, &series, &u_hat, steps_log);
        let (mut approximant, offered) = self.approximant(&series, orthogonalized);
        let series_range = approximant.plain;
        let (end, crossings_redone, interior) =
            self.end_without_crossing(step, &mut approximant)?;
        let mut record = AnmStep {
            step,
            load_range: (self.state.load, end.state.load),
            step_length: end.step_length,
            series_step_length: series_range,
            pade_step_length: offered.pade,
            mapped_step_length: offered.map,
            singularity_behind: offered.behind,
            end_residual: end.residual,
            correction_iterations: end.corrections,
            crossings_redone,
            geometric_radius: geometric_ratio(&series),
            predicted_bifurcation: predicted,
            negative_pivots: self.negative_pivots,
            completed: true,
            mode_parameter: by_mode,
        };
        let last_reported = match self.dense_output(
            step,
            interior,
            (&approximant, end.step_length),
            predicted,
            observer,
        ) {
            Ok(last) => last,
            Err((stop, bracket)) => {
                // Stopped at an interior point: the step is logged up to there.
                record.load_range.1 = self.state.load;
                record.completed = false;
                steps_log.push(record);
                let parts = approximant.into_parts();
                self.tail = Some(StepTail::new(series, parts, bracket));
                return Ok(Some(stop));
            }
        };
        if let Some(p) = self.prediction
            && self.bifurcation.is_none()
            && end.state.load >= p
            && self.state.load < p
        {
            self.bifurcation = Some((p, step));
        }
        steps_log.push(record);
        self.linearization.statistics.steps = step;
        // The next step continues the path tangent at this step's end (not at its start: past a
        // sharp turn the two can point apart), taken from the approximant that gave the end.
        self.previous_direction = Some(approximant.derivative(end.step_length));
        self.previous_start = Some((std::mem::replace(&mut self.state, end.state), u_hat));
        // A corrected end is off the approximant.
        let evaluate = |a: f64| approximant.evaluate(a);
        let event = PathEvent {
            step,
            interior: false,
            state: &self.state,
            relative_residual: end.residual,
            predicted_bifurcation: predicted,
            on_step: (end.corrections == 0).then_some(OnStep {
                parameter: end.step_length,
                previous: last_reported,
                evaluate: &evaluate,
            }),
        };
        if observer(&event) == PathControl::Stop {
            let (parts, bracket) = (approximant.into_parts(), (last_reported, end.step_length));
            self.tail = Some(StepTail::new(series, parts, bracket));
            return Ok(Some(PathStop::Observer));
        }
        Ok(end.hit_max_load.then_some(PathStop::MaxLoad))
    }

    /// The mode whose amplitude parametrises this step ([`AnmOptions::mode_parameter`]): only
    /// from a stable start (no negative pivot). On an unstable branch — past a limit point of
    /// a subcritical path, or a crossing taken as the path's own — the crossing guard no longer
    /// keeps a step from jumping over a bifurcation, and a step in the mode's amplitude did:
    /// the softening beam of `beam_softening.toml`, localised at its middle in the arc length,
    /// ended localised off the middle (an asymmetric branch). There the arc length stays.
    fn mode_parameter(&self) -> Option<&'a [f64]> {
        self.options
            .mode_parameter
            .as_deref()
            .filter(|_| self.negative_pivots == Some(0))
    }

    /// The series of the step at the current point ([`compute_series`]; with its Gram–Schmidt
    /// when Padé approximants are enabled), timed and counted.
    fn series(&mut self) -> Result<StepSeries, SolveError> {
        let t = Instant::now();
        let solves_before = self.linearization.factor().solve_seconds();
        let direction = self
            .previous_direction
            .as_ref()
            .map(|(u, l)| (u.as_slice(), *l));
        let mut orthogonalized = self.options.pade.then(GramSchmidt::new);
        let tape_started = self
            .tape_started_at
            .take()
            .is_some_and(|load| load.to_bits() == self.state.load.to_bits());
        if !tape_started {
            start_tape(self.linearization.problem(), &self.state, &mut self.tape);
        }
        let (series, u_hat, by_mode) = series_with(
            self.linearization.problem(),
            &self.state,
            self.linearization.factor(),
            self.options.order,
            StepOrientation {
                previous_direction: direction,
                mode: self.mode_parameter(),
            },
            &mut self.tape,
            orthogonalized.as_mut(),
        )?;
        let solve_seconds = self.linearization.factor().solve_seconds() - solves_before;
        let statistics = &mut self.linearization.statistics;
        statistics.series_assemblies += series.order() - 1;
        statistics.series_seconds += t.elapsed().as_secs_f64();
        statistics.series_solve_seconds += solve_seconds;
        Ok(StepSeries {
            series,
            u_hat,
            orthogonalized,
            by_mode,
        })
    }

    /// The step's end ([`Self::accept_end`]), redone while it jumped over a critical point
    /// (more negative pivots than the start): returns it with the number of redos and the
    /// step's interior points up to it ([`Self::jumped_over_critical_point`]).
    fn end_without_crossing(
        &mut self,
        step: usize,
        approximant: &mut StepApproximant,
    ) -> Result<(AcceptedEnd, usize, Vec<InteriorPoint>), SolveError> {
        let mut end = self.accept_end(step, approximant)?;
        let mut halvings = 0;
        let mut crossings_redone = 0;
        let mut shortened_extension = false;
        loop {
            let (jumped, interior) = self.jumped_over_critical_point(step, &end, approximant)?;
            if !jumped {
                return Ok((end, crossings_redone, interior));
            }
            // The end has more negative pivots than the start: the step crossed a critical
            // point. Near a nearly perfect bifurcation the singular part of the series is too
            // small for the step-length criteria, and a step can run along the fundamental
            // branch past λ_c onto the unstable branch of the imperfect problem (the strip of
            // example 2 with a 1e-5 imperfection ended at λ = 36 instead of 24.6 mm). A step
            // lengthened by an extension (Padé or the exponential map) is redone once with a
            // shorter range of it, then with the series' own range; a series step with half its
            // length.
            if approximant.extension_at(end.step_length).is_some() {
                // A Padé end far along a nearly linear pre-buckling path passes the residual
                // check past λ_c (the strip's plate: from λ = 0.03 mm to beyond 13.8 mm); the
                // series' range would restart it from a fraction of a millimetre. Once, the
                // Padé range is shortened until the approximant's load is 90 % of the way to
                // the expected critical load; then the series' range.
                match self.extension_range_below_guess(approximant, end.step_length) {
                    Some(range) if !shortened_extension => {
                        shortened_extension = true;
                        approximant.fallback = None;
                        if let Some((_, extended)) = approximant.extension.as_mut() {
                            *extended = range;
                        }
                    }
                    _ => {
                        approximant.extension = None;
                        approximant.fallback = None;
                    }
                }
            } else if halvings < MAX_CROSSING_HALVINGS && self.negative_pivots == Some(0) {
                // Only a stable start is kept stable: once the path is on an unstable branch
                // (a crossing taken as its own), further crossings are the branch's.
                halvings += 1;
                approximant.extension = None;
                approximant.fallback = None;
                approximant.plain = 0.5 * end.step_length;
            } else {
                // Still crossing in a small fraction of the step: a critical point of the path
                // itself (a limit point, or a perfect bifurcation); the next step locates it.
                return Ok((end, crossings_redone, interior));
            }
            self.linearization.statistics.rejected_steps += 1;
            crossings_redone += 1;
            end = self.accept_end(step, approximant)?;
        }
    }

    /// The Padé range, halved from `crossed` (a Padé end that crossed a critical point), at
    /// which the approximant's load is at most 90 % of the way from the step's start to the
    /// expected critical load ([`AnmOptions::bifurcation_load_guess`], known before the path:
    /// the same on any number of threads); `None` without a guess above the start, or when no
    /// such range is longer than the series' own.
    fn extension_range_below_guess(
        &self,
        approximant: &StepApproximant,
        crossed: f64,
    ) -> Option<f64> {
        let start = self.state.load;
        let guess = self
            .options
            .bifurcation_load_guess
            .filter(|guess| guess.is_finite() && *guess > start)?;
        let limit = start + 0.9 * (guess - start);
        let mut range = 0.5 * crossed;
        while range > approximant.plain {
            if approximant.evaluate(range).load <= limit {
                return Some(range);
            }
            range *= 0.5;
        }
        None
    }

    /// Assembles and factorises the tangent at the step's start; a change of its inertia
    /// (negative pivots of $`LDL^\top`$, none after $`LL^\top`$) reveals a critical point crossed
    /// during the previous step, which is then located.
    fn factorize_tangent(
        &mut self,
        step: usize,
        steps_log: &mut [AnmStep],
    ) -> Result<(), SolveError> {
        if !std::mem::take(&mut self.start_factorized) {
            let state = &self.state;
            let held = std::mem::take(&mut self.start_held);
            let factorized = match self.end_check.as_mut() {
                // The first step's factorisation may be the start's Newton's.
                Some(spare) => self
                    .linearization
                    .factorize_unless_held(&state.displacement, state.load, held, spare)
                    .map(|_| ()),
                None => self
                    .linearization
                    .factorize(&state.displacement, state.load),
            };
            factorized.map_err(SolveError::linear(format!(
                "ANM step {step} at load {:.6e}: tangent factorisation",
                state.load
            )))?;
        }
        let negative = self.linearization.negative_pivots();
        if let (Some(before), Some(now)) = (self.negative_pivots, negative)
            && now > before
            && self.options.predict_bifurcation
        {
            // A prediction under way may have passed the bifurcation already.
            self.collect_prediction(steps_log);
            if self.bifurcation.is_none() {
                self.locate_crossed_critical_point(step - 1);
            }
        }
        self.negative_pivots = negative;
        Ok(())
    }

    /// Whether the end `end` of a step has more negative pivots than the step's start: the
    /// step jumped over a critical point (typically onto the unstable fundamental branch past a
    /// bifurcation). Otherwise the end's tangent and factorisation become the next step's (no
    /// extra cost). A failed factorisation at the end (singular: a critical point exactly
    /// there) counts as a jump. Without inertia (LU) nothing is checked.
    ///
    /// Also returns the step's interior points up to `end` ([`interior_points`]), evaluated
    /// **while** the end's tangent is factorised ([`Linearization::factorize_spare_alongside`]):
    /// the factorisation runs on one core, the interior points' residual checks on the other
    /// (the values do not depend on it, each residual is the same sum on any number of
    /// threads). On the plate of example 1 that hides 0.08 of a step's floor (10 residuals a
    /// step). The tape is started at the end there too, the two sweeps the next step's series
    /// would begin with (its order 0 and the order-1 prediction; [`Self::tape_started_at`]):
    /// 0.03 of the reference envelope's floor.
    fn jumped_over_critical_point(
        &mut self,
        step: usize,
        end: &AcceptedEnd,
        approximant: &StepApproximant,
    ) -> Result<(bool, Vec<InteriorPoint>), SolveError> {
        let problem = self.linearization.problem();
        let count = self.options.interior_points;
        let length = end.step_length;
        let interior = || interior_points(problem, approximant, length, count);
        let end = &end.state;
        let Some(before) = self.negative_pivots else {
            let (points, seconds) = interior();
            self.linearization.statistics.residual_assemblies += points.len();
            self.linearization.statistics.residual_seconds += seconds;
            return Ok((false, points));
        };
        let mut spare = match self.end_check.take() {
            Some(spare) => spare,
            None => self
                .linearization
                .spare()
                .map_err(SolveError::linear(format!(
                    "ANM step {step}: symbolic analysis for the end-point check"
                )))?,
        };
        // Beside the factorisation too: the tape started at the end, for the next step's
        // series should the end be its start (it is the last end checked in a step).
        let tape = &mut self.tape;
        let alongside = || {
            let checked = interior();
            start_tape(problem, end, tape);
            checked
        };
        let (factorized, (points, _), added) = self.linearization.factorize_spare_alongside(
            &mut spare,
            &end.displacement,
            end.load,
            alongside,
        );
        self.tape_started_at = Some(end.load);
        // Counted as residual checks; their time only where it outlasted the factorisation.
        self.linearization.statistics.residual_assemblies += points.len();
        self.linearization.statistics.residual_seconds += added;
        let jumped = match (factorized, spare.negative_pivots()) {
            (Err(_), _) => true,
            (Ok(()), Some(after)) => after > before,
            (Ok(()), None) => false,
        };
        if !jumped {
            self.linearization.adopt(&mut spare);
            self.start_factorized = true;
        }
        self.end_check = Some(spare);
        Ok((jumped, points))
    }

    /// Linear buckling about the previous step's start (where the tangent was still positive
    /// definite) along its path tangent: the critical point crossed in that step.
    fn locate_crossed_critical_point(&mut self, crossed_in: usize) {
        let Some((start, u_hat)) = self.previous_start.clone() else {
            return;
        };
        let t = Instant::now();
        let problem = self.linearization.problem();
        let same_analysis = self.linearization.factor().same_analysis();
        let statistics = &mut self.linearization.statistics;
        let counted = statistics.factorizations;
        let located = same_analysis
            .map_err(SolveError::linear(
                "locating a critical point: symbolic analysis",
            ))
            .and_then(|mut factor| {
                let mut tangent = problem.new_matrix();
                factorize_tangent(
                    problem,
                    &start.displacement,
                    start.load,
                    &mut tangent,
                    &mut factor,
                )
                .map_err(SolveError::linear(
                    "locating a critical point: factorisation at the previous step's start",
                ))?;
                statistics.factorizations += 1;
                predict_bifurcation(
                    problem,
                    &start,
                    &u_hat,
                    Unshifted::Factorized(&factor),
                    &tangent,
                    None,
                    None,
                    &mut statistics.factorizations,
                )
            });
        statistics.bifurcation_seconds += t.elapsed().as_secs_f64();
        statistics.prediction_factorizations += statistics.factorizations - counted;
        match located {
            Ok(load) => self.bifurcation = Some((load, crossed_in)),
            Err(error) => self.warnings.push(format!(
                "the tangent lost positive definiteness during step {crossed_in} (a critical point was crossed) but locating it failed: {error}"
            )),
        }
    }

    /// When the series first shows a geometric tail (a singularity within reach: the ANM
    /// signature of a nearby bifurcation or of the sharp turn of an imperfect path), one linear
    /// buckling analysis about the step's start predicts the bifurcation load.
    ///
    /// Shifted towards a guess ([`predict_bifurcation`]), it runs on a thread of its own beside
    /// the path ([`PendingPrediction`]) with a copy of the tangent and a factorisation of its
    /// own: its shifted factorisation and eigen-solve take the core the next step's series
    /// solves leave idle (0.6–2.2 s of the path on example 1's plate and envelope and on the
    /// strip's plate). It is collected after the next step's series
    /// ([`Self::collect_prediction`]), or before that when a crossed critical point or the
    /// path's end needs it; what it gives does not depend on when. When the shifted analysis
    /// does not decide, the thread factorises the tangent itself (one factorisation more than
    /// in place). Unshifted, or with one worker thread, it runs in place with the path's
    /// factorisation. Returns the load when it ran in place.
    fn watch_bifurcation(
        &mut self,
        step: usize,
        series: &PathSeries,
        u_hat: &[f64],
        steps_log: &mut [AnmStep],
    ) -> Option<f64> {
        if !self.options.predict_bifurcation
            || self.prediction.is_some()
            || self.pending.is_some()
            || series.load[1] <= 0.0
            || self.negative_pivots.is_some_and(|n| n > 0)
            || geometric_ratio(series).is_none()
        {
            return None;
        }
        let clock = Instant::now();
        let problem = self.linearization.problem();
        let shifted = prediction_shift(self.options.bifurcation_load_guess, self.state.load);
        if shifted.is_none() || rayon::current_num_threads() < 2 {
            // In place, with the path's factorisation: an unshifted prediction needs no other.
            let mut factorizations = 0;
            let load = predict_bifurcation(
                problem,
                &self.state,
                u_hat,
                Unshifted::Factorized(self.linearization.factor()),
                self.linearization.tangent(),
                self.options.bifurcation_mode_guess.clone(),
                self.options.bifurcation_load_guess,
                &mut factorizations,
            );
            self.linearization.statistics.bifurcation_seconds += clock.elapsed().as_secs_f64();
            let made = (step, steps_log.len(), self.state.load);
            let outcome = PredictionOutcome {
                load,
                factorizations,
            };
            return self.settle_prediction(made, outcome, steps_log);
        }
        let analysis = match self.linearization.factor().same_analysis() {
            Ok(analysis) => analysis,
            Err(error) => {
                self.prediction_failed(
                    step,
                    self.state.load,
                    &SolveError::linear("bifurcation prediction: symbolic analysis")(error),
                );
                return None;
            }
        };
        let tangent = self.linearization.tangent().clone();
        let state = self.state.clone();
        let u_hat = u_hat.to_vec();
        let start = self.options.bifurcation_mode_guess.clone();
        let guess = self.options.bifurcation_load_guess;
        let predict = move || {
            let mut factorizations = 0;
            let load = predict_bifurcation(
                problem,
                &state,
                &u_hat,
                Unshifted::Analysed(Box::new(analysis)),
                &tangent,
                start,
                guess,
                &mut factorizations,
            );
            PredictionOutcome {
                load,
                factorizations,
            }
        };
        self.linearization.statistics.bifurcation_seconds += clock.elapsed().as_secs_f64();
        self.pending = Some(PendingPrediction {
            step,
            record: steps_log.len(),
            load: self.state.load,
            handle: self.scope.spawn(predict),
        });
        None
    }

    /// Waits for the prediction under way, if any, and takes what it gives
    /// ([`Self::settle_prediction`]). The time waited counts as the prediction's. Returns its
    /// load.
    fn collect_prediction(&mut self, steps_log: &mut [AnmStep]) -> Option<f64> {
        let pending = self.pending.take()?;
        let clock = Instant::now();
        let outcome = match pending.handle.join() {
            Ok(outcome) => outcome,
            Err(panic) => std::panic::resume_unwind(panic),
        };
        self.linearization.statistics.bifurcation_seconds += clock.elapsed().as_secs_f64();
        let made = (pending.step, pending.record, pending.load);
        self.settle_prediction(made, outcome, steps_log)
    }

    /// Takes what the prediction made at step `made.0` (whose record goes at `made.1` of the
    /// steps' log, from load `made.2`) gave: its load, also into that record once logged, with
    /// the first logged step since then whose end passes it as the bifurcation's; or a warning
    /// when it failed. Returns the load.
    fn settle_prediction(
        &mut self,
        made: (usize, usize, f64),
        outcome: PredictionOutcome,
        steps_log: &mut [AnmStep],
    ) -> Option<f64> {
        let (step, logged, start_load) = made;
        let statistics = &mut self.linearization.statistics;
        statistics.factorizations += outcome.factorizations;
        statistics.prediction_factorizations += outcome.factorizations;
        match outcome.load {
            Ok(load) => {
                self.prediction = Some(load);
                for record in steps_log.iter_mut().skip(logged) {
                    if record.step == step {
                        record.predicted_bifurcation = Some(load);
                    }
                    let (from, to) = record.load_range;
                    if record.completed && self.bifurcation.is_none() && to >= load && from < load {
                        self.bifurcation = Some((load, record.step));
                    }
                }
                Some(load)
            }
            Err(error) => {
                self.prediction_failed(step, start_load, &error);
                None
            }
        }
    }

    /// Keeps the failure of the prediction at `step` (from `load`) as a warning; it is not
    /// retried at every step.
    fn prediction_failed(&mut self, step: usize, load: f64, error: &SolveError) {
        self.warnings.push(format!(
            "step {step}: bifurcation prediction by linear buckling at load {load:.6e} failed: {error}"
        ));
        self.prediction = Some(f64::INFINITY);
    }

    /// What the step evaluates, and the ranges Padé and the exponential map offered (when
    /// enabled and, for the map, when the series shows a singularity behind the step,
    /// [`singularity_behind`]). A Padé range without bound becomes [`UNBOUNDED_PADE_RANGE`]
    /// times the series' range. The step is lengthened by whichever of the two reaches
    /// further, when it reaches beyond the series' own range.
    fn approximant<'s>(
        &self,
        series: &'s PathSeries,
        orthogonalized: Option<GramSchmidt>,
    ) -> (StepApproximant<'s>, Offered) {
        let tolerance = self.options.series_tolerance;
        let plain = series_step_length(series, tolerance);
        let pade = self
            .options
            .pade
            .then(|| match orthogonalized {
                Some(orthogonalized) => PadeApproximant::orthogonalized(series, orthogonalized),
                None => PadeApproximant::new(series),
            })
            .and_then(Result::ok)
            .map(|p| {
                let range = p.pade_step_length(tolerance);
                (p, range)
            });
        let behind = singularity_behind(series);
        let map = behind
            .filter(|_| self.options.exponential_map)
            .and_then(|radius| ExponentialMap::new(series, radius).ok())
            .map(|map| {
                let range = map.step_length(tolerance);
                (map, range)
            });
        let offered = Offered {
            pade: pade.as_ref().map(|&(_, range)| range),
            map: map.as_ref().map(|&(_, range)| range),
            behind,
        };
        let pade = pade.map(|(pade, range)| {
            let unbounded = !range.is_finite() && plain.is_finite();
            let range = if unbounded {
                UNBOUNDED_PADE_RANGE * plain
            } else {
                range
            };
            (Extension::Pade(pade), range)
        });
        let map = map.map(|(map, range)| (Extension::Map(map), range));
        let mut extensions: Vec<(Extension, f64)> = [pade, map]
            .into_iter()
            .flatten()
            .filter(|&(_, range)| range.is_finite() && range > plain)
            .collect();
        // Longest first; the other is the fallback.
        extensions.sort_by(|x, y| y.1.total_cmp(&x.1));
        let mut extensions = extensions.into_iter();
        let approximant = StepApproximant {
            series,
            plain,
            extension: extensions.next(),
            fallback: extensions.next(),
        };
        (approximant, offered)
    }

    /// The step's end point: the step length ([`Self::first_end`]), then the residual check,
    /// a Riks correction when needed ([`Self::corrected_end`]), or halving. A Padé end that
    /// misses the tolerance is halved towards the series' range first and never corrected: in
    /// the strip of example 2 such an end (range 522 against the series' 54) was corrected in
    /// 2 iterations, but 6 of its 10 interior points missed the tolerance, and the path's last
    /// point overshot the amplitude target 4 h to 6.2 h. An end on the exponential map that
    /// misses its tolerance ([`MAPPED_END_RESIDUAL_FRACTION`]) is halved like a Padé end, or
    /// gives way to the other extension ([`StepApproximant::fallback`]) once that reaches
    /// further than the halved end.
    fn accept_end(
        &mut self,
        step: usize,
        approximant: &mut StepApproximant,
    ) -> Result<AcceptedEnd, SolveError> {
        let tolerance = self.options.residual_tolerance;
        let (mut a, mut hit_max_load) = self.first_end(approximant);
        // Halvings of a series end; shortening a Padé end towards the series' range does not
        // count (it ends there after log2(range / series range) tries, residual checks only).
        let mut halvings = 0;
        while halvings <= MAX_END_HALVINGS {
            let candidate = approximant.evaluate(a);
            let residual = self
                .linearization
                .relative_residual(&candidate.displacement, candidate.load);
            let accepted = match approximant.extension_at(a) {
                Some(Extension::Map(_)) => MAPPED_END_RESIDUAL_FRACTION * tolerance,
                _ => tolerance,
            };
            if residual.is_finite() && residual <= accepted {
                return Ok(AcceptedEnd {
                    state: candidate,
                    residual,
                    corrections: 0,
                    step_length: a,
                    hit_max_load,
                });
            }
            if matches!(approximant.extension_at(a), Some(Extension::Map(_)))
                && approximant
                    .fallback
                    .as_ref()
                    .is_some_and(|&(_, range)| range >= 0.5 * a)
            {
                // The map's end halved would be shorter than the other extension's range: that
                // is tried instead. On the strip's plate (the example's graded 56 × 16 mesh) map
                // ends of 507 and 823 were halved down to the series' 61 and 109, where Padé's
                // 240 and 1273 passed.
                self.linearization.statistics.rejected_steps += 1;
                approximant.extension = approximant.fallback.take();
                (a, hit_max_load) = self.first_end(approximant);
                continue;
            }
            if approximant.extension_at(a).is_some() {
                // A Padé end off the path: the Padé range over-estimated the approximant's
                // accuracy, and the step's interior is no better than its end. It is shortened
                // towards the series' range, not corrected (a corrected end would leave the
                // interior points off the path, and the dense output without them).
                self.linearization.statistics.rejected_steps += 1;
                a = (0.5 * a).max(approximant.plain);
                hit_max_load = false;
                continue;
            }
            // Riks corrector on the arc through the predicted point (works through limit points).
            if residual.is_finite()
                && let Some(end) = self.corrected_end(&candidate, a, hit_max_load)
            {
                return Ok(end);
            }
            self.linearization.statistics.rejected_steps += 1;
            a *= 0.5;
            hit_max_load = false;
            halvings += 1;
        }
        Err(SolveError::Path {
            load: self.state.load,
            message: format!(
                "step {step}: residual above tolerance {tolerance:.1e} even after {MAX_END_HALVINGS} halvings and arc-length corrections"
            ),
        })
    }

    /// The first end tried: the approximant's range (capped by `max_step_length`, 1 when
    /// both are infinite), shortened to land on `max_load` when the step passes it; and whether
    /// it was.
    fn first_end(&self, approximant: &StepApproximant) -> (f64, bool) {
        let options = self.options;
        let mut a = approximant.range();
        if !a.is_finite() {
            a = if options.max_step_length.is_finite() {
                options.max_step_length
            } else {
                1.0
            };
        }
        a = a.min(options.max_step_length);
        if let Some(max_load) = options.max_load
            && approximant.evaluate(a).load >= max_load
            && self.state.load < max_load
        {
            let a = parameter_at_load(|a| approximant.evaluate(a).load, a, max_load);
            return (a, true);
        }
        (a, false)
    }

    /// The Riks correction of a candidate end off the path, on the arc through it about the
    /// step's start ([`correct_on_arc`], to `residual_tolerance / 100`): the end when the
    /// correction converged to the residual tolerance.
    fn corrected_end(
        &mut self,
        candidate: &PathState,
        step_length: f64,
        hit_max_load: bool,
    ) -> Option<AcceptedEnd> {
        let options = self.options;
        let corrector = ArcCorrectorOptions {
            tolerance: options.residual_tolerance * 1e-2,
            max_iterations: options.corrector.max_iterations,
            load_scale: 1.0,
            constraint: ArcLengthConstraint::Linearized,
        };
        let corrected =
            correct_on_arc(&mut self.linearization, &self.state, candidate, &corrector).ok()?;
        self.linearization.statistics.corrections += 1;
        (corrected.relative_residual <= options.residual_tolerance).then_some(AcceptedEnd {
            state: corrected.state,
            residual: corrected.relative_residual,
            corrections: corrected.iterations,
            step_length,
            hit_max_load,
        })
    }

    /// The step's interior points ([`interior_points`] on `approximant`, over a step of length
    /// `length`); only those at the residual tolerance are reported. Returns the path
    /// parameter of the last point reported (0, the step's start, when none was), or the
    /// observer's stop with the parameters of the point reported before it and of its own.
    fn dense_output(
        &mut self,
        step: usize,
        interior: Vec<InteriorPoint>,
        (approximant, length): (&StepApproximant, f64),
        predicted: Option<f64>,
        observer: &mut dyn FnMut(&PathEvent) -> PathControl,
    ) -> Result<f64, (PathStop, (f64, f64))> {
        // The parameter of the last point reported: the step's start, then each interior
        // point's (equally spaced over the step, `interior_points`).
        let mut reported = 0.0;
        let count = interior.len();
        let evaluate = |a: f64| approximant.evaluate(a);
        for (k, (inner, residual)) in interior.into_iter().enumerate() {
            if residual.is_nan() || residual > self.options.residual_tolerance {
                continue;
            }
            let a = length * (k + 1) as f64 / (count + 1) as f64;
            let event = PathEvent {
                step,
                interior: true,
                state: &inner,
                relative_residual: residual,
                predicted_bifurcation: predicted,
                on_step: Some(OnStep {
                    parameter: a,
                    previous: reported,
                    evaluate: &evaluate,
                }),
            };
            if observer(&event) == PathControl::Stop {
                self.linearization.statistics.steps = step;
                self.state = inner;
                return Err((PathStop::Observer, (reported, a)));
            }
            reported = a;
        }
        Ok(reported)
    }
}

/// A point inside a step and its relative residual.
type InteriorPoint = (PathState, f64);

/// The `count` equally spaced interior points of a step of length `length` on `approximant`,
/// each with its relative residual ([`Problem::relative_residual`]), and the seconds taken.
fn interior_points<M: EnergyModel>(
    problem: &Problem<M>,
    approximant: &StepApproximant,
    length: f64,
    count: usize,
) -> (Vec<InteriorPoint>, f64) {
    let clock = Instant::now();
    let points = (1..=count)
        .map(|k| {
            let inner = approximant.evaluate(length * k as f64 / (count + 1) as f64);
            let residual = problem.relative_residual(&inner.displacement, inner.load);
            (inner, residual)
        })
        .collect();
    (points, clock.elapsed().as_secs_f64())
}

/// The shift $`\mu_s`$ of a bifurcation prediction about `load` towards `load_guess`
/// ([`predict_bifurcation`]); `None` without a guess ahead.
fn prediction_shift(load_guess: Option<f64>, load: f64) -> Option<f64> {
    load_guess
        .map(|guess| LOCAL_SHIFT * (guess - load))
        .filter(|shift| shift.is_finite() && *shift > 0.0)
}

/// The factorisation of $`K_t`$ a bifurcation prediction falls back on ([`predict_bifurcation`]).
enum Unshifted<'f> {
    /// $`K_t`$ factorised already (the one at a previous step's start).
    Factorized(&'f SparseFactorization),
    /// An unfactorised factorisation of the same analysis ([`SparseFactorization::same_analysis`]):
    /// the shifted tangent's, then $`K_t`$'s when the shifted analysis does not decide (one
    /// factorisation more, counted) — what a prediction on its own thread uses, the path's own
    /// factorisation being the next step's by then.
    Analysed(Box<SparseFactorization>),
}

/// Smallest bifurcation load ahead, from linear buckling about `state` along the path tangent
/// $`dU/d\lambda = \hat U`$: $`(K_t + \mu\,\partial_\lambda K_t)\varphi = 0`$,
/// $`\lambda_b = \lambda + \mu`$. `tangent` must be $`K_t`$ at `state` and `unshifted` its
/// factorisation or one to make it in; `start` warm-starts the eigen-solver. The
/// factorisations it makes are added to `factorizations`.
///
/// **Shifted towards a guess.** With a guess $`\lambda_g > \lambda`$ of the bifurcation load
/// (the threshold of a linear buckling analysis), the eigen-solve is first done about
/// $`\mu_s = `$ [`LOCAL_SHIFT`]$`\,(\lambda_g - \lambda)`$: $`A_s = K_t + \mu_s B`$ is factorised
/// and, when it has no negative pivot, the smallest positive $`\nu`$ of
/// $`(A_s + \nu B)\varphi = 0`$ gives $`\mu = \mu_s + \nu`$. No $`\mu \in (0, \mu_s]`$ is
/// missed: $`K_t + \mu B`$ is a convex combination of the positive definite $`K_t`$ and
/// $`A_s`$ there. Shift-invert about $`\mu_s`$ separates the wanted load from the next, and
/// the prediction takes 0.11 s instead of 0.17–0.19 s (28 operator applications unshifted;
/// example 1 at 40 × 20), for one more factorisation. When the shifted
/// factorisation or eigen-solve fails, or $`A_s`$ is indefinite (the guess is beyond this
/// path's bifurcation), the unshifted analysis decides, and reports its own failure.
#[allow(clippy::too_many_arguments)]
fn predict_bifurcation<M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    u_hat: &[f64],
    unshifted: Unshifted<'_>,
    tangent: &SparseMatrix,
    start: Option<Vec<f64>>,
    load_guess: Option<f64>,
    factorizations: &mut usize,
) -> Result<f64, SolveError> {
    let mut b = problem.new_matrix();
    problem.tangent_derivative_into(&state.displacement, state.load, u_hat, 1.0, &mut b);
    let options = BucklingOptions {
        tolerance: 1e-8,
        start,
        ..BucklingOptions::default()
    };
    let mut unshifted = unshifted;
    if let Some(shift) = prediction_shift(load_guess, state.load) {
        let mut shifted = tangent.clone();
        for (a, &b) in shifted.values.iter_mut().zip(&b.values) {
            *a += shift * b;
        }
        // The analysed factorisation given, else a new one of the factorised tangent's analysis.
        let mut made;
        let shifted_factor = match &mut unshifted {
            Unshifted::Analysed(factor) => Some(&mut **factor),
            Unshifted::Factorized(factor) => {
                made = factor.same_analysis().ok();
                made.as_mut()
            }
        };
        if let Some(shifted_factor) = shifted_factor {
            *factorizations += 1;
            let ahead = (shifted_factor.factorize(&shifted).is_ok()
                && shifted_factor.negative_pivots() == Some(0))
            .then(|| smallest_positive_buckling(&shifted, shifted_factor, &b, &options).ok())
            .flatten()
            .and_then(|solution| solution.modes.first().map(|m| m.load_factor));
            if let Some(nu) = ahead {
                return Ok(state.load + shift + nu);
            }
        }
    }
    let factor: &SparseFactorization = match &mut unshifted {
        Unshifted::Factorized(factor) => factor,
        Unshifted::Analysed(factor) => {
            *factorizations += 1;
            factor.factorize(tangent).map_err(SolveError::linear(
                "bifurcation prediction: factorisation of the tangent",
            ))?;
            factor
        }
    };
    let solution = smallest_positive_buckling(tangent, factor, &b, &options)
        .map_err(SolveError::linear("bifurcation prediction: eigen-solver"))?;
    solution
        .modes
        .first()
        .map(|m| state.load + m.load_factor)
        .ok_or_else(|| SolveError::Buckling("no positive buckling load ahead".into()))
}
