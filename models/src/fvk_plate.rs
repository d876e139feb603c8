//! Föppl–von Kármán plate with Reissner–Mindlin bending: THEORY.md §2, the paper's eqs (16)–(17).
//!
//! The project's "full model": it resolves every wrinkle, and is the reference the envelope
//! models are checked against.
//!
//! Unknowns, in dof order, with the role each field plays: `u` `[displacement_x]`, `v`
//! `[displacement_y]` the in-plane displacements, `w` `[deflection]`, `theta_x` `[rotation_x]` and
//! `theta_y` `[rotation_y]` the rotations, i.e. the slopes of the normal,
//! $`\boldsymbol\theta \approx \nabla w`$ (**sign convention**: $`\theta_x`$ is the slope
//! $`\partial w/\partial X`$ in the Kirchhoff limit, so a positive $`\theta_x`$ turns the normal
//! toward $`+X`$; it is a rotation about $`-Y`$).
//!
//! * membrane strain $`\gamma = \varepsilon(u) + \tfrac12\nabla w\otimes\nabla w`$, Voigt
//!   $`(\gamma_X, \gamma_Y, 2\gamma_{XY}) = (u_{,X} + \tfrac12 w_{,X}^2,\ v_{,Y} + \tfrac12 w_{,Y}^2,\
//!   u_{,Y} + v_{,X} + w_{,X} w_{,Y})`$, energy $`\tfrac12\gamma\cdot L_m\gamma`$ with
//!   $`L_m = \frac{Eh}{1-\nu^2}\begin{bmatrix}1&\nu&0\\\nu&1&0\\0&0&\frac{1-\nu}{2}\end{bmatrix}`$
//!   (16);
//! * curvature $`\kappa = \operatorname{sym}\nabla\boldsymbol\theta`$:
//!   $`\kappa_{XX} = \theta_{x,X}`$, $`\kappa_{YY} = \theta_{y,Y}`$,
//!   $`\kappa_{XY} = \tfrac12(\theta_{x,Y} + \theta_{y,X})`$; bending energy
//!   $$`\tfrac12 D\left[(\operatorname{tr}\kappa)^2 - 2(1-\nu)\det\kappa\right]
//!   = \tfrac{D}{2}\left[\kappa_{XX}^2 + \kappa_{YY}^2 + 2\nu\kappa_{XX}\kappa_{YY}
//!   + 2(1-\nu)\kappa_{XY}^2\right],\qquad D = \frac{Eh^3}{12(1-\nu^2)},`$$
//!   which for $`\boldsymbol\theta = \nabla w`$ is the FvK bending energy
//!   $`\tfrac12 D[(\Delta w)^2 - 2(1-\nu)(w_{,XX}w_{,YY} - w_{,XY}^2)]`$ of (17);
//! * transverse shear $`\tfrac12 k G h\,|\nabla w - \boldsymbol\theta|^2`$, $`k = 5/6`$,
//!   $`G = E/(2(1+\nu))`$, a term of its own integrated with the reduced 2×2 Gauss rule
//!   (membrane and bending use 3×3).
//!
//! What the reduced rule does, measured (`models/examples/fvk_plate_study.rs`, tests
//! `models/tests/fvk_plate_kirchhoff.rs`, `models/tests/fvk_plate_example1_buckling.rs`):
//! * no spurious zero-energy mode: a free plate has exactly the 6 rigid modes (1×1, 2×2, 4×4
//!   meshes), clamped and simply supported tangents are positive definite, and the lowest
//!   eigenvalue of $`K\varphi = \mu M\varphi`$ ($`M`$ the deflection mass) is the physical
//!   one (at most 0.2 % below Kirchhoff's, the Mindlin shear softening at L/h = 100), never
//!   near zero;
//! * it still locks on coarse meshes of thin plates with boundary layers: the centre deflection
//!   of a clamped square under pressure is within 1 % from n × n = 8×8, 16×16, 32×32 for
//!   L/h = 10², 10³, 10⁴ (−26 % on 16×16 at L/h = 10⁴);
//! * on the wrinkling problem (the paper's example 1, L_Y/h = 4000) it converges as
//!   $`O(h_e^4)`$ with 8–16 Q8 per wavelength; a Lyly–Stenberg–Vihinen stabilised shear
//!   (locking-free on the square plates) converges there only as $`O(\alpha h_e^2)`$, from
//!   below, so it is not used.
//!
//! Stationarity gives $`\operatorname{div}N = 0`$ and, in the Kirchhoff limit,
//! $`D\Delta^2 w - \operatorname{div}(N\nabla w) = 0`$ (17).
//!
//! Boundary conditions in these variables: clamped $`w = \theta_x = \theta_y = 0`$; hard simple
//! support $`w = 0`$ and the tangential rotation zero ($`\theta_y = 0`$ on an edge $`X = `$ const,
//! $`\theta_x = 0`$ on an edge $`Y = `$ const).

wrinkle_macros::energy_model! {
    /// Föppl–von Kármán plate, Reissner–Mindlin bending and reduced-integrated shear (Damil, Potier-Ferry & Hu 2014, eqs 16–17).
    model FvkPlate as "fvk-plate" {
        fields: u [displacement_x], v [displacement_y], w [deflection],
            theta_x [rotation_x], theta_y [rotation_y];
        parameters: young "Young's modulus E (MPa)", poisson "Poisson ratio",
            thickness "thickness h (mm)";
        let membrane_stiffness = young * thickness / (1 - poisson^2);
        let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
        let shear_stiffness = 5 / 6 * young / (2 * (1 + poisson)) * thickness;
        let gx = u.x + 0.5 * w.x^2;
        let gy = v.y + 0.5 * w.y^2;
        let gxy = u.y + v.x + w.x * w.y;
        let kxx = theta_x.x;
        let kyy = theta_y.y;
        let kxy = 0.5 * (theta_x.y + theta_y.x);
        energy membrane = 0.5 * membrane_stiffness
            * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
        energy bending = 0.5 * bending_stiffness
            * (kxx^2 + kyy^2 + 2 * poisson * kxx * kyy + 2 * (1 - poisson) * kxy^2);
        energy shear [reduced] = 0.5 * shear_stiffness * ((w.x - theta_x)^2 + (w.y - theta_y)^2);
    }
}
