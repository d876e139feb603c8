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
