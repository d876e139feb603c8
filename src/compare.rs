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

mod overlay;

pub use overlay::{ModelState, read_state};

use crate::error::{Error, io_error, output_directory_error};
use crate::output::{
    DirectoryLock, Quantity, Response, ResponsePoint, plot_comparison, write_bytes_atomically,
    write_json,
};
use crate::results::{RunSummary, load_quantity};
use crate::run::run_with;
use crate::scene::{AxisRatio, Scene};
use crate::study::{check_model_list, load_at_amplitude, number_cell};
use crate::threshold::{
    MIN_ELEMENTS_PER_WAVELENGTH, ThresholdOptions, WavenumberModel, closed_form_threshold,
};
use serde_json::json;
use std::path::Path;
use wrinkle_runtime::fem::mesh::AxisGrading;
use wrinkle_runtime::wavelength::WavelengthSelection;

/// Physical amplitudes $`a/h`$ at which the loads are compared.
pub const AMPLITUDE_LEVELS: [f64; 3] = [0.5, 1.0, 2.0];

/// One model's line of the comparison.
#[derive(Clone, Debug, serde::Serialize)]
pub struct CompareRow {
    /// Model name.
    pub model: String,
    /// `reached`, `incomplete`, `invalid`, `failed`, `interrupted` (a run's outcome) or
    /// `error` (the run could not start).
    pub outcome: String,
    /// The exit code `wrinkle run` would have ended with (its outcome's, or the error's).
    pub exit_code: i32,
    /// Why it did not reach its target, if it did not.
    pub reason: Option<String>,
    /// The validity checks that failed (`scale_separation`, `ellipticity`, `mode_resolution`,
    /// `well_posedness`), accepted by the scene or not: a row with any is not a valid result of
    /// its model, is drawn grey and dashed, and never serves as the reference.
    pub failed_checks: Vec<String>,
    /// The mesh the model ran on, `NX×NY`.
    pub mesh: Option<String>,
    /// Why the mesh differs from the scene's (chosen by `compare` to resolve the model's
    /// waves), `None` when it is the scene's or the user's.
    pub mesh_note: Option<String>,
    /// Critical load of linear buckling.
    pub critical_load: Option<f64>,
    /// $`\lambda_c`$ relative to the reference's (the first valid model's,
    /// [`Comparison::reference`]).
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
    /// The model the `ratio` column is relative to: the first one with a critical load and no
    /// failed validity check (`None` when there is none; the ratios are then empty).
    pub reference: Option<String>,
}

impl CompareRow {
    /// Whether the row is a valid result of its model: it ran, and no validity check failed.
    pub fn is_valid(&self) -> bool {
        matches!(self.outcome.as_str(), "reached" | "incomplete") && self.failed_checks.is_empty()
    }
}

/// The exit codes of the rows from the most to the least severe: interrupted (130), a model
/// that failed or could not start (1), a model used outside its validity (4), a path stopped
/// before its target (3).
pub const EXIT_CODES_BY_SEVERITY: [i32; 4] = [crate::error::EXIT_INTERRUPTED, 1, 4, 3];

impl Comparison {
    /// The comparison's exit code: the most severe of its rows' ([`EXIT_CODES_BY_SEVERITY`]),
    /// 0 when every model reached what was asked — a model outside its validity that the scene
    /// accepts (`validity.accept`) reached it, as in `wrinkle run`.
    pub fn exit_code(&self) -> i32 {
        EXIT_CODES_BY_SEVERITY
            .into_iter()
            .find(|code| self.rows.iter().any(|row| row.exit_code == *code))
            .unwrap_or(0)
    }

    /// The error the command ends with when a model did not reach what was asked, with the
    /// comparison's exit code ([`Self::exit_code`]): every such model, its outcome and why,
    /// followed by `detail` (where the results are); `None` when every model reached it.
    pub fn error(&self, detail: &str) -> Option<Error> {
        let models: Vec<String> = self
            .rows
            .iter()
            .filter(|row| row.exit_code != 0)
            .map(|row| match &row.reason {
                Some(reason) => format!("{} ({}): {reason}", row.model, row.outcome),
                None => format!("{} ({})", row.model, row.outcome),
            })
            .collect();
        let message = format!("{}; {detail}", models.join("; "));
        match self.exit_code() {
            0 => None,
            1 => Some(Error::Solver(message)),
            3 => Some(Error::Incomplete(message)),
            4 => Some(Error::Invalid(message)),
            _ => Some(Error::Interrupted(message)),
        }
    }
}

/// One model's row from the result of its run.
fn row_of(model: &str, summary: &RunSummary) -> CompareRow {
    let finite = |value: Option<f64>| value.filter(|v| v.is_finite());
    CompareRow {
        model: model.to_string(),
        outcome: summary.outcome.name().into(),
        exit_code: summary.outcome.exit_code(),
        reason: summary.outcome.reason().map(str::to_string),
        failed_checks: summary
            .threshold
            .warnings
            .iter()
            .map(|w| w.check.to_string())
            .collect(),
        mesh: None,
        mesh_note: None,
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
    let response = Response::new(model, load.clone(), critical, response_points);
    let checks: Vec<&str> = summary.threshold.warnings.iter().map(|w| w.check).collect();
    Some(if checks.is_empty() {
        response
    } else {
        response.with_caveat(checks.join(", "))
    })
}

/// The largest element of `n` along one axis of length `length` graded by `grading`.
fn largest_element(grading: &AxisGrading, length: f64, n: usize) -> f64 {
    grading
        .breakpoints(length, n)
        .windows(2)
        .map(|pair| pair[1] - pair[0])
        .fold(0.0, f64::max)
}

/// A structured mesh chosen by `compare` for a model resolved by the mesh.
#[derive(Clone, Copy, Debug, PartialEq)]
struct ResolvingMesh {
    nx: usize,
    ny: usize,
    /// Whether the wave axis is X (else Y); that axis is made uniform.
    along_x: bool,
}

/// For a model whose wrinkles are fields resolved by the mesh (a plate), the structured mesh
/// of `scene` refined along the wave direction to at least [`MIN_ELEMENTS_PER_WAVELENGTH`]
/// elements per wavelength (with a tenth to spare, a multiple of 4) and made uniform along
/// that axis (a grading there would leave the waves under-resolved where the elements are
/// largest), the other axis keeping its grading with at least as many elements as a uniform
/// mesh of elements at most 4 times longer than wide; `None` when the scene's mesh already resolves `wavelength`
/// (mm) with its largest element, or when the mesh is a file (its own run checks it).
fn resolving_mesh(scene: &Scene, wavelength: f64, direction_degrees: f64) -> Option<ResolvingMesh> {
    if !scene.mesh.file.is_empty() {
        return None;
    }
    let theta = direction_degrees.to_radians();
    let along_y = theta.sin().abs() > theta.cos().abs();
    let [grading_x, grading_y] = scene.mesh.axis_gradings();
    let (nx, ny) = (scene.mesh.elements_x, scene.mesh.elements_y);
    let (lx, ly) = (scene.geometry.length_x, scene.geometry.length_y);
    let (n_wave, l_wave, g_wave, n_other, l_other) = if along_y {
        (ny, ly, grading_y, nx, lx)
    } else {
        (nx, lx, grading_x, ny, ly)
    };
    if largest_element(&g_wave, l_wave, n_wave) * MIN_ELEMENTS_PER_WAVELENGTH <= wavelength {
        return None;
    }
    let needed =
        (1.1 * MIN_ELEMENTS_PER_WAVELENGTH * l_wave / wavelength / 4.0).ceil() as usize * 4;
    // As many elements across as a uniform mesh whose elements are at most 4 times longer
    // than wide; a grading across is kept (it is there for the membrane state, which the
    // wave axis's count does not see).
    let other = n_other.max((l_other / (4.0 * l_wave / needed as f64)).ceil() as usize);
    Some(if along_y {
        ResolvingMesh {
            nx: other,
            ny: needed,
            along_x: false,
        }
    } else {
        ResolvingMesh {
            nx: needed,
            ny: other,
            along_x: true,
        }
    })
}

/// The scene of `model` in the comparison: `scene` with the model's `--model-set` overrides,
/// and, for a model resolved by the mesh whose overrides do not set the mesh, a mesh that
/// resolves the wavelength of the wavenumber model (with a note saying so).
fn model_scene(
    scene: &Scene,
    model: &str,
    overrides: &[(String, String)],
    wavenumber_model: &WavenumberModel,
    quiet: bool,
) -> Result<(Scene, Option<String>), Error> {
    let mut one = scene.clone();
    one.model.name = model.to_string();
    let mut mesh_given = false;
    for (name, assignment) in overrides {
        if name == model {
            one.apply_override(assignment)?;
            mesh_given |= assignment.trim_start().starts_with("mesh.");
        }
    }
    one.validate()?;
    let resolved_by_mesh = wrinkle_models::catalogue()
        .into_iter()
        .find(|spec| spec.name == model)
        .is_some_and(|spec| spec.wavelength_selection() == WavelengthSelection::ResolvedByMesh);
    if !resolved_by_mesh || mesh_given {
        return Ok((one, None));
    }
    let carrier = wavenumber_model.threshold(quiet)?;
    let wavelength = std::f64::consts::TAU / carrier.wavenumber;
    // `"auto"`: the plate's waves are taken along the wavenumber model's direction.
    let direction = one
        .model
        .direction
        .fixed_degrees()
        .unwrap_or(carrier.direction_degrees);
    let Some(ResolvingMesh { nx, ny, along_x }) = resolving_mesh(&one, wavelength, direction)
    else {
        return Ok((one, None));
    };
    let [grading_x, grading_y] = one.mesh.axis_gradings();
    let was_graded = if along_x { grading_x } else { grading_y }.ratio > 1.0;
    let uniform_note = if was_graded {
        format!(", uniform along {}", if along_x { "X" } else { "Y" })
    } else {
        String::new()
    };
    let note = format!(
        "{model}: mesh {nx}×{ny}{uniform_note} instead of the scene's {}×{}, to resolve its waves ({} elements per wavelength of {wavelength:.2} mm, the wavelength of {}); set another with --model-set {model}:mesh.nx=…",
        one.mesh.elements_x,
        one.mesh.elements_y,
        MIN_ELEMENTS_PER_WAVELENGTH,
        wavenumber_model.name()
    );
    one.mesh.elements_x = nx;
    one.mesh.elements_y = ny;
    if was_graded {
        if along_x {
            one.mesh.grading_x = AxisRatio::Fixed(1.0);
        } else {
            one.mesh.grading_y = AxisRatio::Fixed(1.0);
        }
    }
    // A mesh too large to solve: refuse (exit 4) naming the model and the mesh it needs.
    one.validate().map_err(|error| {
        Error::Invalid(format!(
            "{model} needs a {nx}×{ny} mesh to resolve its waves ({} elements per wavelength of {wavelength:.2} mm), which cannot be solved here: {error}; compare it on a smaller domain, or set its mesh with --model-set {model}:mesh.nx=… (its run then says whether the mode is resolved)",
            MIN_ELEMENTS_PER_WAVELENGTH
        ))
    })?;
    Ok((one, Some(note)))
}

/// The models `wrinkle compare` runs when none is named: every registered model of a plane
/// domain (roles that give a plane [`Layout`](crate::physics::Layout)) written by hand (no
/// [`ModelSpec::derivation`](wrinkle_runtime::model::ModelSpec::derivation)).
pub fn default_models() -> Vec<String> {
    wrinkle_models::catalogue()
        .into_iter()
        .filter(|spec| crate::physics::Layout::from_spec(spec).is_ok())
        .filter(|spec| spec.derivation.is_none())
        .map(|spec| spec.name.to_string())
        .collect()
}

/// Runs `scene` with each of `models` into `directory/MODEL/` and writes the comparison files.
pub fn compare(
    scene: &Scene,
    models: &[String],
    model_overrides: &[String],
    directory: &Path,
    quiet: bool,
) -> Result<Comparison, Error> {
    // The whole command line is checked before any work (the meshes chosen below come after).
    model_scenes(scene, models, model_overrides)?;
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
    // The meshes that resolve each model's waves are chosen (or refused) before any model runs.
    let overrides = parse_model_overrides(models, model_overrides)?;
    let planned = models
        .iter()
        .map(|model| model_scene(scene, model, &overrides, &wavenumber_model, quiet))
        .collect::<Result<Vec<_>, Error>>()?;
    // Every model also writes its fields at one common load, for the overlaid profiles.
    let overlay_load = overlay_load(scene, &wavenumber_model, quiet);
    for (model, (mut one, mesh_note)) in models.iter().zip(planned) {
        if let Some(load) = overlay_load {
            one.output.vtu_loads.push(load);
        }
        if let (Some(note), false) = (&mesh_note, quiet) {
            crate::output::message_line(&format!("note: {note}"));
        }
        let mesh = Some(format!("{}×{}", one.mesh.elements_x, one.mesh.elements_y));
        let out = directory.join(model);
        match run_with(&one, &out, &options) {
            Ok(report) => {
                rows.push(CompareRow {
                    mesh,
                    mesh_note,
                    ..row_of(model, &report.summary)
                });
                responses.extend(response_of(model, &report.summary, &load));
            }
            Err(error @ Error::Scene { .. }) => return Err(error),
            Err(error) => rows.push(CompareRow {
                model: model.clone(),
                outcome: "error".into(),
                exit_code: error.exit_code(),
                reason: Some(error.to_string()),
                failed_checks: Vec::new(),
                mesh,
                mesh_note,
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
    let reference = rows
        .iter()
        .find(|r| r.is_valid() && r.critical_load.is_some())
        .map(|r| (r.model.clone(), r.critical_load));
    let reference_load = reference.as_ref().and_then(|(_, l)| *l);
    for row in &mut rows {
        row.critical_load_ratio = row.critical_load.zip(reference_load).map(|(l, f)| l / f);
    }
    let comparison = Comparison {
        rows,
        closed_form_critical_load: closed_form_threshold(scene).map(|(l, _)| l),
        reference: reference.map(|(model, _)| model),
    };
    let profiles = match overlay_load {
        Some(load) => {
            // `"auto"`: the line runs along the wavenumber model's direction.
            let direction = scene.model.direction.fixed_degrees().unwrap_or_else(|| {
                wavenumber_model
                    .threshold(quiet)
                    .map_or(0.0, |carrier| carrier.direction_degrees)
            });
            overlay::write_profile_overlay(scene, models, load, direction, directory)?
        }
        None => false,
    };
    write_comparison(scene, &comparison, &responses, profiles, directory)?;
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

/// The load at which the models' wrinkles are overlaid: 1.1 × the wavenumber model's
/// threshold, past every valid model's threshold and below its target; `None` without plots
/// or VTU files, or when that threshold cannot be found (the comparison goes on without it).
fn overlay_load(scene: &Scene, wavenumber_model: &WavenumberModel, quiet: bool) -> Option<f64> {
    if !(scene.output.plots && scene.output.vtu) {
        return None;
    }
    let carrier = wavenumber_model.threshold(quiet).ok()?;
    Some(OVERLAY_LOAD_RATIO * carrier.critical_load).filter(|l| l.is_finite() && *l > 0.0)
}

/// The overlay's load over the wavenumber model's threshold.
const OVERLAY_LOAD_RATIO: f64 = 1.1;

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

/// `compare.csv`, `compare.json`, `compare.png|svg`, `index.html` (showing
/// `compare_profiles.png` when `profiles` were written).
fn write_comparison(
    scene: &Scene,
    comparison: &Comparison,
    responses: &[Response],
    profiles: bool,
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
        "reference": comparison.reference,
        "exit_code": comparison.exit_code(),
        "models": comparison.rows,
    });
    write_json(&path, &value).map_err(io_error(&path))?;
    let plotted = !responses.is_empty() && scene.output.plots;
    if plotted {
        let stem = directory.join("compare");
        plot_comparison(
            &stem,
            "Physical wrinkle amplitude, model by model",
            responses,
        )
        .map_err(io_error(&stem))?;
    }
    let path = directory.join("index.html");
    let html = index_page(scene, comparison, plotted, profiles);
    write_bytes_atomically(&path, html.as_bytes()).map_err(io_error(&path))?;
    Ok(())
}

/// `index.html`: the comparison table with each model's run linked (`MODEL/report.html`), the
/// overlaid responses and profiles, and links to `compare.csv` and `compare.json`.
fn index_page(scene: &Scene, comparison: &Comparison, plotted: bool, profiles: bool) -> String {
    use crate::output::report::escape;
    let unit = crate::threshold::load_unit(scene);
    let mut html = format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <title>wrinkle compare — {source}</title>\n<style>\n\
         body {{ font-family: sans-serif; max-width: 75rem; margin: 2rem auto; padding: 0 1rem; }}\n\
         table {{ border-collapse: collapse; }} td, th {{ padding: 0.3rem 0.7rem; border-bottom: 1px solid #ddd; text-align: right; }}\n\
         td:first-child, th:first-child, td:last-child {{ text-align: left; }}\n\
         td:not(:last-child) {{ white-space: nowrap; }}\n\
         tr.invalid {{ color: #777; }} img {{ max-width: 100%; }}\n</style>\n</head>\n<body>\n\
         <h1>Models compared on {source}</h1>\n<p>written {date}; the ratio is to {reference}; \
         grey rows failed a validity check and are drawn grey and dashed.</p>\n<table>\n\
         <tr><th>model</th><th>mesh</th><th>λ_c ({unit})</th><th>ratio</th><th>wavelength (mm)</th>",
        source = escape(&scene.source),
        date = crate::output::report::utc_timestamp(std::time::SystemTime::now()),
        reference = comparison
            .reference
            .as_deref()
            .map_or("no model (none is valid)".to_string(), escape),
    );
    for level in AMPLITUDE_LEVELS {
        html.push_str(&format!("<th>λ(a/h = {level})</th>"));
    }
    html.push_str("<th>outcome</th></tr>\n");
    let number = |v: Option<f64>| v.map_or("—".to_string(), |v| format!("{v:.5e}"));
    for row in &comparison.rows {
        let class = if row.is_valid() {
            ""
        } else {
            " class=\"invalid\""
        };
        let mut outcome = escape(&row.outcome);
        if !row.failed_checks.is_empty() {
            outcome.push_str(&format!(
                " (failed: {})",
                escape(&row.failed_checks.join(", "))
            ));
        }
        if let Some(note) = &row.mesh_note {
            outcome.push_str(&format!("<br><small>{}</small>", escape(note)));
        }
        html.push_str(&format!(
            "<tr{class}><td><a href=\"{model}/report.html\">{model}</a></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>",
            escape(row.mesh.as_deref().unwrap_or("—")),
            number(row.critical_load),
            row.critical_load_ratio.map_or("—".into(), |r| format!("{r:.4}")),
            row.wavelength.map_or("—".into(), |l| format!("{l:.3}")),
            model = escape(&row.model),
        ));
        for load in &row.load_at_amplitude {
            html.push_str(&format!("<td>{}</td>", number(*load)));
        }
        html.push_str(&format!("<td>{outcome}</td></tr>\n"));
    }
    html.push_str("</table>\n");
    if let Some(l) = comparison.closed_form_critical_load {
        html.push_str(&format!(
            "<p>closed form (42), envelope: λ_c = {l:.6e} {unit}</p>\n"
        ));
    }
    if plotted {
        html.push_str("<p><img src=\"compare.png\" alt=\"overlaid responses\"></p>\n");
    }
    if profiles {
        html.push_str(
            "<p><img src=\"compare_profiles.png\" alt=\"the models' wrinkles at one load\"></p>\n",
        );
    }
    html.push_str(
        "<p><a href=\"compare.csv\">compare.csv</a> · <a href=\"compare.json\">compare.json</a></p>\n</body>\n</html>\n",
    );
    html
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
    match &comparison.reference {
        Some(model) => text.push_str(&format!("ratio: λ_c / λ_c of {model}\n")),
        None => text.push_str("ratio: no model ran without a failed validity check\n"),
    }
    for row in &comparison.rows {
        if !row.failed_checks.is_empty() {
            text.push_str(&format!(
                "not valid: {}: {}\n",
                row.model,
                row.failed_checks.join(", ")
            ));
        }
        if let Some(note) = &row.mesh_note {
            text.push_str(&format!("note: {note}\n"));
        }
    }
    if let Some(l) = comparison.closed_form_critical_load {
        text.push_str(&format!(
            "closed form (42), envelope: λ_c = {l:.6e} {unit}\n"
        ));
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Example 1 (400 × 200 mm, 32 × 16): 2 elements per 26.69 mm wavelength along X; the plate
    /// gets 132 elements along X (8.8 per wavelength, a multiple of 4) and 17 across, so that
    /// elements are at most 4 times longer than wide. A mesh that resolves the waves is kept.
    #[test]
    fn a_plate_gets_a_mesh_that_resolves_its_waves() {
        let scene = Scene::default();
        assert_eq!(
            (scene.geometry.length_x, scene.geometry.length_y),
            (400.0, 200.0)
        );
        let wavelength = 26.6876;
        assert_eq!(
            resolving_mesh(&scene, wavelength, 0.0),
            Some(ResolvingMesh {
                nx: 132,
                ny: 17,
                along_x: true
            })
        );
        let mut fine = scene.clone();
        fine.mesh.elements_x = 128;
        fine.mesh.elements_y = 32;
        assert_eq!(resolving_mesh(&fine, wavelength, 0.0), None);
        // Waves along Y (the strip): Y is refined.
        let along_y = scene.clone();
        let ResolvingMesh { nx, ny, along_x } = resolving_mesh(&along_y, wavelength, 90.0).unwrap();
        assert!(
            !along_x && ny as f64 * wavelength / 200.0 >= 8.0 && nx >= 32,
            "{nx}×{ny}"
        );
    }

    /// The shipped long strip (1400 × 200 mm, 56 × 16 graded 12 toward its four corners, waves
    /// of 25.30 mm along Y): its 16 elements across are 1.3 per wavelength where they are
    /// largest. The plate gets 72 uniform elements across (8.5 per wavelength everywhere) and
    /// 126 along X, graded as the scene says; a file mesh is never replaced.
    #[test]
    fn a_graded_strip_gets_a_mesh_uniform_along_its_waves() {
        let scene = Scene::load(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/examples/scenes/long_strip.toml"
        ))
        .unwrap();
        let wavelength = 25.3044;
        let ResolvingMesh { nx, ny, along_x } = resolving_mesh(&scene, wavelength, 90.0).unwrap();
        assert!(!along_x);
        assert_eq!(ny, 72);
        // 1400 / (4 × 200 / 72) = 126 along X, still graded 12 toward the corners.
        assert_eq!(nx, 126);
        let mut file = scene.clone();
        file.mesh.file = "annulus.msh".into();
        assert_eq!(resolving_mesh(&file, wavelength, 90.0), None);
    }

    fn row(model: &str, outcome: &str, checks: &[&str], critical: f64) -> CompareRow {
        CompareRow {
            model: model.into(),
            outcome: outcome.into(),
            exit_code: match outcome {
                "reached" => 0,
                "incomplete" => 3,
                "invalid" => 4,
                _ => 1,
            },
            reason: None,
            failed_checks: checks.iter().map(|c| c.to_string()).collect(),
            mesh: None,
            mesh_note: None,
            critical_load: Some(critical),
            critical_load_ratio: None,
            wavenumber: None,
            wavelength: None,
            load_at_amplitude: vec![None; AMPLITUDE_LEVELS.len()],
            dofs: None,
            seconds: None,
        }
    }

    /// An ill-posed or unresolved model is not valid (and so never the reference); an
    /// incomplete run without failed checks is.
    #[test]
    fn only_runs_without_failed_checks_are_valid() {
        assert!(!row("fvk-plate", "invalid", &["mode_resolution"], 0.0945).is_valid());
        assert!(!row("pure-membrane", "reached", &["well_posedness"], 0.0444).is_valid());
        assert!(!row("x", "error", &[], 0.1).is_valid());
        assert!(row("reference-envelope", "reached", &[], 0.0895).is_valid());
        assert!(row("reference-envelope", "incomplete", &[], 0.0895).is_valid());
    }

    fn comparison(rows: Vec<CompareRow>) -> Comparison {
        Comparison {
            rows,
            closed_form_critical_load: None,
            reference: None,
        }
    }

    /// The comparison ends as its most severe row: a failure (1) before a model outside its
    /// validity (4) before a path that stopped early (3); 0 only when every model reached its
    /// target — an accepted failed check (outcome `reached`) included.
    #[test]
    fn the_comparison_exits_with_its_most_severe_row() {
        let valid = row("reference-envelope", "reached", &[], 0.0895);
        let accepted = row("pure-membrane", "reached", &["well_posedness"], 0.0444);
        let ill_posed = row("pure-membrane", "invalid", &["well_posedness"], 0.0444);
        let stopped = row("complex-envelope", "incomplete", &[], 0.0895);
        let failed = row("fvk-plate", "error", &[], 0.09);
        let all_reached = comparison(vec![valid.clone(), accepted]);
        assert_eq!(all_reached.exit_code(), 0);
        assert!(all_reached.error("written").is_none());
        let invalid = comparison(vec![valid.clone(), ill_posed.clone(), stopped.clone()]);
        assert_eq!(invalid.exit_code(), 4);
        let error = invalid.error("written to OUT").unwrap();
        assert_eq!(error.exit_code(), 4);
        let text = error.to_string();
        assert!(text.contains("pure-membrane (invalid)"), "{text}");
        assert!(text.contains("complex-envelope (incomplete)"), "{text}");
        assert!(!text.contains("reference-envelope"), "{text}");
        assert!(text.ends_with("written to OUT"), "{text}");
        assert_eq!(comparison(vec![stopped.clone(), valid]).exit_code(), 3);
        assert_eq!(comparison(vec![ill_posed, failed, stopped]).exit_code(), 1);
    }
}
