//! The beam through the CLI (`geometry.kind = "line"`, `docs/beam.md` "The CLI on a line"): every
//! `examples/scenes/beam_*.toml` runs (reduced to 10.25 wavelengths with `--set`), `wrinkle
//! buckle` gives the closed forms of `docs/beam.md` §3, `compare` overlays the models, and a
//! model on the wrong domain or a profile on a constant parameter is a scene error (exit 2).
//!
//! Source: THEORY.md §7; units $`EI = c = 1`$ ($`Q = 1`$, $`\lambda_c = 2`$), $`ES = 1200`$,
//! $`h = 0.1`$. Closed forms for a finite length $`L`$: the simply supported full beam
//! $`\min_n EIk_n^2 + c/k_n^2`$, $`k_n = n\pi/L`$; the real envelope with $`v_1 = 0`$ at the ends
//! $`(6EIQ^2k^2 + EIQ^4 + c)/(Q^2 + k^2)`$, $`k = \pi/L`$.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const WAVELENGTHS: f64 = 10.25;

fn length() -> f64 {
    WAVELENGTHS * 2.0 * std::f64::consts::PI
}

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes")
        .join(name)
}

fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-beam-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn wrinkle(arguments: &[String]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .output()
        .expect("run wrinkle")
}

/// `--set` overrides that shorten a beam scene to 10.25 wavelengths (16 elements each).
fn reduced(scene_name: &str) -> Vec<String> {
    let l = length();
    let mut sets = vec![
        format!("geometry.lx={l}"),
        format!("mesh.nx={}", (16.0 * WAVELENGTHS).round()),
        "solver.max_amplitude_over_h=2.0".to_string(),
    ];
    if scene_name.contains("varying") {
        sets.push(format!(
            "model.profiles.foundation=[[0.0, 1.3], [{}, 1.0], [{l}, 1.3]]",
            l / 2.0
        ));
        sets.push("solver.max_amplitude_over_h=100.0".to_string());
    }
    sets.into_iter()
        .flat_map(|s| ["--set".to_string(), s])
        .collect()
}

fn text(output: &Output) -> String {
    format!(
        "{}\n{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    )
}

#[test]
fn every_beam_scene_runs_reduced() {
    let mut names: Vec<String> = std::fs::read_dir(scene(""))
        .unwrap()
        .filter_map(|e| e.ok()?.file_name().into_string().ok())
        .filter(|n| n.starts_with("beam_") && n.ends_with(".toml"))
        .collect();
    names.sort();
    assert!(names.len() >= 5, "{names:?}");
    for name in names {
        let out = scratch(&name);
        let mut arguments = vec!["run".to_string(), scene(&name).display().to_string()];
        arguments.extend(reduced(&name));
        arguments.extend([
            "--out".to_string(),
            out.display().to_string(),
            "--quiet".into(),
        ]);
        let output = wrinkle(&arguments);
        println!("{name}:\n{}", text(&output));
        assert_eq!(output.status.code(), Some(0), "{name}: {}", text(&output));
        for file in [
            "path.csv",
            "profile_final.csv",
            "profile_final.png",
            "response.png",
            "fields_final.vtu",
            "profile_final.vtu",
            "summary.json",
        ] {
            assert!(out.join(file).is_file(), "{name}: no {file}");
        }
        let _ = std::fs::remove_dir_all(&out);
    }
}

fn buckle_json(model: &str, elements: usize) -> f64 {
    let mut arguments = vec![
        "buckle".to_string(),
        scene("beam_simply_supported.toml").display().to_string(),
        "--json".to_string(),
    ];
    arguments.extend(reduced("beam_simply_supported.toml"));
    for set in [format!("model.name={model}"), format!("mesh.nx={elements}")] {
        arguments.extend(["--set".to_string(), set]);
    }
    let output = wrinkle(&arguments);
    assert_eq!(output.status.code(), Some(0), "{}", text(&output));
    let json: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    json["critical_load"].as_f64().unwrap()
}

#[test]
fn the_cli_beam_thresholds_are_the_closed_forms() {
    let l = length();
    let full_exact = (1..1000)
        .map(|n| {
            let k = n as f64 * std::f64::consts::PI / l;
            k * k + 1.0 / (k * k)
        })
        .fold(f64::INFINITY, f64::min);
    let full = buckle_json("beam-full", 328);
    println!("beam-full, 32 Hermite2 per wavelength: {full:.12} against {full_exact:.12}");
    assert!(
        (full - full_exact).abs() < 1e-5,
        "{full} against {full_exact}"
    );
    let k2 = (std::f64::consts::PI / l).powi(2);
    let envelope_exact = (6.0 * k2 + 1.0 + 1.0) / (1.0 + k2);
    let envelope = buckle_json("beam-envelope", 8);
    println!("beam-envelope, 8 Line3: {envelope:.12} against {envelope_exact:.12}");
    assert!(
        (envelope - envelope_exact).abs() < 1e-6,
        "{envelope} against {envelope_exact}"
    );
}

#[test]
fn compare_overlays_the_beam_models() {
    let out = scratch("compare");
    let mut arguments = vec![
        "compare".to_string(),
        scene("beam_clamped.toml").display().to_string(),
        "--out".to_string(),
        out.display().to_string(),
        "--quiet".to_string(),
    ];
    arguments.extend(reduced("beam_clamped.toml"));
    let output = wrinkle(&arguments);
    println!("{}", text(&output));
    assert_eq!(output.status.code(), Some(0), "{}", text(&output));
    for file in ["compare.csv", "compare.json", "compare_profiles.png"] {
        assert!(out.join(file).is_file(), "no {file}");
    }
    let csv = std::fs::read_to_string(out.join("compare.csv")).unwrap();
    for model in ["beam-full", "beam-envelope", "beam-complex-envelope"] {
        assert!(csv.contains(model), "{csv}");
    }
    let _ = std::fs::remove_dir_all(&out);
}

fn scene_error(arguments: &[&str]) -> String {
    let arguments: Vec<String> = arguments.iter().map(|a| a.to_string()).collect();
    let output = wrinkle(&arguments);
    assert_eq!(output.status.code(), Some(2), "{}", text(&output));
    String::from_utf8_lossy(&output.stderr).to_string()
}

#[test]
fn a_model_on_the_wrong_domain_or_a_constant_parameter_profiled_exits_2() {
    let beam = scene("beam_clamped.toml").display().to_string();
    let message = scene_error(&["buckle", &beam, "--set", "model.name=reference-envelope"]);
    assert!(
        message.contains("reference-envelope") && message.contains("line"),
        "{message}"
    );
    let message = scene_error(&[
        "buckle",
        "--set",
        "model.name=beam-full",
        "--set",
        "model.parameters.bending_stiffness=1.0",
        "--set",
        "model.parameters.axial_stiffness=1200.0",
        "--set",
        "model.parameters.foundation=1.0",
        "--set",
        "model.parameters.foundation_cubic=2.0",
    ]);
    assert!(
        message.contains("beam-full") && message.contains("geometry.kind"),
        "{message}"
    );
    let message = scene_error(&[
        "buckle",
        &beam,
        "--set",
        "model.profiles.bending_stiffness=[[0.0, 1.0], [10.0, 2.0]]",
    ]);
    assert!(
        message.contains("model.profiles.bending_stiffness"),
        "{message}"
    );
    let message = scene_error(&[
        "buckle",
        &beam,
        "--set",
        "model.profiles.foundation=[[1.0, 1.0], [0.5, 2.0]]",
    ]);
    assert!(message.contains("model.profiles.foundation"), "{message}");
}
