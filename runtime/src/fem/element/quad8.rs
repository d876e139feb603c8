//! The 8-node serendipity quadrilateral (Q8): value and first derivatives, $`C^0`$ across edges.
//!
//! Reference square $`[-1,1]^2`$, nodes in VTK order (`VTK_QUADRATIC_QUAD`, type 23): the four
//! corners counter-clockwise from $`(-1,-1)`$, then the mid-side nodes of edges 0–1, 1–2, 2–3, 3–0.
//! Shape functions
//! * corners $`(\xi_i,\eta_i)`$: $`N_i = \tfrac14(1+\xi\xi_i)(1+\eta\eta_i)(\xi\xi_i+\eta\eta_i-1)`$,
//! * mid-sides with $`\xi_i = 0`$: $`N_i = \tfrac12(1-\xi^2)(1+\eta\eta_i)`$,
//! * mid-sides with $`\eta_i = 0`$: $`N_i = \tfrac12(1+\xi\xi_i)(1-\eta^2)`$.

use super::{Element, ElementKind, GaussRule, Mapping};
use crate::model::{Derivative, QuadratureRule};

/// Number of nodes of a [`Quad8`].
pub const QUAD8_NODES: usize = 8;

/// Reference coordinates of the Q8 nodes (VTK order).
pub const QUAD8_REFERENCE_NODES: [[f64; 2]; QUAD8_NODES] = [
    [-1.0, -1.0],
    [1.0, -1.0],
    [1.0, 1.0],
    [-1.0, 1.0],
    [0.0, -1.0],
    [1.0, 0.0],
    [0.0, 1.0],
    [-1.0, 0.0],
];

/// The Q8 serendipity element on the reference square.
#[derive(Clone, Copy, Debug, Default)]
pub struct Quad8;

impl Quad8 {
    /// Shape function values $`N_i(\xi,\eta)`$.
    pub fn shape_values(xi: f64, eta: f64) -> [f64; QUAD8_NODES] {
        let mut n = [0.0; QUAD8_NODES];
        for (i, [xi_i, eta_i]) in QUAD8_REFERENCE_NODES.iter().copied().enumerate() {
            n[i] = if i < 4 {
                0.25 * (1.0 + xi * xi_i) * (1.0 + eta * eta_i) * (xi * xi_i + eta * eta_i - 1.0)
            } else if xi_i == 0.0 {
                0.5 * (1.0 - xi * xi) * (1.0 + eta * eta_i)
            } else {
                0.5 * (1.0 + xi * xi_i) * (1.0 - eta * eta)
            };
        }
        n
    }

    /// Reference gradients $`(\partial N_i/\partial\xi, \partial N_i/\partial\eta)`$.
    pub fn shape_reference_gradients(xi: f64, eta: f64) -> [[f64; 2]; QUAD8_NODES] {
        let mut g = [[0.0; 2]; QUAD8_NODES];
        for (i, [xi_i, eta_i]) in QUAD8_REFERENCE_NODES.iter().copied().enumerate() {
            g[i] = if i < 4 {
                [
                    0.25 * xi_i * (1.0 + eta * eta_i) * (2.0 * xi * xi_i + eta * eta_i),
                    0.25 * eta_i * (1.0 + xi * xi_i) * (xi * xi_i + 2.0 * eta * eta_i),
                ]
            } else if xi_i == 0.0 {
                [-xi * (1.0 + eta * eta_i), 0.5 * eta_i * (1.0 - xi * xi)]
            } else {
                [0.5 * xi_i * (1.0 - eta * eta), -eta * (1.0 + xi * xi_i)]
            };
        }
        g
    }
}

impl Element for Quad8 {
    const KIND: ElementKind = ElementKind::Quad8;
    const NODES: usize = QUAD8_NODES;
    const DIMENSION: usize = 2;
    const COMPONENTS: usize = 1;
    const DERIVATIVES: &'static [Derivative] = &[Derivative::Value, Derivative::X, Derivative::Y];
    const REFERENCE_NODES: &'static [[f64; 2]] = &QUAD8_REFERENCE_NODES;
    const FACETS: &'static [&'static [usize]] = &[&[0, 1, 4], &[1, 2, 5], &[2, 3, 6], &[3, 0, 7]];
    const VTK_CELL_TYPE: u8 = 23;

    /// 3×3 (full: exact for the mass matrix of an affine element) or 2×2 (reduced, e.g. the
    /// transverse shear of Reissner–Mindlin).
    fn quadrature(rule: QuadratureRule) -> GaussRule {
        match rule {
            QuadratureRule::Full => GaussRule::square(3),
            QuadratureRule::Reduced => GaussRule::square(2),
        }
    }

    /// Rows $`N_i`$, $`\partial_X N_i`$, $`\partial_Y N_i`$ with
    /// $`\nabla_X N = J^{-T}\nabla_\xi N`$, $`J = \partial(X, Y)/\partial(\xi, \eta)`$.
    fn basis(coordinates: &[[f64; 2]], [xi, eta]: [f64; 2], rows: &mut [f64]) -> Mapping {
        let n = Quad8::shape_values(xi, eta);
        let dn = Quad8::shape_reference_gradients(xi, eta);
        let (jac, point) = Quad8::jacobian(coordinates, &n, &dn);
        let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
        // ∇_X N = J^{-T} ∇_ξ N
        let inv = [
            [jac[1][1] / det, -jac[0][1] / det],
            [-jac[1][0] / det, jac[0][0] / det],
        ];
        let (values, gradients) = rows.split_at_mut(QUAD8_NODES);
        let (gradients_x, gradients_y) = gradients.split_at_mut(QUAD8_NODES);
        values.copy_from_slice(&n);
        for i in 0..QUAD8_NODES {
            gradients_x[i] = inv[0][0] * dn[i][0] + inv[1][0] * dn[i][1];
            gradients_y[i] = inv[0][1] * dn[i][0] + inv[1][1] * dn[i][1];
        }
        Mapping {
            point,
            jacobian: det,
        }
    }

    fn value_weights(_coordinates: &[[f64; 2]], [xi, eta]: [f64; 2], weights: &mut [f64]) {
        weights.copy_from_slice(&Quad8::shape_values(xi, eta));
    }

    /// Newton inversion of the isoparametric map from the centre (20 iterations at most), after
    /// a bounding-box test.
    fn reference_of(coordinates: &[[f64; 2]], point: [f64; 2]) -> Option<[f64; 2]> {
        let tolerance = 1e-10;
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &[x, y] in coordinates {
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        let slack = tolerance * ((x1 - x0) + (y1 - y0));
        if point[0] < x0 - slack
            || point[0] > x1 + slack
            || point[1] < y0 - slack
            || point[1] > y1 + slack
        {
            return None;
        }
        let mut reference = [0.0, 0.0];
        for _ in 0..20 {
            let n = Quad8::shape_values(reference[0], reference[1]);
            let dn = Quad8::shape_reference_gradients(reference[0], reference[1]);
            let (jac, x) = Quad8::jacobian(coordinates, &n, &dn);
            let r = [point[0] - x[0], point[1] - x[1]];
            let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
            if det.abs() < f64::MIN_POSITIVE {
                break;
            }
            let d = [
                (jac[1][1] * r[0] - jac[0][1] * r[1]) / det,
                (-jac[1][0] * r[0] + jac[0][0] * r[1]) / det,
            ];
            reference[0] += d[0];
            reference[1] += d[1];
            if d[0].abs() + d[1].abs() < 1e-14 {
                break;
            }
        }
        (reference[0].abs() <= 1.0 + 1e-9 && reference[1].abs() <= 1.0 + 1e-9).then_some(reference)
    }
}

impl Quad8 {
    /// The Jacobian $`J_{ab} = \partial X_a/\partial\xi_b`$ and the mapped point, from the shape
    /// values `n` and reference gradients `dn` (sums in node order).
    fn jacobian(
        coordinates: &[[f64; 2]],
        n: &[f64; QUAD8_NODES],
        dn: &[[f64; 2]; QUAD8_NODES],
    ) -> ([[f64; 2]; 2], [f64; 2]) {
        // J = [[dX/dξ, dX/dη], [dY/dξ, dY/dη]]
        let mut jac = [[0.0; 2]; 2];
        let mut point = [0.0; 2];
        for i in 0..QUAD8_NODES {
            for a in 0..2 {
                point[a] += n[i] * coordinates[i][a];
                for b in 0..2 {
                    jac[a][b] += coordinates[i][a] * dn[i][b];
                }
            }
        }
        (jac, point)
    }
}

#[cfg(test)]
mod tests {
    use super::super::ElementValues;
    use super::*;

    #[test]
    fn quad8_shape_functions_are_nodal_and_partition_unity() {
        for (j, [xj, yj]) in QUAD8_REFERENCE_NODES.iter().copied().enumerate() {
            let n = Quad8::shape_values(xj, yj);
            for (i, v) in n.iter().enumerate() {
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((v - expected).abs() < 1e-14);
            }
        }
        for &(xi, eta) in &[(0.3, -0.7), (-0.9, 0.1), (0.0, 0.0)] {
            let n = Quad8::shape_values(xi, eta);
            assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-14);
            let g = Quad8::shape_reference_gradients(xi, eta);
            let sx: f64 = g.iter().map(|v| v[0]).sum();
            let sy: f64 = g.iter().map(|v| v[1]).sum();
            assert!(sx.abs() < 1e-14 && sy.abs() < 1e-14);
        }
    }

    #[test]
    fn quad8_gradients_match_finite_differences() {
        let (xi, eta, h) = (0.37, -0.21, 1e-6);
        let g = Quad8::shape_reference_gradients(xi, eta);
        let (p, m) = (
            Quad8::shape_values(xi + h, eta),
            Quad8::shape_values(xi - h, eta),
        );
        let (pe, me) = (
            Quad8::shape_values(xi, eta + h),
            Quad8::shape_values(xi, eta - h),
        );
        for i in 0..8 {
            assert!((g[i][0] - (p[i] - m[i]) / (2.0 * h)).abs() < 1e-9);
            assert!((g[i][1] - (pe[i] - me[i]) / (2.0 * h)).abs() < 1e-9);
        }
    }

    #[test]
    fn quad8_reproduces_quadratics_on_a_skewed_parallelogram() {
        // Skewed parallelogram (affine map): the isoparametric Q8 reproduces any complete
        // quadratic exactly, values and gradients. (On a general quadrilateral the serendipity
        // element loses quadratic completeness, so the mesh generator keeps elements affine.)
        let corners = [[0.0, 0.0], [2.0, 0.2], [2.5, 1.7], [0.5, 1.5]];
        let mut xy = [[0.0; 2]; 8];
        for i in 0..4 {
            xy[i] = corners[i];
            let j = (i + 1) % 4;
            xy[4 + i] = [
                0.5 * (corners[i][0] + corners[j][0]),
                0.5 * (corners[i][1] + corners[j][1]),
            ];
        }
        let f = |x: f64, y: f64| 1.0 + 2.0 * x - y + 0.5 * x * x + 0.3 * x * y - 0.7 * y * y;
        let grad = |x: f64, y: f64| [2.0 + x + 0.3 * y, -1.0 + 0.3 * x - 1.4 * y];
        let nodal: Vec<f64> = xy.iter().map(|p| f(p[0], p[1])).collect();
        let ev = ElementValues::new::<Quad8>(0, &xy, &GaussRule::square(3)).unwrap();
        let area: f64 = ev.weights.iter().sum();
        // shoelace area
        let mut shoelace = 0.0;
        for i in 0..4 {
            let j = (i + 1) % 4;
            shoelace += corners[i][0] * corners[j][1] - corners[j][0] * corners[i][1];
        }
        assert!((area - 0.5 * shoelace).abs() < 1e-12);
        for q in 0..9 {
            let [x, y] = ev.points[q];
            let row = |r: usize| -> f64 { (0..8).map(|i| ev.row(q, r)[i] * nodal[i]).sum() };
            let (v, gx, gy) = (row(0), row(1), row(2));
            assert!((v - f(x, y)).abs() < 1e-12);
            assert!((gx - grad(x, y)[0]).abs() < 1e-11);
            assert!((gy - grad(x, y)[1]).abs() < 1e-11);
        }
    }

    #[test]
    fn inverted_element_is_an_error() {
        let mut xy = [[0.0; 2]; 8];
        for i in 0..8 {
            xy[i] = [-QUAD8_REFERENCE_NODES[i][0], QUAD8_REFERENCE_NODES[i][1]];
        }
        let err = ElementValues::new::<Quad8>(7, &xy, &GaussRule::square(2)).unwrap_err();
        assert_eq!(err.element, 7);
    }
}
