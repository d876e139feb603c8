//! What one benchmark point measured ([`BenchRow`]: settings, cost split, results, errors) and
//! the whole benchmark ([`Bench`]).

use super::plan::{Method, Sweep};

/// One point of the benchmark: its settings, cost, results and errors. Result and error
/// columns are `None` (empty in the CSV) when the run failed, stopped early or did not reach
/// the level; cost columns are kept whenever the run produced a summary.
#[derive(Clone, Debug, serde::Serialize)]
pub struct BenchRow {
    /// Model name.
    pub model: String,
    /// Which sweep.
    pub sweep: Sweep,
    /// `reached`, `invalid` (a validity check failed; numbers kept), `incomplete`, `failed`
    /// or `error` (the run could not start).
    pub outcome: String,
    /// Why the run did not reach its target, if it did not.
    pub reason: Option<String>,
    /// Settings of the point.
    #[serde(flatten)]
    pub settings: SettingsRecord,
    /// Free unknowns.
    pub dofs: Option<usize>,
    /// Wavenumber $`Q`$ (1/mm) of envelope models.
    pub wavenumber: Option<f64>,
    /// Whether $`Q`$ was fixed to the reference's instead of searched.
    pub wavenumber_fixed: bool,
    /// Accepted solver steps.
    pub steps: Option<usize>,
    /// Factorisations of the tangent along the path.
    pub factorizations: Option<usize>,
    /// Of `factorizations`, the bifurcation predictions' (timed in `time_bifurcation`).
    pub prediction_factorizations: Option<usize>,
    /// Wall time of the threshold (buckling and wavenumber search), s.
    pub time_threshold: Option<f64>,
    /// Wall time of the path following, s.
    pub time_path: Option<f64>,
    /// Wall time of the whole run (without writing files), s.
    pub time_total: Option<f64>,
    /// Where the path's time went, and the memory it took.
    #[serde(flatten)]
    pub cost: CostSplit,
    /// What the point measured.
    #[serde(flatten)]
    pub measured: Measurement,
    /// Relative errors against the reference.
    #[serde(flatten)]
    pub errors: Errors,
}

/// The path's time by part (seconds, summed over the path; `timings` of `summary.json`) and
/// the run's memory. The parts overlap nothing but do not cover everything: the rest of
/// `time_path` is Padé approximants, step-length and crossing bookkeeping.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct CostSplit {
    /// Tangent assemblies.
    pub time_assembly: Option<f64>,
    /// Numeric factorisations.
    pub time_factorization: Option<f64>,
    /// ANM series: Taylor-mode right-hand sides and their solves (0 for Riks).
    pub time_series: Option<f64>,
    /// Of `time_series`, the forward/backward solves.
    pub time_series_solves: Option<f64>,
    /// `f64` residual evaluations: checks of step ends and interior points, corrector iterations.
    pub time_residual_checks: Option<f64>,
    /// Bifurcation prediction and location (eigen-solves).
    pub time_bifurcation: Option<f64>,
    /// Recording accepted points, with the Legendre–Hadamard check of each step end.
    pub time_recording: Option<f64>,
    /// A step's floor (issue 30): one factorisation plus the $`N - 1`$ series solves with it,
    /// $`t_\text{fact}/n_\text{fact} + (N-1)\,t_\text{solves}/n_\text{solves}`$ from the
    /// run's own means, $`n_\text{fact}`$ without the predictions' factorisations (empty for
    /// Riks, which has no series).
    pub time_step_floor: Option<f64>,
    /// Peak resident memory of the run, MB ($`10^6`$ bytes; Linux only).
    pub peak_memory_mb: Option<f64>,
    /// The ANM's Taylor tape, MB (empty for Riks).
    pub tape_mb: Option<f64>,
    /// Entries of the tangent's factor (fill-in included).
    pub factor_nonzeros: Option<usize>,
}

/// [`Settings`](super::plan::Settings) as serialised into a row.
#[derive(Clone, Copy, Debug, serde::Serialize)]
pub struct SettingsRecord {
    /// Elements along X.
    pub nx: usize,
    /// Elements along Y.
    pub ny: usize,
    /// ANM order.
    pub order: usize,
    /// Series tolerance.
    pub series_tolerance: f64,
    /// Path-following method.
    pub method: Method,
}

/// The three results of a point.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Measurement {
    /// $`\lambda_c`$ (as λ).
    pub critical_load: Option<f64>,
    /// $`\lambda`$ where the maximum $`a/h`$ first reaches [`AMPLITUDE_LEVEL`](crate::bench::AMPLITUDE_LEVEL).
    pub load_at_amplitude_1: Option<f64>,
    /// Maximum $`a/h`$ at $`\lambda = `$ [`LOAD_RATIO`](crate::bench::LOAD_RATIO) $`\lambda_c`$.
    pub amplitude_at_1_1: Option<f64>,
}

/// Relative errors of a [`Measurement`].
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Errors {
    /// Of $`\lambda_c`$ against the reference.
    pub error_critical_load: Option<f64>,
    /// Of $`\lambda_c`$ against the exact minimum of eq. (42), where it applies.
    pub error_critical_load_closed_form: Option<f64>,
    /// Of $`\lambda_{a/h=1}`$ against the reference.
    pub error_load_at_amplitude_1: Option<f64>,
    /// Of $`a/h`$ at $`1.1\lambda_c`$ against the reference.
    pub error_amplitude_at_1_1: Option<f64>,
}

/// The whole benchmark.
#[derive(Clone, Debug)]
pub struct Bench {
    /// Rows, model by model: reference, mesh, order, tolerance.
    pub rows: Vec<BenchRow>,
    /// Exact minimum of eq. (42) when the scene is the clamped biaxial rectangle.
    pub closed_form_critical_load: Option<f64>,
    /// Unit of the load λ.
    pub load_unit: &'static str,
    /// Reduced sweep.
    pub quick: bool,
}
