//! The files of a line run, buckle and comparison (`docs/outputs.md`, "Line domains"): CSV
//! tables, VTU polylines, PNG/SVG plots, JSON. Writers only format results computed by
//! [`super::threshold`], [`super::path`] and [`super::compare`].
//!
//! **VTU.** `fields_final.vtu`: the mesh as cells of its element (Line3 as VTK quadratic edges,
//! type 21; Hermite2 as lines, type 3) with every field's nodal value (the value component;
//! a Hermite slope is not written) and the physical deflection `physical_deflection` at the
//! nodes. `profile_final.vtu` / `mode.vtu`: the sampled profile as a chain of line cells
//! (type 3; meshio drops poly-line cells), points at $`(X, 0, w)`$, with `physical_deflection` and, for an envelope,
//! `envelope_amplitude` ($`2|v_1|`$). ASCII, numeric arrays only (meshio reads them).

use super::layout::LineLayout;
use super::path::{LineRun, ProfileSample};
use super::threshold::LineThreshold;
use crate::output::{
    Profile, ProfilePlot, Quantity, Response, ResponsePoint, plot_profiles, plot_response,
    write_atomically,
};
use std::io;
use std::path::Path;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::problem::Problem;

/// A named array of point values.
pub struct PointValues<'a> {
    /// Array name.
    pub name: &'a str,
    /// One value per point.
    pub values: Vec<f64>,
}

/// The load a VTU is at, written as field data `load` (Float64) and `load_unit` (UTF-8
/// bytes, UInt8: meshio refuses strings), as the plane's VTU files do.
pub struct VtuLoad<'a> {
    /// $`\lambda`$.
    pub value: f64,
    /// Its unit.
    pub unit: &'a str,
}

/// Writes an ASCII VTU of `points` with `cells` (connectivity lists) of VTK type `cell_type`.
pub fn write_line_vtu(
    path: &Path,
    load: &VtuLoad,
    (points, cells, cell_type): (&[[f64; 3]], &[Vec<usize>], u8),
    arrays: &[PointValues],
) -> io::Result<()> {
    write_atomically(path, |out| {
        writeln!(out, r#"<?xml version="1.0"?>"#)?;
        writeln!(
            out,
            r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
        )?;
        writeln!(out, "<UnstructuredGrid><FieldData>")?;
        writeln!(
            out,
            r#"<DataArray type="Float64" Name="load" NumberOfTuples="1" format="ascii">{:e}</DataArray>"#,
            load.value
        )?;
        let bytes: Vec<String> = load.unit.bytes().map(|b| b.to_string()).collect();
        writeln!(
            out,
            r#"<DataArray type="UInt8" Name="load_unit" NumberOfTuples="{}" format="ascii">{}</DataArray>"#,
            bytes.len(),
            bytes.join(" ")
        )?;
        writeln!(out, "</FieldData>")?;
        writeln!(
            out,
            r#"<Piece NumberOfPoints="{}" NumberOfCells="{}">"#,
            points.len(),
            cells.len()
        )?;
        let floats = |values: &mut dyn Iterator<Item = f64>| -> String {
            values
                .map(|v| format!("{v:e}"))
                .collect::<Vec<_>>()
                .join(" ")
        };
        writeln!(
            out,
            r#"<Points><DataArray type="Float64" NumberOfComponents="3" format="ascii">"#
        )?;
        writeln!(out, "{}", floats(&mut points.iter().flatten().copied()))?;
        writeln!(out, "</DataArray></Points>")?;
        let integers = |values: Vec<usize>| -> String {
            values
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(" ")
        };
        let offsets: Vec<usize> = cells
            .iter()
            .scan(0, |end, cell| {
                *end += cell.len();
                Some(*end)
            })
            .collect();
        writeln!(out, "<Cells>")?;
        writeln!(
            out,
            r#"<DataArray type="Int64" Name="connectivity" format="ascii">"#
        )?;
        writeln!(out, "{}", integers(cells.concat()))?;
        writeln!(
            out,
            r#"</DataArray><DataArray type="Int64" Name="offsets" format="ascii">"#
        )?;
        writeln!(out, "{}", integers(offsets))?;
        writeln!(
            out,
            r#"</DataArray><DataArray type="UInt8" Name="types" format="ascii">"#
        )?;
        writeln!(out, "{}", integers(vec![cell_type as usize; cells.len()]))?;
        writeln!(out, "</DataArray></Cells>")?;
        writeln!(out, "<PointData>")?;
        for array in arrays {
            writeln!(
                out,
                r#"<DataArray type="Float64" Name="{}" format="ascii">"#,
                array.name
            )?;
            writeln!(out, "{}", floats(&mut array.values.iter().copied()))?;
            writeln!(out, "</DataArray>")?;
        }
        writeln!(out, "</PointData></Piece></UnstructuredGrid></VTKFile>")
    })
}

/// The mesh and nodal fields of a state (`fields_final.vtu`, module documentation).
pub fn write_fields_vtu<M: EnergyModel>(
    path: &Path,
    (problem, layout): (&Problem<M>, &LineLayout),
    (free, load, unit): (&[f64], f64, &str),
    wavenumber: f64,
) -> io::Result<()> {
    let global = problem.dofs().expand(free, load);
    let mesh = problem.assembler.mesh();
    let components = mesh.kind.components();
    let nf = layout.field_count;
    let points: Vec<[f64; 3]> = mesh.nodes.iter().map(|p| [p[0], p[1], 0.0]).collect();
    let cells: Vec<Vec<usize>> = mesh.elements().map(<[usize]>::to_vec).collect();
    let mut arrays: Vec<PointValues> = M::SPEC
        .fields
        .iter()
        .enumerate()
        .map(|(field, name)| PointValues {
            name,
            values: (0..mesh.nodes.len())
                .map(|node| global[(node * nf + field) * components])
                .collect(),
        })
        .collect();
    arrays.push(PointValues {
        name: "physical_deflection",
        values: mesh
            .nodes
            .iter()
            .map(|p| layout.deflection_at(mesh, &global, wavenumber, p[0]))
            .collect(),
    });
    let vtu_load = VtuLoad { value: load, unit };
    let cell_type = mesh.kind.vtk_cell_type();
    write_line_vtu(path, &vtu_load, (&points, &cells, cell_type), &arrays)
}

/// A sampled profile as a chain of line cells (`profile_final.vtu`, `mode.vtu`) at `load`; `scale`
/// turns the samples' values into millimetres for the points' Z.
pub fn write_profile_vtu(
    path: &Path,
    load: &VtuLoad,
    samples: &[ProfileSample],
    scale: f64,
) -> io::Result<()> {
    let points: Vec<[f64; 3]> = samples
        .iter()
        .map(|s| [s.x, 0.0, s.deflection_over_h * scale])
        .collect();
    let mut arrays = vec![PointValues {
        name: "physical_deflection",
        values: samples
            .iter()
            .map(|s| s.deflection_over_h * scale)
            .collect(),
    }];
    if samples.iter().all(|s| s.envelope_over_h.is_some()) {
        arrays.push(PointValues {
            name: "envelope_amplitude",
            values: samples
                .iter()
                .map(|s| s.envelope_over_h.unwrap_or(0.0) * scale)
                .collect(),
        });
    }
    let cells: Vec<Vec<usize>> = (1..samples.len()).map(|k| vec![k - 1, k]).collect();
    write_line_vtu(path, load, (&points, &cells, 3), &arrays)
}

/// `profile_final.csv`: `x`, `deflection_over_h` and, for an envelope, `envelope_over_h`.
pub fn write_profile_csv(path: &Path, samples: &[ProfileSample]) -> io::Result<()> {
    let envelope = samples.iter().all(|s| s.envelope_over_h.is_some());
    write_atomically(path, |out| {
        if envelope {
            writeln!(out, "x,deflection_over_h,envelope_over_h")?;
        } else {
            writeln!(out, "x,deflection_over_h")?;
        }
        for s in samples {
            match s.envelope_over_h {
                Some(e) if envelope => writeln!(out, "{},{},{}", s.x, s.deflection_over_h, e)?,
                _ => writeln!(out, "{},{}", s.x, s.deflection_over_h)?,
            }
        }
        Ok(())
    })
}

/// `path.csv` of a line run.
pub fn write_line_path_csv(path: &Path, run: &LineRun) -> io::Result<()> {
    write_atomically(path, |out| {
        writeln!(
            out,
            "step,interior,lambda,max_amplitude_over_h,centre_amplitude_over_h,residual"
        )?;
        for p in &run.points {
            writeln!(
                out,
                "{},{},{},{},{},{:e}",
                p.step,
                p.interior,
                p.lambda,
                p.max_amplitude_over_h,
                p.centre_amplitude_over_h,
                p.residual
            )?;
        }
        Ok(())
    })
}

/// The profile lines of a state: $`w/h`$ and, for an envelope, $`\pm 2|v_1|/h`$, labelled with
/// `label`.
pub fn profile_lines(label: &str, samples: &[ProfileSample]) -> Vec<Profile> {
    let mut lines = vec![Profile {
        label: format!("{label}: w / h"),
        points: samples.iter().map(|s| (s.x, s.deflection_over_h)).collect(),
    }];
    lines.extend(envelope_lines(label, samples));
    lines
}

/// $`\pm 2|v_1|/h`$ of an envelope's state (none for a resolved deflection).
pub fn envelope_lines(label: &str, samples: &[ProfileSample]) -> Vec<Profile> {
    let mut lines = Vec::new();
    if samples.iter().all(|s| s.envelope_over_h.is_some()) {
        for sign in [1.0, -1.0] {
            lines.push(Profile {
                label: format!("{label}: {}2|v₁| / h", if sign > 0.0 { "+" } else { "−" }),
                points: samples
                    .iter()
                    .map(|s| (s.x, sign * s.envelope_over_h.unwrap_or(0.0)))
                    .collect(),
            });
        }
    }
    lines
}

/// `profile_final.png/.svg`: the last state along the beam.
pub fn plot_final_profile(stem: &Path, run: &LineRun) -> io::Result<Vec<std::path::PathBuf>> {
    let last = run.points.last().map_or(0.0, |p| p.lambda);
    let load = &run.threshold.load;
    let plot = ProfilePlot {
        abscissa: Quantity::coordinate("X"),
        ordinate: Quantity::deflection_over_thickness(),
        location: format!(
            "along the beam at λ = {} {} ({:.4} λ_c)",
            crate::output::quantity::format_significant(last, 6),
            load.unit,
            last / run.threshold.critical_load
        ),
        profiles: profile_lines(&run.threshold.model, &run.profile),
    };
    let title = format!("{}: physical deflection", run.threshold.model);
    plot_profiles(stem, &title, &plot).map(|output| output.files)
}

/// `response.png/.svg`: amplitude against load.
pub fn plot_line_response(stem: &Path, run: &LineRun) -> io::Result<Vec<std::path::PathBuf>> {
    let points = run
        .points
        .iter()
        .map(|p| ResponsePoint {
            load: p.lambda,
            max_amplitude_over_h: p.max_amplitude_over_h,
            centre_amplitude_over_h: Some(p.centre_amplitude_over_h),
            step_end: !p.interior,
        })
        .collect();
    let threshold = &run.threshold;
    let response = Response::new(
        threshold.model.clone(),
        threshold.load.clone(),
        threshold.critical_load,
        points,
    )
    .with_marker(crate::output::LoadMarker::linear_buckling(
        threshold.critical_load,
        &threshold.load,
    ));
    let title = format!("{}: amplitude against load", threshold.model);
    plot_response(stem, &title, &response).map(|output| output.files)
}

/// The samples of a buckling mode (unit peak; `deflection_over_h` holds $`w`$).
pub fn mode_samples(threshold: &LineThreshold) -> Vec<ProfileSample> {
    threshold
        .mode
        .iter()
        .enumerate()
        .map(|(k, &(x, w))| ProfileSample {
            x,
            deflection_over_h: w,
            envelope_over_h: threshold.mode_envelope.get(k).map(|e| e.1),
        })
        .collect()
}

/// The files of a line run besides `fields_final.vtu` and `summary.json`: `path.csv`,
/// `profile_final.csv`, `profile_final.vtu`, `profile_final.png/.svg`, `response.png/.svg`.
pub fn write_run_files(
    directory: &crate::output::RunDirectory,
    run: &LineRun,
    thickness: f64,
) -> io::Result<Vec<std::path::PathBuf>> {
    let mut files = vec![
        directory.path("path.csv"),
        directory.path("profile_final.csv"),
        directory.path("profile_final.vtu"),
    ];
    write_line_path_csv(&files[0], run)?;
    write_profile_csv(&files[1], &run.profile)?;
    let load = VtuLoad {
        value: run.points.last().map_or(0.0, |p| p.lambda),
        unit: &run.threshold.load.unit,
    };
    write_profile_vtu(&files[2], &load, &run.profile, thickness)?;
    files.extend(plot_final_profile(&directory.path("profile_final"), run)?);
    files.extend(plot_line_response(&directory.path("response"), run)?);
    Ok(files)
}

/// `wrinkle buckle --out DIR` on a line: `mode_profile.csv`, `mode.vtu`,
/// `mode_profile.png/.svg` and `buckle.json`.
pub fn write_buckle_files(directory: &Path, threshold: &LineThreshold) -> io::Result<()> {
    std::fs::create_dir_all(directory)?;
    let samples = mode_samples(threshold);
    write_profile_csv(&directory.join("mode_profile.csv"), &samples)?;
    let load = VtuLoad {
        value: threshold.critical_load,
        unit: &threshold.load.unit,
    };
    write_profile_vtu(&directory.join("mode.vtu"), &load, &samples, 1.0)?;
    crate::output::write_json(&directory.join("buckle.json"), threshold)?;
    let plot = ProfilePlot {
        abscissa: Quantity::coordinate("X"),
        ordinate: Quantity::new("first buckling mode", "w / max|w|", ""),
        location: format!(
            "λ_c = {} {}",
            crate::output::quantity::format_significant(threshold.critical_load, 8),
            threshold.load.unit
        ),
        profiles: profile_lines(&threshold.model, &samples),
    };
    let title = format!("{}: first buckling mode", threshold.model);
    plot_profiles(&directory.join("mode_profile"), &title, &plot)?;
    Ok(())
}
