//! Beam on a nonlinear (Winkler) foundation, the full model: THEORY.md §7, the paper's eq. (5)
//! and its potential (11).
//!
//! Unknowns: axial displacement `u` `[displacement_x]` and deflection `v` `[deflection]`, both
//! on the mesh's element — the cubic Hermite line (`Hermite2`, value and slope per node), since
//! the bending energy reads $`v''`$ (the runtime gives every field the mesh's element, so `u`
//! is cubic too: one more slope dof per node, no locking, the membrane strain
//! $`u' + \tfrac12 v'^2`$ is then a quartic whose two parts have comparable degree). The energy
//! per unit length is
//! $$`\psi = \tfrac12 ES\left(u' + \tfrac12 v'^2\right)^2 + \tfrac12 EI\,v''^2
//! + \tfrac12 c\,v^2 + \tfrac14 c_3 v^4,`$$
//! whose Euler–Lagrange equations are (5): $`n' = 0`$ with $`n = ES(u' + \tfrac12 v'^2)`$, and
//! $`EI\,v'''' - (n v')' + c v + c_3 v^3 = 0`$. Under an end force $`n = -\lambda`$ the second is
//! the Swift–Hohenberg equation (1) with a cubic term, $`A = EI`$, $`B = c`$: neutral curve
//! $`\lambda(k) = EI k^2 + c/k^2`$ (2), critical wavenumber $`Q = (c/EI)^{1/4}`$ and load
//! $`\lambda_c = 2\sqrt{EI\,c}`$ (3). `foundation_cubic` $`c_3 > 0`$ hardens the foundation
//! (supercritical bifurcation), $`c_3 < 0`$ softens it (subcritical, localisation): see
//! `docs/beam.md`.
//!
//! Units (the project's mm, N): `bending_stiffness` $`EI`$ in N·mm², `axial_stiffness`
//! $`ES`$ in N, `foundation` $`c`$ in N/mm² (force per length per deflection),
//! `foundation_cubic` $`c_3`$ in N/mm⁴; the load parameter is an axial force in N.

wrinkle_macros::energy_model! {
    /// Beam on a nonlinear Winkler foundation (Damil, Potier-Ferry & Hu 2014, eq 5): the full model, every wave resolved.
    model BeamFull as "beam-full" {
        fields: u [displacement_x], v [deflection];
        parameters: bending_stiffness "bending stiffness EI (N mm^2)", axial_stiffness "axial stiffness ES (N)",
            foundation [varying] "foundation stiffness c (N/mm^2), a function of X allowed", foundation_cubic "cubic foundation stiffness c3 (N/mm^4)";
        let strain = u.x + 0.5 * v.x^2;
        energy membrane = 0.5 * axial_stiffness * strain^2;
        energy bending [reduced] = 0.5 * bending_stiffness * v.xx^2;
        energy winkler = 0.5 * foundation * v^2 + 0.25 * foundation_cubic * v^4;
    }
}
