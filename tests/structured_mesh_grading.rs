//! The structured rectangle graded along X and Y separately toward the edges and corners that
//! `mesh.refine_toward` names (`docs/scenes.md`, `[mesh]`): the mesh the keys make, and hostile
//! values refused with exit 2 naming the key.

use std::process::Command;
use wrinkle::scene::Scene;
use wrinkle::setup::build_mesh;

fn scene(settings: &[&str]) -> Result<Scene, wrinkle::Error> {
    let mut scene = Scene::default();
    for setting in settings {
        scene.apply_override(setting)?;
    }
    scene.validate()?;
    Ok(scene)
}

/// Element widths along X of the scene's mesh (first row of elements).
fn widths_x(scene: &Scene) -> Vec<f64> {
    let mesh = build_mesh(scene).unwrap();
    let xs = mesh.grid.unwrap().xs;
    xs.windows(2).map(|w| w[1] - w[0]).collect()
}

#[test]
fn the_grading_keys_make_the_mesh_they_say() {
    // Default: today's mesh, graded by `mesh.grading` toward all four edges.
    let plain = scene(&["mesh.grading=4"]).unwrap();
    let auto = scene(&["mesh.grading=4", "mesh.grading_x=\"auto\""]).unwrap();
    assert_eq!(widths_x(&plain), widths_x(&auto));
    let plain_mesh = build_mesh(&plain).unwrap();
    let written = build_mesh(&scene(&["mesh.grading_x=4", "mesh.grading_y=4"]).unwrap()).unwrap();
    assert_eq!(plain_mesh.nodes, written.nodes);
    // Toward the right edge only: smallest at X = L_X, ratio 6; Y stays uniform.
    let right = scene(&["mesh.grading_x=6", "mesh.refine_toward=[\"right\"]"]).unwrap();
    let widths = widths_x(&right);
    let (first, last) = (widths[0], widths[widths.len() - 1]);
    assert!((first / last - 6.0).abs() < 1e-9, "{widths:?}");
    let ys = build_mesh(&right).unwrap().grid.unwrap().ys;
    let heights: Vec<f64> = ys.windows(2).map(|w| w[1] - w[0]).collect();
    assert!(heights.iter().all(|h| (h - heights[0]).abs() < 1e-9));
    // A corner refines both of its edges.
    let corner = scene(&["mesh.grading=3", "mesh.refine_toward=[\"top_left\"]"]).unwrap();
    let grid = build_mesh(&corner).unwrap().grid.unwrap();
    assert!(grid.xs[1] - grid.xs[0] < grid.xs[32] - grid.xs[31]);
    assert!(grid.ys[16] - grid.ys[15] < grid.ys[1] - grid.ys[0]);
}

/// `wrinkle buckle --set KEY=VALUE`: exit code and standard error.
fn buckle(settings: &[&str]) -> (Option<i32>, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_wrinkle"));
    command.arg("buckle");
    for setting in settings {
        command.args(["--set", setting]);
    }
    let output = command.output().unwrap();
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn hostile_gradings_exit_2_naming_the_key() {
    for (settings, key, says) in [
        (&["mesh.grading_x=0.5"][..], "mesh.grading_x", "≥ 1"),
        (&["mesh.grading_y=51"][..], "mesh.grading_y", "at most 50"),
        (&["mesh.grading_x=nan"][..], "mesh.grading_x", ""),
        (&["mesh.grading_y=\"fine\""][..], "mesh.grading_y", "auto"),
        (
            &["mesh.refine_toward=[\"middle\"]"][..],
            "mesh.refine_toward",
            "expected one of",
        ),
        (
            &[
                "mesh.grading_y=3",
                "mesh.refine_toward=[\"left\", \"right\"]",
            ][..],
            "mesh.grading_y",
            "names neither `bottom` nor `top`",
        ),
        (
            &["mesh.grading=3", "mesh.refine_toward=[\"bottom\"]"][..],
            "mesh.grading",
            "along X",
        ),
        (
            &["mesh.grading_x=50", "mesh.nx=4", "mesh.ny=64"][..],
            "mesh.grading_x",
            "times longer than wide",
        ),
    ] {
        let (code, stderr) = buckle(settings);
        assert_eq!(code, Some(2), "{settings:?}: {stderr}");
        assert!(stderr.contains(key), "{settings:?}: {stderr}");
        assert!(stderr.contains(says), "{settings:?}: {stderr}");
    }
}
