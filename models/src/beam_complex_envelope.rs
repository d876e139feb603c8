//! Beam on a nonlinear foundation, the complex-envelope model: THEORY.md §7 and §6, the
//! paper's eqs (12)–(13) with a complex envelope, its phase a local wavenumber.
//!
//! Unknowns: the mean axial displacement $`u_0`$ `[displacement_x]` and the complex envelope
//! $`v_1 = a + ib`$, `a` `[envelope_real]`, `b` `[envelope_imaginary]`; the physical deflection
//! is $`v = 2\,\mathrm{Re}(v_1 e^{iQX}) = 2(a\cos QX - b\sin QX)`$, amplitude $`2|v_1|`$.
//!
//! **Membrane** (10): $`\gamma_0 = u_0' + |v_1' + iQv_1|^2 = u_0' + (a' - Qb)^2 + (b' + Qa)^2`$.
//!
//! **Bending** (12)–(13): $`|K_1|^2 = |v_1'' + 2iQv_1' - Q^2v_1|^2`$; keeping up to two slow
//! derivatives and integrating $`-2Q^2\,\mathrm{Re}(v_1''\bar v_1)`$ by parts (with $`v_1 = 0`$
//! at the ends) gives, as in 2D (THEORY.md §6),
//! $$`EI\left[Q^4|v_1|^2 + 6Q^2|v_1'|^2 + 4Q^3(a b' - b a')\right].`$$
//! For $`v_1 = r e^{ikX}`$ this is $`EI r^2(Q^4 + 4Q^3k + 6Q^2k^2)`$, the exact
//! $`EIr^2(Q+k)^4`$ to second order in $`k`$: the phase of $`v_1`$ shifts the local wavenumber
//! to $`Q + (\arg v_1)'`$. With $`b = 0`$ the model is `beam-envelope` exactly.
//!
//! **Foundation**: period means $`c|v_1|^2 + \tfrac32 c_3|v_1|^4`$.
//!
//! Linearised under an end force $`n = -\lambda`$, a plane wave $`v_1 = e^{imX}`$ has
//! $`(6EIQ^2 - \lambda)m^2 + (4EIQ^3 - 2\lambda Q)m + EIQ^4 + c - \lambda Q^2 = 0`$; the first-order
//! coupling vanishes at $`\lambda = 2EIQ^2`$, the threshold, as in 2D.

wrinkle_macros::energy_model! {
    /// Beam on a nonlinear foundation, complex-envelope model (Damil, Potier-Ferry & Hu 2014, eqs 12-13): phase as local wavenumber.
    model BeamComplexEnvelope as "beam-complex-envelope" {
        fields: u0 [displacement_x], a [envelope_real], b [envelope_imaginary];
        parameters: bending_stiffness "bending stiffness EI (N mm^2)", axial_stiffness "axial stiffness ES (N)",
            foundation [varying] "foundation stiffness c (N/mm^2), a function of X allowed", foundation_cubic "cubic foundation stiffness c3 (N/mm^4)",
            wavenumber "wavenumber Q (1/mm)";
        let q = wavenumber;
        let modulus2 = a^2 + b^2;
        let strain = u0.x + (a.x - q * b)^2 + (b.x + q * a)^2;
        energy membrane = 0.5 * axial_stiffness * strain^2;
        energy bending = bending_stiffness * (q^4 * modulus2 + 6 * q^2 * (a.x^2 + b.x^2)
            + 4 * q^3 * (a * b.x - b * a.x));
        energy winkler = foundation * modulus2 + 1.5 * foundation_cubic * modulus2^2;
    }
}
