//! The files of a run (documented in `docs/outputs.md`): `path.csv`, `fields_*.vtu`,
//! `surface_final.vtu`, the plots, `report.html`, `scene.toml`, and `summary.json` last with the
//! list of every file written — all into the staging directory of a [`RunDirectory`], swapped
//! in whole once complete. Nothing here decides or recomputes a result: the numbers come
//! from the [`RunSummary`] (decided before anything is written) and the states from the
//! [`Trace`]; the physical deflection is read through the field roles ([`crate::physics::Snapshot`]).

use crate::error::{Error, io_error};
use crate::output::run_directory::SERIES_DIRECTORY;
use crate::output::{
    ClosedFormCurve, FieldData, GridField, LoadMarker, PointArray, Profile, ProfilePlot, Quantity,
    ReferenceLevel, Report, ReportFigure, Response, ResponsePoint, RunDirectory, SeriesEntry,
    SummaryTable, plot_profiles, plot_profiles_with_level, plot_response, plot_wrinkle_map,
    write_fields_vtu_with_cells, write_path_csv, write_pvd, write_surface_vtu,
};
use crate::results::{
    FINAL_FIELDS_FILE, FINAL_SURFACE_FILE, RunContext, RunReport, RunSummary, Snap, Trace,
    fields_file_at,
};
use crate::scene::PathMethod;
use crate::threshold::load_unit;
use std::path::{Path, PathBuf};

/// The load and the threshold as field data of a VTU file.
fn field_data(context: &RunContext, load: f64) -> FieldData {
    let data =
        FieldData::load(load, load_unit(context.scene)).with_text("model", context.spec.name);
    // A plate has no carrier wavenumber (not 0): only the wavelength read from its mode.
    let data = match context.threshold.wavenumber {
        Some(wavenumber) => data.with_number("wavenumber", wavenumber),
        None => data,
    };
    let data = match context.threshold.wavelength {
        Some(wavelength) => data.with_number("wavelength", wavelength),
        None => data,
    };
    data.with_number("critical_load", context.threshold.critical_load())
}

/// Samples per side of the surface grids: about 12 per wavelength, 50 to 1500.
fn samples(context: &RunContext, length: f64) -> usize {
    let wavelength = context.threshold.wavelength.unwrap_or(length);
    (12.0 * length / wavelength).clamp(50.0, 1500.0) as usize
}

/// Writes every output of a run — the result `summary` of `context` and `trace`, serialised —
/// into the staging directory of `run_directory`, then swaps it in whole
/// ([`RunDirectory::commit`]); `given` is the directory as the user named it (the paths of
/// [`RunReport::files`] are in it).
pub fn write_run(
    context: &RunContext,
    trace: &Trace,
    summary: RunSummary,
    mut run_directory: RunDirectory,
    given: &Path,
) -> Result<RunReport, Error> {
    let dir = run_directory.staging().to_path_buf();
    let mut files: Vec<PathBuf> = Vec::new();
    let csv = dir.join("path.csv");
    write_path_csv(&csv, &summary.path).map_err(io_error(&csv))?;
    files.push(csv);
    // The VTU files and the plots are independent: written side by side.
    let (fields, figures) = rayon::join(
        || write_fields(context, trace, &dir),
        || {
            if context.scene.output.plots {
                write_plots(context, trace, &summary, &dir)
            } else {
                Ok(Vec::new())
            }
        },
    );
    files.extend(fields?);
    let figures = figures?;
    files.extend(figures.iter().flat_map(|(f, _)| f.clone()));
    files.extend(crate::run_figures::write_profile_line_csv(
        context, trace, &dir,
    )?);
    let scene_path = dir.join("scene.toml");
    crate::output::write_bytes_atomically(&scene_path, context.scene.to_toml_string().as_bytes())
        .map_err(io_error(&scene_path))?;
    files.push(scene_path);
    let table = summary_table(context, &summary);
    let report_path = dir.join("report.html");
    run_directory
        .record(files.iter().chain([&report_path]))
        .map_err(io_error(&dir))?;
    let mut report = Report::from_summary(&table);
    report.title = format!("{} on {}", context.spec.name, context.scene.source);
    report.subtitle = format!(
        "scene file: {} · written {} · files below are links",
        context.scene.source,
        crate::output::report::utc_timestamp(std::time::SystemTime::now())
    );
    report.warnings = summary.notices.clone();
    report.figures = figures
        .iter()
        .filter_map(|(f, caption)| f.first().map(|png| ReportFigure::png(png, caption.clone())))
        .collect();
    report.scene_toml = context.scene.to_toml_string();
    report.files = run_directory.files().to_vec();
    crate::output::write_report(&report_path, &report).map_err(io_error(&report_path))?;
    run_directory
        .write_summary(&summary)
        .map_err(io_error(&dir))?;
    let files = run_directory
        .files()
        .iter()
        .map(|name| given.join(name))
        .collect();
    run_directory.commit().map_err(io_error(given))?;
    let summary_text = summary_text(&table, &summary);
    Ok(RunReport {
        summary,
        files,
        summary_text,
    })
}

/// What `wrinkle run` prints at the end: the table, then one line per notice.
fn summary_text(table: &SummaryTable, summary: &RunSummary) -> String {
    let mut text = table.to_text();
    for notice in &summary.notices {
        text.push_str(&format!(
            "{}: {}: {}\n",
            notice.severity.label(),
            notice.title,
            notice.detail
        ));
    }
    text
}

/// `fields_final.vtu`, `fields_load_*.vtu`, `surface_final.vtu`, and the path's time series
/// (`fields.pvd`, `surface.pvd` over `series/`).
fn write_fields(context: &RunContext, trace: &Trace, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut files = Vec::new();
    if context.scene.output.vtu {
        files.push(write_fields_file(
            context,
            &dir.join(FINAL_FIELDS_FILE),
            &trace.last,
        )?);
        for snap in &trace.requested {
            files.push(write_fields_file(
                context,
                &dir.join(fields_file_at(snap.load, &context.scene.output.vtu_loads)),
                snap,
            )?);
        }
    }
    if context.scene.output.surface {
        files.push(write_surface_file(
            context,
            &dir.join(FINAL_SURFACE_FILE),
            &trace.last,
        )?);
    }
    files.extend(write_series(context, trace, dir)?);
    Ok(files)
}

/// One `fields_*.vtu`: the nodal fields of `snap`, the envelope's amplitude, the stress
/// resultants per element, the field data.
fn write_fields_file(context: &RunContext, path: &Path, snap: &Snap) -> Result<PathBuf, Error> {
    let extra = nodal_amplitude(context, &snap.values);
    let cells: Vec<PointArray> = ["N_X", "N_Y", "N_XY"]
        .iter()
        .zip(&snap.stress_resultants)
        .map(|(name, values)| PointArray::scalar(*name, values.clone()))
        .collect();
    write_fields_vtu_with_cells(
        path,
        context.mesh,
        context.spec.fields,
        &snap.values,
        &extra,
        &cells,
        &field_data(context, snap.load),
    )
    .map_err(io_error(path))?;
    Ok(path.to_path_buf())
}

/// One `surface_*.vtu`: the physical deflection of `snap` on a fine grid.
fn write_surface_file(context: &RunContext, path: &Path, snap: &Snap) -> Result<PathBuf, Error> {
    let bounds = context.mesh.bounds();
    let snapshot = context.snapshot(&snap.values);
    let (sx, sy) = (
        samples(context, bounds[1] - bounds[0]),
        samples(context, bounds[3] - bounds[2]),
    );
    let grid = GridField::sample(Quantity::deflection(), bounds, sx + 1, sy + 1, |x, y| {
        snapshot.deflection([x, y])
    });
    write_surface_vtu(path, &grid, 1.0, &[], &field_data(context, snap.load))
        .map_err(io_error(path))?;
    Ok(path.to_path_buf())
}

/// The path as ParaView time series: `series/fields_NNNN.vtu` (with `output.vtu`) and
/// `series/surface_NNNN.vtu` (with `output.surface` too) at every step end and the last point,
/// listed by `fields.pvd` and `surface.pvd` with the load as time.
fn write_series(context: &RunContext, trace: &Trace, dir: &Path) -> Result<Vec<PathBuf>, Error> {
    let mut snaps: Vec<&Snap> = trace.step_ends.iter().collect();
    if !context.scene.output.vtu || trace.last.values.is_empty() {
        return Ok(Vec::new());
    }
    if snaps.last().map(|snap| snap.load) != Some(trace.last.load) {
        snaps.push(&trace.last);
    }
    let series = dir.join(SERIES_DIRECTORY);
    std::fs::create_dir_all(&series).map_err(io_error(&series))?;
    let mut files = Vec::new();
    let mut fields = Vec::new();
    let mut surfaces = Vec::new();
    for (index, snap) in snaps.iter().enumerate() {
        let name = format!("{SERIES_DIRECTORY}/fields_{index:04}.vtu");
        files.push(write_fields_file(context, &dir.join(&name), snap)?);
        fields.push(SeriesEntry {
            load: snap.load,
            file: name,
        });
        if context.scene.output.surface {
            let name = format!("{SERIES_DIRECTORY}/surface_{index:04}.vtu");
            files.push(write_surface_file(context, &dir.join(&name), snap)?);
            surfaces.push(SeriesEntry {
                load: snap.load,
                file: name,
            });
        }
    }
    for (name, entries) in [("fields.pvd", fields), ("surface.pvd", surfaces)] {
        if entries.is_empty() {
            continue;
        }
        let path = dir.join(name);
        write_pvd(&path, &entries).map_err(io_error(&path))?;
        files.push(path);
    }
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
    summary: &RunSummary,
    dir: &Path,
) -> Result<Vec<(Vec<PathBuf>, String)>, Error> {
    // The wrinkle map (the dearest: a fine grid of the deflection) is drawn beside the others.
    let (curves, map) = rayon::join(
        || write_curve_plots(context, trace, summary, dir),
        || write_wrinkle_map(context, trace, dir),
    );
    let mut out = curves?;
    out.push(map?);
    out.extend(crate::run_figures::write_extra_figures(
        context, trace, dir,
    )?);
    Ok(out)
}

/// `response`, `profiles_x`, `profiles_y` and the local wavenumber plot, with captions.
fn write_curve_plots(
    context: &RunContext,
    trace: &Trace,
    summary: &RunSummary,
    dir: &Path,
) -> Result<Vec<(Vec<PathBuf>, String)>, Error> {
    // Independent figures, drawn side by side; listed in a fixed order.
    let (response_plot, (profiles, local_wavenumber)) = rayon::join(
        || {
            let stem = dir.join("response");
            plot_response(
                &stem,
                &format!("{}: physical wrinkle amplitude", context.spec.name),
                &response(context, summary),
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
    // A masked map (a mesh file: holes, curved outlines) needs samples finer than its waves
    // to draw its outline without steps: at least 400 along each side.
    let least = if context.mesh.grid.is_some() { 0 } else { 400 };
    let (mx, my) = (
        samples(context, bounds[1] - bounds[0]).max(least).min(900),
        samples(context, bounds[3] - bounds[2]).max(least).min(450),
    );
    let field = GridField::sample(
        Quantity::deflection(),
        bounds,
        mx + 1,
        my + 1,
        crate::run_figures::domain_sampler(context.mesh, |x, y| snapshot.deflection([x, y])),
    );
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
            .with_peak(snapshot.max_deflection())
            .with_outline(crate::run_figures::map_outline(context.mesh)),
    )
    .map_err(io_error(&stem))?;
    Ok((
        plot.files,
        "Physical deflection at the last point".to_string(),
    ))
}

/// The load–amplitude response of `summary` with its closed form and the markers.
fn response(context: &RunContext, summary: &RunSummary) -> Response {
    let load = context.load_quantity();
    let critical = summary.linear_buckling_load;
    let points = summary
        .path
        .iter()
        .map(|p| ResponsePoint {
            load: p.lambda,
            max_amplitude_over_h: p.max_amplitude_over_h,
            centre_amplitude_over_h: Some(p.centre_amplitude_over_h),
            step_end: !p.interior,
        })
        .collect();
    let mut response = Response::new(summary.model, load.clone(), critical, points)
        .with_marker(LoadMarker::linear_buckling(critical, &load));
    if let Some(curve) = &summary.closed_form_amplitudes {
        response = response.with_closed_form(ClosedFormCurve {
            label:
                "one-mode closed form (62): 2a/h at the centre (compare with |w| / h at the centre)"
                    .into(),
            points: curve.clone(),
        });
    }
    if let Some(loss) = &summary.loss_of_ellipticity {
        response = response.with_marker(LoadMarker::loss_of_ellipticity(
            loss.load,
            Some(loss.area_fraction),
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
    let samples = (2 * samples(context, high - low)).max(400);
    let load = context.load_quantity();
    trace
        .profiles
        .iter()
        .map(|snap| {
            let snapshot = context.snapshot(&snap.values);
            // NaN (a gap in the line) where the line crosses a hole or leaves the outline.
            let value = |p: [f64; 2]| match snapshot.envelope_amplitude(p) {
                _ if context.mesh.grid.is_none() && !context.mesh.contains(p) => f64::NAN,
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
    let theta = context.threshold.direction_degrees.to_radians();
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
    let carrier = context.threshold.wavenumber.map(|q| ReferenceLevel {
        value: q,
        label: format!("carrier Q = {q:.5} /mm"),
    });
    let plot = plot_profiles_with_level(
        &stem,
        &format!("{}: local wavenumber", context.spec.name),
        &ProfilePlot {
            abscissa: Quantity::coordinate(coordinate),
            ordinate: Quantity::new("local wavenumber", "Q + ∂arg(w₁)", "1/mm"),
            location: location.clone(),
            profiles,
        },
        carrier.as_ref(),
    )
    .map_err(io_error(&stem))?;
    Ok(Some((plot.files, format!("Local wavenumber {location}"))))
}

/// The terminal and report table of `summary`.
fn summary_table(context: &RunContext, summary: &RunSummary) -> SummaryTable {
    let scene = context.scene;
    let last = summary.path.last();
    SummaryTable {
        model: summary.model.to_string(),
        method: match (
            scene.solver.method,
            scene.solver.pade,
            scene.solver.exponential_map,
        ) {
            (PathMethod::Anm, true, true) => "ANM + Padé + exp. map".to_string(),
            (PathMethod::Anm, true, false) => "ANM + Padé".to_string(),
            (PathMethod::Anm, false, true) => "ANM + exp. map".to_string(),
            (method, _, _) => method.as_str().to_uppercase(),
        },
        dofs: summary.dofs,
        wavenumber: summary.wavenumber,
        wavelength: summary.wavelength,
        load: context.load_quantity(),
        critical_load: Some(summary.linear_buckling_load),
        closed_form_critical_load: summary.closed_form_critical_load,
        closed_form_source: "eq. (42), envelope".into(),
        final_load: last.map(|p| p.lambda),
        final_amplitude_over_h: last.map(|p| p.max_amplitude_over_h),
        target_amplitude_over_h: Some(scene.solver.max_amplitude_over_thickness),
        thickness: Some(scene.material.thickness),
        steps: summary.steps,
        factorizations: summary.statistics.factorizations,
        seconds: summary.timings.total,
        peak_memory_bytes: summary.memory.peak_resident_bytes,
        stop: summary
            .outcome
            .reason()
            .unwrap_or(&summary.stop)
            .to_string(),
        reached_target: summary.outcome == crate::results::RunOutcome::Reached,
    }
}
