//! The complex-envelope model with mean deflection (THEORY.md §6, the paper's (35)–(39), with
//! the $`4Q^3`$ bending term) **derived by the DSL** from the Kirchhoff FvK plate
//! ([`crate::from_kirchhoff_plate`]), except the bending of the mean deflection, which is
//! written by hand as in `complex-envelope`: the Q8 element has no second derivatives, so
//! $`w_0`$ bends as a Reissner–Mindlin plate with its rotations.
//!
//! Ansatz: $`u = u_0`$, $`v = v_0`$, $`w = w_0 + 2\,\mathrm{Re}((a + ib)\,e^{iQ\,\mathbf e\cdot\mathbf X})`$,
//! slow derivatives to order 2.
//! * `membrane`: zeroth harmonic of the strain before squaring (`mean(gx, gy, gxy)`):
//!   $`\gamma = \varepsilon(u) + \tfrac12\nabla w_0\otimes\nabla w_0 + \mathbf P\otimes\mathbf P
//!   + \mathbf R\otimes\mathbf R`$, $`\mathbf P + i\mathbf R = \nabla w_1 + iQw_1\mathbf e`$ (37);
//! * `envelope_bending`: zeroth harmonic of the Kirchhoff bending with $`w_0`$ left out
//!   (`without(w0)`: its bending is the hand-written `mean_bending` and `mean_shear`),
//!   truncated and integrated by parts with $`w_1 = 0`$ on the boundary:
//!   $`D[Q^4|w_1|^2 + 6Q^2|\partial_e w_1|^2 + 2Q^2|\partial_{e^\perp}w_1|^2 +
//!   4Q^3\,\mathrm{Im}(\bar w_1\partial_e w_1)]`$ — the term the printed (39) lacks comes out of
//!   the derivation by itself;
//! * `mean_bending`, `mean_shear`: the Reissner–Mindlin bending of $`w_0`$, by hand, as in
//!   `complex-envelope` (`models/src/complex_envelope.rs`).
//!
//! Checked against `complex-envelope` in `models/tests/derived_models_reproduce_hand_written.rs`.

crate::from_kirchhoff_plate! {
    /// Complex-envelope model with mean deflection derived by the DSL from the Kirchhoff FvK plate (Damil, Potier-Ferry & Hu 2014, eqs 35-39, with the 4Q^3 bending term).
    model DerivedComplexEnvelope as "derived-complex-envelope" {
        fields: u [displacement_x], v [displacement_y], w0 [mean_deflection],
            theta_x [rotation_x], theta_y [rotation_y], a [envelope_real], b [envelope_imaginary];
        parameters: wavenumber "wavenumber Q (1/mm)", direction "wave-vector angle from X (rad)";
        ansatz {
            wavenumber: wavenumber;
            direction: direction;
            slow_derivatives: 2;
            u = u;
            v = v;
            w = w0 + 2 Re((a + i b) e^{i Q e.X});
        }
        let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
        let shear_stiffness = 5 / 6 * young / (2 * (1 + poisson)) * thickness;
        let kxx = theta_x.x;
        let kyy = theta_y.y;
        let kxy = 0.5 * (theta_x.y + theta_y.x);
        energy membrane = average(membrane, mean(gx, gy, gxy));
        energy mean_bending = 0.5 * bending_stiffness
            * (kxx^2 + kyy^2 + 2 * poisson * kxx * kyy + 2 * (1 - poisson) * kxy^2);
        energy mean_shear [reduced] = 0.5 * shear_stiffness
            * ((w0.x - theta_x)^2 + (w0.y - theta_y)^2);
        energy envelope_bending = average(bending, without(w0));
    }
}
