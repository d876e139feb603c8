//! Renders sample plots with realistic data for visual inspection:
//! `cargo test -p wrinkle --test output_samples -- --ignored`, then open the PNG files in
//! `$TMPDIR/wrinkle-output-samples/`.

use std::f64::consts::PI;
use wrinkle::output::{
    Curve, CurveStyle, VerticalMarker, grid_cell_centres, plot_map, plot_profiles, plot_response,
};

#[test]
#[ignore = "writes sample pictures for a human to look at"]
fn render_sample_plots() {
    let dir = std::env::temp_dir().join("wrinkle-output-samples");
    std::fs::create_dir_all(&dir).unwrap();

    // Amplitude rising like a square root from the threshold 0.09; the FE path has step ends
    // every few dense-output points and drifts slightly from the closed form at large loads.
    let threshold = 0.09;
    let closed_form = |lambda: f64| 2.1 * ((lambda - threshold).max(0.0) / threshold).sqrt();
    let fe: Vec<(f64, f64)> = (0..=90)
        .map(|k| {
            let lambda = 0.06 + 0.0015 * k as f64;
            let excess = (lambda - threshold).max(0.0);
            (lambda, closed_form(lambda) * (1.0 - 0.8 * excess))
        })
        .collect();
    let steps: Vec<(f64, f64)> = fe.iter().step_by(9).copied().collect();
    let reference: Vec<(f64, f64)> = (0..=200)
        .map(|k| {
            let lambda = 0.06 + 0.000675 * k as f64;
            (lambda, closed_form(lambda))
        })
        .collect();
    let curves = [
        Curve {
            label: "finite elements (ANM, ● step ends)".into(),
            points: fe,
            style: CurveStyle::LineWithMarkers(steps),
        },
        Curve::dashed("closed form (eq. 61)", reference),
    ];
    let markers = [
        VerticalMarker {
            label: "bifurcation λc = 0.090".into(),
            x: threshold,
        },
        VerticalMarker {
            label: "loss of ellipticity".into(),
            x: 0.17,
        },
    ];
    plot_response(
        &dir.join("response"),
        "Clamped rectangle 400 × 200 mm: wrinkle amplitude",
        &curves,
        "load parameter λ",
        "max |w_env| / h",
        &markers,
    )
    .unwrap();

    let profiles: Vec<Curve> = [0.1, 0.12, 0.14, 0.16]
        .iter()
        .map(|&lambda: &f64| {
            let amplitude = 2.0 * ((lambda - threshold) / threshold).sqrt();
            let points = (0..=200)
                .map(|i| {
                    let x = 2.0 * i as f64;
                    (
                        x,
                        amplitude
                            * (PI * x / 400.0)
                                .sin()
                                .powf(1.0 + 10.0 * (lambda - threshold)),
                    )
                })
                .collect();
            Curve::line(format!("λ = {lambda:.2}"), points)
        })
        .collect();
    plot_profiles(
        &dir.join("profiles"),
        "Envelope along Y = 100 mm",
        "X (mm)",
        &profiles,
    )
    .unwrap();

    for (length, name) in [(400.0, "map"), (1400.0, "map_long")] {
        let bounds = [0.0, length, 0.0, 200.0];
        let (nx, ny) = ((length as usize) * 2, 100);
        let values: Vec<f64> = grid_cell_centres(bounds, nx, ny)
            .into_iter()
            .map(|(x, y)| 2.0 * (PI * x / length).sin() * (PI * y / 200.0).sin() * (0.24 * x).cos())
            .collect();
        plot_map(
            &dir.join(name),
            &format!("Wrinkles w = 2 A cos(Q X) (mm), {length:.0} × 200 mm"),
            bounds,
            nx,
            ny,
            &values,
        )
        .unwrap();
    }
    eprintln!("samples in {}", dir.display());
}
