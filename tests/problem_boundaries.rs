//! Conditions on named boundaries (`[load.boundary.NAME]`, docs/scenes.md "Boundaries").
//!
//! * The presets are boundary specifications: example 1 written out by hand with
//!   `load.kind = "boundaries"` gives the biaxial preset's critical load bit for bit, and the
//!   strip's likewise.
//! * Hostile specifications and meshes — an unknown boundary, a malformed entry, a traction on
//!   a point, conflicting values at a corner, an in-plane problem left singular (translation or
//!   rotation), a mesh file that is missing, foreign, of another size, with an unsupported
//!   element, or without a group the scene names — each exit with code 2 and one line naming
//!   the key.

use std::process::{Command, Output};
use wrinkle::commands::buckle;
use wrinkle::scene::Scene;

fn wrinkle(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the wrinkle binary runs")
}

fn scene_with(settings: &[&str]) -> Scene {
    let mut scene = Scene::default();
    for setting in settings {
        scene.apply_override(setting).unwrap();
    }
    scene.validate().unwrap();
    scene
}

#[test]
fn example_one_written_out_by_hand_is_the_biaxial_preset_bit_for_bit() {
    let by_hand = scene_with(&[
        "load.kind=boundaries",
        "load.boundary.left={transverse=\"clamped\", in_plane={traction_per_load=[-1.0, 0.0]}}",
        "load.boundary.right={transverse=\"clamped\", in_plane={traction_per_load=[-1.0, 0.0]}}",
        "load.boundary.bottom={transverse=\"clamped\", in_plane={traction=[10.0, 0.0]}}",
        "load.boundary.top={transverse=\"clamped\", in_plane={traction=[10.0, 0.0]}}",
        "load.boundary.centre={in_plane=\"fixed\"}",
        "load.boundary.right_middle={in_plane={displacement=[\"free\", 0.0]}}",
        "model.wavenumber=0.2",
    ]);
    let preset = scene_with(&["model.wavenumber=0.2"]);
    let (a, b) = (
        buckle(&by_hand, true).unwrap().critical_load(),
        buckle(&preset, true).unwrap().critical_load(),
    );
    assert_eq!(a.to_bits(), b.to_bits(), "{a} vs {b}");
}

#[test]
fn the_strip_written_out_by_hand_is_the_strip_preset_bit_for_bit() {
    let common = [
        "geometry.lx=1400",
        "geometry.ly=200",
        "mesh.nx=28",
        "mesh.ny=8",
        "model.direction=90",
        "model.wavenumber=0.3",
    ];
    let mut by_hand = common.to_vec();
    by_hand.extend([
        "load.kind=boundaries",
        "load.boundary.left={transverse=\"clamped\", in_plane=\"fixed\"}",
        "load.boundary.right={transverse=\"clamped\", in_plane={displacement=[0.0, 0.0], displacement_per_load=[1.0, 0.0]}}",
    ]);
    let mut preset = common.to_vec();
    preset.push("load.kind=strip");
    let (a, b) = (
        buckle(&scene_with(&by_hand), true).unwrap().critical_load(),
        buckle(&scene_with(&preset), true).unwrap().critical_load(),
    );
    assert_eq!(a.to_bits(), b.to_bits(), "{a} vs {b}");
}

/// Runs `buckle` with `settings` and checks exit code 2, one line on stderr naming `key`
/// and containing `words`.
fn refused(settings: &[&str], key: &str, words: &str) {
    let mut arguments = vec!["buckle"];
    for setting in settings {
        arguments.extend(["--set", setting]);
    }
    let output = wrinkle(&arguments);
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{settings:?}: {stderr}");
    assert_eq!(stderr.lines().count(), 1, "{settings:?}: {stderr}");
    assert!(
        stderr.contains(key),
        "{settings:?}: `{key}` not in {stderr}"
    );
    assert!(
        stderr.contains(words),
        "{settings:?}: `{words}` not in {stderr}"
    );
}

#[test]
fn hostile_boundary_specifications_exit_2_naming_the_key() {
    refused(
        &["load.boundary.middle={in_plane=\"fixed\"}"],
        "load.boundary.middle",
        "no boundary `middle`",
    );
    refused(
        &["load.boundary.top={transverse=\"glued\"}"],
        "load.boundary.top",
        "\"simply_supported\"",
    );
    refused(
        &["load.boundary.top={in_plane={displacement=[1.0]}}"],
        "load.boundary.top",
        "expected [X, Y]",
    );
    refused(
        &[
            "load.boundary.top={in_plane={displacement=[\"free\", 0.0], displacement_per_load=[1.0, 0.0]}}",
        ],
        "load.boundary.top",
        "\"free\" in one of",
    );
    refused(
        &["load.boundary.top={in_plane={displacement=[0.0, 0.0], traction=[1.0, 0.0]}}"],
        "load.boundary.top",
        "give one",
    );
    refused(
        &["load.boundary.top={in_plane={pressure=1.0}}"],
        "load.boundary.top",
        "unknown key `pressure`",
    );
    refused(
        &["load.boundary.top={}"],
        "load.boundary.top",
        "empty boundary table",
    );
    refused(
        &["load.boundary.centre={in_plane={traction=[1.0, 0.0]}}"],
        "load.boundary.centre",
        "point set",
    );
    // The strip's right end moves with λ; a fixed bottom edge holds its corner at u = 0.
    refused(
        &[
            "load.kind=strip",
            "load.boundary.bottom={in_plane=\"fixed\"}",
        ],
        "load.boundary",
        "conflicting boundary values",
    );
}

#[test]
fn a_singular_in_plane_problem_names_the_missing_constraint() {
    // Tractions alone hold nothing.
    refused(
        &[
            "load.kind=boundaries",
            "load.boundary.left={transverse=\"clamped\", in_plane={traction_per_load=[-1.0, 0.0]}}",
            "load.boundary.right={transverse=\"clamped\", in_plane={traction_per_load=[-1.0, 0.0]}}",
        ],
        "load.boundary",
        "rigid translation along X",
    );
    // The biaxial preset without its second support turns about the centre.
    refused(
        &["load.boundary.right_middle={in_plane=\"free\"}"],
        "load.boundary",
        "rigid rotation in the plane (about (200.000000, 100.000000))",
    );
    // Held along X only.
    refused(
        &[
            "load.boundary.centre={in_plane={displacement=[0.0, \"free\"]}}",
            "load.boundary.right_middle={in_plane=\"free\"}",
        ],
        "load.boundary",
        "rigid translation along Y",
    );
}

#[test]
fn hostile_mesh_files_exit_2_naming_the_file_or_the_group() {
    let rectangle = "mesh.file=\"examples/meshes/example1_rectangle.msh\"";
    refused(
        &["mesh.file=\"examples/meshes/no_such_file.msh\""],
        "mesh.file",
        "cannot read",
    );
    refused(
        &["mesh.file=\"examples/scenes/long_strip.toml\""],
        "mesh.file",
        "Gmsh file",
    );
    refused(
        &[rectangle, "geometry.lx=300"],
        "geometry.lx",
        "set geometry.lx = 400",
    );
    refused(
        &[rectangle, "load.boundary.hole={transverse=\"free\"}"],
        "load.boundary.hole",
        "no boundary `hole`",
    );
    refused(
        &[
            rectangle,
            "load.kind=strip",
            "load.boundary.top={in_plane=\"fixed\"}",
            "load.boundary.left={in_plane={displacement=[\"free\", 0.0]}}",
        ],
        "load.boundary",
        "conflicting",
    );
    // A copy of the shipped file whose quadrilaterals claim to be 9-node ones (type 10).
    let text = std::fs::read_to_string("examples/meshes/example1_rectangle.msh").unwrap();
    let block = text
        .lines()
        .find(|line| line.starts_with("2 ") && line.split_whitespace().nth(2) == Some("16"))
        .unwrap()
        .to_string();
    let changed = text.replacen(&block, &block.replacen(" 16 ", " 10 ", 1), 1);
    let path = format!("{}/quad9.msh", env!("CARGO_TARGET_TMPDIR"));
    std::fs::write(&path, changed).unwrap();
    refused(
        &[&format!("mesh.file=\"{path}\"")],
        "mesh.file",
        "is of type 10 (9-node quadrangle)",
    );
}
