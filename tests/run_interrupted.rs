//! Ctrl-C during `wrinkle run` stops the path after the current point, writes every output from
//! the completed points and exits with 130; nothing computed is lost.

#![cfg(unix)]

use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};

#[test]
fn ctrl_c_on_the_path_keeps_every_completed_point() {
    let directory =
        std::env::temp_dir().join(format!("wrinkle_run_interrupted_{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&directory);
    // A slow path (fine mesh, tight series) so that the signal arrives while it runs.
    let mut child = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args([
            "run",
            "--out",
            directory.to_str().unwrap(),
            "--set",
            "mesh.nx=48",
            "--set",
            "mesh.ny=24",
            "--set",
            "model.wavenumber=0.2354",
            "--set",
            "solver.series_tolerance=1e-10",
            "--set",
            "solver.order=8",
            "--set",
            "output.plots=false",
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stderr = BufReader::new(child.stderr.take().unwrap());
    let mut seen = String::new();
    loop {
        let mut line = String::new();
        if stderr.read_line(&mut line).unwrap() == 0 {
            panic!("the run ended before its path started:\n{seen}");
        }
        seen.push_str(&line);
        if line.starts_with("wrinkle run") && line.contains("started") {
            break;
        }
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let mut rest = String::new();
    std::io::Read::read_to_string(&mut stderr, &mut rest).unwrap();
    let status = child.wait().unwrap();
    assert_eq!(status.code(), Some(130), "{seen}{rest}");
    assert!(rest.contains("interrupted"), "{rest}");
    let csv = std::fs::read_to_string(directory.join("path.csv")).unwrap();
    let rows = csv.lines().filter(|l| !l.starts_with('#')).count();
    assert!(rows >= 2, "path.csv keeps the completed points:\n{csv}");
    let summary: serde_json::Value =
        serde_json::from_slice(&std::fs::read(directory.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["outcome"], "interrupted");
    assert_eq!(summary["exit_code"], 130);
    let points = summary["path"].as_array().unwrap();
    assert_eq!(points.len(), rows - 1, "one header row in path.csv");
    assert!(
        points
            .iter()
            .all(|p| p["lambda"].as_f64().unwrap().is_finite())
    );
    let _ = std::fs::remove_dir_all(&directory);
}
