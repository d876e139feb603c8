//! Shape-function values and derivatives of one element at the points of one quadrature rule.

use super::{Element, GaussRule};

/// The physical basis of one element at the points of one rule: for point $`q`$, row $`r`$
/// (the element's `DERIVATIVES[r]`) and local function $`b`$, the value
/// $`\partial_r \varphi_b(\mathbf X_q)`$; with the weights $`w_q\,|J_q|`$ and the points.
///
/// A jet entry $`(f, r)`$ at point $`q`$ is $`\sum_b U^f_b\,B_{qrb}`$: the basis rows are the
/// weights with which it takes its value from the element's dofs.
#[derive(Clone, Debug)]
pub struct ElementValues {
    /// Local functions $`B`$ of the element.
    functions: usize,
    /// Rows per point (derivatives the element supplies).
    rows: usize,
    /// `basis[(q * rows + r) * functions + b]`.
    basis: Vec<f64>,
    /// Integration weight times Jacobian, per point.
    pub weights: Vec<f64>,
    /// Physical coordinates of each point.
    pub points: Vec<[f64; 2]>,
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
    /// Evaluates element `element` of type `E`, with node coordinates `coordinates`, at the
    /// points of `rule`. A Jacobian that is not positive (or NaN) at any point is an error.
    pub fn new<E: Element>(
        element: usize,
        coordinates: &[[f64; 2]],
        rule: &GaussRule,
    ) -> Result<Self, JacobianError> {
        let (functions, rows) = (E::FUNCTIONS, E::DERIVATIVES.len());
        let count = rule.points.len();
        let mut basis = vec![0.0; count * rows * functions];
        let mut weights = Vec::with_capacity(count);
        let mut points = Vec::with_capacity(count);
        for (q, (&reference, point_basis)) in rule
            .points
            .iter()
            .zip(basis.chunks_exact_mut(rows * functions))
            .enumerate()
        {
            let mapping = E::basis(coordinates, reference, point_basis);
            let determinant = mapping.jacobian;
            if determinant.is_nan() || determinant <= 0.0 {
                return Err(JacobianError {
                    element,
                    determinant,
                });
            }
            weights.push(rule.weights[q] * determinant);
            points.push(mapping.point);
        }
        Ok(ElementValues {
            functions,
            rows,
            basis,
            weights,
            points,
        })
    }

    /// Number of points.
    pub fn point_count(&self) -> usize {
        self.weights.len()
    }

    /// Row `row` of the basis at point `q`: one value per local function.
    pub fn row(&self, q: usize, row: usize) -> &[f64] {
        &self.basis[(q * self.rows + row) * self.functions..][..self.functions]
    }

    /// Every row at point `q`, each of the element's `B` functions, as fixed-size arrays (the
    /// assembler's inner loops run over `B` as a constant).
    ///
    /// # Panics
    /// If `B` is not the element's number of functions.
    #[inline(always)]
    pub fn point_basis<const B: usize>(&self, q: usize) -> &[[f64; B]] {
        assert_eq!(B, self.functions, "basis length of another element");
        let (rows, _) = self.basis[q * self.rows * B..][..self.rows * B].as_chunks::<B>();
        rows
    }
}
