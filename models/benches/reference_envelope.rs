//! Generated tangent kernel vs a num-dual Hessian, per quadrature point, for the reference
//! envelope model (mirrors `models/src/reference_envelope.rs`).
//!
//! `cargo bench -p wrinkle-models --bench reference_envelope`

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::SVector;
use num_dual::{Dual2SVec64, hessian};
use std::hint::black_box;
use wrinkle_models::ReferenceEnvelope;
use wrinkle_runtime::EnergyModel;

fn model() -> ReferenceEnvelope {
    ReferenceEnvelope::from_parameters(&[70000.0, 0.3, 0.05, 0.1, 0.0])
}

fn kernels(c: &mut Criterion) {
    let m = model();
    let spec = ReferenceEnvelope::SPEC;
    let membrane = spec
        .terms
        .iter()
        .position(|t| t.name == "membrane")
        .unwrap();
    let bending = spec.terms.iter().position(|t| t.name == "bending").unwrap();
    assert_eq!(spec.terms[membrane].jet.len(), 7);
    assert_eq!(spec.terms[bending].jet.len(), 3);
    let membrane_jet = [1.1e-3, -2.0e-4, 3.0e-4, -7.0e-4, 0.04, 2.0e-3, -1.0e-3];
    let bending_jet = [0.04, 2.0e-3, -1.0e-3];

    let mut group = c.benchmark_group("tangent_per_quadrature_point");
    group.bench_function("generated", |b| {
        let mut out_m = vec![0.0; spec.terms[membrane].tangent_pattern.len()];
        let mut out_b = vec![0.0; spec.terms[bending].tangent_pattern.len()];
        b.iter(|| {
            m.tangent(membrane, black_box(&membrane_jet[..]), &mut out_m);
            m.tangent(bending, black_box(&bending_jet[..]), &mut out_b);
            black_box((&out_m, &out_b));
        })
    });
    group.bench_function("num_dual_hessian", |b| {
        let xm = SVector::<f64, 7>::from(membrane_jet);
        let xb = SVector::<f64, 3>::from(bending_jet);
        b.iter(|| {
            let hm = hessian(
                |x: SVector<Dual2SVec64<7>, 7>| m.energy(membrane, x.as_slice()),
                black_box(&xm),
            );
            let hb = hessian(
                |x: SVector<Dual2SVec64<3>, 3>| m.energy(bending, x.as_slice()),
                black_box(&xb),
            );
            black_box((hm, hb));
        })
    });
    group.finish();

    let mut group = c.benchmark_group("residual_per_quadrature_point");
    group.bench_function("generated", |b| {
        let mut out = [0.0; 7];
        b.iter(|| {
            m.residual(membrane, black_box(&membrane_jet[..]), &mut out);
            black_box(&out);
        })
    });
    group.finish();
}

criterion_group!(benches, kernels);
criterion_main!(benches);
