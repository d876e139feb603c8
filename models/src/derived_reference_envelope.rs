//! The reference envelope model (THEORY.md §4, the paper's (22), (23), (64)) **derived by the
//! DSL** from the Kirchhoff FvK plate ([`crate::from_kirchhoff_plate`]) instead of by hand: the
//! check that the automated derivation reproduces the hand-written `reference-envelope`
//! (`models/tests/derived_models_reproduce_hand_written.rs`: same energy, residual and tangent
//! at random states to 1e-12; `models/tests/derived_reference_envelope_path.rs`: same critical
//! load and path on the default scene to 1e-9).
//!
//! Ansatz (THEORY.md §3): $`u = u_0`$, $`v = v_0`$ (no in-plane harmonics), and a real envelope of
//! the first harmonic, $`w = 2\,\mathrm{Re}(w_1 e^{iQ\,\mathbf e\cdot\mathbf X})`$ with
//! $`w_1 = w`$ real, $`\mathbf e = (\cos\theta, \sin\theta)`$, slow derivatives kept to order 2.
//! * `membrane`: the zeroth harmonic of the membrane strain is taken **before** it is squared,
//!   as the paper does — `mean(gx, gy, gxy)` — which gives (20)–(23):
//!   $`\gamma = \varepsilon(u) + \nabla w\otimes\nabla w + Q^2w^2\,\mathbf e\otimes\mathbf e`$;
//! * `bending`: the zeroth harmonic of the Kirchhoff bending energy as a whole, truncated to two
//!   slow derivatives and integrated by parts with $`w = 0`$ on the boundary, which gives (64):
//!   $`D\,(Q^4w^2 + 6Q^2(\mathbf e\cdot\nabla w)^2 + 2Q^2(\mathbf e^\perp\cdot\nabla w)^2)`$; the
//!   averaged Gaussian curvature cancels exactly.
//!
//! `wrinkle models --show derived-reference-envelope` prints the derivation.

crate::from_kirchhoff_plate! {
    /// Reference envelope model derived by the DSL from the Kirchhoff FvK plate (Damil, Potier-Ferry & Hu 2014, eqs 22, 23, 64).
    model DerivedReferenceEnvelope as "derived-reference-envelope" {
        fields: u [displacement_x], v [displacement_y], w [envelope];
        parameters: wavenumber "wavenumber Q (1/mm)", direction "wave-vector angle from X (rad)";
        ansatz {
            wavenumber: wavenumber;
            direction: direction;
            slow_derivatives: 2;
            u = u;
            v = v;
            w = 2 Re(w e^{i Q e.X});
        }
        energy membrane = average(membrane, mean(gx, gy, gxy));
        energy bending = average(bending);
    }
}
