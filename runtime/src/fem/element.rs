//! The 8-node serendipity quadrilateral (Q8) and its Gauss rules.
//!
//! Reference square $`[-1,1]^2`$, nodes in VTK order (`VTK_QUADRATIC_QUAD`, type 23): the four
//! corners counter-clockwise from $`(-1,-1)`$, then the mid-side nodes of edges 0–1, 1–2, 2–3, 3–0.
//! Shape functions
//! * corners $`(\xi_i,\eta_i)`$: $`N_i = \tfrac14(1+\xi\xi_i)(1+\eta\eta_i)(\xi\xi_i+\eta\eta_i-1)`$,
//! * mid-sides with $`\xi_i = 0`$: $`N_i = \tfrac12(1-\xi^2)(1+\eta\eta_i)`$,
//! * mid-sides with $`\eta_i = 0`$: $`N_i = \tfrac12(1+\xi\xi_i)(1-\eta^2)`$.

use crate::model::QuadratureRule;

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

/// A tensor-product Gauss–Legendre rule on the reference square.
#[derive(Clone, Debug)]
pub struct GaussRule {
    /// Points $`(\xi, \eta)`$.
    pub points: Vec<[f64; 2]>,
    /// Weights (sum 4).
    pub weights: Vec<f64>,
}

impl GaussRule {
    /// One-dimensional Gauss–Legendre points and weights on $`[-1, 1]`$ with `n` ∈ {1, 2, 3} points.
    pub fn line(n: usize) -> (Vec<f64>, Vec<f64>) {
        match n {
            1 => (vec![0.0], vec![2.0]),
            2 => {
                let a = 1.0 / 3f64.sqrt();
                (vec![-a, a], vec![1.0, 1.0])
            }
            3 => {
                let a = (3.0f64 / 5.0).sqrt();
                (vec![-a, 0.0, a], vec![5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0])
            }
            _ => panic!("GaussRule::line supports 1 to 3 points, got {n}"),
        }
    }

    /// The `n × n` tensor rule.
    pub fn square(n: usize) -> Self {
        let (x, w) = Self::line(n);
        let mut points = Vec::with_capacity(n * n);
        let mut weights = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                points.push([x[i], x[j]]);
                weights.push(w[i] * w[j]);
            }
        }
        GaussRule { points, weights }
    }

    /// The rule a term asks for: 3×3 (full) or 2×2 (reduced).
    pub fn for_quadrature(rule: QuadratureRule) -> Self {
        match rule {
            QuadratureRule::Full => Self::square(3),
            QuadratureRule::Reduced => Self::square(2),
        }
    }
}

/// Shape values and physical gradients of one element at the points of one rule.
///
/// For point $`q`$: `values[q][i]` $`= N_i`$, `gradients[q][i]` $`= (\partial_X N_i, \partial_Y N_i)`$,
/// `weights[q]` $`= w_q \det J_q`$. Gradients are only filled when `with_gradients` was asked for
/// (a model that uses no derivative never pays for them).
#[derive(Clone, Debug)]
pub struct ElementValues {
    /// $`N_i`$ at each point.
    pub values: Vec<[f64; QUAD8_NODES]>,
    /// $`\nabla N_i`$ at each point (empty when not requested).
    pub gradients: Vec<[[f64; 2]; QUAD8_NODES]>,
    /// Integration weight times Jacobian determinant.
    pub weights: Vec<f64>,
    /// Physical coordinates of each point.
    pub points: Vec<[f64; 2]>,
    /// Per point, the three rows $`(N_i,\ \partial_X N_i,\ \partial_Y N_i)`$ indexed by
    /// [`derivative_row`] (the gradient rows are zero when gradients were not requested): the
    /// weights with which a jet entry takes its value from the element's nodal values.
    pub basis: Vec<[[f64; QUAD8_NODES]; 3]>,
}

/// Row of [`ElementValues::basis`] holding a derivative: value 0, X 1, Y 2; `None` for the
/// second derivatives, which the Q8 element does not supply (its shape functions are only
/// $`C^0`$ across element edges, so $`\partial^2 f`$ of a Q8 field is not square-integrable over
/// the mesh). [`crate::problem::Problem::new`] refuses a model that asks for one.
#[inline(always)]
pub fn derivative_row(derivative: crate::model::Derivative) -> Option<usize> {
    use crate::model::Derivative;
    match derivative {
        Derivative::Value => Some(0),
        Derivative::X => Some(1),
        Derivative::Y => Some(2),
        Derivative::XX | Derivative::XY | Derivative::YY => None,
    }
}

/// Error of the isoparametric map.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "element {element}: non-positive Jacobian determinant {determinant:e} at a quadrature point (inverted or degenerate element)"
)]
pub struct JacobianError {
    /// Element index.
    pub element: usize,
    /// The determinant found.
    pub determinant: f64,
}

impl ElementValues {
    /// Evaluates the Q8 element with node coordinates `coordinates` on `rule`.
    pub fn new(
        element: usize,
        coordinates: &[[f64; 2]; QUAD8_NODES],
        rule: &GaussRule,
        with_gradients: bool,
    ) -> Result<Self, JacobianError> {
        let nq = rule.points.len();
        let mut values = Vec::with_capacity(nq);
        let mut gradients = Vec::with_capacity(if with_gradients { nq } else { 0 });
        let mut weights = Vec::with_capacity(nq);
        let mut points = Vec::with_capacity(nq);
        for (q, &[xi, eta]) in rule.points.iter().enumerate() {
            let n = Quad8::shape_values(xi, eta);
            let dn = Quad8::shape_reference_gradients(xi, eta);
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
            let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
            if det.is_nan() || det <= 0.0 {
                return Err(JacobianError {
                    element,
                    determinant: det,
                });
            }
            if with_gradients {
                // ∇_X N = J^{-T} ∇_ξ N
                let inv = [
                    [jac[1][1] / det, -jac[0][1] / det],
                    [-jac[1][0] / det, jac[0][0] / det],
                ];
                let mut g = [[0.0; 2]; QUAD8_NODES];
                for i in 0..QUAD8_NODES {
                    g[i][0] = inv[0][0] * dn[i][0] + inv[1][0] * dn[i][1];
                    g[i][1] = inv[0][1] * dn[i][0] + inv[1][1] * dn[i][1];
                }
                gradients.push(g);
            }
            values.push(n);
            weights.push(rule.weights[q] * det);
            points.push(point);
        }
        let basis = (0..nq)
            .map(|q| {
                let mut rows = [[0.0; QUAD8_NODES]; 3];
                rows[0] = values[q];
                if with_gradients {
                    for k in 0..QUAD8_NODES {
                        rows[1][k] = gradients[q][k][0];
                        rows[2][k] = gradients[q][k][1];
                    }
                }
                rows
            })
            .collect();
        Ok(ElementValues {
            values,
            gradients,
            weights,
            points,
            basis,
        })
    }
}

/// Values of the 3-node quadratic line (an element edge) at the 3-point Gauss rule:
/// `(N_0, N_1, N_2)` for end, end, middle node, and the weights.
pub fn quadratic_line_rule() -> Vec<([f64; 3], f64)> {
    let (x, w) = GaussRule::line(3);
    x.iter()
        .zip(w.iter())
        .map(|(&s, &wt)| ([0.5 * s * (s - 1.0), 0.5 * s * (s + 1.0), 1.0 - s * s], wt))
        .collect()
}

#[cfg(test)]
mod tests {
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
        let ev = ElementValues::new(0, &xy, &GaussRule::square(3), true).unwrap();
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
            let v: f64 = (0..8).map(|i| ev.values[q][i] * nodal[i]).sum();
            let gx: f64 = (0..8).map(|i| ev.gradients[q][i][0] * nodal[i]).sum();
            let gy: f64 = (0..8).map(|i| ev.gradients[q][i][1] * nodal[i]).sum();
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
        let err = ElementValues::new(7, &xy, &GaussRule::square(2), false).unwrap_err();
        assert_eq!(err.element, 7);
    }
}
