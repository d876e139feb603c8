//! `wrinkle sweep` and its child `wrinkle sweep-point`: the arguments, the local run, the
//! hand-off to the Python package (`--scheduler`), the printed table.

use super::grid::Grid;
use super::local::{LocalOptions, run_pending};
use super::plan::{SweepPlan, SweepRow};
use super::point::{SweepCommand, run_point};
use super::recipe::SceneRecipe;
use super::table::{TABLE_FILE, write_table_csv};
use crate::error::{Error, io_error, output_directory_error};
use crate::output::{DirectoryLock, message_line};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// Largest recipe read by `sweep-point` on its standard input.
const MAX_RECIPE_BYTES: u64 = 4 << 20;

/// The Python interpreter `--scheduler` runs, unless `WRINKLE_PYTHON` names another.
pub const DEFAULT_PYTHON: &str = "python3";

/// `wrinkle sweep`: a scene run over a grid of key values.
#[derive(Debug, clap::Args)]
pub struct SweepArguments {
    /// Scene file (TOML); the built-in default scene when omitted.
    #[arg(value_name = "SCENE")]
    pub path: Option<PathBuf>,
    /// Override one scene key for every point (repeatable, applied before the grid).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
    /// One axis of the grid: a scene key and its values, separated by commas (repeatable; the
    /// points are every combination, the first axis varying slowest).
    #[arg(long = "grid", value_name = "KEY=a,b,c")]
    pub grid: Vec<String>,
    /// What each point runs: `run` (threshold and path) or `buckle` (the threshold only).
    #[arg(long, value_name = "COMMAND", default_value = "run")]
    pub command: String,
    /// Sweep directory: `sweep.csv`, and each point's outputs under `points/COMMAND-HASH/`
    /// (default: `output.directory`/sweep).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Points run at a time, each in its own process (default: one per core).
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub jobs: Option<u16>,
    /// Hand the sweep to the Python package on a Dask scheduler at this address (e.g.
    /// `tcp://10.0.0.1:8786`) instead of running it here; see docs/python.md.
    #[arg(long, value_name = "ADDRESS")]
    pub scheduler: Option<String>,
    /// No progress on standard error.
    #[arg(long, short)]
    pub quiet: bool,
}

/// `wrinkle sweep-point` (hidden): one point of a sweep, its recipe as JSON on standard input.
#[derive(Debug, clap::Args)]
pub struct SweepPointArguments {
    /// `run` or `buckle`.
    #[arg(long, value_name = "COMMAND", default_value = "run")]
    pub command: String,
    /// The sweep directory.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

/// Runs `wrinkle sweep`: the table on standard output, `sweep.csv` in the sweep directory;
/// exit 0 once every point has a row (whatever its outcome), 130 when interrupted.
pub fn sweep(arguments: &SweepArguments) -> Result<(), Error> {
    let command = SweepCommand::parse(&arguments.command)?;
    let mut recipe = match &arguments.path {
        Some(path) => SceneRecipe::from_file(path)?,
        None => SceneRecipe::built_in(),
    };
    recipe.overrides.extend(arguments.overrides.iter().cloned());
    // The base scene is checked before any work; a grid value it refuses is that point's row.
    let base = recipe.build()?;
    let grid = Grid::parse(&arguments.grid)?;
    let directory = arguments
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from(&base.output.directory).join("sweep"));
    let _lock = DirectoryLock::inside(&directory).map_err(output_directory_error(&directory))?;
    if let Some(address) = &arguments.scheduler {
        return hand_to_python(&recipe, &grid, command, &directory, address);
    }
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let jobs = arguments.jobs.map_or(cores, usize::from);
    let options = LocalOptions {
        jobs,
        threads: (cores / jobs).max(1),
        quiet: arguments.quiet,
    };
    let plan = SweepPlan::new(grid.points(&recipe)?, command, &directory);
    if !arguments.quiet {
        message_line(&format!(
            "sweep: {} points, {} to run ({} reused), {jobs} at a time",
            plan.points.len(),
            plan.pending.len(),
            plan.done.len()
        ));
    }
    crate::interrupt::install();
    let phase = crate::interrupt::PathPhase::enter();
    let results = run_pending(&plan, &directory, &options)?;
    drop(phase);
    let rows = plan.rows(&results);
    let table = directory.join(TABLE_FILE);
    write_table_csv(&table, &rows).map_err(io_error(&table))?;
    print_stdout(&rows_summary(&rows))?;
    if crate::interrupt::requested() {
        return Err(Error::Interrupted(format!(
            "the points not run are `lost` rows in {}; run the sweep again to finish it",
            table.display()
        )));
    }
    message_line(&format!("sweep table in {}", table.display()));
    Ok(())
}

/// Runs `wrinkle sweep-point`: reads the recipe, runs the point (Ctrl-C as in `wrinkle run`),
/// writes its `point.json`.
pub fn sweep_point(arguments: &SweepPointArguments) -> Result<(), Error> {
    let command = SweepCommand::parse(&arguments.command)?;
    let mut bytes = Vec::new();
    std::io::stdin()
        .take(MAX_RECIPE_BYTES)
        .read_to_end(&mut bytes)
        .map_err(io_error(Path::new("<stdin>")))?;
    let recipe: SceneRecipe = serde_json::from_slice(&bytes)
        .map_err(|error| Error::Usage(format!("sweep-point: recipe on stdin: {error}")))?;
    crate::interrupt::install();
    run_point(&recipe, command, &arguments.out);
    Ok(())
}

/// `--scheduler`: runs `PYTHON -m wrinkle.cli_sweep` with the sweep as JSON on its standard
/// input (`PYTHON` from `WRINKLE_PYTHON`, default [`DEFAULT_PYTHON`]); a clear usage error when
/// the package cannot be imported.
fn hand_to_python(
    recipe: &SceneRecipe,
    grid: &Grid,
    command: SweepCommand,
    directory: &Path,
    address: &str,
) -> Result<(), Error> {
    let python = std::env::var("WRINKLE_PYTHON").unwrap_or_else(|_| DEFAULT_PYTHON.into());
    let missing = |why: String| {
        Error::Usage(format!(
            "--scheduler hands the sweep to the Python package `wrinkle`, which `{python}` cannot import ({why}): install it with `pip install ./python` (docs/python.md), or set WRINKLE_PYTHON to the interpreter that has it; without --scheduler the sweep runs here"
        ))
    };
    let probe = std::process::Command::new(&python)
        .args(["-c", "import wrinkle.cli_sweep"])
        .output()
        .map_err(|error| missing(error.to_string()))?;
    if !probe.status.success() {
        let text = String::from_utf8_lossy(&probe.stderr);
        return Err(missing(
            text.lines().last().unwrap_or("").trim().to_string(),
        ));
    }
    let request = serde_json::json!({
        "recipe": recipe,
        "grid": grid.axes.iter().map(|a| (a.key.clone(), a.values.clone())).collect::<Vec<_>>(),
        "command": command,
        "out": directory,
        "scheduler": address,
    });
    let mut child = std::process::Command::new(&python)
        .args(["-m", "wrinkle.cli_sweep"])
        .stdin(std::process::Stdio::piped())
        .spawn()
        .map_err(|error| missing(error.to_string()))?;
    if let Some(mut stdin) = child.stdin.take() {
        let _ = stdin.write_all(request.to_string().as_bytes());
    }
    let status = child.wait().map_err(io_error(Path::new(&python)))?;
    match status.code() {
        Some(0) => Ok(()),
        code => Err(Error::Solver(format!(
            "the Python sweep on {address} ended with {}",
            code.map_or("a signal".to_string(), |c| format!("exit code {c}"))
        ))),
    }
}

/// The printed table: index, inputs, outcome, $`\lambda_c`$, wavelength, seconds, reused.
fn rows_summary(rows: &[SweepRow]) -> String {
    let mut text = String::new();
    for row in rows {
        let inputs: Vec<String> = row.inputs.iter().map(|(k, v)| format!("{k}={v}")).collect();
        let result = &row.result;
        let number = |v: Option<f64>| v.map_or("-".to_string(), |v| format!("{v:.6e}"));
        text.push_str(&format!(
            "{:>4}  {}  {:<11} λ_c {}  wavelength {}  {:.2} s{}\n",
            row.index,
            inputs.join(" "),
            result.outcome,
            number(result.critical_load),
            number(result.wavelength),
            result.seconds,
            if result.reused { "  (reused)" } else { "" }
        ));
    }
    text
}

/// Writes to standard output; a closed pipe is not an error.
fn print_stdout(text: &str) -> Result<(), Error> {
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Err(error) if error.kind() != std::io::ErrorKind::BrokenPipe => Err(Error::Io {
            path: "<stdout>".into(),
            error,
        }),
        _ => Ok(()),
    }
}
