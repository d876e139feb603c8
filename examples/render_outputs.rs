//! Renders every plot and the HTML report of a `wrinkle run` output directory with the output
//! APIs of `wrinkle::output`, from the files the run wrote (`summary.json`, `scene.toml`,
//! `fields_*.vtu`): the response curve, the profiles through the maximum of the wrinkles, the
//! wrinkle maps (last field and first field), a comparison of several runs of one scene, and
//! `report.html`.
//!
//! ```sh
//! cargo run --release -- run --out out/o1 --set 'output.vtu_loads=[0.05,0.095,0.1,0.105]'
//! cargo run --release --example render_outputs -- out/o1 --out out/o1/rendered \
//!     [--compare out/o3 ...]
//! ```
//!
//! Runs written before the pipeline report the *envelope*; the physical amplitude is twice it
//! (THEORY §3), and this driver doubles it. The output directory is a [`RunDirectory`]: locked
//! while rendering, written beside itself and swapped in whole (replacing its previous
//! rendering), and its `summary.json` lists the files written.

use std::error::Error;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use vtkio::model::{Attribute, DataSet, Piece, VertexNumbers, Vtk};
use wrinkle::output::report::format_rows;
use wrinkle::output::{
    ClosedFormCurve, GridField, LoadMarker, PathPoint, Profile, ProfilePlot, Quantity, Report,
    ReportFigure, Response, ResponsePoint, RunDirectory, Severity, SummaryTable, Warning,
    WrinkleMap, plot_comparison, plot_profiles, plot_response, plot_wrinkle_map, write_report,
};
use wrinkle_runtime::fem::{ElementKind, Mesh};

type Result<T> = std::result::Result<T, Box<dyn Error>>;

/// Threshold of the wrinkle maps, as a fraction of the thickness.
const FLAT_FRACTION: f64 = 1e-3;

fn main() -> Result<()> {
    let mut arguments = std::env::args().skip(1);
    let mut run_directory = None;
    let mut output = None;
    let mut compare = Vec::new();
    while let Some(argument) = arguments.next() {
        match argument.as_str() {
            "--out" => output = arguments.next().map(PathBuf::from),
            "--compare" => compare.extend(arguments.next().map(PathBuf::from)),
            _ => run_directory = Some(PathBuf::from(argument)),
        }
    }
    let run_directory = run_directory.ok_or(
        "usage: render_outputs RUN_DIRECTORY [--out DIRECTORY] [--compare RUN_DIRECTORY]...",
    )?;
    let output = output.unwrap_or_else(|| run_directory.join("rendered"));
    let run = RunData::load(&run_directory)?;
    let mut directory = RunDirectory::open(&output)?;
    let mut figures = Vec::new();

    let response = run.response();
    let plot = plot_response(
        &directory.path("response"),
        &format!("{}: physical wrinkle amplitude", run.model),
        &response,
    )?;
    directory.record(&plot.files)?;
    figures.push(ReportFigure::png(
        &plot.files[0],
        "Response: largest physical amplitude against the load (left) and the post-buckling \
         part against λ/λ_c (right).",
    ));

    let fields = run.fields()?;
    let last = fields
        .last()
        .ok_or("no fields_*.vtu file in the run directory")?;
    let (crest_x, crest_y) = run.crest(last);
    for (name, along_x) in [("profiles_x", true), ("profiles_y", false)] {
        let plot = run.profiles(&fields, along_x, (crest_x, crest_y));
        let written = plot_profiles(
            &directory.path(name),
            &format!("{}: physical deflection profiles", run.model),
            &plot,
        )?;
        directory.record(&written.files)?;
        figures.push(ReportFigure::png(
            &written.files[0],
            format!("Physical deflection w / h {}.", plot.location),
        ));
    }
    let first = &fields[0];
    for (name, field) in [("wrinkles", last), ("wrinkles_first", first)] {
        if name == "wrinkles_first" && fields.len() < 2 {
            continue;
        }
        let map = WrinkleMap::new(
            run.deflection_grid(field),
            FLAT_FRACTION * run.thickness,
            "10⁻³ h",
        );
        let written = plot_wrinkle_map(
            &directory.path(name),
            &format!(
                "{}: physical deflection at λ = {}",
                run.model,
                run.load.format_value(field.load)
            ),
            &map,
        )?;
        directory.record(&written.files)?;
        figures.push(ReportFigure::png(
            &written.files[0],
            format!(
                "Wrinkle map at λ = {}: {}.",
                run.load.format_value(field.load),
                map.note()
            ),
        ));
    }

    if !compare.is_empty() {
        let mut responses = vec![run.labelled_response()];
        for other in &compare {
            responses.push(RunData::load(other)?.labelled_response());
        }
        let written = plot_comparison(
            &directory.path("comparison"),
            "Comparison on one scene: physical wrinkle amplitude",
            &responses,
        )?;
        directory.record(&written.files)?;
        figures.push(ReportFigure::png(
            &written.files[0],
            "Comparison: largest physical amplitude against the load (left) and against each \
             run's λ/λ_c (right).",
        ));
    }

    let summary = run.summary();
    println!("{}", summary.to_text());
    let mut report = Report::from_summary(&summary);
    report.title = format!("{} — {}", run.model, run.scene_source);
    report.subtitle = format!("run directory {}", run_directory.display());
    report.warnings = run.warnings();
    report.rows = summary.rows();
    report.figures = figures;
    report.scene_toml = run.scene_toml.clone();
    let report_path = directory.path("report.html");
    directory.record([&report_path])?;
    report.files = directory.files().to_vec();
    report.files.push("summary.json".into());
    write_report(&report_path, &report)?;
    directory.write_summary(&serde_json::json!({
        "rendered_from": run_directory.display().to_string(),
        "summary_rows": format_rows(&summary.rows()),
    }))?;
    directory.commit()?;
    println!("rendered into {}", output.display());
    Ok(())
}

/// What a run directory holds, read back.
struct RunData {
    directory: PathBuf,
    summary: serde_json::Value,
    points: Vec<PathPoint>,
    scene_toml: String,
    scene_source: String,
    model: String,
    method: String,
    load: Quantity,
    critical_load: f64,
    thickness: f64,
    wavenumber: f64,
    direction: f64,
}

/// The envelope of one `fields_*.vtu` file on its Q8 mesh.
struct Fields {
    load: f64,
    mesh: Mesh,
    envelope: Vec<f64>,
}

impl RunData {
    fn load(directory: &Path) -> Result<Self> {
        let text = std::fs::read_to_string(directory.join("summary.json"))?;
        let summary: serde_json::Value = serde_json::from_str(&text)?;
        let points: Vec<PathPoint> = serde_json::from_value(summary["path"].clone())?;
        let number = |value: &serde_json::Value, what: &str| {
            value
                .as_f64()
                .ok_or_else(|| format!("summary.json: `{what}` is not a number"))
        };
        let load = if summary["load_kind"] == "strip" {
            Quantity::end_displacement()
        } else {
            Quantity::biaxial_load()
        };
        Ok(RunData {
            directory: directory.to_path_buf(),
            scene_toml: std::fs::read_to_string(directory.join("scene.toml"))?,
            scene_source: summary["scene"]["source"]
                .as_str()
                .unwrap_or("scene")
                .to_string(),
            model: summary["model"].as_str().unwrap_or("model").to_string(),
            method: match summary["method"].as_str().unwrap_or("") {
                "anm" => "ANM".to_string(),
                "riks" => "Riks".to_string(),
                other => other.to_string(),
            },
            load,
            critical_load: number(&summary["linear_buckling_load"], "linear_buckling_load")?,
            thickness: number(&summary["scene"]["material"]["thickness"], "thickness")?,
            wavenumber: number(&summary["wavenumber"], "wavenumber")?,
            direction: number(&summary["scene"]["model"]["direction"], "direction")?.to_radians(),
            points,
            summary,
        })
    }

    /// The response in physical terms (twice the envelope).
    fn response(&self) -> Response {
        let points = self
            .points
            .iter()
            .map(|p| ResponsePoint {
                load: p.lambda,
                max_amplitude_over_h: p.max_amplitude_over_h,
                centre_amplitude_over_h: Some(p.centre_amplitude_over_h.abs()),
                step_end: !p.interior,
            })
            .collect();
        let mut response = Response::new(
            self.model.clone(),
            self.load.clone(),
            self.critical_load,
            points,
        )
        .with_marker(LoadMarker::linear_buckling(self.critical_load, &self.load));
        let closed: Vec<(f64, f64)> = self
            .points
            .iter()
            .filter(|p| p.lambda >= self.critical_load)
            .filter_map(|p| {
                p.closed_form_amplitude_over_h
                    .map(|a| (p.lambda / self.critical_load, a))
            })
            .collect();
        if !closed.is_empty() {
            let mut points = vec![(1.0, 0.0)];
            points.extend(closed);
            response = response.with_closed_form(ClosedFormCurve {
                label: "one-mode closed form (62), physical".into(),
                points,
            });
        }
        if let Some(loss) = self.summary["loss_of_ellipticity"].as_object()
            && let Some(at) = loss["load"].as_f64()
        {
            response = response.with_marker(LoadMarker::loss_of_ellipticity(
                at,
                loss.get("area_fraction").and_then(|f| f.as_f64()),
                &self.load,
            ));
        }
        response
    }

    /// The response named after model and solver, without closed form (for comparisons).
    fn labelled_response(&self) -> Response {
        let mut response = self.response();
        response.model = format!(
            "{}, {}, {} dofs",
            self.model, self.method, self.summary["dofs"]
        );
        response.closed_form = None;
        response
    }

    /// `fields_*.vtu` by increasing load (the final field last).
    fn fields(&self) -> Result<Vec<Fields>> {
        let mut fields = Vec::new();
        for entry in std::fs::read_dir(&self.directory)? {
            let path = entry?.path();
            let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
            let load = if name == "fields_final.vtu" {
                self.points.last().map(|p| p.lambda)
            } else if let Some(load) = name
                .strip_prefix("fields_load_")
                .and_then(|n| n.strip_suffix(".vtu"))
            {
                load.parse().ok()
            } else {
                None
            };
            if let Some(load) = load {
                let (mesh, envelope) = read_q8_envelope(&path)?;
                fields.push(Fields {
                    load,
                    mesh,
                    envelope,
                });
            }
        }
        fields.sort_by(|a, b| a.load.total_cmp(&b.load));
        Ok(fields)
    }

    /// Physical deflection $`w = 2 A \cos(Q\,e\cdot X)`$ at a point (0 outside the mesh).
    fn deflection(&self, field: &Fields, x: f64, y: f64) -> f64 {
        let envelope = field
            .mesh
            .interpolate(&field.envelope, 1, 0, [x, y])
            .unwrap_or(0.0);
        let phase = self.wavenumber * (self.direction.cos() * x + self.direction.sin() * y);
        2.0 * envelope * phase.cos()
    }

    /// The physical deflection of `field` on a grid of about 12 points per wavelength.
    fn deflection_grid(&self, field: &Fields) -> GridField {
        let bounds = field.mesh.bounds();
        let per_mm = 12.0 * self.wavenumber / (2.0 * PI);
        let count = |length: f64| ((length * per_mm).ceil() as usize).clamp(60, 1500);
        GridField::sample(
            Quantity::deflection(),
            bounds,
            count(bounds[1] - bounds[0]),
            count(bounds[3] - bounds[2]),
            |x, y| self.deflection(field, x, y),
        )
    }

    /// The point of largest physical deflection of `field` (on a crest of the wave).
    fn crest(&self, field: &Fields) -> (f64, f64) {
        let grid = self.deflection_grid(field);
        let (i, j, _) = grid.max_abs_point().unwrap_or((0, 0, 0.0));
        let [x, y] = grid.point(i, j);
        (x, y)
    }

    /// Profiles of $`w/h`$ along X (at the crest's Y) or along Y (at the crest's X), one per
    /// field.
    fn profiles(&self, fields: &[Fields], along_x: bool, (cx, cy): (f64, f64)) -> ProfilePlot {
        let bounds = fields[0].mesh.bounds();
        let samples = 1600;
        let profiles = fields
            .iter()
            .map(|field| {
                let points = (0..=samples)
                    .map(|k| {
                        let t = k as f64 / samples as f64;
                        let (x, y) = if along_x {
                            (bounds[0] + t * (bounds[1] - bounds[0]), cy)
                        } else {
                            (cx, bounds[2] + t * (bounds[3] - bounds[2]))
                        };
                        let s = if along_x { x } else { y };
                        (s, self.deflection(field, x, y) / self.thickness)
                    })
                    .collect();
                Profile {
                    label: format!(
                        "λ = {} ({:.3} λ_c)",
                        self.load.format_value(field.load),
                        field.load / self.critical_load
                    ),
                    points,
                }
            })
            .collect();
        let location = if along_x {
            format!("along X at Y = {cy:.1} mm (through the maximum)")
        } else {
            format!("along Y at X = {cx:.1} mm (through the maximum)")
        };
        ProfilePlot {
            abscissa: Quantity::coordinate(if along_x { "X" } else { "Y" }),
            ordinate: Quantity::deflection_over_thickness(),
            location,
            profiles,
        }
    }

    fn summary(&self) -> SummaryTable {
        let s = &self.summary;
        let last = self.points.last();
        let solver = &s["scene"]["solver"];
        let target = solver["max_amplitude_over_h"]
            .as_f64()
            .or_else(|| solver["max_envelope_over_h"].as_f64().map(|t| 2.0 * t));
        let final_amplitude = last.map(|p| p.max_amplitude_over_h);
        let reached = !s["failed"].as_bool().unwrap_or(true)
            && match (final_amplitude, target) {
                (Some(a), Some(t)) => a >= t * (1.0 - 1e-9),
                _ => true,
            };
        SummaryTable {
            model: self.model.clone(),
            method: self.method.clone(),
            dofs: s["dofs"].as_u64().unwrap_or(0) as usize,
            wavenumber: Some(self.wavenumber),
            wavelength: Some(std::f64::consts::TAU / self.wavenumber),
            load: self.load.clone(),
            critical_load: Some(self.critical_load),
            closed_form_critical_load: s["closed_form_critical_load"].as_f64(),
            closed_form_source: "eq. (42)".into(),
            final_load: last.map(|p| p.lambda),
            final_amplitude_over_h: final_amplitude,
            target_amplitude_over_h: target,
            thickness: Some(self.thickness),
            steps: s["steps"].as_u64().unwrap_or(0) as usize,
            factorizations: s["statistics"]["factorizations"].as_u64().unwrap_or(0) as usize,
            seconds: s["timings"]["total"].as_f64().unwrap_or(0.0),
            peak_memory_bytes: s["memory"]["peak_resident_bytes"].as_u64(),
            stop: s["stop"].as_str().unwrap_or("unknown").to_string(),
            reached_target: reached,
        }
    }

    fn warnings(&self) -> Vec<Warning> {
        let s = &self.summary;
        let mut warnings = Vec::new();
        if s["failed"].as_bool().unwrap_or(false) {
            warnings.push(Warning::new(
                Severity::Failure,
                format!("the solver failed: {}", s["stop"].as_str().unwrap_or("?")),
                "The outputs show the path up to the failure.",
            ));
        }
        if let Some(loss) = s["loss_of_ellipticity"].as_object() {
            let at = loss["load"].as_f64().unwrap_or(f64::NAN);
            let fraction = loss.get("area_fraction").and_then(|f| f.as_f64());
            warnings.push(Warning::new(
                Severity::Warning,
                format!("loss of ellipticity at λ = {}", self.load.format_value(at)),
                format!(
                    "The model is not elliptic on {} of the area from this load on (at {}); \
                     the envelope model may then resolve the mesh rather than the wrinkles.",
                    fraction
                        .map(|f| format!("{:.2} %", 100.0 * f))
                        .unwrap_or_else(|| "part".into()),
                    loss.get("location")
                        .and_then(|l| l.as_array())
                        .map(|l| {
                            let c: Vec<String> = l
                                .iter()
                                .filter_map(|c| c.as_f64())
                                .map(|c| format!("{c:.1}"))
                                .collect();
                            format!("(X, Y) = ({}) mm", c.join(", "))
                        })
                        .unwrap_or_else(|| "an unknown point".into())
                ),
            ));
        }
        if let Some(bifurcation) = s["detected_bifurcation"].as_object() {
            let relative = bifurcation["relative_difference_to_linear_buckling"]
                .as_f64()
                .unwrap_or(0.0);
            if relative.abs() > 0.02 {
                warnings.push(Warning::new(
                    Severity::Warning,
                    format!(
                        "the bifurcation on the path differs from λ_c by {:+.1} %",
                        100.0 * relative
                    ),
                    "",
                ));
            }
        } else {
            warnings.push(Warning::new(
                Severity::Note,
                "no bifurcation detected on the path",
                "",
            ));
        }
        warnings
    }
}

/// Mesh and the `w` (envelope) point array of a Q8 `fields_*.vtu` file.
fn read_q8_envelope(path: &Path) -> Result<(Mesh, Vec<f64>)> {
    let vtk = Vtk::import(path)?;
    let DataSet::UnstructuredGrid { pieces, .. } = vtk.data else {
        return Err(format!("{}: not an unstructured grid", path.display()).into());
    };
    let Some(Piece::Inline(piece)) = pieces.into_iter().next() else {
        return Err(format!("{}: no inline piece", path.display()).into());
    };
    let coordinates: Vec<f64> = piece
        .points
        .cast_into::<f64>()
        .ok_or("points are not numbers")?;
    let nodes = coordinates.chunks(3).map(|c| [c[0], c[1]]).collect();
    let VertexNumbers::XML { connectivity, .. } = &piece.cells.cell_verts else {
        return Err("cells are not in XML form".into());
    };
    let connectivity = connectivity.iter().map(|&n| n as usize).collect();
    let envelope = piece
        .data
        .point
        .iter()
        .find(|a| a.name() == "w")
        .and_then(|a| match a {
            Attribute::DataArray(array) => array.data.clone().cast_into::<f64>(),
            _ => None,
        })
        .ok_or_else(|| format!("{}: no point array `w`", path.display()))?;
    let mesh = Mesh::new(ElementKind::Quad8, nodes, connectivity)?;
    Ok((mesh, envelope))
}
