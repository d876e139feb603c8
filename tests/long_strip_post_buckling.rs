//! Post-buckling of the long strip in uniaxial traction (the paper's example 2,
//! `examples/scenes/long_strip.toml`) with the default path method, ANM with Padé approximants.
//!
//! The strip's bifurcation is nearly perfect: the imperfection barely projects on the mode, so
//! the singular part of the series is tiny until the path is close to λ_c. On this mesh a Padé
//! step from λ ≈ 0.05 met Padé's own accuracy criterion all the way past λ_c = 14.47 mm and
//! ended on the unstable fundamental branch (2 negative pivots), and the path then wandered on
//! unstable branches to λ = 36 instead of 24.6. The jump guard of the ANM redoes such a step
//! with the series' range. Expected:
//! * the guard acted at least once (a step whose Padé range was longer than the step it took);
//! * the tangent is positive definite at the start of every step (the path stays on the stable,
//!   wrinkled branch);
//! * every point is at the residual tolerance, the target is reached, and the bifurcation is
//!   detected within 1e-4 of the linear buckling load of the same mesh.

use std::path::Path;
use wrinkle::output::PathPoint;
use wrinkle::run::run;
use wrinkle::scene::Scene;

#[test]
fn long_strip_pade_steps_never_jump_onto_the_unstable_branch() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/long_strip.toml");
    let mut scene = Scene::load(&path).unwrap();
    for setting in [
        "output.plots=false",
        "output.vtu=false",
        "output.surface=false",
    ] {
        scene.apply_override(setting).unwrap();
    }
    scene.validate().unwrap();
    assert!(scene.solver.pade, "Padé is the default");
    let dir = std::env::temp_dir().join(format!("wrinkle-test-strip-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let report = run(&scene, &dir, true).unwrap();
    assert!(report.failure.is_none());
    let summary = &report.summary;

    let steps = summary["anm_steps"].as_array().unwrap();
    let refused = steps.iter().filter(|s| {
        let length = s["step_length"].as_f64().unwrap();
        let series = s["series_step_length"].as_f64().unwrap();
        s["pade_step_length"]
            .as_f64()
            .is_some_and(|pade| pade > length && length == series)
    });
    assert!(refused.count() >= 1, "the jump guard never acted");
    for s in steps {
        assert_eq!(s["negative_pivots"].as_u64(), Some(0), "{s}");
    }

    let points: Vec<PathPoint> = serde_json::from_value(summary["path"].clone()).unwrap();
    let worst = points.iter().map(|p| p.residual).fold(0.0, f64::max);
    assert!(worst <= 1e-6, "worst relative residual {worst:e}");
    let last = points.last().unwrap();
    let target = scene.solver.max_amplitude_over_thickness;
    assert!(last.max_amplitude_over_h >= target && last.max_amplitude_over_h < 1.2 * target);
    let lambda_c = summary["linear_buckling_load"].as_f64().unwrap();
    let detected = summary["detected_bifurcation"]["load"].as_f64().unwrap();
    assert!(
        (detected - lambda_c).abs() < 1e-4 * lambda_c,
        "{detected} vs {lambda_c}"
    );
    assert!(
        last.lambda > lambda_c && last.lambda < 2.0 * lambda_c,
        "{}",
        last.lambda
    );
    let _ = std::fs::remove_dir_all(&dir);
}
