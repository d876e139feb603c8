//! The same post-buckling path traced by the ANM and by the Newton–Riks baseline, side by side:
//! steps, tangent factorisations, wall time, worst residual, and the agreement of the two curves.
//!
//! `cargo run --release --example anm_vs_riks -- [NX NY]` (default 40 × 20, the paper's
//! example 1 to envelope/h = 2). CI runs the reduced 16 × 8 version inside
//! `tests/example_one_post_buckling.rs`.

use wrinkle::output::PathPoint;
use wrinkle::run::run;
use wrinkle::scene::Scene;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    let nx = arguments
        .first()
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(40usize);
    let ny = arguments
        .get(1)
        .map(|s| s.parse())
        .transpose()?
        .unwrap_or(20usize);
    let base = std::env::temp_dir().join("wrinkle-anm-vs-riks");
    let mut rows = Vec::new();
    let mut curves: Vec<Vec<PathPoint>> = Vec::new();
    for method in ["anm", "riks"] {
        let mut scene = Scene::default();
        for setting in [
            format!("mesh.nx={nx}"),
            format!("mesh.ny={ny}"),
            format!("solver.method={method}"),
            "solver.max_steps=5000".to_string(),
            "output.plots=false".to_string(),
        ] {
            scene.apply_override(&setting)?;
        }
        let report = run(&scene, &base.join(method), false)?;
        let s = report.summary;
        let worst = s.path.iter().map(|p| p.residual).fold(0.0, f64::max);
        rows.push(format!(
            "{method:>5} | {:>5} | {:>15} | {:>10.2} | {:>9.2} | {:>9.2e} | {}",
            s.steps, s.statistics.factorizations, s.timings.path, s.timings.series, worst, s.stop
        ));
        curves.push(s.path);
    }
    println!("example 1, mesh {nx} x {ny}, path from 0 to envelope/h = 2");
    println!("method | steps | factorisations | path (s) | series (s) | worst res | stop");
    for row in rows {
        println!("{row}");
    }
    // Agreement: ANM max envelope/h interpolated at each Riks point past the threshold.
    let (anm, riks) = (&curves[0], &curves[1]);
    let mut worst: f64 = 0.0;
    for p in riks.iter().filter(|p| p.max_amplitude_over_h > 0.1) {
        if let Some(w) = anm.windows(2).find_map(|w| {
            (w[0].lambda <= p.lambda && p.lambda <= w[1].lambda && w[1].lambda > w[0].lambda).then(
                || {
                    let t = (p.lambda - w[0].lambda) / (w[1].lambda - w[0].lambda);
                    w[0].max_amplitude_over_h
                        + t * (w[1].max_amplitude_over_h - w[0].max_amplitude_over_h)
                },
            )
        }) {
            worst = worst.max((w - p.max_amplitude_over_h).abs() / p.max_amplitude_over_h);
        }
    }
    println!(
        "largest relative difference of max envelope/h (ANM interpolated at Riks points, envelope/h > 0.1): {worst:.2e}"
    );
    Ok(())
}
