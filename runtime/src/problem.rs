//! A discrete problem: model + mesh + constraints + loads, and its residual
//! $`R(U,\lambda) = \partial\Pi/\partial U - F_0 - \lambda F_1`$ over the free dofs.
//!
//! **Prescribed values** ([`DirichletCondition`], $`f_c = g_0 + \lambda g_1`$ per boundary set,
//! field and nodal component) are eliminated: the unknowns $`U`$ are the free dofs only, and
//! every evaluation first builds the global vector $`\bar U(U, \lambda)`$ whose constrained
//! entries hold their known values $`g_0 + \lambda g_1`$ ([`DofMap::expand`]). The residual is
//! the free rows of the internal forces at $`\bar U`$,
//! $$`R(U,\lambda) = f^{int}_F\big(\bar U(U,\lambda)\big) - F_0 - \lambda F_1,`$$
//! so the known values act as a right-hand side (in the linear case
//! $`R = K_{FF}U + K_{FC}(g_0 + \lambda g_1) - F_0 - \lambda F_1`$: a constant force
//! $`-K_{FC}g_0`$ and a load-proportional force $`-K_{FC}g_1`$). The tangent is
//! $`K_{FF} = \partial R/\partial U`$; the load derivative
//! $`\partial R/\partial\lambda = K_{FC}(\bar U)\,g_1 - F_1`$ includes the constrained dofs'
//! rate, by one dual-number residual evaluation ([`Problem::load_derivative`]); Newton, linear
//! buckling and Riks use only these. The ANM's Taylor mode starts at $`\bar U(U_0,\lambda_0)`$
//! and commits the order-$`k`$ coefficient of the global vector as the free $`U_k`$ with
//! constrained entries $`g_1\lambda_k`$ ([`DofMap::expand_increment`]): $`\bar U(a)`$ is the
//! series of the constrained path, so every order of the right-hand side sees the prescribed
//! motion (the constant $`g_0`$ only in the order-0 state).

use crate::fem::{
    Assembler, DirichletCondition, DofMap, ElementKind, LoadVectors, Loads, Mesh, ParameterProfile,
    TaylorTape,
};
use crate::linear::pattern::SparseMatrix;
/// Euclidean norm (re-exported from [`crate::linear::vector`], where the vector kernels live).
pub use crate::linear::vector::norm;
use crate::model::EnergyModel;
use crate::scalar::Scalar;
use num_dual::Dual64;
use std::sync::Arc;

/// Errors setting a problem up.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProblemError {
    /// Bad constraints.
    #[error(transparent)]
    Dofs(#[from] crate::fem::dofs::DofError),
    /// Degenerate element.
    #[error(transparent)]
    Jacobian(#[from] crate::fem::element::JacobianError),
    /// A load on a missing boundary set or component.
    #[error(transparent)]
    Load(#[from] crate::fem::loads::LoadError),
    /// The model's jet asks for a derivative the mesh's element does not supply (a second
    /// derivative on the $`C^0`$ Q8 element, a Y derivative on a line): refused before any
    /// work.
    #[error(
        "model `{model}` asks for `{field}.{derivative}`, which the {element} element does not supply",
        derivative = derivative.name()
    )]
    UnsupportedDerivative {
        /// Model name.
        model: &'static str,
        /// The element of the mesh.
        element: ElementKind,
        /// The field whose derivative is asked for.
        field: &'static str,
        /// The derivative asked for.
        derivative: crate::model::Derivative,
    },
    /// A term's jet is longer than the kernels' stack buffers.
    #[error(
        "model `{model}`: term `{term}` reads {length} jet entries; at most {max} are supported"
    )]
    JetTooLong {
        /// Model name.
        model: &'static str,
        /// Term name.
        term: &'static str,
        /// Its jet length.
        length: usize,
        /// The limit ([`crate::model::MAX_JET`]).
        max: usize,
    },
    /// A profile given to a parameter the model does not have, or did not declare `[varying]`.
    #[error(
        "model `{model}`: parameter `{parameter}` cannot vary over the domain (parameters declared `[varying]`: {varying})"
    )]
    ParameterNotVarying {
        /// Model name.
        model: &'static str,
        /// The parameter given a profile.
        parameter: String,
        /// The model's varying parameters, comma-separated (`none` when it has none).
        varying: String,
    },
    /// The model has more fields than the assembler's element buffers hold.
    #[error("model `{model}` has {count} fields; at most {max} are supported")]
    TooManyFields {
        /// Model name.
        model: &'static str,
        /// Its field count.
        count: usize,
        /// The limit.
        max: usize,
    },
}

/// Model, discretisation, constraints and loads.
#[derive(Debug)]
pub struct Problem<M: EnergyModel> {
    /// Element loop over the model's kernels.
    pub assembler: Assembler<M>,
    /// $`F_0`$, $`F_1`$.
    pub loads: LoadVectors,
    /// $`\|\partial R/\partial\lambda(0, 0)\|`$, computed on first use.
    load_rate_norm: std::sync::OnceLock<f64>,
    /// [`Self::load_elements`], computed on first use.
    load_elements: std::sync::OnceLock<Vec<bool>>,
    /// Values of matrices handed back ([`Self::recycle_matrix`]), at most
    /// [`MAX_RECYCLED_MATRICES`], for [`Self::new_matrix`] to reuse.
    recycled: std::sync::Mutex<Vec<Vec<f64>>>,
}

/// Most matrices' values a [`Problem`] keeps for reuse ([`Problem::recycle_matrix`]): the two
/// of a buckling analysis (its tangent and load stiffness), which become the path's tangent
/// and its spare after the threshold.
pub const MAX_RECYCLED_MATRICES: usize = 2;

impl<M: EnergyModel> Problem<M> {
    /// Builds dofs, assembler and load vectors, after checking that the mesh's element supplies
    /// every derivative the model's jet reads and that the kernels' buffers hold the model.
    pub fn new(
        model: M,
        mesh: Arc<Mesh>,
        conditions: &[DirichletCondition],
        loads: &Loads,
    ) -> Result<Self, ProblemError> {
        let field_count = M::SPEC.fields.len();
        if field_count > crate::fem::assembly::MAX_FIELDS {
            return Err(ProblemError::TooManyFields {
                model: M::SPEC.name,
                count: field_count,
                max: crate::fem::assembly::MAX_FIELDS,
            });
        }
        check_model_fits::<M>(mesh.kind)?;
        let dofs = Arc::new(DofMap::new(&mesh, field_count, conditions)?);
        let loads = LoadVectors::assemble(&mesh, &dofs, loads)?;
        let assembler = Assembler::new(model, mesh, dofs)?;
        Ok(Problem {
            assembler,
            loads,
            load_rate_norm: std::sync::OnceLock::new(),
            load_elements: std::sync::OnceLock::new(),
            recycled: std::sync::Mutex::new(Vec::new()),
        })
    }

    /// Makes the named parameters functions of position: each `(name, profile)` replaces that
    /// parameter at every quadrature point by the profile's value there
    /// ([`Assembler::set_parameter_profiles`]). Every name must be a parameter the model
    /// declares `[varying]` ([`crate::model::ModelSpec::varying_parameters`]); otherwise
    /// nothing changes.
    pub fn set_parameter_profiles(
        &mut self,
        profiles: Vec<(String, ParameterProfile)>,
    ) -> Result<(), ProblemError> {
        let spec = M::SPEC;
        let mut indexed = Vec::with_capacity(profiles.len());
        for (name, profile) in profiles {
            match spec.parameter_index(&name) {
                Some(index) if spec.parameter_may_vary(&name) => indexed.push((index, profile)),
                _ => {
                    let varying = if spec.varying_parameters.is_empty() {
                        "none".to_string()
                    } else {
                        spec.varying_parameters.join(", ")
                    };
                    return Err(ProblemError::ParameterNotVarying {
                        model: spec.name,
                        parameter: name,
                        varying,
                    });
                }
            }
        }
        self.assembler.set_parameter_profiles(indexed);
        Ok(())
    }

    /// The dof map.
    pub fn dofs(&self) -> &DofMap {
        self.assembler.dofs()
    }

    /// Number of free dofs.
    pub fn free_count(&self) -> usize {
        self.assembler.dofs().free_count
    }

    /// A zero matrix on the tangent's pattern: the values of a recycled matrix, zeroed, when
    /// there is one ([`Self::recycle_matrix`]), else fresh.
    pub fn new_matrix(&self) -> SparseMatrix {
        let pattern = self.assembler.pattern().clone();
        let recycled = self.recycled.lock().ok().and_then(|mut kept| kept.pop());
        match recycled {
            Some(mut values) => {
                values.fill(0.0);
                SparseMatrix { pattern, values }
            }
            None => SparseMatrix::zeros(pattern),
        }
    }

    /// Hands `matrix` back for [`Self::new_matrix`] to reuse its values (when on this problem's
    /// pattern and fewer than [`MAX_RECYCLED_MATRICES`] are kept; else it is dropped).
    ///
    /// A fresh matrix's memory is mapped page by page at its first assembly. A buckling
    /// analysis hands back its two matrices, so that the path after a threshold assembles into
    /// memory the threshold has mapped already.
    pub fn recycle_matrix(&self, matrix: SparseMatrix) {
        if !Arc::ptr_eq(&matrix.pattern, self.assembler.pattern())
            || matrix.values.len() != matrix.pattern.nnz()
        {
            return;
        }
        if let Ok(mut kept) = self.recycled.lock()
            && kept.len() < MAX_RECYCLED_MATRICES
        {
            kept.push(matrix.values);
        }
    }

    /// How many matrices' values are kept for reuse ([`Self::recycle_matrix`]).
    pub fn recycled_matrices(&self) -> usize {
        self.recycled.lock().map_or(0, |kept| kept.len())
    }

    /// $`R(U, \lambda)`$, generic over the scalar (series, dual numbers).
    pub fn residual<S: Scalar>(&self, free: &[S], load: S) -> Vec<S> {
        self.residual_where(free, load, None)
    }

    /// [`Self::residual`] with the internal forces of the elements `e` with `elements[e]`
    /// only (all without a mask; [`Assembler::internal_forces_where`]).
    fn residual_where<S: Scalar>(&self, free: &[S], load: S, elements: Option<&[bool]>) -> Vec<S> {
        let global = self.assembler.dofs().expand(free, load);
        let mut r = self.assembler.internal_forces_where(&global, elements);
        for (i, ri) in r.iter_mut().enumerate() {
            *ri = *ri - (load * self.loads.proportional[i] + self.loads.fixed[i]);
        }
        r
    }

    /// Taylor mode, order 0, at $`(U_0, \lambda_0)`$: see [`Assembler::taylor_start`].
    pub fn taylor_start(&self, free: &[f64], load: f64, tape: &mut TaylorTape) {
        let global = self.assembler.dofs().expand(free, load);
        self.assembler.taylor_start(&global, tape);
    }

    /// Taylor mode: the order-$`k`$ coefficient of $`R(U(a), \lambda(a))`$ with
    /// $`U_k = 0`$, $`\lambda_k = 0`$ (the loads are affine in $`\lambda`$, so only the
    /// internal forces contribute): the ANM right-hand side is its negative.
    pub fn taylor_residual(&self, order: usize, tape: &mut TaylorTape) -> Vec<f64> {
        self.assembler.taylor_predict(order, tape)
    }

    /// Taylor mode: records the order-$`k`$ coefficients $`(U_k, \lambda_k)`$ once solved.
    pub fn taylor_commit(&self, order: usize, free: &[f64], load: f64, tape: &mut TaylorTape) {
        let increment = self.assembler.dofs().expand_increment(free, load);
        self.assembler.taylor_commit(order, &increment, tape);
    }

    /// Taylor mode: [`Self::taylor_commit`] at order $`k`$ then [`Self::taylor_residual`] at
    /// order $`k + 1`$ in one sweep over the tape (the same numbers, one memory pass fewer).
    pub fn taylor_commit_then_residual(
        &self,
        order: usize,
        free: &[f64],
        load: f64,
        tape: &mut TaylorTape,
    ) -> Vec<f64> {
        let increment = self.assembler.dofs().expand_increment(free, load);
        self.assembler
            .taylor_commit_then_predict(order, &increment, tape)
    }

    /// Total potential energy $`\Pi(U) - U\cdot(F_0 + \lambda F_1)`$ (the work of prescribed
    /// displacements is not included).
    pub fn potential_energy(&self, free: &[f64], load: f64) -> f64 {
        let global = self.assembler.dofs().expand(free, load);
        let internal = self.assembler.energy(&global);
        let external: f64 = free
            .iter()
            .enumerate()
            .map(|(i, u)| u * (self.loads.fixed[i] + load * self.loads.proportional[i]))
            .sum();
        internal - external
    }

    /// Tangent $`K_t = \partial R/\partial U`$ into `matrix`.
    pub fn tangent_into(&self, free: &[f64], load: f64, matrix: &mut SparseMatrix) {
        let global = self.assembler.dofs().expand(free, load);
        self.assembler.assemble_tangent_into(&global, matrix);
    }

    /// $`\partial R/\partial\lambda`$ at fixed free dofs (includes prescribed displacements
    /// proportional to the load), by one dual-number residual evaluation over the elements the
    /// load reaches.
    ///
    /// The load enters the internal forces only through the prescribed values
    /// $`g_0 + \lambda g_1`$: an element without a dof of $`g_1 \ne 0`$ has a jet whose dual
    /// parts vanish, so its forces' dual parts are zeros, which change no sum. Those elements
    /// are left out ([`Self::load_elements`]): the same values as the whole element loop, in a
    /// fraction of its time (none at all under force control, the edges under displacement
    /// control). This derivative starts every ANM step, every Newton correction's load column
    /// and every arc-length step.
    pub fn load_derivative(&self, free: &[f64], load: f64) -> Vec<f64> {
        let free_dual: Vec<Dual64> = free.iter().map(|&u| Dual64::from_re(u)).collect();
        let r = self.residual_where(
            &free_dual,
            Dual64::new(load, 1.0),
            Some(self.load_elements()),
        );
        r.iter().map(|v| v.eps).collect()
    }

    /// The elements with a prescribed dof whose value depends on the load (one flag per
    /// element; computed on first use): the only ones whose internal forces depend on
    /// $`\lambda`$ at fixed free dofs ([`Self::load_derivative`]).
    pub fn load_elements(&self) -> &[bool] {
        self.load_elements.get_or_init(|| {
            let dofs = self.assembler.dofs();
            self.assembler
                .elements_with_dofs(|g| dofs.is_load_dependent(g))
        })
    }

    /// Directional derivative of the tangent,
    /// $`\frac{d}{d\epsilon} K_t(U + \epsilon\,\delta U, \lambda + \epsilon\,\delta\lambda)\big|_0`$,
    /// from the generated tangent kernels on dual numbers (the geometric stiffness of linear
    /// buckling).
    pub fn tangent_derivative_into(
        &self,
        free: &[f64],
        load: f64,
        direction: &[f64],
        load_direction: f64,
        matrix: &mut SparseMatrix,
    ) {
        let free_dual: Vec<Dual64> = free
            .iter()
            .zip(direction)
            .map(|(&u, &d)| Dual64::new(u, d))
            .collect();
        let global = self
            .assembler
            .dofs()
            .expand(&free_dual, Dual64::new(load, load_direction));
        self.assembler
            .assemble_tangent_derivative_into(&global, matrix);
    }

    /// Scale for relative residuals at load `load`:
    /// $`\|F_0\| + |\lambda|\,\|\partial R/\partial\lambda(0,0)\|`$ — the external force, or for
    /// displacement control the reaction of the linearised problem — or 1 when it vanishes.
    pub fn residual_scale(&self, load: f64) -> f64 {
        let rate = *self.load_rate_norm.get_or_init(|| {
            let zero = vec![0.0; self.free_count()];
            norm(&self.load_derivative(&zero, 0.0))
        });
        let s = norm(&self.loads.fixed) + load.abs() * rate;
        if s > 0.0 { s } else { 1.0 }
    }

    /// Field-balanced relative residual: $`\max_f \|R_f\| / s_f`$ over the fields $`f`$, with
    /// $`s_f`$ the norm over that field's free dofs of the element force magnitudes
    /// $`\sum_e|f^e_a|`$ plus the external force. Each field is measured against its own forces,
    /// so a small field (the envelope next to membrane forces) is held to the same relative
    /// accuracy. Each $`s_f`$ is floored at [`FIELD_SCALE_FLOOR`] times the largest field scale
    /// (a field whose forces vanish, such as $`u`$ when $`N_X = 0`$, is otherwise measured against
    /// round-off), and [`Self::residual_scale`] is used when every scale vanishes.
    pub fn relative_residual(&self, free: &[f64], load: f64) -> f64 {
        self.residual_with_relative(free, load).1
    }

    /// $`R(U,\lambda)`$ and its [`Self::relative_residual`], from one element loop.
    pub fn residual_with_relative(&self, free: &[f64], load: f64) -> (Vec<f64>, f64) {
        let dofs = self.assembler.dofs();
        let global = dofs.expand(free, load);
        let (mut residual, magnitudes) = self.assembler.internal_forces_and_magnitudes(&global);
        for (i, r) in residual.iter_mut().enumerate() {
            *r -= load * self.loads.proportional[i] + self.loads.fixed[i];
        }
        let nf = dofs.field_count;
        let mut residual_norm = vec![0.0; nf];
        let mut scale = vec![0.0; nf];
        for i in 0..residual.len() {
            let f = dofs.field_of_free(i);
            let external = (self.loads.fixed[i] + load * self.loads.proportional[i]).abs();
            residual_norm[f] += residual[i] * residual[i];
            scale[f] += (magnitudes[i] + external).powi(2);
        }
        let largest = scale.iter().cloned().fold(0.0, f64::max).sqrt();
        let floor = if largest > 0.0 {
            FIELD_SCALE_FLOOR * largest
        } else {
            self.residual_scale(load)
        };
        // An overflowed state is never "converged": NaN propagates.
        let relative =
            max_or_nan((0..nf).map(|f| residual_norm[f].sqrt() / scale[f].sqrt().max(floor)));
        (residual, relative)
    }
}

/// Refuses, before any work, a model whose jet reads a derivative the element `element` does
/// not supply, or whose term jets overflow the kernels' buffers.
fn check_model_fits<M: EnergyModel>(element: ElementKind) -> Result<(), ProblemError> {
    let spec = M::SPEC;
    if let Some(entry) = spec
        .jet
        .iter()
        .find(|entry| !element.supplies(entry.derivative))
    {
        return Err(ProblemError::UnsupportedDerivative {
            model: spec.name,
            element,
            field: spec.fields[entry.field],
            derivative: entry.derivative,
        });
    }
    if let Some(term) = spec
        .terms
        .iter()
        .find(|term| term.jet.len() > crate::model::MAX_JET)
    {
        return Err(ProblemError::JetTooLong {
            model: spec.name,
            term: term.name,
            length: term.jet.len(),
            max: crate::model::MAX_JET,
        });
    }
    Ok(())
}

/// Relative floor of the per-field residual scales in [`Problem::relative_residual`].
pub const FIELD_SCALE_FLOOR: f64 = 1e-6;

/// The largest of non-negative `values` (0 when empty), NaN if any is NaN: `f64::max` drops
/// NaN and would report an overflowed quantity as finite.
pub fn max_or_nan(values: impl IntoIterator<Item = f64>) -> f64 {
    values.into_iter().fold(0.0, |largest: f64, value| {
        if largest.is_nan() || value.is_nan() {
            f64::NAN
        } else {
            largest.max(value)
        }
    })
}
