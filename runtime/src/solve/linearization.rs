//! One linearisation of $`R(U, \lambda) = 0`$ at a point: the tangent
//! $`K_t = \partial R/\partial U`$ assembled and factorised, the work counted, and the load
//! tangent $`\delta U_F = -K_t^{-1}\,\partial R/\partial\lambda`$ solved with the factor.
//!
//! * [`factorize_tangent`] and [`load_tangent`]: the two operations on their own, uncounted —
//!   what Newton ([`newton`](super::newton)) and linear buckling
//!   ([`buckling`](super::buckling)) need, and the ANM's order 1.
//! * [`Linearization`]: the same operations for the path solvers (the ANM, Riks, the
//!   arc-length corrector and the landing), which count every tangent assembly,
//!   factorisation and residual evaluation, with their times, in a [`PathStatistics`].
//! * [`SpareTangent`]: a second tangent and factorisation on the same pattern (the ANM's check
//!   of a step's end), which [`Linearization::adopt`] makes the current one.
//! * [`Workspace`]: a path's matrix and spare made before the path, so that the start's Newton
//!   iterations assemble into the path's own matrix and the first step keeps their last
//!   factorisation when the tangent at the start is the same ([`same_tangent`]).

use std::time::Instant;

use super::error::SolveError;
use super::newton::{NewtonOptions, NewtonSolution, newton};
use super::path::PathStatistics;
use crate::linear::factor::{FactorizationKind, LinearError, SparseFactorization};
use crate::linear::pattern::SparseMatrix;
use crate::model::EnergyModel;
use crate::problem::Problem;

/// Assembles $`K_t(U, \lambda)`$ into `matrix` and factorises it into `factor` (uncounted).
pub fn factorize_tangent<M: EnergyModel>(
    problem: &Problem<M>,
    displacement: &[f64],
    load: f64,
    matrix: &mut SparseMatrix,
    factor: &mut SparseFactorization,
) -> Result<FactorizationKind, LinearError> {
    problem.tangent_into(displacement, load, matrix);
    factor.factorize(matrix)
}

/// The load tangent $`\delta U_F = -K_t^{-1}\,\partial R/\partial\lambda`$ at $`(U, \lambda)`$
/// with `factor` holding $`K_t`$ there (uncounted): the linear response to a unit load
/// increment, the first-order term of the ANM, the load rate of linear buckling and the
/// predictor of Riks. $`\partial R/\partial\lambda`$ comes from one dual-number residual
/// ([`Problem::load_derivative`]).
pub fn load_tangent<M: EnergyModel>(
    problem: &Problem<M>,
    factor: &SparseFactorization,
    displacement: &[f64],
    load: f64,
) -> Result<Vec<f64>, LinearError> {
    let mut tangent = problem.load_derivative(displacement, load);
    for value in tangent.iter_mut() {
        *value = -*value;
    }
    factor.solve_in_place(&mut tangent)?;
    Ok(tangent)
}

/// The tangent of a path solver: its matrix, the factorisation it refactorises (analysed once
/// for the problem's pattern), and the work counters of the path.
pub struct Linearization<'a, M: EnergyModel> {
    problem: &'a Problem<M>,
    factor: &'a mut SparseFactorization,
    matrix: SparseMatrix,
    /// Work done through this linearisation (and whatever else the path solver counts in it).
    pub statistics: PathStatistics,
}

impl<'a, M: EnergyModel> Linearization<'a, M> {
    /// A linearisation of `problem` refactorising `factor`, which must have been analysed for
    /// the problem's tangent pattern; zero counters.
    pub fn new(problem: &'a Problem<M>, factor: &'a mut SparseFactorization) -> Self {
        let matrix = problem.new_matrix();
        Self::with_matrix(problem, factor, matrix)
    }

    /// [`Self::new`] assembling into `matrix`, which must be on the problem's pattern (a
    /// [`Workspace`]'s).
    pub fn with_matrix(
        problem: &'a Problem<M>,
        factor: &'a mut SparseFactorization,
        matrix: SparseMatrix,
    ) -> Self {
        Linearization {
            problem,
            factor,
            matrix,
            statistics: PathStatistics::default(),
        }
    }

    /// The problem linearised.
    pub fn problem(&self) -> &'a Problem<M> {
        self.problem
    }

    /// The factorisation of the last tangent factorised.
    pub fn factor(&self) -> &SparseFactorization {
        self.factor
    }

    /// The last tangent assembled.
    pub fn tangent(&self) -> &SparseMatrix {
        &self.matrix
    }

    /// Negative pivots of the last factorisation (`None` without inertia: after LU).
    pub fn negative_pivots(&self) -> Option<usize> {
        self.factor.negative_pivots()
    }

    /// Assembles and factorises $`K_t(U, \lambda)`$: one tangent assembly and one
    /// factorisation counted (a failed factorisation too: its work was done), with their times.
    pub fn factorize(&mut self, displacement: &[f64], load: f64) -> Result<(), LinearError> {
        self.assemble(displacement, load, None);
        let (result, seconds) = timed_factorize(self.factor, &self.matrix);
        self.count_factorization(seconds);
        result
    }

    /// Assembles $`K_t(U, \lambda)`$ into `spare`'s matrix, or the current one without it;
    /// one tangent assembly counted, with its time.
    fn assemble(&mut self, displacement: &[f64], load: f64, spare: Option<&mut SpareTangent>) {
        let clock = Instant::now();
        let matrix = match spare {
            Some(spare) => &mut spare.matrix,
            None => &mut self.matrix,
        };
        self.problem.tangent_into(displacement, load, matrix);
        self.statistics.tangent_assemblies += 1;
        self.statistics.assembly_seconds += clock.elapsed().as_secs_f64();
    }

    fn count_factorization(&mut self, seconds: f64) {
        self.statistics.factorizations += 1;
        self.statistics.factorization_seconds += seconds;
    }

    /// Solves $`K_t x = b`$ in place with the current factorisation.
    pub fn solve_in_place(&self, rhs: &mut [f64]) -> Result<(), LinearError> {
        self.factor.solve_in_place(rhs)
    }

    /// [`load_tangent`] with the current factorisation; the dual-number
    /// $`\partial R/\partial\lambda`$ counts as one residual assembly.
    pub fn load_tangent(
        &mut self,
        displacement: &[f64],
        load: f64,
    ) -> Result<Vec<f64>, LinearError> {
        self.statistics.residual_assemblies += 1;
        load_tangent(self.problem, self.factor, displacement, load)
    }

    /// $`(R, \|R\|/\text{scale})`$ at a point ([`Problem::residual_with_relative`]), counted
    /// and timed.
    pub fn residual(&mut self, displacement: &[f64], load: f64) -> (Vec<f64>, f64) {
        let problem = self.problem;
        self.statistics
            .time_residual(|| problem.residual_with_relative(displacement, load))
    }

    /// The field-balanced relative residual at a point ([`Problem::relative_residual`]),
    /// counted and timed.
    pub fn relative_residual(&mut self, displacement: &[f64], load: f64) -> f64 {
        let problem = self.problem;
        self.statistics
            .time_residual(|| problem.relative_residual(displacement, load))
    }

    /// Runs `work` on a linearisation that shares this one's problem and factorisation (with a
    /// matrix and counters of its own), then adds its linear-algebra work to these counters
    /// ([`PathStatistics::add_linear_work`]): e.g. an arc-length correction inside an ANM step,
    /// whose Newton iterations are not the path's corrections.
    pub fn nested<T>(&mut self, work: impl FnOnce(&mut Linearization<'_, M>) -> T) -> T {
        let mut nested = Linearization::new(self.problem, &mut *self.factor);
        let result = work(&mut nested);
        self.statistics.add_linear_work(&nested.statistics);
        result
    }

    /// A second tangent and factorisation on this problem's pattern, sharing the current
    /// factorisation's symbolic analysis ([`SparseFactorization::same_analysis`]: the ordering
    /// is not computed again).
    pub fn spare(&self) -> Result<SpareTangent, LinearError> {
        Ok(SpareTangent {
            matrix: self.problem.new_matrix(),
            factor: self.factor.same_analysis()?,
        })
    }

    /// [`Self::factorize`] into `spare`, leaving the current tangent and factorisation as they
    /// are, counted the same way, with `alongside` run on the other core **during the
    /// factorisation** (after the tangent's assembly, which uses every core): the numeric
    /// factorisation is sequential, so a second, independent piece of work costs no wall time
    /// while it is shorter. Returns the factorisation's result, `alongside`'s, and the wall
    /// time `alongside` added beyond the factorisation's (0 when it finished first): the
    /// counters stay a split of the path's wall time.
    pub fn factorize_spare_alongside<T: Send>(
        &mut self,
        spare: &mut SpareTangent,
        displacement: &[f64],
        load: f64,
        alongside: impl FnOnce() -> T + Send,
    ) -> (Result<(), LinearError>, T, f64) {
        self.assemble(displacement, load, Some(&mut *spare));
        let (matrix, factor) = (&spare.matrix, &mut spare.factor);
        let both = Instant::now();
        let ((result, seconds), other) = rayon::join(|| timed_factorize(factor, matrix), alongside);
        let wall = both.elapsed().as_secs_f64();
        self.count_factorization(seconds);
        (result, other, (wall - seconds).max(0.0))
    }

    /// The first factorisation of a path whose factorisation may already hold the current
    /// matrix's (`held`: the caller's Newton iterations for the start left it there, in a
    /// [`Workspace`]): the tangent at $`(U, \lambda)`$ is assembled into `spare`'s matrix and
    /// made the current one (one assembly counted). When it equals the held one to
    /// [`HELD_TANGENT_TOLERANCE`] ([`same_tangent`]) the factorisation is kept, uncounted, and
    /// `Ok(true)` returned; otherwise (or without `held`) it is factorised as by
    /// [`Self::factorize`]. `spare`'s matrix is left with the previous one.
    ///
    /// Newton's last correction is so small at a converged start that the tangents at its
    /// last two iterates agree to $`10^{-13}`$–$`10^{-12}`$ of the largest entry on every
    /// example scene (`docs/benchmarks.md`, round twelve): the factorisation of either is the
    /// other's to within its own rounding, and the path's residual checks see no difference.
    pub fn factorize_unless_held(
        &mut self,
        displacement: &[f64],
        load: f64,
        held: bool,
        spare: &mut SpareTangent,
    ) -> Result<bool, LinearError> {
        self.assemble(displacement, load, Some(&mut *spare));
        std::mem::swap(&mut self.matrix, &mut spare.matrix);
        if held && same_tangent(&spare.matrix, &self.matrix) {
            return Ok(true);
        }
        let (result, seconds) = timed_factorize(self.factor, &self.matrix);
        self.count_factorization(seconds);
        result.map(|()| false)
    }

    /// Makes the tangent and factorisation in `spare` the current ones (and the current ones
    /// the spare).
    pub fn adopt(&mut self, spare: &mut SpareTangent) {
        std::mem::swap(&mut self.matrix, &mut spare.matrix);
        std::mem::swap(self.factor, &mut spare.factor);
    }
}

/// The memory a path's linearisation works in — the tangent's matrix, and the spare tangent and
/// factorisation of the ANM's end checks — made before the path, so that the start's Newton
/// iterations assemble into the path's own matrix ([`Self::newton`]) and the path keeps
/// their last factorisation for its first step when the tangent at the start is the same
/// ([`Linearization::factorize_unless_held`]).
pub struct Workspace {
    matrix: SparseMatrix,
    spare: SpareTangent,
    held: bool,
}

impl Workspace {
    /// The buffers for a path of `problem` with `factor` (analysed for its pattern); nothing
    /// is touched yet.
    pub fn new<M: EnergyModel>(
        problem: &Problem<M>,
        factor: &SparseFactorization,
    ) -> Result<Self, LinearError> {
        Ok(Workspace {
            matrix: problem.new_matrix(),
            spare: SpareTangent {
                matrix: problem.new_matrix(),
                factor: factor.same_analysis()?,
            },
            held: false,
        })
    }

    /// Newton for the path's start ([`newton`](super::newton::newton)), assembling into the
    /// path's own matrix: when it iterated, `factor` is left holding the factorisation of its
    /// last tangent, and the path's first step keeps it when the tangent at the start is the
    /// same ([`Linearization::factorize_unless_held`]).
    pub fn newton<M: EnergyModel>(
        &mut self,
        problem: &Problem<M>,
        initial: Vec<f64>,
        load: f64,
        factor: &mut SparseFactorization,
        options: &NewtonOptions,
    ) -> Result<NewtonSolution, SolveError> {
        self.held = false;
        let solution = newton(problem, initial, load, factor, &mut self.matrix, options)?;
        self.held = solution.iterations > 0;
        Ok(solution)
    }

    /// [`Self::newton`] in `workspace` when there is one, else Newton assembling into a matrix
    /// of its own.
    pub fn newton_in<M: EnergyModel>(
        workspace: Option<&mut Self>,
        problem: &Problem<M>,
        initial: Vec<f64>,
        load: f64,
        factor: &mut SparseFactorization,
        options: &NewtonOptions,
    ) -> Result<NewtonSolution, SolveError> {
        match workspace {
            Some(workspace) => workspace.newton(problem, initial, load, factor, options),
            None => newton(
                problem,
                initial,
                load,
                factor,
                &mut problem.new_matrix(),
                options,
            ),
        }
    }

    /// Whether its spare factorisation was made for `factor`'s analysis.
    pub fn fits(&self, factor: &SparseFactorization) -> bool {
        self.spare.factor.shares_analysis(factor)
    }

    /// The tangent's matrix, the spare, and whether the factorisation holds the matrix's.
    pub fn into_parts(self) -> (SparseMatrix, SpareTangent, bool) {
        (self.matrix, self.spare, self.held)
    }
}

/// Largest entry-wise difference between two tangents, relative to the largest entry of the
/// first, below which [`Linearization::factorize_unless_held`] keeps a factorisation of one for
/// the other. A hundred times the differences measured after Newton's last correction on the
/// example scenes (at most $`8\cdot10^{-13}`$, the long strip), and far below what the path
/// resolves: a tangent off by $`\delta K`$ changes a step's series by about
/// $`K^{-1}\delta K\,U_n`$, which the step's residual checks (tolerance $`10^{-6}`$) would
/// see long before the loads do.
pub const HELD_TANGENT_TOLERANCE: f64 = 1e-10;

/// Whether `candidate` has `held`'s pattern and its values to [`HELD_TANGENT_TOLERANCE`] of
/// `held`'s largest entry (a non-finite entry never matches).
pub fn same_tangent(held: &SparseMatrix, candidate: &SparseMatrix) -> bool {
    let same_pattern = std::sync::Arc::ptr_eq(&held.pattern, &candidate.pattern)
        || held.pattern == candidate.pattern;
    if !same_pattern || held.values.len() != candidate.values.len() {
        return false;
    }
    let scale = held.values.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let bound = HELD_TANGENT_TOLERANCE * scale;
    scale.is_finite()
        && scale > 0.0
        && held
            .values
            .iter()
            .zip(&candidate.values)
            // `<=` is false for NaN: a non-finite entry never matches.
            .all(|(a, b)| (a - b).abs() <= bound)
}

/// Factorises `matrix` into `factor` (uncounted), with the seconds it took.
fn timed_factorize(
    factor: &mut SparseFactorization,
    matrix: &SparseMatrix,
) -> (Result<(), LinearError>, f64) {
    let clock = Instant::now();
    let result = factor.factorize(matrix).map(|_| ());
    (result, clock.elapsed().as_secs_f64())
}

/// A tangent and its factorisation kept beside a [`Linearization`]'s
/// ([`Linearization::spare`]).
pub struct SpareTangent {
    matrix: SparseMatrix,
    factor: SparseFactorization,
}

impl SpareTangent {
    /// Negative pivots of its factorisation (`None` without inertia: after LU).
    pub fn negative_pivots(&self) -> Option<usize> {
        self.factor.negative_pivots()
    }
}
