//! `wrinkle compare` ends with the exit code of its most severe model (docs/outputs.md, exit
//! codes): a model used outside its validity says which and why, every result computed is kept,
//! and the command exits 4; a plate whose resolving mesh cannot be solved is refused with exit
//! 4 before any model runs, naming the model and the mesh it needs.
//!
//! Source: issue 32 ("`wrinkle compare` exits 0 when a model is invalid"). Scenes: example 1
//! (the default scene, 32 × 16) for the envelope and the pure membrane; example 1 stretched to
//! 30 000 × 2 000 mm for the refusal.

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

fn compare_json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("compare.json")).unwrap()).unwrap()
}

fn compare(dir: &Path, extra: &[&str]) -> Output {
    let out = dir.display().to_string();
    let mut arguments = vec![
        "compare",
        "-q",
        "--models",
        "reference-envelope,pure-membrane",
        "--out",
        &out,
    ];
    arguments.extend(extra);
    wrinkle(&arguments)
}

/// The pure membrane on example 1 is ill-posed just beyond its threshold (`well_posedness`):
/// the comparison exits 4 naming it and the check, and still writes every file — both runs,
/// the table, `compare.csv/json/png`, `index.html` — with `exit_code` 4 in `compare.json`.
#[test]
fn an_ill_posed_model_makes_compare_exit_4_with_every_result_written() {
    let dir = directory("compare-ill-posed");
    let output = compare(&dir, &[]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(4), "{stdout}{stderr}");
    assert!(
        stderr.contains("outside the model's validity: pure-membrane (invalid): well_posedness"),
        "{stderr}"
    );
    assert!(stderr.contains(&dir.display().to_string()), "{stderr}");
    assert!(!stderr.contains("reference-envelope ("), "{stderr}");
    assert!(
        stdout.contains("not valid: pure-membrane: well_posedness"),
        "{stdout}"
    );
    for file in [
        "compare.csv",
        "compare.json",
        "compare.png",
        "compare.svg",
        "index.html",
        "reference-envelope/summary.json",
        "reference-envelope/path.csv",
        "pure-membrane/summary.json",
        "pure-membrane/path.csv",
    ] {
        assert!(dir.join(file).is_file(), "missing {file}");
    }
    let json = compare_json(&dir);
    assert_eq!(json["exit_code"], 4);
    assert_eq!(json["reference"], "reference-envelope");
    let rows = json["models"].as_array().unwrap();
    assert_eq!(rows[0]["exit_code"], 0);
    assert_eq!(rows[1]["outcome"], "invalid");
    assert_eq!(rows[1]["exit_code"], 4);
    let _ = std::fs::remove_dir_all(&dir);
}

/// A scene that accepts the check (`validity.accept`) sees it as a note, as `wrinkle run` does:
/// the comparison exits 0, the row still lists the failed check and is not the reference.
#[test]
fn an_accepted_check_lets_compare_exit_0() {
    let dir = directory("compare-accepted");
    let output = compare(&dir, &["--set", "validity.accept=well_posedness"]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    let json = compare_json(&dir);
    assert_eq!(json["exit_code"], 0);
    assert_eq!(json["models"][1]["outcome"], "reached");
    assert_eq!(json["models"][1]["failed_checks"][0], "well_posedness");
    assert_eq!(json["reference"], "reference-envelope");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Example 1 stretched to 30 000 × 2 000 mm: the reference envelope's wavelength is 84.35 mm,
/// so the plate would need 3132 × 53 elements (8.8 per wavelength along X, elements at most 4
/// times longer than wide) = 165 996, more than the 120 000 the tool solves. `compare` refuses
/// with exit 4 before any model runs, naming the plate and that mesh.
#[test]
fn a_plate_whose_resolving_mesh_is_too_large_is_refused_with_exit_4() {
    let dir = directory("compare-too-large");
    let out = dir.display().to_string();
    let output = wrinkle(&[
        "compare",
        "-q",
        "--models",
        "reference-envelope,fvk-plate",
        "--set",
        "geometry.lx=30000",
        "--set",
        "geometry.ly=2000",
        "--out",
        &out,
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(4), "{stderr}");
    assert!(
        stderr.contains("fvk-plate needs a 3132×53 mesh"),
        "{stderr}"
    );
    assert!(
        stderr.contains("--model-set fvk-plate:mesh.nx="),
        "{stderr}"
    );
    // Refused before any work: no model ran.
    assert!(!dir.join("reference-envelope").exists());
    assert!(!dir.join("fvk-plate").exists());
    let _ = std::fs::remove_dir_all(&dir);
}
