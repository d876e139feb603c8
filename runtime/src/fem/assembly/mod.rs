//! Assembly of energy, residual and tangent from a model's generated kernels, on a mesh of any
//! element.
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
//! **Elements.** The assembler is generic over the model only; the element is the mesh's
//! [`ElementKind`](crate::fem::ElementKind). Each public operation matches the kind once and
//! runs the element loop of its `local` module monomorphised for that element (its node count, dofs per
//! node and shape functions per field are constants there).
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

mod colouring;
mod local;
mod taylor;

pub use colouring::colour_elements;
pub use taylor::TaylorTape;

use super::dofs::DofMap;
use super::element::{Element, ElementValues, JacobianError, with_element};
use super::mesh::Mesh;
use super::parameter_profile::ParameterProfile;
use crate::linear::pattern::{SparseMatrix, SparsityPattern};
use crate::model::{EnergyModel, JetEntry, QuadratureRule};
/// The stack buffers' sizes, owned by the kernel contract (re-exported for older paths).
pub use crate::model::{MAX_FIELDS, MAX_JET};
use crate::scalar::Scalar;
use colouring::ElementSink;
use num_dual::Dual64;
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
    /// (field, basis row) of each term-local jet entry (the row of the element's
    /// [`Element::DERIVATIVES`] holding the derivative).
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
    /// Parameters that vary over the domain: (parameter index, profile); empty when every
    /// parameter is constant.
    profiles: Vec<(usize, ParameterProfile)>,
    /// With profiles, the model at every quadrature point of each value set (points per
    /// element, instances `[e * points + q]`); empty otherwise.
    point_models: Vec<(usize, Vec<M>)>,
}

/// The values of every element of `mesh` at the points of the element's rule `rule`.
fn element_values(mesh: &Mesh, rule: QuadratureRule) -> Result<Vec<ElementValues>, JacobianError> {
    with_element!(mesh.kind, E => {
        let rule = E::quadrature(rule);
        (0..mesh.element_count())
            .map(|e| ElementValues::new::<E>(e, &mesh.element_coordinates(e), &rule))
            .collect()
    })
}

impl<M: EnergyModel> Assembler<M> {
    /// Prepares element values (one set per quadrature rule the model's terms use), element
    /// dof lists, the sparsity pattern and the scatter tables.
    ///
    /// # Panics
    /// If the model's jet asks for a derivative the mesh's element does not supply;
    /// [`crate::problem::Problem::new`] checks this first and returns
    /// [`crate::problem::ProblemError::UnsupportedDerivative`].
    pub fn new(model: M, mesh: Arc<Mesh>, dofs: Arc<DofMap>) -> Result<Self, JacobianError> {
        let spec = M::SPEC;
        let mut value_sets: Vec<(QuadratureRule, Vec<ElementValues>)> = Vec::new();
        let mut terms = Vec::new();
        for term in spec.terms {
            let value_set = match value_sets.iter().position(|(r, _)| *r == term.quadrature) {
                Some(k) => k,
                None => {
                    value_sets.push((term.quadrature, element_values(&mesh, term.quadrature)?));
                    value_sets.len() - 1
                }
            };
            let jet: Vec<JetEntry> = term.jet.iter().map(|&i| spec.jet[i]).collect();
            let derivatives = mesh.kind.derivatives();
            let rows = jet
                .iter()
                .map(|e| {
                    let row = derivatives.iter().position(|&d| d == e.derivative);
                    let row = row.expect("Problem::new refuses derivatives the element lacks");
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
            .elements()
            .map(|nodes| dofs.element_dofs(nodes))
            .collect();
        let couplings = field_couplings(spec);
        let (nf, components) = (dofs.field_count, dofs.components);
        let field = |local: usize| (local / components) % nf;
        let pattern = Arc::new(
            SparsityPattern::try_from_coupled_element_dofs(
                dofs.free_count,
                element_dofs.iter().map(|d| d.as_slice()),
                |a, b| couplings[field(a) * nf + field(b)],
            )
            .expect("dof indices come from the dof map"),
        );
        let element_slots = element_dofs
            .par_iter()
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
            profiles: Vec::new(),
            point_models: Vec::new(),
        })
    }

    /// The model instance.
    pub fn model(&self) -> &M {
        &self.model
    }
    /// Replaces the model parameters (same model type, so pattern and element values stay);
    /// profiled parameters keep their profiles.
    pub fn set_model(&mut self, model: M) {
        self.model = model;
        self.place_point_models();
    }

    /// Makes parameters vary over the domain: each `(parameter index, profile)` replaces that
    /// parameter of the model at every quadrature point by the profile's value there
    /// ([`ParameterProfile::value_at`]). An empty list makes every parameter constant again.
    /// Whether the model allows a parameter to vary is checked by
    /// [`crate::problem::Problem::set_parameter_profiles`].
    pub fn set_parameter_profiles(&mut self, profiles: Vec<(usize, ParameterProfile)>) {
        self.profiles = profiles;
        self.place_point_models();
    }

    /// The parameter profiles in use.
    pub fn parameter_profiles(&self) -> &[(usize, ParameterProfile)] {
        &self.profiles
    }

    /// Rebuilds [`Self::point_models`] from the model and the profiles.
    fn place_point_models(&mut self) {
        self.point_models.clear();
        if self.profiles.is_empty() {
            return;
        }
        let constant = self.model.parameter_values();
        for (_, values) in &self.value_sets {
            let points = values.first().map_or(0, ElementValues::point_count);
            let models = values
                .iter()
                .flat_map(|element| &element.points)
                .map(|&point| {
                    let mut local = constant.clone();
                    for (parameter, profile) in &self.profiles {
                        local[*parameter] = profile.value_at(point);
                    }
                    M::from_parameters(&local)
                })
                .collect();
            self.point_models.push((points, models));
        }
    }

    /// The model at quadrature point `q` of element `e` in value set `value_set`: the model
    /// itself unless some parameter has a profile.
    #[inline(always)]
    fn model_at(&self, value_set: usize, e: usize, q: usize) -> &M {
        if self.point_models.is_empty() {
            &self.model
        } else {
            let (points, models) = &self.point_models[value_set];
            &models[e * points + q]
        }
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
        self.accumulate_where(out, None, work);
    }

    /// [`Self::accumulate`] over the elements `e` with `elements[e]` only (all without a
    /// mask): each entry is summed in the same order, less the elements left out.
    fn accumulate_where<S: Scalar>(
        &self,
        out: &mut [S],
        elements: Option<&[bool]>,
        work: impl Fn(usize, &mut ElementSink<S>) + Sync,
    ) {
        let sink = ElementSink {
            data: out.as_mut_ptr(),
            len: out.len(),
        };
        let kept = |e: usize| elements.is_none_or(|mask| mask[e]);
        for colour in &self.colours {
            match self.parallelism {
                Parallelism::Sequential => {
                    for &e in colour.iter().filter(|&&e| kept(e)) {
                        work(e, &mut sink.clone());
                    }
                }
                Parallelism::Chunks(_) => {
                    colour
                        .par_iter()
                        .filter(|&&e| kept(e))
                        .for_each(|&e| work(e, &mut sink.clone()));
                }
            }
        }
    }

    /// Which elements have a node with a global dof for which `pick(g)` holds (by element).
    pub fn elements_with_dofs(&self, pick: impl Fn(usize) -> bool) -> Vec<bool> {
        with_element!(self.mesh.kind, E => {
            let per_node = self.dofs.field_count * E::COMPONENTS;
            (0..self.mesh.element_count())
                .map(|e| {
                    self.mesh
                        .nodes_of::<E>(e)
                        .iter()
                        .any(|&node| (node * per_node..(node + 1) * per_node).any(&pick))
                })
                .collect()
        })
    }

    /// `work(element)` for every element, in element order (parallel unless sequential).
    fn map_elements<T: Send>(&self, work: impl Fn(usize) -> T + Sync + Send) -> Vec<T> {
        let n = self.mesh.element_count();
        match self.parallelism {
            Parallelism::Sequential => (0..n).map(work).collect(),
            Parallelism::Chunks(_) => (0..n).into_par_iter().map(work).collect(),
        }
    }

    /// Total energy $`\Pi = \sum_t \int \psi_t`$ of the global nodal values.
    pub fn energy<S: Scalar>(&self, global: &[S]) -> S {
        let per_element = with_element!(self.mesh.kind, E => self.map_elements(|e| {
            self.element_energy::<E, { E::FUNCTIONS }, S>(e, global)
        }));
        per_element
            .into_iter()
            .fold(S::zero(), |total, value| total + value)
    }

    /// Internal forces $`\partial\Pi/\partial U_a`$ over the free dofs, from global nodal values
    /// (prescribed entries included in `global`).
    pub fn internal_forces<S: Scalar>(&self, global: &[S]) -> Vec<S> {
        self.internal_forces_where(global, None)
    }

    /// [`Self::internal_forces`] summed over the elements `e` with `elements[e]` only (every
    /// element without a mask), in the same order: the sums of those elements' contributions.
    pub fn internal_forces_where<S: Scalar>(
        &self,
        global: &[S],
        elements: Option<&[bool]>,
    ) -> Vec<S> {
        if let Some(mask) = elements {
            assert_eq!(
                mask.len(),
                self.mesh.element_count(),
                "one flag per element"
            );
        }
        with_element!(self.mesh.kind, E => {
            self.internal_forces_on::<E, { E::FUNCTIONS }, S>(global, elements)
        })
    }

    fn internal_forces_on<E: Element, const B: usize, S: Scalar>(
        &self,
        global: &[S],
        elements: Option<&[bool]>,
    ) -> Vec<S> {
        let mut out = vec![S::zero(); self.dofs.free_count];
        let wide = crate::simd::has_avx2();
        self.accumulate_where(&mut out, elements, |e, sink| {
            let element = self.element_internal_forces_wide::<E, B, S>(wide, e, global);
            self.for_each_free_dof::<E, B, S>(e, &element, |i, value| sink.add(i, value));
        });
        out
    }

    /// Internal forces and, in the same element loop, the force magnitudes
    /// $`\sum_e |f^e_a|`$ over the free dofs: the size of the element forces that meet at each
    /// dof, a per-dof scale for residuals (large where forces cancel at equilibrium, unlike the
    /// assembled internal force).
    pub fn internal_forces_and_magnitudes(&self, global: &[f64]) -> (Vec<f64>, Vec<f64>) {
        with_element!(self.mesh.kind, E => {
            self.internal_forces_and_magnitudes_on::<E, { E::FUNCTIONS }>(global)
        })
    }

    fn internal_forces_and_magnitudes_on<E: Element, const B: usize>(
        &self,
        global: &[f64],
    ) -> (Vec<f64>, Vec<f64>) {
        let n = self.dofs.free_count;
        let mut both = vec![0.0; 2 * n];
        let wide = crate::simd::has_avx2();
        self.accumulate(&mut both, |e, sink| {
            let element = self.element_internal_forces_wide::<E, B, f64>(wide, e, global);
            self.for_each_free_dof::<E, B, f64>(e, &element, |i, value| {
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
        with_element!(self.mesh.kind, E => {
            self.tangent_values_on::<E, { E::FUNCTIONS }, S>(global)
        })
    }

    fn tangent_values_on<E: Element, const B: usize, S: Scalar>(&self, global: &[S]) -> Vec<S> {
        let mut out = vec![S::zero(); self.pattern.nnz()];
        self.add_projected_tangent_values_on::<E, B, S, S>(global, &mut out, |value| value);
        out
    }

    /// Adds `project` of the tangent's values at `global` into `out` (on [`Self::pattern`]),
    /// entry by entry in the order of [`Self::tangent_values`]' sums.
    fn add_projected_tangent_values_on<E: Element, const B: usize, S: Scalar, T: Scalar>(
        &self,
        global: &[S],
        out: &mut [T],
        project: impl Fn(S) -> T + Sync + Copy,
    ) {
        assert_eq!(
            out.len(),
            self.pattern.nnz(),
            "values off the tangent's pattern"
        );
        let wide = crate::simd::has_avx2();
        self.accumulate(out, |e, sink| {
            #[cfg(target_arch = "x86_64")]
            if wide {
                // SAFETY: the processor has AVX2.
                unsafe { self.add_element_tangent_avx2::<E, B, S, T>(e, global, sink, project) };
                return;
            }
            self.add_element_tangent::<E, B, S, T>(e, global, sink, project);
        });
    }

    /// [`Self::element_internal_forces`], compiled for AVX2 when `wide` ([`crate::simd`]: the
    /// same bits).
    #[inline(always)]
    fn element_internal_forces_wide<E: Element, const B: usize, S: Scalar>(
        &self,
        wide: bool,
        e: usize,
        global: &[S],
    ) -> local::ElementLocal<S, B> {
        #[cfg(target_arch = "x86_64")]
        if wide {
            // SAFETY: `wide` says the processor has AVX2.
            return unsafe { self.element_internal_forces_avx2::<E, B, S>(e, global) };
        }
        let _ = wide;
        self.element_internal_forces::<E, B, S>(e, global)
    }

    /// [`Self::element_internal_forces`] compiled for AVX2.
    ///
    /// # Safety
    /// The processor must have AVX2 ([`crate::simd::has_avx2`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn element_internal_forces_avx2<E: Element, const B: usize, S: Scalar>(
        &self,
        e: usize,
        global: &[S],
    ) -> local::ElementLocal<S, B> {
        self.element_internal_forces::<E, B, S>(e, global)
    }

    /// Adds element `e`'s tangent to `sink`. A holds each pattern entry once (diagonal entries
    /// halved): $`K = A + A^\top`$.
    #[inline(always)]
    fn add_element_tangent<E: Element, const B: usize, S: Scalar, T: Scalar>(
        &self,
        e: usize,
        global: &[S],
        sink: &mut ElementSink<T>,
        project: impl Fn(S) -> T,
    ) {
        let element = self.element_tangent::<E, B, S>(e, global);
        self.for_each_tangent_slot::<E, B, S>(e, &element, |s, value| sink.add(s, project(value)));
    }

    /// [`Self::add_element_tangent`] compiled for AVX2 ([`crate::simd`]: the same bits).
    ///
    /// # Safety
    /// The processor must have AVX2 ([`crate::simd::has_avx2`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    unsafe fn add_element_tangent_avx2<E: Element, const B: usize, S: Scalar, T: Scalar>(
        &self,
        e: usize,
        global: &[S],
        sink: &mut ElementSink<T>,
        project: impl Fn(S) -> T,
    ) {
        self.add_element_tangent::<E, B, S, T>(e, global, sink, project);
    }

    /// Assembles the `f64` tangent into `matrix` (which must be on [`Self::pattern`]), in
    /// place: the same sums as [`Self::tangent_values`]. (Through a fresh vector and a copy, as
    /// before, every assembly also mapped a fresh copy of the values page by page: the reference
    /// envelope's path at 128 × 64, 48 MB of values, spent 0.46–0.51 s in its 9 assemblies
    /// against 0.32–0.37 s in place.)
    pub fn assemble_tangent_into(&self, global: &[f64], matrix: &mut SparseMatrix) {
        self.assemble_projected_tangent_into(global, matrix, |value| value);
    }

    /// Assembles into `matrix` (on [`Self::pattern`]) the dual parts of the tangent at the
    /// dual-number nodal values `global`: the directional derivative of the tangent along their
    /// dual parts. The dual parts add on their own, so the values are those of
    /// [`Self::tangent_values`]' dual parts, without its dual-number matrix (twice the
    /// tangent's memory, mapped afresh at each call).
    pub fn assemble_tangent_derivative_into(&self, global: &[Dual64], matrix: &mut SparseMatrix) {
        self.assemble_projected_tangent_into(global, matrix, |value| value.eps);
    }

    /// `project` of the tangent's values at `global`, assembled into `matrix` in place.
    fn assemble_projected_tangent_into<S: Scalar>(
        &self,
        global: &[S],
        matrix: &mut SparseMatrix,
        project: impl Fn(S) -> f64 + Sync + Copy,
    ) {
        matrix.values.fill(0.0);
        with_element!(self.mesh.kind, E => {
            self.add_projected_tangent_values_on::<E, { E::FUNCTIONS }, S, f64>(
                global,
                &mut matrix.values,
                project,
            )
        })
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
        let per_element = with_element!(self.mesh.kind, E => self.map_elements(|e| {
            self.element_mean_conjugates_of::<E, { E::FUNCTIONS }>(e, global, &positions, entries.len())
        }));
        (0..entries.len())
            .map(|k| per_element.iter().map(|sums| sums[k]).collect())
            .collect()
    }

    /// Calls `visit(term, element, q, point, weight, jet)` at every quadrature point of every term
    /// (for diagnostics such as ellipticity checks; `f64` only).
    pub fn for_each_quadrature_point(
        &self,
        global: &[f64],
        visit: impl FnMut(usize, usize, usize, [f64; 2], f64, &[f64]),
    ) {
        with_element!(self.mesh.kind, E => {
            self.for_each_quadrature_point_on::<E, { E::FUNCTIONS }>(global, visit)
        })
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
