//! The reference envelope model declared through the macro: generated residual and tangent
//! against num-dual derivatives and central finite differences of the generated energy,
//! plus the `ModelSpec` metadata.

use num_dual::{Dual64, HyperDual64};
use wrinkle_runtime::{Derivative, EnergyModel, JetEntry, QuadratureRule};

wrinkle_macros::energy_model! {
    /// Reference envelope model of Damil, Potier-Ferry & Hu (2014), eqs 22, 23, 64.
    model ReferenceEnvelope as "reference-envelope" {
        fields: u, v, w;
        parameters: young "Young's modulus E (MPa)", poisson "Poisson ratio", thickness, wavenumber, direction;
        let c = cos(direction);
        let s = sin(direction);
        let stiffness = young * thickness / (1 - poisson^2);
        let d = young * thickness^3 / (12 * (1 - poisson^2));
        let gx = u.x + w.x^2 + (wavenumber * c)^2 * w^2;
        let gy = v.y + w.y^2 + (wavenumber * s)^2 * w^2;
        let gxy = u.y + v.x + 2 * w.x * w.y + 2 * wavenumber^2 * c * s * w^2;
        energy membrane = 0.5 * stiffness * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
        energy bending = d * (wavenumber^4 * w^2 + 6 * wavenumber^2 * (c * w.x + s * w.y)^2
                              + 2 * wavenumber^2 * (c * w.y - s * w.x)^2);
    }
}

/// A tiny deterministic generator (64-bit LCG, top 53 bits).
struct Lcg(u64);

impl Lcg {
    fn uniform(&mut self, low: f64, high: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let unit = (self.0 >> 11) as f64 / (1u64 << 53) as f64;
        low + (high - low) * unit
    }
}

fn model() -> ReferenceEnvelope {
    ReferenceEnvelope::new(3.5, 0.3, 0.2, 1.7, 0.4)
}

fn relative_error(value: f64, truth: f64) -> f64 {
    (value - truth).abs() / truth.abs().max(1.0)
}

/// The 20 seeded term-local jets of one term.
fn jets(term: usize) -> Vec<Vec<f64>> {
    let length = ReferenceEnvelope::SPEC.terms[term].jet.len();
    let mut random = Lcg(2014 + term as u64);
    (0..20)
        .map(|_| (0..length).map(|_| random.uniform(-0.6, 0.6)).collect())
        .collect()
}

#[test]
fn spec_metadata_matches_the_declaration() {
    let spec = ReferenceEnvelope::SPEC;
    assert_eq!(spec.name, "reference-envelope");
    assert_eq!(
        spec.description,
        "Reference envelope model of Damil, Potier-Ferry & Hu (2014), eqs 22, 23, 64."
    );
    assert_eq!(spec.fields, ["u", "v", "w"]);
    assert_eq!(
        spec.parameters,
        ["young", "poisson", "thickness", "wavenumber", "direction"]
    );
    let entry = |field, derivative| JetEntry { field, derivative };
    assert_eq!(
        spec.jet,
        [
            entry(0, Derivative::X),
            entry(0, Derivative::Y),
            entry(1, Derivative::X),
            entry(1, Derivative::Y),
            entry(2, Derivative::Value),
            entry(2, Derivative::X),
            entry(2, Derivative::Y),
        ]
    );
    assert_eq!(spec.terms.len(), 2);
    assert_eq!(spec.terms[0].name, "membrane");
    assert_eq!(spec.terms[1].name, "bending");
    assert_eq!(spec.terms[0].quadrature, QuadratureRule::Full);
    assert_eq!(spec.terms[0].jet, [0, 1, 2, 3, 4, 5, 6]);
    assert_eq!(spec.terms[1].jet, [4, 5, 6]);
    for term in spec.terms {
        assert!(term.jet.windows(2).all(|pair| pair[0] < pair[1]));
        let pattern = term.tangent_pattern;
        assert!(pattern.iter().all(|&(i, j)| i <= j && j < term.jet.len()));
        assert!(
            pattern.windows(2).all(|pair| pair[0] < pair[1]),
            "row-major, no repeats"
        );
    }
    assert_eq!(
        spec.terms[1].tangent_pattern,
        [(0, 0), (1, 1), (1, 2), (2, 2)]
    );
    assert!(spec.needs_gradient(0) && spec.needs_gradient(1) && spec.needs_gradient(2));
    assert!(spec.simplification_report.contains("term `membrane`"));
    assert!(spec.simplification_report.contains("stopped: "));
    let instance = model();
    assert_eq!(instance.parameter_values(), [3.5, 0.3, 0.2, 1.7, 0.4]);
    assert_eq!(
        ReferenceEnvelope::from_parameters(&instance.parameter_values()),
        instance
    );
    assert_eq!(instance.parameter("wavenumber"), Some(1.7));
}

#[test]
fn residual_and_tangent_agree_with_num_dual() {
    let model = model();
    for (term, spec) in ReferenceEnvelope::SPEC.terms.iter().enumerate() {
        let n = spec.jet.len();
        for jet in jets(term) {
            let mut residual = vec![0.0; n];
            model.residual::<f64>(term, &jet, &mut residual);
            let mut tangent = vec![0.0; spec.tangent_pattern.len()];
            model.tangent::<f64>(term, &jet, &mut tangent);
            for (i, &exact) in residual.iter().enumerate() {
                let dual: Vec<Dual64> = jet
                    .iter()
                    .enumerate()
                    .map(|(k, &x)| Dual64::new(x, if k == i { 1.0 } else { 0.0 }))
                    .collect();
                let gradient = model.energy(term, &dual).eps;
                assert!(
                    relative_error(exact, gradient) < 1e-10,
                    "{} residual {i}: {exact} vs {gradient}",
                    spec.name
                );
            }
            for i in 0..n {
                for j in i..n {
                    let hyper: Vec<HyperDual64> = jet
                        .iter()
                        .enumerate()
                        .map(|(k, &x)| {
                            HyperDual64::new(
                                x,
                                if k == i { 1.0 } else { 0.0 },
                                if k == j { 1.0 } else { 0.0 },
                                0.0,
                            )
                        })
                        .collect();
                    let second = model.energy(term, &hyper).eps1eps2;
                    match spec.tangent_pattern.iter().position(|&e| e == (i, j)) {
                        Some(p) => assert!(
                            relative_error(tangent[p], second) < 1e-10,
                            "{} tangent ({i},{j}): {} vs {second}",
                            spec.name,
                            tangent[p]
                        ),
                        None => assert_eq!(second, 0.0, "{} ({i},{j}) is not zero", spec.name),
                    }
                }
            }
        }
    }
}

#[test]
fn residual_and_tangent_agree_with_finite_differences() {
    let model = model();
    let step = 1e-6;
    for (term, spec) in ReferenceEnvelope::SPEC.terms.iter().enumerate() {
        let n = spec.jet.len();
        for jet in jets(term) {
            let mut residual = vec![0.0; n];
            model.residual::<f64>(term, &jet, &mut residual);
            let mut tangent = vec![0.0; spec.tangent_pattern.len()];
            model.tangent::<f64>(term, &jet, &mut tangent);
            for i in 0..n {
                let (mut plus, mut minus) = (jet.clone(), jet.clone());
                plus[i] += step;
                minus[i] -= step;
                let difference = (model.energy::<f64>(term, &plus)
                    - model.energy::<f64>(term, &minus))
                    / (2.0 * step);
                assert!(
                    relative_error(residual[i], difference) < 1e-6,
                    "{} residual {i}: {} vs FD {difference}",
                    spec.name,
                    residual[i]
                );
                // Row i of the Hessian by differences of the residual.
                let mut residual_plus = vec![0.0; n];
                let mut residual_minus = vec![0.0; n];
                model.residual::<f64>(term, &plus, &mut residual_plus);
                model.residual::<f64>(term, &minus, &mut residual_minus);
                for j in 0..n {
                    let difference = (residual_plus[j] - residual_minus[j]) / (2.0 * step);
                    let (a, b) = (i.min(j), i.max(j));
                    let exact = spec
                        .tangent_pattern
                        .iter()
                        .position(|&e| e == (a, b))
                        .map_or(0.0, |p| tangent[p]);
                    assert!(
                        relative_error(exact, difference) < 1e-6,
                        "{} tangent ({a},{b}): {exact} vs FD {difference}",
                        spec.name
                    );
                }
            }
        }
    }
}

#[test]
fn energy_has_the_closed_form_value_in_plain_stretching() {
    // With w = 0 only the in-plane strains remain: membrane = ½ C (ex² + ey² + 2ν ex ey
    // + ½(1-ν) gxy²) with C = E t/(1-ν²).
    let model = model();
    let (ux, uy, vx, vy) = (0.01, -0.02, 0.03, 0.005);
    let energy = model.energy::<f64>(0, &[ux, uy, vx, vy, 0.0, 0.0, 0.0]);
    let (e, nu, t): (f64, f64, f64) = (3.5, 0.3, 0.2);
    let c = e * t / (1.0 - nu * nu);
    let gxy = uy + vx;
    let truth = 0.5 * c * (ux * ux + vy * vy + 2.0 * nu * ux * vy + 0.5 * (1.0 - nu) * gxy * gxy);
    assert!(relative_error(energy, truth) < 1e-14);
}
