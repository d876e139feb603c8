//! Linear buckling about the pre-buckling state, for any model.
//!
//! With $`U_0`$ the equilibrium at $`\lambda_0`$ and $`\dot U`$ its load rate
//! ($`K_t \dot U = -\partial R/\partial\lambda`$), the tangent along the fundamental path is
//! $`K_t(\lambda_0 + \mu) \approx A + \mu B`$ with $`A = K_t(U_0,\lambda_0)`$ and
//! $`B = \frac{d}{d\epsilon}K_t(U_0 + \epsilon\dot U, \lambda_0 + \epsilon)`$ — obtained from the
//! generated tangent kernels on dual numbers, never written by hand. The critical load is
//! $`\lambda_c = \lambda_0 + \mu_c`$ with $`\mu_c`$ the smallest positive root of
//! $`(A + \mu B)\varphi = 0`$ (shift-invert Lanczos). Exact when the pre-buckling path is linear
//! (flat membranes under in-plane loads).

use super::error::SolveError;
use super::linearization::{factorize_tangent, load_tangent};
use super::newton::{NewtonOptions, newton};
use crate::linear::eigen::{BucklingOptions, smallest_positive_buckling};
use crate::linear::factor::SparseFactorization;
use crate::model::EnergyModel;
use crate::problem::Problem;

/// Result of [`linear_buckling`].
#[derive(Clone, Debug)]
pub struct LinearBuckling {
    /// Critical load parameters $`\lambda_c`$, ascending (as many as asked for).
    pub critical_loads: Vec<f64>,
    /// Buckling modes (free dofs), one per critical load.
    pub modes: Vec<Vec<f64>>,
    /// Relative eigen-residuals $`\|(A+\mu B)\varphi\|/\|A\varphi\|`$.
    pub residuals: Vec<f64>,
    /// Pre-buckling state $`U_0`$ at the reference load.
    pub prebuckling: Vec<f64>,
    /// Load rate $`\dot U`$.
    pub prebuckling_rate: Vec<f64>,
    /// Lanczos iterations.
    pub eigen_iterations: usize,
}

/// Settings of [`linear_buckling`].
#[derive(Clone, Debug)]
pub struct LinearBucklingOptions {
    /// Load about which to linearise (usually 0).
    pub reference_load: f64,
    /// Newton settings for the pre-buckling state.
    pub newton: NewtonOptions,
    /// Eigen-solver settings (including an optional warm-start vector).
    pub eigen: BucklingOptions,
    /// A guess of the pre-buckling state (e.g. that of a nearby parameter value); zero when
    /// `None`.
    pub initial_state: Option<Vec<f64>>,
}

impl LinearBuckling {
    /// The pre-buckling state at `load`, $`U_0 + (\lambda - \lambda_0)\dot U`$, with
    /// $`\lambda_0`$ the `reference_load` the analysis linearised about (exact on a linear
    /// fundamental path).
    pub fn state_at(&self, reference_load: f64, load: f64) -> Vec<f64> {
        self.prebuckling
            .iter()
            .zip(&self.prebuckling_rate)
            .map(|(u, r)| u + (load - reference_load) * r)
            .collect()
    }
}

impl Default for LinearBucklingOptions {
    fn default() -> Self {
        LinearBucklingOptions {
            reference_load: 0.0,
            newton: NewtonOptions::default(),
            eigen: BucklingOptions::default(),
            initial_state: None,
        }
    }
}

/// Linear buckling analysis of `problem`. `factor` must have been analysed on the problem's
/// pattern (it is reused: the symbolic analysis is done once per pattern).
pub fn linear_buckling<M: EnergyModel>(
    problem: &Problem<M>,
    factor: &mut SparseFactorization,
    options: &LinearBucklingOptions,
) -> Result<LinearBuckling, SolveError> {
    let n = problem.free_count();
    let load = options.reference_load;
    let mut a = problem.new_matrix();
    let initial = match &options.initial_state {
        Some(state) if state.len() == n => state.clone(),
        _ => vec![0.0; n],
    };
    let pre = newton(problem, initial, load, factor, &mut a, &options.newton)?;
    factorize_tangent(problem, &pre.solution, load, &mut a, factor).map_err(SolveError::linear(
        "linear buckling: factorisation of the pre-buckling tangent",
    ))?;
    // The eigen-solver needs A positive definite: say so before assembling what it would use.
    if let Some(negative) = factor.negative_pivots().filter(|&count| count > 0) {
        return Err(SolveError::Buckling(format!(
            "linear buckling: the tangent at the reference load {load:e} has {negative} negative pivots: the reference state is already beyond a critical point"
        )));
    }
    let rate = load_tangent(problem, factor, &pre.solution, load)
        .map_err(SolveError::linear("linear buckling: load rate"))?;
    let mut b = problem.new_matrix();
    problem.tangent_derivative_into(&pre.solution, load, &rate, 1.0, &mut b);
    if b.values.iter().any(|v| !v.is_finite()) {
        return Err(SolveError::NonFinite {
            location: "geometric stiffness (directional derivative of the tangent)".into(),
        });
    }
    let solution = smallest_positive_buckling(&a, factor, &b, &options.eigen)
        .map_err(SolveError::linear("linear buckling: eigen-solver"))?;
    // Their memory is mapped: the next analysis, or the path, assembles into it.
    problem.recycle_matrix(a);
    problem.recycle_matrix(b);
    Ok(LinearBuckling {
        critical_loads: solution
            .modes
            .iter()
            .map(|m| load + m.load_factor)
            .collect(),
        residuals: solution.modes.iter().map(|m| m.residual).collect(),
        modes: solution.modes.into_iter().map(|m| m.vector).collect(),
        prebuckling: pre.solution,
        prebuckling_rate: rate,
        eigen_iterations: solution.iterations,
    })
}
