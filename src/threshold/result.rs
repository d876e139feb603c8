//! The threshold of a scene ([`Threshold`]): the buckling analysis at the critical load, how
//! its wavenumber was found, its notes and its failed validity checks.

use wrinkle_runtime::solve::buckling::LinearBuckling;
use wrinkle_runtime::solve::ellipticity::EllipticityReport;
use wrinkle_runtime::solve::wavenumber::WavenumberEvaluation;

/// The threshold of a scene and how it was found.
#[derive(Clone, Debug)]
pub struct Threshold {
    /// Registry name of the model.
    pub model: &'static str,
    /// Linear buckling at the threshold (critical loads, modes, pre-buckling state and rate).
    pub buckling: LinearBuckling,
    /// Strong ellipticity at the threshold.
    pub ellipticity: EllipticityReport,
    /// Load the buckling analysis linearised about (0, or a shift, see `robust_buckling`).
    pub reference_load: f64,
    /// Wavenumber $`Q`$ (1/mm) of an envelope model.
    pub wavenumber: Option<f64>,
    /// Wavelength (mm): $`2\pi/Q`$, or read from the plate's mode.
    pub wavelength: Option<f64>,
    /// `"fixed"`, `"auto"` (minimised), `"auto (MODEL)"` (the minimiser of `MODEL`, the scene's
    /// `model.wavenumber_model`), `"auto (reused)"` or `"mode"` (plate).
    pub wavenumber_source: String,
    /// Direction $`\theta`$ of the wave vector (degrees from X): `model.direction`, or the
    /// angle chosen for `"auto"`.
    pub direction_degrees: f64,
    /// How the direction was found: `"fixed"` (`model.direction`), `"auto (lowest threshold)"`
    /// (minimised), `"auto (mode)"` (a plate's mode) or `"auto (MODEL)"` (the wavenumber
    /// model's); a note says how.
    pub direction_source: String,
    /// Linear buckling analyses done.
    pub evaluations: usize,
    /// The wavenumber search, when there was one.
    pub search: Vec<WavenumberEvaluation>,
    /// Notes for the user (a parameter not used, where the wavenumber came from).
    pub notes: Vec<String>,
    /// Failed validity checks.
    pub warnings: Vec<ValidityWarning>,
    /// Free unknowns.
    pub dofs: usize,
    /// Seconds spent.
    pub seconds: f64,
}

impl Threshold {
    /// Critical load $`\lambda_c`$.
    pub fn critical_load(&self) -> f64 {
        self.buckling.critical_loads[0]
    }

    /// The first failed validity check the scene does not accept (`validity.accept`), as the
    /// reason of exit code 4 — shared by `buckle` and `run`.
    pub fn validity_failure(&self, validity: &crate::scene::ValiditySpec) -> Option<String> {
        self.warnings
            .iter()
            .find(|w| !validity.accepts(w.check))
            .map(|w| {
                format!(
                    "{}: {} (`validity.accept = [\"{}\"]` accepts it)",
                    w.check, w.message, w.check
                )
            })
    }
}

/// A validity check that failed.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ValidityWarning {
    /// Short identifier: `scale_separation`, `ellipticity`, `mode_resolution`.
    pub check: &'static str,
    /// What was found and what it means.
    pub message: String,
}
