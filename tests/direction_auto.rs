//! `model.direction = "auto"`: the wave direction chosen where the threshold is lowest.
//!
//! * Example 1 (THEORY.md §8: clamped 400 × 200 mm rectangle, $`\lambda = -N_X`$, $`N_Y`$ = 10
//!   N/mm), reference envelope on 16 × 8: the load compresses along X, and the threshold rises
//!   steeply off it ($`N_Y Q^2\sin^2\theta`$ adds to it: about 0.167 N/mm at ±5° against 0.0895):
//!   "auto" must give 0° and the very threshold of `model.direction = 0`.
//! * Pure shear of a clamped square (200 × 200 mm, h = 0.05 mm) under an isotropic tension
//!   $`T`$ = 1 N/mm plus a shear $`N_{XY} = \lambda`$ applied by tangential tractions: the
//!   membrane force $`T\,\mathbf I + \lambda(\mathbf e_X\mathbf e_Y^T + \mathbf e_Y\mathbf e_X^T)`$
//!   is uniform, with principal compression $`T - \lambda`$ along $`-45°`$ (closed form). The
//!   square and the state are symmetric about the diagonal, so $`\lambda_c(\theta)`$ is symmetric
//!   about $`-45°`$: "auto" must give exactly $`-45°`$ and the threshold of
//!   `model.direction = -45`.

use wrinkle::Scene;
use wrinkle::threshold::buckle;

const PURE_SHEAR: &str = r#"
[geometry]
lx = 200.0
ly = 200.0

[material]
young = 70000.0
poisson = 0.3
thickness = 0.05

[model]
name = "reference-envelope"
direction = "auto"

[mesh]
nx = 12
ny = 12

[load]
kind = "boundaries"

[load.boundary.bottom]
transverse = "clamped"
in_plane = { traction = [1.0, 0.0], traction_per_load = [0.0, -1.0] }

[load.boundary.top]
transverse = "clamped"
in_plane = { traction = [1.0, 0.0], traction_per_load = [0.0, -1.0] }

[load.boundary.left]
transverse = "clamped"
in_plane = { traction = [1.0, 0.0], traction_per_load = [0.0, 1.0] }

[load.boundary.right]
transverse = "clamped"
in_plane = { traction = [1.0, 0.0], traction_per_load = [0.0, 1.0] }

[load.boundary.centre]
in_plane = "fixed"

[load.boundary.right_middle]
in_plane = { displacement = ["free", 0.0] }

[validity]
accept = ["all"]
"#;

fn scene(text: &str, sets: &[&str]) -> Scene {
    let mut scene = Scene::from_toml_str(text, "test scene").unwrap();
    for set in sets {
        scene.apply_override(set).unwrap();
    }
    scene.validate().unwrap();
    scene
}

#[test]
fn auto_direction_on_example_one_is_the_explicit_angle() {
    let base = ["mesh.nx = 16", "mesh.ny = 8"];
    let fixed = buckle(&scene("", &base), true).unwrap();
    let auto = buckle(
        &scene("", &[base[0], base[1], "model.direction = \"auto\""]),
        true,
    )
    .unwrap();
    assert_eq!(auto.direction_degrees, 0.0);
    assert_eq!(auto.direction_source, "auto (lowest threshold)");
    assert_eq!(auto.critical_load(), fixed.critical_load());
    assert_eq!(auto.wavenumber, fixed.wavenumber);
    let note = auto.notes.iter().find(|n| n.contains("direction")).unwrap();
    assert!(note.contains("the load rate compresses along 0°"), "{note}");
}

#[test]
fn auto_direction_of_pure_shear_is_minus_45_degrees() {
    let auto = buckle(&scene(PURE_SHEAR, &[]), true).unwrap();
    assert_eq!(auto.direction_degrees, -45.0, "{:?}", auto.notes);
    let fixed = buckle(&scene(PURE_SHEAR, &["model.direction = -45.0"]), true).unwrap();
    assert_eq!(auto.critical_load(), fixed.critical_load());
    // The principal compression T − λ changes sign at λ = T = 1 N/mm: the threshold is above.
    assert!(fixed.critical_load() > 1.0, "{}", fixed.critical_load());
}
