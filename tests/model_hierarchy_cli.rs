//! Every registered model runs through the same CLI: `models` lists the roles, `buckle` and
//! `run` work for the plate and the envelope models alike, `compare` puts them side by side, and
//! the exit codes say how a run ended (docs/outputs.md).

use std::path::PathBuf;
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

fn summary(dir: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap()
}

#[test]
fn models_lists_the_four_levels_with_their_field_roles() {
    let output = wrinkle(&["models"]);
    assert_eq!(output.status.code(), Some(0));
    let text = String::from_utf8_lossy(&output.stdout);
    for expected in [
        "fvk-plate",
        "complex-envelope",
        "reference-envelope",
        "pure-membrane",
        "w [deflection]",
        "theta_x [rotation_x]",
        "a [envelope_real]",
        "b [envelope_imaginary]",
        "w0 [mean_deflection]",
        "w [envelope]",
    ] {
        assert!(text.contains(expected), "missing `{expected}` in\n{text}");
    }
}

/// The pure membrane's threshold is $`-N_X = DQ^2`$ at the reference envelope's $`Q`$, about half
/// the reference envelope's $`2DQ^2`$ (THEORY.md §5): both through `buckle --json`.
#[test]
fn pure_membrane_wrinkles_at_about_half_the_envelope_load() {
    // The pure membrane is ill-posed beyond its threshold (exit 4 without this): accepted here,
    // the threshold itself is what is compared.
    let coarse = [
        "--set",
        "mesh.nx=8",
        "--set",
        "mesh.ny=4",
        "--set",
        "validity.accept=well_posedness",
        "--json",
        "-q",
    ];
    let json = |model: &str| -> serde_json::Value {
        let mut arguments = vec!["buckle", "--set"];
        let name = format!("model.name={model}");
        arguments.push(&name);
        arguments.extend(coarse);
        let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
            .args(&arguments)
            .output()
            .unwrap();
        assert_eq!(
            output.status.code(),
            Some(0),
            "{}",
            String::from_utf8_lossy(&output.stderr)
        );
        serde_json::from_slice(&output.stdout).unwrap()
    };
    let reference = json("reference-envelope");
    let membrane = json("pure-membrane");
    let q = membrane["wavenumber"].as_f64().unwrap();
    assert_eq!(q, reference["wavenumber"].as_f64().unwrap());
    assert_eq!(membrane["wavenumber_mode"], "auto (reference-envelope)");
    // D Q² with the default material: E = 70000 MPa, ν = 0.3, h = 0.05 mm.
    let d = 70000.0 * 0.05f64.powi(3) / (12.0 * (1.0 - 0.09));
    let closed = d * q * q;
    let lambda = membrane["critical_load"].as_f64().unwrap();
    assert!(
        (lambda - closed).abs() / closed < 1e-3,
        "pure membrane λ_c {lambda} vs D Q² {closed}"
    );
    let ratio = lambda / reference["critical_load"].as_f64().unwrap();
    assert!((ratio - 0.5).abs() < 0.02, "ratio {ratio}");
}

/// A plate on a mesh far too coarse for its wrinkles runs to the end, writes everything, and
/// exits with 4 (mode not resolved); `max_steps = 1` exits with 3 (target not reached).
#[test]
fn exit_codes_say_unresolved_plate_and_incomplete_run() {
    let dir = directory("plate-coarse");
    let out = dir.display().to_string();
    let output = wrinkle(&[
        "run",
        "-q",
        "--set",
        "model.name=fvk-plate",
        "--set",
        "mesh.nx=8",
        "--set",
        "mesh.ny=4",
        "--set",
        "output.plots=false",
        "--out",
        &out,
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(4), "{stderr}");
    assert!(stderr.contains("mode_resolution"), "{stderr}");
    let s = summary(&dir);
    assert_eq!(s["outcome"], "invalid");
    assert_eq!(s["exit_code"], 4);
    assert!(s["wavenumber"].is_null());
    assert!(s["wavelength"].as_f64().unwrap() > 0.0);

    let dir = directory("incomplete");
    let out = dir.display().to_string();
    let output = wrinkle(&[
        "run",
        "-q",
        "--set",
        "mesh.nx=8",
        "--set",
        "mesh.ny=4",
        "--set",
        "solver.max_steps=1",
        "--set",
        "output.plots=false",
        "--out",
        &out,
    ]);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(3), "{stderr}");
    assert_eq!(summary(&dir)["outcome"], "incomplete");
    assert!(dir.join("path.csv").exists());
}

/// `compare` on two models writes one run directory per model and the comparison files, with
/// the thresholds side by side.
#[test]
fn compare_puts_the_envelope_and_the_complex_envelope_side_by_side() {
    let dir = directory("compare");
    let out = dir.display().to_string();
    let output = wrinkle(&[
        "compare",
        "-q",
        "--models",
        "reference-envelope,complex-envelope",
        "--set",
        "mesh.nx=8",
        "--set",
        "mesh.ny=4",
        "--set",
        "solver.max_amplitude_over_h=1",
        "--out",
        &out,
    ]);
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{stdout}{}",
        String::from_utf8_lossy(&output.stderr)
    );
    for file in [
        "compare.csv",
        "compare.json",
        "compare.png",
        "reference-envelope/summary.json",
        "complex-envelope/summary.json",
    ] {
        assert!(dir.join(file).exists(), "missing {file}");
    }
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("compare.json")).unwrap()).unwrap();
    let rows = json["models"].as_array().unwrap();
    assert_eq!(rows.len(), 2);
    let ratio = rows[1]["critical_load_ratio"].as_f64().unwrap();
    // Same carrier Q; the complex envelope's phase lowers the threshold only slightly.
    assert!(
        (ratio - 1.0).abs() < 1e-3,
        "complex/reference threshold ratio {ratio}"
    );
    assert!(stdout.contains("complex-envelope"), "{stdout}");
}
