//! The two-level wavenumber search of a model that selects its own wavelength (module
//! documentation of [`crate::threshold`]): a global scan on a half mesh, a local refinement on
//! the real one, both started from the closed form where it applies.

use super::{analyse, closed_form_threshold};
use crate::error::Error;
use crate::scene::Scene;
use crate::setup::build_problem;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::linear_buckling;
use wrinkle_runtime::solve::wavenumber::{
    LOCAL_SHIFT, LocalGuess, WavenumberEvaluation, WavenumberSearch, WavenumberSearchOptions,
    minimise_critical_load, set_model_parameter,
};
use wrinkle_runtime::wavelength::WAVENUMBER_PARAMETER;

/// Relative accuracy of $`Q`$ on the coarse mesh of the two-level search.
const COARSE_RELATIVE_TOLERANCE: f64 = 1e-2;
/// Relative accuracy of $`Q`$ on the real mesh: $`\lambda_c`$ is flat to second order at its
/// minimum, $`\delta\lambda_c/\lambda_c \approx 2(\delta Q/Q)^2`$ on eq. (42) near the
/// optimum, so $`2\cdot10^{-4}`$ in $`Q`$ is about $`10^{-7}`$ in $`\lambda_c`$ (measured on example
/// 1: $`10^{-3}`$ gave $`1.4\cdot10^{-6}`$, above the mesh error $`10^{-6}`$).
const FINE_RELATIVE_TOLERANCE: f64 = 2e-4;
/// Log-spaced points of the global scan.
pub(super) const SCAN_POINTS: usize = 17;
/// Half-width (as a factor) of the bracket around the coarse minimiser searched on the real mesh
/// when the local search does not bracket the minimum.
const LOCAL_BRACKET: f64 = 1.1;
/// Relative distance of the first neighbours of the coarse minimiser on the real mesh: twice the
/// coarse tolerance, which also covers the coarse-to-fine shift of the minimiser (0.35 % on
/// example 1 from 16 × 8 to 32 × 16).
const LOCAL_STEP: f64 = 2e-2;

/// The coarse mesh of the two-level wavenumber search: half the elements each way; `None` when
/// the mesh has fewer than 16 × 8 elements (then the search runs on the mesh itself). The
/// buckling mode of an envelope model is a smooth envelope, so half the elements put the coarse
/// minimiser within the local bracket ([`LOCAL_BRACKET`]) of the fine one.
fn coarse_scene(scene: &Scene) -> Option<Scene> {
    let (nx, ny) = (scene.mesh.elements_x, scene.mesh.elements_y);
    (nx >= 16 && ny >= 8).then(|| {
        let mut coarse = scene.clone();
        coarse.mesh.elements_x = nx / 2;
        coarse.mesh.elements_y = ny / 2;
        coarse
    })
}

/// The global search on a half mesh, then the local refinement on `problem` (module
/// documentation); on the problem itself when its mesh is already coarse.
pub(super) fn two_level_search<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &WavenumberSearchOptions,
    observer: &mut dyn FnMut(&WavenumberEvaluation),
) -> Result<WavenumberSearch, Error> {
    let options = &closed_form_start(scene, options);
    let coarse = coarse_scene(scene);
    let mut direct_evaluations = Vec::new();
    if let (Some(_), Some(guess)) = (&coarse, options.local_guess) {
        // The closed form's minimiser is within 1.3e-4 of the FE one on example 1 from 6 × 4 to
        // 40 × 20 elements, closer than the half mesh's (1 %): the real mesh refines from it
        // directly, as it would from the half mesh's. No minimum bracketed near it, or one at
        // the edge of the ±10 % bracket, means this model's minimum is elsewhere (another
        // model than the one eq. (42) solves): then the two-level search, as before.
        let local = WavenumberSearchOptions {
            scan_after_local: false,
            ..fine_options(options, guess.parameter, None)
        };
        let (low, high) = local.range;
        let mut record = |evaluation: &WavenumberEvaluation| {
            direct_evaluations.push(evaluation.clone());
            observer(evaluation)
        };
        match minimise_critical_load(problem, factor, &local, &mut record) {
            Ok(found)
                if found.parameter > low * (1.0 + LOCAL_STEP)
                    && found.parameter < high / (1.0 + LOCAL_STEP) =>
            {
                return Ok(found);
            }
            // Kept in the count: the analyses of the attempt were done.
            _ => {}
        }
    }
    let mut search = match coarse {
        None => minimise_critical_load(problem, factor, options, observer).map_err(solve_error)?,
        Some(coarse) => {
            // Global scan (or a local search from the closed form) on the coarse mesh, then a
            // local refinement on the real one.
            let first = coarse_level(&coarse, problem, options, observer)?;
            let local = fine_options(
                options,
                first.parameter,
                first.buckling.critical_loads.first().copied(),
            );
            let mut fine =
                minimise_critical_load(problem, factor, &local, observer).map_err(solve_error)?;
            let mut evaluations = first.evaluations;
            for evaluation in &mut evaluations {
                evaluation.coarse = true;
            }
            evaluations.append(&mut fine.evaluations);
            fine.evaluations = evaluations;
            fine
        }
    };
    if !direct_evaluations.is_empty() {
        direct_evaluations.append(&mut search.evaluations);
        search.evaluations = direct_evaluations;
    }
    Ok(search)
}

/// An estimate of the minimum of $`\lambda_c(Q)`$ over `options.range`, for the shift of
/// another model's buckling analysis ([`WavenumberModel::critical_load_estimate`]): the global
/// level of [`two_level_search`] (the scan and refinement to 1 % in $`Q`$ on the half mesh),
/// then one analysis on `problem` at its minimiser, shifted about the half mesh's
/// $`\lambda_c`$. $`\lambda_c`$ is flat at its minimum ($`\delta\lambda_c/\lambda_c \approx
/// 2(\delta Q/Q)^2`$, [`FINE_RELATIVE_TOLERANCE`]), so that is the threshold to within 1e-3
/// (5e-7 on the long strip at 112 × 64, 6e-4 on its shipped 56 × 16 graded mesh, whose half
/// mesh shifts the minimiser more), without the real mesh's refinement. On a mesh too
/// coarse to halve, the search to 1 % on `problem`; the half mesh's $`\lambda_c`$ when the
/// analysis at its minimiser fails.
///
/// [`WavenumberModel::critical_load_estimate`]: super::wavenumber_model::WavenumberModel::critical_load_estimate
pub(super) fn estimate_minimum<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &WavenumberSearchOptions,
    observer: &mut dyn FnMut(&WavenumberEvaluation),
) -> Result<f64, Error> {
    let options = &closed_form_start(scene, options);
    let Some(coarse) = coarse_scene(scene) else {
        let found = minimise_critical_load(problem, factor, &coarse_options(options), observer)
            .map_err(solve_error)?;
        return lowest_load(&found);
    };
    let first = coarse_level(&coarse, problem, options, observer)?;
    let coarse_load = lowest_load(&first)?;
    set_model_parameter(problem, WAVENUMBER_PARAMETER, first.parameter).map_err(solve_error)?;
    let shifted = super::steps::threshold_buckling(LOCAL_SHIFT * coarse_load);
    Ok(match linear_buckling(problem, factor, &shifted) {
        Ok(buckling) if factor.negative_pivots() == Some(0) => buckling
            .critical_loads
            .first()
            .copied()
            .filter(|load| load.is_finite() && *load > 0.0)
            .unwrap_or(coarse_load),
        _ => coarse_load,
    })
}

/// The global level of [`two_level_search`]: the search to [`COARSE_RELATIVE_TOLERANCE`] in
/// $`Q`$ on the half mesh `coarse`, with `problem`'s model.
fn coarse_level<M: EnergyModel>(
    coarse: &Scene,
    problem: &Problem<M>,
    options: &WavenumberSearchOptions,
    observer: &mut dyn FnMut(&WavenumberEvaluation),
) -> Result<WavenumberSearch, Error> {
    let mut coarse_problem = build_problem(coarse, problem.assembler.model().clone())?;
    let mut coarse_factor = analyse(&coarse_problem)?;
    minimise_critical_load(
        &mut coarse_problem,
        &mut coarse_factor,
        &coarse_options(options),
        observer,
    )
    .map_err(solve_error)
}

/// `options` with the global level's tolerance, [`COARSE_RELATIVE_TOLERANCE`] in $`Q`$.
fn coarse_options(options: &WavenumberSearchOptions) -> WavenumberSearchOptions {
    WavenumberSearchOptions {
        relative_tolerance: COARSE_RELATIVE_TOLERANCE,
        ..options.clone()
    }
}

/// A solver's error as the threshold's.
fn solve_error(error: impl std::fmt::Display) -> Error {
    Error::Solver(error.to_string())
}

/// The lowest critical load of a search's analysis at its minimiser.
fn lowest_load(search: &WavenumberSearch) -> Result<f64, Error> {
    search
        .buckling
        .critical_loads
        .first()
        .copied()
        .ok_or_else(|| Error::Solver("the wavenumber search found no critical load".into()))
}

/// The real mesh's local refinement about `q` (a minimiser found on the half mesh, or the
/// closed form's): parabolic steps from `q` ± [`LOCAL_STEP`] to [`FINE_RELATIVE_TOLERANCE`],
/// within ±10 % ([`LOCAL_BRACKET`]); `load_guess` (when given) replaces `options`' guess.
fn fine_options(
    options: &WavenumberSearchOptions,
    q: f64,
    load_guess: Option<f64>,
) -> WavenumberSearchOptions {
    WavenumberSearchOptions {
        range: (q / LOCAL_BRACKET, q * LOCAL_BRACKET),
        scan_points: 3,
        relative_tolerance: FINE_RELATIVE_TOLERANCE,
        load_guess: load_guess.or(options.load_guess),
        local_guess: Some(LocalGuess {
            parameter: q,
            relative_step: LOCAL_STEP,
        }),
        ..options.clone()
    }
}

/// Relative distance of the first neighbours of the closed-form minimiser in a search that
/// starts from it (`closed_form_start`). The FE minimiser of the reference envelope lies within
/// 1.3e-4 of it on example 1 from 6 × 4 to 40 × 20 elements (the mesh error shifts $`\lambda_c`$
/// nearly uniformly in $`Q`$); ±3 % brackets it with a wide margin for other models and scenes,
/// and the first parabola's vertex is then within the half mesh's 1 % tolerance.
const CLOSED_FORM_STEP: f64 = 3e-2;

/// `options` with the search started from the closed-form threshold (eq. (42) minimised) when
/// the scene has one inside the searched range: a local search about its $`Q`$, shifted about
/// its $`\lambda_c`$, instead of the global scan. The closed form solves the reference envelope
/// on a clamped rectangle under biaxial load, the scenes it applies to; the local search falls
/// back to the global scan when it cannot bracket a minimum near the guess (a model whose
/// $`\lambda_c(Q)`$ differs, or none at all), so the guess only decides where the search
/// starts, never what it finds. With a half mesh, the real mesh is first searched directly from
/// the closed form (`two_level_search`): 3 analyses on example 1 at 40 × 20, against 18 with the
/// global scan and 6 with the half mesh started from the closed form.
fn closed_form_start(scene: &Scene, options: &WavenumberSearchOptions) -> WavenumberSearchOptions {
    let (low, high) = options.range;
    match closed_form_threshold(scene) {
        Some((load, q)) if q > low && q < high && load.is_finite() && load > 0.0 => {
            WavenumberSearchOptions {
                load_guess: Some(load),
                local_guess: Some(LocalGuess {
                    parameter: q,
                    relative_step: CLOSED_FORM_STEP,
                }),
                ..options.clone()
            }
        }
        _ => options.clone(),
    }
}
