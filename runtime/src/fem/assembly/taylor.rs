//! Taylor mode of the assembler: per-quadrature-point tapes of the models' Taylor-mode kernels
//! and the sweeps that fill them and assemble the ANM's right-hand sides.

use super::local::ElementLocal;
use super::{Assembler, Parallelism};
use crate::fem::element::{Element, with_element};
use crate::model::{EnergyModel, MAX_FIELDS, MAX_JET};
use rayon::prelude::*;

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

impl<M: EnergyModel> Assembler<M> {
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
            data: vec![0.0; element_len * self.mesh.element_count()],
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
        self.taylor_sweep(global, tape, |model, t, jet, block, stride| {
            model.taylor_start(t, jet, block, stride)
        });
    }

    /// Taylor mode, order $`k \ge 1`$, after [`Self::taylor_predict`] at order $`k`$: records
    /// the true order-$`k`$ coefficients for the order-$`k`$ global nodal values `increment`
    /// (prescribed entries included, see
    /// [`DofMap::expand_increment`](crate::fem::DofMap::expand_increment)).
    pub fn taylor_commit(&self, order: usize, increment: &[f64], tape: &mut TaylorTape) {
        assert!(order >= 1 && order < tape.orders, "order outside the tape");
        self.taylor_sweep(increment, tape, |model, t, jet, block, stride| {
            model.taylor_commit(t, order, jet, block, stride)
        });
    }

    /// Calls `kernel(model at the point, term, jet, point's tape, stride)` at every point of
    /// every taped term with the jet of `global` (see [`TaylorTape`] for the layout).
    fn taylor_sweep(
        &self,
        global: &[f64],
        tape: &mut TaylorTape,
        kernel: impl Fn(&M, usize, &[f64], &mut [f64], usize) + Sync + Send,
    ) {
        with_element!(self.mesh.kind, E => {
            self.taylor_sweep_on::<E, { E::FUNCTIONS }>(global, tape, kernel)
        })
    }

    fn taylor_sweep_on<E: Element, const B: usize>(
        &self,
        global: &[f64],
        tape: &mut TaylorTape,
        kernel: impl Fn(&M, usize, &[f64], &mut [f64], usize) + Sync + Send,
    ) {
        let orders = tape.orders;
        let layout = tape.layout.clone();
        self.for_each_tape_block(tape, |e, block| {
            let local = self.gather::<E, B, f64>(e, global);
            let mut jet = [0.0; MAX_JET];
            for entry in &layout {
                let term = &self.terms[entry.term];
                let values = &self.value_sets[term.value_set].1[e];
                let m = term.jet.len();
                let per_point = entry.slots * orders;
                for q in 0..values.weights.len() {
                    Self::jet_at(term, values, q, &local, &mut jet[..m]);
                    let start = entry.offset + q * per_point;
                    let point = &mut block[start..start + per_point];
                    let model = self.model_at(term.value_set, e, q);
                    kernel(model, entry.term, &jet[..m], point, entry.slots);
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
        with_element!(self.mesh.kind, E => {
            self.taylor_commit_and_predict_on::<E, { E::FUNCTIONS }>(order, commit, tape)
        })
    }

    fn taylor_commit_and_predict_on<E: Element, const B: usize>(
        &self,
        order: usize,
        commit: Option<(usize, &[f64])>,
        tape: &mut TaylorTape,
    ) -> Vec<f64> {
        let local_len = B * self.dofs.field_count;
        let mut element_forces = vec![0.0; self.mesh.element_count() * local_len];
        if tape.element_len > 0 {
            let orders = tape.orders;
            let layout = tape.layout.clone();
            let wide = crate::simd::has_avx2();
            let work = |(block, forces): (&mut [f64], &mut [f64]), e: usize| {
                let taped = TapedElement {
                    e,
                    orders,
                    layout: &layout,
                    block,
                };
                #[cfg(target_arch = "x86_64")]
                if wide {
                    // SAFETY: the processor has AVX2.
                    unsafe {
                        self.element_taylor_forces_avx2::<E, B>(taped, order, commit, forces)
                    };
                    return;
                }
                self.element_taylor_forces::<E, B>(taped, order, commit, forces)
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
        // field (`forces[f * B + b]`).
        let mut out = vec![0.0; self.dofs.free_count];
        for (e, forces) in element_forces.chunks(local_len).enumerate() {
            let (fields, _) = forces.as_chunks::<B>();
            self.for_each_free_dof::<E, B, f64>(e, fields, |i, value| out[i] += value);
        }
        out
    }

    /// [`Self::element_taylor_forces`] compiled for AVX2 ([`crate::simd`]: the same bits).
    ///
    /// # Safety
    /// The processor must have AVX2 ([`crate::simd::has_avx2`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn element_taylor_forces_avx2<E: Element, const B: usize>(
        &self,
        taped: TapedElement<'_>,
        order: usize,
        commit: Option<(usize, &[f64])>,
        forces: &mut [f64],
    ) {
        self.element_taylor_forces::<E, B>(taped, order, commit, forces);
    }

    /// Element `e`'s order-`order` Taylor forces by field (`forces[f * B + b]`, which must be
    /// zero on entry), after the optional commit of `(order − 1, increment)` at each of its
    /// taped points.
    #[inline(always)]
    fn element_taylor_forces<E: Element, const B: usize>(
        &self,
        taped: TapedElement<'_>,
        order: usize,
        commit: Option<(usize, &[f64])>,
        forces: &mut [f64],
    ) {
        let TapedElement {
            e,
            orders,
            layout,
            block,
        } = taped;
        let mut residual = [0.0; MAX_JET];
        let mut jet = [0.0; MAX_JET];
        let mut sums: ElementLocal<f64, B> = [[0.0; B]; MAX_FIELDS];
        let local = commit.map(|(_, increment)| self.gather::<E, B, f64>(e, increment));
        for entry in layout {
            let term = &self.terms[entry.term];
            let values = &self.value_sets[term.value_set].1[e];
            let m = term.jet.len();
            let per_point = entry.slots * orders;
            for q in 0..values.weights.len() {
                let start = entry.offset + q * per_point;
                // The next point in memory: this term's next, the next term's first, or the
                // next element's first (whose rows are as many as this one's, or about).
                prefetch(
                    block.as_ptr().wrapping_add(start + per_point),
                    (order + 1) * entry.slots,
                );
                let point = &mut block[start..start + per_point];
                let model = self.model_at(term.value_set, e, q);
                if let (Some((committed, _)), Some(local)) = (commit, &local) {
                    Self::jet_at(term, values, q, local, &mut jet[..m]);
                    model.taylor_commit(entry.term, committed, &jet[..m], point, entry.slots);
                }
                model.taylor_predict(entry.term, order, point, entry.slots, &mut residual[..m]);
                let w = values.weights[q];
                let basis = values.point_basis::<B>(q);
                for (&r, &(field, row)) in residual[..m].iter().zip(&term.rows) {
                    let r = r * w;
                    for (f, &b) in sums[field].iter_mut().zip(&basis[row]) {
                        *f += r * b;
                    }
                }
            }
        }
        // Summed on the stack (a row at a time, several entries at once), from zero as
        // `forces` starts: the same sums.
        for (forces, sums) in forces.chunks_exact_mut(B).zip(&sums) {
            forces.copy_from_slice(sums);
        }
    }
}

/// Asks the cache for the `len` values from `start` ahead of their use (nothing off x86-64):
/// a sweep of order $`k`$ reads rows $`0..k`$ of every point, last touched a whole tape ago,
/// and a point's rows are too short a run for the hardware prefetcher (the reference
/// envelope's Taylor sweeps took 30 % less time with it, 128 × 64).
#[inline(always)]
fn prefetch(start: *const f64, len: usize) {
    #[cfg(target_arch = "x86_64")]
    for line in (0..len).step_by(8) {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        // SAFETY: a prefetch is a hint: it reads nothing into the program and faults on no
        // address, even past the tape's end. SSE is part of the x86-64 baseline.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(line).cast()) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (start, len);
}

/// One element's part of a tape during a sweep.
struct TapedElement<'a> {
    e: usize,
    orders: usize,
    layout: &'a [TapeBlock],
    block: &'a mut [f64],
}
