//! Pure membrane model: THEORY.md §5, the paper's eqs (33)–(34).
//!
//! The reference envelope model (THEORY.md §4) with every derivative of the envelope dropped.
//! Unknowns: in-plane displacement `u` `[displacement_x]`, `v` `[displacement_y]` and the real
//! envelope `w` `[envelope]` (physical deflection $`2w\cos(Q\,\mathbf e\cdot\mathbf X)`$), wave
//! direction $`\mathbf e = (\cos\theta, \sin\theta)`$ (parameter `direction` $`=\theta`$):
//! $$`\gamma = \varepsilon(u) + Q^2 w^2\,\mathbf e\otimes\mathbf e,\qquad
//! \psi = \tfrac12\gamma\cdot L_m\gamma + D Q^4 w^2,`$$
//! $`L_m = \frac{Eh}{1-\nu^2}\begin{bmatrix}1&\nu&0\\\nu&1&0\\0&0&\frac{1-\nu}{2}\end{bmatrix}`$,
//! $`D = Eh^3/(12(1-\nu^2))`$. Stationarity in $`w`$ is pointwise, with no derivative of $`w`$:
//! $$`\partial\psi/\partial w = 2Q^2\,(N_e + DQ^2)\,w,\qquad N_e = \mathbf e\cdot N\mathbf e,`$$
//! so that with a small transverse load it reads $`(N_e + DQ^2)\,w = \delta`$ (33) (the load
//! scaled by $`1/(2Q^2)`$), and eliminating $`w`$ gives (34). Along X ($`\theta = 0`$),
//! $`N_e = N_X`$: the fundamental state loses stability when $`N_X = -DQ^2`$, everywhere at
//! once for a uniform membrane state — half the envelope model's $`-2DQ^2`$, the paper's
//! "the pure membrane model under-estimates the wrinkling load".
//!
//! Without gradient stiffness in $`w`$ the problem has no length scale: beyond the threshold
//! the $`w`$-equation is a pointwise law with a negative coefficient, ill-posed, and a
//! Legendre–Hadamard test over the gradient block cannot see it (measured in
//! `models/tests/pure_membrane_example1.rs`). There is no wavelength selection either: its
//! threshold $`DQ^2`$ falls with $`Q`$, so $`Q`$ must come from elsewhere (eq. 44 or the reference
//! envelope's minimisation).

wrinkle_macros::energy_model! {
    /// Pure membrane model (Damil, Potier-Ferry & Hu 2014, eqs 33-34): reference envelope without gradients of w.
    model PureMembrane as "pure-membrane" {
        fields: u [displacement_x], v [displacement_y], w [envelope];
        parameters: young "Young's modulus E (MPa)", poisson "Poisson ratio", thickness "thickness h (mm)",
            wavenumber "wavenumber Q (1/mm)", direction "wave-vector angle from X (rad)";
        let c = cos(direction);
        let s = sin(direction);
        let membrane_stiffness = young * thickness / (1 - poisson^2);
        let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
        let q2 = wavenumber^2;
        let gx = u.x + q2 * c^2 * w^2;
        let gy = v.y + q2 * s^2 * w^2;
        let gxy = u.y + v.x + 2 * q2 * c * s * w^2;
        energy membrane = 0.5 * membrane_stiffness
            * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
        energy bending = bending_stiffness * q2^2 * w^2;
    }
}
