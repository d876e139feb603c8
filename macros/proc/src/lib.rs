//! Procedural-macro shim of the wrinkle energy DSL.
//!
//! All the work (parsing, validation, differentiation, e-graph simplification, code
//! generation) lives in the plain library `wrinkle-energy`; see `docs/dsl.md` for the
//! language reference.

use proc_macro::TokenStream;

/// Declares an energy-density model and generates its parameter struct and its
/// `wrinkle_runtime::EnergyModel` implementation (energy, residual and tangent kernels).
///
/// ```ignore
/// wrinkle_macros::energy_model! {
///     /// Linear bar on an elastic foundation.
///     model Bar as "bar" {
///         fields: w;
///         parameters: stiffness "axial stiffness", foundation;
///         energy stretching = 0.5 * stiffness * w.x^2;
///         energy support = 0.5 * foundation * w^2;
///     }
/// }
/// ```
#[proc_macro]
pub fn energy_model(input: TokenStream) -> TokenStream {
    wrinkle_energy::expand(input.into()).into()
}
