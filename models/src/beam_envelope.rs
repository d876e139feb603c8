//! Beam on a nonlinear foundation, the real-envelope model: THEORY.md §7, the paper's eq. (14).
//!
//! Unknowns: the mean axial displacement $`u_0`$ `[displacement_x]` and the real envelope
//! $`v_1`$ `[envelope]` of the first harmonic; the physical deflection is
//! $`v(X) = 2 v_1(X)\cos QX`$ (the peak deflection is **twice** the envelope). Fourier series
//! with slowly varying coefficients (6)–(8) with $`v_0 = 0`$, $`u_1 = 0`$, the $`v_1''`$ of
//! the curvature dropped after one integration by parts (13)–(14):
//! $$`\psi = 6EIQ^2 v_1'^2 + EIQ^4 v_1^2 + \tfrac{ES}2\left(u_0' + v_1'^2 + Q^2v_1^2\right)^2
//! + c\,v_1^2 + \tfrac32 c_3 v_1^4 .`$$
//! The foundation terms are the period means of $`\tfrac12 c v^2`$ and $`\tfrac14 c_3 v^4`$
//! ($`\langle\cos^2\rangle = \tfrac12`$, $`\langle\cos^4\rangle = \tfrac38`$). Under an end
//! force the uniform envelope satisfies $`2(EIQ^4 + c - \lambda Q^2)v_1 + 6c_3v_1^3 = 0`$: the
//! Landau law $`(2v_1)^2 = 4Q^2(\lambda - \lambda_Q)/(3c_3)`$, $`\lambda_Q = EIQ^2 + c/Q^2`$, the
//! full model's (`docs/beam.md`). The model reads first derivatives only: any line element
//! (`Line3`, `Hermite2`) carries it. Parameters as `beam-full` plus `wavenumber` $`Q`$ (1/mm).

wrinkle_macros::energy_model! {
    /// Beam on a nonlinear foundation, real-envelope model (Damil, Potier-Ferry & Hu 2014, eq 14): deflection 2 v1 cos QX.
    model BeamEnvelope as "beam-envelope" {
        fields: u0 [displacement_x], v1 [envelope];
        parameters: bending_stiffness "bending stiffness EI (N mm^2)", axial_stiffness "axial stiffness ES (N)",
            foundation [varying] "foundation stiffness c (N/mm^2), a function of X allowed", foundation_cubic "cubic foundation stiffness c3 (N/mm^4)",
            wavenumber "wavenumber Q (1/mm)";
        let q2 = wavenumber^2;
        let strain = u0.x + v1.x^2 + q2 * v1^2;
        energy membrane = 0.5 * axial_stiffness * strain^2;
        energy bending = bending_stiffness * (6 * q2 * v1.x^2 + q2^2 * v1^2);
        energy winkler = foundation * v1^2 + 1.5 * foundation_cubic * v1^4;
    }
}
