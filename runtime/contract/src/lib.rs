//! The vocabulary the energy DSL and the runtime share: what a field *is* ([`FieldRole`]),
//! which derivative of a field a kernel reads ([`Derivative`]), and the pair of the two that
//! makes one entry of a model's jet ([`JetEntry`]).
//!
//! The engine (`wrinkle-energy`) parses these from a model declaration and writes them into
//! the generated code; the runtime (`wrinkle-runtime`, which re-exports them) reads them back
//! from the model's `ModelSpec`. Both use this one definition, spellings included, so the DSL
//! accepts exactly the values the runtime understands. The crate has no dependencies: the
//! engine turns a value into tokens itself, from [`FieldRole::variant_name`] and
//! [`Derivative::variant_name`].
//!
//! A new derivative or a new role is one variant plus its spelling in the lists below. Which
//! derivatives a *discretisation* can supply is not said here: the DSL accepts every spelling
//! below, and the runtime refuses, when a problem is built, a model whose jet asks its element
//! for a derivative the element does not supply (the second derivatives need a $`C^1`$ element
//! such as the cubic Hermite line).

#![no_std]

/// Declares a fieldless enum whose variants each have a DSL spelling, with the lookups both
/// sides need: `ALL` (declaration order), `name` (the spelling), `from_name` and
/// `variant_name` (the Rust variant, for generated code).
macro_rules! spelled_enum {
    (
        $(#[$attribute:meta])*
        pub enum $enum:ident {
            $(
                $(#[doc = $documentation:literal])*
                $variant:ident => $spelling:literal,
            )+
        }
    ) => {
        $(#[$attribute])*
        pub enum $enum {
            $(
                $(#[doc = $documentation])*
                $variant,
            )+
        }

        impl $enum {
            /// Every value, in declaration order (`ALL[v.index()] == v`).
            pub const ALL: &'static [$enum] = &[$($enum::$variant),+];

            /// The DSL spelling.
            pub const fn name(self) -> &'static str {
                match self {
                    $($enum::$variant => $spelling,)+
                }
            }

            /// The value with DSL spelling `name`, if there is one.
            pub fn from_name(name: &str) -> Option<Self> {
                Self::ALL.iter().copied().find(|value| value.name() == name)
            }

            /// The Rust name of the variant (`"Deflection"`), for code that names it.
            pub const fn variant_name(self) -> &'static str {
                match self {
                    $($enum::$variant => stringify!($variant),)+
                }
            }

            /// Position in [`Self::ALL`].
            pub const fn index(self) -> usize {
                self as usize
            }
        }
    };
}

spelled_enum! {
    /// Which derivative of a field a jet entry holds. Its spelling is the suffix the DSL
    /// writes after the field's name and a dot (`w.x`, `w.xx`): one letter per
    /// differentiation, in the order X before Y; the value itself, written `w`, has the empty
    /// spelling.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
    pub enum Derivative {
        /// The field value $`f`$.
        Value => "",
        /// $`\partial f/\partial X`$.
        X => "x",
        /// $`\partial f/\partial Y`$.
        Y => "y",
        /// $`\partial^2 f/\partial X^2`$ (a beam's curvature $`v''`$; a plate's $`w_{,XX}`$).
        XX => "xx",
        /// $`\partial^2 f/\partial X\,\partial Y`$ (the twist $`w_{,XY}`$).
        XY => "xy",
        /// $`\partial^2 f/\partial Y^2`$.
        YY => "yy",
    }
}

impl Derivative {
    /// How many times the field is differentiated: 0 for the value, 1 for `x` and `y`, 2 for
    /// `xx`, `xy` and `yy` (the length of the spelling, one letter per differentiation).
    pub const fn order(self) -> usize {
        self.name().len()
    }
}

/// One entry of a model's jet: a field and one of its derivatives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct JetEntry {
    /// Index into the model's fields (`ModelSpec::fields` in the runtime).
    pub field: usize,
    /// Which derivative.
    pub derivative: Derivative,
}

spelled_enum! {
    /// What a field is. Declared in the DSL (`w [deflection]`, the spelling in brackets); the
    /// application layer derives from it which boundary conditions an edge imposes on the
    /// field, how the physical deflection is reconstructed and which amplitude a path reports —
    /// never from the field's name.
    #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
    pub enum FieldRole {
        /// In-plane displacement $`u`$ along X.
        DisplacementX => "displacement_x",
        /// In-plane displacement $`v`$ along Y.
        DisplacementY => "displacement_y",
        /// Transverse deflection $`w`$ of a plate (THEORY.md §2).
        Deflection => "deflection",
        /// Reissner–Mindlin rotation $`\theta_X`$, paired with $`\partial w/\partial X`$ in the
        /// transverse shear strain $`\nabla w - \theta`$.
        RotationX => "rotation_x",
        /// Reissner–Mindlin rotation $`\theta_Y`$, paired with $`\partial w/\partial Y`$.
        RotationY => "rotation_y",
        /// Real envelope $`w_1`$ of the first harmonic: physical deflection
        /// $`2 w_1 \cos(Q\,\mathbf{e}\cdot\mathbf{X})`$ (THEORY.md §3–4).
        Envelope => "envelope",
        /// Real part $`a`$ of a complex first-harmonic envelope $`w_1 = a + i b`$
        /// (THEORY.md §6).
        EnvelopeReal => "envelope_real",
        /// Imaginary part $`b`$ of a complex first-harmonic envelope.
        EnvelopeImaginary => "envelope_imaginary",
        /// Mean (zeroth-harmonic) deflection $`w_0`$ of an envelope model.
        MeanDeflection => "mean_deflection",
        /// Real envelope $`w_2`$ of the second harmonic of the deflection: it adds
        /// $`2 w_2 \cos(2Q\,\mathbf{e}\cdot\mathbf{X})`$ to the physical deflection
        /// (THEORY.md §3).
        SecondEnvelope => "second_envelope",
        /// Real part of the second harmonic $`u_2`$ of the in-plane displacement along X,
        /// $`u = u_0 + 2\,\mathrm{Re}(u_2 e^{2iQ\,\mathbf{e}\cdot\mathbf{X}})`$ (an envelope
        /// of the membrane: zero where the envelopes are).
        SecondDisplacementXReal => "second_displacement_x_real",
        /// Imaginary part of the second harmonic $`u_2`$ of the in-plane displacement along X.
        SecondDisplacementXImaginary => "second_displacement_x_imaginary",
        /// Real part of the second harmonic $`v_2`$ of the in-plane displacement along Y.
        SecondDisplacementYReal => "second_displacement_y_real",
        /// Imaginary part of the second harmonic $`v_2`$ of the in-plane displacement along Y.
        SecondDisplacementYImaginary => "second_displacement_y_imaginary",
        /// No role declared: the runtime derives nothing from the field.
        Other => "other",
    }
}

impl FieldRole {
    /// Whether the field is an out-of-plane quantity (a deflection, a rotation, an envelope) or
    /// a harmonic envelope of the in-plane displacement: clamped and simply supported plate
    /// edges constrain these, not the in-plane displacements themselves.
    pub fn is_transverse(self) -> bool {
        !matches!(
            self,
            FieldRole::DisplacementX | FieldRole::DisplacementY | FieldRole::Other
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spellings_round_trip_and_index_the_lists() {
        for (index, &role) in FieldRole::ALL.iter().enumerate() {
            assert_eq!(FieldRole::from_name(role.name()), Some(role));
            assert_eq!(role.index(), index);
        }
        for (index, &derivative) in Derivative::ALL.iter().enumerate() {
            assert_eq!(Derivative::from_name(derivative.name()), Some(derivative));
            assert_eq!(derivative.index(), index);
        }
        assert_eq!(FieldRole::EnvelopeReal.variant_name(), "EnvelopeReal");
        assert_eq!(Derivative::from_name("z"), None);
    }

    #[test]
    fn derivative_order_counts_the_differentiations() {
        assert_eq!(Derivative::Value.order(), 0);
        assert_eq!(Derivative::X.order(), 1);
        assert_eq!(Derivative::Y.order(), 1);
        assert_eq!(Derivative::XX.order(), 2);
        assert_eq!(Derivative::XY.order(), 2);
        assert_eq!(Derivative::YY.order(), 2);
        assert_eq!(Derivative::from_name("xy"), Some(Derivative::XY));
        assert_eq!(Derivative::from_name("yx"), None);
    }
}
