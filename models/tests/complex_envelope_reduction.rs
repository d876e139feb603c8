//! The complex-envelope model (`complex-envelope`, THEORY.md §6) against the reference envelope
//! model (`reference-envelope`, §4) and against closed forms.
//!
//! Source: THEORY.md §6 and the doc comment of `models/src/complex_envelope.rs`. Parameters:
//! `E = 70000` MPa, `ν = 0.3`, `h = 0.05` mm, `Q = 0.23` /mm for the kernel checks, example 1
//! (THEORY.md §9, `envelope_support`) for the buckling checks.
//!
//! * **Reduction** (`complex_envelope_with_real_envelope_reduces_to_reference_envelope`): at
//!   random jets with `b = w0 = θ = 0` (and all their derivatives), directions 0 and 0.3 rad,
//!   the energy, the residual entries and the tangent block of `(u, v, a)` equal the reference
//!   envelope's with `w = a`, entry by entry mapped by field and derivative, to 1e-12 relative;
//!   the mean-deflection terms contribute exactly nothing there. The residual in `b` does not
//!   vanish: it is the hand-derived
//!   $`\partial\psi/\partial\nabla b = (2Q\,N\mathbf e + 4DQ^3\mathbf e)\,a`$,
//!   $`\partial\psi/\partial b = -(2Q\,(N\mathbf e)\cdot\nabla a + 4DQ^3\,\partial_e a)`$ with
//!   $`N = L_m(\varepsilon(u) + \nabla a\otimes\nabla a + Q^2a^2\mathbf e\otimes\mathbf e)`$
//!   (1e-12 relative).
//! * **Plane wave** (`complex_envelope_plane_wave_bending_density`): for
//!   $`w_1 = re^{ik\,\mathbf e\cdot\mathbf X}`$ the `envelope_bending` density is
//!   $`Dr^2(Q^4 + 4Q^3k + 6Q^2k^2)`$ (1e-13 relative), and its error against the exact
//!   $`Dr^2(Q+k)^4`$ is $`Dr^2(4Qk^3 + k^4)`$: the ratio of errors as `k` halves is
//!   $`8(4Q+k)/(4Q+k/2) \to 8`$ (checked to 1e-9, and within 0.13 of 8 from `k = Q/8`).
//! * **Example 1 buckling** (32 × 16 Q8, as the reference envelope's CI mesh):
//!   `complex_envelope_example1_buckling_at_reference_optimum` and
//!   `complex_envelope_example1_buckling_where_first_order_terms_cancel`. Linearised about the
//!   uniform state $`N_X = -\lambda`$, the envelope equation is
//!   $`-\alpha\,\partial_X^2 w_1 - (N_Y + 2DQ^2)\partial_Y^2 w_1 + (DQ^4 - \lambda Q^2)w_1 -
//!   i c\,\partial_X w_1 = 0`$ with $`\alpha = 6DQ^2 - \lambda`$, $`c = 4DQ^3 - 2Q\lambda`$;
//!   $`w_1 = e^{-icX/(2\alpha)}\psi`$ removes the first-order term, so on the clamped rectangle the
//!   threshold is the smallest root of
//!   $$`F(\lambda) = \alpha\frac{\pi^2}{L_X^2} + (N_Y + 2DQ^2)\frac{\pi^2}{L_Y^2} + DQ^4 -
//!   \lambda Q^2 - \frac{c^2}{4\alpha} = 0,`$$
//!   i.e. (42) with the extra $`-c^2/(4\alpha)`$: **below** the reference envelope's threshold
//!   unless $`c = 0`$, i.e. unless that threshold is exactly $`2DQ^2`$. At the reference optimum
//!   `Q_c = 0.2354346` /mm (closed-form minimiser of (42), `λ_ref = 0.08952124`),
//!   $`\lambda_{ref} - 2DQ^2 = 6.9\times10^{-4}`$ and the complex envelope buckles at
//!   `0.08951856`, **3.00e-5 relative below** the reference envelope (the phase lets the local
//!   wavenumber drift by $`\kappa = -c/(2\alpha) \approx +9.2\times10^{-4}`$ /mm, toward `Q*`
//!   below). So the equality "to 1e-8 at the reference optimum" does not hold; what holds is
//!   (a) the measured FE shift equals this closed-form shift (measured −2.99655e-5 against
//!   −2.99576e-5: asserted to 1e-3 of it), and (b) at `Q* = 0.2363534` /mm, where (42) gives
//!   exactly $`2DQ^2`$, the two FE thresholds agree to 1e-8 (the first-order terms of (39)
//!   cancel at the threshold of (91)). In both cases the first eigenvalue is two-fold: with the
//!   mode $`(a, b)`$, the phase-rotated $`(-b, a)`$ has the same load and eigen-residual, and the
//!   mean deflection and rotations of the mode vanish (decoupled at the pre-buckling state).

mod envelope_support;

use envelope_support::*;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_models::{ComplexEnvelope, ReferenceEnvelope};
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::LinearBuckling;
use wrinkle_runtime::{Derivative, EnergyModel};

/// Energy, residual and dense tangent of a model summed over its terms, on the model-level jet.
struct Evaluated {
    energy: f64,
    residual: Vec<f64>,
    tangent: Vec<Vec<f64>>,
}

/// Evaluates the terms of `M` whose name passes `keep` at the model-level jet `jet`.
fn evaluate<M: EnergyModel>(model: &M, jet: &[f64], keep: &dyn Fn(&str) -> bool) -> Evaluated {
    let spec = M::SPEC;
    let n = spec.jet.len();
    let mut out = Evaluated {
        energy: 0.0,
        residual: vec![0.0; n],
        tangent: vec![vec![0.0; n]; n],
    };
    for (t, term) in spec.terms.iter().enumerate() {
        if !keep(term.name) {
            continue;
        }
        let local: Vec<f64> = term.jet.iter().map(|&i| jet[i]).collect();
        out.energy += model.energy(t, &local);
        let mut residual = vec![0.0; local.len()];
        model.residual(t, &local, &mut residual);
        for (k, &i) in term.jet.iter().enumerate() {
            out.residual[i] += residual[k];
        }
        let mut packed = vec![0.0; term.tangent_pattern.len()];
        model.tangent(t, &local, &mut packed);
        for (p, &(i, j)) in term.tangent_pattern.iter().enumerate() {
            let (gi, gj) = (term.jet[i], term.jet[j]);
            out.tangent[gi][gj] += packed[p];
            if gi != gj {
                out.tangent[gj][gi] += packed[p];
            }
        }
    }
    out
}

/// Index of `(field, derivative)` in the model-level jet of `M`.
fn jet_index<M: EnergyModel>(field: &str, derivative: Derivative) -> Option<usize> {
    let f = M::SPEC.field_index(field)?;
    M::SPEC
        .jet
        .iter()
        .position(|e| e.field == f && e.derivative == derivative)
}

/// `(field, derivative)` of a model-level jet entry of `M`.
fn jet_entry<M: EnergyModel>(index: usize) -> (&'static str, Derivative) {
    let entry = M::SPEC.jet[index];
    (M::SPEC.fields[entry.field], entry.derivative)
}

fn max_abs<'a>(values: impl IntoIterator<Item = &'a f64>) -> f64 {
    values.into_iter().fold(0.0_f64, |m, v| m.max(v.abs()))
}

fn kernel_model<M: EnergyModel>(direction: f64) -> M {
    let mut m: M = envelope_model(0.23);
    m.set_parameter("direction", direction).unwrap();
    m
}

/// Membrane force $`N = L_m\gamma`$ (Voigt, $`N_{XY}`$ third) of the reference envelope at a
/// jet given as a lookup of `(field, derivative)`, with the wave direction `(c, s)`.
fn reference_force(value: &dyn Fn(&str, Derivative) -> f64, q: f64, c: f64, s: f64) -> [f64; 3] {
    let (ax, ay, a) = (
        value("a", Derivative::X),
        value("a", Derivative::Y),
        value("a", Derivative::Value),
    );
    let gx = value("u", Derivative::X) + ax * ax + q * q * c * c * a * a;
    let gy = value("v", Derivative::Y) + ay * ay + q * q * s * s * a * a;
    let gxy = value("u", Derivative::Y)
        + value("v", Derivative::X)
        + 2.0 * ax * ay
        + 2.0 * q * q * c * s * a * a;
    let k = YOUNG * THICKNESS / (1.0 - POISSON * POISSON);
    [
        k * (gx + POISSON * gy),
        k * (POISSON * gx + gy),
        k * 0.5 * (1.0 - POISSON) * gxy,
    ]
}

/// The complex-envelope field holding a reference-envelope field (`w = a`).
fn rename(field: &str) -> &str {
    match field {
        "w" => "a",
        other => other,
    }
}

fn check_reduction_at(direction: f64, rng: &mut StdRng) {
    let complex: ComplexEnvelope = kernel_model(direction);
    let reference: ReferenceEnvelope = kernel_model(direction);
    // Random complex-envelope jet: u, v ~ 1 mm with strains 1e-3, a ~ 0.1 mm with slopes 5e-3;
    // b, w0, θ and all their derivatives zero.
    let jet: Vec<f64> = (0..ComplexEnvelope::SPEC.jet.len())
        .map(|i| match jet_entry::<ComplexEnvelope>(i) {
            ("u" | "v", Derivative::Value) => rng.random_range(-1.0..1.0),
            ("u" | "v", _) => 1e-3 * rng.random_range(-1.0..1.0),
            ("a", Derivative::Value) => 0.1 * rng.random_range(-1.0..1.0),
            ("a", _) => 5e-3 * rng.random_range(-1.0..1.0),
            _ => 0.0,
        })
        .collect();
    let value =
        |field: &str, d: Derivative| jet_index::<ComplexEnvelope>(field, d).map_or(0.0, |i| jet[i]);
    // The reference jet, entry by entry, from the complex one (w = a).
    let map: Vec<usize> = (0..ReferenceEnvelope::SPEC.jet.len())
        .map(|r| {
            let (field, d) = jet_entry::<ReferenceEnvelope>(r);
            jet_index::<ComplexEnvelope>(rename(field), d).expect("same derivatives")
        })
        .collect();
    let reference_jet: Vec<f64> = map.iter().map(|&c| jet[c]).collect();
    let all = |_: &str| true;
    let x = evaluate(&complex, &jet, &all);
    let y = evaluate(&reference, &reference_jet, &all);

    let energy_error = (x.energy - y.energy).abs() / y.energy.abs();
    assert!(energy_error < 1e-12, "energy differs by {energy_error:e}");
    let scale = max_abs(&y.residual);
    for (r, &c) in map.iter().enumerate() {
        let error = (x.residual[c] - y.residual[r]).abs() / scale;
        assert!(
            error < 1e-12,
            "residual {:?}: {error:e}",
            jet_entry::<ReferenceEnvelope>(r)
        );
    }
    let scale = max_abs(y.tangent.iter().flatten());
    for (r, &c) in map.iter().enumerate() {
        for (s, &d) in map.iter().enumerate() {
            let error = (x.tangent[c][d] - y.tangent[r][s]).abs() / scale;
            assert!(error < 1e-12, "tangent ({r}, {s}): {error:e}");
        }
    }
    // Complex-envelope entries of (u, v, a) with no reference counterpart hold nothing.
    let in_plane_or_a = |i: usize| matches!(jet_entry::<ComplexEnvelope>(i).0, "u" | "v" | "a");
    for i in (0..jet.len()).filter(|&i| in_plane_or_a(i) && !map.contains(&i)) {
        assert_eq!(x.residual[i], 0.0);
    }
    // The mean-deflection terms contribute exactly nothing to (u, v, a).
    let mean = evaluate(&complex, &jet, &|name| name.starts_with("mean_"));
    assert_eq!(mean.energy, 0.0);
    for i in (0..jet.len()).filter(|&i| in_plane_or_a(i)) {
        assert_eq!(mean.residual[i], 0.0);
        for j in (0..jet.len()).filter(|&j| in_plane_or_a(j)) {
            assert_eq!(mean.tangent[i][j], 0.0);
        }
    }
    check_imaginary_residual(&x, &value, direction);
}

/// The residual in `b` at `b = 0` against its hand derivation (module documentation).
fn check_imaginary_residual(
    x: &Evaluated,
    value: &dyn Fn(&str, Derivative) -> f64,
    direction: f64,
) {
    let (q, d) = (0.23, bending_stiffness());
    let (c, s) = (direction.cos(), direction.sin());
    let n = reference_force(value, q, c, s);
    let ne = [n[0] * c + n[2] * s, n[2] * c + n[1] * s];
    let a = value("a", Derivative::Value);
    let grad_a = [value("a", Derivative::X), value("a", Derivative::Y)];
    let expected = [
        (
            Derivative::X,
            (2.0 * q * ne[0] + 4.0 * d * q.powi(3) * c) * a,
        ),
        (
            Derivative::Y,
            (2.0 * q * ne[1] + 4.0 * d * q.powi(3) * s) * a,
        ),
        (
            Derivative::Value,
            -(2.0 * q * (ne[0] * grad_a[0] + ne[1] * grad_a[1])
                + 4.0 * d * q.powi(3) * (c * grad_a[0] + s * grad_a[1])),
        ),
    ];
    let scale = max_abs(expected.iter().map(|(_, v)| v));
    for (derivative, truth) in expected {
        let i = jet_index::<ComplexEnvelope>("b", derivative).unwrap();
        let error = (x.residual[i] - truth).abs() / scale;
        assert!(
            error < 1e-12,
            "∂ψ/∂b {derivative:?}: {} vs {truth} ({error:e})",
            x.residual[i]
        );
    }
}

#[test]
fn complex_envelope_with_real_envelope_reduces_to_reference_envelope() {
    let mut rng = StdRng::seed_from_u64(20140106);
    for direction in [0.0, 0.3] {
        for _ in 0..20 {
            check_reduction_at(direction, &mut rng);
        }
    }
}

/// The `envelope_bending` density at the plane wave $`w_1 = re^{ik\,\mathbf e\cdot\mathbf X}`$
/// of phase `phase` at the evaluation point.
fn plane_wave_density(model: &ComplexEnvelope, r: f64, k: f64, phase: f64, direction: f64) -> f64 {
    let spec = ComplexEnvelope::SPEC;
    let t = spec
        .terms
        .iter()
        .position(|t| t.name == "envelope_bending")
        .unwrap();
    let (c, s) = (direction.cos(), direction.sin());
    let jet: Vec<f64> = spec.terms[t]
        .jet
        .iter()
        .map(|&i| {
            let (field, derivative) = jet_entry::<ComplexEnvelope>(i);
            let along = match derivative {
                Derivative::Value => None,
                Derivative::X => Some(c),
                Derivative::Y => Some(s),
                Derivative::XX | Derivative::XY | Derivative::YY => {
                    unreachable!("the model reads first derivatives only")
                }
            };
            match (field, along) {
                ("a", None) => r * phase.cos(),
                ("b", None) => r * phase.sin(),
                ("a", Some(e)) => -r * k * phase.sin() * e,
                ("b", Some(e)) => r * k * phase.cos() * e,
                _ => 0.0,
            }
        })
        .collect();
    model.energy(t, &jet)
}

#[test]
fn complex_envelope_plane_wave_bending_density() {
    let d = bending_stiffness();
    let (q, r) = (0.23, 0.1);
    for direction in [0.0, 0.3] {
        let model: ComplexEnvelope = kernel_model(direction);
        for phase in [0.0, 0.7, 2.5] {
            for sign in [1.0, -1.0] {
                let mut previous_error: Option<f64> = None;
                for halvings in 3..=7 {
                    let k = sign * q / f64::from(1 << halvings);
                    let density = plane_wave_density(&model, r, k, phase, direction);
                    let expected =
                        d * r * r * (q.powi(4) + 4.0 * q.powi(3) * k + 6.0 * q * q * k * k);
                    let relative = (density - expected).abs() / expected;
                    assert!(relative < 1e-13, "k = {k}: density off by {relative:e}");
                    let error = d * r * r * (q + k).powi(4) - density;
                    if let Some(previous) = previous_error {
                        let ratio = previous / error;
                        let predicted = 8.0 * (4.0 * q + 2.0 * k) / (4.0 * q + k);
                        assert!(
                            (ratio / predicted - 1.0).abs() < 1e-9,
                            "k = {k}: error ratio {ratio}, predicted {predicted}"
                        );
                        assert!((ratio - 8.0).abs() < 0.13, "k = {k}: error ratio {ratio}");
                    }
                    previous_error = Some(error);
                }
            }
        }
    }
}

/// Smallest root of $`F(\lambda)`$ (module documentation): the complex envelope's threshold on
/// the clamped rectangle, by bisection on `[0.9, 1] × (42)` where `F` changes sign once.
fn complex_envelope_threshold(q: f64) -> f64 {
    let d = bending_stiffness();
    let (cx, cy) = (
        std::f64::consts::PI.powi(2) / (LX * LX),
        std::f64::consts::PI.powi(2) / (LY * LY),
    );
    let f = |lambda: f64| {
        let alpha = 6.0 * d * q * q - lambda;
        let c = 4.0 * d * q.powi(3) - 2.0 * q * lambda;
        alpha * cx + (TENSION + 2.0 * d * q * q) * cy + d * q.powi(4)
            - lambda * q * q
            - c * c / (4.0 * alpha)
    };
    let (mut low, mut high) = (0.9 * neutral_curve(q), neutral_curve(q));
    assert!(f(low) > 0.0 && f(high) <= 0.0);
    for _ in 0..100 {
        let middle = 0.5 * (low + high);
        if f(middle) > 0.0 {
            low = middle;
        } else {
            high = middle;
        }
    }
    0.5 * (low + high)
}

const MESH: (usize, usize) = (32, 16);

/// Phase-rotated mode $`(a, b) \mapsto (-b, a)`$ (other fields unchanged).
fn rotate_phase(problem: &Problem<ComplexEnvelope>, mode: &[f64]) -> Vec<f64> {
    let dofs = problem.dofs();
    let nf = dofs.field_count;
    let (a, b) = (
        ComplexEnvelope::SPEC.field_index("a").unwrap(),
        ComplexEnvelope::SPEC.field_index("b").unwrap(),
    );
    let mut rotated = mode.to_vec();
    for i in 0..mode.len() {
        let global = dofs.global_of_free(i);
        let (node, field) = (global / nf, global % nf);
        if field == a {
            let j = dofs.free(node, b).expect("a and b share their constraints");
            rotated[i] = -mode[j];
            rotated[j] = mode[i];
        }
    }
    rotated
}

/// $`\|(A + \lambda B)\varphi\|/\|A\varphi\|`$ at the pre-buckling state of `buckling`.
fn eigen_residual(
    problem: &Problem<ComplexEnvelope>,
    buckling: &LinearBuckling,
    load: f64,
    mode: &[f64],
) -> f64 {
    let n = problem.free_count();
    let (mut a, mut b) = (problem.new_matrix(), problem.new_matrix());
    problem.tangent_into(&buckling.prebuckling, 0.0, &mut a);
    problem.tangent_derivative_into(
        &buckling.prebuckling,
        0.0,
        &buckling.prebuckling_rate,
        1.0,
        &mut b,
    );
    let (mut am, mut bm) = (vec![0.0; n], vec![0.0; n]);
    a.multiply_into(mode, &mut am);
    b.multiply_into(mode, &mut bm);
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let residual: Vec<f64> = am.iter().zip(&bm).map(|(x, y)| x + load * y).collect();
    norm(&residual) / norm(&am)
}

/// Thresholds of both models on example 1 at `q`; checks the complex envelope's mode and its
/// two-fold degeneracy; returns `(reference, complex)`.
fn thresholds(q: f64) -> (f64, f64) {
    let (nx, ny) = MESH;
    let reference = buckle(&example1(envelope_model::<ReferenceEnvelope>(q), nx, ny));
    let problem = example1(envelope_model::<ComplexEnvelope>(q), nx, ny);
    let complex = buckle(&problem);
    let (lambda_ref, lambda) = (reference.critical_loads[0], complex.critical_loads[0]);
    let mode = &complex.modes[0];
    let magnitude = field_magnitudes(&problem, mode);
    let spec = ComplexEnvelope::SPEC;
    let envelope =
        magnitude[spec.field_index("a").unwrap()].max(magnitude[spec.field_index("b").unwrap()]);
    for field in ["u", "v", "w0", "theta_x", "theta_y"] {
        let m = magnitude[spec.field_index(field).unwrap()];
        assert!(
            m < 1e-8 * envelope,
            "mode has {field} {m:e} (envelope {envelope:e})"
        );
    }
    let rotated = rotate_phase(&problem, mode);
    let (residual, rotated_residual) = (
        eigen_residual(&problem, &complex, lambda, mode),
        eigen_residual(&problem, &complex, lambda, &rotated),
    );
    let overlap = mode.iter().zip(&rotated).map(|(x, y)| x * y).sum::<f64>()
        / mode.iter().map(|x| x * x).sum::<f64>();
    println!(
        "Q {q:.7}: λ_ref {lambda_ref:.10}, λ_complex {lambda:.10} (rel {:+.3e}); eigen-residual \
         {residual:.1e}, phase-rotated {rotated_residual:.1e}, overlap {overlap:.1e}",
        lambda / lambda_ref - 1.0
    );
    assert!(
        overlap.abs() < 1e-12,
        "rotated mode not independent: {overlap:e}"
    );
    assert!(
        rotated_residual < 1e-6 && rotated_residual < 10.0 * residual.max(1e-12),
        "phase-rotated mode is not a mode at the same load: {rotated_residual:e} ({residual:e})"
    );
    (lambda_ref, lambda)
}

#[test]
fn complex_envelope_example1_buckling_at_reference_optimum() {
    let q = optimal_wavenumber();
    let (lambda_ref, lambda) = thresholds(q);
    let predicted = complex_envelope_threshold(q) / neutral_curve(q) - 1.0;
    let measured = lambda / lambda_ref - 1.0;
    println!("relative shift: FE {measured:.6e}, closed form {predicted:.6e}");
    assert!(
        (predicted + 3.0e-5).abs() < 1e-7,
        "closed form {predicted:e}"
    );
    assert!(
        (measured / predicted - 1.0).abs() < 1e-3,
        "FE shift {measured:e} vs closed form {predicted:e}"
    );
}

#[test]
fn complex_envelope_example1_buckling_where_first_order_terms_cancel() {
    // Q* with (42) = 2DQ²: D s² − (4Dπ²/L_X² + 2Dπ²/L_Y²) s − N_Y π²/L_Y² = 0, s = Q².
    let d = bending_stiffness();
    let (cx, cy) = (
        std::f64::consts::PI.powi(2) / (LX * LX),
        std::f64::consts::PI.powi(2) / (LY * LY),
    );
    let half_sum = 2.0 * cx + cy;
    let q = (half_sum + (half_sum * half_sum + TENSION * cy / d).sqrt()).sqrt();
    assert!((neutral_curve(q) / (2.0 * d * q * q) - 1.0).abs() < 1e-14);
    let (lambda_ref, lambda) = thresholds(q);
    let difference = (lambda / lambda_ref - 1.0).abs();
    assert!(difference < 1e-8, "thresholds differ by {difference:e}");
}
