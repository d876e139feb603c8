//! A path that cannot meet its tolerance ends with a clear message, keeps the points computed so
//! far (start point in summary.json and path.csv) and exits non-zero.
//!
//! Scene: the default example 1 on a 4 × 2 mesh with `solver.tolerance = 1e-15`, below what
//! double precision reaches, so the first ANM step cannot be accepted even after halvings and
//! Newton corrections.

use std::process::Command;

#[test]
fn unreachable_tolerance_fails_cleanly_with_outputs_written() {
    let dir = std::env::temp_dir().join(format!("wrinkle-test-failure-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args([
            "run",
            "--set",
            "mesh.nx=4",
            "--set",
            "mesh.ny=2",
            "--set",
            "solver.tolerance=1e-15",
            "--set",
            "solver.order=6",
            "--out",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "stderr: {stderr}");
    assert!(
        stderr.contains("residual") && stderr.contains("tolerance"),
        "stderr: {stderr}"
    );
    assert!(!stderr.contains("panicked"));
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["failed"], true);
    assert!(!summary["path"].as_array().unwrap().is_empty());
    assert!(dir.join("path.csv").exists());
    let _ = std::fs::remove_dir_all(&dir);
}

/// A wave vector across the compression finds no buckling wavenumber: the strip load on the
/// default scene (whose `model.direction` is 0, right for example 1) compresses the sheet along
/// Y, and example 1 with `model.direction = 90` has no compression along Y. Both fail with
/// exit 1, and the message names `model.direction` and the value to set.
#[test]
fn a_wave_vector_across_the_compression_names_model_direction() {
    for (settings, expected) in [
        (
            ["load.kind=strip", "model.direction=0"],
            "set model.direction = 90",
        ),
        (
            ["load.kind=biaxial", "model.direction=90"],
            "set model.direction = 0",
        ),
    ] {
        let mut command = Command::new(env!("CARGO_BIN_EXE_wrinkle"));
        command.args(["buckle", "--set", "mesh.nx=8", "--set", "mesh.ny=4"]);
        for setting in settings {
            command.args(["--set", setting]);
        }
        let output = command.output().unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "stderr: {stderr}");
        assert!(stderr.contains(expected), "stderr: {stderr}");
        assert!(!stderr.contains("panicked"));
    }
}
