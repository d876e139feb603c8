//! `wrinkle buckle --out DIR`: the threshold as files a researcher opens beside the numbers —
//! the first buckling mode as VTU (the model's fields on the Q8 mesh, and the physical
//! deflection of the mode on a fine grid), the critical load against the wavenumber of the
//! search, $`\lambda_c(Q)`$, as CSV and plot, and the `buckle --json` object as `buckle.json`.
//!
//! Nothing is recomputed: the mode, the pre-buckling state and the search come from the one
//! threshold analysis (`crate::threshold::find_threshold`); the files only format them.

use crate::error::{Error, io_error, output_directory_error};
use crate::output::{
    FieldData, GridField, PointArray, Profile, ProfilePlot, Quantity, ReferenceLevel, RunDirectory,
    plot_profiles_with_level, write_bytes_atomically, write_fields_vtu, write_json,
    write_surface_vtu,
};
use crate::physics::{Layout, Snapshot};
use crate::scene::Scene;
use crate::setup::{build_problem, configure_model, layout_of, unknown_model};
use crate::threshold::{Threshold, analyse, find_threshold, load_unit, wavenumber_range};
use std::path::{Path, PathBuf};
use wrinkle_models::{ModelVisitor, with_model};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::wavenumber::WavenumberEvaluation;

/// The buckling mode's fields file.
pub const MODE_FILE: &str = "mode.vtu";
/// The mode's physical deflection on a fine grid.
pub const MODE_SURFACE_FILE: &str = "mode_surface.vtu";
/// The wavenumber search, $`\lambda_c(Q)`$.
pub const SEARCH_CSV_FILE: &str = "wavenumber_search.csv";

/// How the caller describes a threshold in `buckle.json` (the `buckle --json` object).
pub type Describe<'a> = &'a dyn Fn(&Scene, &Threshold) -> serde_json::Value;

/// The threshold of `scene` (as `wrinkle buckle`), with its files written into `directory`
/// (the previous run's files removed first), `buckle.json` being `describe` of the threshold;
/// returns the threshold and the files written.
pub fn buckle_with_outputs(
    scene: &Scene,
    quiet: bool,
    directory: &Path,
    describe: Describe,
) -> Result<(Threshold, Vec<PathBuf>), Error> {
    with_model(
        &scene.model.name,
        BuckleOutputs {
            scene,
            quiet,
            directory,
            describe,
        },
    )
    .unwrap_or_else(|| Err(unknown_model(scene)))
}

struct BuckleOutputs<'a> {
    scene: &'a Scene,
    quiet: bool,
    directory: &'a Path,
    describe: Describe<'a>,
}

impl ModelVisitor for BuckleOutputs<'_> {
    type Output = Result<(Threshold, Vec<PathBuf>), Error>;
    fn visit<M: EnergyModel>(self, mut model: M) -> Self::Output {
        let scene = self.scene;
        let q = match scene.model.wavenumber {
            crate::scene::Wavenumber::Fixed(q) => q,
            crate::scene::Wavenumber::Auto => 1.0,
        };
        configure_model(scene, &mut model, q)?;
        let mut problem = build_problem(scene, model)?;
        let mut factor = analyse(&problem)?;
        let threshold = find_threshold(scene, &mut problem, &mut factor, self.quiet)?;
        let layout = layout_of::<M>(scene)?;
        let json = (self.describe)(scene, &threshold);
        // The scan sets the model's wavenumber parameter; the mode and the pre-buckling state
        // written below come from the threshold, not from the problem's parameters.
        let evaluations: Vec<WavenumberEvaluation> = threshold
            .search
            .iter()
            .cloned()
            .chain(scan_around_minimum(&mut problem, &mut factor, &threshold))
            .collect();
        let outputs = BuckleFiles {
            threshold: &threshold,
            evaluations: &evaluations,
            json: &json,
        };
        let files = write_buckle_outputs(scene, &problem, &layout, &outputs, self.directory)?;
        Ok((threshold, files))
    }
}

/// What `buckle --out` writes besides the mode: the evaluations of $`\lambda_c(Q)`$ and the
/// `buckle --json` object.
struct BuckleFiles<'a> {
    threshold: &'a Threshold,
    evaluations: &'a [WavenumberEvaluation],
    json: &'a serde_json::Value,
}

/// Relative half-widths of the scan of $`\lambda_c(Q)`$ about the minimum: from
/// $`0.6\,Q`$ to $`1.6\,Q`$ in [`SCAN_POINTS`] analyses.
const SCAN_RANGE: (f64, f64) = (0.6, 1.6);
/// Linear buckling analyses of the scan.
const SCAN_POINTS: usize = 21;

/// $`\lambda_c`$ at [`SCAN_POINTS`] wavenumbers about the threshold's (envelope models whose
/// $`Q`$ was searched): the curve the minimum sits on, which a search started from the closed
/// form (3 analyses) does not show. Failures leave the curve shorter, never fail `buckle`.
fn scan_around_minimum<M: EnergyModel>(
    problem: &mut Problem<M>,
    factor: &mut wrinkle_runtime::linear::factor::SparseFactorization,
    threshold: &Threshold,
) -> Vec<WavenumberEvaluation> {
    let Some(q) = threshold
        .wavenumber
        .filter(|_| !threshold.search.is_empty())
    else {
        return Vec::new();
    };
    let options = wrinkle_runtime::solve::wavenumber::WavenumberSearchOptions {
        range: (SCAN_RANGE.0 * q, SCAN_RANGE.1 * q),
        scan_points: SCAN_POINTS,
        load_guess: Some(threshold.critical_load()),
        ..Default::default()
    };
    let mut evaluations = Vec::new();
    let mut observer = |e: &WavenumberEvaluation| evaluations.push(e.clone());
    let _ = wrinkle_runtime::solve::wavenumber::minimise_critical_load(
        problem,
        factor,
        &options,
        &mut observer,
    );
    evaluations
}

/// Writes the mode, the search and `buckle.json`, then `summary.json` listing them.
fn write_buckle_outputs<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
    outputs: &BuckleFiles,
    directory: &Path,
) -> Result<Vec<PathBuf>, Error> {
    let (threshold, json) = (outputs.threshold, outputs.json);
    let mut run_directory =
        RunDirectory::open(directory).map_err(output_directory_error(directory))?;
    let dir = run_directory.staging().to_path_buf();
    let mut files = write_mode(scene, problem, layout, threshold, &dir)?;
    if !outputs.evaluations.is_empty() {
        files.extend(write_search(scene, threshold, outputs.evaluations, &dir)?);
    }
    let path = dir.join("buckle.json");
    write_json(&path, json).map_err(io_error(&path))?;
    files.push(path);
    run_directory.record(&files).map_err(io_error(&dir))?;
    run_directory.write_summary(json).map_err(io_error(&dir))?;
    let names = run_directory.files().to_vec();
    let root = run_directory.commit().map_err(io_error(directory))?;
    Ok(names.iter().map(|name| root.join(name)).collect())
}

/// `mode.vtu` (the first mode's fields, scaled to a largest deflection field of 1, with the
/// pre-buckling state at $`\lambda_c`$ as `prebuckling_FIELD` arrays and, for envelope models,
/// the mode's local amplitude) and `mode_surface.vtu` (its physical deflection on a grid of
/// about 12 samples per wavelength, points at $`z = w`$).
fn write_mode<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
    threshold: &Threshold,
    dir: &Path,
) -> Result<Vec<PathBuf>, Error> {
    let Some(mode) = threshold.buckling.modes.first() else {
        return Ok(Vec::new());
    };
    let mesh = problem.assembler.mesh();
    let mut values = problem.dofs().expand_increment(mode, 0.0);
    let nf = layout.field_count;
    let largest = (0..mesh.nodes.len())
        .map(|n| values[n * nf + layout.primary].abs())
        .fold(0.0, f64::max);
    if largest > 0.0 {
        values.iter_mut().for_each(|v| *v /= largest);
    }
    let critical = threshold.critical_load();
    let prebuckling = problem.dofs().expand(
        &threshold
            .buckling
            .state_at(threshold.reference_load, critical),
        critical,
    );
    let fields = M::SPEC.fields;
    let mut extra: Vec<PointArray> = fields
        .iter()
        .enumerate()
        .map(|(f, name)| {
            PointArray::scalar(
                format!("prebuckling_{name}"),
                (0..mesh.nodes.len())
                    .map(|n| prebuckling[n * nf + f])
                    .collect(),
            )
        })
        .collect();
    let snapshot = Snapshot {
        mesh,
        layout,
        values: &values,
        wavenumber: threshold.wavenumber.unwrap_or(0.0),
        direction: threshold.direction_degrees.to_radians(),
    };
    if layout.is_envelope() {
        extra.push(PointArray::scalar(
            "amplitude",
            mesh.nodes
                .iter()
                .map(|p| snapshot.envelope_amplitude([p[0], p[1]]).unwrap_or(0.0))
                .collect(),
        ));
    }
    let field_data = mode_field_data(scene, threshold);
    let mut files = Vec::new();
    let path = dir.join(MODE_FILE);
    write_fields_vtu(&path, mesh, fields, &values, &extra, &field_data).map_err(io_error(&path))?;
    files.push(path);
    let bounds = mesh.bounds();
    let wavelength = threshold.wavelength.unwrap_or(bounds[1] - bounds[0]);
    let samples = |length: f64| (12.0 * length / wavelength).clamp(50.0, 1500.0) as usize + 1;
    let grid = GridField::sample(
        Quantity::new("physical deflection of the mode", "w", ""),
        bounds,
        samples(bounds[1] - bounds[0]),
        samples(bounds[3] - bounds[2]),
        |x, y| snapshot.deflection([x, y]),
    );
    let path = dir.join(MODE_SURFACE_FILE);
    // Scaled so that the mode's largest deflection is a tenth of the shorter side: visible
    // without warping.
    let height = 0.1 * (bounds[1] - bounds[0]).min(bounds[3] - bounds[2]);
    let peak = grid.values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let scale = if peak > 0.0 { height / peak } else { 1.0 };
    write_surface_vtu(&path, &grid, scale, &[], &field_data).map_err(io_error(&path))?;
    files.push(path);
    Ok(files)
}

/// Field data of the mode's files: the critical load and its unit, the model, the wavenumber
/// (envelope models) or the wavelength.
fn mode_field_data(scene: &Scene, threshold: &Threshold) -> FieldData {
    let data = FieldData::load(threshold.critical_load(), load_unit(scene))
        .with_text("model", threshold.model)
        .with_number("critical_load", threshold.critical_load());
    let data = match threshold.wavenumber {
        Some(q) => data.with_number("wavenumber", q),
        None => data,
    };
    match threshold.wavelength {
        Some(wavelength) => data.with_number("wavelength", wavelength),
        None => data,
    }
}

/// The plot of the search draws the evaluations below this multiple of $`\lambda_c`$.
const PLOT_LOAD_WINDOW: f64 = 3.0;

/// `wavenumber_search.csv` (one row per evaluation, in the order done: the search's, then the
/// scan's) and `wavenumber_search.png/.svg` ($`\lambda_c`$ against $`Q`$, accepted
/// evaluations).
fn write_search(
    scene: &Scene,
    threshold: &Threshold,
    evaluations: &[WavenumberEvaluation],
    dir: &Path,
) -> Result<Vec<PathBuf>, Error> {
    let mut csv = String::from("wavenumber,critical_load,phase,mesh,rejected\n");
    let searched = threshold.search.len();
    for (index, evaluation) in evaluations.iter().enumerate() {
        csv.push_str(&search_row(evaluation, index < searched));
    }
    let path = dir.join(SEARCH_CSV_FILE);
    write_bytes_atomically(&path, csv.as_bytes()).map_err(io_error(&path))?;
    let mut files = vec![path];
    // One curve per mesh: the half mesh's first level of the search and the scene's own mesh
    // give different λ_c(Q) (the strip: 13.44 against 14.38 mm at the minimum), and one line
    // through both would zigzag between them.
    let curve = |coarse: bool| {
        let mut points: Vec<(f64, f64)> = evaluations
            .iter()
            .filter(|e| e.coarse == coarse)
            .filter_map(|e| e.critical_load.map(|load| (e.parameter, load)))
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        points
    };
    let (mut points, mut coarse_points) = (curve(false), curve(true));
    if points.len() + coarse_points.len() < 2 {
        return Ok(files);
    }
    // The search's log-scan reaches loads hundreds of times the threshold (the strip: 900 mm
    // against 14.4 mm), which would flatten the minimum the plot is for: the plot keeps the
    // evaluations below PLOT_LOAD_WINDOW × λ_c when enough remain; the CSV keeps them all.
    let window = PLOT_LOAD_WINDOW * threshold.critical_load().abs();
    let near = |points: &[(f64, f64)]| -> Vec<(f64, f64)> {
        points
            .iter()
            .copied()
            .filter(|&(_, load)| load.abs() <= window)
            .collect()
    };
    let (near_fine, near_coarse) = (near(&points), near(&coarse_points));
    let all = points.len() + coarse_points.len();
    let kept = near_fine.len() + near_coarse.len();
    let left_out = if kept >= 5 && kept < all {
        points = near_fine;
        coarse_points = near_coarse;
        format!("; {} above {PLOT_LOAD_WINDOW} λ_c: CSV only", all - kept)
    } else {
        String::new()
    };
    let mut profiles = Vec::new();
    if !points.is_empty() {
        profiles.push(Profile {
            label: format!(
                "scene's mesh ({}×{}), {} evaluations",
                scene.mesh.elements_x,
                scene.mesh.elements_y,
                points.len()
            ),
            points,
        });
    }
    if !coarse_points.is_empty() {
        profiles.push(Profile {
            label: format!(
                "half mesh ({}×{}, first level), {} evaluations",
                scene.mesh.elements_x / 2,
                scene.mesh.elements_y / 2,
                coarse_points.len()
            ),
            points: coarse_points,
        });
    }
    let load = crate::results::load_quantity(scene);
    let (low, high) = wavenumber_range(scene);
    let chosen = threshold.wavenumber.map_or(String::new(), |q| {
        format!(
            "; minimum Q = {q:.5} /mm, λ_c = {}",
            load.format_value(threshold.critical_load())
        )
    });
    let plot = ProfilePlot {
        abscissa: Quantity::new("wavenumber", "Q", "1/mm"),
        ordinate: Quantity::new("critical load", "λ_c", &load.unit),
        location: format!(
            "Q in [{low:.3}, {high:.3}] /mm, then {}–{} Q{chosen}{left_out}",
            SCAN_RANGE.0, SCAN_RANGE.1
        ),
        profiles,
    };
    let stem = dir.join("wavenumber_search");
    let minimum = ReferenceLevel {
        value: threshold.critical_load(),
        label: format!("λ_c = {}", load.format_value(threshold.critical_load())),
    };
    let output = plot_profiles_with_level(
        &stem,
        &format!("{}: critical load against the wavenumber", threshold.model),
        &plot,
        Some(&minimum),
    )
    .map_err(io_error(&stem))?;
    files.extend(output.files);
    Ok(files)
}

/// One CSV row of an evaluation: of the search (`searched`) or of the scan.
fn search_row(evaluation: &WavenumberEvaluation, searched: bool) -> String {
    let rejected = evaluation
        .rejected
        .as_deref()
        .unwrap_or("")
        .replace(['"', ','], ";");
    format!(
        "{},{},{},{},{}\n",
        evaluation.parameter,
        evaluation
            .critical_load
            .map_or(String::new(), |l| l.to_string()),
        match (searched, evaluation.scan) {
            (true, true) => "search scan",
            (true, false) => "search refinement",
            (false, _) => "curve scan",
        },
        if evaluation.coarse { "half" } else { "scene" },
        rejected
    )
}
