//! The 2-node cubic Hermite line (Hermite2): value, $`\partial/\partial X`$ and
//! $`\partial^2/\partial X^2`$, $`C^1`$ at the nodes — the beam element.
//!
//! Each node carries two dofs per field, the value $`v`$ and the slope $`\theta = dv/dX`$
//! (component 0 and 1). On the element $`[X_0, X_1]`$, $`h = X_1 - X_0`$,
//! $`X = X_0 + \tfrac h2(1 + \xi)`$, $`J = dX/d\xi = h/2`$:
//! $$`v(\xi) = H_0 v_0 + J H_1 \theta_0 + H_2 v_1 + J H_3 \theta_1,`$$
//! $$`H_0 = \tfrac14(1-\xi)^2(2+\xi),\quad H_1 = \tfrac14(1-\xi)^2(1+\xi),\quad
//! H_2 = \tfrac14(1+\xi)^2(2-\xi),\quad H_3 = -\tfrac14(1+\xi)^2(1-\xi).`$$
//! The slope functions are scaled by $`J`$, so that the slope dof is the physical $`dv/dX`$ (the
//! same on both elements that share the node, which makes $`v`$ $`C^1`$). Derivatives:
//! $`\partial_X = J^{-1}\partial_\xi`$, $`\partial_X^2 = J^{-2}\partial_\xi^2`$ with
//! $$`H_0' = -\tfrac34(1-\xi^2),\ H_1' = \tfrac14(1-\xi)(-1-3\xi),\ H_2' = \tfrac34(1-\xi^2),\
//! H_3' = -\tfrac14(1+\xi)(1-3\xi),`$$
//! $$`H_0'' = \tfrac32\xi,\quad H_1'' = \tfrac12(3\xi - 1),\quad H_2'' = -\tfrac32\xi,\quad
//! H_3'' = \tfrac12(3\xi + 1).`$$
//! The element reproduces cubics in $`X`$ exactly. The geometry is linear (two nodes); VTK
//! draws it as a line (type 3).

use super::{Element, ElementKind, GaussRule, Mapping};
use crate::model::{Derivative, QuadratureRule};

/// The cubic Hermite line element.
#[derive(Clone, Copy, Debug, Default)]
pub struct Hermite2;

impl Hermite2 {
    /// Reference functions $`H_k(\xi)`$ (value, slope, value, slope; the slope ones unscaled).
    pub fn reference_values(xi: f64) -> [f64; 4] {
        let (m, p) = (1.0 - xi, 1.0 + xi);
        [
            0.25 * m * m * (2.0 + xi),
            0.25 * m * m * p,
            0.25 * p * p * (2.0 - xi),
            -0.25 * p * p * m,
        ]
    }

    /// First reference derivatives $`H_k'(\xi)`$.
    pub fn reference_first_derivatives(xi: f64) -> [f64; 4] {
        let (m, p) = (1.0 - xi, 1.0 + xi);
        [
            -0.75 * m * p,
            0.25 * m * (-1.0 - 3.0 * xi),
            0.75 * m * p,
            -0.25 * p * (1.0 - 3.0 * xi),
        ]
    }

    /// Second reference derivatives $`H_k''(\xi)`$.
    pub fn reference_second_derivatives(xi: f64) -> [f64; 4] {
        [
            1.5 * xi,
            0.5 * (3.0 * xi - 1.0),
            -1.5 * xi,
            0.5 * (3.0 * xi + 1.0),
        ]
    }

    /// $`J = (X_1 - X_0)/2`$ and the mapped point.
    fn map(coordinates: &[[f64; 2]], xi: f64) -> ([f64; 2], f64) {
        let (left, right) = (0.5 * (1.0 - xi), 0.5 * (1.0 + xi));
        let point = [
            left * coordinates[0][0] + right * coordinates[1][0],
            left * coordinates[0][1] + right * coordinates[1][1],
        ];
        (point, 0.5 * (coordinates[1][0] - coordinates[0][0]))
    }
}

impl Element for Hermite2 {
    const KIND: ElementKind = ElementKind::Hermite2;
    const NODES: usize = 2;
    const DIMENSION: usize = 1;
    const COMPONENTS: usize = 2;
    const DERIVATIVES: &'static [Derivative] = &[Derivative::Value, Derivative::X, Derivative::XX];
    const REFERENCE_NODES: &'static [[f64; 2]] = &[[-1.0, 0.0], [1.0, 0.0]];
    const FACETS: &'static [&'static [usize]] = &[&[0], &[1]];
    const VTK_CELL_TYPE: u8 = 3;

    /// 4 points (full: exact for the mass matrix, degree 6) or 2 (reduced: exact for
    /// $`\int H_i'' H_j''`$).
    fn quadrature(rule: QuadratureRule) -> GaussRule {
        match rule {
            QuadratureRule::Full => GaussRule::line(4),
            QuadratureRule::Reduced => GaussRule::line(2),
        }
    }

    fn basis(coordinates: &[[f64; 2]], [xi, _]: [f64; 2], rows: &mut [f64]) -> Mapping {
        let (point, jacobian) = Hermite2::map(coordinates, xi);
        let values = Hermite2::reference_values(xi);
        let first = Hermite2::reference_first_derivatives(xi);
        let second = Hermite2::reference_second_derivatives(xi);
        // Per function: the power of J its slope scaling adds (1 for slope functions).
        for b in 0..4 {
            let scale = if b % 2 == 1 { jacobian } else { 1.0 };
            rows[b] = values[b] * scale;
            rows[4 + b] = first[b] * scale / jacobian;
            rows[8 + b] = second[b] * scale / (jacobian * jacobian);
        }
        Mapping { point, jacobian }
    }

    fn value_weights(coordinates: &[[f64; 2]], [xi, _]: [f64; 2], weights: &mut [f64]) {
        let (_, jacobian) = Hermite2::map(coordinates, xi);
        let values = Hermite2::reference_values(xi);
        for b in 0..4 {
            weights[b] = if b % 2 == 1 {
                values[b] * jacobian
            } else {
                values[b]
            };
        }
    }

    /// The linear map inverted; the point must lie on the axis (within $`10^{-10}`$ of the
    /// element's length).
    fn reference_of(coordinates: &[[f64; 2]], point: [f64; 2]) -> Option<[f64; 2]> {
        let (left, right) = (coordinates[0][0], coordinates[1][0]);
        let length = right - left;
        if length <= 0.0 || (point[1] - coordinates[0][1]).abs() > 1e-10 * length {
            return None;
        }
        let xi = 2.0 * (point[0] - left) / length - 1.0;
        (xi.abs() <= 1.0 + 1e-9).then_some([xi.clamp(-1.0, 1.0), 0.0])
    }
}
