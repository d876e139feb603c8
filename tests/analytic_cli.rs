//! `wrinkle analytic` against values computed inside this test from the formulas of THEORY.md §8
//! (re-typed, not calling the library): the exact minimum of (42) through the root of its
//! stationarity quadratic, (44), (96), the Galerkin integrals I_1…I_4 by composite Simpson
//! quadrature of their one-dimensional factors, and C(α) of (62).
//!
//! Scenes (all clamped, biaxial, reference envelope, wave vector along X):
//! * default (the paper's example 1): 400 × 200 mm, h 0.05 mm, E 70000 MPa, ν 0.3, N_Y 10 N/mm;
//!   expected λ_c = 0.0895212413 N/mm (docs/validation.md), C(0.5) = 1.1303105782 one-term,
//!   1.0892638396 converged (the 100-term 40-digit reference of
//!   `tests/analytic_stress_function_galerkin.rs`; the tail beyond 100 terms is below 1e-10);
//! * 200 × 200 mm, N_Y 5 N/mm (Table 1's first row): λ_c = 0.0640597 N/mm, C(1) = 1.6509242685;
//! * 300 × 120 mm, h 0.1 mm, E 210000 MPa, ν 0.25, N_Y 4 N/mm.
//!
//! Tolerance 1e-9 relative. The strip scene must fail with exit code 2 naming `load.kind`.

use serde_json::Value;
use std::f64::consts::PI;
use std::process::{Command, Output};

fn wrinkle(arguments: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the wrinkle binary runs")
}

fn analytic_json(overrides: &[&str]) -> Value {
    let mut arguments = vec!["analytic", "--json"];
    for assignment in overrides {
        arguments.push("--set");
        arguments.push(assignment);
    }
    let output = wrinkle(&arguments);
    assert_eq!(
        output.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let text = String::from_utf8(output.stdout).unwrap();
    let value: Value = serde_json::from_str(&text).expect("exactly one JSON object");
    assert!(value.is_object());
    value
}

/// Composite Simpson rule with 4000 intervals on [−1, 1].
fn simpson(f: impl Fn(f64) -> f64) -> f64 {
    let intervals = 4000;
    let step = 2.0 / intervals as f64;
    let mut sum = f(-1.0) + f(1.0);
    for index in 1..intervals {
        let weight = if index % 2 == 1 { 4.0 } else { 2.0 };
        sum += weight * f(-1.0 + step * index as f64);
    }
    sum * step / 3.0
}

struct Expected {
    critical_load: f64,
    wavenumber: f64,
    critical_load_eq44: f64,
    wavenumber_eq44: f64,
    stress_eq44: f64,
    critical_load_eq96: f64,
    integrals: [f64; 4],
    amplitude_coefficient: f64,
}

/// THEORY.md §8, re-typed.
fn expected(lx: f64, ly: f64, h: f64, e: f64, nu: f64, ny: f64) -> Expected {
    let d = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
    // (42) in s = Q²: λ = (D s² + a s + b)/(s + c); dλ/ds = 0 ⇔ D s² + 2Dc s + ac − b = 0.
    let a = 6.0 * d * PI * PI / (lx * lx) + 2.0 * d * PI * PI / (ly * ly);
    let b = ny * PI * PI / (ly * ly);
    let c = PI * PI / (lx * lx);
    let s = -c + (c * c - (a * c - b) / d).sqrt();
    let q = s.sqrt();
    let lambda = (6.0 * d * q * q * PI * PI / (lx * lx)
        + (2.0 * d * q * q + ny) * PI * PI / (ly * ly)
        + d * q.powi(4))
        / (q * q + PI * PI / (lx * lx));
    let sigma_y = ny / h;
    let q_wr =
        (12.0 * PI * PI * (1.0 - nu * nu)).powf(0.25) / (h * ly).sqrt() * (sigma_y / e).powf(0.25);
    let stress_eq44 = PI / (3.0 * (1.0 - nu * nu)).sqrt() * (e * sigma_y).sqrt() * h / ly;
    let stress_eq96 = stress_eq44
        + e * PI * PI / (6.0 * (1.0 - nu * nu)) * (2.0 * h * h / (lx * lx) + h * h / (ly * ly));
    // W = F(r) F(s), F = (1 − x²)², F'' = 12x² − 4; w¹ = cos(πr/2) cos(πs/2); α = L_Y/L_X.
    let alpha = ly / lx;
    let f = |x: f64| (1.0 - x * x).powi(2);
    let f2 = |x: f64| 12.0 * x * x - 4.0;
    let mode = |x: f64| (PI * x / 2.0).cos().powi(2);
    let i1 = alpha.powi(4) * simpson(|x| f2(x).powi(2)) * simpson(|x| f(x).powi(2))
        + 2.0 * alpha * alpha * simpson(|x| f2(x) * f(x)).powi(2)
        + simpson(|x| f(x).powi(2)) * simpson(|x| f2(x).powi(2));
    let i2 = simpson(|r| (1.0 - (PI * (1.0 + r)).cos()) * f(r))
        * simpson(|s| (PI * (1.0 + s)).cos() * f(s));
    let i3 = simpson(mode).powi(2);
    let i4 = simpson(|r| f(r) * mode(r)) * simpson(|s| f2(s) * mode(s));
    Expected {
        critical_load: lambda,
        wavenumber: q,
        critical_load_eq44: 2.0 * d * q_wr * q_wr,
        wavenumber_eq44: q_wr,
        stress_eq44,
        critical_load_eq96: stress_eq96 * h,
        integrals: [i1, i2, i3, i4],
        amplitude_coefficient: (2.0 * i1 * i3 / (3.0 * PI * PI * (1.0 - nu * nu) * i2 * i4)).sqrt(),
    }
}

fn assert_close(json: &Value, key: &str, expected: f64, tolerance: f64) {
    let value = json[key]
        .as_f64()
        .unwrap_or_else(|| panic!("{key} is a number"));
    assert!(
        ((value - expected) / expected).abs() < tolerance,
        "{key}: {value} vs {expected}"
    );
}

fn check_scene(json: &Value, lx: f64, expected: &Expected) {
    assert_close(json, "critical_load_exact", expected.critical_load, 1e-9);
    assert_close(json, "n_x_exact", -expected.critical_load, 1e-9);
    assert_close(json, "wavenumber_exact", expected.wavenumber, 1e-9);
    assert_close(
        json,
        "wavelength_exact",
        2.0 * PI / expected.wavenumber,
        1e-9,
    );
    assert_close(
        json,
        "length_x_over_wavelength",
        lx * expected.wavenumber / (2.0 * PI),
        1e-9,
    );
    assert_close(
        json,
        "critical_load_eq44",
        expected.critical_load_eq44,
        1e-9,
    );
    assert_close(json, "wavenumber_eq44", expected.wavenumber_eq44, 1e-9);
    assert_close(
        json,
        "wavelength_eq44",
        2.0 * PI / expected.wavenumber_eq44,
        1e-9,
    );
    assert_close(json, "wrinkling_stress_eq44", expected.stress_eq44, 1e-9);
    assert_close(
        json,
        "critical_load_eq96",
        expected.critical_load_eq96,
        1e-9,
    );
    for (index, name) in ["i1", "i2", "i3", "i4"].iter().enumerate() {
        let value = json["galerkin_integrals"][name].as_f64().unwrap();
        let exact = expected.integrals[index];
        assert!(
            ((value - exact) / exact).abs() < 1e-9,
            "{name}: {value} vs {exact}"
        );
    }
    assert_close(
        json,
        "amplitude_coefficient",
        expected.amplitude_coefficient,
        1e-9,
    );
    // The envelope amplitude curve (62) from λ/λ_c = 1 to 2, and its physical double.
    let curve = json["amplitude_curve"].as_array().unwrap();
    let physical = json["amplitude_curve_physical"].as_array().unwrap();
    assert_eq!(curve.len(), 21);
    for (point, physical_point) in curve.iter().zip(physical) {
        let ratio = point[0].as_f64().unwrap();
        let amplitude = point[1].as_f64().unwrap();
        let expected_amplitude = expected.amplitude_coefficient * (ratio - 1.0).sqrt();
        assert!((amplitude - expected_amplitude).abs() <= 1e-9 * expected_amplitude.max(1e-300));
        assert_eq!(physical_point[0].as_f64().unwrap(), ratio);
        assert!((physical_point[1].as_f64().unwrap() - 2.0 * amplitude).abs() <= 1e-15);
    }
    assert_eq!(curve[0][0].as_f64(), Some(1.0));
    assert_eq!(curve[20][0].as_f64(), Some(2.0));
    // The multi-term sequence starts with the one-term closed form and ends at the converged one.
    let sequence = json["amplitude_coefficient_convergence"]
        .as_array()
        .unwrap();
    assert_eq!(sequence[0]["terms"].as_u64(), Some(1));
    let first = sequence[0]["amplitude_coefficient"].as_f64().unwrap();
    assert!(((first - expected.amplitude_coefficient) / first).abs() < 1e-9);
    assert_eq!(
        sequence.last().unwrap()["amplitude_coefficient"],
        json["amplitude_coefficient_converged"]
    );
    assert_eq!(json["amplitude_coefficient_convergence_stop"], "converged");
}

#[test]
fn analytic_json_default_scene_is_example_one() {
    let json = analytic_json(&[]);
    let expected = expected(400.0, 200.0, 0.05, 70000.0, 0.3, 10.0);
    check_scene(&json, 400.0, &expected);
    // docs/validation.md: the eq. (42) minimum is 0.0895212413 N/mm.
    assert!((json["critical_load_exact"].as_f64().unwrap() - 0.089_521_241_3).abs() < 1e-10);
    // 40-digit reference of the converged Galerkin solution of (55) at α = 0.5.
    assert_close(
        &json,
        "amplitude_coefficient_converged",
        1.089_263_839_6,
        1e-9,
    );
    assert_eq!(json["scene"]["geometry"]["lx"].as_f64(), Some(400.0));
    assert!(json["table_1"].is_null());
}

#[test]
fn analytic_json_square_table_one_scene() {
    let json = analytic_json(&["geometry.lx=200", "load.tension_y=5"]);
    let expected = expected(200.0, 200.0, 0.05, 70000.0, 0.3, 5.0);
    check_scene(&json, 200.0, &expected);
    // Table 1, first row: N_X^wr = −0.064, L_X/ℓ = 6.28 (printed, truncated), a/h = 1.66.
    assert!((json["n_x_exact"].as_f64().unwrap() + 0.064).abs() < 5e-4);
    assert!((json["amplitude_coefficient"].as_f64().unwrap() - 1.650_924_268_5).abs() < 1e-9);
    assert_close(
        &json,
        "amplitude_coefficient_converged",
        1.579_021_773_3,
        1e-9,
    );
}

#[test]
fn analytic_json_steel_like_scene() {
    let json = analytic_json(&[
        "geometry.lx=300",
        "geometry.ly=120",
        "material.young=210000",
        "material.poisson=0.25",
        "material.thickness=0.1",
        "load.tension_y=4",
    ]);
    let expected = expected(300.0, 120.0, 0.1, 210000.0, 0.25, 4.0);
    check_scene(&json, 300.0, &expected);
}

#[test]
fn analytic_table_one_flag_reproduces_the_printed_columns_with_poisson_point_three() {
    let output = wrinkle(&["analytic", "--json", "--table-1"]);
    assert_eq!(output.status.code(), Some(0));
    let json: Value = serde_json::from_slice(&output.stdout).unwrap();
    let rows = json["table_1"]["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 4);
    for row in rows {
        let printed = row["printed_n_x_wr"].as_f64().unwrap();
        assert!((row["n_x_wr"].as_f64().unwrap() - printed).abs() <= 5e-4);
        let miss = (row["n_x_wr_poisson_zero"].as_f64().unwrap() - printed) / printed;
        assert!((-0.05..-0.04).contains(&miss), "{miss}");
        let printed_ratio = row["printed_length_x_over_wavelength"].as_f64().unwrap();
        let ratio = row["length_x_over_wavelength"].as_f64().unwrap();
        assert!(ratio >= printed_ratio && ratio < printed_ratio + 0.01);
        assert_eq!(row["printed_amplitude_over_thickness"].as_f64(), Some(1.66));
        let one_term = row["amplitude_over_thickness_one_term"].as_f64().unwrap();
        assert!((one_term - 1.650_924_268_5).abs() < 1e-9);
        let converged = row["amplitude_over_thickness_converged"].as_f64().unwrap();
        assert!((converged - 1.579_021_773_3).abs() < 2e-9);
    }
}

#[test]
fn analytic_rejects_the_strip_scene_naming_the_key_and_the_file() {
    let output = wrinkle(&["analytic", "examples/scenes/long_strip.toml"]);
    assert_eq!(output.status.code(), Some(2));
    assert!(output.stdout.is_empty());
    let stderr = String::from_utf8(output.stderr).unwrap();
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("error: scene examples/scenes/long_strip.toml: key `load.kind`"));
    assert!(stderr.contains("strip"), "{stderr}");
    for (assignment, key) in [
        ("model.direction=30", "model.direction"),
        ("load.tension_y=0", "load.tension_y"),
        ("model.name=pure-membrane", "model.name"),
    ] {
        let output = wrinkle(&["analytic", "--json", "--set", assignment]);
        assert_eq!(output.status.code(), Some(2), "{assignment}");
        let stderr = String::from_utf8(output.stderr).unwrap();
        assert!(stderr.contains(&format!("key `{key}`")), "{stderr}");
    }
}

#[test]
fn analytic_human_output_states_units_and_which_amplitude() {
    let output = wrinkle(&["analytic"]);
    assert_eq!(output.status.code(), Some(0));
    let text = String::from_utf8(output.stdout).unwrap();
    for unit in [
        "(N/mm)", "(MPa)", "(1/mm)", "(mm)", "N·mm", "envelope", "physical",
    ] {
        assert!(text.contains(unit), "missing {unit}:\n{text}");
    }
    assert!(text.contains("8.952124"), "{text}");
}
