//! Assembly of energy, residual and tangent from a model's generated kernels.
//!
//! The assembler knows nothing about the model beyond the kernel contract
//! ([`EnergyModel`](crate::model::EnergyModel)): it evaluates each term's jet at that term's
//! quadrature points, calls the term kernels, and scatters
//! $$`R_a = \sum_e \sum_q w_q \sum_i r_i(\mathbf{j}_q)\, B_{i a},\qquad
//! K_{ab} = \sum_e \sum_q w_q \sum_{ij} k_{ij}(\mathbf{j}_q)\, B_{i a} B_{j b},`$$
//! with $`B_{ia}`$ the shape function value or derivative that jet entry $`i`$ takes from dof
//! $`a`$. Residual and tangent are generic over [`Scalar`]: the same loop assembles `f64`
//! values, dual numbers (directional derivatives of the tangent) and truncated series (ANM).
//! The sparsity pattern and the element → value-slot tables are built once.

use super::dofs::DofMap;
use super::element::{ElementValues, GaussRule, JacobianError, QUAD8_NODES};
use super::mesh::Mesh;
use crate::linear::pattern::{SparseMatrix, SparsityPattern};
use crate::model::{Derivative, EnergyModel, JetEntry, QuadratureRule};
use crate::scalar::Scalar;
use rayon::prelude::*;
use std::sync::Arc;

/// How the element loop is split.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Parallelism {
    /// One thread, no per-thread buffers.
    Sequential,
    /// Elements split into this many contiguous chunks, run on the rayon pool, buffers summed.
    Chunks(usize),
}

impl Parallelism {
    /// One chunk per rayon thread (sequential when the pool has one thread).
    pub fn available() -> Self {
        let n = rayon::current_num_threads();
        if n <= 1 {
            Parallelism::Sequential
        } else {
            Parallelism::Chunks(n)
        }
    }
}

/// Shape data of one term at its quadrature points, per element.
#[derive(Debug)]
struct TermData {
    /// Index of the element-values set used (terms with the same rule share one).
    value_set: usize,
    /// (field, derivative) of each term-local jet entry.
    jet: Vec<JetEntry>,
}

/// Assembles a model on a mesh with a dof map.
#[derive(Debug)]
pub struct Assembler<M: EnergyModel> {
    model: M,
    mesh: Arc<Mesh>,
    dofs: Arc<DofMap>,
    value_sets: Vec<(QuadratureRule, Vec<ElementValues>)>,
    terms: Vec<TermData>,
    element_dofs: Vec<Vec<Option<usize>>>,
    pattern: Arc<SparsityPattern>,
    element_slots: Vec<Vec<Option<usize>>>,
    parallelism: Parallelism,
}

impl<M: EnergyModel> Assembler<M> {
    /// Prepares element values (only the rules and derivatives the model's terms use), element
    /// dof lists, the sparsity pattern and the scatter tables.
    pub fn new(model: M, mesh: Arc<Mesh>, dofs: Arc<DofMap>) -> Result<Self, JacobianError> {
        let spec = M::SPEC;
        let mut value_sets: Vec<(QuadratureRule, Vec<ElementValues>)> = Vec::new();
        let mut terms = Vec::new();
        for term in spec.terms {
            let needs_gradients = spec.terms.iter().any(|t| {
                t.quadrature == term.quadrature
                    && t.jet
                        .iter()
                        .any(|&i| spec.jet[i].derivative != Derivative::Value)
            });
            let value_set = match value_sets.iter().position(|(r, _)| *r == term.quadrature) {
                Some(k) => k,
                None => {
                    let rule = GaussRule::for_quadrature(term.quadrature);
                    let values = (0..mesh.elements.len())
                        .map(|e| {
                            ElementValues::new(
                                e,
                                &mesh.element_coordinates(e),
                                &rule,
                                needs_gradients,
                            )
                        })
                        .collect::<Result<Vec<_>, _>>()?;
                    value_sets.push((term.quadrature, values));
                    value_sets.len() - 1
                }
            };
            terms.push(TermData {
                value_set,
                jet: term.jet.iter().map(|&i| spec.jet[i]).collect(),
            });
        }
        let element_dofs: Vec<Vec<Option<usize>>> = mesh
            .elements
            .iter()
            .map(|nodes| dofs.element_dofs(nodes))
            .collect();
        let pattern = Arc::new(SparsityPattern::from_element_dofs(
            dofs.free_count,
            element_dofs.iter().map(|d| d.as_slice()),
        ));
        let element_slots = element_dofs
            .iter()
            .map(|d| pattern.element_slots(d))
            .collect();
        Ok(Assembler {
            model,
            mesh,
            dofs,
            value_sets,
            terms,
            element_dofs,
            pattern,
            element_slots,
            parallelism: Parallelism::available(),
        })
    }

    /// The model instance.
    pub fn model(&self) -> &M {
        &self.model
    }
    /// Replaces the model parameters (same model type, so pattern and element values stay).
    pub fn set_model(&mut self, model: M) {
        self.model = model;
    }
    /// The mesh.
    pub fn mesh(&self) -> &Arc<Mesh> {
        &self.mesh
    }
    /// The dof map.
    pub fn dofs(&self) -> &Arc<DofMap> {
        &self.dofs
    }
    /// The sparsity pattern of the tangent (free dofs).
    pub fn pattern(&self) -> &Arc<SparsityPattern> {
        &self.pattern
    }
    /// Sets how the element loop is split.
    pub fn set_parallelism(&mut self, parallelism: Parallelism) {
        self.parallelism = parallelism;
    }

    /// Number of quadrature-point kernel calls one assembly makes.
    pub fn kernel_calls(&self) -> usize {
        self.terms
            .iter()
            .map(|t| {
                self.value_sets[t.value_set]
                    .1
                    .iter()
                    .map(|v| v.weights.len())
                    .sum::<usize>()
            })
            .sum()
    }

    /// Runs `work(element, buffer)` over all elements, summing per-chunk buffers of length `len`.
    fn accumulate<S: Scalar>(&self, len: usize, work: impl Fn(usize, &mut [S]) + Sync) -> Vec<S> {
        let n = self.mesh.elements.len();
        let chunks = match self.parallelism {
            Parallelism::Sequential => 1,
            Parallelism::Chunks(c) => c.clamp(1, n.max(1)),
        };
        if chunks == 1 {
            let mut out = vec![S::zero(); len];
            for e in 0..n {
                work(e, &mut out);
            }
            return out;
        }
        let per = n.div_ceil(chunks);
        (0..chunks)
            .into_par_iter()
            .map(|c| {
                let mut out = vec![S::zero(); len];
                for e in (c * per)..((c + 1) * per).min(n) {
                    work(e, &mut out);
                }
                out
            })
            .reduce_with(|mut a, b| {
                for (x, y) in a.iter_mut().zip(b) {
                    *x = *x + y;
                }
                a
            })
            .unwrap_or_else(|| vec![S::zero(); len])
    }

    /// Gathers the element's nodal values: entry `k * field_count + f`.
    #[inline]
    fn gather<S: Scalar>(&self, e: usize, global: &[S]) -> [S; QUAD8_NODES * MAX_FIELDS] {
        let nf = self.dofs.field_count;
        let mut local = [S::zero(); QUAD8_NODES * MAX_FIELDS];
        for (k, &node) in self.mesh.elements[e].iter().enumerate() {
            for f in 0..nf {
                local[k * nf + f] = global[node * nf + f];
            }
        }
        local
    }

    /// Evaluates the term-local jet at quadrature point `q` of element `e`.
    #[inline]
    fn jet_at<S: Scalar>(
        &self,
        term: &TermData,
        values: &ElementValues,
        q: usize,
        local: &[S],
        jet: &mut [S],
    ) {
        let nf = self.dofs.field_count;
        for (i, entry) in term.jet.iter().enumerate() {
            let mut acc = S::zero();
            for k in 0..QUAD8_NODES {
                acc = acc
                    + local[k * nf + entry.field] * shape_weight(values, q, k, entry.derivative);
            }
            jet[i] = acc;
        }
    }

    /// Total energy $`\Pi = \sum_t \int \psi_t`$ of the global nodal values.
    pub fn energy<S: Scalar>(&self, global: &[S]) -> S {
        let total = self.accumulate(1, |e, out: &mut [S]| {
            let local = self.gather(e, global);
            let mut jet = [S::zero(); MAX_JET];
            for (t, term) in self.terms.iter().enumerate() {
                let values = &self.value_sets[term.value_set].1[e];
                let m = term.jet.len();
                for q in 0..values.weights.len() {
                    self.jet_at(term, values, q, &local, &mut jet[..m]);
                    out[0] = out[0] + self.model.energy(t, &jet[..m]) * values.weights[q];
                }
            }
        });
        total[0]
    }

    /// Internal force vector of element `e` (local dofs `k * field_count + f`).
    #[inline]
    fn element_internal_forces<S: Scalar>(
        &self,
        e: usize,
        global: &[S],
    ) -> [S; QUAD8_NODES * MAX_FIELDS] {
        let nf = self.dofs.field_count;
        let local = self.gather(e, global);
        let mut element = [S::zero(); QUAD8_NODES * MAX_FIELDS];
        let mut jet = [S::zero(); MAX_JET];
        let mut residual = [S::zero(); MAX_JET];
        for (t, term) in self.terms.iter().enumerate() {
            let values = &self.value_sets[term.value_set].1[e];
            let m = term.jet.len();
            for q in 0..values.weights.len() {
                self.jet_at(term, values, q, &local, &mut jet[..m]);
                self.model.residual(t, &jet[..m], &mut residual[..m]);
                let w = values.weights[q];
                for (i, entry) in term.jet.iter().enumerate() {
                    let r = residual[i];
                    for k in 0..QUAD8_NODES {
                        let b = shape_weight(values, q, k, entry.derivative);
                        if b != 0.0 {
                            let a = k * nf + entry.field;
                            element[a] = element[a] + r * (b * w);
                        }
                    }
                }
            }
        }
        element
    }

    /// Internal forces $`\partial\Pi/\partial U_a`$ over the free dofs, from global nodal values
    /// (prescribed entries included in `global`).
    pub fn internal_forces<S: Scalar>(&self, global: &[S]) -> Vec<S> {
        self.accumulate(self.dofs.free_count, |e, out: &mut [S]| {
            let element = self.element_internal_forces(e, global);
            for (a, dof) in self.element_dofs[e].iter().enumerate() {
                if let Some(i) = dof {
                    out[*i] = out[*i] + element[a];
                }
            }
        })
    }

    /// Internal forces and, in the same element loop, the force magnitudes
    /// $`\sum_e |f^e_a|`$ over the free dofs: the size of the element forces that meet at each
    /// dof, a per-dof scale for residuals (large where forces cancel at equilibrium, unlike the
    /// assembled internal force).
    pub fn internal_forces_and_magnitudes(&self, global: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = self.dofs.free_count;
        let mut both = self.accumulate(2 * n, |e, out: &mut [f64]| {
            let element = self.element_internal_forces(e, global);
            for (a, dof) in self.element_dofs[e].iter().enumerate() {
                if let Some(i) = dof {
                    out[*i] += element[a];
                    out[n + *i] += element[a].abs();
                }
            }
        });
        let magnitudes = both.split_off(n);
        (both, magnitudes)
    }

    /// Tangent values $`\partial^2\Pi/\partial U_a\partial U_b`$ on [`Self::pattern`], generic
    /// over the scalar (dual numbers give directional derivatives of the tangent).
    pub fn tangent_values<S: Scalar>(&self, global: &[S]) -> Vec<S> {
        let nf = self.dofs.field_count;
        let m_local = QUAD8_NODES * nf;
        self.accumulate(self.pattern.nnz(), |e, out: &mut [S]| {
            let local = self.gather(e, global);
            let mut element = vec![S::zero(); m_local * m_local];
            let mut jet = [S::zero(); MAX_JET];
            let spec = M::SPEC;
            for (t, term) in self.terms.iter().enumerate() {
                let values = &self.value_sets[term.value_set].1[e];
                let m = term.jet.len();
                let pattern = spec.terms[t].tangent_pattern;
                let mut hessian = vec![S::zero(); pattern.len()];
                for q in 0..values.weights.len() {
                    self.jet_at(term, values, q, &local, &mut jet[..m]);
                    self.model.tangent(t, &jet[..m], &mut hessian);
                    let w = values.weights[q];
                    for (p, &(i, j)) in pattern.iter().enumerate() {
                        let (ei, ej) = (term.jet[i], term.jet[j]);
                        let h = hessian[p];
                        for k in 0..QUAD8_NODES {
                            let bi = shape_weight(values, q, k, ei.derivative) * w;
                            if bi == 0.0 {
                                continue;
                            }
                            let row = k * nf + ei.field;
                            for l in 0..QUAD8_NODES {
                                let bj = shape_weight(values, q, l, ej.derivative);
                                if bj == 0.0 {
                                    continue;
                                }
                                let col = l * nf + ej.field;
                                let v = h * (bi * bj);
                                element[row * m_local + col] = element[row * m_local + col] + v;
                                if i != j {
                                    element[col * m_local + row] = element[col * m_local + row] + v;
                                }
                            }
                        }
                    }
                }
            }
            for (slot, v) in self.element_slots[e].iter().zip(element) {
                if let Some(s) = slot {
                    out[*s] = out[*s] + v;
                }
            }
        })
    }

    /// Assembles the `f64` tangent into `matrix` (which must be on [`Self::pattern`]).
    pub fn assemble_tangent_into(&self, global: &[f64], matrix: &mut SparseMatrix) {
        let values = self.tangent_values(global);
        matrix.values.copy_from_slice(&values);
    }

    /// Calls `visit(term, element, q, point, weight, jet)` at every quadrature point of every term
    /// (for diagnostics such as ellipticity checks; `f64` only).
    pub fn for_each_quadrature_point(
        &self,
        global: &[f64],
        mut visit: impl FnMut(usize, usize, usize, [f64; 2], f64, &[f64]),
    ) {
        let mut jet = [0.0; MAX_JET];
        for e in 0..self.mesh.elements.len() {
            let local = self.gather(e, global);
            for (t, term) in self.terms.iter().enumerate() {
                let values = &self.value_sets[term.value_set].1[e];
                let m = term.jet.len();
                for q in 0..values.weights.len() {
                    self.jet_at(term, values, q, &local, &mut jet[..m]);
                    visit(t, e, q, values.points[q], values.weights[q], &jet[..m]);
                }
            }
        }
    }
}

/// Most fields a model may have (element buffers are on the stack).
pub const MAX_FIELDS: usize = 8;
/// Longest term jet (3 entries per field).
pub const MAX_JET: usize = 3 * MAX_FIELDS;

#[inline(always)]
fn shape_weight(values: &ElementValues, q: usize, k: usize, derivative: Derivative) -> f64 {
    match derivative {
        Derivative::Value => values.values[q][k],
        Derivative::X => values.gradients[q][k][0],
        Derivative::Y => values.gradients[q][k][1],
    }
}
