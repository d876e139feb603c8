//! The kernel contract: what a model declared with `wrinkle_macros::energy_model!` generates,
//! and what every part of the runtime (assembly, Newton, buckling, ANM, Riks) consumes.
//!
//! A model is an energy density $`\psi(\mathbf{j}; \mathbf{p})`$ of a *jet* $`\mathbf{j}`$ —
//! the values and derivatives (first, and second where the element supplies them) of its
//! fields at a point — and named parameters
//! $`\mathbf{p}`$. The density is a sum of *terms*, each integrated with its own quadrature
//! rule and depending on a subset of the jet:
//! $$`\Pi(U) = \sum_t \int_\Omega \psi_t(\mathbf{j}_t(U))\,d\Omega .`$$
//! For every term the generated code provides the triad energy → residual
//! $`r_i = \partial\psi_t/\partial j_i`$ → tangent $`k_{ij} = \partial^2\psi_t/\partial j_i\partial j_j`$,
//! all generic over [`Scalar`].
//!
//! The vocabulary the DSL engine writes into a [`ModelSpec`] — [`FieldRole`], [`Derivative`],
//! [`JetEntry`] — is defined once in the `wrinkle-contract` crate, which the engine depends on
//! too, and re-exported here. This module owns the sizes every kernel call fits in
//! ([`MAX_FIELDS`], [`MAX_JET`]); assembly imports them from here.

use crate::scalar::Scalar;
use crate::series::Series;

pub use wrinkle_contract::{Derivative, FieldRole, JetEntry};

/// Most fields a model may have (element buffers are on the stack).
pub const MAX_FIELDS: usize = 8;
/// Longest term jet: a value and two derivatives for each of [`MAX_FIELDS`] fields (the
/// kernels' stack buffers are this long; [`crate::problem::Problem::new`] refuses a longer
/// term jet, which only second derivatives of many fields can make).
pub const MAX_JET: usize = 3 * MAX_FIELDS;

/// Quadrature rule a term is integrated with; each element says what it is
/// ([`Element::quadrature`](crate::fem::Element::quadrature)).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QuadratureRule {
    /// Exact for the element's mass matrix (the default): 3×3 Gauss–Legendre on Q8, 3 points
    /// on Line3, 4 on Hermite2.
    Full,
    /// One order lower (reduced integration, e.g. transverse shear of Reissner–Mindlin): 2×2
    /// on Q8, 2 points on the lines.
    Reduced,
}

/// One energy-density term of a model.
#[derive(Clone, Copy, Debug)]
pub struct TermSpec {
    /// Name given in the declaration (or `term0`, `term1`, … when unnamed).
    pub name: &'static str,
    /// Quadrature rule of this term.
    pub quadrature: QuadratureRule,
    /// The jet entries this term depends on, as ascending indices into [`ModelSpec::jet`].
    /// Kernels of this term take and return *term-local* arrays of this length, in this order.
    pub jet: &'static [usize],
    /// Structurally non-zero entries $`(i, j)`$, $`i \le j`$, of the term's Hessian in
    /// term-local jet indices. The tangent kernel writes them in this order; the Hessian is
    /// symmetric, so $`(j, i)`$ holds the same value.
    pub tangent_pattern: &'static [(usize, usize)],
    /// Number of tape slots per quadrature point the term's Taylor-mode kernels use
    /// ([`EnergyModel::taylor_start`]): one per jet-dependent intermediate whose coefficient
    /// history a recurrence reads. The default (hand-written) kernels store the jet itself, so
    /// they need `jet.len()` slots.
    pub taylor_slots: usize,
    /// Whether the term's residual is linear (affine) in the jet. Its Taylor coefficients of
    /// order $`k \ge 1`$ then vanish when the order-$`k`$ jet does, so the ANM right-hand sides
    /// skip it and it needs no tape.
    pub linear_residual: bool,
}

/// Everything about a model that is known at compile time.
#[derive(Clone, Copy, Debug)]
pub struct ModelSpec {
    /// Registry name, e.g. `"reference-envelope"`.
    pub name: &'static str,
    /// One-line description (`wrinkle models` prints it).
    pub description: &'static str,
    /// Unknown fields in dof order, e.g. `["u", "v", "w"]`.
    pub fields: &'static [&'static str],
    /// The role of each field, in [`Self::fields`] order.
    pub field_roles: &'static [FieldRole],
    /// Runtime parameters, in the order [`EnergyModel::from_parameters`] takes them.
    pub parameters: &'static [&'static str],
    /// The parameters declared `[varying]`: those the runtime may make functions of the
    /// position, evaluated at each quadrature point
    /// ([`ParameterProfile`](crate::fem::ParameterProfile)); the model's density then reads
    /// the local value (a foundation $`c(X)`$ that varies slowly along a beam).
    pub varying_parameters: &'static [&'static str],
    /// The model-level jet: every (field, derivative) that some term uses, sorted by field then
    /// derivative. The runtime evaluates nothing else.
    pub jet: &'static [JetEntry],
    /// The density terms.
    pub terms: &'static [TermSpec],
    /// Why the e-graph simplification of each kernel stopped, and its sizes (human readable).
    pub simplification_report: &'static str,
    /// For a model the DSL derived from a microscopic energy (an `ansatz`, `docs/dsl.md`): its
    /// provenance (the microscopic energy and the ansatz), the derived densities in DSL syntax
    /// and the derivation's sizes (human readable). `None` for a hand-written model.
    pub derivation: Option<&'static str>,
}

impl ModelSpec {
    /// Index of a parameter by name.
    pub fn parameter_index(&self, name: &str) -> Option<usize> {
        self.parameters.iter().position(|p| *p == name)
    }
    /// Whether the parameter `name` is declared `[varying]` (may be a function of position).
    pub fn parameter_may_vary(&self, name: &str) -> bool {
        self.varying_parameters.contains(&name)
    }
    /// Index of a field by name.
    pub fn field_index(&self, name: &str) -> Option<usize> {
        self.fields.iter().position(|f| *f == name)
    }
    /// Index of the field with `role`, if the model has one.
    pub fn field_with_role(&self, role: FieldRole) -> Option<usize> {
        self.field_roles.iter().position(|r| *r == role)
    }
    /// Whether any term needs a derivative (first or second) of `field`.
    pub fn needs_gradient(&self, field: usize) -> bool {
        self.jet
            .iter()
            .any(|e| e.field == field && e.derivative != Derivative::Value)
    }
}

/// A model instance: generated kernels plus the values of its named parameters.
///
/// Implemented by the code `energy_model!` generates; hand-written implementations (tests,
/// special models) must honour the same conventions.
pub trait EnergyModel: Clone + Send + Sync + 'static {
    /// Compile-time description of the model.
    const SPEC: &'static ModelSpec;

    /// Builds an instance from parameter values in [`ModelSpec::parameters`] order.
    fn from_parameters(values: &[f64]) -> Self;

    /// Current parameter values, in [`ModelSpec::parameters`] order.
    fn parameter_values(&self) -> Vec<f64>;

    /// $`\psi_t(\mathbf{j}_t)`$ for term `term`; `jet.len() == SPEC.terms[term].jet.len()`.
    fn energy<S: Scalar>(&self, term: usize, jet: &[S]) -> S;

    /// $`\partial\psi_t/\partial j_i`$ for every term-local jet entry, written to `out`
    /// (`out.len() == jet.len()`).
    fn residual<S: Scalar>(&self, term: usize, jet: &[S], out: &mut [S]);

    /// $`\partial^2\psi_t/\partial j_i \partial j_j`$ for the term's
    /// [`TermSpec::tangent_pattern`], in that order
    /// (`out.len() == tangent_pattern.len()`).
    fn tangent<S: Scalar>(&self, term: usize, jet: &[S], out: &mut [S]);

    /// Taylor mode, order 0: evaluates the term at the jet $`\mathbf{j}_0`$ (term-local, `f64`)
    /// and records on `tape` the order-0 coefficient of every stored intermediate.
    ///
    /// **Tape layout**: one row per order, [`TermSpec::taylor_slots`] slots per row: slot
    /// $`s`$, order $`k`$ is `tape[k * stride + s]` (`stride` ≥ the slots; the tape holds the
    /// rows up to the highest order). Order $`k`$ reads the contiguous rows $`0..k`$ and writes
    /// row $`k`$.
    ///
    /// With the three Taylor-mode kernels the coefficients of the residual along a jet series
    /// $`\mathbf{j}(a) = \sum_k \mathbf{j}_k a^k`$ are computed order by order, each from the
    /// lower orders on the tape at $`O(k)`$ per product:
    /// [`Self::taylor_predict`] gives the order-$`k`$ residual coefficient with
    /// $`\mathbf{j}_k = 0`$ (the ANM right-hand side), [`Self::taylor_commit`] then records the
    /// true order-$`k`$ coefficients once $`\mathbf{j}_k`$ is known — they are affine in
    /// $`\mathbf{j}_k`$, with the slope of the order-0 derivative.
    ///
    /// The default implementation (for hand-written models) stores the jet history and
    /// evaluates [`Self::residual`] on truncated [`Series`]; the code generator overrides all
    /// three kernels with straight-line recurrences.
    fn taylor_start(&self, _term: usize, jet: &[f64], tape: &mut [f64], _stride: usize) {
        for (i, &value) in jet.iter().enumerate() {
            tape[i] = value;
        }
    }

    /// Taylor mode, order $`k \ge 1`$: the order-$`k`$ coefficient of the residual
    /// $`\partial\psi_t/\partial j_i`$ for $`\mathbf{j}_k = 0`$, written to `out` (term-local,
    /// `out.len() == jet.len()`), from orders $`0..k-1`$ on the tape; records the predicted
    /// order-$`k`$ coefficients that [`Self::taylor_commit`] completes. See
    /// [`Self::taylor_start`].
    fn taylor_predict(
        &self,
        term: usize,
        order: usize,
        tape: &mut [f64],
        stride: usize,
        out: &mut [f64],
    ) {
        let m = out.len();
        let mut jet = [Series::zeros(1); MAX_JET];
        for (i, series) in jet[..m].iter_mut().enumerate() {
            let mut coefficients: Vec<f64> = (0..=order).map(|k| tape[k * stride + i]).collect();
            coefficients[order] = 0.0;
            *series = Series::from_coefficients(&coefficients)
                .expect("ANM orders stay below the series capacity");
        }
        let mut residual = [Series::zeros(1); MAX_JET];
        self.residual(term, &jet[..m], &mut residual[..m]);
        for (o, r) in out.iter_mut().zip(&residual[..m]) {
            *o = r.coefficient(order);
        }
    }

    /// Taylor mode, order $`k \ge 1`$, after [`Self::taylor_predict`] at the same order:
    /// records the true order-$`k`$ coefficients for the order-$`k`$ jet `jet` (term-local).
    fn taylor_commit(
        &self,
        _term: usize,
        order: usize,
        jet: &[f64],
        tape: &mut [f64],
        stride: usize,
    ) {
        for (i, &value) in jet.iter().enumerate() {
            tape[order * stride + i] = value;
        }
    }

    /// Sets one parameter by name; `Err` lists the valid names.
    fn set_parameter(&mut self, name: &str, value: f64) -> Result<(), String> {
        let spec = Self::SPEC;
        match spec.parameter_index(name) {
            Some(i) => {
                let mut values = self.parameter_values();
                values[i] = value;
                *self = Self::from_parameters(&values);
                Ok(())
            }
            None => Err(format!(
                "model `{}` has no parameter `{}` (parameters: {})",
                spec.name,
                name,
                spec.parameters.join(", ")
            )),
        }
    }

    /// Value of one parameter by name.
    fn parameter(&self, name: &str) -> Option<f64> {
        Self::SPEC
            .parameter_index(name)
            .map(|i| self.parameter_values()[i])
    }
}
