//! The paper's example 2 (the long strip, `examples/scenes/long_strip.toml`) converged by a
//! graded mesh: `docs/validation.md`, "Long strip: mesh convergence".
//!
//! Source: the refinement study of `docs/validation.md` — `reference-envelope`, wavenumber
//! searched, uniform meshes 56 × 16 … 280 × 80 and meshes graded toward the four clamped–free
//! corners (ratio 6, 12, 24) up to 224 × 64; three-point Richardson extrapolation of the graded
//! families gives the converged onset $`\lambda_c^\infty = 14.3445`$ mm (±0.0003). Expected: the
//! shipped scene (56 × 16, graded 12 along X and Y toward the corners) within 0.3 % of it
//! (measured +0.21 %), and better than the uniform mesh of the same size, 8 301 dofs (+0.87 %),
//! by at least a factor 3. Reduced here to the two meshes of equal size (about a second each).

use wrinkle::commands::buckle;
use wrinkle::scene::Scene;

/// Converged envelope onset of the strip (mm of end displacement), `docs/validation.md`.
const CONVERGED_ONSET: f64 = 14.3445;

fn strip(settings: &[&str]) -> Scene {
    let path = format!(
        "{}/examples/scenes/long_strip.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    let mut scene = Scene::load(path).unwrap();
    for setting in settings {
        scene.apply_override(setting).unwrap();
    }
    scene.validate().unwrap();
    scene
}

#[test]
fn the_graded_strip_converges_faster_than_the_uniform_one_at_equal_dofs() {
    let graded = buckle(&strip(&[]), true).unwrap();
    let uniform = buckle(
        &strip(&[
            "mesh.grading_x=1",
            "mesh.grading_y=1",
            "mesh.refine_toward=\"edges\"",
        ]),
        true,
    )
    .unwrap();
    assert_eq!(graded.dofs, uniform.dofs);
    let error = |onset: f64| onset / CONVERGED_ONSET - 1.0;
    let (graded_error, uniform_error) = (
        error(graded.critical_load()),
        error(uniform.critical_load()),
    );
    eprintln!(
        "{} dofs: graded λ_c = {:.6} mm ({:+.3} %), uniform λ_c = {:.6} mm ({:+.3} %)",
        graded.dofs,
        graded.critical_load(),
        100.0 * graded_error,
        uniform.critical_load(),
        100.0 * uniform_error
    );
    assert!(graded_error.abs() < 3e-3, "{graded_error:e}");
    assert!(
        graded_error.abs() < uniform_error.abs() / 3.0,
        "{graded_error:e} vs {uniform_error:e}"
    );
    // The uniform mesh is the shipped scene before grading: 14.470 mm (0.87 % above).
    assert!((uniform.critical_load() - 14.470).abs() < 1e-3);
}
