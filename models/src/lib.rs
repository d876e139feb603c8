//! Wrinkling models declared as energy densities in the `energy_model!` DSL, and a registry
//! that lets the CLI pick one by name while every solver stays monomorphised per model.
//!
//! **Adding a model** is one new file in this directory (an `energy_model!` declaration with
//! field roles) plus one line in the `registry!` invocation below: the catalogue, the dispatch
//! by name, `wrinkle models`, and the kernel cross-checks of `tests/every_model_kernels.rs`
//! (generated kernels against dual numbers and finite differences) all follow from that line.

use wrinkle_runtime::{EnergyModel, ModelSpec};

#[doc(hidden)]
pub use wrinkle_macros as __macros;

pub mod microscopic;

/// Something to do with a model chosen at run time: `visit` is monomorphised per model.
pub trait ModelVisitor {
    /// What the visit returns.
    type Output;
    /// Called with a model instance whose parameters are all zero (set them by name).
    fn visit<M: EnergyModel>(self, model: M) -> Self::Output;
}

fn zero_instance<M: EnergyModel>() -> M {
    M::from_parameters(&vec![0.0; M::SPEC.parameters.len()])
}

/// Declares the registered models, `module::Type` each, in catalogue order: the modules, their
/// re-exports, [`catalogue`] and [`with_model`].
macro_rules! registry {
    ($($module:ident :: $model:ident),+ $(,)?) => {
        $(pub mod $module; pub use $module::$model;)+

        /// Specifications of every registered model, in registry order.
        pub fn catalogue() -> Vec<&'static ModelSpec> {
            vec![$(<$model as EnergyModel>::SPEC),+]
        }

        /// Runs `visitor` on the model named `name`; `None` if there is no such model.
        pub fn with_model<V: ModelVisitor>(name: &str, visitor: V) -> Option<V::Output> {
            $(if name == <$model as EnergyModel>::SPEC.name {
                return Some(visitor.visit(zero_instance::<$model>()));
            })+
            None
        }
    };
}

registry! {
    fvk_plate::FvkPlate,
    complex_envelope::ComplexEnvelope,
    reference_envelope::ReferenceEnvelope,
    pure_membrane::PureMembrane,
    beam_full::BeamFull,
    beam_envelope::BeamEnvelope,
    beam_complex_envelope::BeamComplexEnvelope,
    derived_reference_envelope::DerivedReferenceEnvelope,
    derived_complex_envelope::DerivedComplexEnvelope,
    two_harmonic_envelope::TwoHarmonicEnvelope,
}

/// Names of every registered model.
pub fn names() -> Vec<&'static str> {
    catalogue().iter().map(|s| s.name).collect()
}

/// Name of the registry's reference model, [`ReferenceEnvelope`] (`"reference-envelope"`,
/// THEORY.md §4): the default of a scene's `model.name`, and of `model.wavenumber_model`, the
/// model whose minimisation of $`\lambda_c(Q)`$ gives the wavenumber $`Q`$ to models that do not
/// select their own. Taken from the model's declaration, so it cannot drift from it.
pub const REFERENCE_MODEL: &str = <ReferenceEnvelope as EnergyModel>::SPEC.name;
