//! The element-level work of the assembler, monomorphised per element: gather an element's
//! dofs, evaluate a term's jet at a point, integrate element forces and tangents, and add them
//! to the free dofs.
//!
//! Every function is generic over the element `E` and its number of shape functions per field
//! `B = E::FUNCTIONS` (a const parameter, because array lengths cannot be an associated
//! constant of a type parameter on stable Rust): loop bounds are constants and element arrays
//! live on the stack. Local function $`b`$ of a field belongs to node `b / E::COMPONENTS`,
//! component `b % E::COMPONENTS`; element vectors are stored by field (`[f][b]`).

use super::{Assembler, TermData};
use crate::fem::element::{Element, ElementValues};
use crate::model::{EnergyModel, MAX_FIELDS, MAX_JET};
use crate::scalar::Scalar;

/// An element's dofs (or forces) by field: `[f][b]` is local function `b` of field `f`.
pub(super) type ElementLocal<S, const B: usize> = [[S; B]; MAX_FIELDS];

impl<M: EnergyModel> Assembler<M> {
    /// Gathers the element's dofs by field: `local[f][b]`, so that a jet entry is one
    /// `B`-term dot product of contiguous values.
    #[inline(always)]
    pub(super) fn gather<E: Element, const B: usize, S: Scalar>(
        &self,
        e: usize,
        global: &[S],
    ) -> ElementLocal<S, B> {
        let per_node = self.dofs.field_count * E::COMPONENTS;
        let mut local = [[S::zero(); B]; MAX_FIELDS];
        for (k, &node) in self.mesh.nodes_of::<E>(e).iter().enumerate() {
            let values = &global[node * per_node..][..per_node];
            for (field, components) in local.iter_mut().zip(values.chunks_exact(E::COMPONENTS)) {
                field[k * E::COMPONENTS..][..E::COMPONENTS].copy_from_slice(components);
            }
        }
        local
    }

    /// Evaluates the term-local jet at quadrature point `q` of element values `values`:
    /// $`j_i = \sum_{b} U^{f_i}_b\, B_{r_i b}`$, summed in local function order.
    #[inline(always)]
    pub(super) fn jet_at<const B: usize, S: Scalar>(
        term: &TermData,
        values: &ElementValues,
        q: usize,
        local: &ElementLocal<S, B>,
        jet: &mut [S],
    ) {
        let basis = values.point_basis::<B>(q);
        for (j, &(field, row)) in jet.iter_mut().zip(&term.rows) {
            let (u, b) = (&local[field], &basis[row]);
            let mut acc = S::zero();
            for k in 0..B {
                acc = acc + u[k] * b[k];
            }
            *j = acc;
        }
    }

    /// Calls `add(dof, value)` for each entry of the element vector `fields` (by field,
    /// `fields[f][b]`, see [`Self::gather`]) that sits on a free dof of element `e`, in the
    /// element's local dof order (node, then field, then component).
    #[inline]
    pub(super) fn for_each_free_dof<E: Element, const B: usize, S: Scalar>(
        &self,
        e: usize,
        fields: &[[S; B]],
        mut add: impl FnMut(usize, S),
    ) {
        let mut dofs = self.element_dofs[e].iter();
        for k in 0..E::NODES {
            for field in &fields[..self.dofs.field_count] {
                for value in &field[k * E::COMPONENTS..][..E::COMPONENTS] {
                    if let Some(Some(i)) = dofs.next() {
                        add(*i, *value);
                    }
                }
            }
        }
    }

    /// The energy of element `e`: $`\sum_t \sum_q w_q \psi_t(\mathbf j_q)`$.
    pub(super) fn element_energy<E: Element, const B: usize, S: Scalar>(
        &self,
        e: usize,
        global: &[S],
    ) -> S {
        let local = self.gather::<E, B, S>(e, global);
        let mut jet = [S::zero(); MAX_JET];
        let mut sum = S::zero();
        for (t, term) in self.terms.iter().enumerate() {
            let values = &self.value_sets[term.value_set].1[e];
            let m = term.jet.len();
            for q in 0..values.weights.len() {
                Self::jet_at(term, values, q, &local, &mut jet[..m]);
                let model = self.model_at(term.value_set, e, q);
                sum = sum + model.energy(t, &jet[..m]) * values.weights[q];
            }
        }
        sum
    }

    /// Internal force vector of element `e`, by field (`element[f][b]`, as [`Self::gather`]).
    #[inline(always)]
    pub(super) fn element_internal_forces<E: Element, const B: usize, S: Scalar>(
        &self,
        e: usize,
        global: &[S],
    ) -> ElementLocal<S, B> {
        let local = self.gather::<E, B, S>(e, global);
        let mut element = [[S::zero(); B]; MAX_FIELDS];
        let mut jet = [S::zero(); MAX_JET];
        let mut residual = [S::zero(); MAX_JET];
        for (t, term) in self.terms.iter().enumerate() {
            let values = &self.value_sets[term.value_set].1[e];
            let m = term.jet.len();
            for q in 0..values.weights.len() {
                Self::jet_at(term, values, q, &local, &mut jet[..m]);
                let model = self.model_at(term.value_set, e, q);
                model.residual(t, &jet[..m], &mut residual[..m]);
                let w = values.weights[q];
                let basis = values.point_basis::<B>(q);
                for (&r, &(field, row)) in residual[..m].iter().zip(&term.rows) {
                    for (f, &b) in element[field].iter_mut().zip(&basis[row]) {
                        *f = *f + r * (b * w);
                    }
                }
            }
        }
        element
    }

    /// The element tangent's half $`A`$ with $`K^e = A + A^\top`$: every upper-triangle entry
    /// $`(i, j)`$ of each term's jet Hessian added once as the outer product
    /// $`h_{ij} w\, B_i B_j^\top`$ (diagonal entries with $`h_{ii}/2`$). Stored by field blocks:
    /// the entry of local functions $`(k, l)`$ and fields $`(f_i, f_j)`$ is at
    /// `((fi * nf + fj) * B + k) * B + l`, so that each outer product adds to contiguous rows
    /// of `B` (which the compiler vectorises).
    #[inline(always)]
    pub(super) fn element_tangent<E: Element, const B: usize, S: Scalar>(
        &self,
        e: usize,
        global: &[S],
    ) -> Vec<S> {
        let nf = self.dofs.field_count;
        let local = self.gather::<E, B, S>(e, global);
        let mut element = vec![S::zero(); nf * nf * B * B];
        let mut jet = [S::zero(); MAX_JET];
        let mut hessian = [S::zero(); MAX_JET * (MAX_JET + 1) / 2];
        let spec = M::SPEC;
        for (t, term) in self.terms.iter().enumerate() {
            let values = &self.value_sets[term.value_set].1[e];
            let m = term.jet.len();
            let pattern = spec.terms[t].tangent_pattern;
            let hessian = &mut hessian[..pattern.len()];
            for q in 0..values.weights.len() {
                Self::jet_at(term, values, q, &local, &mut jet[..m]);
                self.model_at(term.value_set, e, q)
                    .tangent(t, &jet[..m], hessian);
                let w = values.weights[q];
                let basis = values.point_basis::<B>(q);
                for (p, &(i, j)) in pattern.iter().enumerate() {
                    let (fi, ri) = term.rows[i];
                    let (fj, rj) = term.rows[j];
                    let c = hessian[p] * if i == j { 0.5 * w } else { w };
                    // Row `bj` copied to the stack: the compiler then knows the block's
                    // stores cannot change it and updates a row several entries at a time.
                    let (bi, bj) = (&basis[ri], basis[rj]);
                    let block = &mut element[(fi * nf + fj) * B * B..][..B * B];
                    let (rows, _) = block.as_chunks_mut::<B>();
                    for (row, &b) in rows.iter_mut().zip(bi.iter()) {
                        let a = c * b;
                        for (value, &b) in row.iter_mut().zip(&bj) {
                            *value = *value + a * b;
                        }
                    }
                }
            }
        }
        element
    }

    /// Calls `add(slot, value)` for every entry of $`K^e = A + A^\top`$ (from
    /// [`Self::element_tangent`]) on the tangent's pattern, in the element's row-major local dof
    /// order (local dof = node, field, component).
    #[inline(always)]
    pub(super) fn for_each_tangent_slot<E: Element, const B: usize, S: Scalar>(
        &self,
        e: usize,
        element: &[S],
        mut add: impl FnMut(usize, S),
    ) {
        let nf = self.dofs.field_count;
        let block = |fi: usize, fj: usize| &element[(fi * nf + fj) * B * B..][..B * B];
        let mut slots = self.element_slots[e].iter();
        for k in 0..E::NODES {
            for fi in 0..nf {
                for ci in 0..E::COMPONENTS {
                    let row = k * E::COMPONENTS + ci;
                    for l in 0..E::NODES {
                        for fj in 0..nf {
                            for cj in 0..E::COMPONENTS {
                                let column = l * E::COMPONENTS + cj;
                                if let Some(Some(s)) = slots.next() {
                                    add(
                                        *s,
                                        block(fi, fj)[row * B + column]
                                            + block(fj, fi)[column * B + row],
                                    );
                                }
                            }
                        }
                    }
                }
            }
        }
    }
}

impl<M: EnergyModel> Assembler<M> {
    /// Element `e`'s part of [`Assembler::element_mean_conjugates`]: per requested entry, the
    /// mean over the element of its conjugate (`positions[t][k]`: where entry `k` of the
    /// `count` requested sits in term `t`'s jet).
    pub(super) fn element_mean_conjugates_of<E: Element, const B: usize>(
        &self,
        e: usize,
        global: &[f64],
        positions: &[Vec<Option<usize>>],
        count: usize,
    ) -> Vec<f64> {
        let local = self.gather::<E, B, f64>(e, global);
        let mut jet = [0.0; MAX_JET];
        let mut residual = [0.0; MAX_JET];
        let mut sums = vec![0.0; count];
        for (t, (term, positions)) in self.terms.iter().zip(positions).enumerate() {
            if positions.iter().all(Option::is_none) {
                continue;
            }
            let values = &self.value_sets[term.value_set].1[e];
            let area: f64 = values.weights.iter().sum();
            let m = term.jet.len();
            for q in 0..values.weights.len() {
                Self::jet_at(term, values, q, &local, &mut jet[..m]);
                let model = self.model_at(term.value_set, e, q);
                model.residual(t, &jet[..m], &mut residual[..m]);
                for (sum, position) in sums.iter_mut().zip(positions) {
                    if let Some(i) = position {
                        *sum += residual[*i] * values.weights[q] / area;
                    }
                }
            }
        }
        sums
    }

    /// [`Assembler::for_each_quadrature_point`] on element `E`.
    pub(super) fn for_each_quadrature_point_on<E: Element, const B: usize>(
        &self,
        global: &[f64],
        mut visit: impl FnMut(usize, usize, usize, [f64; 2], f64, &[f64]),
    ) {
        let mut jet = [0.0; MAX_JET];
        for e in 0..self.mesh.element_count() {
            let local = self.gather::<E, B, f64>(e, global);
            for (t, term) in self.terms.iter().enumerate() {
                let values = &self.value_sets[term.value_set].1[e];
                let m = term.jet.len();
                for q in 0..values.weights.len() {
                    Self::jet_at(term, values, q, &local, &mut jet[..m]);
                    visit(t, e, q, values.points[q], values.weights[q], &jet[..m]);
                }
            }
        }
    }
}
