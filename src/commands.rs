//! What the subcommands compute, as library functions that take a scene and return results;
//! nothing here parses arguments or prints — [`crate::cli`] does both.
//!
//! `buckle`, `run` and `models` are here; `compare`, `bench` and `analytic` are the entry points
//! of their own modules ([`crate::compare::compare`], [`crate::bench::bench`],
//! [`crate::analytic::analyse`]). Dependencies go one way:
//! `cli → {commands, compare, bench, analytic} → {threshold, run} → {results, run_outputs} →
//! {setup, physics, output}`, and `compare` and `bench` share [`crate::study`].

use crate::error::Error;
use crate::results::RunReport;
use crate::scene::Scene;
use crate::threshold::{PriorThreshold, Threshold, ThresholdOptions};
use std::path::Path;

/// Linear buckling analysis of a scene (`wrinkle buckle`); progress on standard error unless
/// `quiet`.
pub fn buckle(scene: &Scene, quiet: bool) -> Result<Threshold, Error> {
    crate::threshold::buckle(scene, quiet)
}

/// [`buckle`] that also writes the buckling mode, the wavenumber search and `buckle.json`
/// (`describe` of the threshold) into `output_directory` (`wrinkle buckle --out DIR`, files in
/// `docs/outputs.md`).
pub fn buckle_with_outputs(
    scene: &Scene,
    quiet: bool,
    output_directory: &Path,
    describe: crate::buckle_outputs::Describe,
) -> Result<Threshold, Error> {
    crate::buckle_outputs::buckle_with_outputs(scene, quiet, output_directory, describe)
        .map(|(threshold, _files)| threshold)
}

/// Path following of a scene (`wrinkle run`), writing its outputs into `output_directory`.
/// The report comes back whatever the outcome once every output computed was written; a run
/// that does not reach what was asked says so in [`crate::results::RunOutcome::error`] (exit
/// codes 1 failure, 3 incomplete, 4 validity, 130 interrupted). An `Err` means the run could
/// not be done at all (a scene error, a failed threshold, an output that cannot be written).
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
    crate::run::run_with(scene, output_directory, &options)
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

/// `wrinkle models --show NAME`: one model's description, fields, parameters and terms, and
/// its derivation (provenance, derived energy in DSL syntax, sizes) or that it is hand-written.
pub fn model_details(name: &str) -> Result<String, Error> {
    let catalogue = wrinkle_models::catalogue();
    let Some(spec) = catalogue.iter().find(|spec| spec.name == name) else {
        return Err(Error::Usage(format!(
            "no model `{name}` (registered: {})",
            wrinkle_models::names().join(", ")
        )));
    };
    let fields: Vec<String> = spec
        .fields
        .iter()
        .zip(spec.field_roles)
        .map(|(f, r)| format!("{f} [{}]", r.name()))
        .collect();
    let terms: Vec<String> = spec
        .terms
        .iter()
        .map(|t| format!("{} ({:?} quadrature)", t.name, t.quadrature))
        .collect();
    let derivation = spec.derivation.map_or_else(
        || "hand-written (not derived by the DSL)\n".to_string(),
        |text| text.to_string(),
    );
    Ok(format!(
        "{}\n    {}\n    fields: {}\n    parameters: {}\n    terms: {}\n{derivation}",
        spec.name,
        spec.description,
        fields.join(", "),
        spec.parameters.join(", "),
        terms.join(", ")
    ))
}
