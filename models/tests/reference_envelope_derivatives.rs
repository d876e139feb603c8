//! Verification of the generated kernels of the reference envelope model.
//!
//! Source: THEORY.md §4 (the paper's eqs 22, 23, 64). Parameters: E = 70000 MPa, ν = 0.3,
//! h = 0.05 mm, Q = 0.1 /mm (and 0.13 /mm), wave direction θ = 0 and θ = 0.3 rad.
//! Checks, at 25 seeded random jets per case:
//! * the generated energy equals the density written by hand from eqs (22), (23), (64)
//!   (relative 1e-13);
//! * the symbolic residual equals the num-dual gradient (`Dual64`) of the generated energy and
//!   a 5-point central finite difference of it (exact for this quartic density up to round-off);
//! * the symbolic tangent equals num-dual Hessians (`HyperDual64`) and nested 5-point finite
//!   differences of the energy; entries outside the published pattern are zero;
//!   all to relative 1e-9 or better (norm-wise over the jet).

use num_dual::{Dual64, HyperDual64};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_models::ReferenceEnvelope;
use wrinkle_runtime::{Derivative, EnergyModel};

const YOUNG: f64 = 70000.0;
const POISSON: f64 = 0.3;
const THICKNESS: f64 = 0.05;

fn model(q: f64, direction: f64) -> ReferenceEnvelope {
    let mut m = ReferenceEnvelope::from_parameters(&[0.0; 5]);
    for (name, value) in [
        ("young", YOUNG),
        ("poisson", POISSON),
        ("thickness", THICKNESS),
        ("wavenumber", q),
        ("direction", direction),
    ] {
        m.set_parameter(name, value).unwrap();
    }
    m
}

/// Model-level jet value for (field, derivative), from a named map.
fn random_state(rng: &mut StdRng) -> [f64; 9] {
    // u, u.x, u.y, v, v.x, v.y, w, w.x, w.y — realistic magnitudes (strains 1e-3, envelope ~h,
    // envelope slopes ~ h / L).
    let mut s = [0.0; 9];
    for (k, scale) in [1.0, 1e-3, 1e-3, 1.0, 1e-3, 1e-3, 0.1, 5e-3, 5e-3]
        .iter()
        .enumerate()
    {
        s[k] = scale * rng.random_range(-1.0..1.0);
    }
    s
}

fn term_jet(term: usize, state: &[f64; 9]) -> Vec<f64> {
    let spec = ReferenceEnvelope::SPEC;
    spec.terms[term]
        .jet
        .iter()
        .map(|&i| {
            let e = spec.jet[i];
            let d = match e.derivative {
                Derivative::Value => 0,
                Derivative::X => 1,
                Derivative::Y => 2,
                Derivative::XX | Derivative::XY | Derivative::YY => {
                    unreachable!("the model reads first derivatives only")
                }
            };
            state[3 * e.field + d]
        })
        .collect()
}

/// Hand-written density of THEORY.md §4 at a full state.
fn hand_density(q: f64, theta: f64, s: &[f64; 9]) -> f64 {
    let (u_x, u_y, v_x, v_y, w, w_x, w_y) = (s[1], s[2], s[4], s[5], s[6], s[7], s[8]);
    let (c, sn) = (theta.cos(), theta.sin());
    let gx = u_x + w_x * w_x + q * q * w * w * c * c;
    let gy = v_y + w_y * w_y + q * q * w * w * sn * sn;
    let gxy = u_y + v_x + 2.0 * w_x * w_y + 2.0 * q * q * w * w * c * sn;
    let eh = YOUNG * THICKNESS / (1.0 - POISSON * POISSON);
    let d = YOUNG * THICKNESS.powi(3) / (12.0 * (1.0 - POISSON * POISSON));
    let membrane = 0.5
        * eh
        * (gx * gx + gy * gy + 2.0 * POISSON * gx * gy + 0.5 * (1.0 - POISSON) * gxy * gxy);
    let along = c * w_x + sn * w_y;
    let across = -sn * w_x + c * w_y;
    let bending =
        d * (q.powi(4) * w * w + 6.0 * q * q * along * along + 2.0 * q * q * across * across);
    membrane + bending
}

fn relative(a: &[f64], b: &[f64]) -> f64 {
    let diff: f64 = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt();
    let scale: f64 = b.iter().map(|y| y * y).sum::<f64>().sqrt();
    if scale == 0.0 { diff } else { diff / scale }
}

/// 5-point central difference of `f` along coordinate `i` (exact for polynomials of degree ≤ 4).
fn five_point(f: &dyn Fn(&[f64]) -> f64, x: &[f64], i: usize, h: f64) -> f64 {
    let at = |t: f64| {
        let mut y = x.to_vec();
        y[i] += t;
        f(&y)
    };
    (8.0 * (at(h) - at(-h)) - (at(2.0 * h) - at(-2.0 * h))) / (12.0 * h)
}

fn step(x: f64) -> f64 {
    1e-2 * x.abs().max(1e-3)
}

fn check_case(q: f64, theta: f64, seed: u64) {
    let m = model(q, theta);
    let spec = ReferenceEnvelope::SPEC;
    let mut rng = StdRng::seed_from_u64(seed);
    for _ in 0..25 {
        let state = random_state(&mut rng);
        let mut total = 0.0;
        for (t, term) in spec.terms.iter().enumerate() {
            let jet = term_jet(t, &state);
            let n = jet.len();
            total += m.energy(t, &jet);

            // Residual: symbolic vs Dual64 vs finite differences.
            let mut residual = vec![0.0; n];
            m.residual(t, &jet, &mut residual);
            let dual: Vec<f64> = (0..n)
                .map(|i| {
                    let x: Vec<Dual64> = (0..n)
                        .map(|k| Dual64::new(jet[k], if k == i { 1.0 } else { 0.0 }))
                        .collect();
                    m.energy(t, &x).eps
                })
                .collect();
            let energy = |x: &[f64]| m.energy(t, x);
            let fd: Vec<f64> = (0..n)
                .map(|i| five_point(&energy, &jet, i, step(jet[i])))
                .collect();
            assert!(
                relative(&residual, &dual) < 1e-12,
                "term {} residual vs dual: {:e}",
                term.name,
                relative(&residual, &dual)
            );
            assert!(
                relative(&residual, &fd) < 1e-9,
                "term {} residual vs FD: {:e}",
                term.name,
                relative(&residual, &fd)
            );

            // Tangent: symbolic (pattern) vs HyperDual64 vs nested finite differences.
            let mut packed = vec![0.0; term.tangent_pattern.len()];
            m.tangent(t, &jet, &mut packed);
            let mut symbolic = vec![0.0; n * n];
            for (p, &(i, j)) in term.tangent_pattern.iter().enumerate() {
                assert!(i <= j, "pattern must be upper triangular");
                symbolic[i * n + j] = packed[p];
                symbolic[j * n + i] = packed[p];
            }
            let mut hyper = vec![0.0; n * n];
            let mut fd2 = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    let x: Vec<HyperDual64> = (0..n)
                        .map(|k| {
                            HyperDual64::new(
                                jet[k],
                                if k == i { 1.0 } else { 0.0 },
                                if k == j { 1.0 } else { 0.0 },
                                0.0,
                            )
                        })
                        .collect();
                    hyper[i * n + j] = m.energy(t, &x).eps1eps2;
                    let gradient_j = |y: &[f64]| five_point(&energy, y, j, step(jet[j]));
                    fd2[i * n + j] = five_point(&gradient_j, &jet, i, step(jet[i]));
                }
            }
            assert!(
                relative(&symbolic, &hyper) < 1e-12,
                "term {} tangent vs hyper-dual: {:e}",
                term.name,
                relative(&symbolic, &hyper)
            );
            assert!(
                relative(&symbolic, &fd2) < 1e-9,
                "term {} tangent vs FD: {:e}",
                term.name,
                relative(&symbolic, &fd2)
            );
        }
        let hand = hand_density(q, theta, &state);
        assert!(
            (total - hand).abs() <= 1e-13 * hand.abs().max(1e-30),
            "energy {total} vs hand-written {hand}"
        );
    }
}

#[test]
fn reference_envelope_kernels_agree_along_x() {
    check_case(0.1, 0.0, 7);
}

#[test]
fn reference_envelope_kernels_agree_rotated_direction() {
    check_case(0.13, 0.3, 11);
}

#[test]
fn reference_envelope_metadata() {
    let spec = ReferenceEnvelope::SPEC;
    assert_eq!(spec.name, "reference-envelope");
    assert_eq!(spec.fields, &["u", "v", "w"]);
    assert_eq!(
        spec.parameters,
        &["young", "poisson", "thickness", "wavenumber", "direction"]
    );
    // Only first derivatives of u and v are used, never their values.
    for e in spec.jet {
        if e.field < 2 {
            assert_ne!(e.derivative, Derivative::Value);
        }
    }
    assert_eq!(spec.jet.len(), 7);
    // The bending term involves only w and its gradient.
    let bending = spec.terms.iter().find(|t| t.name == "bending").unwrap();
    assert!(bending.jet.iter().all(|&i| spec.jet[i].field == 2));
    assert_eq!(bending.jet.len(), 3);
    assert!(!spec.simplification_report.is_empty());
}
