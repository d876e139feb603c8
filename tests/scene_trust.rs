//! Issue 26, "Trust, round two": scene inputs that used to be silently ignored, taken twice, or
//! reported as a solver failure far from their cause. Each case reproduces one defect of the
//! issue and checks that the input is now refused with exit 2 naming the key, before any work,
//! or used as given.
//!
//! Source: issue 26 ("Silent nonsense", "Errors that do not name the cause", "Unbounded
//! work"); the bounds are those of `docs/scenes.md`.

use std::process::{Command, Output};
use std::time::{Duration, Instant};
use wrinkle::Error;
use wrinkle::scene::{Direction, Scene, Wavenumber};

fn wrinkle(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .output()
        .unwrap()
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// The key and message of a scene error.
fn scene_error<T: std::fmt::Debug>(result: Result<T, Error>) -> (String, String) {
    match result {
        Err(Error::Scene { key, message, .. }) => (key, message),
        other => panic!("expected a scene error, got {other:?}"),
    }
}

/// Applies `overrides` to the default scene and validates it.
fn with(overrides: &[&str]) -> Result<Scene, Error> {
    let mut scene = Scene::default();
    for assignment in overrides {
        scene.apply_override(assignment)?;
    }
    scene.validate()?;
    Ok(scene)
}

/// Issue: `--set model.parameters.wavenumber=0.5` beside `model.wavenumber` was ignored.
#[test]
fn model_parameter_wavenumber_beside_model_wavenumber_is_refused() {
    let (key, message) = scene_error(with(&[
        "model.wavenumber=0.25",
        "model.parameters.wavenumber=0.5",
    ]));
    assert_eq!(key, "model.parameters.wavenumber");
    assert!(message.contains("`model.wavenumber`"), "{message}");
    assert!(message.contains("give one of the two"), "{message}");
}

/// Issue: with `wavenumber = "auto"` even `model.parameters.wavenumber = -0.2` was ignored.
#[test]
fn model_parameter_wavenumber_is_validated_and_fixes_the_wavenumber() {
    let (key, message) = scene_error(with(&["model.parameters.wavenumber=-0.2"]));
    assert_eq!(key, "model.parameters.wavenumber");
    assert!(message.contains("must be > 0"), "{message}");
    let scene = with(&["model.parameters.wavenumber=0.5"]).unwrap();
    assert_eq!(scene.model.wavenumber, Wavenumber::Fixed(0.5));
    assert!(scene.model.parameters.is_empty());
}

/// Issue: `model.parameters.young = -1` failed with "239 negative pivots" while
/// `material.young = -1` was a clean exit 2: a parameter is validated like its source key.
#[test]
fn model_parameter_young_is_validated_like_material_young() {
    for assignment in ["model.parameters.young=-1", "material.young=-1"] {
        let output = wrinkle(&["buckle", "--set", assignment]);
        let text = stderr(&output);
        assert_eq!(output.status.code(), Some(2), "{text}");
        let key = assignment.split('=').next().unwrap();
        assert!(text.contains(&format!("key `{key}`")), "{text}");
        assert!(text.contains("must be > 0"), "{text}");
    }
    let output = wrinkle(&["buckle", "--set", "model.parameters.young=1e308"]);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("key `model.parameters.young`"), "{text}");
    let scene = with(&[
        "model.parameters.young=1000",
        "model.parameters.direction=0.5",
    ])
    .unwrap();
    assert_eq!(scene.material.young_modulus, 1000.0);
    assert_eq!(scene.model.direction, Direction::Fixed(0.5f64.to_degrees()));
    assert!(scene.to_toml_string().contains("young = 1000.0"));
}

/// Issue: a scene giving both `max_amplitude_over_h` and the older `max_envelope_over_h`
/// silently took one.
#[test]
fn amplitude_target_and_its_older_spelling_together_are_refused() {
    let text = "[solver]\nmax_amplitude_over_h = 3\nmax_envelope_over_h = 1\n";
    let (key, message) = scene_error(Scene::from_toml_str(text, "both.toml"));
    assert!(
        key == "solver.max_envelope_over_h" || key == "solver.max_amplitude_over_h",
        "{key}"
    );
    assert!(message.contains("give one of the two"), "{message}");
    // Across a file and an override too; the same spelling overrides as always.
    let mut scene =
        Scene::from_toml_str("[solver]\nmax_envelope_over_h = 1\n", "old.toml").unwrap();
    let (key, message) = scene_error(scene.apply_override("solver.max_amplitude_over_h=3"));
    assert_eq!(key, "solver.max_amplitude_over_h");
    assert!(message.contains("scene old.toml"), "{message}");
    scene
        .apply_override("solver.max_envelope_over_h=2")
        .unwrap();
    assert_eq!(scene.solver.max_amplitude_over_thickness, 4.0);
}

/// Issue: `material.young = 1e308` failed with a NaN in matrix entry (0, 0) and a hint about
/// thickness and tension; derived products out of range name the key that drives them.
#[test]
fn young_modulus_of_1e308_is_refused_naming_material_young() {
    let output = wrinkle(&["buckle", "--set", "material.young=1e308"]);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("key `material.young`"), "{text}");
    assert!(text.contains("membrane stiffness"), "{text}");
    for (assignment, key, product) in [
        (
            "material.young=1e-100",
            "material.young",
            "membrane stiffness",
        ),
        (
            "material.thickness=1e-30",
            "material.thickness",
            "bending stiffness",
        ),
        ("load.tension_y=1e50", "load.tension_y", "tension strain"),
        ("material.young=1e-3", "material.young", "tension strain"),
    ] {
        let (found, message) = scene_error(with(&[assignment]));
        assert_eq!(found, key, "{assignment}: {message}");
        assert!(message.contains(product), "{assignment}: {message}");
    }
}

/// Issue: `mesh.nx = 100000, mesh.ny = 1` was inside the documented limits and still in the
/// wavenumber search after two minutes at 3 GB. Elements more than 50 times longer than wide
/// (grading included) are refused at once, and so are their relatives.
#[test]
fn mesh_of_100000_by_1_elements_is_refused_at_once() {
    let start = Instant::now();
    let output = wrinkle(&["buckle", "--set", "mesh.nx=100000", "--set", "mesh.ny=1"]);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("longer than wide"), "{text}");
    assert!(start.elapsed() < Duration::from_secs(10));
    for overrides in [
        &["mesh.nx=1", "mesh.ny=1000"][..],
        &["geometry.lx=1e6", "mesh.nx=4"],
        &["mesh.grading=50", "mesh.nx=64", "mesh.ny=8"],
    ] {
        let (key, message) = scene_error(with(overrides));
        assert!(key.starts_with("mesh."), "{overrides:?}: {key}: {message}");
        assert!(message.contains("longer than wide"), "{message}");
    }
    // The meshes of the examples and of the test suite stay accepted.
    for overrides in [
        &["mesh.nx=64", "mesh.ny=16"][..],
        &["mesh.nx=128", "mesh.ny=4"],
        &["mesh.grading=2", "mesh.nx=40", "mesh.ny=20"],
    ] {
        with(overrides).unwrap();
    }
}

/// Issue: a huge `solver.perturbation` failed with "residual above tolerance after 12
/// halvings"; an imperfection at or above the amplitude target "reached" it at λ = 0.
#[test]
fn perturbation_beyond_a_thickness_or_the_target_is_refused() {
    let (key, message) = scene_error(with(&["solver.perturbation=1e6"]));
    assert_eq!(key, "solver.perturbation");
    assert!(message.contains("at most 1"), "{message}");
    let (key, message) = scene_error(with(&["solver.perturbation=1e-300"]));
    assert_eq!(key, "solver.perturbation");
    assert!(message.contains("round-off"), "{message}");
    let (key, message) = scene_error(with(&["solver.max_amplitude_over_h=1e-6"]));
    assert_eq!(key, "solver.max_amplitude_over_h");
    assert!(message.contains("imperfection"), "{message}");
    with(&["solver.perturbation=0"]).unwrap();
}

/// Issue: two `output.vtu_loads` that print the same in the file name wrote one file over the
/// other; equal loads are refused, and the number of loads is bounded.
#[test]
fn equal_vtu_loads_and_too_many_are_refused() {
    let (key, message) = scene_error(with(&["output.vtu_loads=[0.1, 0.2, 0.1]"]));
    assert_eq!(key, "output.vtu_loads");
    assert!(message.contains("item 2"), "{message}");
    let many: Vec<String> = (0..101).map(|k| format!("{k}.0")).collect();
    let assignment = format!("output.vtu_loads=[{}]", many.join(","));
    let (key, message) = scene_error(with(&[assignment.as_str()]));
    assert_eq!(key, "output.vtu_loads");
    assert!(message.contains("at most 100"), "{message}");
}
