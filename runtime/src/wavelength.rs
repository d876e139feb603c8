//! What a model needs to find its wrinkle wavelength at the threshold, derived from its declared
//! roles and its jet ([`ModelSpec::wavelength_selection`]), never from its name.
//!
//! An envelope model (THEORY.md §3–§6) describes the wrinkles as a carrier
//! $`\cos(Q\,\mathbf e\cdot\mathbf X)`$ of wavenumber $`Q`$ — a parameter named `wavenumber` —
//! modulated by a slowly varying envelope. Its critical load $`\lambda_c(Q)`$ is a function of
//! that parameter, and the threshold is its minimum over $`Q`$ when the model selects a
//! wavelength at all:
//! * the bending energy of a real envelope with gradient stiffness grows as $`DQ^4`$ at short
//!   wavelengths, and the membrane coupling of its envelope gradient penalises long ones (eq. 42
//!   on the clamped rectangle), so $`\lambda_c(Q)`$ has a minimum: the model selects its own
//!   wavelength ([`WavelengthSelection::OwnMinimum`]);
//! * an envelope without gradient stiffness (no term reads its first derivatives — the pure
//!   membrane, threshold $`DQ^2`$) has a $`\lambda_c(Q)`$ that falls with $`Q`$ to the end of
//!   any range: nothing selects a wavelength;
//! * a complex envelope $`w_1 = a + ib`$ (a field of role `envelope_imaginary`, a phase) moves
//!   its local wavenumber $`Q + \partial\arg w_1`$ freely, and its bending is a second-order
//!   expansion about $`Q`$, so its own $`\lambda_c(Q)`$ is meaningless away from the optimum of a
//!   model that does select (measured on example 1: a spurious minimum at $`Q = 0.099`$/mm,
//!   $`\lambda_c`$ half the plate's).
//!
//! The last two take $`Q`$ from another model ([`WavelengthSelection::Carried`]); a model
//! without a `wavenumber` parameter (the plate) resolves the wrinkles themselves on the mesh and
//! has no $`Q`$ at all ([`WavelengthSelection::ResolvedByMesh`]).

use crate::model::{FieldRole, ModelSpec};

/// Name of the model parameter that is the carrier wavenumber $`Q`$ (1/mm) of an envelope model.
pub const WAVENUMBER_PARAMETER: &str = "wavenumber";

/// How a model's threshold gets its wrinkle wavelength (module documentation).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WavelengthSelection {
    /// A `wavenumber` parameter, an envelope with gradient stiffness and no phase: the minimum of
    /// $`\lambda_c(Q)`$ over $`Q`$ is the model's own wavelength.
    OwnMinimum,
    /// A `wavenumber` parameter but no selection of its own: $`Q`$ is carried from a model that
    /// selects it (the scene's `model.wavenumber_model`).
    Carried(CarriedBecause),
    /// No `wavenumber` parameter: the wrinkles are fields of the model, resolved by the mesh.
    ResolvedByMesh,
}

/// Why a model with a `wavenumber` parameter does not select its own wavelength.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CarriedBecause {
    /// Its envelope has a phase (a field of role `envelope_imaginary`): the local wavenumber is
    /// free and the bending is only valid near the carrier.
    Phase,
    /// No term reads the gradient of its envelope (or it has no envelope field): its threshold
    /// falls with $`Q`$ (the pure membrane's $`DQ^2`$).
    NoEnvelopeGradient,
}

impl WavelengthSelection {
    /// Whether the model minimises $`\lambda_c(Q)`$ itself (and so can give $`Q`$ to others).
    pub fn selects_its_own(self) -> bool {
        self == WavelengthSelection::OwnMinimum
    }
}

impl ModelSpec {
    /// What the model needs for its threshold's wavelength, from its parameters, roles and jet
    /// (module documentation): a `wavenumber` parameter, the envelope field (role `envelope`, or
    /// `envelope_real` of a complex envelope) and whether any term reads its gradient, and a
    /// field of role `envelope_imaginary`.
    pub fn wavelength_selection(&self) -> WavelengthSelection {
        if self.parameter_index(WAVENUMBER_PARAMETER).is_none() {
            return WavelengthSelection::ResolvedByMesh;
        }
        if self.field_with_role(FieldRole::EnvelopeImaginary).is_some() {
            return WavelengthSelection::Carried(CarriedBecause::Phase);
        }
        let envelope = self
            .field_with_role(FieldRole::Envelope)
            .or_else(|| self.field_with_role(FieldRole::EnvelopeReal));
        match envelope {
            Some(field) if self.needs_gradient(field) => WavelengthSelection::OwnMinimum,
            _ => WavelengthSelection::Carried(CarriedBecause::NoEnvelopeGradient),
        }
    }
}
