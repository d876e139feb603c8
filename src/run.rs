//! `wrinkle run`: path following of a scene (ANM or Riks) with every output a user needs.
//!
//! Steps: pick the model; fix $`Q`$ (linear buckling minimised over $`Q`$ when `auto`); build the
//! problem with the small transverse perturbation on the envelope; trace the path, checking the
//! Legendre–Hadamard condition at every accepted point; write `summary.json`, `path.csv`,
//! `.vtu` fields and surfaces, PNG/SVG plots. A failed solve still writes everything computed.

use crate::Error;
use crate::commands::{BuckleReport, buckle};
use crate::output::{
    ClosedFormCurve, FieldData, GridField, LoadMarker, PathPoint, PointArray, Profile, ProfilePlot,
    Progress, ProgressSink, ProgressTarget, Quantity, Response, ResponsePoint, RunDirectory,
    WrinkleMap, plot_profiles, plot_response, plot_wrinkle_map, write_fields_vtu, write_path_csv,
    write_surface_vtu,
};
use crate::scene::{LoadKind, PathMethod, Scene, Wavenumber};
use crate::setup::{build_problem, configure_model};
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Instant;
use wrinkle_models::{ModelVisitor, with_model};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::solve::anm::{AnmOptions, AnmStep, follow_path_anm};
use wrinkle_runtime::solve::ellipticity::{EllipticityReport, legendre_hadamard};
use wrinkle_runtime::solve::newton::NewtonOptions;
use wrinkle_runtime::solve::path::{PathControl, PathEvent, PathResult, PathState};
use wrinkle_runtime::solve::riks::{RiksOptions, follow_path_riks};

/// What `run` produced (also written to `summary.json`).
#[derive(Debug)]
pub struct RunReport {
    /// The summary object.
    pub summary: serde_json::Value,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// Whether the path ended by a failure (the caller exits non-zero).
    pub failure: Option<String>,
}

/// A snapshot of the envelope along the two mid-lines, for the profile plots.
struct Profiles {
    load: f64,
    along_x: Vec<(f64, f64)>,
    along_y: Vec<(f64, f64)>,
}

fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |error| Error::Io {
        path: path.display().to_string(),
        error,
    }
}

/// Envelope field index: `w` if the model has one.
fn envelope_field(spec: &wrinkle_runtime::ModelSpec) -> Option<usize> {
    spec.field_index("w")
}

struct RunVisitor<'a> {
    scene: &'a Scene,
    directory: RunDirectory,
    threshold: BuckleReport,
}

/// Path following of a scene, writing its outputs into `output_directory`.
pub fn run(scene: &Scene, output_directory: &Path) -> Result<RunReport, Error> {
    // Removes the previous run's files (only those it listed) before anything is written.
    let directory = RunDirectory::prepare(output_directory).map_err(io_error(output_directory))?;
    // The threshold (and the wavenumber when `auto`) from linear buckling of the same mesh.
    let threshold = buckle(scene)?;
    let visitor = RunVisitor {
        scene,
        directory,
        threshold,
    };
    with_model(&scene.model.name, visitor)
        .unwrap_or_else(|| Err(crate::commands::unknown_model(scene)))
}

impl ModelVisitor for RunVisitor<'_> {
    type Output = Result<RunReport, Error>;

    fn visit<M: EnergyModel>(mut self, mut model: M) -> Self::Output {
        let scene = self.scene;
        let spec = M::SPEC;
        let begin = Instant::now();
        let q = match scene.model.wavenumber {
            Wavenumber::Fixed(q) => q,
            Wavenumber::Auto => self.threshold.wavenumber,
        };
        configure_model(scene, &mut model, q)?;
        let h = scene.material.thickness;
        let w_field = envelope_field(spec).ok_or_else(|| {
            crate::setup::scene_error(
                scene,
                "model.name",
                format!("model `{}` has no envelope field `w`", spec.name),
            )
        })?;
        // Transverse perturbation: the load that would give envelope/h = `perturbation` on an
        // unloaded sheet, f = perturbation · h · D Q⁴.
        let e = scene.material.young_modulus;
        let nu = scene.material.poisson_ratio;
        let bending = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
        let force = scene.solver.perturbation * h * bending * q.powi(4);
        let problem = build_problem(scene, model, force)?;
        let mesh = problem.assembler.mesh().clone();
        let nf = spec.fields.len();
        let bounds = mesh.bounds();
        let centre = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])];
        let direction = scene.model.direction_degrees.to_radians();
        let lambda_c = self.threshold.critical_load;
        let biaxial = scene.load.kind == LoadKind::Biaxial;
        let load_quantity = if biaxial {
            Quantity::biaxial_load()
        } else {
            Quantity::end_displacement()
        };
        let closed_form_amplitude =
            (biaxial && spec.name == "reference-envelope" && scene.model.direction_degrees == 0.0)
                .then(|| {
                    let rectangle = scene.clamped_rectangle();
                    (rectangle.aspect_ratio(), nu)
                });

        let mut factor = SparseFactorization::analyze(problem.assembler.pattern())
            .map_err(|e| Error::Solver(format!("symbolic analysis of the tangent: {e}")))?;

        // Observer state.
        let mut points: Vec<PathPoint> = Vec::new();
        let mut first_loss_of_ellipticity: Option<(f64, EllipticityReport)> = None;
        let mut previous_state: Option<PathState> = None;
        let mut vtu_requests: Vec<f64> = scene.output.vtu_loads.clone();
        vtu_requests.sort_by(f64::total_cmp);
        let mut vtu_written: Vec<(f64, PathBuf)> = Vec::new();
        let mut vtu_errors: Vec<String> = Vec::new();
        let target = scene.solver.max_envelope_over_thickness;
        let profile_levels: Vec<f64> = [0.05, 0.25, 0.5, 0.75, 1.0]
            .iter()
            .map(|f| f * target)
            .collect();
        let mut profiles: Vec<Profiles> = Vec::new();
        let progress = Progress::new(
            "wrinkle run",
            ProgressTarget::new(
                Quantity::new("envelope", "max |w_env| / h", ""),
                0.0,
                target,
            ),
            ProgressSink::standard_error(false),
        );
        let mut last_state = PathState {
            displacement: vec![],
            load: 0.0,
        };

        let sample_profiles = |global: &[f64], load: f64| Profiles {
            load,
            along_x: (0..=200)
                .map(|k| {
                    let x = bounds[0] + (bounds[1] - bounds[0]) * k as f64 / 200.0;
                    (
                        x,
                        mesh.interpolate(global, nf, w_field, [x, centre[1]])
                            .unwrap_or(0.0)
                            / h,
                    )
                })
                .collect(),
            along_y: (0..=200)
                .map(|k| {
                    let y = bounds[2] + (bounds[3] - bounds[2]) * k as f64 / 200.0;
                    (
                        y,
                        mesh.interpolate(global, nf, w_field, [centre[0], y])
                            .unwrap_or(0.0)
                            / h,
                    )
                })
                .collect(),
        };

        let mut observer = |event: &PathEvent| -> PathControl {
            let state = event.state;
            let global = problem.dofs().expand(&state.displacement, state.load);
            let max_envelope = (0..mesh.nodes.len())
                .map(|n| global[n * nf + w_field].abs())
                .fold(0.0, f64::max);
            let centre_value = mesh
                .interpolate(&global, nf, w_field, centre)
                .unwrap_or(0.0);
            let ellipticity = legendre_hadamard(&problem, &state.displacement, state.load);
            if !ellipticity.elliptic && first_loss_of_ellipticity.is_none() {
                first_loss_of_ellipticity = Some((state.load, ellipticity.clone()));
            }
            let closed = closed_form_amplitude.map(|(alpha, nu)| {
                crate::closed_form::amplitude_from_load_ratio(alpha, nu, state.load / lambda_c)
            });
            points.push(PathPoint {
                step: event.step,
                interior: event.interior,
                lambda: state.load,
                n_x: biaxial.then_some(-state.load),
                max_envelope,
                max_envelope_over_h: max_envelope / h,
                center_envelope_over_h: centre_value / h,
                residual: event.relative_residual,
                elliptic: ellipticity.elliptic,
                closed_form_envelope_over_h: closed,
            });
            // Fields at requested loads, interpolated between the two path points around them.
            if let Some(previous) = &previous_state {
                while let Some(&requested) = vtu_requests.first() {
                    if !(previous.load <= requested && requested <= state.load) {
                        if requested < previous.load {
                            vtu_requests.remove(0);
                            continue;
                        }
                        break;
                    }
                    vtu_requests.remove(0);
                    let t = if state.load > previous.load {
                        (requested - previous.load) / (state.load - previous.load)
                    } else {
                        1.0
                    };
                    let interpolated: Vec<f64> = previous
                        .displacement
                        .iter()
                        .zip(&state.displacement)
                        .map(|(a, b)| a + t * (b - a))
                        .collect();
                    let g = problem.dofs().expand(&interpolated, requested);
                    let path = self
                        .directory
                        .path(format!("fields_load_{requested:.6}.vtu"));
                    let field_data = FieldData::load(requested, load_quantity.unit.clone());
                    match write_fields_vtu(&path, &mesh, spec.fields, &g, &[], &field_data) {
                        Ok(()) => vtu_written.push((requested, path)),
                        Err(e) => vtu_errors.push(format!("{}: {e}", path.display())),
                    }
                }
            }
            while profiles.len() < profile_levels.len()
                && max_envelope / h >= profile_levels[profiles.len()]
            {
                profiles.push(sample_profiles(&global, state.load));
            }
            previous_state = Some(state.clone());
            last_state = state.clone();
            progress.update(
                max_envelope / h,
                &format!(
                    "step {}, λ = {}",
                    event.step,
                    load_quantity.format_value(state.load)
                ),
            );
            if max_envelope / h >= target {
                PathControl::Stop
            } else {
                PathControl::Continue
            }
        };

        // Start on the path: equilibrium at λ = 0 under the fixed loads (tension, perturbation).
        let start = {
            let mut matrix = problem.new_matrix();
            let solution = wrinkle_runtime::solve::newton::newton(
                &problem,
                vec![0.0; problem.free_count()],
                0.0,
                &mut factor,
                &mut matrix,
                &NewtonOptions::default(),
            )
            .map_err(|e| Error::Solver(format!("equilibrium at zero load: {e}")))?;
            PathState {
                displacement: solution.solution,
                load: 0.0,
            }
        };
        let max_load = (scene.solver.max_load > 0.0).then_some(scene.solver.max_load);
        let mut anm_steps: Vec<AnmStep> = Vec::new();
        let result: PathResult = match scene.solver.method {
            PathMethod::Anm => {
                let options = AnmOptions {
                    order: scene.solver.order,
                    series_tolerance: scene.solver.series_tolerance,
                    residual_tolerance: scene.solver.tolerance,
                    max_steps: scene.solver.max_steps,
                    max_load,
                    pade: scene.solver.pade,
                    corrector: NewtonOptions {
                        tolerance: scene.solver.tolerance * 1e-3,
                        max_iterations: 12,
                    },
                    ..AnmOptions::default()
                };
                follow_path_anm(
                    &problem,
                    start,
                    &mut factor,
                    &options,
                    &mut observer,
                    &mut anm_steps,
                )
            }
            PathMethod::Riks => {
                // Arc length in (U [mm], λ/λ_c), at most 1 % of the threshold per step: larger
                // steps jump over the sharp turn of the perturbed branch at the threshold and
                // converge back onto the unstable fundamental branch.
                let options = RiksOptions {
                    tolerance: scene.solver.tolerance,
                    max_steps: scene.solver.max_steps,
                    max_load,
                    load_scale: 1.0 / lambda_c.abs().max(f64::MIN_POSITIVE),
                    initial_arc_length: 0.01,
                    max_arc_length: 0.01,
                    ..RiksOptions::default()
                };
                follow_path_riks(&problem, start, &mut factor, &options, &mut observer)
            }
        };
        progress.finish(&format!(
            "{} ({} steps)",
            result.stop.describe(),
            result.statistics.steps
        ));

        // ---- outputs ----
        let mut files = Vec::new();
        let dir = self.directory.root().to_path_buf();
        let csv = dir.join("path.csv");
        write_path_csv(&csv, &points).map_err(io_error(&csv))?;
        files.push(csv);
        let final_global = problem
            .dofs()
            .expand(&last_state.displacement, last_state.load);
        let fields = dir.join("fields_final.vtu");
        let final_field_data = FieldData::load(last_state.load, load_quantity.unit.clone());
        write_fields_vtu(
            &fields,
            &mesh,
            spec.fields,
            &final_global,
            &[],
            &final_field_data,
        )
        .map_err(io_error(&fields))?;
        files.push(fields);
        let envelope_at = |x: f64, y: f64| {
            mesh.interpolate(&final_global, nf, w_field, [x, y])
                .unwrap_or(0.0)
        };
        let refine = |length: f64| {
            ((length * q / (2.0 * std::f64::consts::PI)) * 12.0).clamp(50.0, 1500.0) as usize
        };
        let (sx, sy) = (refine(bounds[1] - bounds[0]), refine(bounds[3] - bounds[2]));
        // Physical deflection w = 2 w_env cos(Q e·X) (THEORY §3).
        let deflection_at = |x: f64, y: f64| {
            2.0 * envelope_at(x, y) * (q * (direction.cos() * x + direction.sin() * y)).cos()
        };
        let surface = dir.join("surface_final.vtu");
        let surface_grid = GridField::sample(
            Quantity::deflection(),
            bounds,
            sx + 1,
            sy + 1,
            deflection_at,
        );
        let envelope_array = PointArray::scalar(
            "envelope",
            GridField::sample(Quantity::deflection(), bounds, sx + 1, sy + 1, envelope_at).values,
        );
        write_surface_vtu(
            &surface,
            &surface_grid,
            1.0,
            &[envelope_array],
            &final_field_data,
        )
        .map_err(io_error(&surface))?;
        files.push(surface);
        for (_, p) in &vtu_written {
            files.push(p.clone());
        }

        // Plots.
        let plots_written = if scene.output.plots {
            // Physical amplitudes are twice the envelope (THEORY §3).
            let response_points = points
                .iter()
                .map(|p| ResponsePoint {
                    load: p.lambda,
                    max_amplitude_over_h: 2.0 * p.max_envelope_over_h,
                    centre_amplitude_over_h: Some(2.0 * p.center_envelope_over_h.abs()),
                    step_end: !p.interior,
                })
                .collect();
            let mut response =
                Response::new(spec.name, load_quantity.clone(), lambda_c, response_points)
                    .with_marker(LoadMarker::linear_buckling(lambda_c, &load_quantity));
            if let Some((alpha, nu)) = closed_form_amplitude {
                let last = points.last().map(|p| p.lambda).unwrap_or(lambda_c);
                let top = (last / lambda_c).max(1.001);
                let closed: Vec<(f64, f64)> = (0..=200)
                    .map(|k| {
                        let ratio = 1.0 + (top - 1.0) * k as f64 / 200.0;
                        (
                            ratio,
                            2.0 * crate::closed_form::amplitude_from_load_ratio(alpha, nu, ratio),
                        )
                    })
                    .collect();
                response = response.with_closed_form(ClosedFormCurve {
                    label: "one-mode closed form (62), physical".into(),
                    points: closed,
                });
            }
            if let Some((load, report)) = &first_loss_of_ellipticity {
                response = response.with_marker(LoadMarker::loss_of_ellipticity(
                    *load,
                    Some(report.violated_fraction),
                    &load_quantity,
                ));
            }
            let stem = dir.join("response");
            let plot = plot_response(
                &stem,
                &format!("{}: physical wrinkle amplitude", spec.name),
                &response,
            )
            .map_err(io_error(&stem))?;
            files.extend(plot.files);
            for (name, abscissa, location, pick) in [
                ("profiles_x", "X", "along X at Y = L_Y/2", 0usize),
                ("profiles_y", "Y", "along Y at X = L_X/2", 1usize),
            ] {
                let profiles: Vec<Profile> = profiles
                    .iter()
                    .map(|p| Profile {
                        label: format!("λ = {}", load_quantity.format_value(p.load)),
                        points: if pick == 0 { &p.along_x } else { &p.along_y }
                            .iter()
                            .map(|&(s, a)| (s, 2.0 * a))
                            .collect(),
                    })
                    .collect();
                if !profiles.is_empty() {
                    let stem = dir.join(name);
                    let plot = plot_profiles(
                        &stem,
                        &format!("{}: physical amplitude profiles", spec.name),
                        &ProfilePlot {
                            abscissa: Quantity::coordinate(abscissa),
                            ordinate: Quantity::new("physical amplitude", "2 w_env / h", ""),
                            location: location.to_string(),
                            profiles,
                        },
                    )
                    .map_err(io_error(&stem))?;
                    files.extend(plot.files);
                }
            }
            let (mx, my) = (sx.min(900), sy.min(450));
            let field = GridField::sample(
                Quantity::deflection(),
                bounds,
                mx + 1,
                my + 1,
                deflection_at,
            );
            let stem = dir.join("wrinkles");
            let plot = plot_wrinkle_map(
                &stem,
                &format!(
                    "{}: physical deflection at λ = {}",
                    spec.name,
                    load_quantity.format_value(last_state.load)
                ),
                &WrinkleMap::new(field, 1e-3 * h, "10⁻³ h"),
            )
            .map_err(io_error(&stem))?;
            files.extend(plot.files);
            true
        } else {
            false
        };

        let stats = &result.statistics;
        let failure = result.stop.is_failure().then(|| result.stop.describe());
        let summary = json!({
            "model": spec.name,
            "method": scene.solver.method.as_str(),
            "dofs": problem.free_count(),
            "wavenumber": q,
            "wavelength": 2.0 * std::f64::consts::PI / q,
            "load_kind": scene.load.kind.as_str(),
            "linear_buckling_load": lambda_c,
            "closed_form_critical_load": self.threshold.closed_form_critical_load,
            "detected_bifurcation": result.bifurcation.map(|(load, step)| json!({"load": load, "step": step,
                "relative_difference_to_linear_buckling": (load - lambda_c) / lambda_c})),
            "loss_of_ellipticity": first_loss_of_ellipticity.as_ref().map(|(load, r)| json!({
                "load": load, "location": r.location, "direction_rad": r.direction, "field": r.field, "margin": r.worst_margin,
                "area_fraction": r.violated_fraction})),
            "perturbation_load": force,
            "stop": result.stop.describe(),
            "failed": failure.is_some(),
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
                "assembly": stats.assembly_seconds,
                "factorization": stats.factorization_seconds,
                "series": stats.series_seconds,
                "bifurcation_prediction": stats.bifurcation_seconds,
                "path": stats.total_seconds,
                "total": begin.elapsed().as_secs_f64(),
            },
            "anm_steps": anm_steps.iter().map(|s| json!({
                "step": s.step, "load_start": s.load_range.0, "load_end": s.load_range.1, "step_length": s.step_length,
                "series_step_length": s.series_step_length, "pade_step_length": s.pade_step_length,
                "end_residual": s.end_residual, "correction_iterations": s.correction_iterations,
                "geometric_radius": s.geometric_radius, "predicted_bifurcation": s.predicted_bifurcation,
            })).collect::<Vec<_>>(),
            "vtu": vtu_written.iter().map(|(l, p)| json!({"load": l, "file": p.display().to_string()})).collect::<Vec<_>>(),
            "vtu_errors": vtu_errors,
            "plots": plots_written,
            "path": points,
            "scene": scene.echo_json(),
        });
        let scene_path = dir.join("scene.toml");
        crate::output::write_bytes_atomically(&scene_path, scene.to_toml_string().as_bytes())
            .map_err(io_error(&scene_path))?;
        files.push(scene_path);
        self.directory.record(&files).map_err(io_error(&dir))?;
        // `summary.json` last, with the list of every file written (`files`).
        let summary_path = dir.join("summary.json");
        let mut summary = summary;
        self.directory
            .write_summary(summary.clone())
            .map_err(io_error(&summary_path))?;
        if let Some(object) = summary.as_object_mut() {
            object.insert("files".into(), json!(self.directory.files()));
        }
        files.push(summary_path);
        Ok(RunReport {
            summary,
            files,
            failure,
        })
    }
}
