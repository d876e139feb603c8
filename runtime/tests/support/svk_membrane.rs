//! The Saint-Venant–Kirchhoff plane-stress membrane (Green–Lagrange strains) of the runtime's
//! geometrically nonlinear tests, written in the energy DSL.

wrinkle_macros::energy_model! {
    /// Saint-Venant–Kirchhoff plane-stress membrane (Green–Lagrange strains).
    model SvkMembrane as "test-svk-membrane" {
        fields: u [displacement_x], v [displacement_y];
        parameters: young, poisson, thickness;
        let c = young * thickness / (1 - poisson^2);
        let exx = u.x + 0.5 * (u.x^2 + v.x^2);
        let eyy = v.y + 0.5 * (u.y^2 + v.y^2);
        let gxy = u.y + v.x + u.x * u.y + v.x * v.y;
        energy membrane = 0.5 * c * (exx^2 + eyy^2 + 2 * poisson * exx * eyy
            + 0.5 * (1 - poisson) * gxy^2);
    }
}
