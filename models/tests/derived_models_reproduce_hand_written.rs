//! The envelope models the DSL derives from microscopic energies against the hand-written
//! hierarchy (issue 29).
//!
//! Source: THEORY.md §3–§7, the paper's (14), (20)–(27), (35)–(39), (63)–(64); the derived
//! models `models/src/derived_*.rs` and the microscopic energies `models/src/microscopic.rs`.
//! Parameters: `E = 70000` MPa, `ν = 0.3`, `h = 0.05` mm, `Q = 0.23` /mm, directions 0, 0.3 rad
//! and π/2; 20 seeded random states per case, physically scaled (displacement gradients 1e-3,
//! envelopes 0.1 mm with slopes 5e-3).
//!
//! * `derived_reference_envelope_reproduces_reference_envelope`: from the Kirchhoff FvK plate,
//!   the reference ansatz (real envelope, strain averaged before squaring, bending averaged as a
//!   whole, integrated by parts) gives the energy, residual and tangent of `reference-envelope`
//!   (eqs 23 + 64) term by term, to 1e-12 relative (max norm over the entries).
//! * `derived_complex_envelope_reproduces_complex_envelope`: the complex ansatz with mean
//!   deflection gives those of `complex-envelope` — with its $`4Q^3`$ term — term by term.
//!   The forms match pointwise: the derivation integrates by parts symmetrically
//!   ($`a\,b_{,XY} \to -\tfrac12(a_{,X}b_{,Y} + a_{,Y}b_{,X})`$), which is rotation-covariant, so
//!   the averaged Gaussian curvature, a null Lagrangian, cancels exactly and no assembled
//!   comparison is needed.
//! * `beam_ansatz_gives_equation_14`: from the beam on a nonlinear foundation (THEORY.md §7),
//!   the 1D ansatz gives (14) written by hand,
//!   $`6EIQ^2v_1'^2 + EIQ^4v_1^2 + \tfrac{ES}2(u_0' + v_1'^2 + Q^2v_1^2)^2 + cv_1^2 + \tfrac32c_3v_1^4`$,
//!   to 1e-12 relative.
//! * `two_harmonic_model_leaves_the_second_deflection_harmonic_unforced`: in
//!   `two-harmonic-envelope`, at random states with $`w_2 = 0`$ (and its gradient), the residual
//!   of $`w_2`$ is exactly zero (the energy is even in $`w_2`$: the symmetry of the model's doc);
//!   with the in-plane second harmonics zero too, its bending equals the reference's and its
//!   membrane energy exceeds the reference's by the non-negative energy of the unrelaxed strain
//!   harmonics.
//! * `derived_models_carry_their_derivation`: the derived models publish their provenance and
//!   derivation in `ModelSpec::derivation`; hand-written ones publish none.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_models::{
    ComplexEnvelope, DerivedComplexEnvelope, DerivedReferenceEnvelope, ReferenceEnvelope,
    TwoHarmonicEnvelope,
};
use wrinkle_runtime::{Derivative, EnergyModel};

/// Energy, residual and dense tangent of one term on the model-level jet.
struct Evaluated {
    energy: f64,
    residual: Vec<f64>,
    tangent: Vec<f64>,
}

fn evaluate<M: EnergyModel>(model: &M, term: &str, jet: &[f64]) -> Evaluated {
    let spec = M::SPEC;
    let t = spec
        .terms
        .iter()
        .position(|s| s.name == term)
        .unwrap_or_else(|| panic!("{} has no term `{term}`", spec.name));
    let term_spec = &spec.terms[t];
    let n = spec.jet.len();
    let local: Vec<f64> = term_spec.jet.iter().map(|&i| jet[i]).collect();
    let mut residual = vec![0.0; local.len()];
    model.residual(t, &local, &mut residual);
    let mut out = Evaluated {
        energy: model.energy(t, &local),
        residual: vec![0.0; n],
        tangent: vec![0.0; n * n],
    };
    for (k, &i) in term_spec.jet.iter().enumerate() {
        out.residual[i] = residual[k];
    }
    let mut packed = vec![0.0; term_spec.tangent_pattern.len()];
    model.tangent(t, &local, &mut packed);
    for (p, &(i, j)) in term_spec.tangent_pattern.iter().enumerate() {
        let (gi, gj) = (term_spec.jet[i], term_spec.jet[j]);
        out.tangent[gi * n + gj] = packed[p];
        out.tangent[gj * n + gi] = packed[p];
    }
    out
}

/// Max-norm relative difference.
fn relative_difference(value: &[f64], truth: &[f64]) -> f64 {
    let scale = truth.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let difference = value
        .iter()
        .zip(truth)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    difference / scale.max(f64::MIN_POSITIVE)
}

fn with_parameters<M: EnergyModel>(direction: f64) -> M {
    let mut model = M::from_parameters(&vec![0.0; M::SPEC.parameters.len()]);
    for (name, value) in [
        ("young", 70000.0),
        ("poisson", 0.3),
        ("thickness", 0.05),
        ("wavenumber", 0.23),
        ("direction", direction),
    ] {
        model.set_parameter(name, value).unwrap();
    }
    model
}

/// A random model-level jet of `M`: in-plane entries 1e-3 (gradients), transverse values 0.1
/// and their gradients 5e-3.
fn random_jet<M: EnergyModel>(random: &mut StdRng) -> Vec<f64> {
    M::SPEC
        .jet
        .iter()
        .map(|entry| {
            let transverse = M::SPEC.field_roles[entry.field].is_transverse();
            let scale = match (transverse, entry.derivative) {
                (false, _) => 1e-3,
                (true, Derivative::Value) => 0.1,
                (true, _) => 5e-3,
            };
            scale * random.random_range(-1.0..1.0)
        })
        .collect()
}

/// Checks that `D` (derived) and `H` (hand-written) have the same jet and, for each pair of
/// term names, the same energy, residual and tangent at 20 random states.
fn assert_reproduces<D: EnergyModel, H: EnergyModel>(terms: &[(&str, &str)], seed: u64) {
    assert_eq!(D::SPEC.fields, H::SPEC.fields);
    assert_eq!(D::SPEC.field_roles, H::SPEC.field_roles);
    assert_eq!(D::SPEC.parameters, H::SPEC.parameters);
    assert_eq!(D::SPEC.jet, H::SPEC.jet);
    let mut random = StdRng::seed_from_u64(seed);
    let mut worst = 0.0_f64;
    for direction in [0.0, 0.3, std::f64::consts::FRAC_PI_2] {
        let derived: D = with_parameters(direction);
        let hand: H = with_parameters(direction);
        for _ in 0..20 {
            let jet = random_jet::<H>(&mut random);
            for (derived_term, hand_term) in terms {
                let (a, b) = (
                    evaluate(&derived, derived_term, &jet),
                    evaluate(&hand, hand_term, &jet),
                );
                let errors = [
                    relative_difference(&[a.energy], &[b.energy]),
                    relative_difference(&a.residual, &b.residual),
                    relative_difference(&a.tangent, &b.tangent),
                ];
                for (error, what) in errors.iter().zip(["energy", "residual", "tangent"]) {
                    assert!(
                        *error < 1e-12,
                        "{} `{derived_term}` vs {} `{hand_term}`, direction {direction}: {what} differs by {error:e}",
                        D::SPEC.name,
                        H::SPEC.name
                    );
                    worst = worst.max(*error);
                }
            }
        }
    }
    println!(
        "{} reproduces {}: worst relative difference {worst:e}",
        D::SPEC.name,
        H::SPEC.name
    );
}

#[test]
fn derived_reference_envelope_reproduces_reference_envelope() {
    assert_reproduces::<DerivedReferenceEnvelope, ReferenceEnvelope>(
        &[("membrane", "membrane"), ("bending", "bending")],
        29,
    );
}

#[test]
fn derived_complex_envelope_reproduces_complex_envelope() {
    assert_reproduces::<DerivedComplexEnvelope, ComplexEnvelope>(
        &[
            ("membrane", "membrane"),
            ("mean_bending", "mean_bending"),
            ("mean_shear", "mean_shear"),
            ("envelope_bending", "envelope_bending"),
        ],
        2929,
    );
}

wrinkle_models::from_beam! {
    /// The beam's envelope model derived by the DSL (Damil, Potier-Ferry & Hu 2014, eq. 14).
    model DerivedBeamEnvelope as "derived-beam-envelope" {
        fields: u [displacement_x], v [envelope];
        parameters: wavenumber "wavenumber Q (1/mm)";
        ansatz {
            wavenumber: wavenumber;
            u = u;
            v = 2 Re(v e^{i Q e.X});
        }
        energy stretching = average(stretching, mean(strain));
        energy bending = average(bending);
        energy support = average(support);
    }
}

wrinkle_macros::energy_model! {
    /// Eq. (14) of the paper, written by hand (THEORY.md §7).
    model BeamEnvelopeByHand as "beam-envelope-by-hand" {
        fields: u [displacement_x], v [envelope];
        parameters: axial_stiffness, beam_bending_stiffness, foundation, cubic_foundation, wavenumber;
        let q = wavenumber;
        energy all = 6 * beam_bending_stiffness * q^2 * v.x^2 + beam_bending_stiffness * q^4 * v^2
            + axial_stiffness / 2 * (u.x + v.x^2 + q^2 * v^2)^2
            + foundation * v^2 + 1.5 * cubic_foundation * v^4;
    }
}

#[test]
fn beam_ansatz_gives_equation_14() {
    let parameters = [700.0, 0.3, 0.02, 0.5, 0.8];
    let derived = DerivedBeamEnvelope::from_parameters(&parameters);
    let hand = BeamEnvelopeByHand::from_parameters(&parameters);
    assert_eq!(DerivedBeamEnvelope::SPEC.jet, BeamEnvelopeByHand::SPEC.jet);
    let mut random = StdRng::seed_from_u64(14);
    let n = BeamEnvelopeByHand::SPEC.jet.len();
    for _ in 0..20 {
        let jet: Vec<f64> = (0..n).map(|_| random.random_range(-0.3..0.3)).collect();
        let mut sum = Evaluated {
            energy: 0.0,
            residual: vec![0.0; n],
            tangent: vec![0.0; n * n],
        };
        for term in ["stretching", "bending", "support"] {
            let part = evaluate(&derived, term, &jet);
            sum.energy += part.energy;
            sum.residual
                .iter_mut()
                .zip(&part.residual)
                .for_each(|(s, p)| *s += p);
            sum.tangent
                .iter_mut()
                .zip(&part.tangent)
                .for_each(|(s, p)| *s += p);
        }
        let truth = evaluate(&hand, "all", &jet);
        assert!(relative_difference(&[sum.energy], &[truth.energy]) < 1e-12);
        assert!(relative_difference(&sum.residual, &truth.residual) < 1e-12);
        assert!(relative_difference(&sum.tangent, &truth.tangent) < 1e-12);
    }
}

#[test]
fn two_harmonic_model_leaves_the_second_deflection_harmonic_unforced() {
    type Two = TwoHarmonicEnvelope;
    let spec = Two::SPEC;
    let two: Two = with_parameters(0.3);
    let reference: ReferenceEnvelope = with_parameters(0.3);
    let field = |name: &str| spec.field_index(name).unwrap();
    let mut random = StdRng::seed_from_u64(22);
    for _ in 0..20 {
        let mut jet = random_jet::<Two>(&mut random);
        for (k, entry) in spec.jet.iter().enumerate() {
            if entry.field == field("w2") {
                jet[k] = 0.0;
            }
        }
        for term in ["membrane", "bending"] {
            let evaluated = evaluate(&two, term, &jet);
            for (k, entry) in spec.jet.iter().enumerate() {
                if entry.field == field("w2") {
                    assert_eq!(evaluated.residual[k], 0.0, "{term}: w2 is forced");
                }
            }
        }
        // In-plane second harmonics zero too: compare with the reference on (u, v, w).
        let in_plane = ["u2r", "u2i", "v2r", "v2i"].map(field);
        for (k, entry) in spec.jet.iter().enumerate() {
            if in_plane.contains(&entry.field) {
                jet[k] = 0.0;
            }
        }
        let reduced: Vec<f64> = ReferenceEnvelope::SPEC
            .jet
            .iter()
            .map(|entry| {
                let name = ReferenceEnvelope::SPEC.fields[entry.field];
                let position = spec
                    .jet
                    .iter()
                    .position(|e| spec.fields[e.field] == name && e.derivative == entry.derivative);
                jet[position.unwrap()]
            })
            .collect();
        let bending = evaluate(&two, "bending", &jet).energy;
        let expected = evaluate(&reference, "bending", &reduced).energy;
        assert!((bending - expected).abs() <= 1e-12 * expected.abs());
        let membrane = evaluate(&two, "membrane", &jet).energy;
        let paper = evaluate(&reference, "membrane", &reduced).energy;
        assert!(membrane >= paper * (1.0 - 1e-12), "{membrane} < {paper}");
    }
}

#[test]
fn derived_models_carry_their_derivation() {
    for spec in [DerivedReferenceEnvelope::SPEC, DerivedComplexEnvelope::SPEC] {
        let derivation = spec.derivation.expect("a derived model has a derivation");
        assert!(derivation.contains("derived from the microscopic energy `kirchhoff_plate`"));
        assert!(derivation.contains("vanishes on the boundary"));
        assert!(derivation.contains("work (bounded by"));
    }
    assert!(ReferenceEnvelope::SPEC.derivation.is_none());
    let derivation = DerivedComplexEnvelope::SPEC.derivation.unwrap();
    assert!(
        derivation.contains("w = w0 + 2 Re((a + i b) e^{i Q e.X})"),
        "{derivation}"
    );
}
