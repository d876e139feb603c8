//! The tables of `docs/outputs.md` against what the writers write: every column of `path.csv`,
//! every key of `summary.json`, of `buckle --json` and of `compare.json` (top level and per
//! model) is documented, and every documented one is written — so that the documentation cannot
//! drift from the program unnoticed. Runs on the default scene at 8 × 4 (a second or two).
//!
//! Source: issue 32 ("`compare.json` does not match its documentation"; "the doc tables
//! generated or checked against the writers").

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn wrinkle(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .output()
        .unwrap()
}

fn directory(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn outputs_md() -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("docs/outputs.md")).unwrap()
}

/// The names in the first column of the `index`-th table (from 0) after the line that starts
/// with `heading`: every backticked name of the cell (`` `outcome`, `exit_code` `` gives two).
fn documented_names(document: &str, heading: &str, index: usize) -> BTreeSet<String> {
    let start = document
        .lines()
        .position(|line| line.starts_with(heading))
        .unwrap_or_else(|| panic!("no heading `{heading}` in docs/outputs.md"));
    let lines: Vec<&str> = document.lines().skip(start + 1).collect();
    let mut tables = Vec::new();
    let mut current: Vec<&str> = Vec::new();
    for line in lines {
        if line.starts_with('#') {
            break;
        }
        if line.starts_with('|') {
            current.push(line);
        } else if !current.is_empty() {
            tables.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        tables.push(current);
    }
    let table = tables
        .get(index)
        .unwrap_or_else(|| panic!("no table {index} after `{heading}`"));
    table
        .iter()
        .skip(2)
        .flat_map(|row| {
            let cell = row.split('|').nth(1).unwrap_or("");
            cell.split('`')
                .skip(1)
                .step_by(2)
                .map(str::to_string)
                .collect::<Vec<_>>()
        })
        .collect()
}

fn keys(value: &serde_json::Value) -> BTreeSet<String> {
    value
        .as_object()
        .expect("a JSON object")
        .keys()
        .cloned()
        .collect()
}

fn assert_same(what: &str, documented: &BTreeSet<String>, written: &BTreeSet<String>) {
    let undocumented: Vec<_> = written.difference(documented).collect();
    let unwritten: Vec<_> = documented.difference(written).collect();
    assert!(
        undocumented.is_empty() && unwritten.is_empty(),
        "{what}: written but not in docs/outputs.md: {undocumented:?}; documented but not written: {unwritten:?}"
    );
}

const SMALL: [&str; 4] = ["--set", "mesh.nx=8", "--set", "mesh.ny=4"];

#[test]
fn path_csv_and_summary_json_are_documented_key_by_key() {
    let dir = directory("docs-run-tables");
    let out = dir.display().to_string();
    let mut arguments = vec!["run", "-q", "--out", &out];
    arguments.extend(SMALL);
    let output = wrinkle(&arguments);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let document = outputs_md();
    let path_csv = std::fs::read_to_string(dir.join("path.csv")).unwrap();
    let header: BTreeSet<String> = path_csv
        .lines()
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let columns = documented_names(&document, "### `path.csv` columns", 0);
    assert_same("path.csv", &columns, &header);
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let documented = documented_names(&document, "### `summary.json` keys", 0);
    assert_same("summary.json", &documented, &keys(&summary));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn buckle_json_is_documented_key_by_key() {
    let mut arguments = vec!["buckle", "-q", "--json"];
    arguments.extend(SMALL);
    let output = wrinkle(&arguments);
    assert_eq!(output.status.code(), Some(0));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let documented = documented_names(&outputs_md(), "## `wrinkle buckle --json`", 0);
    assert_same("buckle --json", &documented, &keys(&json));
}

#[test]
fn compare_json_is_documented_key_by_key() {
    let dir = directory("docs-compare-tables");
    let out = dir.display().to_string();
    let mut arguments = vec![
        "compare",
        "-q",
        "--models",
        "reference-envelope,complex-envelope",
        "--out",
        &out,
    ];
    arguments.extend(SMALL);
    let output = wrinkle(&arguments);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("compare.json")).unwrap()).unwrap();
    let document = outputs_md();
    let top = documented_names(&document, "## `wrinkle compare`", 0);
    assert_same("compare.json", &top, &keys(&json));
    let per_model = documented_names(&document, "## `wrinkle compare`", 1);
    assert_same(
        "compare.json models[0]",
        &per_model,
        &keys(&json["models"][0]),
    );
    let _ = std::fs::remove_dir_all(&dir);
}
