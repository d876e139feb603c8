//! The 3-node quadratic Lagrange line (Line3): value and $`\partial/\partial X`$, $`C^0`$ at
//! the nodes.
//!
//! Reference line $`[-1, 1]`$, nodes in VTK order (`VTK_QUADRATIC_EDGE`, type 21): the two ends
//! $`\xi = -1, 1`$, then the middle $`\xi = 0`$ — the order of a plane element's edge
//! `[end, end, middle]`. Shape functions and their derivatives
//! $$`N_0 = \tfrac12\xi(\xi - 1),\quad N_1 = \tfrac12\xi(\xi + 1),\quad N_2 = 1 - \xi^2,`$$
//! $$`N_0' = \xi - \tfrac12,\quad N_1' = \xi + \tfrac12,\quad N_2' = -2\xi;`$$
//! isoparametric map $`X(\xi) = \sum_i N_i X_i`$, $`\partial_X N_i = N_i'/X'(\xi)`$. The element
//! reproduces quadratics in $`X`$ exactly when the middle node is at the middle (affine map).

use super::{Element, ElementKind, GaussRule, Mapping};
use crate::model::{Derivative, QuadratureRule};

/// The quadratic Lagrange line element.
#[derive(Clone, Copy, Debug, Default)]
pub struct Line3;

impl Line3 {
    /// Shape values $`N_i(\xi)`$.
    pub fn shape_values(xi: f64) -> [f64; 3] {
        [0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi]
    }

    /// Reference derivatives $`dN_i/d\xi`$.
    pub fn shape_reference_derivatives(xi: f64) -> [f64; 3] {
        [xi - 0.5, xi + 0.5, -2.0 * xi]
    }

    /// $`X(\xi)`$, $`Y(\xi)`$ and $`dX/d\xi`$.
    fn map(coordinates: &[[f64; 2]], xi: f64) -> ([f64; 2], f64) {
        let n = Line3::shape_values(xi);
        let dn = Line3::shape_reference_derivatives(xi);
        let mut point = [0.0; 2];
        let mut jacobian = 0.0;
        for i in 0..3 {
            point[0] += n[i] * coordinates[i][0];
            point[1] += n[i] * coordinates[i][1];
            jacobian += dn[i] * coordinates[i][0];
        }
        (point, jacobian)
    }
}

impl Element for Line3 {
    const KIND: ElementKind = ElementKind::Line3;
    const NODES: usize = 3;
    const DIMENSION: usize = 1;
    const COMPONENTS: usize = 1;
    const DERIVATIVES: &'static [Derivative] = &[Derivative::Value, Derivative::X];
    const REFERENCE_NODES: &'static [[f64; 2]] = &[[-1.0, 0.0], [1.0, 0.0], [0.0, 0.0]];
    const FACETS: &'static [&'static [usize]] = &[&[0], &[1]];
    const VTK_CELL_TYPE: u8 = 21;

    /// 3 points (full: exact for the mass matrix, degree 4) or 2 (reduced: exact for
    /// $`\int N_i' N_j'`$ on an affine element).
    fn quadrature(rule: QuadratureRule) -> GaussRule {
        match rule {
            QuadratureRule::Full => GaussRule::line(3),
            QuadratureRule::Reduced => GaussRule::line(2),
        }
    }

    fn basis(coordinates: &[[f64; 2]], [xi, _]: [f64; 2], rows: &mut [f64]) -> Mapping {
        let (point, jacobian) = Line3::map(coordinates, xi);
        let dn = Line3::shape_reference_derivatives(xi);
        rows[..3].copy_from_slice(&Line3::shape_values(xi));
        for (row, derivative) in rows[3..6].iter_mut().zip(dn) {
            *row = derivative / jacobian;
        }
        Mapping { point, jacobian }
    }

    fn value_weights(_coordinates: &[[f64; 2]], [xi, _]: [f64; 2], weights: &mut [f64]) {
        weights.copy_from_slice(&Line3::shape_values(xi));
    }

    /// Newton on $`X(\xi) = X_p`$ from $`\xi = 0`$; the point must lie on the axis (within
    /// $`10^{-10}`$ of the element's length).
    fn reference_of(coordinates: &[[f64; 2]], point: [f64; 2]) -> Option<[f64; 2]> {
        let length = (coordinates[1][0] - coordinates[0][0]).abs();
        if (point[1] - coordinates[2][1]).abs() > 1e-10 * length {
            return None;
        }
        let mut xi = 0.0;
        for _ in 0..20 {
            let (mapped, jacobian) = Line3::map(coordinates, xi);
            if jacobian.abs() < f64::MIN_POSITIVE {
                return None;
            }
            let step = (point[0] - mapped[0]) / jacobian;
            xi += step;
            if step.abs() < 1e-14 {
                break;
            }
        }
        (xi.abs() <= 1.0 + 1e-9).then_some([xi.clamp(-1.0, 1.0), 0.0])
    }
}

/// Values of the 3-node quadratic segment (a plane element's edge, or a [`Line3`]) at the
/// 3-point Gauss rule: `(N_0, N_1, N_2)` for end, end, middle node, and the weights.
pub fn quadratic_line_rule() -> Vec<([f64; 3], f64)> {
    let (x, w) = GaussRule::legendre(3);
    x.iter()
        .zip(w.iter())
        .map(|(&s, &wt)| ([0.5 * s * (s - 1.0), 0.5 * s * (s + 1.0), 1.0 - s * s], wt))
        .collect()
}
