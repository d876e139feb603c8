//! Verification of the generated kernels of the `fvk-plate` model.
//!
//! Source: THEORY.md §2 (the paper's eqs 16–17 with Reissner–Mindlin bending). Parameters:
//! E = 70000 MPa, ν = 0.3, h = 0.05 mm. At 25 seeded random jets (15 entries: u, v, w, θ_x, θ_y
//! and their first derivatives):
//! * the sum of the generated term energies equals the density written by hand
//!   (relative 1e-13);
//! * the symbolic residual of every term equals the `Dual64` gradient of its energy
//!   (relative 1e-12) and a 5-point central difference (relative 1e-9; exact for this quartic
//!   density up to round-off);
//! * the symbolic tangent equals `HyperDual64` Hessians (relative 1e-12) and 5-point differences
//!   of the symbolic residual (relative 1e-9); entries outside the published pattern are zero.

use num_dual::{Dual64, HyperDual64};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_models::FvkPlate;
use wrinkle_runtime::{Derivative, EnergyModel, QuadratureRule};

const YOUNG: f64 = 70000.0;
const POISSON: f64 = 0.3;
const THICKNESS: f64 = 0.05;

fn plate() -> FvkPlate {
    FvkPlate::from_parameters(&[YOUNG, POISSON, THICKNESS])
}

/// u, u.x, u.y, v, …, θ_y.y: in-plane values ~1 mm, strains ~1e-3, deflection ~h, slopes ~1e-2,
/// curvatures ~1e-3.
fn random_state(rng: &mut StdRng) -> [f64; 15] {
    let scales = [
        1.0, 1e-3, 1e-3, 1.0, 1e-3, 1e-3, 0.05, 1e-2, 1e-2, 1e-2, 1e-3, 1e-3, 1e-2, 1e-3, 1e-3,
    ];
    let mut s = [0.0; 15];
    for (k, scale) in scales.iter().enumerate() {
        s[k] = scale * rng.random_range(-1.0..1.0);
    }
    s
}

fn term_jet(term: usize, state: &[f64; 15]) -> Vec<f64> {
    let spec = FvkPlate::SPEC;
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

/// THEORY.md §2 written out by hand.
fn hand_density(s: &[f64; 15]) -> f64 {
    let (u_x, u_y, v_x, v_y) = (s[1], s[2], s[4], s[5]);
    let (w_x, w_y) = (s[7], s[8]);
    let (tx, tx_x, tx_y, ty, ty_x, ty_y) = (s[9], s[10], s[11], s[12], s[13], s[14]);
    let c = YOUNG * THICKNESS / (1.0 - POISSON * POISSON);
    let d = YOUNG * THICKNESS.powi(3) / (12.0 * (1.0 - POISSON * POISSON));
    let kgh = 5.0 / 6.0 * YOUNG / (2.0 * (1.0 + POISSON)) * THICKNESS;
    let g = [
        u_x + 0.5 * w_x * w_x,
        v_y + 0.5 * w_y * w_y,
        u_y + v_x + w_x * w_y,
    ];
    let membrane = 0.5
        * c
        * (g[0] * g[0]
            + g[1] * g[1]
            + 2.0 * POISSON * g[0] * g[1]
            + 0.5 * (1.0 - POISSON) * g[2] * g[2]);
    // ½ D [(tr κ)² − 2(1−ν) det κ], κ = sym ∇θ.
    let (kxx, kyy, kxy) = (tx_x, ty_y, 0.5 * (tx_y + ty_x));
    let bending = 0.5 * d * ((kxx + kyy).powi(2) - 2.0 * (1.0 - POISSON) * (kxx * kyy - kxy * kxy));
    let shear = 0.5 * kgh * ((w_x - tx).powi(2) + (w_y - ty).powi(2));
    membrane + bending + shear
}

fn relative(a: &[f64], b: &[f64]) -> f64 {
    let diff = a
        .iter()
        .zip(b)
        .map(|(x, y)| (x - y).powi(2))
        .sum::<f64>()
        .sqrt();
    let scale = b.iter().map(|y| y * y).sum::<f64>().sqrt();
    if scale == 0.0 { diff } else { diff / scale }
}

/// 5-point central difference of `f` along coordinate `i`.
fn five_point(f: &dyn Fn(&[f64]) -> f64, x: &[f64], i: usize) -> f64 {
    let h = 1e-2 * x[i].abs().max(1e-4);
    let at = |t: f64| {
        let mut y = x.to_vec();
        y[i] += t;
        f(&y)
    };
    (8.0 * (at(h) - at(-h)) - (at(2.0 * h) - at(-2.0 * h))) / (12.0 * h)
}

fn unit<T>(n: usize, i: usize, make: impl Fn(usize, f64) -> T) -> Vec<T> {
    (0..n)
        .map(|k| make(k, if k == i { 1.0 } else { 0.0 }))
        .collect()
}

#[test]
fn fvk_plate_kernels_agree_with_dual_numbers_and_differences() {
    let m = plate();
    let spec = FvkPlate::SPEC;
    let mut rng = StdRng::seed_from_u64(2014);
    for _ in 0..25 {
        let state = random_state(&mut rng);
        let mut total = 0.0;
        for (t, term) in spec.terms.iter().enumerate() {
            let jet = term_jet(t, &state);
            let n = jet.len();
            total += m.energy(t, &jet);
            let mut residual = vec![0.0; n];
            m.residual(t, &jet, &mut residual);
            let dual: Vec<f64> = (0..n)
                .map(|i| m.energy(t, &unit(n, i, |k, e| Dual64::new(jet[k], e))).eps)
                .collect();
            let energy = |x: &[f64]| m.energy(t, x);
            let fd: Vec<f64> = (0..n).map(|i| five_point(&energy, &jet, i)).collect();
            let (r_dual, r_fd) = (relative(&residual, &dual), relative(&residual, &fd));
            assert!(
                r_dual < 1e-12,
                "term {}: residual vs Dual64 {r_dual:e}",
                term.name
            );
            assert!(r_fd < 1e-9, "term {}: residual vs FD {r_fd:e}", term.name);

            let mut packed = vec![0.0; term.tangent_pattern.len()];
            m.tangent(t, &jet, &mut packed);
            let mut symbolic = vec![0.0; n * n];
            for (p, &(i, j)) in term.tangent_pattern.iter().enumerate() {
                assert!(i <= j, "pattern must be upper triangular");
                symbolic[i * n + j] = packed[p];
                symbolic[j * n + i] = packed[p];
            }
            let mut hyper = vec![0.0; n * n];
            for i in 0..n {
                for j in 0..n {
                    let x: Vec<HyperDual64> = (0..n)
                        .map(|k| {
                            let (a, b) = (f64::from(k == i), f64::from(k == j));
                            HyperDual64::new(jet[k], a, b, 0.0)
                        })
                        .collect();
                    hyper[i * n + j] = m.energy(t, &x).eps1eps2;
                }
            }
            let r = relative(&symbolic, &hyper);
            assert!(
                r < 1e-12,
                "term {}: tangent vs HyperDual64 {r:e}",
                term.name
            );
            // Columns of the tangent: 5-point differences of the symbolic residual.
            let mut fd2 = vec![0.0; n * n];
            for j in 0..n {
                let residual_j = |x: &[f64]| {
                    let mut out = vec![0.0; n];
                    m.residual(t, x, &mut out);
                    out[j]
                };
                for i in 0..n {
                    fd2[i * n + j] = five_point(&residual_j, &jet, i);
                }
            }
            let r = relative(&symbolic, &fd2);
            assert!(
                r < 1e-9,
                "term {}: tangent vs FD of residual {r:e}",
                term.name
            );
        }
        let hand = hand_density(&state);
        assert!(
            (total - hand).abs() <= 1e-13 * hand.abs(),
            "energy {total} vs hand-written {hand}"
        );
    }
}

#[test]
fn fvk_plate_metadata() {
    let spec = FvkPlate::SPEC;
    assert_eq!(spec.name, "fvk-plate");
    assert_eq!(spec.fields, &["u", "v", "w", "theta_x", "theta_y"]);
    assert_eq!(spec.parameters, &["young", "poisson", "thickness"]);
    let names: Vec<&str> = spec.terms.iter().map(|t| t.name).collect();
    assert_eq!(names, ["membrane", "bending", "shear"]);
    let shear = &spec.terms[2];
    assert_eq!(shear.quadrature, QuadratureRule::Reduced);
    assert_eq!(spec.terms[0].quadrature, QuadratureRule::Full);
    assert_eq!(spec.terms[1].quadrature, QuadratureRule::Full);
    // Shear: w.x, w.y, θ_x, θ_y; bending: the four rotation gradients only.
    assert_eq!(shear.jet.len(), 4);
    assert!(spec.terms[1].jet.iter().all(|&i| spec.jet[i].field >= 3));
    assert!(wrinkle_models::names().contains(&"fvk-plate"));
}
