//! `model.direction = "auto"`: the direction $`\mathbf e = (\cos\theta, \sin\theta)`$ of the wave
//! vector chosen where the threshold is lowest.
//!
//! **First guess: the principal compression.** Wrinkles of an envelope model run across the
//! compression: the wave vector lies along the principal direction of the most compressive
//! membrane force of the pre-buckling state (THEORY.md §8: $`\lambda_c(\theta)`$ of a uniform
//! state is lowest where $`\mathbf e\cdot\mathbf N\,\mathbf e`$ is most negative). For a membrane
//! force $`\mathbf N = \begin{pmatrix}N_X & N_{XY}\\ N_{XY} & N_Y\end{pmatrix}`$ that direction
//! $`\varphi`$ satisfies $`(\cos 2\varphi, \sin 2\varphi) \parallel -(N_X - N_Y,\, 2N_{XY})`$;
//! the element directions are averaged as axes (doubled angles,
//! [`principal_compression_direction`]). Where the wrinkles start is not known before a
//! buckling analysis, so the guess is made twice: from the load rate $`\dot U`$ (weights: the
//! rate's compression times the element area), then from the state at the first threshold,
//! weighted by the first mode's squared amplitude over the compressed elements — where
//! wrinkling starts.
//!
//! **Then the lowest threshold.** For a model that selects its own wavelength,
//! $`\lambda_c(\theta) = \min_Q \lambda_c(Q, \theta)`$ is minimised by successive parabolic
//! interpolation from that guess (first neighbours at ±[`FIRST_STEP_DEGREES`], each value a local
//! search in $`Q`$ from the last minimiser on the run's mesh) to [`RESOLUTION_DEGREES`]; the
//! angle is rounded to that resolution and the threshold is the scene's **with the direction
//! fixed at that angle**: a run with `model.direction` set to the reported angle gives the same
//! numbers. $`\lambda_c`$ is flat to second order at the minimum, so a tenth of a degree is far
//! below what the load can tell apart. The minimisation is local: with several compressed
//! zones at different angles it finds the minimum nearest to where the first mode lives.
//!
//! **Models without a minimisation of their own.** A plate resolves its wrinkles on the mesh
//! and has no direction parameter: its direction is the principal compression where its first
//! mode lives, used to read the wavelength off the mode and check its resolution. A complex
//! envelope (free phase) and the pure membrane take the direction with the wavenumber from
//! `model.wavenumber_model`, as they take its $`Q`$.

use super::steps::threshold_buckling;
use super::wavenumber_model::WavenumberModel;
use super::{
    Threshold, ThresholdOptions, fixed_direction_threshold, mode_wavelength, threshold_checks,
};
use crate::error::Error;
use crate::physics::Layout;
use crate::scene::{Direction, Scene, Wavenumber};
use crate::setup::layout_of;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::element::ElementKind;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::model::{Derivative, JetEntry};
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::brent::{ScalarMinimum, local_parabolic_minimum};
use wrinkle_runtime::solve::buckling::linear_buckling;
use wrinkle_runtime::solve::linearization::{factorize_tangent, load_tangent};
use wrinkle_runtime::solve::newton::{NewtonOptions, newton};
use wrinkle_runtime::solve::wavenumber::{
    LocalGuess, WavenumberSearchOptions, minimise_critical_load, set_model_parameter,
    state_at_critical_load,
};
use wrinkle_runtime::wavelength::{WAVENUMBER_PARAMETER, WavelengthSelection};

/// The model parameter that holds $`\theta`$ (radians).
const DIRECTION_PARAMETER: &str = "direction";
/// Distance of the first neighbours of the guess in the minimisation of $`\lambda_c(\theta)`$.
pub const FIRST_STEP_DEGREES: f64 = 5.0;
/// Resolution of the chosen angle: the minimisation stops below it, and the angle is rounded
/// to it.
pub const RESOLUTION_DEGREES: f64 = 0.1;
/// Most evaluations of $`\lambda_c(\theta)`$ in the minimisation.
const MAX_DIRECTION_EVALUATIONS: usize = 12;
/// Relative accuracy of $`Q`$ in each evaluation of $`\lambda_c(\theta)`$ (the evaluations only
/// rank directions; the final threshold searches $`Q`$ to its own accuracy).
const EVALUATION_Q_TOLERANCE: f64 = 1e-3;

/// The threshold of a scene with `model.direction = "auto"` (module documentation).
pub(super) fn auto_direction_threshold<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &ThresholdOptions,
) -> Result<Threshold, Error> {
    let start = std::time::Instant::now();
    if let Some(degrees) = options.prior.and_then(|prior| prior.direction_degrees) {
        let mut threshold = threshold_at(scene, degrees, problem, factor, options)?;
        threshold.direction_source = "auto (reused)".into();
        threshold.notes.push(format!(
            "model.direction = \"auto\": {degrees}° is reused from the same file as Q (the direction found there for this scene)"
        ));
        return Ok(threshold);
    }
    let spec = M::SPEC;
    let two_dimensional = problem.assembler.mesh().kind == ElementKind::Quad8;
    let mut threshold = if !two_dimensional {
        let mut threshold = threshold_at(scene, 0.0, problem, factor, options)?;
        threshold.notes.push(
            "model.direction = \"auto\": a line has one direction; the wave vector is along X (0°)"
                .into(),
        );
        threshold
    } else if spec.parameter_index(DIRECTION_PARAMETER).is_none() {
        direction_of_the_mode(scene, problem, factor, options)?
    } else {
        match spec.wavelength_selection() {
            WavelengthSelection::Carried(_) => carried_direction(scene, problem, factor, options)?,
            _ => lowest_threshold_direction(scene, problem, factor, options)?,
        }
    };
    threshold.seconds = start.elapsed().as_secs_f64();
    Ok(threshold)
}

/// The threshold of `scene` with `model.direction` fixed at `degrees`, the model in `problem`
/// set to that direction first (it was configured from the scene's `"auto"`).
fn threshold_at<M: EnergyModel>(
    scene: &Scene,
    degrees: f64,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &ThresholdOptions,
) -> Result<Threshold, Error> {
    if M::SPEC.parameter_index(DIRECTION_PARAMETER).is_some() {
        set_model_parameter(problem, DIRECTION_PARAMETER, degrees.to_radians())
            .map_err(|e| Error::Solver(e.to_string()))?;
    }
    fixed_direction_threshold(&at(scene, degrees), problem, factor, options)
}

/// `scene` with `model.direction` fixed at `degrees`.
fn at(scene: &Scene, degrees: f64) -> Scene {
    let mut fixed = scene.clone();
    fixed.model.direction = Direction::Fixed(degrees);
    fixed
}

/// `degrees` as an axis in $`(-90°, 90°]`$ rounded to [`RESOLUTION_DEGREES`] (never $`-0`$).
pub fn normalised_axis(degrees: f64) -> f64 {
    let mut axis = degrees.rem_euclid(180.0);
    if axis > 90.0 {
        axis -= 180.0;
    }
    let rounded = (axis / RESOLUTION_DEGREES).round() * RESOLUTION_DEGREES;
    // One decimal exactly as written (−44.9, not −44.900000000000006), and 0 for −0.
    let tidy: f64 = format!("{rounded:.1}").parse().unwrap_or(rounded);
    if tidy <= -90.0 {
        tidy + 180.0
    } else {
        tidy + 0.0
    }
}

/// The principal compression direction (degrees from X, an axis in $`(-90°, 90°]`$) of the
/// membrane forces `forces[e] = [N_X, N_Y, N_XY]`, averaged as axes with the weights
/// `weight(e, σ₂)` (σ₂ the element's most compressive principal force; elements with
/// σ₂ ≥ 0 are left out). `None` when no element is compressed or the average has no direction
/// (as many elements compressed along one axis as across it).
pub fn principal_compression_direction(
    forces: &[[f64; 3]],
    weight: impl Fn(usize, f64) -> f64,
) -> Option<f64> {
    let (mut cos_sum, mut sin_sum) = (0.0, 0.0);
    for (e, &[nx, ny, nxy]) in forces.iter().enumerate() {
        let half_difference = 0.5 * (nx - ny);
        let radius = half_difference.hypot(nxy);
        let compression = 0.5 * (nx + ny) - radius;
        if !(compression < 0.0 && radius > 0.0) {
            continue;
        }
        let w = weight(e, compression);
        if !(w.is_finite() && w > 0.0) {
            continue;
        }
        // The compression axis φ: (cos 2φ, sin 2φ) = −(N_X − N_Y, 2 N_XY)/(2 radius).
        cos_sum -= w * half_difference / radius;
        sin_sum -= w * nxy / radius;
    }
    let norm = cos_sum.hypot(sin_sum);
    (norm > 0.0 && norm.is_finite()).then(|| (0.5 * sin_sum.atan2(cos_sum)).to_degrees())
}

/// Element means of the membrane forces $`[N_X, N_Y, N_{XY}]`$ of the nodal `values` (from the
/// model's own residual kernel, as the run's `membrane_force_*` plots).
fn membrane_forces<M: EnergyModel>(
    problem: &Problem<M>,
    layout: &Layout,
    values: &[f64],
) -> Vec<[f64; 3]> {
    let [u, v] = layout.in_plane;
    let entry = |field, derivative| JetEntry { field, derivative };
    let means = problem.assembler.element_mean_conjugates(
        values,
        &[
            entry(u, Derivative::X),
            entry(v, Derivative::Y),
            entry(u, Derivative::Y),
        ],
    );
    (0..means[0].len())
        .map(|e| [means[0][e], means[1][e], means[2][e]])
        .collect()
}

/// Area of each element (its corner quadrilateral).
fn element_areas(problem: &Problem<impl EnergyModel>) -> Vec<f64> {
    let mesh = problem.assembler.mesh();
    (0..mesh.element_count())
        .map(|e| {
            let corners = &mesh.element_coordinates(e)[..4];
            let twice: f64 = (0..4)
                .map(|i| {
                    let (a, b) = (corners[i], corners[(i + 1) % 4]);
                    a[0] * b[1] - b[0] * a[1]
                })
                .sum();
            0.5 * twice.abs()
        })
        .collect()
}

/// The direction the load rate compresses: the principal compression of $`\dot U`$ at the
/// unloaded equilibrium, weighted by its compression times the element area. `None` when the
/// rate compresses nothing.
fn load_rate_direction<M: EnergyModel>(
    problem: &Problem<M>,
    factor: &mut SparseFactorization,
    layout: &Layout,
) -> Result<Option<f64>, Error> {
    let solver = |e: wrinkle_runtime::solve::SolveError| Error::Solver(e.to_string());
    let mut matrix = problem.new_matrix();
    let zero = vec![0.0; problem.free_count()];
    let unloaded = newton(
        problem,
        zero,
        0.0,
        factor,
        &mut matrix,
        &NewtonOptions::default(),
    )
    .map_err(solver)?;
    factorize_tangent(problem, &unloaded.solution, 0.0, &mut matrix, factor)
        .map_err(|e| Error::Solver(format!("the load rate for model.direction = \"auto\": {e}")))?;
    let rate = load_tangent(problem, factor, &unloaded.solution, 0.0)
        .map_err(|e| Error::Solver(format!("the load rate for model.direction = \"auto\": {e}")))?;
    let values = problem.dofs().expand_increment(&rate, 1.0);
    let forces = membrane_forces(problem, layout, &values);
    let areas = element_areas(problem);
    Ok(principal_compression_direction(
        &forces,
        |e, compression| -compression * areas[e],
    ))
}

/// The principal compression of the pre-buckling state at the threshold where its first mode
/// lives: weights the mode's squared deflection fields (element mean over the nodes) times the
/// element area.
fn where_wrinkling_starts<M: EnergyModel>(
    problem: &Problem<M>,
    layout: &Layout,
    threshold: &Threshold,
) -> Option<f64> {
    let mode = threshold.buckling.modes.first()?;
    let state = state_at_critical_load(&threshold.buckling, threshold.reference_load);
    let values = problem.dofs().expand(&state, threshold.critical_load());
    let mode_values = problem.dofs().expand_increment(mode, 0.0);
    let forces = membrane_forces(problem, layout, &values);
    let areas = element_areas(problem);
    let mesh = problem.assembler.mesh();
    let fields = layout.deflection_fields();
    let nf = layout.field_count;
    let mode_values = &mode_values;
    let fields = &fields;
    principal_compression_direction(&forces, |e, _| {
        let nodes = mesh.element_nodes(e);
        let squares: f64 = nodes
            .iter()
            .flat_map(|&n| fields.iter().map(move |&f| mode_values[n * nf + f].powi(2)))
            .sum();
        squares / nodes.len() as f64 * areas[e]
    })
}

/// A plate: the threshold (its direction matters only to read the wavelength off the mode),
/// then the principal compression where the mode lives, the wavelength along it and the checks.
fn direction_of_the_mode<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &ThresholdOptions,
) -> Result<Threshold, Error> {
    let layout = layout_of::<M>(scene)?;
    let mut threshold = threshold_at(scene, 0.0, problem, factor, options)?;
    let found = where_wrinkling_starts(problem, &layout, &threshold);
    let degrees = normalised_axis(found.unwrap_or(0.0));
    let fixed = at(scene, degrees);
    threshold.wavelength = mode_wavelength(&fixed, problem, &layout, &threshold.buckling, degrees);
    threshold.direction_degrees = degrees;
    threshold.direction_source = "auto (mode)".into();
    threshold.warnings = threshold_checks(&fixed, problem, &layout, &threshold);
    threshold.notes.push(match found {
        Some(_) => format!(
            "model.direction = \"auto\": {degrees}°, the principal compression direction of the pre-buckling state at λ_c where the first mode lives (weights: the mode's squared deflection); the wavelength is read along it"
        ),
        None => "model.direction = \"auto\": the first mode lives where nothing is compressed; the wavelength is read along X (0°)".into(),
    });
    Ok(threshold)
}

/// A model that takes its wavenumber from `model.wavenumber_model` (a free phase, no envelope
/// gradient) takes its direction too: the threshold at the wavenumber model's direction, which
/// that model found by its own `"auto"` search and whose threshold is passed on as found.
fn carried_direction<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &ThresholdOptions,
) -> Result<Threshold, Error> {
    let Some(own) = WavenumberModel::of(scene)? else {
        return lowest_threshold_direction(scene, problem, factor, options);
    };
    let model = match options.wavenumber_model {
        Some(shared) if shared.same_as(&own) => shared,
        _ => &own,
    };
    let carrier = model.threshold(options.quiet)?;
    let degrees = carrier.direction_degrees;
    let fixed = at(scene, degrees);
    let known = WavenumberModel::with_threshold(&fixed, carrier)?;
    let fixed_options = ThresholdOptions {
        wavenumber_model: Some(&known),
        ..*options
    };
    let mut threshold = threshold_at(&fixed, degrees, problem, factor, &fixed_options)?;
    threshold.direction_source = format!("auto ({})", model.name());
    threshold.notes.push(format!(
        "model.direction = \"auto\": {degrees}°, the direction of the {} threshold on the same scene (taken with its Q: model `{}` does not select its own wavelength)",
        model.name(),
        M::SPEC.name
    ));
    Ok(threshold)
}

/// A model that selects its own wavelength: $`\lambda_c(\theta)`$ minimised from the principal
/// compression where the first mode lives (module documentation), then the threshold at the
/// chosen angle.
fn lowest_threshold_direction<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &ThresholdOptions,
) -> Result<Threshold, Error> {
    let layout = layout_of::<M>(scene)?;
    let rate = load_rate_direction(problem, factor, &layout)?.map(normalised_axis);
    let rate_degrees = rate.unwrap_or(0.0);
    let first = threshold_at(scene, rate_degrees, problem, factor, options)?;
    let start = where_wrinkling_starts(problem, &layout, &first).map(normalised_axis);
    let mut search = DirectionSearch {
        problem,
        factor,
        fixed_wavenumber: match scene.model.wavenumber {
            Wavenumber::Fixed(q) => Some(q),
            Wavenumber::Auto => None,
        },
        wavenumber: first.wavenumber.unwrap_or(1.0),
        load: first.critical_load(),
        evaluations: Vec::new(),
        analyses: 0,
    };
    let centre = start.unwrap_or(rate_degrees);
    let mut minimum = search.local_minimum(centre)?;
    if minimum.is_none()
        && let Some(best) = search.best().filter(|&best| best != centre)
    {
        // Not bracketed near the guess (λ_c still falling where the bracket stopped, or an
        // evaluation without threshold): once more from the lowest value found.
        minimum = search.local_minimum(best)?;
    }
    let chosen = normalised_axis(
        minimum
            .map(|m| m.argument)
            .or_else(|| search.best())
            .unwrap_or(centre),
    );
    let (evaluations, analyses) = (search.table(), search.analyses);
    let mut threshold = if chosen == rate_degrees {
        // The search moved the problem's parameters: back to the first threshold's.
        let solver = |e: wrinkle_runtime::solve::SolveError| Error::Solver(e.to_string());
        set_model_parameter(problem, DIRECTION_PARAMETER, chosen.to_radians()).map_err(solver)?;
        if let Some(q) = first.wavenumber {
            set_model_parameter(problem, WAVENUMBER_PARAMETER, q).map_err(solver)?;
        }
        first
    } else {
        let mut found = threshold_at(scene, chosen, problem, factor, options)?;
        found.evaluations += first.evaluations;
        found
    };
    threshold.evaluations += analyses;
    threshold.direction_source = "auto (lowest threshold)".into();
    let rate_text = match rate {
        Some(degrees) => format!("the load rate compresses along {degrees}°"),
        None => "the load rate compresses nothing (0° taken)".into(),
    };
    let start_text = match start {
        Some(degrees) => format!(
            "at that direction's threshold the first mode lives where the principal compression is at {degrees}°"
        ),
        None => "the first mode lives where nothing is compressed".into(),
    };
    let outcome = match minimum {
        Some(_) => format!("the lowest λ_c is at {chosen}° (to {RESOLUTION_DEGREES}°)"),
        None => format!(
            "no minimum was bracketed: {chosen}°, the lowest λ_c evaluated, is kept (not a converged minimum)"
        ),
    };
    threshold.notes.push(format!(
        "model.direction = \"auto\": {rate_text}; {start_text}; λ_c(θ) minimised from there ({evaluations}): {outcome}"
    ));
    Ok(threshold)
}

/// The evaluations of $`\lambda_c(\theta)`$ of [`lowest_threshold_direction`], each a local
/// search in $`Q`$ from the last minimiser (or one analysis at a fixed $`Q`$).
struct DirectionSearch<'a, M: EnergyModel> {
    problem: &'a mut Problem<M>,
    factor: &'a mut SparseFactorization,
    /// The scene's fixed $`Q`$, if any.
    fixed_wavenumber: Option<f64>,
    /// The last minimiser $`Q`$: where the next local search starts.
    wavenumber: f64,
    /// The last critical load: the next analysis's shift guess.
    load: f64,
    /// `(θ in degrees, λ_c)`, `None` for an evaluation that found no threshold.
    evaluations: Vec<(f64, Option<f64>)>,
    /// Linear buckling analyses done.
    analyses: usize,
}

impl<M: EnergyModel> DirectionSearch<'_, M> {
    /// Successive parabolic interpolation of $`\lambda_c(\theta)`$ from `centre` (degrees);
    /// `None` when no minimum is bracketed near it.
    fn local_minimum(&mut self, centre: f64) -> Result<Option<ScalarMinimum>, Error> {
        local_parabolic_minimum(
            |degrees| Ok::<f64, Error>(self.critical_load_at(degrees)),
            centre,
            FIRST_STEP_DEGREES,
            0.5 * RESOLUTION_DEGREES,
            MAX_DIRECTION_EVALUATIONS,
        )
    }

    /// The direction of the lowest $`\lambda_c`$ evaluated so far (degrees).
    fn best(&self) -> Option<f64> {
        self.evaluations
            .iter()
            .filter_map(|&(degrees, load)| Some((degrees, load?)))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(degrees, _)| degrees)
    }

    /// $`\lambda_c`$ at the direction `degrees` ($`+\infty`$ when no threshold is found there).
    fn critical_load_at(&mut self, degrees: f64) -> f64 {
        let found = self.threshold_at(degrees.to_radians());
        self.evaluations.push((degrees, found));
        found.unwrap_or(f64::INFINITY)
    }

    fn threshold_at(&mut self, theta: f64) -> Option<f64> {
        set_model_parameter(self.problem, DIRECTION_PARAMETER, theta).ok()?;
        if let Some(q) = self.fixed_wavenumber {
            set_model_parameter(self.problem, WAVENUMBER_PARAMETER, q).ok()?;
            self.analyses += 1;
            let buckling =
                linear_buckling(self.problem, self.factor, &threshold_buckling(0.0)).ok()?;
            return buckling.critical_loads.first().copied();
        }
        let q = self.wavenumber;
        let local = WavenumberSearchOptions {
            range: (q / 1.1, q * 1.1),
            scan_points: 3,
            relative_tolerance: EVALUATION_Q_TOLERANCE,
            load_guess: Some(self.load).filter(|l| l.is_finite() && *l > 0.0),
            local_guess: Some(LocalGuess {
                parameter: q,
                relative_step: 0.02,
            }),
            ..WavenumberSearchOptions::default()
        };
        // Q can move by more than the local bracket between directions: then a scan over a
        // factor 2 either side, unshifted.
        let wide = WavenumberSearchOptions {
            range: (q / 2.0, q * 2.0),
            scan_points: 7,
            relative_tolerance: EVALUATION_Q_TOLERANCE,
            ..WavenumberSearchOptions::default()
        };
        let mut count = 0;
        let mut counter = |_: &_| count += 1;
        let search = minimise_critical_load(self.problem, self.factor, &local, &mut counter)
            .or_else(|_| minimise_critical_load(self.problem, self.factor, &wide, &mut counter));
        self.analyses += count;
        let search = search.ok()?;
        let load = *search.buckling.critical_loads.first()?;
        self.wavenumber = search.parameter;
        self.load = load;
        Some(load)
    }

    /// The evaluations as text: `θ° → λ_c`, in the order made.
    fn table(&self) -> String {
        self.evaluations
            .iter()
            .map(|(degrees, load)| match load {
                Some(load) => format!("{degrees:.2}° → {load:.6e}"),
                None => format!("{degrees:.2}° → none"),
            })
            .collect::<Vec<_>>()
            .join(", ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pure_shear_compresses_at_minus_45_degrees() {
        // N_XY > 0 alone: tension along +45°, compression along −45° (wave vector there).
        let shear = [[0.0, 0.0, 1.0]; 3];
        assert_eq!(
            principal_compression_direction(&shear, |_, _| 1.0).map(normalised_axis),
            Some(-45.0)
        );
        // Uniaxial compression along X and along Y.
        let along_x = [[-1.0, 0.2, 0.0]];
        let along_y = [[0.3, -2.0, 0.0]];
        assert_eq!(
            principal_compression_direction(&along_x, |_, _| 1.0).map(normalised_axis),
            Some(0.0)
        );
        assert_eq!(
            principal_compression_direction(&along_y, |_, _| 1.0).map(normalised_axis),
            Some(90.0)
        );
        // Pure tension has no compression direction.
        assert_eq!(
            principal_compression_direction(&[[1.0, 2.0, 0.1]], |_, _| 1.0),
            None
        );
    }

    #[test]
    fn a_rotated_uniaxial_compression_is_found_at_its_angle() {
        // N = −p e eᵀ with e at 30°: N_X = −p cos², N_Y = −p sin², N_XY = −p cos sin.
        let (c, s) = (30f64.to_radians().cos(), 30f64.to_radians().sin());
        let forces = [[-c * c, -s * s, -c * s]];
        let found = principal_compression_direction(&forces, |_, _| 1.0).unwrap();
        assert!((found - 30.0).abs() < 1e-12, "{found}");
    }

    #[test]
    fn axes_are_normalised_and_rounded_to_the_resolution() {
        assert_eq!(normalised_axis(135.0), -45.0);
        assert_eq!(normalised_axis(-90.0), 90.0);
        assert_eq!(normalised_axis(-1e-15), 0.0);
        assert!(normalised_axis(-1e-15).is_sign_positive());
        assert_eq!(normalised_axis(-44.93), -44.9);
        assert_eq!(normalised_axis(224.96), 45.0);
    }
}
