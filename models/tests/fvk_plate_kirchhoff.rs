//! Kirchhoff limit of the `fvk-plate` model: centre deflection of a square plate under uniform
//! pressure.
//!
//! Source: Timoshenko & Woinowsky-Krieger, *Theory of plates and shells* (1959), Table 35 and
//! Navier's series: centre deflection $`w_c = c\,qL^4/D`$ with $`c = 0.00126532`$ (clamped) and
//! $`c = 0.00406235`$ (simply supported). Parameters: unit square, E = 70000 MPa, ν = 0.3,
//! $`h = L/100, L/1000, L/10000`$, $`q = 1`$ on `w` (linear problem $`K_t(0)U = F`$);
//! $`u = v = 0`$ on the boundary; clamped $`w = \theta_x = \theta_y = 0`$, hard simple support
//! $`w = 0`$ and tangential rotation $`= 0`$. Expected: within 1 % on uniform n × n Q8 meshes,
//! with a positive definite tangent (Cholesky succeeds: no zero-energy mode).
//!
//! Meshes: the registered model integrates the shear with 2×2 Gauss alone, which locks
//! progressively as the plate gets thinner; these are the coarsest meshes (from the study
//! `cargo run -p wrinkle-models --release --example fvk_plate_study -- kirchhoff reduced`) that
//! pass with margin. The Mindlin solution itself differs from Kirchhoff's by +0.20 % (clamped)
//! and +0.05 % (simply supported) at L/h = 100. Measured errors:
//!
//! | support | L/h | n | error |
//! | --- | --- | --- | --- |
//! | clamped | 100 | 12 | +0.154 % |
//! | clamped | 1000 | 24 | −0.039 % |
//! | clamped | 10000 | 48 | −0.034 % |
//! | simply supported | 100 | 8 | +0.042 % |
//! | simply supported | 1000 | 12 | −0.021 % |
//! | simply supported | 10000 | 24 | −0.008 % |
//!
//! The last test checks the Lyly–Stenberg–Vihinen stabilised prototype (α = 0.01, diameter
//! $`h_e = \sqrt2/n`$): within 1 % on the same coarse 8 × 8 mesh at every L/h.

mod fvk_plate_support;

use fvk_plate_support::*;
use wrinkle_runtime::linear::factor::FactorizationKind;

fn check(support: Support, ratio: f64, n: usize, expected_error_percent: f64) {
    let reference = match support {
        Support::Clamped => CLAMPED_CENTRE,
        Support::SimplySupported => SIMPLY_SUPPORTED_CENTRE,
    };
    let (w, kind) = centre_deflection(plate(1.0 / ratio), n, support);
    let error = 100.0 * (w / reference - 1.0);
    assert_eq!(
        kind,
        FactorizationKind::Cholesky,
        "{support:?} L/h {ratio}: tangent not SPD"
    );
    assert!(
        error.abs() < 1.0,
        "{support:?} L/h {ratio} n {n}: error {error:.4} %"
    );
    // The measured value, so that a change of the kernels or the assembly shows.
    assert!(
        (error - expected_error_percent).abs() < 1e-2,
        "{support:?} L/h {ratio} n {n}: error {error:.5} %, measured {expected_error_percent} %"
    );
}

#[test]
fn kirchhoff_clamped_square_l_over_h_100() {
    check(Support::Clamped, 100.0, 12, 0.1542);
}

#[test]
fn kirchhoff_clamped_square_l_over_h_1000() {
    check(Support::Clamped, 1000.0, 24, -0.0391);
}

#[test]
fn kirchhoff_clamped_square_l_over_h_10000() {
    check(Support::Clamped, 10000.0, 48, -0.0335);
}

#[test]
fn kirchhoff_simply_supported_square_l_over_h_100() {
    check(Support::SimplySupported, 100.0, 8, 0.0416);
}

#[test]
fn kirchhoff_simply_supported_square_l_over_h_1000() {
    check(Support::SimplySupported, 1000.0, 12, -0.0208);
}

#[test]
fn kirchhoff_simply_supported_square_l_over_h_10000() {
    check(Support::SimplySupported, 10000.0, 24, -0.0079);
}

#[test]
fn kirchhoff_square_stabilised_shear_prototype_is_locking_free_on_8x8() {
    let n = 8;
    for (support, reference) in [
        (Support::Clamped, CLAMPED_CENTRE),
        (Support::SimplySupported, SIMPLY_SUPPORTED_CENTRE),
    ] {
        for ratio in [100.0, 1000.0, 10000.0] {
            let extra = [
                ("element_size", 2f64.sqrt() / n as f64),
                ("stabilisation", 0.01),
            ];
            let model = model::<FvkPlateStabilisedReduced>(1.0 / ratio, &extra);
            let (w, kind) = centre_deflection(model, n, support);
            let error = 100.0 * (w / reference - 1.0);
            assert_eq!(kind, FactorizationKind::Cholesky);
            assert!(
                error.abs() < 1.0,
                "{support:?} L/h {ratio}: error {error:.4} %"
            );
        }
    }
}
