//! `wrinkle run --threshold FILE` reuses the wavenumber of an earlier threshold of the same
//! scene (`wrinkle buckle --json`, or a run's `summary.json`) instead of searching it again.
//!
//! Scene: the paper's example 1 (the default scene) on a 16 × 8 mesh, where the search is the
//! same two-level search as on finer meshes (18 buckling analyses).
//! Truths: the reused wavenumber is the searched one to the last bit (the file keeps every
//! digit), the critical load of the one analysis agrees with the search's to round-off, and the
//! path is the same curve: the load at physical amplitude h, interpolated between path points,
//! to 1e-4 (measured 1.3e-7 here). The step sequence moves with round-off, and two paths with
//! different step ends agree only to what the residual tolerance allows past the threshold,
//! where the tangent is nearly singular: up to about 1e-4 on example 1 at 32 × 16. A file computed for another scene
//! is refused naming the first key that differs (exit 2).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const MESH: [&str; 4] = ["--set", "mesh.nx=16", "--set", "mesh.ny=8"];

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-reuse-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn wrinkle(arguments: &[&str], extra: &[&std::ffi::OsStr]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .args(extra)
        .output()
        .unwrap()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn run(out: &Path, extra: &[&str]) -> (Output, serde_json::Value) {
    let mut arguments = vec!["run", "-q"];
    arguments.extend(MESH);
    arguments.extend(extra);
    let output = wrinkle(&arguments, &["--out".as_ref(), out.as_os_str()]);
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert_eq!(output.status.code(), Some(0), "stderr: {stderr}");
    (output, json(&out.join("summary.json")))
}

#[test]
fn example_one_run_reusing_buckle_json_has_the_searched_wavenumber_and_the_same_curve() {
    let dir = scratch("buckle");
    let mut arguments = vec!["buckle", "--json", "-q"];
    arguments.extend(MESH);
    let buckle = wrinkle(&arguments, &[]);
    assert_eq!(buckle.status.code(), Some(0));
    let file = dir.join("threshold.json");
    std::fs::write(&file, &buckle.stdout).unwrap();
    let searched = json(&file);

    let (_, cold) = run(&dir.join("cold"), &[]);
    let file_argument = file.to_str().unwrap();
    let (_, reused) = run(&dir.join("reused"), &["--threshold", file_argument]);

    let (cold_t, reused_t) = (&cold["threshold"], &reused["threshold"]);
    assert_eq!(cold_t["wavenumber_mode"], "auto");
    assert_eq!(reused_t["wavenumber_mode"], "auto (reused)");
    // A search (3 analyses from the closed form on this mesh) against a single analysis.
    assert!(cold_t["buckling_evaluations"].as_u64().unwrap() >= 3);
    assert_eq!(reused_t["buckling_evaluations"], 1);
    // Bit-identical wavenumber: the search is deterministic and the file keeps every digit.
    let q = searched["wavenumber"].as_f64().unwrap();
    assert_eq!(cold_t["wavenumber"].as_f64().unwrap(), q);
    assert_eq!(reused_t["wavenumber"].as_f64().unwrap(), q);
    let (lc_cold, lc_reused) = (
        cold_t["critical_load"].as_f64().unwrap(),
        reused_t["critical_load"].as_f64().unwrap(),
    );
    assert!(
        ((lc_reused - lc_cold) / lc_cold).abs() < 1e-9,
        "λ_c {lc_cold} searched, {lc_reused} reused"
    );
    let note = reused_t["notes"].to_string();
    assert!(
        note.contains("reused from") && note.contains(file_argument),
        "{note}"
    );
    // The same curve: the load at physical amplitude h.
    let at_h = |summary: &serde_json::Value| {
        let points: Vec<wrinkle::output::PathPoint> =
            serde_json::from_value(summary["path"].clone()).unwrap();
        wrinkle::study::load_at_amplitude(&points, 1.0).expect("the path reaches a/h = 1")
    };
    let (cold_load, reused_load) = (at_h(&cold), at_h(&reused));
    assert!(
        ((reused_load - cold_load) / cold_load).abs() < 1e-4,
        "λ(a/h = 1): {cold_load} searched, {reused_load} reused"
    );

    // A run's summary.json serves as well, with other solver settings.
    let summary = dir.join("cold").join("summary.json");
    let (_, again) = run(
        &dir.join("again"),
        &[
            "--threshold",
            summary.to_str().unwrap(),
            "--set",
            "solver.max_amplitude_over_h=1",
        ],
    );
    assert_eq!(again["threshold"]["wavenumber"].as_f64().unwrap(), q);
    assert_eq!(again["threshold"]["wavenumber_mode"], "auto (reused)");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Runs with `--threshold` that must be refused with exit 2; returns stderr.
fn refused(file: &Path, extra: &[&str]) -> String {
    let mut arguments = vec!["run", "-q"];
    arguments.extend(MESH);
    arguments.extend(extra);
    arguments.extend(["--threshold", file.to_str().unwrap()]);
    let out = file.with_extension("out");
    let output = wrinkle(&arguments, &["--out".as_ref(), out.as_os_str()]);
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert_eq!(output.status.code(), Some(2), "stderr: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert!(stderr.contains(file.to_str().unwrap()), "{stderr}");
    assert!(
        !out.exists(),
        "nothing is computed before the file is accepted"
    );
    stderr
}

#[test]
fn run_refuses_a_threshold_of_another_scene_naming_the_key() {
    let dir = scratch("refuse");
    let mut arguments = vec!["buckle", "--json", "-q"];
    arguments.extend(MESH);
    let buckle = wrinkle(&arguments, &[]);
    let file = dir.join("threshold.json");
    std::fs::write(&file, &buckle.stdout).unwrap();

    let stderr = refused(&file, &["--set", "mesh.nx=20"]);
    assert!(
        stderr.contains("mesh.nx") && stderr.contains("16") && stderr.contains("20"),
        "{stderr}"
    );
    let stderr = refused(&file, &["--set", "material.thickness=0.04"]);
    assert!(stderr.contains("material.thickness"), "{stderr}");
    // Solver settings do not enter the threshold: accepted (checked above); a fixed
    // wavenumber has no search to skip.
    let stderr = refused(&file, &["--set", "model.wavenumber=0.2"]);
    assert!(stderr.contains("model.wavenumber"), "{stderr}");

    let garbage = dir.join("garbage.json");
    std::fs::write(&garbage, "λ_c = 0.0895").unwrap();
    let stderr = refused(&garbage, &[]);
    assert!(stderr.contains("not JSON"), "{stderr}");
    let missing = dir.join("missing.json");
    let stderr = refused(&missing, &[]);
    assert!(stderr.contains("cannot read"), "{stderr}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// A threshold file written before `model.wavenumber_model` existed lacks the key: it was
/// computed with the default wavenumber model and is accepted for a scene that has it; a file
/// naming another wavenumber model is refused naming the key.
#[test]
fn a_file_without_wavenumber_model_is_read_as_the_default() {
    use wrinkle::Scene;
    use wrinkle::threshold::PriorThreshold;
    let dir = scratch("older");
    let scene = Scene::default();
    let mut recorded = scene.echo_json();
    let model = recorded["model"].as_object_mut().unwrap();
    assert!(model.remove("wavenumber_model").is_some());
    let file = dir.join("older.json");
    let older = serde_json::json!({
        "scene": recorded,
        "wavenumber": 0.2354,
        "critical_load": 0.0895,
    });
    std::fs::write(&file, older.to_string()).unwrap();
    let prior = PriorThreshold::read(&file, &scene).expect("an older file is accepted");
    assert_eq!((prior.wavenumber, prior.critical_load), (0.2354, 0.0895));

    let mut other = scene.clone();
    other
        .apply_override("model.wavenumber_model=pure-membrane")
        .unwrap();
    match PriorThreshold::read(&file, &other) {
        Err(wrinkle::Error::Scene { key, message, .. }) => {
            assert_eq!(key, "model.wavenumber_model", "{message}");
            assert!(message.contains("reference-envelope"), "{message}");
        }
        other => panic!("expected a scene error, got {other:?}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}
