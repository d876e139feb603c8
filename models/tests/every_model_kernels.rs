//! Cross-checks of the generated kernels of **every registered model** (the registry is walked,
//! so a model is tested the moment it is registered).
//!
//! For each model and term, at seeded random jets with physically scaled magnitudes:
//! * residual = `Dual64` gradient of the generated energy (relative 1e-11) and = a 5-point central
//!   finite difference of it (relative 1e-6);
//! * tangent = `Dual64` Jacobian of the generated residual (relative 1e-11); entries outside the
//!   published pattern are zero there, and the pattern is symmetric;
//! * Taylor-mode kernels (`taylor_start` / `taylor_predict` / `taylor_commit`) = the generic
//!   residual on truncated `Series` (the reference path of the ANM), order by order up to 16,
//!   relative 1e-12 of each order's coefficient scale.
//!
//! Parameters are set by name: `young` 70000 MPa, `poisson` 0.3, `thickness` 0.05 mm,
//! `wavenumber` 0.23 /mm, `direction` 0.3 rad, anything else 1.

use num_dual::Dual64;
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_models::{ModelVisitor, catalogue, with_model};
use wrinkle_runtime::series::Series;
use wrinkle_runtime::{Derivative, EnergyModel, FieldRole};

const ORDERS: usize = 16;

fn parameter_value(name: &str) -> f64 {
    match name {
        "young" => 70000.0,
        "poisson" => 0.3,
        "thickness" => 0.05,
        "wavenumber" => 0.23,
        "direction" => 0.3,
        _ => 1.0,
    }
}

/// Magnitude of a jet entry: displacements ~ 1 mm with strains 1e-3, transverse fields ~ 0.1 mm
/// with slopes 5e-3.
fn jet_scale<M: EnergyModel>(model_jet_index: usize) -> f64 {
    let entry = M::SPEC.jet[model_jet_index];
    let transverse = M::SPEC.field_roles[entry.field].is_transverse();
    match (transverse, entry.derivative) {
        (false, Derivative::Value) => 1.0,
        (false, _) => 1e-3,
        (true, Derivative::Value) => 0.1,
        (true, _) => 5e-3,
    }
}

fn relative_error(value: &[f64], truth: &[f64]) -> f64 {
    let scale = truth.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let difference = value
        .iter()
        .zip(truth)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    if scale == 0.0 {
        difference
    } else {
        difference / scale
    }
}

struct Check {
    seed: u64,
}

impl ModelVisitor for Check {
    type Output = ();
    fn visit<M: EnergyModel>(self, mut model: M) {
        let spec = M::SPEC;
        assert_eq!(spec.field_roles.len(), spec.fields.len(), "{}", spec.name);
        for name in spec.parameters {
            model.set_parameter(name, parameter_value(name)).unwrap();
        }
        let mut rng = StdRng::seed_from_u64(self.seed);
        for (t, term) in spec.terms.iter().enumerate() {
            let m = term.jet.len();
            let scales: Vec<f64> = term.jet.iter().map(|&i| jet_scale::<M>(i)).collect();
            for _ in 0..10 {
                let jet: Vec<f64> = scales
                    .iter()
                    .map(|s| s * rng.random_range(-1.0..1.0))
                    .collect();
                check_derivatives(&model, t, &jet, &scales);
                check_taylor(&model, t, &scales, &mut rng);
            }
            // The published pattern is the upper triangle, without duplicates.
            for &(i, j) in term.tangent_pattern {
                assert!(i <= j && j < m, "{}: pattern entry ({i}, {j})", spec.name);
            }
        }
    }
}

fn check_derivatives<M: EnergyModel>(model: &M, t: usize, jet: &[f64], scales: &[f64]) {
    let spec = M::SPEC;
    let m = jet.len();
    let mut residual = vec![0.0; m];
    model.residual(t, jet, &mut residual);
    // Dual64 gradient and finite differences of the energy.
    let mut gradient = vec![0.0; m];
    let mut finite = vec![0.0; m];
    for i in 0..m {
        let dual: Vec<Dual64> = jet
            .iter()
            .enumerate()
            .map(|(k, &x)| Dual64::new(x, if k == i { 1.0 } else { 0.0 }))
            .collect();
        gradient[i] = model.energy(t, &dual).eps;
        let h = 1e-3 * scales[i];
        let at = |d: f64| {
            let mut y = jet.to_vec();
            y[i] += d;
            model.energy(t, &y)
        };
        finite[i] = (8.0 * (at(h) - at(-h)) - (at(2.0 * h) - at(-2.0 * h))) / (12.0 * h);
    }
    let name = spec.name;
    let term = spec.terms[t].name;
    assert!(
        relative_error(&residual, &gradient) < 1e-11,
        "{name}/{term}: residual vs Dual64 gradient {:e}",
        relative_error(&residual, &gradient)
    );
    assert!(
        relative_error(&residual, &finite) < 1e-6,
        "{name}/{term}: residual vs finite differences {:e}",
        relative_error(&residual, &finite)
    );
    // Dual64 Jacobian of the residual against the packed tangent.
    let pattern = spec.terms[t].tangent_pattern;
    let mut packed = vec![0.0; pattern.len()];
    model.tangent(t, jet, &mut packed);
    let mut dense = vec![0.0; m * m];
    for (p, &(i, j)) in pattern.iter().enumerate() {
        dense[i * m + j] = packed[p];
        dense[j * m + i] = packed[p];
    }
    let mut jacobian = vec![0.0; m * m];
    for j in 0..m {
        let dual: Vec<Dual64> = jet
            .iter()
            .enumerate()
            .map(|(k, &x)| Dual64::new(x, if k == j { 1.0 } else { 0.0 }))
            .collect();
        let mut out = vec![Dual64::from(0.0); m];
        model.residual(t, &dual, &mut out);
        for i in 0..m {
            jacobian[i * m + j] = out[i].eps;
        }
    }
    assert!(
        relative_error(&dense, &jacobian) < 1e-11,
        "{name}/{term}: tangent vs Dual64 Jacobian {:e}",
        relative_error(&dense, &jacobian)
    );
}

fn check_taylor<M: EnergyModel>(model: &M, t: usize, scales: &[f64], rng: &mut StdRng) {
    let spec = M::SPEC;
    let m = scales.len();
    // Jet coefficients J_0..J_N, decaying like a convergent series of radius ~2.
    let coefficients: Vec<Vec<f64>> = (0..=ORDERS)
        .map(|k| {
            scales
                .iter()
                .map(|s| s * 0.5f64.powi(k as i32) * rng.random_range(-1.0..1.0))
                .collect()
        })
        .collect();
    // Rows of `stride` > slots entries, one per order: the padding and every row not yet
    // written are NaN, so a kernel reading outside its slots or ahead of its order fails.
    let slots = spec.terms[t].taylor_slots;
    let stride = slots + 2;
    let mut tape = vec![f64::NAN; (ORDERS + 1) * stride];
    model.taylor_start(t, &coefficients[0], &mut tape, stride);
    for k in 1..=ORDERS {
        // Reference: the residual of the series truncated at order k−1, evaluated to order k.
        let jet: Vec<Series> = (0..m)
            .map(|i| {
                let mut c: Vec<f64> = (0..=k).map(|j| coefficients[j][i]).collect();
                c[k] = 0.0;
                Series::from_coefficients(&c).unwrap()
            })
            .collect();
        let mut out = vec![Series::zeros(k + 1); m];
        model.residual(t, &jet, &mut out);
        let reference: Vec<f64> = out.iter().map(|r| r.coefficient(k)).collect();
        let mut predicted = vec![0.0; m];
        model.taylor_predict(t, k, &mut tape, stride, &mut predicted);
        let error = relative_error(&predicted, &reference);
        assert!(
            error < 1e-12,
            "{}/{}: Taylor-mode order {k} differs from the Series path by {error:e}",
            spec.name,
            spec.terms[t].name
        );
        if spec.terms[t].linear_residual {
            assert!(predicted.iter().all(|&r| r == 0.0));
        }
        model.taylor_commit(t, k, &coefficients[k], &mut tape, stride);
    }
}

#[test]
fn every_registered_model_has_consistent_kernels() {
    let names: Vec<&str> = catalogue().iter().map(|s| s.name).collect();
    assert!(!names.is_empty());
    for (k, name) in names.iter().enumerate() {
        with_model(name, Check { seed: 7 + k as u64 }).expect("registered");
    }
}

#[test]
fn every_registered_model_declares_its_field_roles() {
    for spec in catalogue() {
        assert!(
            spec.field_roles.iter().all(|r| *r != FieldRole::Other),
            "model `{}` has a field without a role",
            spec.name
        );
    }
}

/// The assembled sparse tangent of every model, on a 2 × 1 Q8 mesh (3 Hermite2 line elements
/// for a model with second derivatives) at a random state, equals the
/// `Dual64` Jacobian of the assembled internal forces entry by entry — so the sparsity pattern,
/// which leaves out the field blocks no term couples (`field_couplings`), drops nothing.
struct AssembledTangent;

impl ModelVisitor for AssembledTangent {
    type Output = ();
    fn visit<M: EnergyModel>(self, mut model: M) {
        use std::sync::Arc;
        use wrinkle_runtime::fem::Mesh;
        use wrinkle_runtime::fem::assembly::field_couplings;
        use wrinkle_runtime::problem::Problem;
        let spec = M::SPEC;
        for name in spec.parameters {
            model.set_parameter(name, parameter_value(name)).unwrap();
        }
        // A model reading second derivatives (the beam's `v.xx`) on the element that has them.
        let second = spec.jet.iter().any(|entry| entry.derivative.order() == 2);
        let mesh = if second {
            Mesh::line(20.0, 3, 1.0, wrinkle_runtime::fem::ElementKind::Hermite2).unwrap()
        } else {
            Mesh::rectangle(20.0, 10.0, 2, 1, 1.0).unwrap()
        };
        let mesh = Arc::new(mesh);
        let problem = Problem::new(model, mesh, &[], &Default::default()).unwrap();
        let n = problem.free_count();
        let nf = spec.fields.len();
        let mut rng = StdRng::seed_from_u64(11);
        let state: Vec<f64> = (0..n)
            .map(|i| {
                let transverse = spec.field_roles[i % nf].is_transverse();
                (if transverse { 0.1 } else { 0.01 }) * rng.random_range(-1.0..1.0)
            })
            .collect();
        let global = problem.assembler.dofs().expand(&state, 0.0);
        let values = problem.assembler.tangent_values::<f64>(&global);
        let pattern = problem.assembler.pattern();
        let mut sparse = vec![0.0; n * n];
        for column in 0..n {
            let range = pattern.col_ptr()[column]..pattern.col_ptr()[column + 1];
            for (slot, &row) in range.clone().zip(&pattern.row_idx()[range]) {
                sparse[row * n + column] = values[slot];
            }
        }
        let mut scale = 0.0_f64;
        let mut worst = 0.0_f64;
        for b in 0..n {
            let seeded: Vec<Dual64> = state
                .iter()
                .enumerate()
                .map(|(i, &x)| Dual64::new(x, if i == b { 1.0 } else { 0.0 }))
                .collect();
            let global = problem.assembler.dofs().expand(&seeded, Dual64::from(0.0));
            let forces = problem.assembler.internal_forces(&global);
            for (a, force) in forces.iter().enumerate() {
                scale = scale.max(force.eps.abs());
                worst = worst.max((force.eps - sparse[a * n + b]).abs());
            }
        }
        assert!(
            worst <= 1e-11 * scale,
            "{}: assembled tangent vs Dual64 Jacobian {worst:e} (scale {scale:e})",
            spec.name
        );
        let couplings = field_couplings(spec);
        let full = problem.assembler.dofs().field_count.pow(2);
        let kept = couplings.iter().filter(|&&c| c).count();
        println!(
            "{}: {kept} of {full} field blocks coupled, pattern nnz {}",
            spec.name,
            pattern.nnz()
        );
    }
}

#[test]
fn every_registered_model_assembles_its_whole_tangent_on_the_coupled_pattern() {
    for spec in catalogue() {
        with_model(spec.name, AssembledTangent).expect("registered");
    }
    // The plate's in-plane displacements and rotations are not coupled by any term.
    let spec = catalogue()
        .into_iter()
        .find(|s| s.name == "fvk-plate")
        .expect("fvk-plate is registered");
    let nf = spec.fields.len();
    let field = |name| spec.fields.iter().position(|f| *f == name).unwrap();
    let couplings = wrinkle_runtime::fem::assembly::field_couplings(spec);
    assert!(!couplings[field("u") * nf + field("theta_x")]);
    assert!(!couplings[field("v") * nf + field("theta_y")]);
    assert!(couplings[field("u") * nf + field("w")]);
    assert!(couplings[field("w") * nf + field("theta_x")]);
}
