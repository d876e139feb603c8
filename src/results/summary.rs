//! The run's result ([`RunSummary`]) and its parts, typed: `summary.json` is their `serde`
//! serialisation, key for key (documented in `docs/outputs.md`).

use super::RunOutcome;
use crate::output::{PathPoint, Warning};
use crate::threshold::ThresholdSummary;
use serde::Serialize;
use serde::ser::{SerializeStruct, Serializer};

/// Everything a run produced, built once before any file is written ([`RunSummary::new`]); the
/// writers only serialise it. `summary.json` is this struct (the fields marked as not serialised
/// excepted) plus the list of files written.
#[derive(Clone, Debug, Serialize)]
pub struct RunSummary {
    /// Registry name of the model.
    pub model: &'static str,
    /// `solver.method`: `anm` or `riks`.
    pub method: &'static str,
    /// Free unknowns.
    pub dofs: usize,
    /// Wavenumber $`Q`$ (1/mm) of an envelope model.
    pub wavenumber: Option<f64>,
    /// Wavelength (mm).
    pub wavelength: Option<f64>,
    /// `load.kind`: `biaxial` or `strip`.
    pub load_kind: &'static str,
    /// Unit of $`\lambda`$.
    pub load_unit: &'static str,
    /// $`\lambda_c`$ of linear buckling.
    pub linear_buckling_load: f64,
    /// $`\lambda_c`$ of eq. (42) where it applies (the threshold's closed form).
    pub closed_form_critical_load: Option<f64>,
    /// The threshold, with its closed form.
    pub threshold: ThresholdSummary,
    /// The bifurcation the path detected, if any.
    pub detected_bifurcation: Option<DetectedBifurcation>,
    /// The first step end where strong ellipticity failed, if any.
    pub loss_of_ellipticity: Option<LossOfEllipticity>,
    /// Physical amplitude (mm) of the imperfection's response on the unloaded sheet.
    pub imperfection_amplitude: f64,
    /// The imperfection's shape as used, `uniform` or `mode` (`solver.imperfection` resolved
    /// for the model; a note says so where it differs from what the scene asked).
    pub imperfection_shape: &'static str,
    /// Why the path stopped, in words.
    pub stop: String,
    /// How the run ended: `outcome`, `outcome_reason`, `exit_code`, `failed`.
    #[serde(flatten)]
    pub outcome: RunOutcome,
    /// Accepted solver steps.
    pub steps: usize,
    /// What the path cost, counted.
    pub statistics: PathCounts,
    /// Where the time went (s).
    pub timings: Timings,
    /// The memory the run took.
    pub memory: Memory,
    /// The solver's warnings.
    pub solver_warnings: Vec<String>,
    /// The ANM steps (empty for Riks).
    pub anm_steps: Vec<AnmStepRecord>,
    /// The VTU files written, each with its load.
    pub vtu: Vec<VtuFile>,
    /// Loads of `output.vtu_loads` the path did not reach.
    pub unreached_vtu_loads: Vec<f64>,
    /// The path, with the closed-form amplitude of each point where it applies.
    pub path: Vec<PathPoint>,
    /// The effective scene, as echoed.
    pub scene: serde_json::Value,
    /// What the report and the terminal show besides the table: validity checks, loss of
    /// ellipticity, unstable branches, notes — among them every value of the scene that was
    /// not used as given — and solver warnings; serialised as `notes`, each
    /// `{severity, title, detail}`.
    #[serde(rename = "notes")]
    pub notices: Vec<Warning>,
    /// The one-mode closed form (eq. 62) over the path's load range, as
    /// $`(\lambda/\lambda_c, 2a/h)`$, where it applies (not serialised; the response plot draws it).
    #[serde(skip)]
    pub closed_form_amplitudes: Option<Vec<(f64, f64)>>,
}

/// A bifurcation detected on the path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct DetectedBifurcation {
    /// Its load.
    pub load: f64,
    /// The step it was found in.
    pub step: usize,
    /// Relative to $`\lambda_c`$ of linear buckling.
    pub relative_difference_to_linear_buckling: f64,
}

/// Where and how strong ellipticity first failed on the path.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct LossOfEllipticity {
    /// The load.
    pub load: f64,
    /// The worst point (mm).
    pub location: [f64; 2],
    /// The worst direction (radians from X).
    pub direction_rad: f64,
    /// The field where it is worst.
    pub field: &'static str,
    /// The worst margin.
    pub margin: f64,
    /// Area fraction where it fails.
    pub area_fraction: f64,
}

/// What the path cost, counted (`statistics` of `summary.json`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PathCounts {
    /// Numeric factorisations of the tangent.
    pub factorizations: usize,
    /// Of `factorizations`, the bifurcation predictions' and locations' (timed in
    /// `timings.bifurcation_prediction`, not in `timings.factorization`).
    pub prediction_factorizations: usize,
    /// Tangent assemblies.
    pub tangent_assemblies: usize,
    /// Residual assemblies.
    pub residual_assemblies: usize,
    /// Series right-hand side assemblies (ANM).
    pub series_assemblies: usize,
    /// Corrector iterations.
    pub corrections: usize,
    /// Rejected steps.
    pub rejected_steps: usize,
}

/// Where the time went, in seconds (`timings` of `summary.json`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Timings {
    /// The threshold (buckling and wavenumber search).
    pub threshold: f64,
    /// Tangent assemblies of the path.
    pub assembly: f64,
    /// Factorisations of the path.
    pub factorization: f64,
    /// ANM series.
    pub series: f64,
    /// Of `series`, the solves.
    pub series_solves: f64,
    /// Bifurcation prediction and location.
    pub bifurcation_prediction: f64,
    /// Residual checks.
    pub residual_checks: f64,
    /// Legendre–Hadamard checks of the step ends.
    pub ellipticity: f64,
    /// Recording accepted points.
    pub recording: f64,
    /// The whole path.
    pub path: f64,
    /// The whole run before its outputs.
    pub total: f64,
}

/// The memory a run took (`memory` of `summary.json`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Memory {
    /// Peak resident memory of the run (bytes; Linux).
    pub peak_resident_bytes: Option<u64>,
    /// The ANM's Taylor tape (bytes).
    pub taylor_tape_bytes: Option<usize>,
    /// Entries of the tangent's factor.
    pub factor_nonzeros: Option<usize>,
}

/// One ANM step as reported (`anm_steps` of `summary.json`).
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct AnmStepRecord {
    /// Step index.
    pub step: usize,
    /// Load at its start.
    pub load_start: f64,
    /// Load at its end.
    pub load_end: f64,
    /// Path-parameter range used.
    pub step_length: f64,
    /// Range the plain series allowed.
    pub series_step_length: f64,
    /// Range Padé allowed (when enabled).
    pub pade_step_length: Option<f64>,
    /// Range the exponential map allowed (when enabled and the series showed a singularity
    /// behind the step).
    pub mapped_step_length: Option<f64>,
    /// Distance of the singularity behind the step's start its series showed, if any.
    pub singularity_behind: Option<f64>,
    /// Relative residual at the accepted end point.
    pub end_residual: f64,
    /// Newton iterations of the correction (0 = none needed).
    pub correction_iterations: usize,
    /// Times the step was redone because it jumped over a critical point.
    pub crossings_redone: usize,
    /// Radius of convergence estimated from a geometric tail of the series, if any.
    pub geometric_radius: Option<f64>,
    /// Bifurcation load predicted by linear buckling about the step's start.
    pub predicted_bifurcation: Option<f64>,
    /// Negative eigenvalues of the tangent at the step's start.
    pub negative_pivots: Option<usize>,
    /// `false` for a last step the stop criterion ended inside.
    pub completed: bool,
    /// The step's parameter (and lengths) is the buckling mode's amplitude, not the pseudo
    /// arc length.
    pub mode_parameter: bool,
}

/// A VTU file written, with its load.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VtuFile {
    /// The load of the state it holds.
    pub load: f64,
    /// Its name in the run directory.
    pub file: String,
}

/// Name of the VTU file of the fields at the last point.
pub const FINAL_FIELDS_FILE: &str = "fields_final.vtu";
/// Name of the VTU file of the sampled surface at the last point.
pub const FINAL_SURFACE_FILE: &str = "surface_final.vtu";

/// Name of the VTU file of the fields at `load`, one of the requested `loads`
/// (`output.vtu_loads`): `fields_load_L.vtu` with $`L`$ to 6 decimals, or to as many more (up
/// to [`MAX_FIELDS_FILE_DECIMALS`]) as keep the names of all requested loads distinct and no
/// non-zero load at zero (`[1e-7, 2e-7]` gives `fields_load_0.0000001.vtu` and
/// `fields_load_0.0000002.vtu`); beyond that, $`L`$ in the shortest scientific notation that
/// reads back as the load (`fields_load_1e-300.vtu`), distinct for distinct loads.
pub fn fields_file_at(load: f64, loads: &[f64]) -> String {
    match fields_file_decimals(loads) {
        Some(decimals) => format!("fields_load_{load:.decimals$}.vtu"),
        None => format!("fields_load_{load:e}.vtu"),
    }
}

/// Most decimals of a load in a `fields_load_L.vtu` name before scientific notation.
pub const MAX_FIELDS_FILE_DECIMALS: usize = 12;

/// The fewest decimals from 6 to [`MAX_FIELDS_FILE_DECIMALS`] that print every one of `loads`
/// distinctly and no non-zero one as zero; `None` when there are none.
fn fields_file_decimals(loads: &[f64]) -> Option<usize> {
    (6..=MAX_FIELDS_FILE_DECIMALS).find(|&decimals| {
        let texts: Vec<String> = loads.iter().map(|l| format!("{l:.decimals$}")).collect();
        let zero = format!("{:.decimals$}", 0.0);
        let distinct = texts
            .iter()
            .enumerate()
            .all(|(index, text)| !texts[..index].contains(text));
        let faithful = loads.iter().zip(&texts).all(|(load, text)| {
            *load == 0.0 || (text != &zero && text.trim_start_matches('-') != zero)
        });
        distinct && faithful
    })
}

/// `outcome` (its name), `outcome_reason`, `exit_code` and `failed`.
impl Serialize for RunOutcome {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut fields = serializer.serialize_struct("RunOutcome", 4)?;
        fields.serialize_field("outcome", self.name())?;
        fields.serialize_field("outcome_reason", &self.reason())?;
        fields.serialize_field("exit_code", &self.exit_code())?;
        fields.serialize_field("failed", &self.failure().is_some())?;
        fields.end()
    }
}
