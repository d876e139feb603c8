//! The files of a run (documented in `docs/outputs.md`): `path.csv`, `fields_*.vtu`,
//! `surface_final.vtu`, the plots, `report.html`, `scene.toml`, and `summary.json` last with the
//! list of every file written. Nothing here recomputes physics: every number comes from the
//! [`Trace`] and the [`Threshold`]; the physical deflection is read through the field roles
//! ([`Snapshot`]).

use crate::error::Error;
use crate::output::{
    ClosedFormCurve, FieldData, GridField, LoadMarker, PointArray, Profile, ProfilePlot, Quantity,
    Report, ReportFigure, Response, ResponsePoint, RunDirectory, RunSummary, Severity, Warning,
    plot_profiles, plot_response, plot_wrinkle_map, write_fields_vtu_with_cells, write_path_csv,
    write_surface_vtu,
};
use crate::physics::{Layout, Snapshot};
use crate::results::{RunOutcome, RunReport, Snap, Trace};
use crate::scene::{LoadKind, PathMethod, Scene};
use crate::threshold::{Threshold, closed_form_threshold, load_unit, threshold_json};
use serde_json::json;
use std::path::{Path, PathBuf};
use wrinkle_runtime::ModelSpec;
use wrinkle_runtime::fem::Mesh;

/// What the writers need besides the trace.
pub struct RunContext<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The model's specification.
    pub spec: &'static ModelSpec,
    /// The fields' meaning.
    pub layout: &'a Layout,
    /// The mesh.
    pub mesh: &'a Mesh,
    /// The threshold found on the same problem.
    pub threshold: &'a Threshold,
    /// Physical amplitude (mm) of the imperfection's response on the unloaded sheet.
    pub imperfection: f64,
    /// Free unknowns.
    pub dofs: usize,
    /// Seconds before the outputs.
    pub seconds: f64,
    /// Peak resident memory of the process during the run, in bytes (Linux; see
    /// [`crate::memory`]).
    pub peak_memory: Option<u64>,
}

impl RunContext<'_> {
    fn snapshot<'b>(&'b self, values: &'b [f64]) -> Snapshot<'b> {
        Snapshot {
            mesh: self.mesh,
            layout: self.layout,
            values,
            wavenumber: self.threshold.wavenumber.unwrap_or(0.0),
            direction: self.scene.model.direction_degrees.to_radians(),
        }
    }

    fn load_quantity(&self) -> Quantity {
        match self.scene.load.kind {
            LoadKind::Biaxial => Quantity::biaxial_load(),
            LoadKind::Strip => Quantity::end_displacement(),
        }
    }

    fn field_data(&self, load: f64) -> FieldData {
        FieldData::load(load, load_unit(self.scene))
            .with_text("model", self.spec.name)
            .with_number("wavenumber", self.threshold.wavenumber.unwrap_or(0.0))
            .with_number("critical_load", self.threshold.critical_load())
    }

    /// Samples per side of the surface grids: about 12 per wavelength, 50 to 1500.
    fn samples(&self, length: f64) -> usize {
        let wavelength = self.threshold.wavelength.unwrap_or(length);
        (12.0 * length / wavelength).clamp(50.0, 1500.0) as usize
    }
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |error| Error::Io {
        path: path.display().to_string(),
        error,
    }
}

/// Writes every output of a run into `directory` (the previous run's files are removed first).
pub fn write_run(
    context: &RunContext,
    trace: &Trace,
    directory: &Path,
) -> Result<RunReport, Error> {
    let mut run_directory = RunDirectory::prepare(directory).map_err(io_error(directory))?;
    let dir = run_directory.root().to_path_buf();
    let mut files = Vec::new();
    let csv = dir.join("path.csv");
    write_path_csv(&csv, &trace.points).map_err(io_error(&csv))?;
    files.push(csv);
    // The VTU files and the plots are independent: written side by side.
    let (fields, figures) = rayon::join(
        || write_fields(context, trace, &dir),
        || {
            if context.scene.output.plots {
                write_plots(context, trace, &dir)
            } else {
                Ok(Vec::new())
            }
        },
    );
    files.extend(fields?);
    let figures = figures?;
    files.extend(figures.iter().flat_map(|(f, _)| f.clone()));
    let scene_path = dir.join("scene.toml");
    crate::output::write_bytes_atomically(&scene_path, context.scene.to_toml_string().as_bytes())
        .map_err(io_error(&scene_path))?;
    files.push(scene_path);
    let outcome = outcome(context, trace);
    let summary_table = run_summary(context, trace, &outcome);
    let report_path = dir.join("report.html");
    run_directory
        .record(files.iter().chain([&report_path]))
        .map_err(io_error(&dir))?;
    let mut report = Report::from_summary(&summary_table);
    report.title = format!("{} on {}", context.spec.name, context.scene.source);
    report.warnings = warnings(context, trace);
    report.figures = figures
        .iter()
        .filter_map(|(f, caption)| f.first().map(|png| ReportFigure::png(png, caption.clone())))
        .collect();
    report.scene_toml = context.scene.to_toml_string();
    report.files = run_directory.files().to_vec();
    crate::output::write_report(&report_path, &report).map_err(io_error(&report_path))?;
    files.push(report_path);
    let mut summary = summary_json(context, trace, &outcome);
    let summary_path = run_directory
        .write_summary(summary.clone())
        .map_err(io_error(&dir))?;
    if let Some(object) = summary.as_object_mut() {
        object.insert("files".into(), json!(run_directory.files()));
    }
    files.push(summary_path);
    let mut summary_text = summary_table.to_text();
    for warning in &report.warnings {
        summary_text.push_str(&format!(
            "{}: {}: {}\n",
            warning.severity.label(),
            warning.title,
            warning.detail
        ));
    }
    let failure = match &outcome {
        RunOutcome::Failed(reason) => Some(reason.clone()),
        _ => None,
    };
    Ok(RunReport {
        summary,
        files,
        failure,
        outcome,
        summary_text,
    })
}

/// Exit status of the run (see [`RunOutcome`]).
fn outcome(context: &RunContext, trace: &Trace) -> RunOutcome {
    let stop = &trace.result.stop;
    if stop.is_failure() {
        return RunOutcome::Failed(stop.describe());
    }
    if trace.interrupted {
        let at = trace.points.last().map_or_else(
            || "before the first point".to_string(),
            |p| {
                format!(
                    "at λ = {} (max |w|/h = {:.4})",
                    context.load_quantity().format_value(p.lambda),
                    p.max_amplitude_over_h
                )
            },
        );
        return RunOutcome::Interrupted(format!(
            "stopped by the user (Ctrl-C) {at} after {} points; every completed point is in path.csv",
            trace.points.len()
        ));
    }
    if let Some(load) = trace.passed_perfect_bifurcation {
        let loads = context.load_quantity();
        return RunOutcome::Incomplete(format!(
            "no imperfection (solver.perturbation = 0): past λ_c = {} the path stays flat on the unstable fundamental branch (max |w| = 0 at λ = {}); set solver.perturbation (e.g. 1e-4) to wrinkle, or solver.max_load to follow that branch",
            loads.format_value(context.threshold.critical_load()),
            loads.format_value(load)
        ));
    }
    let reached = trace.points.last().is_some_and(|p| {
        p.max_amplitude_over_h >= context.scene.solver.max_amplitude_over_thickness
    });
    if !reached {
        let wrinkled = trace.result.bifurcation.is_some()
            || trace
                .points
                .last()
                .is_some_and(|p| p.lambda > context.threshold.critical_load());
        let why = if wrinkled {
            stop.describe()
        } else {
            format!(
                "{} before the path left the fundamental branch",
                stop.describe()
            )
        };
        return RunOutcome::Incomplete(format!(
            "{why}: the amplitude target max |w|/h = {} was not reached",
            context.scene.solver.max_amplitude_over_thickness
        ));
    }
    match context.threshold.validity_failure(&context.scene.validity) {
        Some(reason) => RunOutcome::Invalid(reason),
        None => RunOutcome::Reached,
    }
}

/// `fields_final.vtu`, `fields_load_*.vtu`, `surface_final.vtu`.
fn write_fields(context: &RunContext, trace: &Trace, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut files = Vec::new();
    let mut write_nodal = |name: String, snap: &Snap| -> Result<(), Error> {
        let path = dir.join(name);
        let extra = nodal_amplitude(context, &snap.values);
        let cells: Vec<PointArray> = ["N_X", "N_Y", "N_XY"]
            .iter()
            .zip(&snap.stress_resultants)
            .map(|(name, values)| PointArray::scalar(*name, values.clone()))
            .collect();
        write_fields_vtu_with_cells(
            &path,
            context.mesh,
            context.spec.fields,
            &snap.values,
            &extra,
            &cells,
            &context.field_data(snap.load),
        )
        .map_err(io_error(&path))?;
        files.push(path);
        Ok(())
    };
    if context.scene.output.vtu {
        write_nodal("fields_final.vtu".into(), &trace.last)?;
        for snap in &trace.requested {
            write_nodal(format!("fields_load_{:.6}.vtu", snap.load), snap)?;
        }
    }
    if !context.scene.output.surface {
        return Ok(files);
    }
    let bounds = context.mesh.bounds();
    let snapshot = context.snapshot(&trace.last.values);
    let (sx, sy) = (
        context.samples(bounds[1] - bounds[0]),
        context.samples(bounds[3] - bounds[2]),
    );
    let grid = GridField::sample(Quantity::deflection(), bounds, sx + 1, sy + 1, |x, y| {
        snapshot.deflection([x, y])
    });
    let path = dir.join("surface_final.vtu");
    write_surface_vtu(&path, &grid, 1.0, &[], &context.field_data(trace.last.load))
        .map_err(io_error(&path))?;
    files.push(path);
    Ok(files)
}

/// Nodal physical amplitude of envelope models (`amplitude`, mm) and, for a complex envelope,
/// the local wavenumber (`local_wavenumber`, 1/mm).
fn nodal_amplitude(context: &RunContext, values: &[f64]) -> Vec<PointArray> {
    let snapshot = context.snapshot(values);
    let nodes = &context.mesh.nodes;
    if !context.layout.is_envelope() {
        return Vec::new();
    }
    let mut arrays = vec![PointArray::scalar(
        "amplitude",
        nodes
            .iter()
            .map(|p| snapshot.envelope_amplitude([p[0], p[1]]).unwrap_or(0.0))
            .collect(),
    )];
    if matches!(
        context.layout.kind,
        crate::physics::DeflectionKind::ComplexEnvelope { .. }
    ) {
        let step = 1e-3 * (context.scene.geometry.length_x + context.scene.geometry.length_y);
        arrays.push(PointArray::scalar(
            "local_wavenumber",
            nodes
                .iter()
                .map(|p| {
                    snapshot
                        .local_wavenumber([p[0], p[1]], step)
                        .unwrap_or(snapshot.wavenumber)
                })
                .collect(),
        ));
    }
    arrays
}

/// `response`, `profiles_x`, `profiles_y`, `wrinkles` (PNG and SVG), with captions.
fn write_plots(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Vec<(Vec<PathBuf>, String)>, Error> {
    // The wrinkle map (the dearest: a fine grid of the deflection) is drawn beside the others.
    let (curves, map) = rayon::join(
        || write_curve_plots(context, trace, dir),
        || write_wrinkle_map(context, trace, dir),
    );
    let mut out = curves?;
    out.push(map?);
    Ok(out)
}

/// `response`, `profiles_x`, `profiles_y` and the local wavenumber plot, with captions.
fn write_curve_plots(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Vec<(Vec<PathBuf>, String)>, Error> {
    // Independent figures, drawn side by side; listed in a fixed order.
    let (response_plot, (profiles, local_wavenumber)) = rayon::join(
        || {
            let stem = dir.join("response");
            plot_response(
                &stem,
                &format!("{}: physical wrinkle amplitude", context.spec.name),
                &response(context, trace),
            )
            .map_err(io_error(&stem))
        },
        || {
            rayon::join(
                || write_profiles(context, trace, dir),
                || write_local_wavenumber(context, trace, dir),
            )
        },
    );
    let mut out = vec![(
        response_plot?.files,
        "Load against physical wrinkle amplitude".to_string(),
    )];
    out.extend(profiles?);
    out.extend(local_wavenumber?);
    Ok(out)
}

/// `wrinkles`: the physical deflection at the last point, with its caption.
fn write_wrinkle_map(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<(Vec<PathBuf>, String), Error> {
    let bounds = context.mesh.bounds();
    let snapshot = context.snapshot(&trace.last.values);
    let (mx, my) = (
        context.samples(bounds[1] - bounds[0]).min(900),
        context.samples(bounds[3] - bounds[2]).min(450),
    );
    let field = GridField::sample(Quantity::deflection(), bounds, mx + 1, my + 1, |x, y| {
        snapshot.deflection([x, y])
    });
    let h = context.scene.material.thickness;
    let stem = dir.join("wrinkles");
    let plot = plot_wrinkle_map(
        &stem,
        &format!(
            "{}: physical deflection at λ = {}",
            context.spec.name,
            context.load_quantity().format_value(trace.last.load)
        ),
        &crate::output::WrinkleMap::new(field, 1e-2 * h, "10⁻² h")
            .with_peak(snapshot.max_deflection()),
    )
    .map_err(io_error(&stem))?;
    Ok((
        plot.files,
        "Physical deflection at the last point".to_string(),
    ))
}

/// The load–amplitude response with the closed form and the markers.
fn response(context: &RunContext, trace: &Trace) -> Response {
    let load = context.load_quantity();
    let critical = context.threshold.critical_load();
    let points = trace
        .points
        .iter()
        .map(|p| ResponsePoint {
            load: p.lambda,
            max_amplitude_over_h: p.max_amplitude_over_h,
            centre_amplitude_over_h: Some(p.centre_amplitude_over_h),
            step_end: !p.interior,
        })
        .collect();
    let mut response = Response::new(context.spec.name, load.clone(), critical, points)
        .with_marker(LoadMarker::linear_buckling(critical, &load));
    if closed_form_threshold(context.scene).is_some() {
        let rectangle = context.scene.clamped_rectangle();
        let nu = context.scene.material.poisson_ratio;
        let last = trace.points.last().map_or(critical, |p| p.lambda);
        let top = (last / critical).max(1.001);
        let curve = (0..=200)
            .map(|k| {
                let ratio = 1.0 + (top - 1.0) * k as f64 / 200.0;
                let a = crate::closed_form::amplitude_from_load_ratio(
                    rectangle.aspect_ratio(),
                    nu,
                    ratio,
                );
                (ratio, 2.0 * a)
            })
            .collect();
        response = response.with_closed_form(ClosedFormCurve {
            label: "one-mode closed form (62), physical 2a/h".into(),
            points: curve,
        });
    }
    if let Some((at, report)) = &trace.loss_of_ellipticity {
        response = response.with_marker(LoadMarker::loss_of_ellipticity(
            *at,
            Some(report.violated_fraction),
            &load,
        ));
    }
    response
}

/// The point of the largest wrinkle of the last state: the largest envelope amplitude, or the
/// largest $`|w|`$ of a plate, on a 201 × 201 grid.
fn largest_wrinkle(context: &RunContext, trace: &Trace) -> Option<[f64; 2]> {
    let last = context.snapshot(&trace.last.values);
    let grid = GridField::sample(
        Quantity::deflection(),
        context.mesh.bounds(),
        201,
        201,
        |x, y| {
            last.envelope_amplitude([x, y])
                .unwrap_or_else(|| last.deflection([x, y]).abs())
        },
    );
    let (i, j, _) = grid.max_abs_point()?;
    Some(grid.point(i, j))
}

/// The profiles of `trace` along `axis` (0: X, 1: Y) through `peak`: the physical amplitude
/// $`2|w_1|/h`$ of envelope models, the deflection $`w/h`$ of a plate.
fn profiles_along(
    context: &RunContext,
    trace: &Trace,
    axis: usize,
    peak: [f64; 2],
) -> Vec<Profile> {
    let bounds = context.mesh.bounds();
    let h = context.scene.material.thickness;
    let (low, high) = (bounds[2 * axis], bounds[2 * axis + 1]);
    let samples = (2 * context.samples(high - low)).max(400);
    let load = context.load_quantity();
    trace
        .profiles
        .iter()
        .map(|snap| {
            let snapshot = context.snapshot(&snap.values);
            let value = |p: [f64; 2]| match snapshot.envelope_amplitude(p) {
                Some(a) => a / h,
                None => snapshot.deflection(p) / h,
            };
            Profile {
                label: format!("λ = {}", load.format_value(snap.load)),
                points: (0..=samples)
                    .map(|k| {
                        let s = low + (high - low) * k as f64 / samples as f64;
                        (
                            s,
                            value(if axis == 0 {
                                [s, peak[1]]
                            } else {
                                [peak[0], s]
                            }),
                        )
                    })
                    .collect(),
            }
        })
        .collect()
}

/// `profiles_x` and `profiles_y` through the largest wrinkle of the last state.
fn write_profiles(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Vec<(Vec<PathBuf>, String)>, Error> {
    let Some(peak) = largest_wrinkle(context, trace) else {
        return Ok(Vec::new());
    };
    let ordinate = if context.layout.is_envelope() {
        Quantity::new("physical amplitude", "2|w_env| / h", "")
    } else {
        Quantity::new("deflection", "w / h", "")
    };
    let mut out = Vec::new();
    for (name, axis) in [("profiles_x", 0usize), ("profiles_y", 1usize)] {
        let profiles = profiles_along(context, trace, axis, peak);
        if profiles.is_empty() {
            continue;
        }
        let (coordinate, location) = if axis == 0 {
            (
                "X",
                format!(
                    "along X at Y = {:.1} mm (through the largest wrinkle)",
                    peak[1]
                ),
            )
        } else {
            (
                "Y",
                format!(
                    "along Y at X = {:.1} mm (through the largest wrinkle)",
                    peak[0]
                ),
            )
        };
        let stem = dir.join(name);
        let plot = plot_profiles(
            &stem,
            &format!("{}: {}", context.spec.name, ordinate.name()),
            &ProfilePlot {
                abscissa: Quantity::coordinate(coordinate),
                ordinate: ordinate.clone(),
                location: location.clone(),
                profiles,
            },
        )
        .map_err(io_error(&stem))?;
        out.push((plot.files, format!("Profiles {location}")));
    }
    Ok(out)
}

/// For a complex envelope: the local wavenumber $`Q + \partial_e\arg w_1`$ along the wave
/// direction through the largest wrinkle (`local_wavenumber.png|svg`), where the local
/// amplitude exceeds 5 % of its maximum (the phase of a vanishing envelope means nothing).
fn write_local_wavenumber(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Option<(Vec<PathBuf>, String)>, Error> {
    let crate::physics::DeflectionKind::ComplexEnvelope { .. } = context.layout.kind else {
        return Ok(None);
    };
    let Some(peak) = largest_wrinkle(context, trace) else {
        return Ok(None);
    };
    let bounds = context.mesh.bounds();
    let theta = context.scene.model.direction_degrees.to_radians();
    let (c, s) = (theta.cos(), theta.sin());
    // The part of the line through `peak` along e inside the rectangle.
    let along = |t: f64| [peak[0] + t * c, peak[1] + t * s];
    let span = (bounds[1] - bounds[0]).hypot(bounds[3] - bounds[2]);
    let step = 1e-3 * span;
    let samples = 800;
    let load = context.load_quantity();
    let profiles: Vec<Profile> = trace
        .profiles
        .iter()
        .map(|snap| {
            let snapshot = context.snapshot(&snap.values);
            let cutoff = 0.05 * snapshot.max_amplitude();
            Profile {
                label: format!("λ = {}", load.format_value(snap.load)),
                points: (0..=samples)
                    .map(|k| -span + 2.0 * span * k as f64 / samples as f64)
                    .filter_map(|t| {
                        let p = along(t);
                        context.mesh.locate(p)?;
                        (snapshot.envelope_amplitude(p)? > cutoff).then_some(())?;
                        let q = snapshot.local_wavenumber(p, step)?;
                        Some((if s.abs() > c.abs() { p[1] } else { p[0] }, q))
                    })
                    .collect(),
            }
        })
        .filter(|p| p.points.len() > 1)
        .collect();
    if profiles.is_empty() {
        return Ok(None);
    }
    let coordinate = if s.abs() > c.abs() { "Y" } else { "X" };
    let location = format!(
        "along the wave direction through ({:.1}, {:.1}) mm; carrier Q = {:.5} /mm; where 2|w₁| > 5 % of its maximum",
        peak[0],
        peak[1],
        context.threshold.wavenumber.unwrap_or(0.0)
    );
    let stem = dir.join("local_wavenumber");
    let plot = plot_profiles(
        &stem,
        &format!("{}: local wavenumber", context.spec.name),
        &ProfilePlot {
            abscissa: Quantity::coordinate(coordinate),
            ordinate: Quantity::new("local wavenumber", "Q + ∂arg(w₁)", "1/mm"),
            location: location.clone(),
            profiles,
        },
    )
    .map_err(io_error(&stem))?;
    Ok(Some((plot.files, format!("Local wavenumber {location}"))))
}

/// Warnings a researcher must see: validity checks, loss of ellipticity, solver notes.
fn warnings(context: &RunContext, trace: &Trace) -> Vec<Warning> {
    let mut warnings: Vec<Warning> = context
        .threshold
        .warnings
        .iter()
        .map(|w| {
            if context.scene.validity.accepts(w.check) {
                Warning::new(
                    Severity::Note,
                    w.check,
                    format!("{} (accepted by `validity.accept`)", w.message),
                )
            } else {
                Warning::new(Severity::Warning, w.check, w.message.clone())
            }
        })
        .collect();
    if let Some((load, report)) = &trace.loss_of_ellipticity {
        warnings.push(Warning::new(
            Severity::Warning,
            "loss of ellipticity",
            format!(
                "from λ = {} on {:.2} % of the area (worst at ({:.4}, {:.4}) mm, field `{}`): beyond it the model's solutions depend on the mesh",
                context.load_quantity().format_value(*load),
                100.0 * report.violated_fraction,
                report.location[0],
                report.location[1],
                report.field
            ),
        ));
    }
    if let Some(step) = trace
        .anm_steps
        .iter()
        .find(|s| s.negative_pivots.is_some_and(|n| n > 0))
    {
        warnings.push(Warning::new(
            Severity::Warning,
            "unstable branch",
            format!(
                "the tangent had {} negative eigenvalue(s) at the start of step {} (λ = {}): the path is on an unstable equilibrium branch — {}",
                step.negative_pivots.unwrap_or(0),
                step.step,
                context.load_quantity().format_value(step.load_range.0),
                if context.scene.solver.perturbation == 0.0 {
                    "without an imperfection (solver.perturbation = 0) it stays on the fundamental branch past the bifurcation"
                } else {
                    "past a secondary bifurcation, or a step jumped over one (a tighter solver.series_tolerance tells which)"
                }
            ),
        ));
    }
    for note in &context.threshold.notes {
        warnings.push(Warning::new(Severity::Note, "threshold", note.clone()));
    }
    if !trace.unreached_vtu_loads.is_empty() {
        let load = context.load_quantity();
        let loads: Vec<String> = trace
            .unreached_vtu_loads
            .iter()
            .map(|&l| load.format_value(l))
            .collect();
        let end = trace.points.last().map_or_else(String::new, |p| {
            format!(" at λ = {}", load.format_value(p.lambda))
        });
        warnings.push(Warning::new(
            Severity::Note,
            "output.vtu_loads",
            format!(
                "λ = {} not reached (the path ended{end}): no fields_load_*.vtu written for {}",
                loads.join(", "),
                if loads.len() == 1 { "it" } else { "them" }
            ),
        ));
    }
    for warning in &trace.result.warnings {
        warnings.push(Warning::new(Severity::Warning, "solver", warning.clone()));
    }
    warnings
}

/// The terminal and report table.
fn run_summary(context: &RunContext, trace: &Trace, outcome: &RunOutcome) -> RunSummary {
    let last = trace.points.last();
    let stats = &trace.result.statistics;
    RunSummary {
        model: context.spec.name.to_string(),
        method: match (context.scene.solver.method, context.scene.solver.pade) {
            (PathMethod::Anm, true) => "ANM + Padé".to_string(),
            (method, _) => method.as_str().to_uppercase(),
        },
        dofs: context.dofs,
        wavenumber: context.threshold.wavenumber,
        load: context.load_quantity(),
        critical_load: Some(context.threshold.critical_load()),
        closed_form_critical_load: closed_form_threshold(context.scene).map(|(l, _)| l),
        closed_form_source: "eq. (42), envelope".into(),
        final_load: last.map(|p| p.lambda),
        final_amplitude_over_h: last.map(|p| p.max_amplitude_over_h),
        target_amplitude_over_h: Some(context.scene.solver.max_amplitude_over_thickness),
        thickness: Some(context.scene.material.thickness),
        steps: stats.steps,
        factorizations: stats.factorizations,
        seconds: context.seconds,
        peak_memory_bytes: context.peak_memory,
        stop: outcome
            .reason()
            .map_or_else(|| trace.result.stop.describe(), str::to_string),
        reached_target: *outcome == RunOutcome::Reached,
    }
}

/// The VTU files written, each with its load (the `vtu` key of `summary.json`).
fn vtu_files(scene: &Scene, trace: &Trace) -> Vec<serde_json::Value> {
    let mut files = Vec::new();
    if scene.output.vtu {
        files.push(json!({"load": trace.last.load, "file": "fields_final.vtu"}));
        files.extend(
            trace
                .requested
                .iter()
                .map(|s| json!({"load": s.load, "file": format!("fields_load_{:.6}.vtu", s.load)})),
        );
    }
    if scene.output.surface {
        files.push(json!({"load": trace.last.load, "file": "surface_final.vtu"}));
    }
    files
}

/// `summary.json` (keys documented in `docs/outputs.md`).
fn summary_json(context: &RunContext, trace: &Trace, outcome: &RunOutcome) -> serde_json::Value {
    let stats = &trace.result.statistics;
    let critical = context.threshold.critical_load();
    json!({
        "model": context.spec.name,
        "method": context.scene.solver.method.as_str(),
        "dofs": context.dofs,
        "wavenumber": context.threshold.wavenumber,
        "wavelength": context.threshold.wavelength,
        "load_kind": context.scene.load.kind.as_str(),
        "load_unit": load_unit(context.scene),
        "linear_buckling_load": critical,
        "closed_form_critical_load": closed_form_threshold(context.scene).map(|(l, _)| l),
        "threshold": threshold_json(context.scene, context.threshold),
        "detected_bifurcation": trace.result.bifurcation.map(|(load, step)| json!({"load": load, "step": step,
            "relative_difference_to_linear_buckling": (load - critical) / critical})),
        "loss_of_ellipticity": trace.loss_of_ellipticity.as_ref().map(|(load, r)| json!({
            "load": load, "location": r.location, "direction_rad": r.direction, "field": r.field,
            "margin": r.worst_margin, "area_fraction": r.violated_fraction})),
        "imperfection_amplitude": context.imperfection,
        "stop": if trace.interrupted { "interrupted by the user (Ctrl-C)".to_string() } else { trace.result.stop.describe() },
        "outcome": outcome.name(),
        "outcome_reason": outcome.reason(),
        "exit_code": outcome.exit_code(),
        "failed": matches!(outcome, RunOutcome::Failed(_)),
        "steps": stats.steps,
        "statistics": {
            "factorizations": stats.factorizations,
            "tangent_assemblies": stats.tangent_assemblies,
            "residual_assemblies": stats.residual_assemblies,
            "series_assemblies": stats.series_assemblies,
            "corrections": stats.corrections,
            "rejected_steps": stats.rejected_steps,
        },
        "timings": {
            "threshold": context.threshold.seconds,
            "assembly": stats.assembly_seconds,
            "factorization": stats.factorization_seconds,
            "series": stats.series_seconds,
            "series_solves": stats.series_solve_seconds,
            "bifurcation_prediction": stats.bifurcation_seconds,
            "residual_checks": stats.residual_seconds,
            "ellipticity": trace.ellipticity_seconds,
            "recording": trace.recording_seconds,
            "path": stats.total_seconds,
            "total": context.seconds,
        },
        "memory": {
            "peak_resident_bytes": context.peak_memory,
            "taylor_tape_bytes": stats.tape_bytes,
            "factor_nonzeros": stats.factor_nonzeros,
        },
        "solver_warnings": trace.result.warnings,
        "anm_steps": trace.anm_steps.iter().map(|s| json!({
            "step": s.step, "load_start": s.load_range.0, "load_end": s.load_range.1, "step_length": s.step_length,
            "series_step_length": s.series_step_length, "pade_step_length": s.pade_step_length,
            "end_residual": s.end_residual, "correction_iterations": s.correction_iterations,
            "crossings_redone": s.crossings_redone,
            "geometric_radius": s.geometric_radius, "predicted_bifurcation": s.predicted_bifurcation,
            "negative_pivots": s.negative_pivots, "completed": s.completed,
        })).collect::<Vec<_>>(),
        "vtu": vtu_files(context.scene, trace),
        "unreached_vtu_loads": trace.unreached_vtu_loads,
        "path": trace.points,
        "scene": context.scene.echo_json(),
    })
}
