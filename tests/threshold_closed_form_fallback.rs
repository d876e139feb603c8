//! The wavenumber search starts on the real mesh from the closed-form minimiser of eq. (42)
//! (`two_level_search` in `src/threshold.rs`). A model whose own minimum is elsewhere must not be
//! stopped there: the local search finds no minimum inside ±10 % of the guess, and the
//! two-level search (global scan on the half mesh, then the real mesh) takes over.
//!
//! Case: the reference envelope with its Young's modulus multiplied by 16 after the scene has
//! set it. Under the scene's load-controlled tractions the pre-buckling stresses do not depend
//! on the modulus, so only the bending stiffness $`D`$ grows 16 times; on eq. (42) the minimiser
//! scales as $`D^{-1/4}`$, so this model's wavenumber is about half the closed form's (which uses
//! the scene's material). Independent check, as in `clamped_rectangle_buckling.rs`: the FE
//! critical load at $`Q(1 \pm 1\%)`$ (fixed wavenumber) is above the one found.

use wrinkle::scene::Scene;
use wrinkle::setup::{build_problem, configure_model};
use wrinkle::threshold::{analyse, find_threshold};
use wrinkle_models::ReferenceEnvelope;
use wrinkle_runtime::EnergyModel;

/// Critical load and wavenumber of the stiffened envelope on `scene`, and the number of
/// analyses.
fn threshold(scene: &Scene) -> (f64, f64, usize) {
    let mut model = ReferenceEnvelope::from_parameters(&[0.0; 5]);
    configure_model(scene, &mut model, 1.0).unwrap();
    model.young *= 16.0;
    let mut problem = build_problem(scene, model).unwrap();
    let mut factor = analyse(&problem).unwrap();
    let found = find_threshold(scene, &mut problem, &mut factor, true).unwrap();
    (
        found.critical_load(),
        found.wavenumber.unwrap(),
        found.evaluations,
    )
}

#[test]
fn a_model_whose_minimum_is_far_from_the_closed_form_is_searched_globally() {
    // 16 × 8: the smallest mesh with a half mesh (two levels).
    let mut scene = Scene::default();
    scene.apply_override("mesh.nx=16").unwrap();
    scene.apply_override("mesh.ny=8").unwrap();
    let (_, q_closed) = scene.clamped_rectangle().critical_point().unwrap();
    let (load, q, evaluations) = threshold(&scene);
    eprintln!("Q {q:.6e} (closed form {q_closed:.6e}), λ_c {load:.8e}, {evaluations} analyses");
    // The minimum is far outside the local bracket of the closed form (±10 %) ...
    assert!(
        (q / q_closed - 0.5).abs() < 0.1,
        "Q / Q* = {}",
        q / q_closed
    );
    // ... found by more than the 3 analyses of a search that succeeds near the guess ...
    assert!(evaluations > 3, "{evaluations} analyses");
    // ... and it is an FE minimum: λ_c at Q(1 ∓ 1 %) is higher.
    for factor in [0.99, 1.01] {
        let mut fixed = scene.clone();
        fixed
            .apply_override(&format!("model.wavenumber={}", q * factor))
            .unwrap();
        let (neighbour, _, _) = threshold(&fixed);
        assert!(
            neighbour > load,
            "λ_c({factor} Q) = {neighbour:e} ≤ {load:e}"
        );
    }
}
