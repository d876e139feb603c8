//! Wrinkling models declared as energy densities in the `energy_model!` DSL, and a registry
//! that lets the CLI pick one by name while every solver stays monomorphised per model.

pub mod fvk_plate;
pub mod reference_envelope;

pub use fvk_plate::FvkPlate;
pub use reference_envelope::ReferenceEnvelope;

use wrinkle_runtime::{EnergyModel, ModelSpec};

/// Something to do with a model chosen at run time: `visit` is monomorphised per model.
pub trait ModelVisitor {
    /// What the visit returns.
    type Output;
    /// Called with a model instance whose parameters are all zero (set them by name).
    fn visit<M: EnergyModel>(self, model: M) -> Self::Output;
}

/// Specifications of every registered model, in registry order.
pub fn catalogue() -> Vec<&'static ModelSpec> {
    vec![ReferenceEnvelope::SPEC, FvkPlate::SPEC]
}

/// Names of every registered model.
pub fn names() -> Vec<&'static str> {
    catalogue().iter().map(|s| s.name).collect()
}

fn zero_instance<M: EnergyModel>() -> M {
    M::from_parameters(&vec![0.0; M::SPEC.parameters.len()])
}

/// Runs `visitor` on the model named `name`; `None` if there is no such model.
pub fn with_model<V: ModelVisitor>(name: &str, visitor: V) -> Option<V::Output> {
    match name {
        "reference-envelope" => Some(visitor.visit(zero_instance::<ReferenceEnvelope>())),
        "fvk-plate" => Some(visitor.visit(zero_instance::<FvkPlate>())),
        _ => None,
    }
}
