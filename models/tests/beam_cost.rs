//! Cost of the full beam against its envelope models for the same accuracy: dofs and wall time
//! (ignored: run with `cargo test -p wrinkle-models --test beam_cost -- --ignored --nocapture`;
//! the test profile is optimised, opt-level 2).
//!
//! Case: the hardening beam of `beam_postbuckling.rs` ($`c_3 = 2`$, clamped, `beam_support`'s
//! $`EI = c = 1`$, $`h = 0.1`$) at 30 wavelengths (at 100 the full beam's Newton continuation in the load stalls where waves enter at the clamped ends, near 1.04–1.07 λ_c); the quantity is the amplitude at the middle
//! at $`\lambda = 1.1\lambda_c`$ (about $`3.7h`$), reached by a 41-load Newton
//! continuation from the model's threshold, geometric in the load's distance to the target. Each model on a sequence of uniform meshes; the error is
//! against its own finest mesh; the time is buckling plus continuation, wall clock.

mod beam_support;

use std::time::Instant;

use beam_support::*;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::problem::Problem;

const HARDENING: f64 = 2.0;
const WAVELENGTHS: f64 = 30.0;

/// Amplitude at the middle at the last load (NaN when the continuation failed), free dofs and
/// seconds.
fn measure<M: EnergyModel>(problem: &Problem<M>) -> (f64, usize, f64)
where
    Problem<M>: Amplitude,
{
    let clock = Instant::now();
    let buckling = buckle(problem);
    let critical = buckling.critical_loads[0];
    // Geometric steps from 1e-4 of the way to the target: the first guess (the mode with the
    // Landau amplitude) must be close, and on a long beam the mode soon turns into a plateau.
    let target = 1.1 * critical_load();
    let loads: Vec<f64> = (0..=40)
        .map(|i| critical + (target - critical) * 10f64.powf(-4.0 * (1.0 - i as f64 / 40.0)))
        .collect();
    let landau = 9.0 * HARDENING / (16.0 * critical_wavenumber().powi(2));
    let (path, failure) = continuation_to(problem, &buckling, landau, &loads, 1e-8);
    let seconds = clock.elapsed().as_secs_f64();
    if let Some(failure) = failure {
        println!("  ({} dofs) {failure}", problem.free_count());
        return (f64::NAN, problem.free_count(), seconds);
    }
    (
        path.last().unwrap().amplitude,
        problem.free_count(),
        seconds,
    )
}

fn table(label: &str, rows: Vec<(f64, (f64, usize, f64))>) {
    let reference = rows.last().unwrap().1.0;
    println!("{label}: elements per wavelength, dofs, seconds, a/h, error against the finest");
    for (per_wavelength, (amplitude, dofs, seconds)) in rows {
        println!(
            "  {per_wavelength:6.2}  {dofs:6}  {seconds:8.3}  {:.5}  {:+.2e}",
            amplitude / THICKNESS,
            amplitude / reference - 1.0
        );
    }
}

#[test]
#[ignore = "timing table for the note: run with --ignored --nocapture"]
fn beam_full_against_envelopes_dofs_and_time_for_the_same_accuracy() {
    let length = length_of(WAVELENGTHS);
    let elements = |per: f64| (WAVELENGTHS * per).round() as usize;
    let full_rows = [4.0, 6.0, 8.0, 12.0, 16.0, 24.0]
        .iter()
        .map(|&p| {
            (
                p,
                measure(&full(length, elements(p), HARDENING, Ends::Clamped)),
            )
        })
        .collect();
    table("beam-full (Hermite2)", full_rows);
    let envelope_rows = [0.25, 0.5, 1.0, 2.0, 4.0, 8.0]
        .iter()
        .map(|&p| (p, measure(&envelope(length, elements(p), HARDENING))))
        .collect();
    table("beam-envelope (Line3)", envelope_rows);
    let complex_rows = [0.25, 0.5, 1.0, 2.0, 4.0, 8.0]
        .iter()
        .map(|&p| {
            (
                p,
                measure(&complex_envelope(length, elements(p), HARDENING)),
            )
        })
        .collect();
    table("beam-complex-envelope (Line3)", complex_rows);
}
