//! The commands behind the CLI, as library functions: each takes a scene and returns its
//! results; the CLI only parses arguments and prints. Dependencies go one way:
//! `cli → commands → {threshold, run, compare} → {setup, physics, output}`.

use crate::error::Error;
use crate::run::{RunOutcome, RunReport};
use crate::scene::Scene;
use crate::threshold::{PriorThreshold, Threshold, ThresholdOptions};
use std::path::Path;

/// Linear buckling analysis of a scene (`wrinkle buckle`); progress on standard error unless
/// `quiet`.
pub fn buckle(scene: &Scene, quiet: bool) -> Result<Threshold, Error> {
    crate::threshold::buckle(scene, quiet)
}

/// Path following of a scene (`wrinkle run`), writing its outputs into `output_directory`.
/// A run that does not reach what was asked is an `Err` with its exit code (1 failure,
/// 3 incomplete, 4 validity), but only after every output computed so far was written.
///
/// With `prior` (`--threshold FILE`), the wavenumber search is replaced by one analysis at the
/// wavenumber of an earlier threshold of the same scene.
pub fn run(
    scene: &Scene,
    output_directory: &Path,
    quiet: bool,
    prior: Option<&PriorThreshold>,
) -> Result<RunReport, Error> {
    let options = ThresholdOptions {
        quiet,
        prior,
        wavenumber_model: None,
    };
    let report = crate::run::run_with(scene, output_directory, &options)?;
    // The summary table goes to stdout whatever the outcome (a closed stdout is not an error).
    {
        use std::io::Write;
        let _ = std::io::stdout().write_all(report.summary_text.as_bytes());
    }
    let written = format!("(outputs written to {})", output_directory.display());
    match &report.summary.outcome {
        RunOutcome::Reached => Ok(report),
        RunOutcome::Failed(why) => Err(Error::Solver(format!("{why} {written}"))),
        RunOutcome::Incomplete(why) => Err(Error::Incomplete(format!("{why} {written}"))),
        RunOutcome::Invalid(why) => Err(Error::Invalid(format!("{why} {written}"))),
        RunOutcome::Interrupted(why) => Err(Error::Interrupted(format!("{why} {written}"))),
    }
}

/// The model registry: `(name, description, fields with roles, parameters)` for every model.
pub fn models() -> Vec<(String, String, Vec<String>, Vec<String>)> {
    wrinkle_models::catalogue()
        .into_iter()
        .map(|s| {
            (
                s.name.to_string(),
                s.description.to_string(),
                s.fields
                    .iter()
                    .zip(s.field_roles)
                    .map(|(f, r)| format!("{f} [{}]", r.name()))
                    .collect(),
                s.parameters.iter().map(|p| p.to_string()).collect(),
            )
        })
        .collect()
}
