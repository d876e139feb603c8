//! Newton–Raphson at a fixed load parameter.

use super::error::SolveError;
use crate::linear::factor::SparseFactorization;
use crate::linear::pattern::SparseMatrix;
use crate::model::EnergyModel;
use crate::problem::Problem;

/// Settings of [`newton`].
#[derive(Clone, Copy, Debug)]
pub struct NewtonOptions {
    /// Accept when the field-balanced [`Problem::relative_residual`] $`\le`$ `tolerance`.
    pub tolerance: f64,
    /// Iteration cap.
    pub max_iterations: usize,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        NewtonOptions {
            tolerance: 1e-8,
            max_iterations: 25,
        }
    }
}

/// Result of [`newton`].
#[derive(Clone, Debug)]
pub struct NewtonSolution {
    /// Free dof values.
    pub solution: Vec<f64>,
    /// Iterations (tangent factorisations) made.
    pub iterations: usize,
    /// Final relative residual.
    pub relative_residual: f64,
}

/// Solves $`R(U, \lambda) = 0`$ for $`U`$ from `initial` with full Newton. The tangent is
/// refactorised each iteration on the pattern `factor` was analysed for.
pub fn newton<M: EnergyModel>(
    problem: &Problem<M>,
    initial: Vec<f64>,
    load: f64,
    factor: &mut SparseFactorization,
    matrix: &mut SparseMatrix,
    options: &NewtonOptions,
) -> Result<NewtonSolution, SolveError> {
    let mut u = initial;
    let (mut residual, mut relative) = problem.residual_with_relative(&u, load);
    let mut iterations = 0;
    while relative > options.tolerance {
        if !relative.is_finite() {
            return Err(SolveError::NonFinite {
                location: format!("Newton residual at load {load:.6e}, iteration {iterations}"),
            });
        }
        if iterations == options.max_iterations {
            return Err(SolveError::NewtonDiverged {
                load,
                iterations,
                residual: relative,
                tolerance: options.tolerance,
            });
        }
        problem.tangent_into(&u, load, matrix);
        factor
            .factorize(matrix)
            .map_err(SolveError::linear(format!(
                "Newton at load {load:.6e}, iteration {iterations}: tangent factorisation"
            )))?;
        for r in residual.iter_mut() {
            *r = -*r;
        }
        factor
            .solve_in_place(&mut residual)
            .map_err(SolveError::linear("Newton: solve"))?;
        for (ui, du) in u.iter_mut().zip(&residual) {
            *ui += du;
        }
        iterations += 1;
        (residual, relative) = problem.residual_with_relative(&u, load);
    }
    Ok(NewtonSolution {
        solution: u,
        iterations,
        relative_residual: relative,
    })
}
