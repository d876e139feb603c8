//! Complex-envelope model with mean deflection: THEORY.md §6, the paper's eqs (35)–(39).
//!
//! Unknowns, in dof order, with their roles: in-plane displacement `u` `[displacement_x]`,
//! `v` `[displacement_y]`; the mean (zeroth-harmonic) deflection `w0` `[mean_deflection]` with its
//! Reissner–Mindlin rotations `theta_x` `[rotation_x]`, `theta_y` `[rotation_y]`; the complex
//! envelope of the first harmonic $`w_1 = a + i b`$, `a` `[envelope_real]`, `b`
//! `[envelope_imaginary]` (the paper's ansatz $`u_1 = 0`$, $`N_1 = 0`$). The physical deflection is
//! $$`w(\mathbf X) = w_0 + 2\,\mathrm{Re}\!\left(w_1\, e^{iQ\,\mathbf{e}\cdot\mathbf X}\right),`$$
//! amplitude $`2|w_1|`$, with the wave direction $`\mathbf e = (\cos\theta, \sin\theta)`$
//! (parameter `direction` $`=\theta`$, radians from X) and $`\mathbf e^\perp = (-\sin\theta,
//! \cos\theta)`$; $`\partial_e = \mathbf e\cdot\nabla`$, $`\partial_{e^\perp} = \mathbf e^\perp\cdot\nabla`$.
//!
//! **Membrane** (37), (20). The gradient of one harmonic is
//! $`\nabla(w_1 e^{iQ\mathbf e\cdot\mathbf X}) = \mathbf p\, e^{iQ\mathbf e\cdot\mathbf X}`$ with the
//! complex vector $`\mathbf p = \nabla w_1 + iQ\,w_1\,\mathbf e = \mathbf P + i\mathbf R`$,
//! $$`\mathbf P = \nabla a - Q\,b\,\mathbf e,\qquad \mathbf R = \nabla b + Q\,a\,\mathbf e,`$$
//! and the period average of $`\tfrac12\nabla w\otimes\nabla w`$ (Parseval) gives
//! $$`\gamma = \varepsilon(u) + \tfrac12\nabla w_0\otimes\nabla w_0 + \gamma^{wr},\qquad
//! \gamma^{wr} = \mathrm{Re}(\mathbf p\otimes\bar{\mathbf p}) = \mathbf P\otimes\mathbf P
//! + \mathbf R\otimes\mathbf R,`$$
//! Voigt $`(\gamma_X, \gamma_Y, 2\gamma_{XY})`$ with $`2\gamma_{XY}^{wr} = 2(P_XP_Y + R_XR_Y)`$.
//! For $`\theta = 0`$ this is THEORY.md §6 literally:
//! $`\gamma_X^{wr} = |\partial_X w_1 + iQw_1|^2 = (a_X - Qb)^2 + (b_X + Qa)^2`$,
//! $`\gamma_Y^{wr} = a_Y^2 + b_Y^2`$, $`2\gamma_{XY}^{wr} = 2[(a_X - Qb)a_Y + (b_X + Qa)b_Y]`$.
//! In general $`\mathbf e\cdot\gamma^{wr}\mathbf e = |\partial_e w_1 + iQw_1|^2`$ and
//! $`\mathbf e^\perp\cdot\gamma^{wr}\mathbf e^\perp = |\partial_{e^\perp}w_1|^2`$: the wave
//! acts along $`\mathbf e`$ only. Energy $`\tfrac12\gamma\cdot L_m\gamma`$,
//! $`L_m = \frac{Eh}{1-\nu^2}\begin{bmatrix}1&\nu&0\\\nu&1&0\\0&0&\frac{1-\nu}{2}\end{bmatrix}`$.
//!
//! **Bending of the mean deflection** (THEORY.md §2, as the `fvk-plate` model): curvature
//! $`\kappa = \operatorname{sym}\nabla\boldsymbol\theta`$ ($`\kappa_{XX} = \theta_{x,X}`$,
//! $`\kappa_{YY} = \theta_{y,Y}`$, $`\kappa_{XY} = \tfrac12(\theta_{x,Y} + \theta_{y,X})`$),
//! $$`\tfrac{D}{2}\left[\kappa_{XX}^2 + \kappa_{YY}^2 + 2\nu\kappa_{XX}\kappa_{YY}
//! + 2(1-\nu)\kappa_{XY}^2\right],\qquad D = \frac{Eh^3}{12(1-\nu^2)},`$$
//! and transverse shear $`\tfrac12 kGh\,|\nabla w_0 - \boldsymbol\theta|^2`$, $`k = 5/6`$,
//! $`G = E/(2(1+\nu))`$, integrated with the reduced 2×2 rule (term `mean_shear`). **Sign
//! convention**: $`\boldsymbol\theta \approx \nabla w_0`$ in the Kirchhoff limit.
//!
//! **Bending of the envelope** (THEORY.md §6, re-derived from (25)–(26): keep up to two slow
//! derivatives, integrate by parts with $`w_1 = 0`$ on the boundary, the Gaussian-curvature term
//! being a null Lagrangian):
//! $$`D\left[Q^4|w_1|^2 + 6Q^2|\partial_e w_1|^2 + 2Q^2|\partial_{e^\perp} w_1|^2 +
//! 4Q^3\,\mathrm{Im}(\bar w_1\,\partial_e w_1)\right],\qquad
//! \mathrm{Im}(\bar w_1\,\partial_e w_1) = a\,\partial_e b - b\,\partial_e a .`$$
//! The $`4Q^3`$ term is absent from the printed (39). For a plane wave
//! $`w_1 = r e^{ik\,\mathbf e\cdot\mathbf X}`$ the density is $`Dr^2(Q^4 + 4Q^3k + 6Q^2k^2)`$,
//! the exact $`Dr^2(Q+k)^4`$ up to $`O(k^3)`$: the phase of $`w_1`$ shifts the local wavenumber
//! to $`Q + \partial_e\arg w_1`$. **Sign convention**: $`k > 0`$ (phase increasing along
//! $`\mathbf e`$) is a *shorter* wavelength.
//!
//! **Consequences** (tested in `models/tests/complex_envelope_*.rs`):
//! * with $`b = 0`$, $`w_0 = 0`$, $`\boldsymbol\theta = 0`$ the energy is the reference
//!   envelope's (THEORY.md §4) with $`w = a`$, and so are the residual and tangent entries of
//!   $`u, v, a`$. The residual in $`b`$ does **not** vanish there: linearised about a membrane
//!   state $`N`$, the $`(a, b)`$ coupling is $`(4DQ^3 + 2QN_e)\,(a\,\partial_e b - b\,\partial_e a)`$
//!   with $`N_e = \mathbf e\cdot N\mathbf e`$, which vanishes only at $`N_e = -2DQ^2`$ — the
//!   two first-order terms of (39) cancel at the threshold of the asymptotic analysis (91);
//! * the energy is invariant under a constant phase, $`w_1 \mapsto e^{i\phi}w_1`$, so every
//!   linear buckling load of the envelope is (at least) two-fold degenerate, with modes
//!   $`(a, b)`$ and $`(-b, a)`$;
//! * at the pre-buckling state ($`w_0 = w_1 = 0`$) the mean deflection decouples from the
//!   envelope: it is a Reissner–Mindlin plate of its own.
//!
//! Stationarity gives $`\operatorname{div}N = 0`$, the plate equation of $`w_0`$ and the
//! complex Ginzburg–Landau-like envelope equation (39) with the extra term
//! $`-4iDQ^3\partial_e w_1`$.

wrinkle_macros::energy_model! {
    /// Complex-envelope model with mean deflection (Damil, Potier-Ferry & Hu 2014, eqs 35-39, with the 4Q^3 bending term).
    model ComplexEnvelope as "complex-envelope" {
        fields: u [displacement_x], v [displacement_y], w0 [mean_deflection],
            theta_x [rotation_x], theta_y [rotation_y], a [envelope_real], b [envelope_imaginary];
        parameters: young "Young's modulus E (MPa)", poisson "Poisson ratio", thickness "thickness h (mm)",
            wavenumber "wavenumber Q (1/mm)", direction "wave-vector angle from X (rad)";
        let c = cos(direction);
        let s = sin(direction);
        let membrane_stiffness = young * thickness / (1 - poisson^2);
        let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
        let shear_stiffness = 5 / 6 * young / (2 * (1 + poisson)) * thickness;
        let q = wavenumber;
        // p = grad w_1 + i Q w_1 e = P + i R.
        let px = a.x - q * c * b;
        let py = a.y - q * s * b;
        let rx = b.x + q * c * a;
        let ry = b.y + q * s * a;
        let gx = u.x + 0.5 * w0.x^2 + px^2 + rx^2;
        let gy = v.y + 0.5 * w0.y^2 + py^2 + ry^2;
        let gxy = u.y + v.x + w0.x * w0.y + 2 * (px * py + rx * ry);
        let kxx = theta_x.x;
        let kyy = theta_y.y;
        let kxy = 0.5 * (theta_x.y + theta_y.x);
        let a_along = c * a.x + s * a.y;
        let b_along = c * b.x + s * b.y;
        let a_across = c * a.y - s * a.x;
        let b_across = c * b.y - s * b.x;
        energy membrane = 0.5 * membrane_stiffness
            * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
        energy mean_bending = 0.5 * bending_stiffness
            * (kxx^2 + kyy^2 + 2 * poisson * kxx * kyy + 2 * (1 - poisson) * kxy^2);
        energy mean_shear [reduced] = 0.5 * shear_stiffness
            * ((w0.x - theta_x)^2 + (w0.y - theta_y)^2);
        energy envelope_bending = bending_stiffness * (q^4 * (a^2 + b^2)
            + 6 * q^2 * (a_along^2 + b_along^2) + 2 * q^2 * (a_across^2 + b_across^2)
            + 4 * q^3 * (a * b_along - b * a_along));
    }
}
