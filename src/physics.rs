//! What a model's fields mean physically, read from the roles the model declares
//! ([`FieldRole`]), never from field names: which fields are in-plane displacements, which are
//! transverse (clamped at a clamped edge), what the physical deflection is, and which wrinkle
//! amplitudes a path reports.
//!
//! Physical deflection $`w(\mathbf X)`$ by model kind (THEORY.md §2–§6), with the wave direction
//! $`\mathbf e = (\cos\theta, \sin\theta)`$:
//! * plate (role `deflection`): $`w`$ itself;
//! * real envelope (role `envelope`): $`w = 2\,w_\text{env}\cos(Q\,\mathbf e\cdot\mathbf X)`$;
//! * complex envelope (roles `envelope_real` $`a`$, `envelope_imaginary` $`b`$, optional
//!   `mean_deflection` $`w_0`$): $`w = w_0 + 2\,\mathrm{Re}\big((a + ib)\,e^{iQ\,\mathbf e\cdot\mathbf X}\big)`$.
//!
//! Wrinkle amplitudes (the same physical quantities for every model, labelled as such in every
//! output):
//! * **maximum amplitude** $`\max|w|`$: the plate's largest nodal $`|w|`$; $`2\max|w_\text{env}|`$
//!   or $`2\max|w_1|`$ for envelope models (the envelope is the local amplitude);
//! * **centre amplitude**, the local wrinkle amplitude at the centre of the domain: for the plate
//!   half the peak-to-peak of $`w`$ along the line through the centre in the wave direction,
//!   within one wavelength either side of the centre; $`2|w_\text{env}|`$ or $`2|w_1|`$ at the
//!   centre for envelope models.

use wrinkle_runtime::fem::Mesh;
use wrinkle_runtime::{FieldRole, ModelSpec};

/// How the physical deflection is built from the fields.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum DeflectionKind {
    /// The deflection is a field.
    Plate {
        /// Field of role `deflection`.
        deflection: usize,
    },
    /// A real envelope of the first harmonic.
    RealEnvelope {
        /// Field of role `envelope`.
        envelope: usize,
    },
    /// A complex envelope $`a + ib`$, optionally with a mean deflection.
    ComplexEnvelope {
        /// Field of role `envelope_real`.
        real: usize,
        /// Field of role `envelope_imaginary`.
        imaginary: usize,
        /// Field of role `mean_deflection`, if any.
        mean: Option<usize>,
    },
}

/// The fields of a model by what they are.
#[derive(Clone, Debug, PartialEq)]
pub struct Layout {
    /// Number of fields (values per node).
    pub field_count: usize,
    /// In-plane displacements $`(u, v)`$.
    pub in_plane: [usize; 2],
    /// Every field that is zero on a clamped edge: all but the in-plane displacements.
    pub transverse: Vec<usize>,
    /// How the physical deflection is built.
    pub kind: DeflectionKind,
    /// The field an imperfection acts on and the path follows (deflection, envelope, or real
    /// part of the complex envelope).
    pub primary: usize,
}

impl Layout {
    /// Reads the layout from the roles of `spec`; the message says which role is missing.
    pub fn from_spec(spec: &ModelSpec) -> Result<Layout, String> {
        let role = |r: FieldRole| spec.field_with_role(r);
        let missing = |r: FieldRole| {
            format!(
                "model `{}` declares no field with role `{}` (fields: {})",
                spec.name,
                r.name(),
                describe_fields(spec)
            )
        };
        let u = role(FieldRole::DisplacementX).ok_or_else(|| missing(FieldRole::DisplacementX))?;
        let v = role(FieldRole::DisplacementY).ok_or_else(|| missing(FieldRole::DisplacementY))?;
        let kind = if let Some(w) = role(FieldRole::Deflection) {
            DeflectionKind::Plate { deflection: w }
        } else if let Some(w) = role(FieldRole::Envelope) {
            DeflectionKind::RealEnvelope { envelope: w }
        } else if let (Some(a), Some(b)) = (
            role(FieldRole::EnvelopeReal),
            role(FieldRole::EnvelopeImaginary),
        ) {
            DeflectionKind::ComplexEnvelope {
                real: a,
                imaginary: b,
                mean: role(FieldRole::MeanDeflection),
            }
        } else {
            return Err(format!(
                "model `{}` has no transverse field: it needs a field with role `deflection`, \
                 `envelope`, or `envelope_real` and `envelope_imaginary` (fields: {})",
                spec.name,
                describe_fields(spec)
            ));
        };
        let primary = match kind {
            DeflectionKind::Plate { deflection } => deflection,
            DeflectionKind::RealEnvelope { envelope } => envelope,
            DeflectionKind::ComplexEnvelope { real, .. } => real,
        };
        Ok(Layout {
            field_count: spec.fields.len(),
            in_plane: [u, v],
            transverse: (0..spec.fields.len())
                .filter(|&k| k != u && k != v)
                .collect(),
            kind,
            primary,
        })
    }

    /// Whether the model describes wrinkles by an envelope (and so needs a wavenumber).
    pub fn is_envelope(&self) -> bool {
        !matches!(self.kind, DeflectionKind::Plate { .. })
    }

    /// The fields the physical deflection is built from: the deflection, the envelope, or the
    /// complex envelope's two parts and its mean deflection.
    pub fn deflection_fields(&self) -> Vec<usize> {
        match self.kind {
            DeflectionKind::Plate { deflection } => vec![deflection],
            DeflectionKind::RealEnvelope { envelope } => vec![envelope],
            DeflectionKind::ComplexEnvelope {
                real,
                imaginary,
                mean,
            } => [Some(real), Some(imaginary), mean]
                .into_iter()
                .flatten()
                .collect(),
        }
    }
}

fn describe_fields(spec: &ModelSpec) -> String {
    spec.fields
        .iter()
        .zip(spec.field_roles)
        .map(|(f, r)| format!("{f} [{}]", r.name()))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A state of the whole mesh (node-major nodal values, prescribed entries included) with what
/// is needed to evaluate the physical deflection anywhere.
pub struct Snapshot<'a> {
    /// The mesh.
    pub mesh: &'a Mesh,
    /// The fields' meaning.
    pub layout: &'a Layout,
    /// Nodal values, `values[n * field_count + f]`.
    pub values: &'a [f64],
    /// Wavenumber $`Q`$ (1/mm) of envelope models (ignored for the plate).
    pub wavenumber: f64,
    /// Wave direction $`\theta`$ (radians from X).
    pub direction: f64,
}

impl Snapshot<'_> {
    fn field_at(&self, field: usize, point: [f64; 2]) -> f64 {
        self.mesh
            .interpolate(self.values, self.layout.field_count, field, point)
            .unwrap_or(0.0)
    }

    fn phase(&self, point: [f64; 2]) -> f64 {
        self.wavenumber * (self.direction.cos() * point[0] + self.direction.sin() * point[1])
    }

    /// Physical deflection $`w`$ (mm) at `point`.
    pub fn deflection(&self, point: [f64; 2]) -> f64 {
        match self.layout.kind {
            DeflectionKind::Plate { deflection } => self.field_at(deflection, point),
            DeflectionKind::RealEnvelope { envelope } => {
                2.0 * self.field_at(envelope, point) * self.phase(point).cos()
            }
            DeflectionKind::ComplexEnvelope {
                real,
                imaginary,
                mean,
            } => {
                let (a, b) = (self.field_at(real, point), self.field_at(imaginary, point));
                let phase = self.phase(point);
                let w0 = mean.map_or(0.0, |m| self.field_at(m, point));
                w0 + 2.0 * (a * phase.cos() - b * phase.sin())
            }
        }
    }

    /// Local wrinkle amplitude (mm) read from the envelope at `point`: $`2|w_\text{env}|`$ or
    /// $`2|w_1|`$; `None` for the plate, whose amplitude is not a field.
    pub fn envelope_amplitude(&self, point: [f64; 2]) -> Option<f64> {
        match self.layout.kind {
            DeflectionKind::Plate { .. } => None,
            DeflectionKind::RealEnvelope { envelope } => {
                Some(2.0 * self.field_at(envelope, point).abs())
            }
            DeflectionKind::ComplexEnvelope {
                real, imaginary, ..
            } => Some(
                2.0 * self
                    .field_at(real, point)
                    .hypot(self.field_at(imaginary, point)),
            ),
        }
    }

    /// Local wavenumber $`Q + \partial_e \arg w_1`$ of a complex envelope at `point`, by a
    /// centred difference of the phase over `step` (mm) along $`\mathbf e`$; `None` for the other
    /// kinds or where $`|w_1|`$ vanishes.
    pub fn local_wavenumber(&self, point: [f64; 2], step: f64) -> Option<f64> {
        let DeflectionKind::ComplexEnvelope {
            real, imaginary, ..
        } = self.layout.kind
        else {
            return None;
        };
        let (c, s) = (self.direction.cos(), self.direction.sin());
        let at = |t: f64| {
            let p = [point[0] + t * c, point[1] + t * s];
            (self.field_at(real, p), self.field_at(imaginary, p))
        };
        let (a0, b0) = at(-step);
        let (a1, b1) = at(step);
        // arg(w(+)) − arg(w(−)) = arg(w(+) · conj(w(−))).
        let (re, im) = (a1 * a0 + b1 * b0, b1 * a0 - a1 * b0);
        (re.hypot(im) > 0.0).then(|| self.wavenumber + im.atan2(re) / (2.0 * step))
    }

    /// Maximum physical wrinkle amplitude (mm): the plate's largest nodal $`|w|`$, twice the
    /// largest nodal envelope modulus otherwise.
    pub fn max_amplitude(&self) -> f64 {
        let nodes = self.mesh.nodes.len();
        // NaN propagates: an overflowed state never reports a finite amplitude.
        wrinkle_runtime::problem::max_or_nan((0..nodes).map(|n| self.nodal_amplitude(n)))
    }

    /// Physical wrinkle amplitude (mm) at node `n`: $`|w|`$, $`2|w_\text{env}|`$ or $`2|w_1|`$.
    fn nodal_amplitude(&self, n: usize) -> f64 {
        let value = |f: usize| self.values[n * self.layout.field_count + f];
        match self.layout.kind {
            DeflectionKind::Plate { deflection } => value(deflection).abs(),
            DeflectionKind::RealEnvelope { envelope } => 2.0 * value(envelope).abs(),
            DeflectionKind::ComplexEnvelope {
                real, imaginary, ..
            } => 2.0 * value(real).hypot(value(imaginary)),
        }
    }

    /// Largest physical deflection $`|w|`$ (mm) over the nodes, taken over every phase of the
    /// wrinkles: the plate's $`|w|`$, $`2|w_\text{env}|`$, or $`|w_0| + 2|w_1|`$ for the complex
    /// envelope with its mean deflection $`w_0`$ (so it equals [`Self::max_amplitude`] unless
    /// there is a mean deflection). A map sampled on a grid can miss a crest that falls between
    /// two samples; this does not.
    pub fn max_deflection(&self) -> f64 {
        let mean = match self.layout.kind {
            DeflectionKind::ComplexEnvelope { mean, .. } => mean,
            _ => None,
        };
        let nf = self.layout.field_count;
        wrinkle_runtime::problem::max_or_nan(
            (0..self.mesh.nodes.len()).map(|n| {
                mean.map_or(0.0, |m| self.values[n * nf + m].abs()) + self.nodal_amplitude(n)
            }),
        )
    }

    /// Local wrinkle amplitude (mm) at `centre` (see the module documentation); `wavelength`
    /// (mm) is the plate's wrinkle wavelength.
    pub fn centre_amplitude(&self, centre: [f64; 2], wavelength: f64) -> f64 {
        if let Some(amplitude) = self.envelope_amplitude(centre) {
            return amplitude;
        }
        let (c, s) = (self.direction.cos(), self.direction.sin());
        let samples = 200;
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..=samples {
            let t = wavelength * (2.0 * k as f64 / samples as f64 - 1.0);
            let p = [centre[0] + t * c, centre[1] + t * s];
            if self.mesh.locate(p).is_none() {
                continue;
            }
            let w = self.deflection(p);
            low = low.min(w);
            high = high.max(w);
        }
        if high >= low { 0.5 * (high - low) } else { 0.0 }
    }
}

/// Wavelength (mm) of a plate's wrinkles read from a deflection profile along the line through
/// `centre` in the wave direction: twice the mean distance between consecutive sign changes
/// of $`w`$ where $`|w|`$ exceeds 1 % of its maximum on the line. `None` with fewer than two
/// sign changes.
pub fn wavelength_along_line(
    snapshot: &Snapshot<'_>,
    centre: [f64; 2],
    length: f64,
) -> Option<f64> {
    let (c, s) = (snapshot.direction.cos(), snapshot.direction.sin());
    let samples = 4000;
    let line: Vec<(f64, f64)> = (0..=samples)
        .filter_map(|k| {
            let t = length * (k as f64 / samples as f64 - 0.5);
            let p = [centre[0] + t * c, centre[1] + t * s];
            snapshot.mesh.locate(p).map(|_| (t, snapshot.deflection(p)))
        })
        .collect();
    let peak = line.iter().map(|(_, w)| w.abs()).fold(0.0, f64::max);
    if peak == 0.0 {
        return None;
    }
    let significant: Vec<&(f64, f64)> =
        line.iter().filter(|(_, w)| w.abs() > 1e-2 * peak).collect();
    let crossings: Vec<f64> = significant
        .windows(2)
        .filter(|pair| pair[0].1.signum() != pair[1].1.signum())
        .map(|pair| 0.5 * (pair[0].0 + pair[1].0))
        .collect();
    if crossings.len() < 2 {
        return None;
    }
    let span = crossings[crossings.len() - 1] - crossings[0];
    Some(2.0 * span / (crossings.len() - 1) as f64)
}

#[cfg(test)]
mod tests {
    use super::*;
    use wrinkle_models::{ComplexEnvelope, FvkPlate, PureMembrane, ReferenceEnvelope};
    use wrinkle_runtime::EnergyModel;

    fn nodal(mesh: &Mesh, layout: &Layout, value: impl Fn(usize, [f64; 2]) -> f64) -> Vec<f64> {
        let nf = layout.field_count;
        let mut values = vec![0.0; mesh.nodes.len() * nf];
        for (n, p) in mesh.nodes.iter().enumerate() {
            for f in 0..nf {
                values[n * nf + f] = value(f, [p[0], p[1]]);
            }
        }
        values
    }

    /// The snapshot of `values` with the wave vector along X.
    fn snapshot<'a>(
        mesh: &'a Mesh,
        layout: &'a Layout,
        values: &'a [f64],
        wavenumber: f64,
    ) -> Snapshot<'a> {
        Snapshot {
            mesh,
            layout,
            values,
            wavenumber,
            direction: 0.0,
        }
    }

    #[test]
    fn layouts_follow_the_declared_roles_of_every_registered_model() {
        let plate = Layout::from_spec(FvkPlate::SPEC).unwrap();
        assert_eq!(plate.kind, DeflectionKind::Plate { deflection: 2 });
        assert_eq!(plate.transverse, vec![2, 3, 4]);
        let envelope = Layout::from_spec(ReferenceEnvelope::SPEC).unwrap();
        assert_eq!(envelope.kind, DeflectionKind::RealEnvelope { envelope: 2 });
        assert_eq!(Layout::from_spec(PureMembrane::SPEC).unwrap(), envelope);
        let complex = Layout::from_spec(ComplexEnvelope::SPEC).unwrap();
        assert_eq!(
            complex.kind,
            DeflectionKind::ComplexEnvelope {
                real: 5,
                imaginary: 6,
                mean: Some(2)
            }
        );
        assert_eq!(complex.transverse, vec![2, 3, 4, 5, 6]);
        assert_eq!(complex.primary, 5);
    }

    /// A uniform envelope $`w_\text{env} = 1`$ is the carrier $`2\cos QX`$ of amplitude 2; a
    /// uniform complex envelope $`0.6 + 0.8i`$ is $`2(0.6\cos QX - 0.8\sin QX)`$ of amplitude 2 and
    /// local wavenumber $`Q`$.
    #[test]
    fn uniform_envelopes_give_the_carrier_wave_and_amplitude_two() {
        let mesh = Mesh::rectangle(10.0, 5.0, 4, 2, 1.0).unwrap();
        let q = 2.3;
        let layout = Layout::from_spec(ReferenceEnvelope::SPEC).unwrap();
        let values = nodal(&mesh, &layout, |f, _| if f == 2 { 1.0 } else { 0.0 });
        let s = snapshot(&mesh, &layout, &values, q);
        for p in [[1.0, 1.0], [3.7, 2.2], [9.1, 4.0]] {
            assert!((s.deflection(p) - 2.0 * (q * p[0]).cos()).abs() < 1e-12);
        }
        assert!((s.max_amplitude() - 2.0).abs() < 1e-12);
        assert!((s.centre_amplitude([5.0, 2.5], 1.0) - 2.0).abs() < 1e-12);

        let layout = Layout::from_spec(ComplexEnvelope::SPEC).unwrap();
        let values = nodal(&mesh, &layout, |f, _| match f {
            5 => 0.6,
            6 => 0.8,
            _ => 0.0,
        });
        let s = snapshot(&mesh, &layout, &values, q);
        let p = [3.7, 2.2];
        let expected = 2.0 * (0.6 * (q * p[0]).cos() - 0.8 * (q * p[0]).sin());
        assert!((s.deflection(p) - expected).abs() < 1e-12);
        assert!((s.max_amplitude() - 2.0).abs() < 1e-12);
        assert!((s.local_wavenumber(p, 0.1).unwrap() - q).abs() < 1e-12);
    }

    /// A uniform complex envelope $`0.6 + 0.8i`$ on a uniform mean deflection $`w_0 = -0.3`$:
    /// $`w = -0.3 + 2\cos(QX + \varphi)`$ reaches $`|w| = 2.3`$ at its troughs, while the wrinkle
    /// amplitude stays 2. Samples every 1/16 of a wavelength approach 2.3 from below.
    #[test]
    fn max_deflection_of_a_complex_envelope_adds_the_mean_deflection() {
        let mesh = Mesh::rectangle(10.0, 5.0, 4, 2, 1.0).unwrap();
        let q = 2.3;
        let layout = Layout::from_spec(ComplexEnvelope::SPEC).unwrap();
        let values = nodal(&mesh, &layout, |f, _| match f {
            2 => -0.3,
            5 => 0.6,
            6 => 0.8,
            _ => 0.0,
        });
        let s = snapshot(&mesh, &layout, &values, q);
        assert!((s.max_amplitude() - 2.0).abs() < 1e-12);
        assert!((s.max_deflection() - 2.3).abs() < 1e-12);
        let step = 2.0 * std::f64::consts::PI / q / 16.0;
        let sampled = (0..=(10.0 / step) as usize)
            .map(|i| s.deflection([i as f64 * step, 2.5]).abs())
            .fold(0.0, f64::max);
        assert!(
            sampled <= 2.3 + 1e-12
                && sampled > 2.3 - 2.0 * (1.0 - (std::f64::consts::PI / 16.0).cos())
        );
        let plate = Layout::from_spec(FvkPlate::SPEC).unwrap();
        let values = nodal(&mesh, &plate, |f, p| if f == 2 { p[0] - 7.0 } else { 0.0 });
        let s = snapshot(&mesh, &plate, &values, q);
        assert_eq!(s.max_deflection(), s.max_amplitude());
        assert!((s.max_deflection() - 7.0).abs() < 1e-12);
    }

    /// A plate deflection $`\sin(2\pi X/\ell)`$ sampled on a fine mesh: the wavelength read from
    /// its sign changes is $`\ell`$ and its local amplitude at the centre is 1.
    #[test]
    fn plate_wavelength_and_local_amplitude_from_a_sine() {
        let mesh = Mesh::rectangle(100.0, 20.0, 80, 4, 1.0).unwrap();
        let layout = Layout::from_spec(FvkPlate::SPEC).unwrap();
        let wavelength = 12.5;
        let values = nodal(&mesh, &layout, |f, p| {
            if f == 2 {
                (2.0 * std::f64::consts::PI * p[0] / wavelength).sin()
            } else {
                0.0
            }
        });
        let s = snapshot(&mesh, &layout, &values, 0.0);
        let measured = wavelength_along_line(&s, [50.0, 10.0], 200.0).unwrap();
        assert!(
            (measured - wavelength).abs() / wavelength < 1e-2,
            "{measured}"
        );
        let amplitude = s.centre_amplitude([50.0, 10.0], wavelength);
        assert!((amplitude - 1.0).abs() < 1e-2, "{amplitude}");
    }
}
