//! Legendre–Hadamard (strong ellipticity) check of a model's energy density, for any model.
//!
//! The margin reported is the smallest $`LDL^T`$ pivot of $`A(\mathbf{n})`$ over sampled
//! directions, relative to its largest diagonal entry: positive iff $`A(\mathbf{n})`$ is positive
//! definite (cheap enough to run at every point of a path).
//!
//! With $`H_{(i,a)(j,b)} = \partial^2\psi/\partial(\partial_a f_i)\,\partial(\partial_b f_j)`$ the
//! block of the generated tangent that couples field gradients (summed over all terms), the
//! acoustic tensor in direction $`\mathbf{n}`$ is $`A_{ij}(\mathbf{n}) = H_{(i,a)(j,b)}\,n_a n_b`$.
//! The density is strongly elliptic at a point when $`A(\mathbf{n})`$ is positive definite for
//! every unit $`\mathbf{n}`$ (for one scalar field, the envelope, this is positivity of its
//! $`2\times 2`$ gradient block). When it fails, the discrete problem's solutions depend on
//! the mesh: an envelope model has stopped being valid there.

use crate::fem::element::{ElementValues, GaussRule, QUAD8_NODES};
use crate::model::{Derivative, EnergyModel};
use crate::problem::Problem;

/// Outcome of a Legendre–Hadamard check over the whole domain.
#[derive(Clone, Debug, PartialEq)]
pub struct EllipticityReport {
    /// Whether $`A(\mathbf{n})`$ is positive definite at every checked point and direction.
    pub elliptic: bool,
    /// Smallest $`LDL^T`$ pivot of $`A(\mathbf{n})`$ over points and directions, divided by the
    /// largest diagonal entry at the same point (negative = violated).
    pub worst_margin: f64,
    /// Where the worst margin occurs.
    pub location: [f64; 2],
    /// Direction $`\mathbf{n}`$ (angle from X, radians) of the worst margin.
    pub direction: f64,
    /// Field whose pivot is the smallest at the worst point.
    pub field: &'static str,
    /// Area fraction of the domain (quadrature weights) where the condition fails.
    pub violated_fraction: f64,
}

/// Most fields with gradients the check handles.
const MAX_GRADIENT_FIELDS: usize = 8;

/// Smallest LDLᵀ pivot of the leading `m × m` block (destroyed) and its index.
fn smallest_pivot(
    a: &mut [[f64; MAX_GRADIENT_FIELDS]; MAX_GRADIENT_FIELDS],
    m: usize,
) -> (f64, usize) {
    let mut smallest = (f64::INFINITY, 0);
    for k in 0..m {
        let d = a[k][k];
        if d < smallest.0 {
            smallest = (d, k);
        }
        if d <= 0.0 {
            // Not positive definite: the remaining pivots are meaningless.
            return smallest;
        }
        // Schur complement of the pivot (full symmetric update; m ≤ 8).
        let pivot_row = a[k];
        for row in a.iter_mut().take(m).skip(k + 1) {
            let l = row[k] / d;
            for (j, value) in row.iter_mut().enumerate().take(m).skip(k + 1) {
                *value -= l * pivot_row[j];
            }
        }
    }
    smallest
}

/// Number of directions sampled on the half circle.
const DIRECTIONS: usize = 36;
/// Relative tolerance below which a margin counts as a violation.
const MARGIN_TOLERANCE: f64 = 1e-10;

/// Checks strong ellipticity at the 3×3 Gauss points of every element for the state `free` at
/// load `load`. All terms are evaluated at the same points (whatever rule they integrate with).
pub fn legendre_hadamard<M: EnergyModel>(
    problem: &Problem<M>,
    free: &[f64],
    load: f64,
) -> EllipticityReport {
    let spec = M::SPEC;
    let nf = spec.fields.len();
    let assembler = &problem.assembler;
    let mesh = assembler.mesh();
    let global = assembler.dofs().expand(free, load);
    let model = assembler.model();
    let rule = GaussRule::square(3);
    let gradient_fields: Vec<usize> = (0..nf).filter(|&f| spec.needs_gradient(f)).collect();
    let m = gradient_fields.len();
    let mut report = EllipticityReport {
        elliptic: true,
        worst_margin: f64::INFINITY,
        location: [0.0, 0.0],
        direction: 0.0,
        field: spec.fields.first().copied().unwrap_or(""),
        violated_fraction: 0.0,
    };
    let mut total_area = 0.0;
    let mut violated_area = 0.0;
    if m == 0 {
        return report;
    }
    let slot = |field: usize| gradient_fields.iter().position(|&f| f == field);
    let mut hessians: Vec<Vec<f64>> = spec
        .terms
        .iter()
        .map(|t| vec![0.0; t.tangent_pattern.len()])
        .collect();
    for e in 0..mesh.elements.len() {
        let Ok(values) = ElementValues::new(e, &mesh.element_coordinates(e), &rule, true) else {
            continue;
        };
        for q in 0..values.weights.len() {
            total_area += values.weights[q];
            let mut point_violated = false;
            // H over (gradient field slot, axis) pairs: index 2 * slot + axis.
            let mut h = vec![0.0; 4 * m * m];
            for (t, term) in spec.terms.iter().enumerate() {
                let jet: Vec<f64> = term
                    .jet
                    .iter()
                    .map(|&i| {
                        let entry = spec.jet[i];
                        (0..QUAD8_NODES)
                            .map(|k| {
                                let node = mesh.elements[e][k];
                                let b = match entry.derivative {
                                    Derivative::Value => values.values[q][k],
                                    Derivative::X => values.gradients[q][k][0],
                                    Derivative::Y => values.gradients[q][k][1],
                                };
                                b * global[node * nf + entry.field]
                            })
                            .sum()
                    })
                    .collect();
                model.tangent(t, &jet, &mut hessians[t]);
                for (p, &(i, j)) in term.tangent_pattern.iter().enumerate() {
                    let (ei, ej) = (spec.jet[term.jet[i]], spec.jet[term.jet[j]]);
                    let axis = |d: Derivative| match d {
                        Derivative::X => Some(0),
                        Derivative::Y => Some(1),
                        Derivative::Value => None,
                    };
                    if let (Some(ai), Some(aj), Some(si), Some(sj)) = (
                        axis(ei.derivative),
                        axis(ej.derivative),
                        slot(ei.field),
                        slot(ej.field),
                    ) {
                        let (r, c) = (2 * si + ai, 2 * sj + aj);
                        h[r * 2 * m + c] += hessians[t][p];
                        if r != c {
                            h[c * 2 * m + r] += hessians[t][p];
                        }
                    }
                }
            }
            for k in 0..DIRECTIONS {
                let angle = std::f64::consts::PI * k as f64 / DIRECTIONS as f64;
                let n = [angle.cos(), angle.sin()];
                // A(n) on the stack, then its LDLᵀ pivots (positive definite ⇔ all pivots > 0).
                let mut acoustic = [[0.0; MAX_GRADIENT_FIELDS]; MAX_GRADIENT_FIELDS];
                let mut scale: f64 = 0.0;
                for i in 0..m {
                    for j in 0..m {
                        let mut sum = 0.0;
                        for a in 0..2 {
                            for b in 0..2 {
                                sum += h[(2 * i + a) * 2 * m + (2 * j + b)] * n[a] * n[b];
                            }
                        }
                        acoustic[i][j] = sum;
                    }
                    scale = scale.max(acoustic[i][i].abs());
                }
                let (pivot, at) = smallest_pivot(&mut acoustic, m);
                let margin = if scale > 0.0 { pivot / scale } else { 0.0 };
                point_violated |= margin <= -MARGIN_TOLERANCE;
                if margin < report.worst_margin {
                    report.worst_margin = margin;
                    report.location = values.points[q];
                    report.direction = angle;
                    report.field = spec.fields[gradient_fields[at]];
                }
            }
            if point_violated {
                violated_area += values.weights[q];
            }
        }
    }
    if total_area > 0.0 {
        report.violated_fraction = violated_area / total_area;
    }
    report.elliptic = report.worst_margin > -MARGIN_TOLERANCE;
    report
}
