//! Legendre–Hadamard (strong ellipticity) check of a model's energy density, for any model.
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
    /// Smallest eigenvalue of $`A(\mathbf{n})`$ over points and directions, divided by the
    /// largest eigenvalue magnitude at the same point (negative = violated).
    pub worst_margin: f64,
    /// Where the worst margin occurs.
    pub location: [f64; 2],
    /// Direction $`\mathbf{n}`$ (angle from X, radians) of the worst margin.
    pub direction: f64,
    /// Field with the largest component in the worst eigenvector.
    pub field: &'static str,
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
    };
    if m == 0 {
        return report;
    }
    let slot = |field: usize| gradient_fields.iter().position(|&f| f == field);
    let mut hessians: Vec<Vec<f64>> = spec.terms.iter().map(|t| vec![0.0; t.tangent_pattern.len()]).collect();
    for e in 0..mesh.elements.len() {
        let Ok(values) = ElementValues::new(e, &mesh.element_coordinates(e), &rule, true) else {
            continue;
        };
        for q in 0..values.weights.len() {
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
                    if let (Some(ai), Some(aj), Some(si), Some(sj)) =
                        (axis(ei.derivative), axis(ej.derivative), slot(ei.field), slot(ej.field))
                    {
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
                let acoustic = nalgebra::DMatrix::from_fn(m, m, |i, j| {
                    let mut s = 0.0;
                    for a in 0..2 {
                        for b in 0..2 {
                            s += h[(2 * i + a) * 2 * m + (2 * j + b)] * n[a] * n[b];
                        }
                    }
                    s
                });
                let eigen = nalgebra::SymmetricEigen::new(acoustic);
                let (imin, &min) = eigen
                    .eigenvalues
                    .iter()
                    .enumerate()
                    .min_by(|a, b| a.1.total_cmp(b.1))
                    .expect("at least one gradient field");
                let scale = eigen.eigenvalues.iter().fold(0.0f64, |s, v| s.max(v.abs()));
                let margin = if scale > 0.0 { min / scale } else { 0.0 };
                if margin < report.worst_margin {
                    let vector = eigen.eigenvectors.column(imin);
                    let dominant = (0..m)
                        .max_by(|&a, &b| vector[a].abs().total_cmp(&vector[b].abs()))
                        .expect("non-empty");
                    report.worst_margin = margin;
                    report.location = values.points[q];
                    report.direction = angle;
                    report.field = spec.fields[gradient_fields[dominant]];
                }
            }
        }
    }
    report.elliptic = report.worst_margin > -MARGIN_TOLERANCE;
    report
}
