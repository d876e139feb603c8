//! Linear thresholds of the three beam models (THEORY.md §7, the paper's eqs 1–3, 5, 13–14)
//! against their closed forms for a finite length, converging at the element's rate.
//!
//! Source: the Swift–Hohenberg beam $`EI\,v'''' + \lambda v'' + c\,v = 0`$, whose infinite-beam
//! threshold is $`\lambda_c = 2\sqrt{EI\,c}`$ at $`Q = (c/EI)^{1/4}`$ (3). Parameters
//! (`beam_support`): $`EI = c = 1`$ ($`Q = 1`$, $`\lambda_c = 2`$), $`ES = 1200`$
//! ($`h = 0.1`$), an axial end force $`\lambda`$. Finite-length closed forms:
//! * `beam-full`, simply supported ($`v = 0`$ at both ends): $`\min_n EIk_n^2 + c/k_n^2`$,
//!   $`k_n = n\pi/L`$;
//! * `beam-envelope`, $`v_1 = 0`$ at both ends: $`(6EIQ^2k^2 + EIQ^4 + c)/(Q^2 + k^2)`$,
//!   $`k = \pi/L`$;
//! * `beam-complex-envelope`, $`a = b = 0`$ at both ends: the root of
//!   $`\beta^2 - 4\alpha\gamma = \alpha^2(2\pi/L)^2`$ (`beam_support`).
//!
//! Measured at $`L = 10.25`$ wavelengths (CI): `beam-full` on Hermite2 at 4, 8, 16 elements per
//! wavelength, errors and rates printed; the envelopes on Line3 at 2, 4, 8 elements over the
//! whole beam. Expected: rates near 4 ($`h^4`$ for both: cubic Hermite on a fourth-order
//! problem, quadratic Lagrange on a second-order one). The ignored test does 100.25
//! wavelengths.

mod beam_support;

use beam_support::*;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::problem::Problem;

/// $`\log_2`$ of successive error ratios (meshes halved each time).
fn rates(errors: &[f64]) -> Vec<f64> {
    errors.windows(2).map(|e| (e[0] / e[1]).log2()).collect()
}

/// Critical loads on a sequence of meshes, their errors against `exact`, and the rates.
fn convergence<M: EnergyModel>(
    label: &str,
    exact: f64,
    problems: impl Iterator<Item = Problem<M>>,
) -> (Vec<f64>, Vec<f64>) {
    let errors: Vec<f64> = problems
        .map(|problem| buckle(&problem).critical_loads[0] - exact)
        .collect();
    let rates = rates(&errors);
    let listed: Vec<String> = errors.iter().map(|e| format!("{e:.3e}")).collect();
    println!(
        "{label}: closed form {exact:.12}, errors [{}], rates {rates:.3?}",
        listed.join(", ")
    );
    (errors, rates)
}

/// Half-waves of the full beam's first mode: sign changes of $`v`$ at the nodes, plus one.
fn half_waves(problem: &Problem<wrinkle_models::BeamFull>, mode: &[f64]) -> usize {
    let global = global(problem, mode, 0.0);
    let dofs = problem.dofs();
    let values: Vec<f64> = (0..problem.assembler.mesh().nodes.len())
        .map(|node| global[dofs.global_index(node, 1, 0)])
        .filter(|v| v.abs() > 1e-9)
        .collect();
    values.windows(2).filter(|p| p[0] * p[1] < 0.0).count() + 1
}

fn full_threshold(wavelengths: f64, per_wavelength: &[usize]) {
    let length = length_of(wavelengths);
    let (exact, k) = full_simply_supported_closed_form(length);
    let elements = |e: usize| (wavelengths * e as f64).round() as usize;
    let (errors, rates) = convergence(
        "beam-full (simply supported, Hermite2)",
        exact,
        per_wavelength
            .iter()
            .map(|&e| full(length, elements(e), 0.0, Ends::SimplySupported)),
    );
    assert!(errors.iter().all(|&e| e > 0.0), "from above: {errors:?}");
    assert!(rates.iter().all(|&r| r > 3.8), "rates {rates:?}");
    assert!(errors.last().unwrap().abs() < 1e-5 * exact);
    // The mode is the closed form's: n = kL/π half-waves; the finite length moves λ by
    // λ(k) − λ_c ≈ 4 EI (k − Q)².
    let finest = full(
        length,
        elements(*per_wavelength.last().unwrap()),
        0.0,
        Ends::SimplySupported,
    );
    let result = buckle(&finest);
    let n = (k * length / std::f64::consts::PI).round() as usize;
    assert_eq!(half_waves(&finest, &result.modes[0]), n);
    assert!((k - critical_wavenumber()).abs() <= std::f64::consts::PI / length);
    assert!(exact - critical_load() <= 4.0 * EI * (std::f64::consts::PI / length).powi(2));
    println!(
        "  n = {n}, k = {k:.6}, λ(k) − λ_c = {:.3e}",
        exact - critical_load()
    );
}

fn envelope_thresholds(wavelengths: f64, elements: &[usize]) {
    let length = length_of(wavelengths);
    let q = critical_wavenumber();
    let exact = envelope_closed_form(length, q);
    let (errors, rates) = convergence(
        "beam-envelope (v1 = 0 at the ends, Line3)",
        exact,
        elements.iter().map(|&n| envelope(length, n, 0.0)),
    );
    assert!(errors.iter().all(|&e| e > 0.0), "from above: {errors:?}");
    assert!(rates.iter().all(|&r| r > 3.8), "rates {rates:?}");
    let complex = complex_envelope_closed_form(length, q);
    let (complex_errors, complex_rates) = convergence(
        "beam-complex-envelope (a = b = 0 at the ends, Line3)",
        complex,
        elements.iter().map(|&n| complex_envelope(length, n, 0.0)),
    );
    assert!(
        complex_errors.iter().all(|&e| e > 0.0),
        "{complex_errors:?}"
    );
    assert!(
        complex_rates.iter().all(|&r| r > 3.8),
        "rates {complex_rates:?}"
    );
    // Both tend to λ_c as 4 EI (π/L)² (the finite-length correction of an envelope pinned at
    // the ends); the complex one, whose phase may drift, lies below the real one.
    let correction = 4.0 * EI * (std::f64::consts::PI / length).powi(2);
    for (name, value) in [("real", exact), ("complex", complex)] {
        let relative = (value - critical_load()) / correction - 1.0;
        println!(
            "  {name}: λ − λ_c = {:.6e} = 4EI(π/L)² (1 {relative:+.3e})",
            value - critical_load()
        );
        assert!(relative.abs() < 0.05);
    }
    assert!(complex < exact);
}

#[test]
fn beam_full_simply_supported_threshold_converges_as_h4_to_min_n_eik2_plus_c_over_k2() {
    full_threshold(10.25, &[8, 16, 32]);
}

#[test]
fn beam_envelopes_thresholds_converge_as_h4_to_their_finite_length_closed_forms() {
    envelope_thresholds(10.25, &[2, 4, 8]);
}

/// Compression by end displacement: the pre-buckling force is $`ES\,\lambda/L`$ for a
/// shortening $`\lambda`$, so the critical shortening is the critical force times $`L/ES`$, on
/// the same mesh to round-off.
#[test]
fn beam_end_shortening_thresholds_are_the_force_thresholds_times_length_over_es() {
    let wavelengths = 10.25;
    let length = length_of(wavelengths);
    let elements = (wavelengths * 16.0) as usize;
    let pairs = [
        (
            buckle(&full_shortened(length, elements, Ends::Clamped)).critical_loads[0],
            buckle(&full(length, elements, 0.0, Ends::Clamped)).critical_loads[0],
        ),
        (
            buckle(&envelope_shortened(length, 8)).critical_loads[0],
            buckle(&envelope(length, 8, 0.0)).critical_loads[0],
        ),
    ];
    for (shortening, force) in pairs {
        let relative = shortening * ES / length / force - 1.0;
        println!("critical shortening {shortening:.10} mm, force {force:.10} N: {relative:+.1e}");
        assert!(relative.abs() < 1e-9, "{relative:e}");
    }
}

#[test]
#[ignore = "100 wavelengths: run with --ignored"]
fn beam_thresholds_at_a_hundred_wavelengths() {
    full_threshold(100.25, &[8, 16, 32]);
    envelope_thresholds(100.25, &[2, 4, 8]);
}
