//! Legendre–Hadamard (strong ellipticity) check of a model's energy density, for any model, and
//! the pointwise stability check of the fields that have no gradient stiffness.
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
//!
//! **Elements, lines and second derivatives.** The check runs on any element, at the points of
//! its full rule, with the jet from the element's basis. On a line mesh the only direction is
//! $`\mathbf n = \mathbf e_X`$ (sampling others would report the missing $`Y`$ stiffness as a
//! zero margin). When some field carries second derivatives (a beam's $`v''`$ on the cubic
//! Hermite line, a Kirchhoff plate's $`w_{,XX}, w_{,XY}, w_{,YY}`$) the condition is on the
//! symbol of each field's *highest* derivatives: with the plane wave's monomials
//! $`m_X = n_X`$, $`m_{XX} = n_X^2`$, $`m_{XY} = n_X n_Y`$, …,
//! $$`A_{ij}(\mathbf n) = \sum_{\alpha\in P_i}\sum_{\beta\in P_j}
//! \frac{\partial^2\psi}{\partial(\partial^\alpha f_i)\,\partial(\partial^\beta f_j)}\,
//! m_\alpha m_\beta,`$$
//! $`P_i`$ the derivatives of highest order of field $`i`$ in the jet (first-order fields keep
//! $`X, Y`$). Lower-order terms do not enter: a beam under compression,
//! $`\tfrac12 EI v''^2 - \tfrac12\lambda v'^2`$, stays elliptic ($`A = EI`$) — buckling is an
//! instability of the discrete problem, not a loss of ellipticity.
//!
//! **Fields without gradient stiffness.** A field $`f`$ whose second derivatives
//! $`\partial^2\psi/\partial(\partial_a f)\,\partial(\partial_b f)`$ vanish identically (no term's
//! tangent pattern holds such an entry; e.g. the envelope $`w`$ of the pure membrane model,
//! THEORY.md §5) has no row in $`A(\mathbf{n})`$, so the test above cannot see it. Its second
//! variation, for a perturbation $`\delta f`$ alone, is purely local:
//! $$`\delta^2\Pi[\delta f] = \int_\Omega k_f\,\delta f^2\,d\Omega,\qquad
//! k_f = \sum_t \frac{\partial^2\psi_t}{\partial f^2},`$$
//! with no length scale. Where $`k_f(\mathbf{X}_0) < 0`$, every perturbation concentrated near
//! $`\mathbf{X}_0`$ — of any support and any oscillation, down to the mesh size — lowers the
//! energy: the linearised $`f`$-equation $`k_f\,\delta f = \dots`$ is a pointwise law with a
//! negative coefficient, ill-posed in the same sense as a loss of strong ellipticity (it is the
//! zeroth-order analogue of the Legendre–Hadamard condition: the oscillating perturbations
//! $`\delta f = \varphi(\mathbf X)\cos(\mathbf n\cdot\mathbf X/\epsilon)`$, $`\epsilon\to 0`$, that
//! probe $`A(\mathbf n)`$ for gradient fields probe $`k_f`$ here). For the pure membrane,
//! $`k_w = 2Q^2(N_e + DQ^2)`$ on a flat state: negative beyond its threshold $`N_e < -DQ^2`$.
//! The margin of such a field is $`k_f / \sum_t |\partial^2\psi_t/\partial f^2|`$ (negative =
//! ill-posed); its area counts in [`EllipticityReport::violated_fraction`].
//! Only the diagonal $`k_f`$ is checked: couplings of $`f`$ to other fields' gradients (which
//! also act at the oscillation scale, and vanish on a flat state) are not.

use crate::fem::element::{Element, ElementValues, with_element};
use crate::model::{Derivative, EnergyModel, ModelSpec, QuadratureRule};
use crate::problem::Problem;
use rayon::prelude::*;

/// Outcome of a Legendre–Hadamard check over the whole domain.
#[derive(Clone, Debug, PartialEq)]
pub struct EllipticityReport {
    /// Whether $`A(\mathbf{n})`$ is positive definite at every checked point and direction (the
    /// Legendre–Hadamard condition over the gradient block only; see [`Self::well_posed`]).
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
    /// Area fraction of the domain (quadrature weights) where the condition fails: the
    /// Legendre–Hadamard condition, or the pointwise condition $`k_f \ge 0`$ of a field without
    /// gradient stiffness (see the module documentation), or both.
    pub violated_fraction: f64,
    /// One entry per field without gradient stiffness (in field order; empty for models whose
    /// every field has one).
    pub gradient_free: Vec<PointwiseReport>,
}

impl EllipticityReport {
    /// Strongly elliptic and every field without gradient stiffness pointwise stable.
    pub fn well_posed(&self) -> bool {
        self.elliptic && self.gradient_free.iter().all(|f| f.stable)
    }
}

/// Pointwise check of one field without gradient stiffness: the sign of
/// $`k_f = \sum_t \partial^2\psi_t/\partial f^2`$ (module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct PointwiseReport {
    /// The field.
    pub field: &'static str,
    /// Whether $`k_f \ge 0`$ (to the relative tolerance) at every checked point.
    pub stable: bool,
    /// Smallest $`k_f / \sum_t |\partial^2\psi_t/\partial f^2|`$ over the points (negative =
    /// ill-posed; $`+\infty`$ when no point was checked).
    pub worst_margin: f64,
    /// Where the worst margin occurs.
    pub location: [f64; 2],
    /// Area fraction of the domain where $`k_f < 0`$.
    pub violated_fraction: f64,
}

/// Smallest $`LDL^T`$ pivot of the symmetric `m × m` matrix `a` (row-major, destroyed) and its
/// index; it stops at the first pivot that is not positive (the rest would mean nothing).
#[inline(always)]
fn smallest_pivot(a: &mut [f64], m: usize) -> (f64, usize) {
    let mut smallest = (f64::INFINITY, 0);
    for k in 0..m {
        let d = a[k * m + k];
        if d < smallest.0 {
            smallest = (d, k);
        }
        if d <= 0.0 {
            // Not positive definite: the remaining pivots are meaningless.
            return smallest;
        }
        // Schur complement of the pivot (full symmetric update; m is small).
        for i in k + 1..m {
            let l = a[i * m + k] / d;
            for j in k + 1..m {
                a[i * m + j] -= l * a[k * m + j];
            }
        }
    }
    smallest
}

/// Number of directions sampled on the half circle.
const DIRECTIONS: usize = 36;
/// Relative tolerance below which a margin counts as a violation.
const MARGIN_TOLERANCE: f64 = 1e-10;

/// Fields without gradient stiffness: no term's tangent pattern couples two derivatives
/// ($`X`$ or $`Y`$) of the field, so $`\partial^2\psi/\partial(\partial_a f)\partial(\partial_b f)
/// \equiv 0`$. Only fields with a value–value entry somewhere (something to check) are listed.
pub fn gradient_free_fields(spec: &ModelSpec) -> Vec<usize> {
    let entries = |wanted: &dyn Fn(usize, usize) -> bool| {
        spec.terms.iter().any(|term| {
            term.tangent_pattern
                .iter()
                .any(|&(i, j)| wanted(term.jet[i], term.jet[j]))
        })
    };
    (0..spec.fields.len())
        .filter(|&f| {
            let gradient =
                |k: usize| spec.jet[k].field == f && spec.jet[k].derivative != Derivative::Value;
            let value =
                |k: usize| spec.jet[k].field == f && spec.jet[k].derivative == Derivative::Value;
            !entries(&|i, j| gradient(i) && gradient(j)) && entries(&|i, j| value(i) && value(j))
        })
        .collect()
}

/// The principal part of a density: the fields with derivatives (*slots*, in field order), and
/// the rows of the principal block $`H`$ — each slot's derivatives of the highest order the
/// field has in the jet.
///
/// For a first-order density (every field's highest derivative is first order) the rows are
/// $`(X, Y)`$ per slot, row `2 * slot + axis`; the acoustic tensor is formed from the three
/// blocks of [`worst_direction`]. When some field has second derivatives the rows of that
/// field are its second derivatives present in the jet (those of a first-order field stay
/// $`X, Y`$), and $`A(\mathbf n)`$ is formed by [`worst_direction_of_principal`].
struct PrincipalPart {
    /// The fields with derivatives.
    fields: Vec<usize>,
    /// Whether some field's highest derivative is of second order.
    second_order: bool,
    /// `(slot, derivative)` of each row of $`H`$.
    rows: Vec<(usize, Derivative)>,
}

impl PrincipalPart {
    fn of(spec: &ModelSpec) -> Self {
        let fields: Vec<usize> = (0..spec.fields.len())
            .filter(|&f| spec.needs_gradient(f))
            .collect();
        let order = |f: usize| {
            let orders = spec.jet.iter().filter(|e| e.field == f);
            orders.map(|e| e.derivative.order()).max().unwrap_or(0)
        };
        let second_order = fields.iter().any(|&f| order(f) >= 2);
        let mut rows = Vec::new();
        for (slot, &f) in fields.iter().enumerate() {
            if second_order && order(f) >= 2 {
                for d in [Derivative::XX, Derivative::XY, Derivative::YY] {
                    if spec.jet.iter().any(|e| e.field == f && e.derivative == d) {
                        rows.push((slot, d));
                    }
                }
            } else {
                rows.extend([(slot, Derivative::X), (slot, Derivative::Y)]);
            }
        }
        PrincipalPart {
            fields,
            second_order,
            rows,
        }
    }

    /// The row of $`H`$ holding jet entry `(field, derivative)`, if it is principal.
    fn row(&self, field: usize, derivative: Derivative) -> Option<usize> {
        let slot = self.fields.iter().position(|&f| f == field)?;
        self.rows.iter().position(|&row| row == (slot, derivative))
    }
}

/// Second derivatives at one quadrature point, summed over terms: the principal block
/// $`H`$ (rows of [`PrincipalPart`]) and, per gradient-free field, the value stiffness
/// $`k_f`$ with the sum of the terms' magnitudes.
struct PointHessian {
    principal_block: Vec<f64>,
    value_stiffness: Vec<(f64, f64)>,
}

/// The checks at one quadrature point, before they are folded into the report.
struct PointCheck {
    weight: f64,
    location: [f64; 2],
    /// Worst direction of the principal block: margin, angle and slot.
    gradient: Option<(f64, f64, usize)>,
    value_stiffness: Vec<(f64, f64)>,
}

/// Where each term-local jet entry of one term goes, found once per check: its basis row, its
/// principal row (if principal) and its gradient-free slot (if a gradient-free field's value).
struct TermTable {
    basis_rows: Vec<(usize, usize)>,
    principal_rows: Vec<Option<usize>>,
    value_slots: Vec<Option<usize>>,
}

impl TermTable {
    fn all(
        spec: &ModelSpec,
        derivatives: &[Derivative],
        principal: &PrincipalPart,
        gradient_free: &[usize],
    ) -> Vec<TermTable> {
        spec.terms
            .iter()
            .map(|term| {
                let entries = term.jet.iter().map(|&i| spec.jet[i]);
                TermTable {
                    basis_rows: entries
                        .clone()
                        .map(|e| {
                            let row = derivatives.iter().position(|&d| d == e.derivative);
                            (e.field, row.expect("Problem::new checked the derivatives"))
                        })
                        .collect(),
                    principal_rows: entries
                        .clone()
                        .map(|e| principal.row(e.field, e.derivative))
                        .collect(),
                    value_slots: entries
                        .map(|e| {
                            let value = e.derivative == Derivative::Value;
                            let slot = gradient_free.iter().position(|&f| f == e.field);
                            slot.filter(|_| value)
                        })
                        .collect(),
                }
            })
            .collect()
    }
}

/// Evaluates every term's tangent at quadrature point `q` of `values` and gathers
/// [`PointHessian`]; `local[b * nf + f]` is the dof of local function `b` of field `f`.
fn point_hessian<M: EnergyModel>(
    model: &M,
    local: &[f64],
    values: &ElementValues,
    q: usize,
    (size, gradient_free): (usize, usize),
    tables: &[TermTable],
    hessians: &mut [Vec<f64>],
) -> PointHessian {
    let spec = M::SPEC;
    let nf = spec.fields.len();
    let mut point = PointHessian {
        principal_block: vec![0.0; size * size],
        value_stiffness: vec![(0.0, 0.0); gradient_free],
    };
    for (t, (term, table)) in spec.terms.iter().zip(tables).enumerate() {
        let jet: Vec<f64> = table
            .basis_rows
            .iter()
            .map(|&(field, row)| {
                let basis = values.row(q, row);
                (0..basis.len())
                    .map(|k| basis[k] * local[k * nf + field])
                    .sum()
            })
            .collect();
        model.tangent(t, &jet, &mut hessians[t]);
        for (p, &(i, j)) in term.tangent_pattern.iter().enumerate() {
            let value = hessians[t][p];
            if let (Some(r), Some(c)) = (table.principal_rows[i], table.principal_rows[j]) {
                point.principal_block[r * size + c] += value;
                if r != c {
                    point.principal_block[c * size + r] += value;
                }
            }
            if i == j
                && let Some(s) = table.value_slots[i]
            {
                point.value_stiffness[s].0 += value;
                point.value_stiffness[s].1 += value.abs();
            }
        }
    }
    point
}

/// $`(\cos^2\theta, \cos\theta\sin\theta, \sin^2\theta)`$ and $`\theta`$ of the sampled
/// directions: $`\theta_k = k\pi/`$[`DIRECTIONS`] on a plane mesh, $`\theta = 0`$ alone on a
/// line (the only direction there is).
fn direction_table(dimension: usize) -> Vec<([f64; 3], f64)> {
    let count = if dimension == 1 { 1 } else { DIRECTIONS };
    (0..count)
        .map(|k| {
            let angle = std::f64::consts::PI * k as f64 / DIRECTIONS as f64;
            let (s, c) = angle.sin_cos();
            ([c * c, c * s, s * s], angle)
        })
        .collect()
}

/// Smallest relative pivot of $`A(\mathbf n)`$ over the sampled directions at one point:
/// `(margin, direction angle, slot of the smallest pivot)`. With
/// $`\mathbf n = (\cos\theta, \sin\theta)`$,
/// $`A_{ij}(\mathbf n) = \cos^2\theta\, H^{xx}_{ij} + \cos\theta\sin\theta\,(H^{xy}_{ij} + H^{yx}_{ij})
/// + \sin^2\theta\, H^{yy}_{ij}`$: the three $`m\times m`$ blocks are formed once per point.
///
/// It runs at the nine Gauss points of every element at every step end, so the usual sizes
/// (one to six fields with gradients) get their own copy with `m` a constant and the arrays on
/// the stack, which the compiler unrolls; any larger `m` takes the same code on the heap.
fn worst_direction(h: &[f64], m: usize, directions: &[([f64; 3], f64)]) -> (f64, f64, usize) {
    macro_rules! on_stack {
        ($m:literal) => {
            worst_direction_in(
                h,
                $m,
                directions,
                &mut [[0.0; 3]; $m * $m],
                &mut [0.0; $m * $m],
            )
        };
    }
    match m {
        1 => on_stack!(1),
        2 => on_stack!(2),
        3 => on_stack!(3),
        4 => on_stack!(4),
        5 => on_stack!(5),
        6 => on_stack!(6),
        _ => worst_direction_in(
            h,
            m,
            directions,
            &mut vec![[0.0; 3]; m * m],
            &mut vec![0.0; m * m],
        ),
    }
}

/// [`worst_direction`] with its work space: `blocks` and `acoustic` hold `m × m` entries.
#[inline(always)]
fn worst_direction_in(
    h: &[f64],
    m: usize,
    directions: &[([f64; 3], f64)],
    blocks: &mut [[f64; 3]],
    acoustic: &mut [f64],
) -> (f64, f64, usize) {
    // (H^xx, H^xy + H^yx, H^yy) of each pair of gradient fields.
    let at = |i: usize, a: usize, j: usize, b: usize| h[(2 * i + a) * 2 * m + (2 * j + b)];
    for i in 0..m {
        for j in 0..m {
            blocks[i * m + j] = [
                at(i, 0, j, 0),
                at(i, 0, j, 1) + at(i, 1, j, 0),
                at(i, 1, j, 1),
            ];
        }
    }
    let mut worst = (f64::INFINITY, 0.0, 0);
    for &(weights, angle) in directions {
        // A(n), then its LDLᵀ pivots (positive definite ⇔ all pivots > 0).
        for (value, block) in acoustic.iter_mut().zip(blocks.iter()) {
            *value = weights[0] * block[0] + weights[1] * block[1] + weights[2] * block[2];
        }
        let scale = (0..m).fold(0.0_f64, |scale, i| scale.max(acoustic[i * m + i].abs()));
        let (pivot, at) = smallest_pivot(acoustic, m);
        let margin = if scale > 0.0 { pivot / scale } else { 0.0 };
        if margin < worst.0 {
            worst = (margin, angle, at);
        }
    }
    worst
}

/// Smallest relative pivot of $`A(\mathbf n)`$ over the sampled directions for a principal part
/// with second derivatives: with the plane wave's derivative monomials
/// $`m_X = c,\ m_Y = s,\ m_{XX} = c^2,\ m_{XY} = cs,\ m_{YY} = s^2`$
/// ($`\mathbf n = (c, s)`$),
/// $$`A_{ij}(\mathbf n) = \sum_{\alpha \in P_i}\sum_{\beta \in P_j} H_{(i\alpha)(j\beta)}\,
/// m_\alpha m_\beta,`$$
/// $`P_i`$ the principal derivatives of slot $`i`$ — the symbol of the highest derivatives,
/// whose positivity is the Legendre–Hadamard condition of a density of mixed order.
fn worst_direction_of_principal(
    h: &[f64],
    principal: &PrincipalPart,
    directions: &[([f64; 3], f64)],
) -> (f64, f64, usize) {
    let m = principal.fields.len();
    let size = principal.rows.len();
    let mut acoustic = vec![0.0; m * m];
    let mut worst = (f64::INFINITY, 0.0, 0);
    for &(weights, angle) in directions {
        let (c, s) = (angle.cos(), angle.sin());
        let monomial = |d: Derivative| match d {
            Derivative::X => c,
            Derivative::Y => s,
            Derivative::XX => weights[0],
            Derivative::XY => weights[1],
            Derivative::YY => weights[2],
            Derivative::Value => 0.0,
        };
        acoustic.iter_mut().for_each(|a| *a = 0.0);
        for (r, &(i, alpha)) in principal.rows.iter().enumerate() {
            for (col, &(j, beta)) in principal.rows.iter().enumerate() {
                acoustic[i * m + j] += h[r * size + col] * monomial(alpha) * monomial(beta);
            }
        }
        let scale = (0..m).fold(0.0_f64, |scale, i| scale.max(acoustic[i * m + i].abs()));
        let (pivot, at) = smallest_pivot(&mut acoustic, m);
        let margin = if scale > 0.0 { pivot / scale } else { 0.0 };
        if margin < worst.0 {
            worst = (margin, angle, at);
        }
    }
    worst
}

/// Checks strong ellipticity at the points of every element's full rule for the state `free`
/// at load `load`, and the pointwise stability $`k_f \ge 0`$ of every field without gradient
/// stiffness ([`gradient_free_fields`]) at the same points. All terms are evaluated at the same
/// points (whatever rule they integrate with).
///
/// On any element: the basis rows give the jet, and on a line mesh the only direction is
/// $`\mathbf n = \mathbf e_X`$. For a density with second derivatives (a beam's $`v''^2`$,
/// a Kirchhoff plate) the condition is on the symbol of the highest derivatives
/// (module documentation): a beam's $`-\tfrac12\lambda v'^2`$ is of lower order and
/// is no loss of ellipticity, while $`EI < 0`$ would be.
pub fn legendre_hadamard<M: EnergyModel>(
    problem: &Problem<M>,
    free: &[f64],
    load: f64,
) -> EllipticityReport {
    let spec = M::SPEC;
    let principal = PrincipalPart::of(spec);
    let gradient_free = gradient_free_fields(spec);
    let mut report = unviolated_report(spec, &gradient_free);
    if principal.fields.is_empty() && gradient_free.is_empty() {
        return report;
    }
    let checks = point_checks(problem, free, load, &principal, &gradient_free);
    fold_checks(&mut report, &checks, spec, &principal.fields);
    report
}

/// The report of a state without violation (margins $`+\infty`$), for the fields
/// `gradient_free`.
fn unviolated_report(spec: &ModelSpec, gradient_free: &[usize]) -> EllipticityReport {
    EllipticityReport {
        elliptic: true,
        worst_margin: f64::INFINITY,
        location: [0.0, 0.0],
        direction: 0.0,
        field: spec.fields.first().copied().unwrap_or(""),
        violated_fraction: 0.0,
        gradient_free: gradient_free
            .iter()
            .map(|&f| PointwiseReport {
                field: spec.fields[f],
                stable: true,
                worst_margin: f64::INFINITY,
                location: [0.0, 0.0],
                violated_fraction: 0.0,
            })
            .collect(),
    }
}

/// The checks of every point of the element's full rule, element by element (elements whose
/// geometry fails give none). They run in parallel over elements and come back in element
/// order, so the report does not depend on the thread count.
fn point_checks<M: EnergyModel>(
    problem: &Problem<M>,
    free: &[f64],
    load: f64,
    principal: &PrincipalPart,
    gradient_free: &[usize],
) -> Vec<Vec<PointCheck>> {
    let mesh = problem.assembler.mesh();
    with_element!(mesh.kind, E => {
        point_checks_on::<M, E>(problem, free, load, principal, gradient_free)
    })
}

/// [`point_checks`] on a mesh of elements `E`.
fn point_checks_on<M: EnergyModel, E: Element>(
    problem: &Problem<M>,
    free: &[f64],
    load: f64,
    principal: &PrincipalPart,
    gradient_free: &[usize],
) -> Vec<Vec<PointCheck>> {
    let spec = M::SPEC;
    let nf = spec.fields.len();
    let m = principal.fields.len();
    let assembler = &problem.assembler;
    let mesh = assembler.mesh();
    let global = assembler.dofs().expand(free, load);
    let rule = E::quadrature(QuadratureRule::Full);
    let directions = direction_table(E::DIMENSION);
    let hessians: Vec<Vec<f64>> = spec
        .terms
        .iter()
        .map(|t| vec![0.0; t.tangent_pattern.len()])
        .collect();
    let tables = TermTable::all(spec, E::DERIVATIVES, principal, gradient_free);
    let sizes = (principal.rows.len(), gradient_free.len());
    (0..mesh.element_count())
        .into_par_iter()
        .map_with(hessians, |hessians, e| {
            let Ok(values) = ElementValues::new::<E>(e, &mesh.element_coordinates(e), &rule) else {
                return Vec::new();
            };
            // local[b * nf + f]: local function b (node b / C, component b % C) of field f.
            let local: Vec<f64> = (0..E::FUNCTIONS)
                .flat_map(|b| {
                    let node = mesh.element_nodes(e)[b / E::COMPONENTS];
                    let start = node * nf * E::COMPONENTS + b % E::COMPONENTS;
                    (0..nf).map(move |f| start + f * E::COMPONENTS)
                })
                .map(|g| global[g])
                .collect();
            (0..values.point_count())
                .map(|q| {
                    let model = assembler.model();
                    let point = point_hessian(model, &local, &values, q, sizes, &tables, hessians);
                    let gradient = (m > 0).then(|| {
                        if principal.second_order {
                            worst_direction_of_principal(
                                &point.principal_block,
                                principal,
                                &directions,
                            )
                        } else {
                            worst_direction(&point.principal_block, m, &directions)
                        }
                    });
                    PointCheck {
                        weight: values.weights[q],
                        location: values.points[q],
                        gradient,
                        value_stiffness: point.value_stiffness,
                    }
                })
                .collect()
        })
        .collect()
}

/// Folds the point checks into `report` in element order: the worst margins with their
/// locations, and the violated fractions of the area.
fn fold_checks(
    report: &mut EllipticityReport,
    checks: &[Vec<PointCheck>],
    spec: &ModelSpec,
    gradient_fields: &[usize],
) {
    let mut total_area = 0.0;
    let mut violated_area = 0.0;
    let mut field_violated_area = vec![0.0; report.gradient_free.len()];
    for check in checks.iter().flatten() {
        let weight = check.weight;
        total_area += weight;
        let mut point_violated = false;
        if let Some((margin, angle, at)) = check.gradient {
            point_violated |= margin <= -MARGIN_TOLERANCE;
            if margin < report.worst_margin {
                report.worst_margin = margin;
                report.location = check.location;
                report.direction = angle;
                report.field = spec.fields[gradient_fields[at]];
            }
        }
        for (s, &(stiffness, magnitude)) in check.value_stiffness.iter().enumerate() {
            let margin = if magnitude > 0.0 {
                stiffness / magnitude
            } else {
                0.0
            };
            let field = &mut report.gradient_free[s];
            if margin < field.worst_margin {
                field.worst_margin = margin;
                field.location = check.location;
            }
            if margin <= -MARGIN_TOLERANCE {
                field_violated_area[s] += weight;
                point_violated = true;
            }
        }
        if point_violated {
            violated_area += weight;
        }
    }
    if total_area > 0.0 {
        report.violated_fraction = violated_area / total_area;
        for (field, area) in report.gradient_free.iter_mut().zip(&field_violated_area) {
            field.violated_fraction = area / total_area;
        }
    }
    report.elliptic = report.worst_margin > -MARGIN_TOLERANCE;
    for field in report.gradient_free.iter_mut() {
        field.stable = field.worst_margin > -MARGIN_TOLERANCE;
    }
}

#[cfg(test)]
mod tests {
    //! A hand-written two-field density with a closed-form answer:
    //! $`\psi = \tfrac12|\nabla g|^2 + \tfrac12 k f^2 - \tfrac12 s f^2`$ (three terms), so that
    //! $`A(\mathbf n) = 1`$ for $`g`$ (margin 1 everywhere) and $`f`$ has no gradient stiffness,
    //! $`k_f = k - s`$, margin $`(k - s)/(k + s)`$.

    use super::*;
    use crate::fem::Mesh;
    use crate::model::{FieldRole, JetEntry, QuadratureRule, TermSpec};
    use crate::scalar::Scalar;
    use std::sync::Arc;

    const fn term(name: &'static str, jet: &'static [usize]) -> TermSpec {
        TermSpec {
            name,
            quadrature: QuadratureRule::Full,
            jet,
            tangent_pattern: if jet.len() == 2 {
                &[(0, 0), (1, 1)]
            } else {
                &[(0, 0)]
            },
            taylor_slots: jet.len(),
            linear_residual: false,
        }
    }

    static TERMS: [TermSpec; 3] = [
        term("gradient", &[0, 1]),
        term("spring", &[2]),
        term("softening", &[2]),
    ];

    static SPEC: ModelSpec = ModelSpec {
        name: "test-gradient-free",
        description: "½|∇g|² + ½ k f² − ½ s f²",
        fields: &["g", "f"],
        field_roles: &[FieldRole::Other, FieldRole::Other],
        parameters: &["k", "s"],
        varying_parameters: &[],
        jet: &[
            JetEntry {
                field: 0,
                derivative: Derivative::X,
            },
            JetEntry {
                field: 0,
                derivative: Derivative::Y,
            },
            JetEntry {
                field: 1,
                derivative: Derivative::Value,
            },
        ],
        terms: &TERMS,
        simplification_report: "hand-written",
        derivation: None,
    };

    #[derive(Clone, Debug)]
    struct GradientFree {
        k: f64,
        s: f64,
    }

    impl EnergyModel for GradientFree {
        const SPEC: &'static ModelSpec = &SPEC;
        fn from_parameters(values: &[f64]) -> Self {
            GradientFree {
                k: values[0],
                s: values[1],
            }
        }
        fn parameter_values(&self) -> Vec<f64> {
            vec![self.k, self.s]
        }
        fn energy<S: Scalar>(&self, term: usize, jet: &[S]) -> S {
            match term {
                0 => (jet[0] * jet[0] + jet[1] * jet[1]) * 0.5,
                1 => jet[0] * jet[0] * (0.5 * self.k),
                _ => jet[0] * jet[0] * (-0.5 * self.s),
            }
        }
        fn residual<S: Scalar>(&self, term: usize, jet: &[S], out: &mut [S]) {
            match term {
                0 => out.copy_from_slice(&jet[..2]),
                1 => out[0] = jet[0] * self.k,
                _ => out[0] = jet[0] * (-self.s),
            }
        }
        fn tangent<S: Scalar>(&self, term: usize, _jet: &[S], out: &mut [S]) {
            match term {
                0 => out.iter_mut().for_each(|o| *o = S::from_f64(1.0)),
                1 => out[0] = S::from_f64(self.k),
                _ => out[0] = S::from_f64(-self.s),
            }
        }
    }

    fn report(k: f64, s: f64) -> EllipticityReport {
        let mesh = Arc::new(Mesh::rectangle(2.0, 1.0, 3, 2, 1.0).unwrap());
        let problem = Problem::new(GradientFree { k, s }, mesh, &[], &Default::default()).unwrap();
        legendre_hadamard(&problem, &vec![0.0; problem.free_count()], 0.0)
    }

    #[test]
    fn gradient_free_field_is_detected_from_the_tangent_pattern() {
        assert_eq!(gradient_free_fields(&SPEC), vec![1]);
    }

    #[test]
    fn positive_value_stiffness_is_well_posed_and_leaves_the_gradient_check_alone() {
        let r = report(3.0, 1.0);
        assert!(r.elliptic && r.well_posed());
        assert_eq!((r.worst_margin, r.field), (1.0, "g"));
        assert_eq!(r.violated_fraction, 0.0);
        assert_eq!(r.gradient_free.len(), 1);
        let f = &r.gradient_free[0];
        assert_eq!(f.field, "f");
        assert!(f.stable && f.violated_fraction == 0.0);
        assert!((f.worst_margin - 0.5).abs() < 1e-15, "{}", f.worst_margin);
    }

    #[test]
    fn negative_value_stiffness_is_ill_posed_over_the_whole_area() {
        let r = report(1.0, 3.0);
        // The gradient block is untouched: still strongly elliptic in the old sense.
        assert!(r.elliptic);
        assert_eq!(r.worst_margin, 1.0);
        assert!(!r.well_posed());
        assert!((r.violated_fraction - 1.0).abs() < 1e-12);
        let f = &r.gradient_free[0];
        assert!(!f.stable);
        assert!((f.violated_fraction - 1.0).abs() < 1e-12);
        assert!((f.worst_margin + 0.5).abs() < 1e-15, "{}", f.worst_margin);
    }

    /// The gradient block $`H`$ (`2m × 2m`, index `2 * field + axis`) of `m` uncoupled fields
    /// with $`\psi = \tfrac12 c_i\,(\partial_X f_i)^2 + \tfrac12 s_i\,(\partial_Y f_i)^2`$:
    /// $`A(\mathbf n) = \mathrm{diag}(c_i\cos^2\theta + s_i\sin^2\theta)`$.
    fn uncoupled_block(c: &[f64], s: &[f64]) -> Vec<f64> {
        let m = c.len();
        let mut h = vec![0.0; 4 * m * m];
        for i in 0..m {
            h[(2 * i) * 2 * m + 2 * i] = c[i];
            h[(2 * i + 1) * 2 * m + 2 * i + 1] = s[i];
        }
        h
    }

    #[test]
    fn worst_direction_of_uncoupled_fields_is_the_closed_form_on_stack_and_heap() {
        // Fields 0..m-1 isotropic with stiffness 1 + i; the last has c = 1 along X and s = -0.5
        // along Y: A_last(θ) = cos²θ - sin²θ/2, smallest at θ = π/2 (sampled exactly). For
        // m ≥ 2 the scale max_j |A_jj| is m - 1 in every direction (1 for m = 2), so the margin
        // is -0.5 / max(m - 1, 1) at π/2. For m = 1 the margin is the sign, -1, first reached at
        // θ = 55° (the first sampled θ with tan²θ > 2).
        let directions = direction_table(2);
        for m in 1..=8 {
            let mut c: Vec<f64> = (0..m).map(|i| 1.0 + i as f64).collect();
            let mut s = c.clone();
            (c[m - 1], s[m - 1]) = (1.0, -0.5);
            let h = uncoupled_block(&c, &s);
            let (margin, angle, slot) = worst_direction(&h, m, &directions);
            let (expected_margin, expected_angle) = if m == 1 {
                (-1.0, 55f64.to_radians())
            } else {
                (-0.5 / (m as f64 - 1.0), std::f64::consts::FRAC_PI_2)
            };
            assert!(
                (margin - expected_margin).abs() < 1e-15,
                "m = {m}: margin {margin}"
            );
            assert!(
                (angle - expected_angle).abs() < 1e-12,
                "m = {m}: angle {angle}"
            );
            assert_eq!(slot, m - 1, "m = {m}");
            // The same on the heap (the path of m > 6), bit for bit.
            let heap = worst_direction_in(
                &h,
                m,
                &directions,
                &mut vec![[0.0; 3]; m * m],
                &mut vec![0.0; m * m],
            );
            assert_eq!(heap, (margin, angle, slot), "m = {m}");
        }
    }
}
