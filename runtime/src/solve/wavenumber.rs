//! The critical load minimised over a model parameter — the wavenumber $`Q`$ of the envelope
//! models, whose threshold $`\lambda_c(Q)`$ selects the wrinkle wavelength (THEORY.md §8).
//!
//! **Global, then local.** $`\lambda_c(Q)`$ is first sampled on a logarithmic scan over the whole
//! range where the caller says the model is valid (a local bracket around a guess can miss the
//! minimum by orders of magnitude when the tension is tiny or huge), then refined by successive
//! parabolic interpolation in $`\ln Q`$ from the best scan point and its neighbours (Brent's
//! method in the best bracket when a neighbour was rejected or the best point is an end of the
//! range). With a guess of the minimiser ([`WavenumberSearchOptions::local_guess`]) the scan is
//! skipped unless the minimum is not bracketed near the guess. Each evaluation is a linear buckling analysis; it is
//! **warm-started** from its neighbour — the pre-buckling state as Newton's initial guess, the
//! mode as the Lanczos start vector — so a scan costs a small multiple of one analysis.
//!
//! **Scan from short to long wavelengths.** The scan starts at the largest $`Q`$ (cheap
//! analyses: the modes are short and the eigen-solver converges in a few iterations) and ends
//! two points past the lowest value: $`\lambda_c(Q)`$ of the envelope models has a single
//! minimum (eq. (42) is a ratio of a quadratic and a linear function of $`Q^2`$), and the
//! long-wavelength end, where the analyses are expensive (on the strip of example 2 the
//! compressed zone is small and Lanczos needs hundreds of iterations) or rejected, is only
//! reached when $`\lambda_c`$ keeps falling there.
//!
//! **Shifted analyses.** Each analysis after the first linearises about
//! $`\sigma = `$ [`WavenumberSearchOptions::shift_fraction`] times the last accepted critical
//! load instead of 0: shift-invert about $`\sigma`$ makes the wanted load factor the dominant
//! end of the spectrum (on the strip of example 2 the unshifted Lanczos needs hundreds of
//! iterations). The shift is used only when the tangent at $`\sigma`$ is positive definite (no
//! negative pivot in its factorisation): the pre-buckling tangent is affine in $`\lambda`$ and
//! positive definite at 0, so by Sylvester's law of inertia no critical load lies in
//! $`(0, \sigma]`$ and the smallest positive load factor about $`\sigma`$ is still the first
//! critical load. Otherwise the evaluation is redone about the caller's reference load (in the
//! wide scan, where $`\lambda_c`$ can fall by more than the margin between neighbours, after a
//! second try at 0.3 times the last load). The first evaluation is shifted too when the caller has a guess
//! ([`WavenumberSearchOptions::load_guess`], e.g. the threshold on a coarser mesh).
//! In the local refinement, where neighbours are a few per cent apart in $`Q`$ and $`\lambda_c`$
//! differs by far less than a per cent, the shift is first 0.98 times the last load
//! (`LOCAL_SHIFT`, then the usual fraction): shift-invert maps the wanted load factor to
//! $`1/(\lambda_c - \sigma)`$, fifty times the next one's instead of a few times, and Lanczos
//! converges in 8–10 operator applications instead of 16–20 (example 1 at 40 × 20).
//!
//! **Accuracy the load can carry.** $`\lambda_c(Q)`$ is flat to second order at its minimum: a
//! relative error $`\delta`$ in $`Q`$ changes $`\lambda_c`$ by $`O(\delta^2)`$, so $`Q`$ is located to
//! [`WavenumberSearchOptions::relative_tolerance`] ($`10^{-4}`$ by default, $`\lambda_c`$ to about
//! $`10^{-8}`$) and no further.
//!
//! **Validity.** Below some $`Q`$ an envelope model stops being strongly elliptic at its own
//! critical load (the X-diffusion $`6DQ^2 - \lambda`$ of eq. (32) turns negative); the lowest
//! discrete eigenvalue is then a mesh-scale mode, not a threshold. Such evaluations are rejected
//! (Legendre–Hadamard check of the generated tangent over more than
//! [`WavenumberSearchOptions::max_violated_fraction`] of the area) and recorded with the reason.

use super::brent::{local_parabolic_minimum, minimize_scalar, parabolic_refinement};
use super::buckling::{LinearBuckling, LinearBucklingOptions, linear_buckling};
use super::ellipticity::{EllipticityReport, legendre_hadamard};
use super::error::SolveError;
use crate::linear::factor::SparseFactorization;
use crate::model::EnergyModel;
use crate::problem::Problem;

/// Settings of [`minimise_critical_load`].
#[derive(Clone, Debug)]
pub struct WavenumberSearchOptions {
    /// Name of the model parameter to vary.
    pub parameter: &'static str,
    /// Smallest and largest values to scan (the range where the model is valid).
    pub range: (f64, f64),
    /// Log-spaced scan points over `range` (at least 3).
    pub scan_points: usize,
    /// Relative accuracy of the minimiser in the parameter.
    pub relative_tolerance: f64,
    /// Area fraction where the Legendre–Hadamard condition may fail at a critical load before
    /// the evaluation is rejected as a mesh-scale mode. Failures at isolated points (stress
    /// singularities at clamped–free corners) do not disqualify a wavenumber.
    pub max_violated_fraction: f64,
    /// Settings of each linear buckling analysis.
    pub buckling: LinearBucklingOptions,
    /// Shift of each analysis after the first, as a fraction of the last accepted critical
    /// load (see the module documentation); 0 disables shifting.
    pub shift_fraction: f64,
    /// A guess of the critical load (e.g. from a coarser mesh) that lets the first evaluation
    /// be shifted too.
    pub load_guess: Option<f64>,
    /// Eigen-solver tolerance (relative Ritz residual) of the scan's analyses, which only rank
    /// wavenumbers: the load factor's error is about the square of the residual over the
    /// relative gap, so $`10^{-5}`$ gives $`\lambda_c`$ to about $`10^{-9}`$.
    pub scan_eigen_tolerance: f64,
    /// A guess of the minimiser (e.g. from a coarser mesh): the search is then local,
    /// successive parabolic interpolation in $`\ln Q`$ from the guess and its neighbours at
    /// the relative distance [`LocalGuess::relative_step`], and falls back to the scan over
    /// `range` only when the minimum is not bracketed near the guess.
    pub local_guess: Option<LocalGuess>,
    /// Whether a local search that brackets no minimum near its guess falls back to the scan
    /// over `range` (default); when `false` it fails at once with [`SolveError::Buckling`], so
    /// that a caller whose guess may belong to another model can try a wider search itself.
    pub scan_after_local: bool,
}

/// Where a local search starts (see [`WavenumberSearchOptions::local_guess`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LocalGuess {
    /// The guessed minimiser.
    pub parameter: f64,
    /// Relative distance of the first neighbours (a few times the guess's uncertainty).
    pub relative_step: f64,
}

impl Default for WavenumberSearchOptions {
    fn default() -> Self {
        let mut buckling = LinearBucklingOptions::default();
        // The load factor's error is about the square of the Ritz residual.
        buckling.eigen.tolerance = 1e-8;
        WavenumberSearchOptions {
            parameter: "wavenumber",
            range: (1e-3, 1e3),
            scan_points: 25,
            relative_tolerance: 1e-4,
            max_violated_fraction: 1e-2,
            buckling,
            shift_fraction: 0.8,
            load_guess: None,
            scan_eigen_tolerance: 1e-5,
            local_guess: None,
            scan_after_local: true,
        }
    }
}

/// One evaluation of $`\lambda_c`$ during the search.
#[derive(Clone, Debug, PartialEq)]
pub struct WavenumberEvaluation {
    /// Parameter value.
    pub parameter: f64,
    /// Critical load, when the evaluation is accepted.
    pub critical_load: Option<f64>,
    /// Why it was rejected (loss of ellipticity, no buckling load, solver failure).
    pub rejected: Option<String>,
    /// Operator applications of the eigen-solver.
    pub eigen_iterations: usize,
    /// Whether this evaluation belongs to the initial scan (else to the refinement).
    pub scan: bool,
    /// Whether it was done on a coarser mesh than the problem's (a caller's two-level search
    /// marks its first level; [`minimise_critical_load`] itself never does).
    pub coarse: bool,
}

/// Outcome of [`minimise_critical_load`].
#[derive(Clone, Debug)]
pub struct WavenumberSearch {
    /// The minimising parameter value.
    pub parameter: f64,
    /// The linear buckling analysis at that value (the model in `problem` is left set to it).
    pub buckling: LinearBuckling,
    /// Legendre–Hadamard check at the critical load.
    pub ellipticity: EllipticityReport,
    /// The load `buckling` linearised about (its pre-buckling state is at this load).
    pub reference_load: f64,
    /// Every evaluation, in order.
    pub evaluations: Vec<WavenumberEvaluation>,
}

/// The state at the first critical load: the pre-buckling state extrapolated linearly from the
/// reference load to $`\lambda_c`$.
pub fn state_at_critical_load(buckling: &LinearBuckling, reference_load: f64) -> Vec<f64> {
    buckling.state_at(reference_load, buckling.critical_loads[0])
}

/// Legendre–Hadamard check of `problem` at the first critical load of `buckling`.
pub fn ellipticity_at_critical_load<M: EnergyModel>(
    problem: &Problem<M>,
    buckling: &LinearBuckling,
    reference_load: f64,
) -> EllipticityReport {
    let state = state_at_critical_load(buckling, reference_load);
    legendre_hadamard(problem, &state, buckling.critical_loads[0])
}

/// Sets the model parameter `name` of `problem` to `value` (same model type: pattern, element
/// values and symbolic factorisation stay valid).
pub fn set_model_parameter<M: EnergyModel>(
    problem: &mut Problem<M>,
    name: &str,
    value: f64,
) -> Result<(), SolveError> {
    let mut model = problem.assembler.model().clone();
    model
        .set_parameter(name, value)
        .map_err(SolveError::Buckling)?;
    problem.assembler.set_model(model);
    Ok(())
}

/// The search state: warm starts and the best analysis so far.
struct Searcher<'a, M: EnergyModel> {
    problem: &'a mut Problem<M>,
    factor: &'a mut SparseFactorization,
    options: &'a WavenumberSearchOptions,
    observer: &'a mut dyn FnMut(&WavenumberEvaluation),
    evaluations: Vec<WavenumberEvaluation>,
    /// The last analysis and the load it linearised about: the next one starts Newton from its
    /// pre-buckling state extrapolated to its own reference load (exact on a linear fundamental
    /// path, so that Newton needs no iteration) and Lanczos from its mode.
    warm: Option<(LinearBuckling, f64)>,
    /// The last accepted critical load (the next evaluation's shift is a fraction of it).
    last_load: Option<f64>,
    best: Option<(f64, LinearBuckling, EllipticityReport, f64)>,
    scanning: bool,
}

impl<M: EnergyModel> Searcher<'_, M> {
    /// $`\lambda_c`$ at `parameter`, or $`+\infty`$ when rejected (reason recorded).
    fn evaluate(&mut self, parameter: f64) -> f64 {
        let mut record = WavenumberEvaluation {
            parameter,
            critical_load: None,
            rejected: None,
            eigen_iterations: 0,
            scan: self.scanning,
            coarse: false,
        };
        let value = match self.analyse(parameter) {
            Ok((buckling, ellipticity, reference)) => {
                record.eigen_iterations = buckling.eigen_iterations;
                let load = buckling.critical_loads[0];
                self.warm = Some((buckling.clone(), reference));
                if ellipticity.violated_fraction > self.options.max_violated_fraction {
                    record.rejected = Some(format!(
                        "not elliptic at its critical load {load:.6e} over {:.1} % of the area (worst at ({:.4}, {:.4}), field `{}`): a mesh-scale mode, not a threshold",
                        100.0 * ellipticity.violated_fraction,
                        ellipticity.location[0],
                        ellipticity.location[1],
                        ellipticity.field
                    ));
                    f64::INFINITY
                } else {
                    record.critical_load = Some(load);
                    self.last_load = Some(load);
                    if self
                        .best
                        .as_ref()
                        .is_none_or(|(_, b, _, _)| load < b.critical_loads[0])
                    {
                        self.best = Some((parameter, buckling, ellipticity, reference));
                    }
                    load
                }
            }
            Err(error) => {
                record.rejected = Some(error.to_string());
                f64::INFINITY
            }
        };
        (self.observer)(&record);
        self.evaluations.push(record);
        value
    }

    /// The critical load expected at `parameter`, which the shift is a fraction of: the last
    /// accepted one, or during the scan its power-law extrapolation from the last two accepted
    /// scan points when that is lower (λ_c falling towards the minimum).
    fn expected_load(&self, parameter: f64) -> Option<f64> {
        let last = self.last_load?;
        if !self.scanning {
            return Some(last);
        }
        let mut accepted = self
            .evaluations
            .iter()
            .rev()
            .filter(|e| e.scan)
            .filter_map(|e| e.critical_load.map(|load| (e.parameter, load)));
        let trend = match (accepted.next(), accepted.next()) {
            (Some((q1, l1)), Some((q0, l0))) if q0 != q1 && l0 > 0.0 && l1 > 0.0 => {
                let exponent = (l1 / l0).ln() / (q1 / q0).ln();
                l1 * (parameter / q1).powf(exponent)
            }
            _ => last,
        };
        Some(if trend.is_finite() {
            last.min(trend)
        } else {
            last
        })
    }

    /// The analysis at `parameter`, about a shift when one is safe (module documentation),
    /// with the load it linearised about.
    fn analyse(
        &mut self,
        parameter: f64,
    ) -> Result<(LinearBuckling, EllipticityReport, f64), SolveError> {
        set_model_parameter(self.problem, self.options.parameter, parameter)?;
        let mut options = self.options.buckling.clone();
        let warm = self.warm.as_ref();
        let start_at = |load: f64| warm.map(|(buckling, from)| buckling.state_at(*from, load));
        options.initial_state = start_at(options.reference_load);
        // Without a neighbour's mode, a constant start vector: the modes searched here are
        // smooth envelopes, on which it has a large component where a pseudo-random vector has
        // mostly mesh-scale content (the first scan point on 64 × 32: 65 Lanczos iterations
        // against 163). The eigen-solver adds a small pseudo-random part to any start.
        options.eigen.start = Some(
            warm.and_then(|(buckling, _)| buckling.modes.first().cloned())
                .unwrap_or_else(|| vec![1.0; self.problem.free_count()]),
        );
        if self.scanning {
            options.eigen.tolerance = options
                .eigen
                .tolerance
                .max(self.options.scan_eigen_tolerance);
        }
        // During a wide scan, neighbours are far apart and λ_c may fall by more than the
        // shift's margin: a second, smaller shift is tried before the analysis about the
        // reference load (each failed try costs one factorisation; a successful one saves most
        // of the eigen-solver's iterations).
        let wide_scan = self.scanning && self.options.load_guess.is_none();
        let local = [LOCAL_SHIFT, self.options.shift_fraction];
        let fractions: &[f64] = if wide_scan {
            &[self.options.shift_fraction, SCAN_SECOND_SHIFT]
        } else if !self.scanning && self.options.shift_fraction > 0.0 {
            &local
        } else {
            &[self.options.shift_fraction]
        };
        for &fraction in fractions {
            let Some(shift) = self
                .expected_load(parameter)
                .map(|load| fraction * load)
                .filter(|&s| s.is_finite() && s > options.reference_load)
            else {
                break;
            };
            let shifted = LinearBucklingOptions {
                reference_load: shift,
                initial_state: start_at(shift),
                ..options.clone()
            };
            if let Ok(buckling) = linear_buckling(self.problem, self.factor, &shifted)
                && self.factor.negative_pivots() == Some(0)
            {
                let ellipticity = ellipticity_at_critical_load(self.problem, &buckling, shift);
                return Ok((buckling, ellipticity, shift));
            }
        }
        let buckling = linear_buckling(self.problem, self.factor, &options)?;
        let ellipticity =
            ellipticity_at_critical_load(self.problem, &buckling, options.reference_load);
        Ok((buckling, ellipticity, options.reference_load))
    }
}

/// Minimises the first critical load of `problem` over the model parameter
/// `options.parameter` (see the module documentation). `observer` sees every evaluation (a
/// progress display). On success the model in `problem` is set to the minimiser.
///
/// # Errors
/// [`SolveError::Buckling`] when no value in the range gives an acceptable critical load; the
/// message lists why the scan points were rejected.
pub fn minimise_critical_load<M: EnergyModel>(
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &WavenumberSearchOptions,
    observer: &mut dyn FnMut(&WavenumberEvaluation),
) -> Result<WavenumberSearch, SolveError> {
    let (low, high) = options.range;
    if !(low > 0.0 && high > low && low.is_finite() && high.is_finite()) {
        return Err(SolveError::Buckling(format!(
            "invalid range [{low:e}, {high:e}] for `{}`",
            options.parameter
        )));
    }
    let points = options.scan_points.max(3);
    let ratio = (high / low).powf(1.0 / (points - 1) as f64);
    let scan: Vec<f64> = (0..points).map(|k| low * ratio.powi(k as i32)).collect();
    let mut searcher = Searcher {
        problem,
        factor,
        options,
        observer,
        evaluations: Vec::new(),
        warm: None,
        last_load: options.load_guess,
        best: None,
        scanning: true,
    };
    if let Some(guess) = options.local_guess
        && guess.parameter > 0.0
        && guess.relative_step > 0.0
        && search_near_guess(&mut searcher, guess)?
    {
        return finish_search(searcher);
    }
    let (values, best) = scan_for_lowest(&mut searcher, &scan)?;
    refine_around(&mut searcher, &scan, ratio, &values, best)?;
    finish_search(searcher)
}

/// The local search from `guess`: successive parabolic interpolation in $`\ln Q`$. Returns
/// whether it bracketed a minimum; when it did not, fails unless
/// [`WavenumberSearchOptions::scan_after_local`], and leaves the searcher scanning.
fn search_near_guess<M: EnergyModel>(
    searcher: &mut Searcher<'_, M>,
    guess: LocalGuess,
) -> Result<bool, SolveError> {
    let options = searcher.options;
    searcher.scanning = false;
    let local = local_parabolic_minimum(
        |x| Ok::<f64, SolveError>(searcher.evaluate(x.exp())),
        guess.parameter.ln(),
        guess.relative_step.ln_1p(),
        options.relative_tolerance.ln_1p(),
        LOCAL_EVALUATIONS,
    )?;
    if local.is_some() {
        return Ok(true);
    }
    if !options.scan_after_local {
        return Err(SolveError::Buckling(format!(
            "no minimum of the critical load bracketed near `{}` = {:e} ({} analyses)",
            options.parameter,
            guess.parameter,
            searcher.evaluations.len()
        )));
    }
    // Not bracketed near the guess (or an evaluation rejected): the global search.
    searcher.scanning = true;
    Ok(false)
}

/// The scan from short to long wavelengths, ending two points past the lowest value (module
/// documentation): the values (unevaluated points keep $`+\infty`$) and the index of the
/// lowest, which must be finite.
fn scan_for_lowest<M: EnergyModel>(
    searcher: &mut Searcher<'_, M>,
    scan: &[f64],
) -> Result<(Vec<f64>, usize), SolveError> {
    let points = scan.len();
    let mut values = vec![f64::INFINITY; points];
    let mut lowest: Option<usize> = None;
    for k in (0..points).rev() {
        values[k] = searcher.evaluate(scan[k]);
        if values[k].is_finite() && lowest.is_none_or(|b| values[k] < values[b]) {
            lowest = Some(k);
        }
        if lowest.is_some_and(|b| b >= k + SCAN_PAST_MINIMUM) {
            break;
        }
    }
    let best = (0..points)
        .min_by(|&a, &b| values[a].total_cmp(&values[b]))
        .expect("the scan is not empty");
    if !values[best].is_finite() {
        return Err(SolveError::Buckling(no_threshold_message(
            searcher.options,
            &searcher.evaluations,
        )));
    }
    Ok((values, best))
}

/// Refines in the bracket around the best scan point, warm-started from it: successive
/// parabolic interpolation in $`\ln Q`$ from the scan's bracket when both neighbours of the
/// best point were accepted, Brent's method over the bracket otherwise (a point at an end of
/// the scan is bracketed one ratio beyond it).
fn refine_around<M: EnergyModel>(
    searcher: &mut Searcher<'_, M>,
    scan: &[f64],
    ratio: f64,
    values: &[f64],
    best: usize,
) -> Result<(), SolveError> {
    let options = searcher.options;
    let (low, high) = options.range;
    let points = scan.len();
    if let Some((_, buckling, _, reference)) = &searcher.best {
        searcher.warm = Some((buckling.clone(), *reference));
        searcher.last_load = buckling.critical_loads.first().copied();
    }
    searcher.scanning = false;
    let bracket_low = if best == 0 {
        low / ratio
    } else {
        scan[best - 1]
    };
    let bracket_high = if best + 1 == points {
        high * ratio
    } else {
        scan[best + 1]
    };
    let interior = best > 0 && best + 1 < points;
    if interior && values[best - 1].is_finite() && values[best + 1].is_finite() {
        let triple = [best - 1, best, best + 1].map(|k| (scan[k].ln(), values[k]));
        parabolic_refinement(
            |x| Ok::<f64, SolveError>(searcher.evaluate(x.exp())),
            triple,
            0,
            options.relative_tolerance.ln_1p(),
            LOCAL_EVALUATIONS,
        )?;
    } else {
        minimize_scalar(
            |q| Ok::<f64, SolveError>(searcher.evaluate(q)),
            bracket_low,
            bracket_high,
            options.relative_tolerance * scan[best],
            100,
        )?;
    }
    Ok(())
}

/// The second shift tried in a wide scan, as a fraction of the last accepted critical load.
const SCAN_SECOND_SHIFT: f64 = 0.3;
/// First shift fraction of the local refinement (module documentation), and of any analysis
/// with a close guess of its critical load.
pub const LOCAL_SHIFT: f64 = 0.98;

/// Scan points evaluated past the lowest value before the scan ends.
const SCAN_PAST_MINIMUM: usize = 2;

/// Evaluations of a local search (bracketing moves included) before it stops at its best point.
const LOCAL_EVALUATIONS: usize = 16;

/// The search's best analysis, with the model set to its parameter.
fn finish_search<M: EnergyModel>(
    mut searcher: Searcher<'_, M>,
) -> Result<WavenumberSearch, SolveError> {
    let (parameter, buckling, ellipticity, reference_load) =
        searcher.best.take().expect("an accepted evaluation exists");
    let evaluations = searcher.evaluations;
    let options = searcher.options;
    set_model_parameter(searcher.problem, options.parameter, parameter)?;
    Ok(WavenumberSearch {
        parameter,
        buckling,
        ellipticity,
        reference_load,
        evaluations,
    })
}

/// Why no threshold was found: the range and a summary of the rejections.
fn no_threshold_message(
    options: &WavenumberSearchOptions,
    evaluations: &[WavenumberEvaluation],
) -> String {
    let mut reasons: Vec<String> = Vec::new();
    for evaluation in evaluations {
        if let Some(reason) = &evaluation.rejected {
            let short = reason.split(':').next().unwrap_or(reason).to_string();
            if !reasons.contains(&short) {
                reasons.push(short);
            }
        }
    }
    let first = evaluations
        .iter()
        .find_map(|e| e.rejected.as_deref())
        .unwrap_or("none");
    format!(
        "no acceptable critical load for `{}` anywhere in [{:.4e}, {:.4e}] ({} evaluations); rejections: {}; the first in full: {first}",
        options.parameter,
        options.range.0,
        options.range.1,
        evaluations.len(),
        reasons.join("; ")
    )
}
