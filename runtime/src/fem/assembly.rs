//! Assembly of energy, residual and tangent from a model's generated kernels.
//!
//! The assembler knows nothing about the model beyond the kernel contract
//! ([`EnergyModel`]): it evaluates each term's jet at that term's
//! quadrature points, calls the term kernels, and scatters
//! $$`R_a = \sum_e \sum_q w_q \sum_i r_i(\mathbf{j}_q)\, B_{i a},\qquad
//! K_{ab} = \sum_e \sum_q w_q \sum_{ij} k_{ij}(\mathbf{j}_q)\, B_{i a} B_{j b},`$$
//! with $`B_{ia}`$ the shape function value or derivative that jet entry $`i`$ takes from dof
//! $`a`$. Residual and tangent are generic over [`Scalar`]: the same loop assembles `f64`
//! values, dual numbers (directional derivatives of the tangent) and truncated series (ANM).
//! The sparsity pattern and the element → value-slot tables are built once.
//!
//! **Determinism.** Elements are coloured so that two elements of one colour share no node; the
//! elements of a colour add into disjoint entries and run in parallel, the colours one after the
//! other. Every global entry is therefore summed in an order fixed by the mesh, whatever the
//! number of threads: results are bit-for-bit the same on 1 or N threads, and no per-thread
//! full-length buffer is needed.
//!
//! **Taylor mode** ([`TaylorTape`]): the ANM's right-hand sides come from the models'
//! Taylor-mode kernels, which keep per quadrature point the coefficient history of the few
//! intermediates their recurrences read.

use super::dofs::DofMap;
use super::element::{ElementValues, GaussRule, JacobianError, QUAD8_NODES, derivative_row};
use super::mesh::Mesh;
use crate::linear::pattern::{SparseMatrix, SparsityPattern};
use crate::model::{Derivative, EnergyModel, JetEntry, QuadratureRule};
/// The stack buffers' sizes, owned by the kernel contract (re-exported for older paths).
pub use crate::model::{MAX_FIELDS, MAX_JET};
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
    /// (field, basis row) of each term-local jet entry (see [`derivative_row`]).
    rows: Vec<(usize, usize)>,
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
    /// Element colours: no two elements of one colour share a node.
    colours: Vec<Vec<usize>>,
    parallelism: Parallelism,
}

impl<M: EnergyModel> Assembler<M> {
    /// Prepares element values (only the rules and derivatives the model's terms use), element
    /// dof lists, the sparsity pattern and the scatter tables.
    ///
    /// # Panics
    /// If the model's jet asks for a derivative the element does not supply
    /// ([`derivative_row`]); [`crate::problem::Problem::new`] checks this first and returns
    /// [`crate::problem::ProblemError::UnsupportedDerivative`].
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
            let jet: Vec<JetEntry> = term.jet.iter().map(|&i| spec.jet[i]).collect();
            let rows = jet
                .iter()
                .map(|e| {
                    let row = derivative_row(e.derivative)
                        .expect("Problem::new refuses derivatives the element does not supply");
                    (e.field, row)
                })
                .collect();
            terms.push(TermData {
                value_set,
                jet,
                rows,
            });
        }
        let element_dofs: Vec<Vec<Option<usize>>> = mesh
            .elements
            .iter()
            .map(|nodes| dofs.element_dofs(nodes))
            .collect();
        let couplings = field_couplings(spec);
        let nf = dofs.field_count;
        let pattern = Arc::new(
            SparsityPattern::try_from_coupled_element_dofs(
                dofs.free_count,
                element_dofs.iter().map(|d| d.as_slice()),
                |a, b| couplings[(a % nf) * nf + b % nf],
            )
            .expect("dof indices come from the dof map"),
        );
        let element_slots = element_dofs
            .iter()
            .map(|d| pattern.element_slots(d))
            .collect();
        let colours = colour_elements(&mesh);
        Ok(Assembler {
            model,
            mesh,
            dofs,
            value_sets,
            terms,
            element_dofs,
            pattern,
            element_slots,
            colours,
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

    /// Element colours (no two elements of one colour share a node).
    pub fn colours(&self) -> &[Vec<usize>] {
        &self.colours
    }

    /// Runs `work(element, sink)` over every element, each adding its contributions into `out`
    /// through `sink`. Elements of one colour touch disjoint entries and run in parallel; colours
    /// run in order, so every entry is summed in the same order for any thread count.
    fn accumulate<S: Scalar>(
        &self,
        out: &mut [S],
        work: impl Fn(usize, &mut ElementSink<S>) + Sync,
    ) {
        let sink = ElementSink {
            data: out.as_mut_ptr(),
            len: out.len(),
        };
        for colour in &self.colours {
            match self.parallelism {
                Parallelism::Sequential => {
                    for &e in colour {
                        work(e, &mut sink.clone());
                    }
                }
                Parallelism::Chunks(_) => {
                    colour.par_iter().for_each(|&e| work(e, &mut sink.clone()));
                }
            }
        }
    }

    /// `work(element)` for every element, in element order (parallel unless sequential).
    fn map_elements<T: Send>(&self, work: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
        let n = self.mesh.elements.len();
        match self.parallelism {
            Parallelism::Sequential => (0..n).map(work).collect(),
            Parallelism::Chunks(_) => (0..n).into_par_iter().map(work).collect(),
        }
    }

    /// Gathers the element's nodal values by field: `local[f][k]` is field `f` at node `k`, so
    /// that a jet entry is one 8-term dot product of contiguous values.
    #[inline]
    fn gather<S: Scalar>(&self, e: usize, global: &[S]) -> ElementLocal<S> {
        let nf = self.dofs.field_count;
        let mut local = [[S::zero(); QUAD8_NODES]; MAX_FIELDS];
        for (k, &node) in self.mesh.elements[e].iter().enumerate() {
            let values = &global[node * nf..][..nf];
            for (field, &value) in local.iter_mut().zip(values) {
                field[k] = value;
            }
        }
        local
    }

    /// Evaluates the term-local jet at quadrature point `q` of element `e`:
    /// $`j_i = \sum_{k=1}^{8} U^{f_i}_k\, B_{r_i k}`$, summed in node order.
    #[inline]
    fn jet_at<S: Scalar>(
        &self,
        term: &TermData,
        values: &ElementValues,
        q: usize,
        local: &ElementLocal<S>,
        jet: &mut [S],
    ) {
        let basis = &values.basis[q];
        for (j, &(field, row)) in jet.iter_mut().zip(&term.rows) {
            let (u, b) = (&local[field], &basis[row]);
            let mut acc = S::zero();
            for k in 0..QUAD8_NODES {
                acc = acc + u[k] * b[k];
            }
            *j = acc;
        }
    }

    /// Calls `add(dof, value)` for each entry of the element vector `fields` (by field,
    /// `fields[f][k]`, see [`Self::gather`]) that sits on a free dof of element `e`, in the
    /// element's local dof order (node `k`, then field `f`).
    #[inline]
    fn for_each_free_dof<S: Scalar>(
        &self,
        e: usize,
        fields: &[[S; QUAD8_NODES]],
        mut add: impl FnMut(usize, S),
    ) {
        let mut dofs = self.element_dofs[e].iter();
        for k in 0..QUAD8_NODES {
            for field in &fields[..self.dofs.field_count] {
                if let Some(Some(i)) = dofs.next() {
                    add(*i, field[k]);
                }
            }
        }
    }

    /// Total energy $`\Pi = \sum_t \int \psi_t`$ of the global nodal values.
    pub fn energy<S: Scalar>(&self, global: &[S]) -> S {
        let per_element = self.map_elements(|e| {
            let local = self.gather(e, global);
            let mut jet = [S::zero(); MAX_JET];
            let mut sum = S::zero();
            for (t, term) in self.terms.iter().enumerate() {
                let values = &self.value_sets[term.value_set].1[e];
                let m = term.jet.len();
                for q in 0..values.weights.len() {
                    self.jet_at(term, values, q, &local, &mut jet[..m]);
                    sum = sum + self.model.energy(t, &jet[..m]) * values.weights[q];
                }
            }
            sum
        });
        per_element
            .into_iter()
            .fold(S::zero(), |total, value| total + value)
    }

    /// Internal force vector of element `e`, by field (`element[f][k]`, as [`Self::gather`]).
    #[inline]
    fn element_internal_forces<S: Scalar>(&self, e: usize, global: &[S]) -> ElementLocal<S> {
        let local = self.gather(e, global);
        let mut element = [[S::zero(); QUAD8_NODES]; MAX_FIELDS];
        let mut jet = [S::zero(); MAX_JET];
        let mut residual = [S::zero(); MAX_JET];
        for (t, term) in self.terms.iter().enumerate() {
            let values = &self.value_sets[term.value_set].1[e];
            let m = term.jet.len();
            for q in 0..values.weights.len() {
                self.jet_at(term, values, q, &local, &mut jet[..m]);
                self.model.residual(t, &jet[..m], &mut residual[..m]);
                let w = values.weights[q];
                let basis = &values.basis[q];
                for (&r, &(field, row)) in residual[..m].iter().zip(&term.rows) {
                    for (f, &b) in element[field].iter_mut().zip(&basis[row]) {
                        *f = *f + r * (b * w);
                    }
                }
            }
        }
        element
    }

    /// Internal forces $`\partial\Pi/\partial U_a`$ over the free dofs, from global nodal values
    /// (prescribed entries included in `global`).
    pub fn internal_forces<S: Scalar>(&self, global: &[S]) -> Vec<S> {
        let mut out = vec![S::zero(); self.dofs.free_count];
        self.accumulate(&mut out, |e, sink| {
            let element = self.element_internal_forces(e, global);
            self.for_each_free_dof(e, &element, |i, value| sink.add(i, value));
        });
        out
    }

    /// Internal forces and, in the same element loop, the force magnitudes
    /// $`\sum_e |f^e_a|`$ over the free dofs: the size of the element forces that meet at each
    /// dof, a per-dof scale for residuals (large where forces cancel at equilibrium, unlike the
    /// assembled internal force).
    pub fn internal_forces_and_magnitudes(&self, global: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let n = self.dofs.free_count;
        let mut both = vec![0.0; 2 * n];
        self.accumulate(&mut both, |e, sink| {
            let element = self.element_internal_forces(e, global);
            self.for_each_free_dof(e, &element, |i, value| {
                sink.add(i, value);
                sink.add(n + i, value.abs());
            });
        });
        let magnitudes = both.split_off(n);
        (both, magnitudes)
    }

    /// Tangent values $`\partial^2\Pi/\partial U_a\partial U_b`$ on [`Self::pattern`], generic
    /// over the scalar (dual numbers give directional derivatives of the tangent).
    pub fn tangent_values<S: Scalar>(&self, global: &[S]) -> Vec<S> {
        let nf = self.dofs.field_count;
        let mut out = vec![S::zero(); self.pattern.nnz()];
        self.accumulate(&mut out, |e, sink| {
            let element = self.element_tangent(e, global);
            let block = |fi: usize, fj: usize| {
                &element[(fi * nf + fj) * QUAD8_NODES * QUAD8_NODES..][..QUAD8_NODES * QUAD8_NODES]
            };
            // A holds each pattern entry once (diagonal entries halved): K = A + Aᵀ. Local dof
            // `k * nf + f` is node k of field f; the slots are row-major over local dofs.
            let mut slots = self.element_slots[e].iter();
            for k in 0..QUAD8_NODES {
                for fi in 0..nf {
                    for l in 0..QUAD8_NODES {
                        for fj in 0..nf {
                            if let Some(Some(s)) = slots.next() {
                                sink.add(
                                    *s,
                                    block(fi, fj)[k * QUAD8_NODES + l]
                                        + block(fj, fi)[l * QUAD8_NODES + k],
                                );
                            }
                        }
                    }
                }
            }
        });
        out
    }

    /// The element tangent's half $`A`$ with $`K^e = A + A^\top`$: every upper-triangle entry
    /// $`(i, j)`$ of each term's jet Hessian added once as the outer product
    /// $`h_{ij} w\, B_i B_j^\top`$ (diagonal entries with $`h_{ii}/2`$). Stored by field blocks:
    /// the entry of nodes $`(k, l)`$ and fields $`(f_i, f_j)`$ is at
    /// `((fi * nf + fj) * 8 + k) * 8 + l`, so that each outer product adds to contiguous rows
    /// of 8 (which the compiler vectorises).
    fn element_tangent<S: Scalar>(&self, e: usize, global: &[S]) -> Vec<S> {
        let nf = self.dofs.field_count;
        let local = self.gather(e, global);
        let mut element = vec![S::zero(); nf * nf * QUAD8_NODES * QUAD8_NODES];
        let mut jet = [S::zero(); MAX_JET];
        let mut hessian = [S::zero(); MAX_JET * (MAX_JET + 1) / 2];
        let spec = M::SPEC;
        for (t, term) in self.terms.iter().enumerate() {
            let values = &self.value_sets[term.value_set].1[e];
            let m = term.jet.len();
            let pattern = spec.terms[t].tangent_pattern;
            let hessian = &mut hessian[..pattern.len()];
            for q in 0..values.weights.len() {
                self.jet_at(term, values, q, &local, &mut jet[..m]);
                self.model.tangent(t, &jet[..m], hessian);
                let w = values.weights[q];
                let basis = &values.basis[q];
                for (p, &(i, j)) in pattern.iter().enumerate() {
                    let (fi, ri) = term.rows[i];
                    let (fj, rj) = term.rows[j];
                    let c = hessian[p] * if i == j { 0.5 * w } else { w };
                    let (bi, bj) = (&basis[ri], &basis[rj]);
                    let block = &mut element[(fi * nf + fj) * QUAD8_NODES * QUAD8_NODES..]
                        [..QUAD8_NODES * QUAD8_NODES];
                    for (row, &b) in block.chunks_exact_mut(QUAD8_NODES).zip(bi.iter()) {
                        let a = c * b;
                        for (value, &b) in row.iter_mut().zip(bj.iter()) {
                            *value = *value + a * b;
                        }
                    }
                }
            }
        }
        element
    }

    /// Assembles the `f64` tangent into `matrix` (which must be on [`Self::pattern`]).
    pub fn assemble_tangent_into(&self, global: &[f64], matrix: &mut SparseMatrix) {
        let values = self.tangent_values(global);
        matrix.values.copy_from_slice(&values);
    }

    /// A zeroed tape for Taylor coefficients up to `highest_order` of every nonlinear term
    /// (terms whose residual is affine in the jet contribute nothing to right-hand sides of
    /// order ≥ 1 and get no tape). Its size is [`TaylorTape::bytes`].
    pub fn taylor_tape(&self, highest_order: usize) -> TaylorTape {
        let orders = highest_order + 1;
        let spec = M::SPEC;
        let mut layout = Vec::new();
        let mut element_len = 0;
        for (t, term) in self.terms.iter().enumerate() {
            let term_spec = &spec.terms[t];
            if term_spec.linear_residual || term_spec.taylor_slots == 0 {
                continue;
            }
            let points = self.value_sets[term.value_set].1[0].weights.len();
            layout.push(TapeBlock {
                term: t,
                slots: term_spec.taylor_slots,
                offset: element_len,
            });
            element_len += points * term_spec.taylor_slots * orders;
        }
        TaylorTape {
            orders,
            layout,
            element_len,
            data: vec![0.0; element_len * self.mesh.elements.len()],
        }
    }

    /// Runs `work(element, element's tape block)` over all elements (in parallel unless
    /// sequential; blocks are disjoint).
    fn for_each_tape_block(
        &self,
        tape: &mut TaylorTape,
        work: impl Fn(usize, &mut [f64]) + Sync + Send,
    ) {
        if tape.element_len == 0 {
            return;
        }
        let chunks = tape.data.chunks_mut(tape.element_len);
        match self.parallelism {
            Parallelism::Sequential => chunks.enumerate().for_each(|(e, b)| work(e, b)),
            Parallelism::Chunks(_) => tape
                .data
                .par_chunks_mut(tape.element_len)
                .enumerate()
                .for_each(|(e, b)| work(e, b)),
        }
    }

    /// Taylor mode, order 0: records the coefficients of order 0 at the global nodal values
    /// `global` ([`EnergyModel::taylor_start`] at every point of every nonlinear term).
    pub fn taylor_start(&self, global: &[f64], tape: &mut TaylorTape) {
        self.taylor_sweep(global, tape, |t, jet, block, stride| {
            self.model.taylor_start(t, jet, block, stride)
        });
    }

    /// Taylor mode, order $`k \ge 1`$, after [`Self::taylor_predict`] at order $`k`$: records
    /// the true order-$`k`$ coefficients for the order-$`k`$ global nodal values `increment`
    /// (prescribed entries included, see [`DofMap::expand_increment`]).
    pub fn taylor_commit(&self, order: usize, increment: &[f64], tape: &mut TaylorTape) {
        assert!(order >= 1 && order < tape.orders, "order outside the tape");
        self.taylor_sweep(increment, tape, |t, jet, block, stride| {
            self.model.taylor_commit(t, order, jet, block, stride)
        });
    }

    /// Calls `kernel(term, jet, point's tape, stride)` at every point of every taped term with
    /// the jet of `global` (see [`TaylorTape`] for the layout).
    fn taylor_sweep(
        &self,
        global: &[f64],
        tape: &mut TaylorTape,
        kernel: impl Fn(usize, &[f64], &mut [f64], usize) + Sync + Send,
    ) {
        let orders = tape.orders;
        let layout = tape.layout.clone();
        self.for_each_tape_block(tape, |e, block| {
            let local = self.gather(e, global);
            let mut jet = [0.0; MAX_JET];
            for entry in &layout {
                let term = &self.terms[entry.term];
                let values = &self.value_sets[term.value_set].1[e];
                let m = term.jet.len();
                let per_point = entry.slots * orders;
                for q in 0..values.weights.len() {
                    self.jet_at(term, values, q, &local, &mut jet[..m]);
                    let start = entry.offset + q * per_point;
                    let point = &mut block[start..start + per_point];
                    kernel(entry.term, &jet[..m], point, entry.slots);
                }
            }
        });
    }

    /// Taylor mode, order $`k \ge 1`$: the order-$`k`$ coefficient of the internal forces over
    /// the free dofs when the order-$`k`$ unknowns are zero — minus the ANM right-hand side —
    /// from orders $`0..k-1`$ on the tape ([`EnergyModel::taylor_predict`]).
    pub fn taylor_predict(&self, order: usize, tape: &mut TaylorTape) -> Vec<f64> {
        assert!(order >= 1 && order < tape.orders, "order outside the tape");
        self.taylor_commit_and_predict(order, None, tape)
    }

    /// [`Self::taylor_commit`] at order $`k`$ (the increment's global nodal values, prescribed
    /// entries included) followed by [`Self::taylor_predict`] at order $`k + 1`$, in **one**
    /// sweep over the tape: each point's history is read while still in cache, and the tape —
    /// the largest array of a step (dofs × orders) — is streamed once per order instead of
    /// twice. Returns the order-$`(k+1)`$ prediction.
    pub fn taylor_commit_then_predict(
        &self,
        order: usize,
        increment: &[f64],
        tape: &mut TaylorTape,
    ) -> Vec<f64> {
        assert!(
            order >= 1 && order + 1 < tape.orders,
            "order outside the tape"
        );
        self.taylor_commit_and_predict(order + 1, Some((order, increment)), tape)
    }

    /// Prediction at `order`, after an optional commit of `(order − 1, increment)` at each
    /// point (see [`Self::taylor_commit_then_predict`]).
    fn taylor_commit_and_predict(
        &self,
        order: usize,
        commit: Option<(usize, &[f64])>,
        tape: &mut TaylorTape,
    ) -> Vec<f64> {
        let nf = self.dofs.field_count;
        let local_len = QUAD8_NODES * nf;
        let orders = tape.orders;
        let layout = tape.layout.clone();
        let mut element_forces = vec![0.0; self.mesh.elements.len() * local_len];
        if tape.element_len > 0 {
            let work = |(block, forces): (&mut [f64], &mut [f64]), e: usize| {
                let mut residual = [0.0; MAX_JET];
                let mut jet = [0.0; MAX_JET];
                let local = commit.map(|(_, increment)| self.gather(e, increment));
                for entry in &layout {
                    let term = &self.terms[entry.term];
                    let values = &self.value_sets[term.value_set].1[e];
                    let m = term.jet.len();
                    let per_point = entry.slots * orders;
                    for q in 0..values.weights.len() {
                        let start = entry.offset + q * per_point;
                        let point = &mut block[start..start + per_point];
                        if let (Some((committed, _)), Some(local)) = (commit, &local) {
                            self.jet_at(term, values, q, local, &mut jet[..m]);
                            self.model.taylor_commit(
                                entry.term,
                                committed,
                                &jet[..m],
                                point,
                                entry.slots,
                            );
                        }
                        self.model.taylor_predict(
                            entry.term,
                            order,
                            point,
                            entry.slots,
                            &mut residual[..m],
                        );
                        let w = values.weights[q];
                        let basis = &values.basis[q];
                        for (&r, &(field, row)) in residual[..m].iter().zip(&term.rows) {
                            let r = r * w;
                            let forces = &mut forces[field * QUAD8_NODES..][..QUAD8_NODES];
                            for (f, &b) in forces.iter_mut().zip(&basis[row]) {
                                *f += r * b;
                            }
                        }
                    }
                }
            };
            let pairs = tape
                .data
                .chunks_mut(tape.element_len)
                .zip(element_forces.chunks_mut(local_len));
            match self.parallelism {
                Parallelism::Sequential => pairs.enumerate().for_each(|(e, p)| work(p, e)),
                Parallelism::Chunks(_) => tape
                    .data
                    .par_chunks_mut(tape.element_len)
                    .zip(element_forces.par_chunks_mut(local_len))
                    .enumerate()
                    .for_each(|(e, p)| work(p, e)),
            }
        }
        // Scatter in element order: the same sums for any thread count. Element forces are by
        // field (`forces[f * 8 + k]`).
        let mut out = vec![0.0; self.dofs.free_count];
        for (e, forces) in element_forces.chunks(local_len).enumerate() {
            let (fields, _) = forces.as_chunks::<QUAD8_NODES>();
            self.for_each_free_dof(e, fields, |i, value| out[i] += value);
        }
        out
    }

    /// Element means of the work conjugates of jet entries: for each requested entry $`j`$
    /// (a field and a derivative) and each element $`e`$,
    /// $$`\bar s_j^e = \frac{1}{A_e}\sum_t \int_{\Omega_e} \frac{\partial\psi_t}{\partial j}\,dA`$$
    /// with every term integrated by its own rule (terms whose jet lacks $`j`$ add nothing).
    /// For an in-plane energy written in $`u_{,X}, u_{,Y}, v_{,X}, v_{,Y}`$ these are the stress
    /// resultants: $`\partial\psi/\partial u_{,X} = N_X`$, $`\partial\psi/\partial v_{,Y} = N_Y`$,
    /// $`\partial\psi/\partial u_{,Y} = \partial\psi/\partial v_{,X} = N_{XY}`$, whatever the
    /// model adds to the strain. Returns `result[entry][element]`.
    pub fn element_mean_conjugates(&self, global: &[f64], entries: &[JetEntry]) -> Vec<Vec<f64>> {
        // Where each requested entry sits in each term's jet (found once, not per element).
        let positions: Vec<Vec<Option<usize>>> = self
            .terms
            .iter()
            .map(|term| {
                entries
                    .iter()
                    .map(|wanted| term.jet.iter().position(|j| j == wanted))
                    .collect()
            })
            .collect();
        let per_element = self.map_elements(|e| {
            let local = self.gather(e, global);
            let mut jet = [0.0; MAX_JET];
            let mut residual = [0.0; MAX_JET];
            let mut sums = vec![0.0; entries.len()];
            for (t, (term, positions)) in self.terms.iter().zip(&positions).enumerate() {
                if positions.iter().all(Option::is_none) {
                    continue;
                }
                let values = &self.value_sets[term.value_set].1[e];
                let area: f64 = values.weights.iter().sum();
                let m = term.jet.len();
                for q in 0..values.weights.len() {
                    self.jet_at(term, values, q, &local, &mut jet[..m]);
                    self.model.residual(t, &jet[..m], &mut residual[..m]);
                    for (sum, position) in sums.iter_mut().zip(positions) {
                        if let Some(i) = position {
                            *sum += residual[*i] * values.weights[q] / area;
                        }
                    }
                }
            }
            sums
        });
        (0..entries.len())
            .map(|k| per_element.iter().map(|sums| sums[k]).collect())
            .collect()
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

/// Which pairs of fields the tangent couples: `coupled[f * nf + g]` is true when some term's
/// structurally non-zero Hessian entry [`TermSpec::tangent_pattern`](crate::model::TermSpec)
/// joins a jet entry of field `f` with one of field `g` (symmetric; the diagonal always). A
/// block of the tangent between two fields no term couples (the plate's in-plane displacements
/// and rotations) is identically zero and is left out of the sparsity pattern.
pub fn field_couplings(spec: &crate::model::ModelSpec) -> Vec<bool> {
    let nf = spec.fields.len();
    let mut coupled = vec![false; nf * nf];
    for f in 0..nf {
        coupled[f * nf + f] = true;
    }
    for term in spec.terms {
        for &(i, j) in term.tangent_pattern {
            let (f, g) = (spec.jet[term.jet[i]].field, spec.jet[term.jet[j]].field);
            coupled[f * nf + g] = true;
            coupled[g * nf + f] = true;
        }
    }
    coupled
}

/// Where one taped term's points live inside an element's block of a [`TaylorTape`].
#[derive(Clone, Copy, Debug)]
struct TapeBlock {
    term: usize,
    slots: usize,
    offset: usize,
}

/// Per-quadrature-point tapes of the Taylor-mode kernels for one path-following step: for every
/// element, every nonlinear term and every quadrature point, the coefficient history of
/// [`TermSpec::taylor_slots`](crate::model::TermSpec) slots per order up to the highest.
///
/// **Layout**: per element, term and quadrature point, one row of slots per order
/// (`[point][order][slot]`, `stride` = slots; see [`EnergyModel::taylor_start`]). Order $`k`$
/// reads a contiguous prefix of each point's block — rows $`0..k`$ — and writes row $`k`$, so
/// a sweep streams only the part of the tape that the order needs. (With slots first, as
/// before, every order touched every slot's cache lines: the series took 15 % longer at
/// 40 × 20 and 104 × 52. Rows interleaving an element's points, `[order][point][slot]`,
/// spread the cache misses over every product and took 80 % longer.)
#[derive(Clone, Debug)]
pub struct TaylorTape {
    /// Rows per point: the highest order + 1.
    orders: usize,
    layout: Vec<TapeBlock>,
    element_len: usize,
    data: Vec<f64>,
}

impl TaylorTape {
    /// Memory held, in bytes.
    pub fn bytes(&self) -> usize {
        self.data.len() * std::mem::size_of::<f64>()
    }
    /// Highest order the tape holds.
    pub fn highest_order(&self) -> usize {
        self.orders - 1
    }
}

/// Where one element adds its contributions during [`Assembler::accumulate`].
///
/// A raw view of the output shared by the elements of one colour. Sound because elements of one
/// colour share no node, hence no dof and no matrix entry: each entry is written by at most one
/// element of the colour being processed, and colours are processed one after the other.
struct ElementSink<S> {
    data: *mut S,
    len: usize,
}

impl<S> Clone for ElementSink<S> {
    fn clone(&self) -> Self {
        ElementSink {
            data: self.data,
            len: self.len,
        }
    }
}

// SAFETY: see the type's documentation: concurrent elements write disjoint entries.
unsafe impl<S: Send> Send for ElementSink<S> {}
unsafe impl<S: Send> Sync for ElementSink<S> {}

impl<S: Scalar> ElementSink<S> {
    #[inline(always)]
    fn add(&mut self, index: usize, value: S) {
        assert!(index < self.len, "assembly index out of range");
        // SAFETY: in bounds (checked), and no other element of the running colour writes
        // `index` (elements of one colour share no dof).
        unsafe {
            let entry = self.data.add(index);
            *entry = *entry + value;
        }
    }
}

/// Greedy colouring of the elements (in element order, smallest free colour) such that no two
/// elements of a colour share a node. Deterministic; a structured Q8 mesh gets 4 colours.
pub fn colour_elements(mesh: &Mesh) -> Vec<Vec<usize>> {
    let mut elements_of_node: Vec<Vec<usize>> = vec![Vec::new(); mesh.nodes.len()];
    for (e, nodes) in mesh.elements.iter().enumerate() {
        for &n in nodes.iter() {
            elements_of_node[n].push(e);
        }
    }
    let mut colour_of = vec![usize::MAX; mesh.elements.len()];
    let mut colours: Vec<Vec<usize>> = Vec::new();
    let mut taken = Vec::new();
    for (e, nodes) in mesh.elements.iter().enumerate() {
        taken.clear();
        for &n in nodes.iter() {
            for &other in &elements_of_node[n] {
                if colour_of[other] != usize::MAX {
                    taken.push(colour_of[other]);
                }
            }
        }
        let colour = (0..)
            .find(|c| !taken.contains(c))
            .expect("a free colour exists");
        if colour == colours.len() {
            colours.push(Vec::new());
        }
        colours[colour].push(e);
        colour_of[e] = colour;
    }
    colours
}

/// An element's nodal values (or forces) by field: `[f][k]` is field `f` at node `k`.
type ElementLocal<S> = [[S; QUAD8_NODES]; MAX_FIELDS];
