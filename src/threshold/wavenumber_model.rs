//! The scene's `model.wavenumber_model`: the model whose minimisation of $`\lambda_c(Q)`$ gives
//! the wavenumber $`Q`$ to a model that does not select its own
//! ([`WavelengthSelection::Carried`], or an own minimum that falls to the end of the range), and
//! whose critical load is the shift guess of a buckling analysis that failed about
//! $`\lambda = 0`$.
//!
//! Its threshold on the run's scene is computed **at most once**, when a step first needs it,
//! and the [`WavenumberModel`] is passed along (no process-wide cache): `wrinkle compare` makes
//! one for its scene and hands it to every model it runs.

use super::scene_quantities::wavenumber_range;
use super::search::{SCAN_POINTS, estimate_minimum};
use super::{ThresholdOptions, analyse, find_threshold_with};
use crate::error::Error;
use crate::output::{ProgressSink, SearchProgress};
use crate::scene::{Direction, Scene, Wavenumber};
use crate::setup::{build_problem, configure_model, scene_error, unknown_model};
use std::cell::OnceCell;
use wrinkle_models::{ModelVisitor, with_model};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::solve::wavenumber::{WavenumberEvaluation, WavenumberSearchOptions};
use wrinkle_runtime::wavelength::WavelengthSelection;

/// The scene key that names the wavenumber model.
pub const WAVENUMBER_MODEL_KEY: &str = "model.wavenumber_model";

/// The wavenumber and critical load of the wavenumber model's threshold on a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CarrierThreshold {
    /// Its minimiser $`Q`$ (1/mm).
    pub wavenumber: f64,
    /// Its critical load $`\lambda_c`$ at that $`Q`$.
    pub critical_load: f64,
    /// Its wave direction (degrees from X): `model.direction`, or the angle it chose.
    pub direction_degrees: f64,
}

/// The wavenumber model of a scene, with its threshold once computed.
#[derive(Debug)]
pub struct WavenumberModel {
    /// The run's scene with `model.name` set to the wavenumber model and no model parameters.
    scene: Scene,
    /// `scene` as TOML: two runs share the threshold only when these agree.
    key: String,
    /// The threshold, once a step asked for it (a failed attempt is not kept).
    found: OnceCell<CarrierThreshold>,
    /// The estimate of its critical load, once a step asked for one.
    estimate: OnceCell<f64>,
}

impl WavenumberModel {
    /// The wavenumber model named by `scene` (its threshold not computed yet). A scene error
    /// naming `model.wavenumber_model` when that model does not select its own wavelength.
    pub fn for_scene(scene: &Scene) -> Result<Self, Error> {
        let name = &scene.model.wavenumber_model;
        let spec = wrinkle_models::catalogue()
            .into_iter()
            .find(|spec| spec.name == name.as_str());
        let Some(spec) = spec else {
            return Err(scene_error(
                scene,
                WAVENUMBER_MODEL_KEY,
                format!(
                    "unknown model `{name}` (models: {})",
                    wrinkle_models::names().join(", ")
                ),
            ));
        };
        if !spec.wavelength_selection().selects_its_own() {
            return Err(scene_error(
                scene,
                WAVENUMBER_MODEL_KEY,
                format!(
                    "model `{name}` does not select its own wavelength ({}), so it cannot give one to other models; use a model that does: {}",
                    describe(spec.wavelength_selection()),
                    selecting_models().join(", ")
                ),
            ));
        }
        let mut own = scene.clone();
        own.model.name = name.clone();
        own.model.parameters.clear();
        Ok(WavenumberModel {
            key: own.to_toml_string(),
            scene: own,
            found: OnceCell::new(),
            estimate: OnceCell::new(),
        })
    }

    /// [`Self::for_scene`], or `None` when the scene's model is the wavenumber model itself
    /// (then it has no helper: its own long-wavelength note applies, nothing falls back).
    pub fn of(scene: &Scene) -> Result<Option<Self>, Error> {
        let helper = Self::for_scene(scene)?;
        Ok((scene.model.name != helper.name()).then_some(helper))
    }

    /// The wavenumber model of `scene` with its threshold there already known (`found`, e.g.
    /// computed on the same scene with `model.direction = "auto"`, which chose the direction
    /// `scene` fixes).
    pub(super) fn with_threshold(scene: &Scene, found: CarrierThreshold) -> Result<Self, Error> {
        let model = Self::for_scene(scene)?;
        let _ = model.found.set(found);
        Ok(model)
    }

    /// Registry name of the wavenumber model.
    pub fn name(&self) -> &str {
        &self.scene.model.name
    }

    /// Whether `self` and `other` compute the same threshold (their scenes agree).
    pub fn same_as(&self, other: &WavenumberModel) -> bool {
        self.key == other.key
    }

    /// Its threshold on the scene: computed on the first call (progress on standard error
    /// unless `quiet`), then returned as found.
    pub fn threshold(&self, quiet: bool) -> Result<CarrierThreshold, Error> {
        if let Some(found) = self.found.get() {
            return Ok(*found);
        }
        let visitor = CarrierVisitor {
            scene: &self.scene,
            quiet,
        };
        let found =
            with_model(self.name(), visitor).unwrap_or_else(|| Err(unknown_model(&self.scene)))?;
        Ok(*self.found.get_or_init(|| found))
    }

    /// An estimate of its critical load on the scene, for the shift of another model's
    /// buckling analysis (a plate's, or one that failed about $`\lambda = 0`$): the threshold
    /// when found already; for a scene with a fixed direction whose wavenumber is searched, the
    /// search's global level on the half mesh and one analysis on the scene's mesh at its
    /// minimiser (`search::estimate_minimum`: the threshold's $`\lambda_c`$ to within 1e-3
    /// without the refinement on the scene's mesh); otherwise the threshold. Computed once.
    pub fn critical_load_estimate(&self, quiet: bool) -> Result<f64, Error> {
        if let Some(found) = self.found.get() {
            return Ok(found.critical_load);
        }
        if let Some(estimate) = self.estimate.get() {
            return Ok(*estimate);
        }
        let model = &self.scene.model;
        let searched = matches!(model.wavenumber, Wavenumber::Auto)
            && matches!(model.direction, Direction::Fixed(_));
        if !searched {
            return self.threshold(quiet).map(|found| found.critical_load);
        }
        let visitor = EstimateVisitor {
            scene: &self.scene,
            quiet,
        };
        let estimate =
            with_model(self.name(), visitor).unwrap_or_else(|| Err(unknown_model(&self.scene)))?;
        Ok(*self.estimate.get_or_init(|| estimate))
    }
}

/// The models of the registry that select their own wavelength.
fn selecting_models() -> Vec<&'static str> {
    wrinkle_models::catalogue()
        .into_iter()
        .filter(|spec| spec.wavelength_selection().selects_its_own())
        .map(|spec| spec.name)
        .collect()
}

/// Why a model does not select its own wavelength, in words.
fn describe(selection: WavelengthSelection) -> &'static str {
    use wrinkle_runtime::wavelength::CarriedBecause;
    match selection {
        WavelengthSelection::OwnMinimum => "it does",
        WavelengthSelection::Carried(CarriedBecause::Phase) => {
            "its envelope has a phase, a field of role `envelope_imaginary`"
        }
        WavelengthSelection::Carried(CarriedBecause::NoEnvelopeGradient) => {
            "no term reads the gradient of its envelope"
        }
        WavelengthSelection::ResolvedByMesh => {
            "it has no `wavenumber` parameter: its wrinkles are resolved by the mesh"
        }
    }
}

/// The estimate of the wavenumber model's critical load on its scene
/// ([`WavenumberModel::critical_load_estimate`]), with its progress.
struct EstimateVisitor<'a> {
    scene: &'a Scene,
    quiet: bool,
}

impl ModelVisitor for EstimateVisitor<'_> {
    type Output = Result<f64, Error>;
    fn visit<M: EnergyModel>(self, mut model: M) -> Self::Output {
        configure_model(self.scene, &mut model, 1.0)?;
        let mut problem = build_problem(self.scene, model)?;
        let mut factor = analyse(&problem)?;
        let options = WavenumberSearchOptions {
            range: wavenumber_range(self.scene),
            scan_points: SCAN_POINTS,
            ..WavenumberSearchOptions::default()
        };
        let progress = SearchProgress::new(
            &format!("{}: critical load estimate (a shift guess)", M::SPEC.name),
            ProgressSink::standard_error(self.quiet),
        );
        let mut count = 0;
        let mut observer = |_: &WavenumberEvaluation| {
            count += 1;
            progress.evaluation(count, "buckling analysis");
        };
        let estimate = estimate_minimum(
            self.scene,
            &mut problem,
            &mut factor,
            &options,
            &mut observer,
        )?;
        progress.finish(&format!("λ_c ≈ {estimate:.6e}"));
        Ok(estimate)
    }
}

/// The threshold of the wavenumber model on its scene.
struct CarrierVisitor<'a> {
    scene: &'a Scene,
    quiet: bool,
}

impl ModelVisitor for CarrierVisitor<'_> {
    type Output = Result<CarrierThreshold, Error>;
    fn visit<M: EnergyModel>(self, mut model: M) -> Self::Output {
        configure_model(self.scene, &mut model, 1.0)?;
        let mut problem = build_problem(self.scene, model)?;
        let mut factor = analyse(&problem)?;
        let options = ThresholdOptions {
            quiet: self.quiet,
            ..ThresholdOptions::default()
        };
        let threshold = find_threshold_with(self.scene, &mut problem, &mut factor, &options)?;
        let wavenumber = threshold.wavenumber.ok_or_else(|| {
            Error::Solver(format!(
                "the wavenumber model `{}` gave no wavenumber",
                M::SPEC.name
            ))
        })?;
        Ok(CarrierThreshold {
            wavenumber,
            critical_load: threshold.critical_load(),
            direction_degrees: threshold.direction_degrees,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The shipped long strip (example 2, 56 × 16 graded) run with the plate: the estimate of
    /// its wavenumber model's critical load, the plate's shift guess, is the reference
    /// envelope's threshold to 1e-3 ($`\lambda_c`$ is flat at its minimum: the half mesh's
    /// scan to 1 % in $`Q`$, then one analysis on the mesh); and once the threshold is found, the
    /// estimate is its critical load.
    #[test]
    fn long_strip_plate_shift_guess_is_the_reference_envelope_threshold() {
        let mut scene = Scene::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/examples/scenes/long_strip.toml"
        ))
        .unwrap();
        scene.apply_override("model.name=fvk-plate").unwrap();
        let estimated = WavenumberModel::for_scene(&scene).unwrap();
        let estimate = estimated.critical_load_estimate(true).unwrap();
        let found = WavenumberModel::for_scene(&scene).unwrap();
        let threshold = found.threshold(true).unwrap().critical_load;
        eprintln!("estimate {estimate:.9e}, threshold {threshold:.9e}");
        assert!(
            (estimate - threshold).abs() <= 1e-3 * threshold,
            "estimate {estimate:e} against the threshold {threshold:e}"
        );
        assert_eq!(found.critical_load_estimate(true).unwrap(), threshold);
    }
}
