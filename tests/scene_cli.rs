//! The `wrinkle` binary's handling of scenes: effective-scene printing, one-line errors and exit
//! codes, and the shape of `buckle --json`.

use std::process::{Command, Output};
use wrinkle::Scene;

fn wrinkle(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the wrinkle binary runs")
}

#[test]
fn scene_command_prints_an_effective_scene_that_parses_back() {
    let output = wrinkle(&[
        "scene",
        "examples/scenes/long_strip.toml",
        "--set",
        "mesh.nx=48",
        "--set",
        "material.poisson=0.2",
    ]);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8(output.stdout).unwrap();
    let printed = Scene::from_toml_str(&text, "printed").unwrap();
    let mut expected = Scene::load("examples/scenes/long_strip.toml").unwrap();
    expected.mesh.elements_x = 48;
    expected.material.poisson_ratio = 0.2;
    assert_eq!(
        Scene {
            source: expected.source.clone(),
            ..printed
        },
        expected
    );
}

#[test]
fn scene_errors_are_one_line_on_stderr_with_exit_code_two() {
    for arguments in [
        &["scene", "--set", "material.poisson=0.6"][..],
        &["buckle", "--json", "--set", "material.poisson=0.6"],
        &["run", "--set", "mesh.nx=0"],
        &["scene", "does/not/exist.toml"],
        &["buckle", "--set", "material.poison=0.3"],
    ] {
        let output = wrinkle(arguments);
        assert_eq!(output.status.code(), Some(2), "{arguments:?}");
        assert!(output.stdout.is_empty(), "{arguments:?}");
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.starts_with("error: "), "{stderr}");
    }
    let stderr =
        String::from_utf8(wrinkle(&["scene", "--set", "material.poisson=0.6"]).stderr).unwrap();
    assert_eq!(
        stderr.trim_end(),
        "error: --set material.poisson=0.6: key `material.poisson`: must satisfy -0.99 ≤ ν < 0.5 (ν → −1 makes the in-plane problem singular), got 0.6"
    );
}

#[test]
fn usage_errors_exit_with_two_and_help_with_zero() {
    assert_eq!(wrinkle(&["frobnicate"]).status.code(), Some(2));
    assert_eq!(
        wrinkle(&["buckle", "--no-such-flag"]).status.code(),
        Some(2)
    );
    assert_eq!(wrinkle(&[]).status.code(), Some(2));
    assert_eq!(wrinkle(&["--help"]).status.code(), Some(0));
}

/// `buckle --json` on a coarse default scene: the documented keys, the effective scene, and a
/// human summary with the load's unit and the closed form beside it.
#[test]
fn buckle_json_has_the_threshold_keys_and_the_scene() {
    let mut scene = Scene::default();
    for s in ["mesh.nx=8", "mesh.ny=4"] {
        scene.apply_override(s).unwrap();
    }
    let threshold = wrinkle::commands::buckle(&scene, true).unwrap();
    let report = wrinkle::threshold::ThresholdSummary::new(&scene, &threshold);
    let json = serde_json::to_value(wrinkle::cli::buckle_json(&scene, &report)).unwrap();
    let object = json.as_object().unwrap();
    assert_eq!(object["model"], "reference-envelope");
    for key in [
        "critical_load",
        "wavenumber",
        "wavelength",
        "dofs",
        "closed_form_critical_load",
        "eigen_iterations",
        "load_unit",
        "warnings",
        "notes",
    ] {
        assert!(object.contains_key(key), "missing {key}");
    }
    let critical = object["critical_load"].as_f64().unwrap();
    let closed = object["closed_form_critical_load"].as_f64().unwrap();
    assert!(
        (critical - closed).abs() / closed < 2e-2,
        "{critical} vs {closed}"
    );
    assert_eq!(object["scene"], scene.echo_json());
    let summary = wrinkle::cli::buckle_summary(&scene, &report);
    assert!(summary.contains("N/mm"), "{summary}");
    assert!(summary.contains("closed form (42)"), "{summary}");
}
