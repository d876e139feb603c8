//! The threshold as a result ([`ThresholdSummary`]): every number `wrinkle buckle --json`
//! prints and a run's `summary.json` holds under `threshold` (keys documented in
//! `docs/outputs.md`), computed once — the closed form included — and serialised as it is.

use super::{Threshold, ValidityWarning, closed_form_threshold, load_unit};
use crate::scene::{LoadKind, Scene};
use serde::Serialize;

/// The closed-form threshold (THEORY.md §8, eq. 42 minimised) beside the computed one, where it
/// applies to the scene ([`closed_form_threshold`]); every field `None` otherwise.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct ClosedFormComparison {
    /// $`\lambda_c`$ of eq. (42) minimised.
    pub closed_form_critical_load: Option<f64>,
    /// Its minimiser $`Q`$ (1/mm).
    pub closed_form_wavenumber: Option<f64>,
    /// $`(\lambda_c - \lambda_c^{(42)})/\lambda_c^{(42)}`$.
    pub closed_form_relative_difference: Option<f64>,
}

impl ClosedFormComparison {
    /// The closed form of `scene` beside the computed critical load `critical`.
    pub fn of(scene: &Scene, critical: f64) -> Self {
        match closed_form_threshold(scene) {
            Some((load, q)) => ClosedFormComparison {
                closed_form_critical_load: Some(load),
                closed_form_wavenumber: Some(q),
                closed_form_relative_difference: Some((critical - load) / load),
            },
            None => ClosedFormComparison::default(),
        }
    }
}

/// The threshold of a scene as it is reported.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThresholdSummary {
    /// Registry name of the model.
    pub model: &'static str,
    /// $`\lambda_c`$.
    pub critical_load: f64,
    /// `load.kind`: `biaxial` or `strip`.
    pub load_kind: &'static str,
    /// Unit of $`\lambda`$ ([`load_unit`]).
    pub load_unit: &'static str,
    /// $`N_X = -\lambda_c`$ (N/mm) under the biaxial load.
    pub n_x: Option<f64>,
    /// Wavenumber $`Q`$ (1/mm) of an envelope model.
    pub wavenumber: Option<f64>,
    /// Wavelength (mm).
    pub wavelength: Option<f64>,
    /// Where $`Q`$ came from ([`Threshold::wavenumber_source`]).
    pub wavenumber_mode: String,
    /// Wave direction $`\theta`$ (degrees from X, [`Threshold::direction_degrees`]).
    pub direction: f64,
    /// How it was found ([`Threshold::direction_source`]).
    pub direction_mode: String,
    /// Free unknowns.
    pub dofs: usize,
    /// Elements of the mesh.
    pub elements: usize,
    /// Linear buckling analyses done.
    pub buckling_evaluations: usize,
    /// Relative residual of the first eigenpair.
    pub eigen_residual: f64,
    /// Iterations of the eigen-solver.
    pub eigen_iterations: usize,
    /// The closed form beside $`\lambda_c`$.
    #[serde(flatten)]
    pub closed_form: ClosedFormComparison,
    /// Whether the Legendre–Hadamard condition holds everywhere at $`\lambda_c`$.
    pub elliptic_at_threshold: bool,
    /// Its worst margin.
    pub ellipticity_margin: f64,
    /// Where (mm).
    pub ellipticity_worst_location: [f64; 2],
    /// In which field.
    pub ellipticity_worst_field: &'static str,
    /// Area fraction where it fails.
    pub ellipticity_violated_area_fraction: f64,
    /// Notes for the user.
    pub notes: Vec<String>,
    /// Failed validity checks.
    pub warnings: Vec<ValidityWarning>,
    /// Seconds spent.
    pub seconds: f64,
}

impl ThresholdSummary {
    /// The summary of `threshold`, found on `scene`.
    pub fn new(scene: &Scene, threshold: &Threshold) -> Self {
        let critical = threshold.critical_load();
        let ellipticity = &threshold.ellipticity;
        ThresholdSummary {
            model: threshold.model,
            critical_load: critical,
            load_kind: scene.load.kind.as_str(),
            load_unit: load_unit(scene),
            n_x: (scene.load.kind == LoadKind::Biaxial).then_some(-critical),
            wavenumber: threshold.wavenumber,
            wavelength: threshold.wavelength,
            wavenumber_mode: threshold.wavenumber_source.clone(),
            direction: threshold.direction_degrees,
            direction_mode: threshold.direction_source.clone(),
            dofs: threshold.dofs,
            elements: scene.mesh.elements_x * scene.mesh.elements_y,
            buckling_evaluations: threshold.evaluations,
            eigen_residual: threshold.buckling.residuals[0],
            eigen_iterations: threshold.buckling.eigen_iterations,
            closed_form: ClosedFormComparison::of(scene, critical),
            elliptic_at_threshold: ellipticity.elliptic,
            ellipticity_margin: ellipticity.worst_margin,
            ellipticity_worst_location: ellipticity.location,
            ellipticity_worst_field: ellipticity.field,
            ellipticity_violated_area_fraction: ellipticity.violated_fraction,
            notes: threshold.notes.clone(),
            warnings: threshold.warnings.clone(),
            seconds: threshold.seconds,
        }
    }
}
