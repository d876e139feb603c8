//! `wrinkle compare`: the same scene through several models, side by side.
//!
//! Each model runs into `OUT/MODEL/` exactly as `wrinkle run` would (same problem, same
//! imperfection size, same amplitude target); then `OUT/compare.csv`, `OUT/compare.json` and
//! the overlaid response plot `OUT/compare.png|svg` put the thresholds, wavelengths and the
//! loads at given physical amplitudes next to each other. A model that fails does not stop the
//! others: its row says why. `MODEL:KEY=VALUE` overrides apply to one model only (a plate
//! needs a mesh that resolves its wrinkles; an envelope model does not).
//!
//! The whole command line is checked before any model runs — the model list (no empty, unknown
//! or repeated entry), every override, every model's scene — and `OUT` is locked
//! ([`DirectoryLock`]): a second comparison into it fails at once.

use crate::error::{Error, io_error, output_directory_error};
use crate::output::{
    DirectoryLock, Quantity, Response, ResponsePoint, plot_comparison, write_bytes_atomically,
    write_json,
};
use crate::results::{RunSummary, load_quantity};
use crate::run::run_with;
use crate::scene::Scene;
use crate::study::{check_model_list, load_at_amplitude, number_cell};
use crate::threshold::{ThresholdOptions, WavenumberModel, closed_form_threshold};
use serde_json::json;
use std::path::Path;

/// Physical amplitudes $`a/h`$ at which the loads are compared.
pub const AMPLITUDE_LEVELS: [f64; 3] = [0.5, 1.0, 2.0];

/// One model's line of the comparison.
#[derive(Clone, Debug, serde::Serialize)]
pub struct CompareRow {
    /// Model name.
    pub model: String,
    /// `reached`, `incomplete`, `invalid`, `failed` or `error`.
    pub outcome: String,
    /// Why it did not reach its target, if it did not.
    pub reason: Option<String>,
    /// Critical load of linear buckling.
    pub critical_load: Option<f64>,
    /// $`\lambda_c`$ relative to the first model's.
    pub critical_load_ratio: Option<f64>,
    /// Wavenumber $`Q`$ (1/mm), envelope models.
    pub wavenumber: Option<f64>,
    /// Wavelength (mm).
    pub wavelength: Option<f64>,
    /// Load at which the maximum physical amplitude first reaches each of
    /// [`AMPLITUDE_LEVELS`] (linear interpolation along the path).
    pub load_at_amplitude: Vec<Option<f64>>,
    /// Free unknowns.
    pub dofs: Option<usize>,
    /// Wall-clock seconds of the run.
    pub seconds: Option<f64>,
}

/// Result of a comparison.
#[derive(Clone, Debug)]
pub struct Comparison {
    /// One row per model, in the order asked.
    pub rows: Vec<CompareRow>,
    /// The closed-form threshold (eq. 42) when the scene has one.
    pub closed_form_critical_load: Option<f64>,
}

/// One model's row from the result of its run.
fn row_of(model: &str, summary: &RunSummary) -> CompareRow {
    let finite = |value: Option<f64>| value.filter(|v| v.is_finite());
    CompareRow {
        model: model.to_string(),
        outcome: summary.outcome.name().into(),
        reason: summary.outcome.reason().map(str::to_string),
        critical_load: finite(Some(summary.linear_buckling_load)),
        critical_load_ratio: None,
        wavenumber: finite(summary.wavenumber),
        wavelength: finite(summary.wavelength),
        load_at_amplitude: AMPLITUDE_LEVELS
            .iter()
            .map(|&a| load_at_amplitude(&summary.path, a))
            .collect(),
        dofs: Some(summary.dofs),
        seconds: finite(Some(summary.timings.total)),
    }
}

/// One model's response in the overlaid plot, from the result of its run.
fn response_of(model: &str, summary: &RunSummary, load: &Quantity) -> Option<Response> {
    let critical = Some(summary.linear_buckling_load).filter(|l| l.is_finite())?;
    let response_points = summary
        .path
        .iter()
        .map(|p| ResponsePoint {
            load: p.lambda,
            max_amplitude_over_h: p.max_amplitude_over_h,
            centre_amplitude_over_h: Some(p.centre_amplitude_over_h),
            step_end: !p.interior,
        })
        .collect();
    Some(Response::new(
        model,
        load.clone(),
        critical,
        response_points,
    ))
}

/// Runs `scene` with each of `models` into `directory/MODEL/` and writes the comparison files.
pub fn compare(
    scene: &Scene,
    models: &[String],
    model_overrides: &[String],
    directory: &Path,
    quiet: bool,
) -> Result<Comparison, Error> {
    let scenes = model_scenes(scene, models, model_overrides)?;
    let _lock = DirectoryLock::inside(directory).map_err(output_directory_error(directory))?;
    let load = load_quantity(scene);
    // One wavenumber model for every model that needs it: its threshold is computed once.
    let wavenumber_model = WavenumberModel::for_scene(scene)?;
    let options = ThresholdOptions {
        quiet,
        prior: None,
        wavenumber_model: Some(&wavenumber_model),
    };
    let mut rows = Vec::new();
    let mut responses = Vec::new();
    for (model, one) in models.iter().zip(&scenes) {
        let out = directory.join(model);
        match run_with(one, &out, &options) {
            Ok(report) => {
                rows.push(row_of(model, &report.summary));
                responses.extend(response_of(model, &report.summary, &load));
            }
            Err(error @ Error::Scene { .. }) => return Err(error),
            Err(error) => rows.push(CompareRow {
                model: model.clone(),
                outcome: "error".into(),
                reason: Some(error.to_string()),
                critical_load: None,
                critical_load_ratio: None,
                wavenumber: None,
                wavelength: None,
                load_at_amplitude: vec![None; AMPLITUDE_LEVELS.len()],
                dofs: None,
                seconds: None,
            }),
        }
    }
    let first = rows.first().and_then(|r| r.critical_load);
    for row in &mut rows {
        row.critical_load_ratio = row.critical_load.zip(first).map(|(l, f)| l / f);
    }
    let comparison = Comparison {
        rows,
        closed_form_critical_load: closed_form_threshold(scene).map(|(l, _)| l),
    };
    write_comparison(scene, &comparison, &responses, directory)?;
    Ok(comparison)
}

/// The scene of each of `models` — `scene` with its model and its `MODEL:KEY=VALUE`
/// overrides — every one checked before any of them runs, as is the list itself
/// ([`check_model_list`]).
fn model_scenes(
    scene: &Scene,
    models: &[String],
    model_overrides: &[String],
) -> Result<Vec<Scene>, Error> {
    check_model_list(models)?;
    let overrides = parse_model_overrides(models, model_overrides)?;
    models
        .iter()
        .map(|model| {
            let mut one = scene.clone();
            one.model.name = model.clone();
            for (name, assignment) in &overrides {
                if name == model {
                    one.apply_override(assignment)?;
                }
            }
            one.validate()?;
            Ok(one)
        })
        .collect()
}

/// Splits `MODEL:KEY=VALUE` overrides; the model must be one of `models`.
fn parse_model_overrides(
    models: &[String],
    overrides: &[String],
) -> Result<Vec<(String, String)>, Error> {
    overrides
        .iter()
        .map(|text| {
            let (model, assignment) = text.split_once(':').ok_or_else(|| {
                Error::Usage(format!(
                    "--model-set `{text}`: expected MODEL:KEY=VALUE, e.g. fvk-plate:mesh.nx=128"
                ))
            })?;
            if !models.iter().any(|m| m == model) {
                return Err(Error::Usage(format!(
                    "--model-set `{text}`: `{model}` is not among the compared models ({})",
                    models.join(", ")
                )));
            }
            Ok((model.to_string(), assignment.to_string()))
        })
        .collect()
}

/// `compare.csv`, `compare.json`, `compare.png|svg`.
fn write_comparison(
    scene: &Scene,
    comparison: &Comparison,
    responses: &[Response],
    directory: &Path,
) -> Result<(), Error> {
    let mut csv =
        String::from("model,outcome,critical_load,critical_load_ratio,wavenumber,wavelength");
    for a in AMPLITUDE_LEVELS {
        csv.push_str(&format!(",load_at_amplitude_{a}"));
    }
    csv.push_str(",dofs,seconds\n");
    for row in &comparison.rows {
        let mut line = vec![
            row.model.clone(),
            row.outcome.clone(),
            number_cell(row.critical_load),
            number_cell(row.critical_load_ratio),
            number_cell(row.wavenumber),
            number_cell(row.wavelength),
        ];
        line.extend(row.load_at_amplitude.iter().map(|v| number_cell(*v)));
        line.push(row.dofs.map(|d| d.to_string()).unwrap_or_default());
        line.push(number_cell(row.seconds));
        csv.push_str(&line.join(","));
        csv.push('\n');
    }
    let path = directory.join("compare.csv");
    write_bytes_atomically(&path, csv.as_bytes()).map_err(io_error(&path))?;
    let path = directory.join("compare.json");
    let value = json!({
        "scene": scene.echo_json(),
        "load_unit": crate::threshold::load_unit(scene),
        "amplitude_levels": AMPLITUDE_LEVELS,
        "closed_form_critical_load": comparison.closed_form_critical_load,
        "models": comparison.rows,
    });
    write_json(&path, &value).map_err(io_error(&path))?;
    if !responses.is_empty() && scene.output.plots {
        let stem = directory.join("compare");
        plot_comparison(
            &stem,
            "Physical wrinkle amplitude, model by model",
            responses,
        )
        .map_err(io_error(&stem))?;
    }
    Ok(())
}

/// The comparison as a text table for the terminal.
pub fn comparison_table(comparison: &Comparison, unit: &str) -> String {
    let mut text = format!(
        "{:<20} {:>14} {:>8} {:>12} {:>14} {:>14} {:>14}  outcome\n",
        "model",
        format!("λ_c ({unit})"),
        "ratio",
        "wavelength",
        "λ(a/h=0.5)",
        "λ(a/h=1)",
        "λ(a/h=2)"
    );
    let f = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.6e}"));
    for row in &comparison.rows {
        text.push_str(&format!(
            "{:<20} {:>14} {:>8} {:>12} {:>14} {:>14} {:>14}  {}\n",
            row.model,
            f(row.critical_load),
            row.critical_load_ratio
                .map_or("—".into(), |r| format!("{r:.4}")),
            row.wavelength.map_or("—".into(), |l| format!("{l:.3} mm")),
            f(row.load_at_amplitude[0]),
            f(row.load_at_amplitude[1]),
            f(row.load_at_amplitude[2]),
            match &row.reason {
                Some(reason) => format!("{}: {reason}", row.outcome),
                None => row.outcome.clone(),
            }
        ));
    }
    if let Some(l) = comparison.closed_form_critical_load {
        text.push_str(&format!(
            "closed form (42), envelope: λ_c = {l:.6e} {unit}\n"
        ));
    }
    text
}
