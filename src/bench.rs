//! `wrinkle bench`: run time against error.
//!
//! For each model the scene is run at a **reference** point — the finest mesh of the plan, the
//! highest ANM order $`N`$, the tightest series tolerance $`\varepsilon`$ and the default
//! method (ANM with Padé approximants) — and then along three one-factor sweeps around it: the
//! mesh (at the reference's $`N`$ and $`\varepsilon`$) for **every path method** ([`Method`]: ANM
//! with Padé, classical ANM, Newton–Riks), the order (at the reference mesh and $`\varepsilon`$)
//! and the series tolerance (at the reference mesh and $`N`$) for both ANM variants. Every
//! point is a whole [`crate::run::run`] (threshold search, imperfection, path to the amplitude
//! target [`TARGET_AMPLITUDE`]); its costs are read from the run's result
//! ([`RunSummary::timings`], `statistics`, `memory`), and three results are compared with the
//! reference of the **same** model:
//!
//! * the critical load $`\lambda_c`$ of linear buckling;
//! * the load $`\lambda_{a/h=1}`$ at which the maximum physical amplitude first reaches one
//!   thickness ([`load_at_amplitude`]);
//! * the maximum physical amplitude $`a/h`$ at $`\lambda/\lambda_c = 1.1`$ (the point's own
//!   $`\lambda_c`$) ([`amplitude_at_load`]);
//!
//! both interpolated by a cubic through the path points around the crossing
//! ([`value_at_crossing`](crate::study::value_at_crossing)).
//!
//! Errors are relative, $`\lvert x - x_\text{ref}\rvert / \lvert x_\text{ref}\rvert`$
//! ([`relative_error`]). Where the scene is the clamped biaxial rectangle, $`\lambda_c`$ is also
//! compared with the exact minimum of eq. (42) ([`closed_form_threshold`]), an independent truth.
//! The order and tolerance sweeps reuse the reference's wavenumber (`model.wavenumber` fixed to
//! it) when the scene asks for `auto`: their threshold is then one buckling analysis instead of a
//! search, and their $`\lambda_c`$ equals the reference's.
//!
//! Outputs (`docs/benchmarks.md`): `bench.csv`, `bench.json`, `bench.png|svg` (error against
//! total time, log–log, one series per sweep), and each point's run directory under
//! `runs/MODEL/`.

mod plan;
mod plot;
mod rows;

pub use plan::{Method, Plan, Settings, Sweep};
pub use rows::{Bench, BenchRow, CostSplit, Errors, Measurement, SettingsRecord};

use crate::error::{Error, io_error};
use crate::output::{write_bytes_atomically, write_json};
use crate::results::{RunOutcome, RunSummary};
use crate::run::run;
use crate::scene::{PathMethod, Scene, Wavenumber};
use crate::study::{amplitude_at_load, load_at_amplitude, number_cell, relative_error};
use crate::threshold::{closed_form_threshold, load_unit};
use serde_json::json;
use std::path::Path;
use std::time::Instant;

/// Model benchmarked when `--models` is not given: the registry's reference model.
pub const DEFAULT_MODEL: &str = wrinkle_models::REFERENCE_MODEL;
/// Physical amplitude $`a/h`$ at which the load is compared.
pub const AMPLITUDE_LEVEL: f64 = 1.0;
/// Load ratio $`\lambda/\lambda_c`$ at which the amplitude is compared.
pub const LOAD_RATIO: f64 = 1.1;
/// Amplitude target $`a/h`$ of every point (`solver.max_amplitude_over_h`): past
/// [`AMPLITUDE_LEVEL`] and past $`\lambda = 1.1\lambda_c`$ on the paper's example 1.
pub const TARGET_AMPLITUDE: f64 = 2.0;

/// Step budget of a Riks point at least (`solver.max_steps` if larger). Since the arc length is
/// dimensionless (at most 0.3 of the linear response to λ_c) Riks takes about 50 steps to
/// a/h = 4 on every mesh of example 1; before, at most 1 % of λ_c in (mm, λ/λ_c), it took
/// 130–270 steps to a/h = 2 on 8×4 … 64×32. The budget stays as a margin.
pub const RIKS_MAX_STEPS: usize = 3000;

/// The columns of `bench.csv`, in order.
pub const CSV_COLUMNS: [&str; 35] = [
    "model",
    "sweep",
    "method",
    "outcome",
    "nx",
    "ny",
    "dofs",
    "order",
    "series_tolerance",
    "wavenumber",
    "wavenumber_fixed",
    "steps",
    "factorizations",
    "prediction_factorizations",
    "time_threshold",
    "time_path",
    "time_total",
    "time_assembly",
    "time_factorization",
    "time_series",
    "time_series_solves",
    "time_residual_checks",
    "time_bifurcation",
    "time_recording",
    "time_step_floor",
    "peak_memory_mb",
    "tape_mb",
    "factor_nonzeros",
    "critical_load",
    "error_critical_load",
    "error_critical_load_closed_form",
    "load_at_amplitude_1",
    "error_load_at_amplitude_1",
    "amplitude_at_1_1",
    "error_amplitude_at_1_1",
];

/// The three results of a run.
pub fn measure(summary: &RunSummary) -> Measurement {
    let points = &summary.path;
    let critical_load = Some(summary.linear_buckling_load).filter(|l| l.is_finite());
    Measurement {
        critical_load,
        load_at_amplitude_1: load_at_amplitude(points, AMPLITUDE_LEVEL),
        amplitude_at_1_1: critical_load.and_then(|l| amplitude_at_load(points, LOAD_RATIO * l)),
    }
}

/// Runs the benchmark of `scene` for `models` (default [`DEFAULT_MODEL`]) into `directory`
/// and writes `bench.csv`, `bench.json` and `bench.png|svg`. Progress goes to standard error.
pub fn bench(
    scene: &Scene,
    models: &[String],
    quick: bool,
    directory: &Path,
) -> Result<Bench, Error> {
    let models: Vec<String> = if models.is_empty() {
        vec![DEFAULT_MODEL.to_string()]
    } else {
        models.to_vec()
    };
    crate::study::check_model_list(&models)?;
    let _lock = crate::output::DirectoryLock::inside(directory)
        .map_err(crate::error::output_directory_error(directory))?;
    let closed_form = closed_form_threshold(scene).map(|(load, _)| load);
    let total: usize = models
        .iter()
        .map(|m| 1 + Plan::for_model(m, quick).points().len())
        .sum();
    let mut progress = Counter { done: 0, total };
    let mut rows = Vec::new();
    for model in &models {
        rows.extend(bench_model(
            scene,
            model,
            &Plan::for_model(model, quick),
            directory,
            &mut progress,
        )?);
    }
    for row in &mut rows {
        row.errors.error_critical_load_closed_form =
            relative_error(row.measured.critical_load, closed_form);
    }
    let bench = Bench {
        rows,
        closed_form_critical_load: closed_form,
        load_unit: load_unit(scene),
        quick,
    };
    write_bench(scene, &bench, directory)?;
    Ok(bench)
}

/// Points done and to do, for the progress lines.
struct Counter {
    done: usize,
    total: usize,
}

/// The reference, then every sweep point of one model, with errors against the reference.
fn bench_model(
    scene: &Scene,
    model: &str,
    plan: &Plan,
    directory: &Path,
    progress: &mut Counter,
) -> Result<Vec<BenchRow>, Error> {
    let reference = run_point(
        scene,
        model,
        (Sweep::Reference, plan.reference()),
        None,
        directory,
        progress,
    )?;
    let fixed = match scene.model.wavenumber {
        Wavenumber::Auto => reference.wavenumber,
        Wavenumber::Fixed(_) => None,
    };
    let mut rows = vec![reference];
    for point in plan.points() {
        let wavenumber = fixed.filter(|_| point.0 != Sweep::Mesh);
        rows.push(run_point(
            scene, model, point, wavenumber, directory, progress,
        )?);
    }
    let truth = rows[0].measured;
    for row in &mut rows {
        row.errors = Errors {
            error_critical_load: relative_error(row.measured.critical_load, truth.critical_load),
            error_critical_load_closed_form: None,
            error_load_at_amplitude_1: relative_error(
                row.measured.load_at_amplitude_1,
                truth.load_at_amplitude_1,
            ),
            error_amplitude_at_1_1: relative_error(
                row.measured.amplitude_at_1_1,
                truth.amplitude_at_1_1,
            ),
        };
    }
    Ok(rows)
}

/// The scene of one point: its settings, the amplitude target, no plots, no VTU requests.
fn point_scene(
    scene: &Scene,
    model: &str,
    settings: Settings,
    wavenumber: Option<f64>,
) -> Result<Scene, Error> {
    let mut point = scene.clone();
    point.model.name = model.to_string();
    if let Some(q) = wavenumber {
        point.model.wavenumber = Wavenumber::Fixed(q);
    }
    point.mesh.elements_x = settings.nx;
    point.mesh.elements_y = settings.ny;
    point.solver.order = settings.order;
    point.solver.series_tolerance = settings.series_tolerance;
    point.solver.pade = settings.method == Method::AnmPade;
    point.solver.method = match settings.method {
        Method::Riks => PathMethod::Riks,
        Method::Anm | Method::AnmPade => PathMethod::Anm,
    };
    if settings.method == Method::Riks {
        point.solver.max_steps = point.solver.max_steps.max(RIKS_MAX_STEPS);
    }
    point.solver.max_amplitude_over_thickness = TARGET_AMPLITUDE;
    point.output.plots = false;
    point.output.vtu_loads.clear();
    point.validate()?;
    Ok(point)
}

/// Runs one point into `directory/runs/MODEL/NAME/` and makes its row (errors not yet set).
fn run_point(
    scene: &Scene,
    model: &str,
    (sweep, settings): (Sweep, Settings),
    wavenumber: Option<f64>,
    directory: &Path,
    progress: &mut Counter,
) -> Result<BenchRow, Error> {
    let point = point_scene(scene, model, settings, wavenumber)?;
    let name = format!(
        "{}-{}-{}x{}-order{}-tol{:.0e}",
        sweep.as_str(),
        settings.method.as_str(),
        settings.nx,
        settings.ny,
        settings.order,
        settings.series_tolerance
    );
    progress.done += 1;
    let label = format!("bench [{}/{}] {model}", progress.done, progress.total);
    crate::output::message_line(&format!(
        "{label} {} {}: {}×{}{}{}",
        sweep.as_str(),
        settings.method.label(),
        settings.nx,
        settings.ny,
        settings
            .method
            .series_settings(settings.order, settings.series_tolerance),
        wavenumber.map_or(String::new(), |q| format!(", Q = {q:.6} fixed")),
    ));
    let begin = Instant::now();
    let mut row = BenchRow {
        model: model.to_string(),
        sweep,
        outcome: "error".into(),
        reason: None,
        settings: SettingsRecord {
            nx: settings.nx,
            ny: settings.ny,
            order: settings.order,
            series_tolerance: settings.series_tolerance,
            method: settings.method,
        },
        dofs: None,
        wavenumber,
        wavenumber_fixed: wavenumber.is_some(),
        steps: None,
        factorizations: None,
        prediction_factorizations: None,
        time_threshold: None,
        time_path: None,
        time_total: None,
        cost: CostSplit::default(),
        measured: Measurement::default(),
        errors: Errors::default(),
    };
    match run(&point, &directory.join("runs").join(model).join(name), true) {
        Ok(report) => fill_row(&mut row, &report.summary),
        Err(error @ Error::Scene { .. }) => return Err(error),
        Err(error) => row.reason = Some(error.to_string()),
    }
    crate::output::message_line(&format!(
        "{label}: {} in {:.1} s",
        match &row.reason {
            Some(reason) => format!("{}: {reason}", row.outcome),
            None => row.outcome.clone(),
        },
        begin.elapsed().as_secs_f64()
    ));
    Ok(row)
}

/// Cost and results of a run that produced a summary.
fn fill_row(row: &mut BenchRow, summary: &RunSummary) {
    let finite = |value: f64| Some(value).filter(|v| v.is_finite());
    let timings = &summary.timings;
    let memory = &summary.memory;
    row.dofs = Some(summary.dofs);
    row.wavenumber = summary.wavenumber.filter(|q| q.is_finite());
    row.steps = Some(summary.steps);
    row.factorizations = Some(summary.statistics.factorizations);
    row.prediction_factorizations = Some(summary.statistics.prediction_factorizations);
    row.time_threshold = finite(timings.threshold);
    row.time_path = finite(timings.path);
    row.time_total = finite(timings.total);
    row.cost = CostSplit {
        time_assembly: finite(timings.assembly),
        time_factorization: finite(timings.factorization),
        time_series: finite(timings.series),
        time_series_solves: finite(timings.series_solves),
        time_residual_checks: finite(timings.residual_checks),
        time_bifurcation: finite(timings.bifurcation_prediction),
        time_recording: finite(timings.recording),
        time_step_floor: step_floor(summary, row.settings.order).filter(|t| t.is_finite()),
        peak_memory_mb: memory.peak_resident_bytes.map(|b| b as f64 / 1e6),
        tape_mb: memory.taylor_tape_bytes.map(|b| b as f64 / 1e6),
        factor_nonzeros: memory.factor_nonzeros,
    };
    let (name, reason, usable) = match &summary.outcome {
        RunOutcome::Reached => ("reached", None, true),
        RunOutcome::Invalid(r) => ("invalid", Some(r.clone()), true),
        RunOutcome::Incomplete(r) => ("incomplete", Some(r.clone()), false),
        RunOutcome::Failed(r) | RunOutcome::Interrupted(r) => ("failed", Some(r.clone()), false),
    };
    row.outcome = name.into();
    row.reason = reason;
    if usable {
        row.measured = measure(summary);
    }
}

fn count_cell(value: Option<usize>) -> String {
    value.map(|v| v.to_string()).unwrap_or_default()
}

/// `bench.csv`: a header of [`CSV_COLUMNS`] and one line per row.
pub fn bench_csv(bench: &Bench) -> String {
    let mut csv = CSV_COLUMNS.join(",");
    csv.push('\n');
    for row in &bench.rows {
        let (m, e) = (&row.measured, &row.errors);
        let line = [
            row.model.clone(),
            row.sweep.as_str().to_string(),
            row.settings.method.as_str().to_string(),
            row.outcome.clone(),
            row.settings.nx.to_string(),
            row.settings.ny.to_string(),
            count_cell(row.dofs),
            row.settings.order.to_string(),
            format!("{:e}", row.settings.series_tolerance),
            number_cell(row.wavenumber),
            row.wavenumber_fixed.to_string(),
            count_cell(row.steps),
            count_cell(row.factorizations),
            count_cell(row.prediction_factorizations),
            number_cell(row.time_threshold),
            number_cell(row.time_path),
            number_cell(row.time_total),
            number_cell(row.cost.time_assembly),
            number_cell(row.cost.time_factorization),
            number_cell(row.cost.time_series),
            number_cell(row.cost.time_series_solves),
            number_cell(row.cost.time_residual_checks),
            number_cell(row.cost.time_bifurcation),
            number_cell(row.cost.time_recording),
            number_cell(row.cost.time_step_floor),
            number_cell(row.cost.peak_memory_mb),
            number_cell(row.cost.tape_mb),
            count_cell(row.cost.factor_nonzeros),
            number_cell(m.critical_load),
            number_cell(e.error_critical_load),
            number_cell(e.error_critical_load_closed_form),
            number_cell(m.load_at_amplitude_1),
            number_cell(e.error_load_at_amplitude_1),
            number_cell(m.amplitude_at_1_1),
            number_cell(e.error_amplitude_at_1_1),
        ];
        csv.push_str(&line.join(","));
        csv.push('\n');
    }
    csv
}

/// `bench.csv`, `bench.json` and `bench.png|svg` into `directory`.
fn write_bench(scene: &Scene, bench: &Bench, directory: &Path) -> Result<(), Error> {
    std::fs::create_dir_all(directory).map_err(io_error(directory))?;
    let path = directory.join("bench.csv");
    write_bytes_atomically(&path, bench_csv(bench).as_bytes()).map_err(io_error(&path))?;
    let path = directory.join("bench.md");
    write_bytes_atomically(&path, bench_markdown(bench).as_bytes()).map_err(io_error(&path))?;
    let references: Vec<_> = bench
        .rows
        .iter()
        .filter(|r| r.sweep == Sweep::Reference)
        .map(|r| {
            json!({
                "model": r.model, "method": r.settings.method, "nx": r.settings.nx, "ny": r.settings.ny,
                "order": r.settings.order, "series_tolerance": r.settings.series_tolerance,
                "wavenumber": r.wavenumber, "outcome": r.outcome,
                "critical_load": r.measured.critical_load,
                "load_at_amplitude_1": r.measured.load_at_amplitude_1,
                "amplitude_at_1_1": r.measured.amplitude_at_1_1,
            })
        })
        .collect();
    let value = json!({
        "scene": scene.echo_json(),
        "load_unit": bench.load_unit,
        "quick": bench.quick,
        "amplitude_level": AMPLITUDE_LEVEL,
        "load_ratio": LOAD_RATIO,
        "target_amplitude_over_h": TARGET_AMPLITUDE,
        "closed_form_critical_load": bench.closed_form_critical_load,
        "wavenumber_fixed_in": ["order", "tolerance"],
        "references": references,
        "columns": CSV_COLUMNS.as_slice(),
        "rows": bench.rows,
    });
    let path = directory.join("bench.json");
    write_json(&path, &value).map_err(io_error(&path))?;
    let stem = directory.join("bench");
    plot::plot_bench(&stem, bench).map_err(io_error(&stem))?;
    Ok(())
}

/// A cell of the order or the series tolerance in `bench.md`: `–` for Riks, which has neither.
fn series_cell(row: &BenchRow, text: String) -> String {
    if row.settings.method.uses_series() {
        text
    } else {
        "–".into()
    }
}

/// Milliseconds per accepted step of a path total, `–` when unknown.
fn per_step(total: Option<f64>, steps: Option<usize>) -> String {
    match (total, steps) {
        (Some(t), Some(n)) if n > 0 => format!("{:.1}", 1e3 * t / n as f64),
        _ => "–".into(),
    }
}

/// The factorisations whose time is in `timings.factorization`: all but the bifurcation
/// predictions' (timed in `timings.bifurcation_prediction`; a prediction on a thread of its own
/// takes no time of the path's).
fn timed_factorizations(factorizations: usize, predictions: Option<usize>) -> usize {
    factorizations.saturating_sub(predictions.unwrap_or(0))
}

/// One step's time over one factorisation's:
/// $`(t_\text{path}/n_\text{steps}) / (t_\text{fact}/n_\text{fact})`$ (the ANM's promise is a
/// step that costs little more than its factorisation).
pub fn step_over_factorization(row: &BenchRow) -> Option<f64> {
    let (path, steps) = (row.time_path?, row.steps?);
    let factorization = row.cost.time_factorization?;
    let count = timed_factorizations(row.factorizations?, row.prediction_factorizations);
    (steps > 0 && count > 0 && factorization > 0.0)
        .then(|| (path / steps as f64) / (factorization / count as f64))
        .filter(|r| r.is_finite())
}

/// A step's floor (issue 30), seconds: one factorisation and the $`N - 1`$ series solves with
/// it, $`t_\text{fact}/n_\text{fact} + (N-1)\,t_\text{solves}/n_\text{solves}`$ with the
/// run's own mean factorisation and solve ($`n_\text{solves}`$ = the series' right-hand sides,
/// `series_assemblies`) at the ANM order `order`; `None` without factorisations or series
/// (Riks).
fn step_floor(summary: &RunSummary, order: usize) -> Option<f64> {
    let (statistics, timings) = (&summary.statistics, &summary.timings);
    let factorizations = timed_factorizations(
        statistics.factorizations,
        Some(statistics.prediction_factorizations),
    );
    let solves = statistics.series_assemblies;
    (factorizations > 0 && solves > 0 && order > 1).then(|| {
        timings.factorization / factorizations as f64
            + (order - 1) as f64 * timings.series_solves / solves as f64
    })
}

/// One step's time over its floor, $`(t_\text{path}/n_\text{steps}) / t_\text{floor}`$
/// ([`CostSplit::time_step_floor`]); issue 30 asks for at most 1.5 at 50k unknowns and more.
pub fn step_over_floor(row: &BenchRow) -> Option<f64> {
    let (path, steps, floor) = (row.time_path?, row.steps?, row.cost.time_step_floor?);
    (steps > 0 && floor > 0.0)
        .then(|| path / steps as f64 / floor)
        .filter(|r| r.is_finite())
}

/// The column headers of `bench.md`.
const MARKDOWN_COLUMNS: [&str; 27] = [
    "model",
    "sweep",
    "method",
    "mesh",
    "dofs",
    "N",
    "ε",
    "steps",
    "fact.",
    "t_total (s)",
    "t_path (s)",
    "assembly (ms/step)",
    "factorisation (ms/step)",
    "series (ms/step)",
    "series solves (ms/step)",
    "residual checks (ms/step)",
    "bifurcation (ms/step)",
    "recording (ms/step)",
    "step / factorisation",
    "floor (ms/step)",
    "step / floor",
    "peak memory (MB)",
    "tape (MB)",
    "err λ_c",
    "err λ(a/h=1)",
    "err a/h(1.1 λ_c)",
    "outcome",
];

/// A reference row's settings and values, for the terminal and `bench.md`; `missing` stands
/// for a value the run did not give.
fn reference_line(row: &BenchRow, missing: &str) -> String {
    let m = &row.measured;
    let value = |v: Option<f64>| v.map_or(missing.to_string(), |v| format!("{v:.8e}"));
    format!(
        "{}: {}, {}×{}{}: λ_c = {}, λ(a/h=1) = {}, a/h(1.1 λ_c) = {}",
        row.model,
        row.settings.method.label(),
        row.settings.nx,
        row.settings.ny,
        row.settings
            .method
            .series_settings(row.settings.order, row.settings.series_tolerance),
        value(m.critical_load),
        value(m.load_at_amplitude_1),
        value(m.amplitude_at_1_1),
    )
}

/// `bench.md`: the rows as a markdown table with the time of one step split by part
/// (milliseconds per accepted step) and the step-to-factorisation ratio, then the references.
pub fn bench_markdown(bench: &Bench) -> String {
    let mut text = format!(
        "| {} |\n|{}\n",
        MARKDOWN_COLUMNS.join(" | "),
        "---|".repeat(MARKDOWN_COLUMNS.len())
    );
    let time = |t: Option<f64>| t.map_or("–".to_string(), |t| format!("{t:.2}"));
    let error = |e: Option<f64>| e.map_or("–".to_string(), |e| format!("{e:.1e}"));
    let megabytes = |m: Option<f64>| m.map_or("–".to_string(), |m| format!("{m:.1}"));
    for row in &bench.rows {
        let c = &row.cost;
        let steps = row.steps;
        let cells = [
            row.model.clone(),
            row.sweep.as_str().to_string(),
            row.settings.method.label().to_string(),
            format!("{}×{}", row.settings.nx, row.settings.ny),
            row.dofs.map_or("–".into(), |d| d.to_string()),
            series_cell(row, row.settings.order.to_string()),
            series_cell(row, format!("{:.0e}", row.settings.series_tolerance)),
            steps.map_or("–".into(), |s| s.to_string()),
            row.factorizations.map_or("–".into(), |s| s.to_string()),
            time(row.time_total),
            time(row.time_path),
            per_step(c.time_assembly, steps),
            per_step(c.time_factorization, steps),
            per_step(c.time_series, steps),
            per_step(c.time_series_solves, steps),
            per_step(c.time_residual_checks, steps),
            per_step(c.time_bifurcation, steps),
            per_step(c.time_recording, steps),
            step_over_factorization(row).map_or("–".into(), |r| format!("{r:.1}")),
            c.time_step_floor
                .map_or("–".into(), |t| format!("{:.1}", 1e3 * t)),
            step_over_floor(row).map_or("–".into(), |r| format!("{r:.2}")),
            megabytes(c.peak_memory_mb),
            megabytes(c.tape_mb),
            error(row.errors.error_critical_load),
            error(row.errors.error_load_at_amplitude_1),
            error(row.errors.error_amplitude_at_1_1),
            row.outcome.clone(),
        ];
        text.push_str(&format!("| {} |\n", cells.join(" | ")));
    }
    text.push('\n');
    for row in bench.rows.iter().filter(|r| r.sweep == Sweep::Reference) {
        text.push_str(&format!(
            "Reference {} ({}).\n",
            reference_line(row, "–"),
            bench.load_unit
        ));
    }
    text
}

/// The benchmark as a compact text table for the terminal.
pub fn bench_table(bench: &Bench) -> String {
    let mut text = format!(
        "{:<18} {:<9} {:<8} {:>7} {:>6} {:>3} {:>5} {:>5} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9}  outcome\n",
        "model",
        "sweep",
        "method",
        "mesh",
        "dofs",
        "N",
        "ε",
        "steps",
        "t_thr/s",
        "t_path/s",
        "t_tot/s",
        "err λ_c",
        "err λ(1)",
        "err a(1.1)"
    );
    let time = |t: Option<f64>| t.map_or("—".to_string(), |t| format!("{t:.2}"));
    let error = |e: Option<f64>| e.map_or("—".to_string(), |e| format!("{e:.2e}"));
    for row in &bench.rows {
        text.push_str(&format!(
            "{:<18} {:<9} {:<8} {:>7} {:>6} {:>3} {:>5.0e} {:>5} {:>8} {:>8} {:>8} {:>9} {:>9} {:>9}  {}\n",
            row.model,
            row.sweep.as_str(),
            row.settings.method.label(),
            format!("{}×{}", row.settings.nx, row.settings.ny),
            row.dofs.map_or("—".into(), |d| d.to_string()),
            row.settings.order,
            row.settings.series_tolerance,
            row.steps.map_or("—".into(), |s| s.to_string()),
            time(row.time_threshold),
            time(row.time_path),
            time(row.time_total),
            error(row.errors.error_critical_load),
            error(row.errors.error_load_at_amplitude_1),
            error(row.errors.error_amplitude_at_1_1),
            match &row.reason {
                Some(reason) => format!("{}: {reason}", row.outcome),
                None => row.outcome.clone(),
            }
        ));
    }
    for row in bench.rows.iter().filter(|r| r.sweep == Sweep::Reference) {
        text.push_str(&format!("reference {}\n", reference_line(row, "—")));
        if let Some(l) = bench.closed_form_critical_load {
            text.push_str(&format!(
                "closed form (42): λ_c = {l:.8e} {}, reference off by {}\n",
                bench.load_unit,
                error(row.errors.error_critical_load_closed_form)
            ));
        }
    }
    text.push_str("order and tolerance sweeps: wavenumber fixed to the reference's\n");
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_reference_is_the_finest_and_tightest_and_is_not_repeated() {
        let plan = Plan::for_model(DEFAULT_MODEL, false);
        let reference = plan.reference();
        assert_eq!((reference.nx, reference.ny), (64, 32));
        assert_eq!(reference.order, 30);
        assert_eq!(reference.series_tolerance, 1e-9);
        assert_eq!(reference.method, Method::AnmPade);
        let points = plan.points();
        // Meshes × 3 methods, orders and tolerances × 2 ANM variants, less the reference.
        assert_eq!(points.len(), (4 * 3 - 1) + (5 * 2 - 1) + (6 * 2 - 1));
        assert!(points.iter().all(|(_, s)| *s != reference));
        for method in Method::ALL {
            let meshes = points
                .iter()
                .filter(|(sweep, s)| *sweep == Sweep::Mesh && s.method == method)
                .count();
            assert_eq!(meshes, if method == Method::AnmPade { 3 } else { 4 });
        }
        assert!(
            points
                .iter()
                .all(|(sweep, s)| s.method.is_anm() || *sweep == Sweep::Mesh)
        );
    }
}
