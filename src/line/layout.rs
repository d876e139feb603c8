//! What a line model's fields are, from their roles ([`FieldRole`]), never from their names:
//! the axial displacement, the fields held at a supported end, and how the physical deflection
//! is built.
//!
//! Physical deflection $`w(X)`$ (the beam's $`v`$; THEORY.md §7, the paper's (6)–(8)):
//! * role `deflection`: $`w`$ itself (the full beam, every wave resolved);
//! * role `envelope` $`v_1`$: $`w = 2v_1\cos QX`$, local amplitude $`2|v_1|`$;
//! * roles `envelope_real` $`a`$, `envelope_imaginary` $`b`$:
//!   $`w = 2\,\mathrm{Re}\big((a + ib)e^{iQX}\big) = 2(a\cos QX - b\sin QX)`$, local amplitude
//!   $`2\sqrt{a^2 + b^2}`$.

use wrinkle_runtime::fem::Mesh;
use wrinkle_runtime::{FieldRole, ModelSpec};

/// How the physical deflection is built from the fields.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineDeflection {
    /// The deflection is a field.
    Resolved {
        /// Field of role `deflection`.
        deflection: usize,
    },
    /// A real envelope of the first harmonic.
    RealEnvelope {
        /// Field of role `envelope`.
        envelope: usize,
    },
    /// A complex envelope $`a + ib`$.
    ComplexEnvelope {
        /// Field of role `envelope_real`.
        real: usize,
        /// Field of role `envelope_imaginary`.
        imaginary: usize,
    },
}

/// The fields of a line model by what they are.
#[derive(Clone, Debug, PartialEq)]
pub struct LineLayout {
    /// Number of fields.
    pub field_count: usize,
    /// The axial displacement $`u`$ (role `displacement_x`).
    pub axial: usize,
    /// How the physical deflection is built.
    pub deflection: LineDeflection,
}

impl LineLayout {
    /// Reads the layout from the roles of `spec`. A model with a field of role
    /// `displacement_y` is a plane model; one without `displacement_x` or a transverse field
    /// cannot run on a line: the message names the model and the domain.
    pub fn from_spec(spec: &ModelSpec) -> Result<LineLayout, String> {
        let role = |r: FieldRole| spec.field_with_role(r);
        if role(FieldRole::DisplacementY).is_some() {
            return Err(format!(
                "model `{}` is a plane model (it has a field of role `displacement_y`) and the \
                 scene's domain is a line (geometry.kind = \"line\"): choose a line model, or \
                 geometry.kind = \"plane\"",
                spec.name
            ));
        }
        let cannot = |what: &str| {
            format!(
                "model `{}` cannot run on a line domain: it declares no {what}",
                spec.name
            )
        };
        let axial =
            role(FieldRole::DisplacementX).ok_or_else(|| cannot("field of role displacement_x"))?;
        let deflection = if let Some(w) = role(FieldRole::Deflection) {
            LineDeflection::Resolved { deflection: w }
        } else if let Some(w) = role(FieldRole::Envelope) {
            LineDeflection::RealEnvelope { envelope: w }
        } else if let (Some(real), Some(imaginary)) = (
            role(FieldRole::EnvelopeReal),
            role(FieldRole::EnvelopeImaginary),
        ) {
            LineDeflection::ComplexEnvelope { real, imaginary }
        } else {
            return Err(cannot(
                "transverse field (role deflection, envelope, or envelope_real and envelope_imaginary)",
            ));
        };
        Ok(LineLayout {
            field_count: spec.fields.len(),
            axial,
            deflection,
        })
    }

    /// Whether the model describes the waves by an envelope (and needs a wavenumber).
    pub fn is_envelope(&self) -> bool {
        !matches!(self.deflection, LineDeflection::Resolved { .. })
    }

    /// Every field but the axial displacement: held at a supported end.
    pub fn transverse(&self) -> Vec<usize> {
        (0..self.field_count).filter(|&f| f != self.axial).collect()
    }

    /// The physical deflection $`w(X)`$ of the nodal values `global` at `x`.
    pub fn deflection_at(&self, mesh: &Mesh, global: &[f64], wavenumber: f64, x: f64) -> f64 {
        let value = |field| {
            mesh.interpolate(global, self.field_count, field, [x, 0.0])
                .unwrap_or(f64::NAN)
        };
        let phase = wavenumber * x;
        match self.deflection {
            LineDeflection::Resolved { deflection } => value(deflection),
            LineDeflection::RealEnvelope { envelope } => 2.0 * value(envelope) * phase.cos(),
            LineDeflection::ComplexEnvelope { real, imaginary } => {
                2.0 * (value(real) * phase.cos() - value(imaginary) * phase.sin())
            }
        }
    }

    /// The envelope's local physical amplitude $`2|v_1|`$ at `x`; `None` for a model that
    /// resolves the waves.
    pub fn envelope_amplitude_at(&self, mesh: &Mesh, global: &[f64], x: f64) -> Option<f64> {
        let value = |field| {
            mesh.interpolate(global, self.field_count, field, [x, 0.0])
                .unwrap_or(f64::NAN)
        };
        match self.deflection {
            LineDeflection::Resolved { .. } => None,
            LineDeflection::RealEnvelope { envelope } => Some(2.0 * value(envelope).abs()),
            LineDeflection::ComplexEnvelope { real, imaginary } => {
                Some(2.0 * value(real).hypot(value(imaginary)))
            }
        }
    }

    /// The local physical amplitude at `x`: $`2|v_1|`$ for an envelope, the largest $`|w|`$
    /// within half a wavelength $`\pi/Q`$ either side of `x` for a resolved deflection
    /// (sampled at 64 points).
    pub fn local_amplitude_at(&self, mesh: &Mesh, global: &[f64], wavenumber: f64, x: f64) -> f64 {
        if let Some(amplitude) = self.envelope_amplitude_at(mesh, global, x) {
            return amplitude;
        }
        let [x0, x1, ..] = mesh.bounds();
        let half = std::f64::consts::PI / wavenumber;
        let (from, to) = ((x - half).max(x0), (x + half).min(x1));
        (0..=64)
            .map(|k| from + (to - from) * k as f64 / 64.0)
            .map(|s| self.deflection_at(mesh, global, wavenumber, s).abs())
            .fold(0.0, f64::max)
    }
}
