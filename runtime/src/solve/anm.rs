//! Asymptotic Numerical Method (ANM): path following by truncated power series (THEORY.md §10).
//!
//! From a regular point $`(U_0,\lambda_0)`$ the branch is expanded as
//! $`U(a) = U_0 + \sum_{n=1}^N a^n U_n`$, $`\lambda(a) = \lambda_0 + \sum_{n=1}^N a^n\lambda_n`$ in
//! the path parameter $`a = \langle U - U_0, U_1\rangle + (\lambda-\lambda_0)\lambda_1`$.
//! With $`K_t = \partial R/\partial U(U_0,\lambda_0)`$ factorised **once per step** and
//! $`F = -\partial R/\partial\lambda`$:
//! * order 1: $`K_t\hat U = F`$, $`\lambda_1 = \pm(1 + \|\hat U\|^2)^{-1/2}`$, $`U_1 = \lambda_1\hat U`$;
//! * order $`n\ge2`$: $`K_t\hat U_n = F^{nl}_n`$ with $`F^{nl}_n`$ minus the $`a^n`$ coefficient of
//!   $`R(\sum_{k<n} a^kU_k, \sum_{k<n}a^k\lambda_k)`$ — obtained by running the model's generated
//!   residual kernels on truncated series ([`Series`]); no model-specific code — then
//!   $`\lambda_n = -\lambda_1\langle\hat U_n, U_1\rangle`$ and $`U_n = \lambda_n\hat U + \hat U_n`$.
//!
//! Step length $`a_{\max} = (\epsilon\|U_1\|/\|U_N\|)^{1/(N-1)}`$ or, optionally, the Padé
//! approximants' longer range. The residual is checked at the end of every step; a Riks
//! (arc-length) correction brings it back under the tolerance when needed (or the step is
//! halved).
//!
//! Bifurcations: at every step start the solver predicts the nearest bifurcation load by linear
//! buckling about the current point along the path tangent (one shift-invert eigen-solve with
//! the step's factorised tangent). Predictions are trusted while two successive ones agree to
//! [`PREDICTION_AGREEMENT`] (the path is still on its fundamental branch); a bifurcation is
//! reported, with the last trusted prediction as its load, at the step whose end passes it.

use super::error::SolveError;
use super::newton::NewtonOptions;
use super::path::{PathControl, PathEvent, PathResult, PathState, PathStatistics, PathStop};
use super::riks::{ArcLengthConstraint, RiksOptions, correct_on_arc};
use crate::fem::TaylorTape;
use crate::linear::eigen::{BucklingOptions, smallest_positive_buckling};
use crate::linear::factor::SparseFactorization;
use crate::linear::pattern::SparseMatrix;
use crate::model::EnergyModel;
use crate::problem::Problem;
use crate::series::{
    MAX_SERIES_LEN, PadeApproximant, PathSeries, Series, geometric_ratio, series_step_length,
};
use std::time::Instant;

/// Relative agreement of two successive bifurcation predictions for the later one to be trusted.
pub const PREDICTION_AGREEMENT: f64 = 1e-5;

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
    /// Use Padé approximants (common denominator) for the step range and evaluation.
    pub pade: bool,
    /// Points evaluated inside each step (dense output).
    pub interior_points: usize,
    /// Iteration cap of the corrector (a Riks correction on the arc through the step's end
    /// point, to `residual_tolerance / 100`); its tolerance field is not used.
    pub corrector: NewtonOptions,
    /// Predict the bifurcation load from each step's tangent (one shift-invert eigen-solve per
    /// step with the already factorised tangent).
    pub predict_bifurcation: bool,
    /// Cap on the path parameter of one step; when the series is exactly polynomial (no
    /// finite range) the step uses this value, or 1 if it is infinite.
    pub max_step_length: f64,
}

impl Default for AnmOptions {
    fn default() -> Self {
        AnmOptions {
            order: 20,
            series_tolerance: 1e-7,
            residual_tolerance: 1e-6,
            max_steps: 200,
            max_load: None,
            pade: false,
            interior_points: 10,
            corrector: NewtonOptions {
                tolerance: 1e-9,
                max_iterations: 12,
            },
            predict_bifurcation: true,
            max_step_length: f64::INFINITY,
        }
    }
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
    /// Range Padé allowed (when enabled).
    pub pade_step_length: Option<f64>,
    /// Relative residual at the end point before any correction.
    pub end_residual: f64,
    /// Newton iterations of the correction (0 = none needed).
    pub correction_iterations: usize,
    /// Radius of convergence estimated from a geometric tail of the series, if any.
    pub geometric_radius: Option<f64>,
    /// Bifurcation load predicted by linear buckling about the step's start.
    pub predicted_bifurcation: Option<f64>,
}

/// Order 1 of a step: $`\hat U = K_t^{-1}F`$, $`\lambda_1 = \pm(1+\|\hat U\|^2)^{-1/2}`$, the sign
/// chosen so that $`(U_1, \lambda_1)`$ continues `previous_direction` (the path tangent at the
/// end of the previous step), else $`\lambda_1 > 0`$. Returns $`(\hat U, \lambda_1)`$.
fn first_order<M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    factor: &SparseFactorization,
    previous_direction: Option<(&[f64], f64)>,
) -> Result<(Vec<f64>, f64), SolveError> {
    let mut u_hat: Vec<f64> = problem
        .load_derivative(&state.displacement, state.load)
        .iter()
        .map(|v| -v)
        .collect();
    factor
        .solve_in_place(&mut u_hat)
        .map_err(SolveError::linear(format!(
            "ANM order 1 at load {:.6e}",
            state.load
        )))?;
    let norm2: f64 = u_hat.iter().map(|v| v * v).sum();
    let mut lambda1 = 1.0 / (1.0 + norm2).sqrt();
    if let Some((u_prev, l_prev)) = previous_direction {
        let dot: f64 = u_hat.iter().zip(u_prev).map(|(a, b)| a * b).sum::<f64>() + l_prev;
        if dot < 0.0 {
            lambda1 = -lambda1;
        }
    }
    Ok((u_hat, lambda1))
}

/// Order $`k \ge 2`$ from its right-hand side $`F^{nl}_k`$ (overwritten): solve
/// $`K_t\hat U_k = F^{nl}_k`$, then $`\lambda_k = -\lambda_1\langle\hat U_k, U_1\rangle`$,
/// $`U_k = \hat U_k + \lambda_k\hat U`$.
fn higher_order(
    factor: &SparseFactorization,
    mut rhs: Vec<f64>,
    u_hat: &[f64],
    u1: &[f64],
    lambda1: f64,
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
    let dot: f64 = rhs.iter().zip(u1).map(|(a, b)| a * b).sum();
    let lambda_k = -lambda1 * dot;
    for (r, h) in rhs.iter_mut().zip(u_hat) {
        *r += lambda_k * h;
    }
    Ok((rhs, lambda_k))
}

/// Computes the series of one step at `state`, whose tangent `factor` holds, with the models'
/// Taylor-mode kernels: per order one right-hand side from the tape ($`O(k)`$ per product at
/// every quadrature point), one solve, one commit. `tape` must hold at least `order` orders.
/// Returns the path series (orders 0..=N) and $`\hat U`$.
pub fn compute_series<M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    factor: &SparseFactorization,
    order: usize,
    previous_direction: Option<(&[f64], f64)>,
    tape: &mut TaylorTape,
) -> Result<(PathSeries, Vec<f64>), SolveError> {
    let order = order.clamp(2, tape.highest_order());
    let (u_hat, lambda1) = first_order(problem, state, factor, previous_direction)?;
    let u1: Vec<f64> = u_hat.iter().map(|v| v * lambda1).collect();
    problem.taylor_start(&state.displacement, state.load, tape);
    // Order 1: the prediction is zero (every coefficient of order 1 is linear in U_1).
    problem.taylor_residual(1, tape);
    problem.taylor_commit(1, &u1, lambda1, tape);
    let mut displacement = vec![state.displacement.clone(), u1];
    let mut load = vec![state.load, lambda1];
    for k in 2..=order {
        let rhs: Vec<f64> = problem
            .taylor_residual(k, tape)
            .iter()
            .map(|r| -r)
            .collect();
        let (u_k, lambda_k) = higher_order(
            factor,
            rhs,
            &u_hat,
            &displacement[1],
            lambda1,
            k,
            state.load,
        )?;
        problem.taylor_commit(k, &u_k, lambda_k, tape);
        displacement.push(u_k);
        load.push(lambda_k);
    }
    let series = PathSeries::new(displacement, load).map_err(|e| SolveError::Path {
        load: state.load,
        message: format!("series: {e}"),
    })?;
    Ok((series, u_hat))
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
    let (u_hat, lambda1) = first_order(problem, state, factor, previous_direction)?;
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

fn evaluate(series: &PathSeries, pade: Option<&PadeApproximant>, a: f64) -> PathState {
    let (displacement, load) = match pade {
        Some(p) => p.evaluate(a),
        None => series.evaluate(a),
    };
    PathState { displacement, load }
}

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
    let begin = Instant::now();
    let mut statistics = PathStatistics::default();
    let mut matrix = problem.new_matrix();
    let mut tape = problem
        .assembler
        .taylor_tape(options.order.clamp(2, MAX_SERIES_LEN - 2));
    let mut state = start;
    let mut bifurcation = None;
    let mut previous: Option<(Vec<f64>, f64)> = None;
    // Bifurcation predictions are trusted while successive ones agree (the path is still on its
    // fundamental branch, where linear buckling about the current point is accurate).
    let mut last_prediction: Option<f64> = None;
    let mut trusted_prediction: Option<f64> = None;
    let finish = |state: PathState, mut statistics: PathStatistics, stop: PathStop, bifurcation| {
        statistics.total_seconds = begin.elapsed().as_secs_f64();
        PathResult {
            last: state,
            statistics,
            stop,
            bifurcation,
        }
    };
    let start_residual = problem.relative_residual(&state.displacement, state.load);
    statistics.residual_assemblies += 1;
    if observer(&PathEvent {
        step: 0,
        interior: false,
        state: &state,
        relative_residual: start_residual,
        predicted_bifurcation: None,
    }) == PathControl::Stop
    {
        return finish(state, statistics, PathStop::Observer, bifurcation);
    }
    for step in 1..=options.max_steps {
        // One tangent factorisation per step.
        let t = Instant::now();
        problem.tangent_into(&state.displacement, state.load, &mut matrix);
        statistics.tangent_assemblies += 1;
        statistics.assembly_seconds += t.elapsed().as_secs_f64();
        let t = Instant::now();
        if let Err(e) = factor.factorize(&matrix) {
            let error = SolveError::linear(format!(
                "ANM step {step} at load {:.6e}: tangent factorisation",
                state.load
            ))(e);
            return finish(state, statistics, PathStop::Failed(error), bifurcation);
        }
        statistics.factorizations += 1;
        statistics.factorization_seconds += t.elapsed().as_secs_f64();

        let t = Instant::now();
        let direction = previous.as_ref().map(|(u, l)| (u.as_slice(), *l));
        let (series, u_hat) =
            match compute_series(problem, &state, factor, options.order, direction, &mut tape) {
                Ok(s) => s,
                Err(e) => return finish(state, statistics, PathStop::Failed(e), bifurcation),
            };
        statistics.series_assemblies += series.order() - 1;
        statistics.series_seconds += t.elapsed().as_secs_f64();

        // Bifurcation predicted by linear buckling about this point along the path tangent.
        let predicted = if options.predict_bifurcation && series.load[1] > 0.0 {
            let t = Instant::now();
            let p = predict_bifurcation(problem, &state, &u_hat, factor, &matrix);
            statistics.bifurcation_seconds += t.elapsed().as_secs_f64();
            p
        } else {
            None
        };

        let plain = series_step_length(&series, options.series_tolerance);
        let pade = if options.pade {
            PadeApproximant::new(&series).ok()
        } else {
            None
        };
        let pade_length = pade
            .as_ref()
            .map(|p| p.pade_step_length(options.series_tolerance));
        let mut a = match pade_length {
            Some(l) if l.is_finite() && l > plain => l,
            _ => plain,
        };
        let evaluator = |a: f64| {
            let use_pade = pade_length.is_some_and(|l| l > plain && a > plain);
            evaluate(&series, if use_pade { pade.as_ref() } else { None }, a)
        };
        if !a.is_finite() {
            a = if options.max_step_length.is_finite() {
                options.max_step_length
            } else {
                1.0
            };
        }
        a = a.min(options.max_step_length);
        let mut hit_max_load = false;
        if let Some(max_load) = options.max_load
            && evaluator(a).load >= max_load
            && state.load < max_load
        {
            {
                // Bisection for λ(a*) = max_load.
                let (mut lo, mut hi) = (0.0, a);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if evaluator(mid).load < max_load {
                        lo = mid
                    } else {
                        hi = mid
                    }
                }
                a = hi;
                hit_max_load = true;
            }
        }
        // End point, residual check, correction or halving.
        let mut attempts = 0;
        let (end, end_residual, corrections) = loop {
            let candidate = evaluator(a);
            let residual = problem.relative_residual(&candidate.displacement, candidate.load);
            statistics.residual_assemblies += 1;
            if residual.is_finite() && residual <= options.residual_tolerance {
                break (candidate, residual, 0);
            }
            // Riks corrector on the arc through the predicted point (works through limit points).
            let corrected = if residual.is_finite() {
                let riks = RiksOptions {
                    tolerance: options.residual_tolerance * 1e-2,
                    max_iterations: options.corrector.max_iterations,
                    load_scale: 1.0,
                    constraint: ArcLengthConstraint::Linearized,
                    ..RiksOptions::default()
                };
                correct_on_arc(problem, factor, &state, &candidate, &riks, &mut statistics).ok()
            } else {
                None
            };
            if let Some(c) = corrected {
                statistics.corrections += 1;
                if c.relative_residual <= options.residual_tolerance {
                    break (c.state, c.relative_residual, c.iterations);
                }
            }
            statistics.rejected_steps += 1;
            attempts += 1;
            a *= 0.5;
            hit_max_load = false;
            if attempts > 12 {
                let error = SolveError::Path {
                    load: state.load,
                    message: format!(
                        "step {step}: residual {residual:.3e} above tolerance {:.1e} even after 12 halvings and arc-length corrections",
                        options.residual_tolerance
                    ),
                };
                return finish(state, statistics, PathStop::Failed(error), bifurcation);
            }
        };
        // Interior points come from the series (their residual is computed and reported).
        for k in 1..=options.interior_points {
            let s = a * k as f64 / (options.interior_points + 1) as f64;
            let inner = evaluator(s);
            let residual = problem.relative_residual(&inner.displacement, inner.load);
            statistics.residual_assemblies += 1;
            if residual.is_nan() || residual > options.residual_tolerance {
                // Only points that meet the tolerance are accepted (possible near the end of a
                // step whose end point needed a correction).
                continue;
            }
            let control = observer(&PathEvent {
                step,
                interior: true,
                state: &inner,
                relative_residual: residual,
                predicted_bifurcation: predicted,
            });
            if control == PathControl::Stop {
                statistics.steps = step;
                return finish(inner, statistics, PathStop::Observer, bifurcation);
            }
        }
        if let Some(p) = predicted {
            if last_prediction.is_some_and(|q| (p - q).abs() <= PREDICTION_AGREEMENT * p.abs()) {
                trusted_prediction = Some(p);
            }
            last_prediction = Some(p);
            let detected = trusted_prediction.unwrap_or(p);
            if bifurcation.is_none() && end.load >= detected {
                bifurcation = Some((detected, step));
            }
        }
        steps_log.push(AnmStep {
            step,
            load_range: (state.load, end.load),
            step_length: a,
            series_step_length: plain,
            pade_step_length: pade_length,
            end_residual,
            correction_iterations: corrections,
            geometric_radius: geometric_ratio(&series),
            predicted_bifurcation: predicted,
        });
        statistics.steps = step;
        // The next step continues the path tangent at this step's end (not at its start: past a
        // sharp turn the two can point apart).
        previous = Some(series.evaluate_derivative(a));
        state = end;
        if observer(&PathEvent {
            step,
            interior: false,
            state: &state,
            relative_residual: end_residual,
            predicted_bifurcation: predicted,
        }) == PathControl::Stop
        {
            return finish(state, statistics, PathStop::Observer, bifurcation);
        }
        if hit_max_load {
            return finish(state, statistics, PathStop::MaxLoad, bifurcation);
        }
    }
    finish(state, statistics, PathStop::MaxSteps, bifurcation)
}

/// Smallest bifurcation load ahead, from linear buckling about `state` along the path tangent
/// $`dU/d\lambda = \hat U`$: $`(K_t + \mu\,\partial_\lambda K_t)\varphi = 0`$, $`\lambda_b = \lambda + \mu`$.
fn predict_bifurcation<M: EnergyModel>(
    problem: &Problem<M>,
    state: &PathState,
    u_hat: &[f64],
    factor: &SparseFactorization,
    tangent: &SparseMatrix,
) -> Option<f64> {
    let mut b = problem.new_matrix();
    problem.tangent_derivative_into(&state.displacement, state.load, u_hat, 1.0, &mut b);
    let options = BucklingOptions::default();
    smallest_positive_buckling(tangent, factor, &b, &options)
        .ok()
        .and_then(|s| s.modes.first().map(|m| state.load + m.load_factor))
}
