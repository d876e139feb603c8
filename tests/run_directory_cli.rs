//! Issue 26, "Lost or mixed outputs": two runs started into the same `--out` at once both
//! exited 0 and left a `summary.json` that disagreed with `path.csv`; a run killed (SIGKILL)
//! while writing had already deleted the previous run's outputs and left a manifest listing
//! only `summary.json` beside files it did not list, which the next run did not clean.
//!
//! Now (`src/output/run_directory.rs`): a second run into a locked directory fails at once
//! (exit 2, naming the holder); a run killed at any moment leaves the previous run or the new
//! one, each consistent with its manifest, and the next run finishes or undoes what was left.
//! Scenes: example 1 on coarse meshes.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output};
use std::time::{Duration, Instant};

/// A fresh, empty directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-rundir-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// `wrinkle run -q` on example 1 with a `nx × ny` mesh and `vtu_loads` into `out`.
fn run_command(out: &Path, nx: usize, vtu_loads: &str) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_wrinkle"));
    command
        .args(["run", "-q", "--set"])
        .arg(format!("mesh.nx={nx}"))
        .arg("--set")
        .arg(format!("mesh.ny={}", nx / 2))
        .arg("--set")
        .arg(format!("output.vtu_loads={vtu_loads}"))
        .arg("--out")
        .arg(out)
        .stdout(std::process::Stdio::null());
    command
}

fn finish(command: &mut Command) -> Output {
    command.output().unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// Names of the entries of `directory`.
fn names(directory: &Path) -> BTreeSet<String> {
    std::fs::read_dir(directory)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// Names of the files of `directory` and of its folders (`series/fields_0000.vtu`).
fn files_within(directory: &Path) -> BTreeSet<String> {
    let mut files = BTreeSet::new();
    for name in names(directory) {
        let path = directory.join(&name);
        if path.is_dir() {
            files.extend(
                files_within(&path)
                    .into_iter()
                    .map(|inner| format!("{name}/{inner}")),
            );
        } else {
            files.insert(name);
        }
    }
    files
}

/// The run in `out` is complete and consistent: its `summary.json` lists exactly the files
/// there besides `foreign` (the user's files, which a kill in the instant between the swap and
/// the cleanup leaves in the sibling for the next run to move back), and agrees with its
/// `path.csv`. Returns its `output.vtu_loads`.
fn consistent_run(out: &Path, foreign: &[&str]) -> serde_json::Value {
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let listed: BTreeSet<String> = summary["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|name| name.as_str().unwrap().to_string())
        .collect();
    let mut present = files_within(out);
    for name in foreign {
        present.remove(*name);
    }
    assert_eq!(present, listed, "the files present are those listed");
    let rows = std::fs::read_to_string(out.join("path.csv"))
        .unwrap()
        .lines()
        .count();
    let points = summary["path"].as_array().unwrap().len();
    assert_eq!(rows, points + 1, "path.csv has the summary's path");
    summary["scene"]["output"]["vtu_loads"].clone()
}

/// Waits until `path` exists or `child` ends; whether it exists.
fn wait_for(path: &Path, child: &mut Child) -> bool {
    let start = Instant::now();
    while start.elapsed() < Duration::from_secs(120) {
        if path.exists() {
            return true;
        }
        if child.try_wait().unwrap().is_some() {
            return path.exists();
        }
        std::thread::sleep(Duration::from_millis(1));
    }
    false
}

/// Two runs into one directory: while the first holds it, the second fails at once with exit 2
/// and a message naming the first; the first completes, consistent. Repeated, as the issue's
/// 12 trials were.
#[test]
fn a_second_run_into_a_busy_directory_fails_at_once() {
    let root = scratch("concurrent");
    let out = root.join("out");
    let staging = root.join(".out.wrinkle-new");
    for trial in 0..3 {
        let mut first = run_command(&out, 32, "[0.05]").spawn().unwrap();
        assert!(wait_for(&staging, &mut first), "trial {trial}: no staging");
        let start = Instant::now();
        let second = finish(&mut run_command(&out, 16, "[0.06]"));
        let elapsed = start.elapsed();
        let first_ended_before = first.try_wait().unwrap().is_some();
        let first = first.wait_with_output().unwrap();
        assert_eq!(first.status.code(), Some(0), "{}", stderr(&first));
        if first_ended_before {
            continue; // the first run ended before the second started: no contest
        }
        let text = stderr(&second);
        assert_eq!(second.status.code(), Some(2), "trial {trial}: {text}");
        assert!(text.contains("another wrinkle run"), "{text}");
        assert!(text.contains("process "), "{text}");
        assert!(elapsed < Duration::from_secs(5), "at once: {elapsed:?}");
        assert_eq!(consistent_run(&out, &[]), serde_json::json!([0.05]));
    }
    let _ = std::fs::remove_dir_all(&root);
}

/// A run killed (SIGKILL) at several moments — before its outputs, and 0 to 3000 ms into
/// writing them — leaves the previous run or the new one, complete and consistent with its
/// manifest, with the user's own file kept; the next run completes and leaves nothing of the
/// killed one (no staging or old directory beside it, no unlisted file in it).
#[cfg(unix)]
#[test]
fn a_run_killed_at_any_moment_leaves_the_old_run_or_the_new_one() {
    let root = scratch("killed");
    let out = root.join("out");
    let previous = finish(&mut run_command(&out, 16, "[0.05]"));
    assert_eq!(previous.status.code(), Some(0), "{}", stderr(&previous));
    std::fs::write(out.join("notes.txt"), "mine").unwrap();
    let loads = "[0.06, 0.07, 0.08, 0.09, 0.1]";
    let staging_csv = root.join(".out.wrinkle-new").join("path.csv");
    let mut outcomes = BTreeSet::new();
    for delay in [
        None,
        Some(0),
        Some(5),
        Some(20),
        Some(60),
        Some(150),
        Some(300),
    ] {
        let mut child = run_command(&out, 24, loads).spawn().unwrap();
        match delay {
            None => std::thread::sleep(Duration::from_millis(50)),
            Some(milliseconds) => {
                wait_for(&staging_csv, &mut child);
                std::thread::sleep(Duration::from_millis(milliseconds));
            }
        }
        let _ = child.kill();
        let status = child.wait().unwrap();
        let found = consistent_run(&out, &["notes.txt"]);
        let which = if found == serde_json::json!([0.05]) {
            "old"
        } else {
            assert_eq!(found.to_string(), loads.replace(' ', ""), "{delay:?}");
            "new"
        };
        let moment = delay.map_or("before writing".to_string(), |d| {
            format!("{d} ms into writing")
        });
        outcomes.insert(format!("{which} ({moment})"));
        // The next run puts the directory back in order.
        let next = finish(&mut run_command(&out, 16, "[0.05]"));
        assert_eq!(next.status.code(), Some(0), "{delay:?}: {}", stderr(&next));
        assert_eq!(
            consistent_run(&out, &["notes.txt"]),
            serde_json::json!([0.05])
        );
        assert_eq!(
            std::fs::read_to_string(out.join("notes.txt")).unwrap(),
            "mine"
        );
        assert_eq!(
            names(&root),
            ["out", ".out.wrinkle-lock"].map(String::from).into(),
            "{delay:?} ({status}): nothing beside the directory but its lock"
        );
    }
    eprintln!("killed runs left: {outcomes:?}");
    assert!(
        outcomes.iter().any(|o| o.starts_with("old")),
        "{outcomes:?}"
    );
    let _ = std::fs::remove_dir_all(&root);
}
