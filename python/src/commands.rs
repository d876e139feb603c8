//! The functions `wrinkle._native` exports. Scenes come as recipes (JSON of
//! [`SceneRecipe`]); results go back as JSON text. Every solve runs through [`interruptible`].

use crate::errors::{bad_argument, to_python};
use crate::{convert, vtu};
use pyo3::prelude::*;
use serde_json::json;
use std::path::{Path, PathBuf};
use std::time::Duration;
use wrinkle::sweep::{PlannedPoint, PointResult, SceneRecipe, SweepCommand, SweepPlan};

/// Adds the functions to the module.
pub fn register(module: &Bound<'_, PyModule>) -> PyResult<()> {
    module.add_function(wrap_pyfunction!(scene_text_of_dict, module)?)?;
    module.add_function(wrap_pyfunction!(value_text, module)?)?;
    module.add_function(wrap_pyfunction!(effective_scene, module)?)?;
    module.add_function(wrap_pyfunction!(content_hash, module)?)?;
    module.add_function(wrap_pyfunction!(models, module)?)?;
    module.add_function(wrap_pyfunction!(buckle, module)?)?;
    module.add_function(wrap_pyfunction!(run, module)?)?;
    module.add_function(wrap_pyfunction!(compare, module)?)?;
    module.add_function(wrap_pyfunction!(default_compare_models, module)?)?;
    module.add_function(wrap_pyfunction!(set_threads, module)?)?;
    module.add_function(wrap_pyfunction!(analytic, module)?)?;
    module.add_function(wrap_pyfunction!(read_vtu, module)?)?;
    module.add_function(wrap_pyfunction!(sweep_plan, module)?)?;
    module.add_function(wrap_pyfunction!(sweep_run_point, module)?)?;
    module.add_function(wrap_pyfunction!(sweep_table, module)?)?;
    Ok(())
}

/// Runs `work` on a new thread with the GIL released, checking Python's signals every 20 ms on
/// this one: a `KeyboardInterrupt` (Ctrl-C) asks the path to stop after its current point
/// ([`wrinkle::interrupt::request`]) and is returned beside the result, to be raised once the
/// outputs are written. Off the main thread (a Dask worker's) there are no signals to check.
fn interruptible<T: Send>(
    py: Python<'_>,
    work: impl FnOnce() -> T + Send,
) -> PyResult<(T, Option<PyErr>)> {
    wrinkle::interrupt::clear();
    std::thread::scope(|scope| {
        let handle = scope.spawn(work);
        let mut interrupt = None;
        while !handle.is_finished() {
            py.detach(|| std::thread::sleep(Duration::from_millis(20)));
            if interrupt.is_none()
                && let Err(error) = py.check_signals()
            {
                wrinkle::interrupt::request();
                interrupt = Some(error);
            }
        }
        let value = handle
            .join()
            .map_err(|_| pyo3::exceptions::PyRuntimeError::new_err("wrinkle: a run panicked"))?;
        Ok((value, interrupt))
    })
}

/// The recipe of JSON text.
fn recipe_of(json: &str) -> PyResult<SceneRecipe> {
    serde_json::from_str(json).map_err(|e| bad_argument(format!("scene recipe: {e}")))
}

/// The scene of a recipe, or the `SceneError` naming the key.
fn scene_of(py: Python<'_>, json: &str) -> PyResult<wrinkle::Scene> {
    recipe_of(json)?.build().map_err(|e| to_python(py, e))
}

/// JSON text of a serialisable value.
fn to_json(value: &impl serde::Serialize) -> PyResult<String> {
    serde_json::to_string(value).map_err(|e| bad_argument(e.to_string()))
}

/// TOML text of a scene given as a dict (as JSON): dotted keys nested.
#[pyfunction]
fn scene_text_of_dict(json: &str) -> PyResult<String> {
    convert::scene_text(json).map_err(bad_argument)
}

/// TOML text of one value (as JSON), for `KEY=VALUE`.
#[pyfunction]
fn value_text(json: &str, key: &str) -> PyResult<String> {
    convert::value_text(json, key).map_err(bad_argument)
}

/// The effective scene of a recipe as TOML (validated), and its JSON echo.
#[pyfunction]
fn effective_scene(py: Python<'_>, recipe: &str) -> PyResult<(String, String)> {
    let scene = scene_of(py, recipe)?;
    Ok((scene.to_toml_string(), scene.echo_json().to_string()))
}

/// The content hash of a recipe's effective scene.
#[pyfunction]
fn content_hash(py: Python<'_>, recipe: &str) -> PyResult<String> {
    Ok(wrinkle::sweep::content_hash(&scene_of(py, recipe)?))
}

/// The model registry as JSON: `[[name, description, fields, parameters], ...]`.
#[pyfunction]
fn models() -> PyResult<String> {
    to_json(&wrinkle::commands::models())
}

/// `wrinkle buckle` (with `--out` when `out` is given): the threshold's keys and the scene.
#[pyfunction]
#[pyo3(signature = (recipe, out=None))]
fn buckle(py: Python<'_>, recipe: &str, out: Option<PathBuf>) -> PyResult<String> {
    let scene = scene_of(py, recipe)?;
    let describe = |scene: &wrinkle::Scene, threshold: &wrinkle::threshold::Threshold| {
        threshold_json(scene, threshold)
    };
    let (found, _) = interruptible(py, || match &out {
        Some(directory) => {
            wrinkle::commands::buckle_with_outputs(&scene, true, directory, &describe)
        }
        None => wrinkle::commands::buckle(&scene, true),
    })?;
    let threshold = found.map_err(|e| to_python(py, e))?;
    let mut value = threshold_json(&scene, &threshold);
    value["validity_failure"] = json!(threshold.validity_failure(&scene.validity));
    to_json(&value)
}

/// The `buckle --json` object of a threshold.
fn threshold_json(
    scene: &wrinkle::Scene,
    threshold: &wrinkle::threshold::Threshold,
) -> serde_json::Value {
    let summary = wrinkle::threshold::ThresholdSummary::new(scene, threshold);
    serde_json::to_value(wrinkle::cli::buckle_json(scene, &summary)).unwrap_or_default()
}

/// `wrinkle run` into `out`: `{summary, files, summary_text, interrupted}`; a Ctrl-C is raised
/// by the Python layer after this returns (the outputs are written).
#[pyfunction]
fn run(py: Python<'_>, recipe: &str, out: PathBuf) -> PyResult<(String, bool)> {
    let scene = scene_of(py, recipe)?;
    let (report, interrupt) =
        interruptible(py, || wrinkle::commands::run(&scene, &out, true, None))?;
    let report = report.map_err(|e| to_python(py, e))?;
    let value = json!({
        "summary": report.summary,
        "files": report.files,
        "summary_text": report.summary_text,
        "directory": out,
    });
    Ok((to_json(&value)?, interrupt.is_some()))
}

/// `wrinkle compare` into `out`: `{rows, closed_form_critical_load, reference, directory}`.
#[pyfunction]
fn compare(
    py: Python<'_>,
    recipe: &str,
    models: Vec<String>,
    model_overrides: Vec<String>,
    out: PathBuf,
) -> PyResult<String> {
    let scene = scene_of(py, recipe)?;
    let (comparison, _) = interruptible(py, || {
        wrinkle::compare::compare(&scene, &models, &model_overrides, &out, true)
    })?;
    let comparison = comparison.map_err(|e| to_python(py, e))?;
    to_json(&json!({
        "rows": comparison.rows,
        "closed_form_critical_load": comparison.closed_form_critical_load,
        "reference": comparison.reference,
        "directory": out,
    }))
}

/// The models `wrinkle compare` runs by default, as JSON.
#[pyfunction]
fn default_compare_models() -> PyResult<String> {
    to_json(&wrinkle::compare::default_models())
}

/// Sets the worker threads of this process (`--threads`); `false` when they were already set
/// (the first call, or the first solve, fixes them for the process). Results do not depend on
/// it.
#[pyfunction]
fn set_threads(threads: usize) -> bool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.max(1))
        .build_global()
        .is_ok()
}

/// `wrinkle analytic --json` (with `--table-1` when `table_1`).
#[pyfunction]
#[pyo3(signature = (recipe, table_1=false))]
fn analytic(py: Python<'_>, recipe: &str, table_1: bool) -> PyResult<String> {
    let scene = scene_of(py, recipe)?;
    let options = wrinkle::analytic::AnalyticOptions {
        table_1,
        ..wrinkle::analytic::AnalyticOptions::default()
    };
    let (report, _) = interruptible(py, || wrinkle::analytic::analyse(&scene, &options))?;
    let report = report.map_err(|e| to_python(py, e))?;
    Ok(report.to_json(&scene).to_string())
}

/// A VTU file's arrays as JSON ([`vtu::read_vtu`]).
#[pyfunction]
fn read_vtu(py: Python<'_>, path: PathBuf) -> PyResult<String> {
    let value = py
        .detach(|| vtu::read_vtu(&path))
        .map_err(pyo3::exceptions::PyOSError::new_err)?;
    Ok(value.to_string())
}

/// The plan of a sweep ([`SweepPlan`] as JSON) from its points (JSON list of
/// `{index, inputs, recipe}`), its command (`run`, `buckle`) and directory.
#[pyfunction]
fn sweep_plan(py: Python<'_>, points: &str, command: &str, out: PathBuf) -> PyResult<String> {
    let points: Vec<PlannedPoint> =
        serde_json::from_str(points).map_err(|e| bad_argument(format!("sweep points: {e}")))?;
    let command = SweepCommand::parse(command).map_err(|e| to_python(py, e))?;
    let plan = py.detach(|| SweepPlan::new(points, command, &out));
    to_json(&plan)
}

/// One point of a sweep ([`wrinkle::sweep::run_point`]): its result as JSON. Never raises for
/// the point's own failure: that is the result's `outcome` and `reason`.
#[pyfunction]
fn sweep_run_point(py: Python<'_>, recipe: &str, command: &str, out: PathBuf) -> PyResult<String> {
    let recipe = recipe_of(recipe)?;
    let command = SweepCommand::parse(command).map_err(|e| to_python(py, e))?;
    let (result, interrupt) =
        interruptible(py, || wrinkle::sweep::run_point(&recipe, command, &out))?;
    if let Some(error) = interrupt {
        return Err(error);
    }
    to_json(&result)
}

/// The table of a sweep: its rows from the plan and the pending runs' results (JSON object,
/// name → result), written as `sweep.csv` in `out`; returns `{columns, rows}` (cells).
#[pyfunction]
fn sweep_table(plan: &str, results: &str, out: PathBuf) -> PyResult<String> {
    let plan: SweepPlan =
        serde_json::from_str(plan).map_err(|e| bad_argument(format!("sweep plan: {e}")))?;
    let results: std::collections::BTreeMap<String, PointResult> =
        serde_json::from_str(results).map_err(|e| bad_argument(format!("sweep results: {e}")))?;
    let rows = plan.rows(&results);
    let path: PathBuf = Path::new(&out).join(wrinkle::sweep::TABLE_FILE);
    wrinkle::sweep::write_table_csv(&path, &rows)
        .map_err(|e| pyo3::exceptions::PyOSError::new_err(format!("{}: {e}", path.display())))?;
    let columns = wrinkle::sweep::table::table_columns(&rows);
    let cells: Vec<Vec<wrinkle::sweep::table::Cell>> = rows
        .iter()
        .map(|row| wrinkle::sweep::table::table_cells(row, &columns))
        .collect();
    to_json(&json!({"columns": columns, "rows": cells}))
}
