//! `wrinkle sweep`: a grid of a reduced example 1 run locally, one child process per point,
//! into `sweep.csv`; an invalid grid value is a row (exit code 2 in it), not a failed sweep; a
//! second call reuses every point; the same scene given twice runs once.

use std::path::{Path, PathBuf};
use std::process::Command;

/// A fresh directory for one test.
fn fresh(name: &str) -> PathBuf {
    let directory =
        std::env::temp_dir().join(format!("wrinkle_sweep_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&directory);
    directory
}

/// `wrinkle sweep` of a reduced example 1 (16 × 8 buckling) over `grid` into `out`: stdout and
/// exit code.
fn sweep(out: &Path, grid: &[&str]) -> (String, i32) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_wrinkle"));
    command.args(["sweep", "--command", "buckle", "--jobs", "2", "-q", "--out"]);
    command.arg(out);
    command.args(["--set", "mesh.nx=16", "--set", "mesh.ny=8"]);
    for axis in grid {
        command.args(["--grid", axis]);
    }
    let output = command.output().unwrap();
    (
        String::from_utf8(output.stdout).unwrap(),
        output.status.code().unwrap_or(-1),
    )
}

/// The rows of `sweep.csv` as cells by column name.
fn table(out: &Path) -> Vec<std::collections::HashMap<String, String>> {
    let text = std::fs::read_to_string(out.join("sweep.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<String> = lines.next().unwrap().split(',').map(String::from).collect();
    lines
        .map(|line| header.iter().cloned().zip(cells(line)).collect())
        .collect()
}

/// The cells of one CSV line (a quoted cell may hold commas and doubled quotes).
fn cells(line: &str) -> Vec<String> {
    let mut cells = vec![String::new()];
    let mut quoted = false;
    let mut characters = line.chars().peekable();
    while let Some(character) = characters.next() {
        match (quoted, character) {
            (true, '"') if characters.peek() == Some(&'"') => {
                characters.next();
                cells.last_mut().unwrap().push('"');
            }
            (_, '"') => quoted = !quoted,
            (false, ',') => cells.push(String::new()),
            (_, c) => cells.last_mut().unwrap().push(c),
        }
    }
    cells
}

#[test]
fn a_grid_sweep_writes_its_table_and_a_second_call_reuses_every_point() {
    let out = fresh("grid");
    let (printed, code) = sweep(&out, &["load.tension_y=5,10", "material.poisson=0.3,0.7"]);
    assert_eq!(code, 0, "{printed}");
    let rows = table(&out);
    assert_eq!(rows.len(), 4);
    let outcomes: Vec<&str> = rows.iter().map(|r| r["outcome"].as_str()).collect();
    assert_eq!(outcomes, ["reached", "error", "reached", "error"]);
    assert_eq!(rows[1]["exit_code"], "2");
    assert_eq!(rows[0]["load.tension_y"], "5");
    assert_ne!(rows[0]["critical_load"], rows[2]["critical_load"]);
    assert!(out.join(&rows[0]["directory"]).join("point.json").is_file());
    assert!(
        out.join(&rows[0]["directory"])
            .join("buckle.json")
            .is_file()
    );

    let (_, code) = sweep(&out, &["load.tension_y=5,10", "material.poisson=0.3,0.7"]);
    assert_eq!(code, 0);
    let again = table(&out);
    assert_eq!(again[0]["reused"], "true");
    assert_eq!(again[2]["reused"], "true");
    assert_eq!(again[0]["critical_load"], rows[0]["critical_load"]);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn points_with_one_effective_scene_run_once_and_bad_grids_exit_2() {
    let out = fresh("same");
    // 10 is the default tension: both points are one scene.
    let (printed, code) = sweep(&out, &["load.tension_y=10,10.0"]);
    assert_eq!(code, 0, "{printed}");
    let rows = table(&out);
    assert_eq!(rows[0]["hash"], rows[1]["hash"]);
    let points = std::fs::read_dir(out.join("points"))
        .unwrap()
        .filter(|e| {
            !e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .starts_with('.')
        })
        .count();
    assert_eq!(points, 1);
    let (_, code) = sweep(&out, &["load.tension_y=5,,6"]);
    assert_eq!(code, 2);
    let _ = std::fs::remove_dir_all(&out);
}
