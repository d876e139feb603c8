//! Newton–Raphson at a fixed load parameter.

use super::error::SolveError;
use super::linearization::factorize_tangent;
use crate::linear::factor::SparseFactorization;
use crate::linear::pattern::SparseMatrix;
use crate::linear::vector::norm;
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

/// Relative size $`\|\delta U\|/\|U\|`$ of a Newton correction below which the iterate is fixed
/// to working precision (about 45 units in the last place): further iterations only stir
/// round-off.
pub const ROUND_OFF_CORRECTION: f64 = 1e-14;

/// Factor by which the relative residual may exceed the tolerance when Newton stops at
/// round-off ([`ROUND_OFF_CORRECTION`]).
///
/// The field-balanced residual measures a field whose forces vanish (the in-plane $`u`$ at
/// $`\lambda = 0`$) against $`10^{-6}`$ of the largest field scale
/// ([`crate::problem::FIELD_SCALE_FLOOR`]), i.e. to about $`10^{-14}`$ of the largest forces;
/// with the conditioning of a nearly incompressible or auxetic sheet (area against shear
/// modulus, $`(1-\nu)/(1+\nu) = 19`$ at $`\nu = -0.9`$) round-off sits there: measured
/// $`1.6`$–$`1.8\cdot10^{-8}`$ against the tolerance $`10^{-8}`$ on example 1 at
/// $`\nu = -0.9`$ (32 × 16), with corrections of $`10^{-16}\|U\|`$ for 23 iterations.
/// A residual more than 100 times the tolerance is not round-off and still fails.
pub const ROUND_OFF_ALLOWANCE: f64 = 100.0;

/// Solves $`R(U, \lambda) = 0`$ for $`U`$ from `initial` with full Newton. The tangent is
/// refactorised each iteration on the pattern `factor` was analysed for. Stops when the
/// relative residual is at `options.tolerance`, or when a correction is at round-off
/// ([`ROUND_OFF_CORRECTION`]) with the residual within [`ROUND_OFF_ALLOWANCE`] of the
/// tolerance (the returned `relative_residual` then says how far above it).
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
        factorize_tangent(problem, &u, load, matrix, factor).map_err(SolveError::linear(
            format!("Newton at load {load:.6e}, iteration {iterations}: tangent factorisation"),
        ))?;
        for r in residual.iter_mut() {
            *r = -*r;
        }
        factor
            .solve_in_place(&mut residual)
            .map_err(SolveError::linear("Newton: solve"))?;
        for (ui, du) in u.iter_mut().zip(&residual) {
            *ui += du;
        }
        let correction = norm(&residual) / norm(&u).max(f64::MIN_POSITIVE);
        iterations += 1;
        (residual, relative) = problem.residual_with_relative(&u, load);
        if correction <= ROUND_OFF_CORRECTION && relative <= ROUND_OFF_ALLOWANCE * options.tolerance
        {
            // Fixed to working precision: further iterations only stir round-off.
            break;
        }
    }
    Ok(NewtonSolution {
        solution: u,
        iterations,
        relative_residual: relative,
    })
}
