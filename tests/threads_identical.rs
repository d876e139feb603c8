//! The same numbers on a laptop and a workstation: `buckle` and a short `run` with 1 and 2
//! worker threads give bit-for-bit the same JSON and files (assembly sums in an element-colour
//! order fixed by the mesh, not by the thread count). Only wall-clock times and the measured
//! peak memory may differ.

use serde_json::Value;
use std::path::Path;
use std::process::Command;

fn wrinkle(arguments: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .output()
        .unwrap()
}

/// Removes wall-clock times, the measured peak memory and the output directory (which differs
/// by construction).
fn without_times(value: &mut Value) {
    match value {
        Value::Object(map) => {
            for key in [
                "seconds",
                "timings",
                "peak_resident_bytes",
                "directory",
                "files",
            ] {
                map.remove(key);
            }
            map.values_mut().for_each(without_times);
        }
        Value::Array(items) => items.iter_mut().for_each(without_times),
        _ => {}
    }
}

fn json_file(path: &Path) -> Value {
    let mut value: Value = serde_json::from_slice(&std::fs::read(path).unwrap()).unwrap();
    without_times(&mut value);
    value
}

#[test]
fn buckle_on_one_and_two_threads_gives_identical_json() {
    let outputs: Vec<Value> = ["1", "2"]
        .iter()
        .map(|threads| {
            let output = wrinkle(&["--threads", threads, "buckle", "--quiet", "--json"]);
            assert_eq!(output.status.code(), Some(0));
            let mut value: Value = serde_json::from_slice(&output.stdout).unwrap();
            without_times(&mut value);
            value
        })
        .collect();
    assert!(outputs[0]["critical_load"].as_f64().unwrap() > 0.0);
    assert_eq!(outputs[0], outputs[1]);
}

/// `wrinkle --threads T run --quiet --out DIR` with the scene `settings` for T = 1 and 2 in
/// directories under `root`; each must exit 0.
fn run_on_one_and_two_threads(root: &Path, settings: &[&str]) -> Vec<std::path::PathBuf> {
    ["1", "2"]
        .iter()
        .map(|threads| {
            let directory = root.join(format!("threads_{threads}"));
            let mut arguments = vec![
                "--threads",
                threads,
                "run",
                "--quiet",
                "--out",
                directory.to_str().unwrap(),
            ];
            for setting in settings {
                arguments.extend(["--set", setting]);
            }
            let output = wrinkle(&arguments);
            assert_eq!(
                output.status.code(),
                Some(0),
                "{}",
                String::from_utf8_lossy(&output.stderr)
            );
            directory
        })
        .collect()
}

#[test]
fn run_on_one_and_two_threads_writes_identical_files() {
    let root = tempfile_root("threads_identical");
    let directories = run_on_one_and_two_threads(
        &root,
        &[
            "solver.max_amplitude_over_h=1",
            "output.plots=false",
            "output.surface=false",
        ],
    );
    // (`scene.toml` differs by its output directory only.)
    for file in ["path.csv", "fields_final.vtu"] {
        let first = std::fs::read(directories[0].join(file)).unwrap();
        let second = std::fs::read(directories[1].join(file)).unwrap();
        assert!(first == second, "{file} differs between 1 and 2 threads");
    }
    let summary = json_file(&directories[0].join("summary.json"));
    assert!(summary["path"].as_array().unwrap().len() > 10);
    // One `anm_steps` entry per counted step, the last one possibly ended inside.
    let steps = summary["anm_steps"].as_array().unwrap();
    assert_eq!(steps.len() as u64, summary["steps"].as_u64().unwrap());
    assert!(
        steps[..steps.len() - 1]
            .iter()
            .all(|s| s["completed"] == true)
    );
    // The bifurcation prediction runs on a thread of its own beside the next step's series
    // with 2 workers and in place with 1: the same load in the same step's record.
    assert!(
        steps.iter().any(|s| s["predicted_bifurcation"].is_number()),
        "no bifurcation prediction on the path"
    );
    assert_eq!(summary, json_file(&directories[1].join("summary.json")));
    let _ = std::fs::remove_dir_all(&root);
}

/// Example 1's reference envelope at Q = 0.05/mm (a 126 mm wavelength, accepted outside the
/// model's validity) loses ellipticity at its second step end and stays without it. The step
/// ends' checks run beside the path with 2 workers and in place with 1: the same `elliptic`
/// column and the same `loss_of_ellipticity`, at the step end where it happened.
#[test]
fn run_losing_ellipticity_on_one_and_two_threads_records_it_identically() {
    let root = tempfile_root("threads_identical_ellipticity");
    let directories = run_on_one_and_two_threads(
        &root,
        &[
            "model.wavenumber=0.05",
            r#"validity.accept=["scale_separation", "ellipticity"]"#,
            "solver.max_amplitude_over_h=1",
            "output.plots=false",
            "output.surface=false",
            "output.vtu=false",
        ],
    );
    let first = std::fs::read_to_string(directories[0].join("path.csv")).unwrap();
    assert_eq!(
        first,
        std::fs::read_to_string(directories[1].join("path.csv")).unwrap(),
        "path.csv differs between 1 and 2 threads"
    );
    let summary = json_file(&directories[0].join("summary.json"));
    assert_eq!(summary, json_file(&directories[1].join("summary.json")));
    // The loss is reported at a step end, and that row and every later step end say so.
    let loss = summary["loss_of_ellipticity"]["load"].as_f64().unwrap();
    let mut rows = first.lines();
    let header: Vec<&str> = rows.next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (interior, lambda, elliptic) = (column("interior"), column("lambda"), column("elliptic"));
    let step_ends: Vec<(f64, bool)> = rows
        .map(|row| row.split(',').collect::<Vec<_>>())
        .filter(|row| row[interior] == "false")
        .map(|row| (row[lambda].parse().unwrap(), row[elliptic] == "true"))
        .collect();
    assert!(step_ends.iter().any(|&(load, _)| load == loss), "{loss}");
    for &(load, is_elliptic) in &step_ends {
        assert_eq!(is_elliptic, load < loss, "step end at λ = {load}");
    }
    let _ = std::fs::remove_dir_all(&root);
}

fn tempfile_root(name: &str) -> std::path::PathBuf {
    let root = std::env::temp_dir().join(format!("wrinkle_{name}_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&root);
    std::fs::create_dir_all(&root).unwrap();
    root
}
