//! The local runner of `wrinkle sweep` (no `--scheduler`): the pending runs of a
//! [`SweepPlan`], each in a child process of this executable (`wrinkle sweep-point`, the
//! recipe as JSON on its standard input), at most `jobs` at a time.
//!
//! A process per point keeps each point's peak memory its own and a crash its own: a child that
//! dies without a result is a `lost` row, never a lost sweep. Ctrl-C reaches the children too
//! (one process group): each stops its path after the current point and writes it (outcome
//! `interrupted`); this runner starts no new point, waits for the running ones and returns what
//! it has.

use super::plan::{PendingRun, SweepPlan};
use super::point::{PointResult, point_directory, read_point_file};
use crate::error::{Error, io_error};
use crate::output::message_line;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Folder of a sweep directory holding each child's standard error, `logs/NAME.txt`.
pub const LOGS_DIRECTORY: &str = "logs";

/// How the local runner runs.
#[derive(Clone, Debug)]
pub struct LocalOptions {
    /// Child processes at a time.
    pub jobs: usize,
    /// `--threads` of each child.
    pub threads: usize,
    /// No progress on standard error.
    pub quiet: bool,
}

/// A child running one pending run.
struct Running {
    child: Child,
    run: PendingRun,
    started: Instant,
}

/// Runs the pending runs of `plan` into the sweep directory `sweep`; their results by name.
pub fn run_pending(
    plan: &SweepPlan,
    sweep: &Path,
    options: &LocalOptions,
) -> Result<BTreeMap<String, PointResult>, Error> {
    let executable = std::env::current_exe().map_err(io_error(Path::new("<executable>")))?;
    let logs = sweep.join(LOGS_DIRECTORY);
    std::fs::create_dir_all(&logs).map_err(io_error(&logs))?;
    let mut queue = plan.pending.iter().cloned();
    let mut running: Vec<Running> = Vec::new();
    let mut results = BTreeMap::new();
    let total = plan.pending.len();
    loop {
        while running.len() < options.jobs.max(1) && !crate::interrupt::requested() {
            let Some(run) = queue.next() else { break };
            let child = spawn_point(&executable, plan, &run, sweep, &logs, options.threads)?;
            running.push(Running {
                child,
                run,
                started: Instant::now(),
            });
        }
        if running.is_empty() {
            break;
        }
        std::thread::sleep(Duration::from_millis(20));
        let mut index = 0;
        while index < running.len() {
            let status = running[index]
                .child
                .try_wait()
                .map_err(io_error(&executable))?;
            let Some(status) = status else {
                index += 1;
                continue;
            };
            let finished = running.swap_remove(index);
            let result = collected(&finished, status, sweep, &logs);
            if !options.quiet {
                message_line(&format!(
                    "sweep: {}/{total} {} ({}, {:.1} s)",
                    results.len() + 1,
                    finished.run.name,
                    result.outcome,
                    result.seconds
                ));
            }
            results.insert(finished.run.name.clone(), result);
        }
    }
    Ok(results)
}

/// Starts `wrinkle --threads T sweep-point --command C --out SWEEP` with the run's recipe on
/// its standard input and its standard error in `logs/NAME.txt`.
fn spawn_point(
    executable: &Path,
    plan: &SweepPlan,
    run: &PendingRun,
    sweep: &Path,
    logs: &Path,
    threads: usize,
) -> Result<Child, Error> {
    // What is there is not final (else the run would not be pending): an interrupted run's,
    // which must not pass for this child's result if it dies before writing its own.
    let stale = point_directory(sweep, &run.name).join(super::point::POINT_FILE);
    let _ = std::fs::remove_file(stale);
    let log_path = logs.join(format!("{}.txt", run.name));
    let log = std::fs::File::create(&log_path).map_err(io_error(&log_path))?;
    let mut child = Command::new(executable)
        .arg("--threads")
        .arg(threads.clamp(1, 1024).to_string())
        .arg("sweep-point")
        .arg("--command")
        .arg(plan.command.name())
        .arg("--out")
        .arg(sweep)
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(log)
        .spawn()
        .map_err(io_error(executable))?;
    let recipe = serde_json::to_vec(&run.recipe).unwrap_or_default();
    if let Some(mut stdin) = child.stdin.take() {
        // A child that died at once closes its end; its exit status says why.
        let _ = stdin.write_all(&recipe);
    }
    Ok(child)
}

/// The result a finished child left in its point's directory, or `lost` with its exit status
/// and the last line of its standard error.
fn collected(
    finished: &Running,
    status: std::process::ExitStatus,
    sweep: &Path,
    logs: &Path,
) -> PointResult {
    let directory = point_directory(sweep, &finished.run.name);
    let hash = finished
        .run
        .name
        .split_once('-')
        .map_or("", |(_, hash)| hash);
    match read_point_file(&directory) {
        Some(result) if result.hash == hash && !result.reused => result,
        _ => {
            let log: PathBuf = logs.join(format!("{}.txt", finished.run.name));
            let last_line = std::fs::read_to_string(&log)
                .ok()
                .and_then(|text| text.lines().last().map(str::to_string))
                .unwrap_or_default();
            PointResult::lost(
                hash,
                &format!("{}/{}", super::point::POINTS_DIRECTORY, finished.run.name),
                format!("the process ended without a result ({status}): {last_line}"),
                finished.started.elapsed().as_secs_f64(),
            )
        }
    }
}
