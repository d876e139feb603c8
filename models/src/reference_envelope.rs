//! Reference envelope model: THEORY.md §4, the paper's eqs (22), (23) and (64).
//!
//! Unknowns: in-plane displacement $`(u, v)`$ and the real envelope $`w`$ of the first
//! harmonic, the physical deflection being $`2w\cos(Q\,\mathbf{e}\cdot\mathbf{X})`$.
//! With the wave direction $`\mathbf{e} = (\cos\theta, \sin\theta)`$,
//! $$`\gamma = \varepsilon(u) + \nabla w\otimes\nabla w + Q^2 w^2\, \mathbf{e}\otimes\mathbf{e},\qquad
//! \psi = \tfrac12\gamma : L_m\gamma + D\left(Q^4 w^2 + 6Q^2(\mathbf{e}\cdot\nabla w)^2
//! + 2Q^2(\mathbf{e}^\perp\cdot\nabla w)^2\right)`$$
//! with $`L_m = \frac{Eh}{1-\nu^2}\begin{bmatrix}1&\nu&0\\\nu&1&0\\0&0&\frac{1-\nu}{2}\end{bmatrix}`$
//! in Voigt form and $`D = Eh^3/(12(1-\nu^2))`$. Its Euler–Lagrange equations are
//! $`\operatorname{div}N = 0`$ and the envelope equation (32).

wrinkle_macros::energy_model! {
    /// Reference envelope model (Damil, Potier-Ferry & Hu 2014, eqs 22, 23, 64): real envelope, one harmonic.
    model ReferenceEnvelope as "reference-envelope" {
        fields: u [displacement_x], v [displacement_y], w [envelope];
        parameters: young "Young's modulus E (MPa)", poisson "Poisson ratio", thickness "thickness h (mm)",
            wavenumber "wavenumber Q (1/mm)", direction "wave-vector angle from X (rad)";
        let c = cos(direction);
        let s = sin(direction);
        let membrane_stiffness = young * thickness / (1 - poisson^2);
        let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
        let q2 = wavenumber^2;
        let gx = u.x + w.x^2 + q2 * c^2 * w^2;
        let gy = v.y + w.y^2 + q2 * s^2 * w^2;
        let gxy = u.y + v.x + 2 * w.x * w.y + 2 * q2 * c * s * w^2;
        energy membrane = 0.5 * membrane_stiffness
            * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
        energy bending = bending_stiffness * (q2^2 * w^2 + 6 * q2 * (c * w.x + s * w.y)^2
            + 2 * q2 * (c * w.y - s * w.x)^2);
    }
}
