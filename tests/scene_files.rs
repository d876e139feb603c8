//! Scene parsing: the example scenes, `--set` overrides, validation errors (docs/scenes.md).

use std::collections::BTreeMap;
use std::path::PathBuf;
use wrinkle::Error;
use wrinkle::scene::{Direction, LoadKind, PathMethod, Scene, Wavenumber};

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("examples/scenes")
        .join(name)
}

/// The one-line rendering of a scene error, and its parts.
fn scene_error(result: Result<impl std::fmt::Debug, Error>) -> (String, String, String, String) {
    let error = result.expect_err("expected a scene error");
    assert_eq!(error.exit_code(), 2, "scene errors exit with 2: {error}");
    let line = error.to_string();
    assert!(!line.contains('\n'), "error must fit on one line: {line:?}");
    match error {
        Error::Scene {
            source,
            key,
            message,
        } => (line, source, key, message),
        other => panic!("expected Error::Scene, got {other:?}"),
    }
}

#[test]
fn clamped_biaxial_example_equals_the_default_scene_field_by_field() {
    let scene = Scene::load(example("clamped_biaxial.toml")).unwrap();
    let default = Scene::default();
    assert_eq!(scene.geometry, default.geometry);
    assert_eq!(scene.material, default.material);
    assert_eq!(scene.model, default.model);
    assert_eq!(scene.mesh, default.mesh);
    assert_eq!(scene.load, default.load);
    assert_eq!(scene.solver, default.solver);
    assert_eq!(scene.output, default.output);
    assert!(scene.source.ends_with("clamped_biaxial.toml"));
    // The defaults are the paper's example 1 (THEORY.md §9).
    assert_eq!(
        (default.geometry.length_x, default.geometry.length_y),
        (400.0, 200.0)
    );
    assert_eq!(default.material.thickness, 0.05);
    assert_eq!(default.material.young_modulus, 70000.0);
    assert_eq!(default.material.poisson_ratio, 0.3);
    assert_eq!(default.load.tension_y, 10.0);
    assert_eq!(default.load.kind, LoadKind::Biaxial);
}

#[test]
fn long_strip_example_is_the_papers_example_two() {
    let scene = Scene::load(example("long_strip.toml")).unwrap();
    assert_eq!(
        (scene.geometry.length_x, scene.geometry.length_y),
        (1400.0, 200.0)
    );
    assert_eq!(scene.material.thickness, 0.05);
    assert_eq!(scene.material.young_modulus, 70000.0);
    assert_eq!(scene.material.poisson_ratio, 0.3);
    assert_eq!(scene.load.kind, LoadKind::Strip);
    assert_eq!(scene.model.direction, Direction::Fixed(90.0));
    assert_eq!((scene.mesh.elements_x, scene.mesh.elements_y), (56, 16));
    assert_eq!(scene.model.wavenumber, Wavenumber::Auto);
}

#[test]
fn empty_scene_gives_the_defaults_and_partial_scene_changes_only_its_keys() {
    let empty = Scene::from_toml_str("", "empty.toml").unwrap();
    assert_eq!(
        Scene {
            source: Scene::default().source,
            ..empty
        },
        Scene::default()
    );
    let partial = Scene::from_toml_str(
        "[mesh]\nnx = 8\n[model]\nwavenumber = 0.25\n",
        "partial.toml",
    )
    .unwrap();
    assert_eq!(partial.mesh.elements_x, 8);
    assert_eq!(partial.mesh.elements_y, 16);
    assert_eq!(partial.model.wavenumber, Wavenumber::Fixed(0.25));
    assert_eq!(partial.material, Scene::default().material);
}

#[test]
fn integers_are_accepted_where_numbers_are_expected() {
    let scene = Scene::from_toml_str("[geometry]\nlx = 300\n", "integers.toml").unwrap();
    assert_eq!(scene.geometry.length_x, 300.0);
}

#[test]
fn overrides_parse_toml_values_and_bare_words() {
    let mut scene = Scene::default();
    for assignment in [
        "material.poisson=0.25",
        "model.wavenumber=auto",
        "load.kind=strip",
        "solver.method=\"riks\"",
        "solver.pade=false",
        "output.vtu_loads=[0.1, 2]",
        "mesh.nx = 12",
        "model.parameters.delta=1e-3",
        "model.name=pure-membrane",
    ] {
        scene.apply_override(assignment).unwrap();
    }
    assert_eq!(scene.material.poisson_ratio, 0.25);
    assert_eq!(scene.model.wavenumber, Wavenumber::Auto);
    assert_eq!(scene.load.kind, LoadKind::Strip);
    assert_eq!(scene.solver.method, PathMethod::Riks);
    assert!(!scene.solver.pade);
    assert_eq!(scene.output.vtu_loads, vec![0.1, 2.0]);
    assert_eq!(scene.mesh.elements_x, 12);
    assert_eq!(
        scene.model.parameters,
        BTreeMap::from([("delta".to_string(), 1e-3)])
    );
    assert_eq!(scene.model.name, "pure-membrane");
    scene.apply_override("model.wavenumber=0.3").unwrap();
    scene
        .apply_override("geometry={ lx = 500, ly = 100.0 }")
        .unwrap();
    assert_eq!(
        (scene.geometry.length_x, scene.geometry.length_y),
        (500.0, 100.0)
    );
    assert_eq!(scene.model.wavenumber, Wavenumber::Fixed(0.3));
}

#[test]
fn out_of_range_override_names_the_override_and_the_key() {
    let mut scene = Scene::default();
    let (line, source, key, message) = scene_error(scene.apply_override("material.poisson=0.6"));
    assert_eq!(source, "--set material.poisson=0.6");
    assert_eq!(key, "material.poisson");
    assert_eq!(
        message,
        "must satisfy -0.99 ≤ ν < 0.5 (ν → −1 makes the in-plane problem singular), got 0.6"
    );
    assert_eq!(
        line,
        "--set material.poisson=0.6: key `material.poisson`: must satisfy -0.99 ≤ ν < 0.5 (ν → −1 makes the in-plane problem singular), got 0.6"
    );
}

#[test]
fn out_of_range_file_value_names_the_file_and_the_key() {
    let (line, _, key, _) = scene_error(Scene::from_toml_str(
        "[material]\npoisson = 0.6\n",
        "examples/scenes/x.toml",
    ));
    assert_eq!(key, "material.poisson");
    assert_eq!(
        line,
        "scene examples/scenes/x.toml: key `material.poisson`: must satisfy -0.99 ≤ ν < 0.5 (ν → −1 makes the in-plane problem singular), got 0.6"
    );
}

#[test]
fn range_violations_of_every_kind_are_reported() {
    let cases = [
        ("geometry.lx=0", "geometry.lx", "must be ≥ 1e-6"),
        ("geometry.ly=-1", "geometry.ly", "must be ≥ 1e-6"),
        ("material.young=0", "material.young", "must be > 0"),
        ("material.poisson=-1", "material.poisson", "-0.99 ≤ ν < 0.5"),
        (
            "material.thickness=-0.1",
            "material.thickness",
            "must be > 0",
        ),
        ("model.wavenumber=0", "model.wavenumber", "must be > 0"),
        ("model.wavenumber=inf", "model.wavenumber", "must be > 0"),
        (
            "model.direction=nan",
            "model.direction",
            "≥ -360 and at most 360",
        ),
        ("mesh.nx=0", "mesh.nx", "between 1 and"),
        ("mesh.ny=-2", "mesh.ny", "between 1 and"),
        ("mesh.grading=0.5", "mesh.grading", "≥ 1"),
        ("load.tension_y=-1", "load.tension_y", "≥ 0"),
        ("solver.order=1", "solver.order", "between 2 and 40"),
        ("solver.order=41", "solver.order", "between 2 and 40"),
        (
            "solver.series_tolerance=0",
            "solver.series_tolerance",
            "must be ≥ 1e-14",
        ),
        (
            "solver.tolerance=-1e-6",
            "solver.tolerance",
            "must be ≥ 1e-15",
        ),
        (
            "solver.max_steps=0",
            "solver.max_steps",
            "between 1 and 10000",
        ),
        ("solver.max_load=-1", "solver.max_load", "≥ 0"),
        (
            "solver.max_envelope_over_h=0",
            "solver.max_envelope_over_h",
            "as `solver.max_amplitude_over_h`: must be > 0",
        ),
        ("solver.perturbation=-1", "solver.perturbation", "≥ 0"),
        (
            "output.directory=\"\"",
            "output.directory",
            "must not be empty",
        ),
        ("output.vtu_loads=[1, nan]", "output.vtu_loads", "item 1"),
        ("model.name=\" \"", "model.name", "must not be empty"),
        ("model.parameters.q=inf", "model.parameters.q", "finite"),
    ];
    for (assignment, expected_key, expected_fragment) in cases {
        let mut scene = Scene::default();
        let (line, _, key, message) = scene_error(scene.apply_override(assignment));
        assert_eq!(key, expected_key, "{line}");
        assert!(message.contains(expected_fragment), "{line}");
    }
}

#[test]
fn wrong_types_say_what_was_expected_and_what_was_found() {
    let cases = [
        (
            "[geometry]\nlx = \"wide\"\n",
            "geometry.lx",
            "expected a number, got string \"wide\"",
        ),
        (
            "[mesh]\nnx = 2.5\n",
            "mesh.nx",
            "expected an integer, got float 2.5",
        ),
        (
            "[solver]\npade = 1\n",
            "solver.pade",
            "expected a boolean (true or false), got integer 1",
        ),
        (
            "[model]\nname = 3\n",
            "model.name",
            "expected a string, got integer 3",
        ),
        (
            "[model]\nwavenumber = \"big\"\n",
            "model.wavenumber",
            "or \"auto\", got string \"big\"",
        ),
        (
            "[load]\nkind = \"shear\"\n",
            "load.kind",
            "expected one of \"biaxial\", \"strip\", \"boundaries\", got \"shear\"",
        ),
        (
            "geometry = 3\n",
            "geometry",
            "expected a table, got integer 3",
        ),
        (
            "[output]\nvtu_loads = 1.0\n",
            "output.vtu_loads",
            "expected an array of numbers, got float 1",
        ),
        (
            "[output]\nvtu_loads = [1.0, \"x\"]\n",
            "output.vtu_loads",
            "item 1: expected a number",
        ),
    ];
    for (text, expected_key, expected_fragment) in cases {
        let (line, source, key, message) = scene_error(Scene::from_toml_str(text, "typed.toml"));
        assert_eq!(source, "scene typed.toml");
        assert_eq!(key, expected_key, "{line}");
        assert!(message.contains(expected_fragment), "{line}");
    }
}

#[test]
fn unknown_keys_suggest_the_closest_valid_key() {
    let (_, _, key, message) = scene_error(Scene::from_toml_str(
        "[material]\npoison = 0.3\n",
        "typo.toml",
    ));
    assert_eq!(key, "material.poison");
    assert_eq!(message, "unknown key; did you mean `material.poisson`?");
    let (_, _, key, message) = scene_error(Scene::from_toml_str(
        "[materail]\npoisson = 0.3\n",
        "typo.toml",
    ));
    assert_eq!(key, "materail");
    assert!(message.contains("did you mean `material`?"), "{message}");
    let mut scene = Scene::default();
    let (_, _, _, message) = scene_error(scene.apply_override("solver.max_step=3"));
    assert!(message.contains("`solver.max_steps`"), "{message}");
    let (_, _, _, message) = scene_error(scene.apply_override("material.zzzzzzzzzz=3"));
    assert!(
        message.contains("accepts young, poisson, thickness"),
        "{message}"
    );
}

#[test]
fn syntax_errors_give_the_line() {
    let text = "[geometry]\nlx = 400.0\nly = = 3\n";
    let (line, source, key, message) = scene_error(Scene::from_toml_str(text, "broken.toml"));
    assert_eq!(source, "scene broken.toml");
    assert!(key.is_empty());
    assert!(message.starts_with("TOML syntax error at line 3"), "{line}");
}

#[test]
fn missing_file_is_a_scene_error() {
    let (line, source, _, message) = scene_error(Scene::load("does/not/exist.toml"));
    assert_eq!(source, "scene does/not/exist.toml");
    assert!(message.starts_with("cannot read file"), "{line}");
}

#[test]
fn malformed_overrides_are_rejected() {
    let mut scene = Scene::default();
    for assignment in [
        "material.poisson",
        "=3",
        "material.=3",
        "material.poisson=",
        "model.name=1.2.3",
        "mesh.nx=[1",
        "material.poisson=0.6",
        "material={ poisson = 0.2, young = -1 }",
    ] {
        let (line, source, _, _) = scene_error(scene.apply_override(assignment));
        assert_eq!(source, format!("--set {assignment}"), "{line}");
    }
    assert_eq!(
        scene,
        Scene::default(),
        "failed overrides leave the scene unchanged"
    );
}

#[test]
fn validate_catches_values_set_through_the_fields() {
    let mut scene = Scene::default();
    scene.validate().unwrap();
    scene.mesh.grading = 0.9;
    let (line, source, key, _) = scene_error(scene.validate());
    assert_eq!(source, "scene <built-in default scene>");
    assert_eq!(key, "mesh.grading", "{line}");
}

#[test]
fn effective_toml_round_trips() {
    let mut scene = Scene::load(example("long_strip.toml")).unwrap();
    for assignment in [
        "model.wavenumber=0.1234567890123",
        "model.parameters.delta=1e-9",
        "model.parameters.\"odd name\"=2",
        "output.vtu_loads=[0.05, 0.1]",
        "output.directory=\"out dir/with \\\"quotes\\\"\"",
        "solver.pade=false",
        "mesh.grading=3.5",
        "output.surface=false",
        "validity.accept=[\"ellipticity\", \"mode_resolution\"]",
    ] {
        scene
            .apply_override(assignment)
            .unwrap_or_else(|error| panic!("{assignment}: {error}"));
    }
    let text = scene.to_toml_string();
    let reparsed = Scene::from_toml_str(&text, &scene.source).unwrap();
    assert_eq!(reparsed, scene, "{text}");
}

#[test]
fn json_echo_uses_the_scene_key_names() {
    let mut scene = Scene::default();
    scene.apply_override("model.wavenumber=0.2").unwrap();
    let echo = scene.echo_json();
    assert_eq!(echo["geometry"]["lx"], 400.0);
    assert_eq!(echo["material"]["poisson"], 0.3);
    assert_eq!(echo["model"]["wavenumber"], 0.2);
    assert_eq!(echo["mesh"]["nx"], 32);
    assert_eq!(echo["load"]["kind"], "biaxial");
    assert_eq!(echo["solver"]["max_amplitude_over_h"], 4.0);
    assert_eq!(echo["output"]["plots"], true);
    assert_eq!(Scene::default().echo_json()["model"]["wavenumber"], "auto");
}

#[test]
fn clamped_rectangle_of_the_default_scene_is_example_one() {
    assert_eq!(
        Scene::default().clamped_rectangle(),
        wrinkle::closed_form::ClampedRectangle::example_one()
    );
}

/// `model.wavenumber_model`, declared once in the schema: its default is the registry's reference
/// model (as `model.name`'s), it must name a registered model, and it is printed and echoed.
#[test]
fn wavenumber_model_defaults_to_the_reference_model_and_must_be_registered() {
    let scene = Scene::default();
    assert_eq!(
        scene.model.wavenumber_model,
        wrinkle_models::REFERENCE_MODEL
    );
    assert_eq!(scene.model.name, wrinkle_models::REFERENCE_MODEL);
    let mut scene = Scene::default();
    let (line, source, key, message) =
        scene_error(scene.apply_override("model.wavenumber_model=nope"));
    assert_eq!(source, "--set model.wavenumber_model=nope");
    assert_eq!(key, "model.wavenumber_model", "{line}");
    assert!(
        message.starts_with("unknown model `nope` (models: "),
        "{line}"
    );
    let (_, _, key, message) = scene_error(Scene::from_toml_str(
        "[model]\nwavenumber_model = 3\n",
        "typed.toml",
    ));
    assert_eq!(key, "model.wavenumber_model");
    assert_eq!(message, "expected a string, got integer 3");
    scene
        .apply_override("model.wavenumber_model=fvk-plate")
        .unwrap();
    let text = scene.to_toml_string();
    assert!(
        text.contains("\nwavenumber = \"auto\"\nwavenumber_model = \"fvk-plate\"\n"),
        "{text}"
    );
    assert_eq!(scene.echo_json()["model"]["wavenumber_model"], "fvk-plate");
    assert_eq!(Scene::from_toml_str(&text, &scene.source).unwrap(), scene);
}

#[test]
fn model_names_and_accepted_checks_are_validated_where_they_enter() {
    let mut scene = Scene::default();
    let (_, _, key, message) = scene_error(scene.apply_override("model.name=nope"));
    assert_eq!(key, "model.name");
    assert!(message.starts_with("unknown model `nope`"), "{message}");
    scene.validity.accept = vec!["bogus".to_string()];
    let (_, _, key, message) = scene_error(scene.validate());
    assert_eq!(key, "validity.accept");
    assert!(message.starts_with("item 0: expected one of"), "{message}");
}
