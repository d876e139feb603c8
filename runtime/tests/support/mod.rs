//! A hand-written nonlinear-spring energy on a strip in uniaxial tension, whose path is known
//! exactly (the model of `riks_paths.rs`):
//! $`\psi(\varepsilon) = \tfrac12 k\varepsilon^2 - \tfrac13 b\varepsilon^3 + \tfrac14 c\varepsilon^4`$,
//! $`\varepsilon = \partial u/\partial X`$. With $`u = 0`$ on `left` and a traction $`\lambda`$ on
//! `right`, every path point is the uniform strain $`u = \varepsilon X`$ with
//! $`\lambda = \sigma(\varepsilon) = k\varepsilon - b\varepsilon^2 + c\varepsilon^3`$.

use std::sync::Arc;

use wrinkle_runtime::fem::{DirichletCondition, EdgeTraction, Loads, Mesh};
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::path::PathState;
use wrinkle_runtime::{
    Derivative, EnergyModel, FieldRole, JetEntry, ModelSpec, QuadratureRule, Scalar, TermSpec,
};

/// One field `u`, one term depending on $`\partial u/\partial X`$.
static TERMS: [TermSpec; 1] = [TermSpec {
    name: "spring",
    quadrature: QuadratureRule::Full,
    jet: &[0],
    tangent_pattern: &[(0, 0)],
    taylor_slots: 1,
    linear_residual: false,
}];

static SPEC: ModelSpec = ModelSpec {
    name: "test-nonlinear-spring",
    description: "1-field nonlinear spring ½kε² − ⅓bε³ + ¼cε⁴ of ε = ∂u/∂X",
    fields: &["u"],
    field_roles: &[FieldRole::DisplacementX],
    parameters: &["k", "b", "c"],
    varying_parameters: &[],
    jet: &[JetEntry {
        field: 0,
        derivative: Derivative::X,
    }],
    terms: &TERMS,
    simplification_report: "hand-written",
    derivation: None,
};

/// The spring's constants.
#[derive(Clone, Debug)]
pub struct NonlinearSpring {
    pub k: f64,
    pub b: f64,
    pub c: f64,
}

impl NonlinearSpring {
    /// Exact stress $`\sigma(\varepsilon)`$ (= the load on the path).
    pub fn stress(&self, strain: f64) -> f64 {
        self.k * strain - self.b * strain * strain + self.c * strain.powi(3)
    }
}

impl EnergyModel for NonlinearSpring {
    const SPEC: &'static ModelSpec = &SPEC;

    fn from_parameters(values: &[f64]) -> Self {
        NonlinearSpring {
            k: values[0],
            b: values[1],
            c: values[2],
        }
    }

    fn parameter_values(&self) -> Vec<f64> {
        vec![self.k, self.b, self.c]
    }

    fn energy<S: Scalar>(&self, _term: usize, jet: &[S]) -> S {
        let e = jet[0];
        e * e * (0.5 * self.k) - e.powi(3) * (self.b / 3.0) + e.powi(4) * (0.25 * self.c)
    }

    fn residual<S: Scalar>(&self, _term: usize, jet: &[S], out: &mut [S]) {
        let e = jet[0];
        out[0] = e * self.k - e * e * self.b + e.powi(3) * self.c;
    }

    fn tangent<S: Scalar>(&self, _term: usize, jet: &[S], out: &mut [S]) {
        let e = jet[0];
        out[0] = -(e * (2.0 * self.b)) + e * e * (3.0 * self.c) + self.k;
    }
}

/// Length of the strip.
pub const LENGTH: f64 = 2.0;

/// Strip `[0, 2] × [0, 1]` of `elements` Q8 elements, `u = 0` on `left`, traction $`\lambda`$
/// on `right`.
pub fn strip_problem(model: NonlinearSpring, elements: usize) -> Problem<NonlinearSpring> {
    let mesh = Mesh::rectangle(LENGTH, 1.0, elements, 1, 1.0).unwrap();
    let conditions = [DirichletCondition::fixed("left", 0)];
    let tractions = [EdgeTraction {
        edge: "right".into(),
        fields: [0, 0],
        traction: [1.0, 0.0],
        proportional: true,
    }];
    let loads = Loads {
        tractions: tractions.to_vec(),
        ..Loads::default()
    };
    Problem::new(model, Arc::new(mesh), &conditions, &loads).unwrap()
}

/// The strain $`\varepsilon`$ of a state on the strip: $`u/X`$ at the free dof furthest from
/// `left`.
pub fn strain(problem: &Problem<NonlinearSpring>, state: &PathState) -> f64 {
    let mesh = problem.assembler.mesh();
    let (index, x_max) = (0..problem.free_count())
        .map(|i| (i, mesh.nodes[problem.dofs().global_of_free(i)][0]))
        .fold(
            (0, 0.0),
            |best, (i, x)| if x > best.1 { (i, x) } else { best },
        );
    state.displacement[index] / x_max
}

/// Asserts that `state` lies on the exact path, $`\lambda = \sigma(\varepsilon)`$ to `1e-8`.
pub fn assert_on_exact_path(problem: &Problem<NonlinearSpring>, state: &PathState) {
    let exact = problem.assembler.model().stress(strain(problem, state));
    assert!(
        (state.load - exact).abs() <= 1e-8 * (1.0 + exact.abs()),
        "load {} off the exact path σ = {exact}",
        state.load
    );
}
