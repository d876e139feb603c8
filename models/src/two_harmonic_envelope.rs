//! A **two-harmonic** envelope model derived by the DSL from the Kirchhoff FvK plate
//! ([`crate::from_kirchhoff_plate`]): the first and second harmonics of the deflection and the
//! second harmonics of the in-plane displacement — a model nobody derives by hand, asked for by
//! the paper's closing question (do more harmonics improve the results?).
//!
//! Ansatz (THEORY.md §3), with $`\mathbf e = (\cos\theta, \sin\theta)`$ and slow derivatives to
//! order 2:
//! $$`u = u_0 + 2\,\mathrm{Re}(u_2 e^{2iQ\,\mathbf e\cdot\mathbf X}),\quad
//! v = v_0 + 2\,\mathrm{Re}(v_2 e^{2iQ\,\mathbf e\cdot\mathbf X}),\quad
//! w = 2\,\mathrm{Re}(w_1 e^{iQ\,\mathbf e\cdot\mathbf X}) + 2\,\mathrm{Re}(w_2 e^{2iQ\,\mathbf e\cdot\mathbf X}),`$$
//! $`w_1 = w`$ and $`w_2`$ real, $`u_2 = u_{2r} + iu_{2i}`$, $`v_2 = v_{2r} + iv_{2i}`$ complex.
//! * `membrane`: the membrane strain is expanded with **all** its harmonics, each truncated to
//!   two slow derivatives (`truncated(gx, gy, gxy)`), and the zeroth harmonic of the energy is
//!   taken of the whole, $`\tfrac12\sum_m \gamma_m\cdot L_m\bar\gamma_m`$. The paper's ansatz
//!   keeps $`\gamma_0`$ only (it averages the strain before squaring: the strain harmonics are
//!   assumed fully relaxed); here $`\gamma_2 = \hat\varepsilon(u_2) + \tfrac12\mathbf p_1\otimes
//!   \mathbf p_1 + \ldots`$, $`\hat\varepsilon(u_2) = \operatorname{sym}(\nabla u_2 + 2iQ\,\mathbf e
//!   \otimes u_2)`$, $`\mathbf p_1 = \nabla w_1 + iQw_1\mathbf e`$, is relaxed only as far as the
//!   in-plane second harmonic can: the energy is the paper's plus $`\sum_{m\ne0}`$ of
//!   non-negative terms;
//! * `bending`: the zeroth harmonic of the Kirchhoff bending, truncated and integrated by parts
//!   with the envelopes zero on the boundary: the reference model's (64) for $`w_1`$ plus
//!   $`D(16Q^4w_2^2 + 24Q^2(\mathbf e\cdot\nabla w_2)^2 + 8Q^2(\mathbf e^\perp\cdot\nabla w_2)^2)`$.
//!
//! **Symmetry.** A shift by half a wavelength combined with $`w \mapsto -w`$ maps
//! $`(w_1, w_2, u_2) \mapsto (w_1, -w_2, u_2)`$ and leaves the energy unchanged, so $`w_2 = 0`$ is
//! invariant: on a path started from a perturbation of $`w_1`$ the second harmonic of the
//! deflection stays exactly zero, and its own threshold ($`\approx 2.1\lambda_c`$ at $`2Q`$) is
//! beyond the paths studied. What the second harmonic changes is the in-plane part $`u_2, v_2`$.
//!
//! **Roles.** `w` is the `envelope` (the path's amplitudes are read from it,
//! $`2w\cos(Q\,\mathbf e\cdot\mathbf X)`$), `w2` the `second_envelope`, and the in-plane
//! harmonics have the roles `second_displacement_{x,y}_{real,imaginary}`: all are zero on
//! clamped edges, like the envelopes. (The application's reconstruction of the physical
//! deflection reads `envelope` only; with $`w_2 = 0`$ on the paths nothing is lost.)

crate::from_kirchhoff_plate! {
    /// Two-harmonic envelope model (w1, w2 and the in-plane second harmonics) derived by the DSL from the Kirchhoff FvK plate.
    model TwoHarmonicEnvelope as "two-harmonic-envelope" {
        fields: u [displacement_x], v [displacement_y], w [envelope], w2 [second_envelope],
            u2r [second_displacement_x_real], u2i [second_displacement_x_imaginary],
            v2r [second_displacement_y_real], v2i [second_displacement_y_imaginary];
        parameters: wavenumber "wavenumber Q (1/mm)", direction "wave-vector angle from X (rad)";
        ansatz {
            wavenumber: wavenumber;
            direction: direction;
            slow_derivatives: 2;
            u = u + 2 Re((u2r + i u2i) e^{2 i Q e.X});
            v = v + 2 Re((v2r + i v2i) e^{2 i Q e.X});
            w = 2 Re(w e^{i Q e.X}) + 2 Re(w2 e^{2 i Q e.X});
        }
        energy membrane = average(membrane, truncated(gx, gy, gxy));
        energy bending = average(bending);
    }
}
