//! The kernel contract: what a model declared with `wrinkle_macros::energy_model!` generates,
//! and what every part of the runtime (assembly, Newton, buckling, ANM, Riks) consumes.
//!
//! A model is an energy density $`\psi(\mathbf{j}; \mathbf{p})`$ of a *jet* $`\mathbf{j}`$ —
//! the values and first derivatives of its fields at a point — and named parameters
//! $`\mathbf{p}`$. The density is a sum of *terms*, each integrated with its own quadrature
//! rule and depending on a subset of the jet:
//! $$`\Pi(U) = \sum_t \int_\Omega \psi_t(\mathbf{j}_t(U))\,d\Omega .`$$
//! For every term the generated code provides the triad energy → residual
//! $`r_i = \partial\psi_t/\partial j_i`$ → tangent $`k_{ij} = \partial^2\psi_t/\partial j_i\partial j_j`$,
//! all generic over [`Scalar`].

use crate::scalar::Scalar;

/// Which derivative of a field a jet entry holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Derivative {
    /// The field value $`f`$.
    Value,
    /// $`\partial f/\partial X`$.
    X,
    /// $`\partial f/\partial Y`$.
    Y,
}

/// One entry of a model's jet: a field and one of its derivatives.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct JetEntry {
    /// Index into [`ModelSpec::fields`].
    pub field: usize,
    /// Which derivative.
    pub derivative: Derivative,
}

/// Quadrature rule a term is integrated with on the Q8 element.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum QuadratureRule {
    /// 3×3 Gauss–Legendre (exact for the Q8 mass matrix; the default).
    Full,
    /// 2×2 Gauss–Legendre (reduced integration, e.g. transverse shear of Reissner–Mindlin).
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
    /// Runtime parameters, in the order [`EnergyModel::from_parameters`] takes them.
    pub parameters: &'static [&'static str],
    /// The model-level jet: every (field, derivative) that some term uses, sorted by field then
    /// derivative. The runtime evaluates nothing else.
    pub jet: &'static [JetEntry],
    /// The density terms.
    pub terms: &'static [TermSpec],
    /// Why the e-graph simplification of each kernel stopped, and its sizes (human readable).
    pub simplification_report: &'static str,
}

impl ModelSpec {
    /// Index of a parameter by name.
    pub fn parameter_index(&self, name: &str) -> Option<usize> {
        self.parameters.iter().position(|p| *p == name)
    }
    /// Index of a field by name.
    pub fn field_index(&self, name: &str) -> Option<usize> {
        self.fields.iter().position(|f| *f == name)
    }
    /// Whether any term needs the first derivatives of `field`.
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
