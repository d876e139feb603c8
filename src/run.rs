//! `wrinkle run`: scene → problem → threshold → imperfection → path → outputs.
//!
//! The problem is built **once**: the threshold (linear buckling, minimised over $`Q`$ for an
//! envelope model with `wavenumber = "auto"`) is found on it, then the imperfection is added to
//! its fixed loads — for envelope models by default the paper's uniform load on the envelope,
//! otherwise (`solver.imperfection = "mode"`, and always for the plate, where a uniform load
//! does not excite the antisymmetric mode) $`F = \varepsilon K_0\varphi`$ shaped like the first
//! mode $`\varphi`$, with the physical amplitude `solver.perturbation`·h on the unloaded
//! sheet — and the path is traced from the
//! equilibrium at $`\lambda = 0`$ with the ANM or Riks. The solver never writes files: a
//! `PathRecorder` keeps what the outputs need in a [`Trace`], [`RunSummary::new`] decides the
//! result from it, and [`crate::run_outputs`] writes them.

use crate::compare::AMPLITUDE_LEVELS;
use crate::error::{Error, output_directory_error};
use crate::output::{PathPoint, Progress, ProgressSink, ProgressTarget, Quantity, RunDirectory};
use crate::physics::{Layout, Snapshot};
pub use crate::results::{
    AppliedImperfection, RunContext, RunOutcome, RunReport, RunSummary, Snap, Trace,
};
use crate::scene::{Imperfection, LoadKind, PathMethod, Scene, Wavenumber};
use crate::setup::{build_problem, configure_model, layout_of, unknown_model};
use crate::threshold::{
    Threshold, ThresholdOptions, analyse, closed_form_threshold, find_threshold_with,
};
use std::path::Path;
use std::time::Instant;
use wrinkle_models::{ModelVisitor, with_model};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::{BodyLoad, LoadVectors, Loads, Mesh};
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::anm::AnmOptions;
use wrinkle_runtime::solve::ellipticity::{EllipticityReport, legendre_hadamard};
use wrinkle_runtime::solve::follow::{
    FollowMethod, FollowOptions, FollowedPath, PathObserver, follow_path_in_workspace,
};
use wrinkle_runtime::solve::landing::parameter_on_step;
use wrinkle_runtime::solve::linearization::Workspace;
use wrinkle_runtime::solve::newton::NewtonOptions;
use wrinkle_runtime::solve::path::{
    OnStep, PathControl, PathEvent, PathResult, PathState, PathStop,
};
use wrinkle_runtime::solve::riks::{AmplitudeControl, RiksOptions};

/// Path following of a scene, writing its outputs into `output_directory`. Progress goes to
/// standard error unless `quiet`.
pub fn run(scene: &Scene, output_directory: &Path, quiet: bool) -> Result<RunReport, Error> {
    let options = ThresholdOptions {
        quiet,
        ..ThresholdOptions::default()
    };
    run_with(scene, output_directory, &options)
}

/// [`run`] with the options of its threshold: the wavenumber search replaced by one analysis at
/// the wavenumber of an earlier threshold of the same scene ([`ThresholdOptions::prior`],
/// `--threshold FILE`), a wavenumber model shared with other runs
/// ([`ThresholdOptions::wavenumber_model`], `wrinkle compare`). `options.quiet` silences the
/// path's progress too.
///
/// The output directory is locked and checked first ([`RunDirectory::open`]): a second run
/// into it fails at once, before any work; the outputs are written beside it and swapped in
/// whole at the end, so that a run that fails or is killed leaves the previous run in place.
pub fn run_with(
    scene: &Scene,
    output_directory: &Path,
    options: &ThresholdOptions,
) -> Result<RunReport, Error> {
    let visitor = RunVisitor {
        scene,
        directory: RunDirectory::open(output_directory)
            .map_err(output_directory_error(output_directory))?,
        given: output_directory,
        options,
    };
    with_model(&scene.model.name, visitor).unwrap_or_else(|| Err(unknown_model(scene)))
}

struct RunVisitor<'a> {
    scene: &'a Scene,
    directory: RunDirectory,
    given: &'a Path,
    options: &'a ThresholdOptions<'a>,
}

impl ModelVisitor for RunVisitor<'_> {
    type Output = Result<RunReport, Error>;

    fn visit<M: EnergyModel>(self, mut model: M) -> Self::Output {
        let scene = self.scene;
        let quiet = self.options.quiet;
        let begin = Instant::now();
        // Without a reset the mark would be the process's, not this run's (a bench runs many).
        let peak_tracked = crate::memory::reset_peak();
        let q = match scene.model.wavenumber {
            Wavenumber::Fixed(q) => q,
            Wavenumber::Auto => 1.0,
        };
        configure_model(scene, &mut model, q)?;
        let layout = layout_of::<M>(scene)?;
        let mut problem = build_problem(scene, model)?;
        let mut factor = analyse(&problem)?;
        let threshold = find_threshold_with(scene, &mut problem, &mut factor, self.options)?;
        // The path's buffers; the start's Newton assembles into them.
        let workspace = Workspace::new(&problem, &factor).ok();
        let (imperfection, response) = add_imperfection(scene, &mut problem, &layout, &threshold)?;
        let _phase = crate::interrupt::PathPhase::enter();
        let trace = trace_path(
            scene,
            &problem,
            &mut factor,
            &layout,
            &threshold,
            (response.as_deref(), workspace),
            quiet,
        )?;
        let context = RunContext {
            scene,
            spec: M::SPEC,
            layout: &layout,
            mesh: problem.assembler.mesh(),
            threshold: &threshold,
            imperfection: imperfection.amplitude,
            imperfection_shape: imperfection.shape,
            dofs: problem.free_count(),
            seconds: begin.elapsed().as_secs_f64(),
            peak_memory: peak_tracked
                .then(crate::memory::peak_resident_bytes)
                .flatten(),
        };
        let mut summary = RunSummary::new(&context, &trace);
        summary
            .notices
            .extend(self.directory.notes().iter().map(|note| {
                crate::output::Warning::new(crate::output::Severity::Note, "output directory", note)
            }));
        crate::run_outputs::write_run(&context, &trace, summary, self.directory, self.given)
    }
}

/// Adds the imperfection of `solver.imperfection` to the fixed loads: uniform (it needs the
/// wavenumber of an envelope model) or mode-shaped — for `"auto"` uniform for envelope models,
/// the mode for the others; a `"uniform"` asked of a model without a wavenumber (the plate)
/// is the mode, and [`AppliedImperfection::shape`] says so. Returns with it the linear response
/// of the unloaded sheet to the imperfection when it is known without a solve (the mode's:
/// $`\varepsilon\varphi`$), where the path's start is sought from.
fn add_imperfection<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    layout: &Layout,
    threshold: &Threshold,
) -> Result<(AppliedImperfection, Option<Vec<f64>>), Error> {
    let uniform = match scene.solver.imperfection {
        Imperfection::Uniform => true,
        Imperfection::Mode => false,
        Imperfection::Auto => layout.is_envelope(),
    };
    if let (true, Some(q)) = (uniform, threshold.wavenumber) {
        let amplitude = add_uniform_imperfection(scene, problem, layout, q)?;
        let applied = AppliedImperfection {
            amplitude,
            shape: Imperfection::Uniform,
        };
        return Ok((applied, None));
    }
    let (amplitude, response) = add_mode_imperfection(scene, problem, layout, threshold)?;
    let applied = AppliedImperfection {
        amplitude,
        shape: Imperfection::Mode,
    };
    Ok((applied, Some(response)))
}

/// Adds the mode-shaped imperfection $`F = \varepsilon K_0\varphi`$ to the fixed loads;
/// returns its physical amplitude on the unloaded sheet (mm) and its linear response
/// $`\varepsilon\varphi`$ (free unknowns).
fn add_mode_imperfection<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    layout: &Layout,
    threshold: &Threshold,
) -> Result<(f64, Vec<f64>), Error> {
    let mode = threshold.buckling.modes.first().ok_or_else(|| {
        Error::Solver("linear buckling returned no mode to shape the imperfection".into())
    })?;
    let values = problem.dofs().expand_increment(mode, 0.0);
    let snapshot = Snapshot {
        mesh: problem.assembler.mesh(),
        layout,
        values: &values,
        wavenumber: threshold.wavenumber.unwrap_or(0.0),
        direction: threshold.direction_degrees.to_radians(),
    };
    let amplitude = snapshot.max_amplitude();
    if !(amplitude.is_finite() && amplitude > 0.0) {
        return Err(Error::Solver(format!(
            "the first buckling mode of `{}` has no transverse component (physical amplitude {amplitude:e}): it is not a wrinkling mode",
            threshold.model
        )));
    }
    let epsilon = scene.solver.perturbation * scene.material.thickness / amplitude;
    let mut matrix = problem.new_matrix();
    let unloaded = threshold.buckling.state_at(threshold.reference_load, 0.0);
    problem.tangent_into(&unloaded, 0.0, &mut matrix);
    let mut force = vec![0.0; mode.len()];
    matrix.multiply_into(mode, &mut force);
    for (f, k) in problem.loads.fixed.iter_mut().zip(&force) {
        *f += epsilon * k;
    }
    let response = mode.iter().map(|m| epsilon * m).collect();
    Ok((epsilon * amplitude, response))
}

/// The uniform imperfection of the paper's envelope runs: a fixed transverse load
/// $`f = \text{perturbation}\cdot h\,DQ^4`$ on the envelope ($`D = Eh^3/(12(1-\nu^2))`$ from the
/// scene's material), which would give an envelope of `perturbation`·h on an unloaded infinite
/// sheet. Returns its nominal physical amplitude $`2\,\text{perturbation}\cdot h`$ (mm).
fn add_uniform_imperfection<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    layout: &Layout,
    q: f64,
) -> Result<f64, Error> {
    let (e, nu, h) = (
        scene.material.young_modulus,
        scene.material.poisson_ratio,
        scene.material.thickness,
    );
    let bending = e * h.powi(3) / (12.0 * (1.0 - nu * nu));
    let load = BodyLoad {
        field: layout.primary,
        value: scene.solver.perturbation * h * bending * q.powi(4),
        proportional: false,
    };
    let loads = Loads {
        body_loads: vec![load],
        ..Loads::default()
    };
    let vectors = LoadVectors::assemble(problem.assembler.mesh(), problem.dofs(), &loads)
        .map_err(|e| Error::Solver(format!("imperfection load: {e}")))?;
    for (f, g) in problem.loads.fixed.iter_mut().zip(&vectors.fixed) {
        *f += g;
    }
    Ok(2.0 * scene.solver.perturbation * h)
}

/// Largest $`\max|w|/h`$ of a path without imperfection still taken as flat past $`\lambda_c`$
/// (the fundamental branch has $`w = 0`$ exactly; a default imperfection gives $`10^{-4}`$
/// unloaded).
const PERFECT_FLATNESS: f64 = 1e-8;

/// Largest change of the deflection (or envelope) fields in one Riks step, in thicknesses:
/// a quarter thickness of envelope is half a thickness of physical amplitude.
const RIKS_MAX_AMPLITUDE_CHANGE: f64 = 0.25;

/// Relative distance from an amplitude level within which a point is landed on it
/// ([`PathRecorder::land_levels`]): the load there is then the level's to about this much
/// times $`d\ln\lambda/d\ln a`$, far below the residual tolerance's effect.
const LEVEL_LANDING_TOLERANCE: f64 = 1e-9;

/// Watches the path: amplitudes, ellipticity at step ends, snapshots; stops at the target or,
/// without imperfection, past the threshold on the flat fundamental branch.
struct PathRecorder<'a, 's, M: EnergyModel> {
    scene: &'a Scene,
    problem: &'a Problem<M>,
    layout: &'a Layout,
    wavenumber: f64,
    /// Wave direction (radians from X) of the threshold.
    direction: f64,
    wavelength: f64,
    critical_load: f64,
    closed_form: Option<(f64, f64)>,
    target: f64,
    vtu_requests: Vec<f64>,
    /// Requested loads below the path's range, never recorded.
    vtu_below_path: Vec<f64>,
    previous: Option<PathState>,
    progress: Progress,
    trace: Trace,
    /// The step ends' ellipticity checks, beside the path.
    checks: EllipticityChecks<'a, 's>,
}

/// Where the step ends' ellipticity checks ([`legendre_hadamard`]) run. None steers the path
/// (its point's `elliptic` and the run's loss of ellipticity are only reported), so each runs
/// on a thread of its own, on a one-worker pool of its own (not on the path's workers), beside
/// the path's next step; it is collected at the next step end, before a point is replaced by
/// its landing, and when the path ends. The checks are the same sums on any thread, so the
/// records are the same as in place. Without a second worker (`--threads 1`) they run in place.
struct EllipticityChecks<'a, 's> {
    /// The scope and the pool of the threaded checks; `None`: in place.
    beside: Option<(&'s std::thread::Scope<'s, 'a>, &'a rayon::ThreadPool)>,
    /// The check under way: the point it is for and its load.
    pending: Option<(
        usize,
        f64,
        std::thread::ScopedJoinHandle<'s, EllipticityReport>,
    )>,
}

impl<M: EnergyModel> PathRecorder<'_, '_, M> {
    fn snapshot<'b>(&'b self, values: &'b [f64]) -> Snapshot<'b> {
        Snapshot {
            mesh: self.problem.assembler.mesh(),
            layout: self.layout,
            values,
            wavenumber: self.wavenumber,
            direction: self.direction,
        }
    }

    fn observe(&mut self, event: &PathEvent) -> PathControl {
        let clock = Instant::now();
        let control = self.record(event);
        self.trace.recording_seconds += clock.elapsed().as_secs_f64();
        control
    }

    /// [`Self::observe`] without its timing: the points landed on the amplitude levels the
    /// path crossed since the last point ([`Self::land_levels`]), then the event's.
    fn record(&mut self, event: &PathEvent) -> PathControl {
        let (values, max_amplitude) = self.measured(event.state);
        if let Some(on_step) = event.on_step {
            let above = max_amplitude / self.scene.material.thickness;
            self.land_levels(event, on_step, above);
        }
        self.record_point(event, values, max_amplitude)
    }

    /// The global nodal values of `state` and its largest physical amplitude (mm).
    fn measured(&self, state: &PathState) -> (Vec<f64>, f64) {
        let values = self.problem.dofs().expand(&state.displacement, state.load);
        let max_amplitude = self.snapshot(&values).max_amplitude();
        (values, max_amplitude)
    }

    /// Records, before `event`, a point on each of [`AMPLITUDE_LEVELS`] (below the target)
    /// that the path crossed since the point recorded last: landed on the step's own
    /// approximant (`on_step`) to within [`LEVEL_LANDING_TOLERANCE`] of the level, and kept
    /// when its relative residual is within the solver's tolerance. The loads at these
    /// amplitudes (the comparison's and the sweep's columns,
    /// [`load_at_amplitude`](crate::study::load_at_amplitude)) are then read at a point of the
    /// path instead of interpolated between two: where the node of the maximum changes between
    /// two points, the maximum has a kink there, and the interpolation missed it by up to 3e-4
    /// of the load on example 1's plate at a/h = 2. `above` is the event's $`\max|w|/h`$.
    fn land_levels(&mut self, event: &PathEvent, on_step: OnStep, above: f64) {
        let Some(below) = self.trace.points.last().map(|p| p.max_amplitude_over_h) else {
            return;
        };
        let landed: Vec<(PathState, f64)> = {
            let measure = |state: &PathState| self.amplitude(state);
            AMPLITUDE_LEVELS
                .iter()
                .filter(|&&level| below < level && level < above && level < self.target)
                .filter_map(|&level| {
                    let state = parameter_on_step(
                        on_step.evaluate,
                        &measure,
                        (on_step.previous, on_step.parameter),
                        level,
                        LEVEL_LANDING_TOLERANCE * level,
                    )?;
                    let residual = self
                        .problem
                        .relative_residual(&state.displacement, state.load);
                    (residual <= self.scene.solver.tolerance).then_some((state, residual))
                })
                .collect()
        };
        for (state, residual) in &landed {
            let (values, max_amplitude) = self.measured(state);
            let event = PathEvent {
                step: event.step,
                interior: true,
                state,
                relative_residual: *residual,
                predicted_bifurcation: event.predicted_bifurcation,
                on_step: None,
            };
            self.record_point(&event, values, max_amplitude);
        }
    }

    /// Records one point, whose global nodal values and largest physical amplitude are
    /// [`Self::measured`]: its amplitudes, the requested states up to it, the profiles it
    /// reaches, its snapshot; then whether the path stops there.
    fn record_point(
        &mut self,
        event: &PathEvent,
        values: Vec<f64>,
        max_amplitude: f64,
    ) -> PathControl {
        let state = event.state;
        let h = self.scene.material.thickness;
        let mesh: &Mesh = self.problem.assembler.mesh();
        let bounds = mesh.bounds();
        let centre = [0.5 * (bounds[0] + bounds[1]), 0.5 * (bounds[2] + bounds[3])];
        let centre_amplitude = self
            .snapshot(&values)
            .centre_amplitude(centre, self.wavelength);
        let biaxial = self.scene.load.kind == LoadKind::Biaxial;
        self.trace.points.push(PathPoint {
            step: event.step,
            interior: event.interior,
            lambda: state.load,
            n_x: biaxial.then_some(-state.load),
            max_amplitude,
            max_amplitude_over_h: max_amplitude / h,
            centre_amplitude_over_h: centre_amplitude / h,
            residual: event.relative_residual,
            // Set by the point's check (step ends only) when it is collected.
            elliptic: true,
            closed_form_amplitude_over_h: self.closed_form_amplitude(state.load),
        });
        if !event.interior {
            self.check_ellipticity(state);
        }
        self.record_requested(state);
        let levels = [0.05, 0.25, 0.5, 0.75, 1.0];
        while self.trace.profiles.len() < levels.len()
            && max_amplitude / h >= levels[self.trace.profiles.len()] * self.target
        {
            self.trace.profiles.push(Snap {
                load: state.load,
                values: values.clone(),
                ..Snap::default()
            });
        }
        if !event.interior && self.scene.output.vtu {
            self.trace.step_ends.push(Snap {
                load: state.load,
                values: values.clone(),
                ..Snap::default()
            });
        }
        self.progress.update_at_load(
            max_amplitude / h,
            state.load,
            &format!("step {}, λ = {:.6e}", event.step, state.load),
        );
        self.previous = Some(state.clone());
        self.trace.last = Snap {
            load: state.load,
            values,
            ..Snap::default()
        };
        if crate::interrupt::requested() {
            self.trace.interrupted = true;
            PathControl::Stop
        } else if max_amplitude / h >= self.target {
            PathControl::Stop
        } else if self.scene.solver.perturbation == 0.0
            && self.scene.solver.max_load == 0.0
            && state.load > self.critical_load
            && max_amplitude / h < PERFECT_FLATNESS
        {
            // A perfect bifurcation: without an imperfection the path goes on along the
            // fundamental branch, which is unstable past λ_c, and never wrinkles.
            self.trace.passed_perfect_bifurcation = Some(state.load);
            PathControl::Stop
        } else {
            PathControl::Continue
        }
    }

    /// Starts the ellipticity check of the step end `state`, the point recorded last, after
    /// collecting the previous one's: beside the path when it can, else in place.
    fn check_ellipticity(&mut self, state: &PathState) {
        self.collect_ellipticity();
        let point = self.trace.points.len() - 1;
        let problem = self.problem;
        match self.checks.beside {
            Some((scope, pool)) => {
                let displacement = state.displacement.clone();
                let load = state.load;
                let handle = scope.spawn(move || {
                    pool.install(|| legendre_hadamard(problem, &displacement, load))
                });
                self.checks.pending = Some((point, load, handle));
            }
            None => {
                let clock = Instant::now();
                let report = legendre_hadamard(problem, &state.displacement, state.load);
                self.trace.ellipticity_seconds += clock.elapsed().as_secs_f64();
                self.settle_ellipticity(point, state.load, report);
            }
        }
    }

    /// Waits for the check under way, if any, and records it (the wait is the path's
    /// ellipticity time).
    fn collect_ellipticity(&mut self) {
        let Some((point, load, handle)) = self.checks.pending.take() else {
            return;
        };
        let clock = Instant::now();
        let report = handle
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        self.trace.ellipticity_seconds += clock.elapsed().as_secs_f64();
        self.settle_ellipticity(point, load, report);
    }

    /// Records the check `report` of point `point` (at `load`): its `elliptic`, and the run's
    /// first loss of ellipticity.
    fn settle_ellipticity(&mut self, point: usize, load: f64, report: EllipticityReport) {
        let well_posed = report.well_posed();
        if let Some(recorded) = self.trace.points.get_mut(point) {
            recorded.elliptic = well_posed;
        }
        if !well_posed && self.trace.loss_of_ellipticity.is_none() {
            self.trace.loss_of_ellipticity = Some((load, report));
        }
    }

    /// Physical closed-form amplitude $`2a/h`$ (eq. 62) at `load`, for the clamped biaxial
    /// rectangle.
    fn closed_form_amplitude(&self, load: f64) -> Option<f64> {
        self.closed_form.map(|(alpha, nu)| {
            2.0 * crate::closed_form::amplitude_from_load_ratio(
                alpha,
                nu,
                load / self.critical_load,
            )
        })
    }

    /// States at requested loads, interpolated linearly between the two path points around them.
    fn record_requested(&mut self, state: &PathState) {
        let Some(previous) = &self.previous else {
            return;
        };
        while let Some(&requested) = self.vtu_requests.first() {
            if requested < previous.load.min(state.load) {
                // Below the path (a load under its start): no state, and a note says so.
                let below = self.vtu_requests.remove(0);
                self.vtu_below_path.push(below);
                continue;
            }
            if requested > state.load.max(previous.load) {
                break;
            }
            self.vtu_requests.remove(0);
            let span = state.load - previous.load;
            let t = if span != 0.0 {
                (requested - previous.load) / span
            } else {
                1.0
            };
            let interpolated: Vec<f64> = previous
                .displacement
                .iter()
                .zip(&state.displacement)
                .map(|(a, b)| a + t * (b - a))
                .collect();
            self.trace.requested.push(Snap {
                load: requested,
                values: self.problem.dofs().expand(&interpolated, requested),
                ..Snap::default()
            });
        }
    }
}

/// Equilibrium at $`\lambda = 0`$ under the fixed loads (tension, imperfection), by Newton from
/// the pre-buckling state plus the imperfection's linear `response` when known (then the
/// residual left to correct is the imperfection's quadratic part: one iteration fewer).
/// Newton assembles into the path's `workspace` when given ([`Workspace::newton`]: the path's
/// first step keeps its last factorisation when the tangent at the start is the same).
fn start_point<M: EnergyModel>(
    problem: &Problem<M>,
    factor: &mut SparseFactorization,
    threshold: &Threshold,
    response: Option<&[f64]>,
    workspace: Option<&mut Workspace>,
) -> Result<PathState, Error> {
    let mut initial = threshold.buckling.state_at(threshold.reference_load, 0.0);
    if let Some(response) = response {
        for (u, r) in initial.iter_mut().zip(response) {
            *u += r;
        }
    }
    let options = NewtonOptions::default();
    let solution = Workspace::newton_in(workspace, problem, initial, 0.0, factor, &options)
        .map_err(|e| Error::Solver(format!("equilibrium at zero load: {e}")))?;
    Ok(PathState {
        displacement: solution.solution,
        load: 0.0,
    })
}

impl<'a, 's, M: EnergyModel> PathRecorder<'a, 's, M> {
    /// The recorder of a path from `start`; its ellipticity checks run `beside` the path in
    /// that scope and pool when given, else in place.
    #[allow(clippy::too_many_arguments)]
    fn new(
        scene: &'a Scene,
        problem: &'a Problem<M>,
        layout: &'a Layout,
        threshold: &Threshold,
        start: &PathState,
        quiet: bool,
        beside: Option<(&'s std::thread::Scope<'s, 'a>, &'a rayon::ThreadPool)>,
    ) -> Self {
        let target = scene.solver.max_amplitude_over_thickness;
        let mut vtu_requests = scene.output.vtu_loads.clone();
        vtu_requests.sort_by(f64::total_cmp);
        let shortest = scene.geometry.length_x.min(scene.geometry.length_y);
        let closed_form = closed_form_threshold(scene).map(|_| {
            (
                scene.clamped_rectangle().aspect_ratio(),
                scene.material.poisson_ratio,
            )
        });
        let progress = Progress::new(
            &format!("wrinkle run ({})", threshold.model),
            ProgressTarget::new(
                Quantity::new("max amplitude", "max |w| / h", ""),
                0.0,
                target,
            )
            .with_critical_load(threshold.critical_load()),
            ProgressSink::standard_error(quiet),
        );
        PathRecorder {
            scene,
            problem,
            layout,
            wavenumber: threshold.wavenumber.unwrap_or(0.0),
            direction: threshold.direction_degrees.to_radians(),
            wavelength: threshold.wavelength.unwrap_or(shortest / 4.0),
            critical_load: threshold.critical_load(),
            closed_form,
            target,
            vtu_requests,
            vtu_below_path: Vec::new(),
            previous: None,
            progress,
            trace: Trace {
                points: Vec::new(),
                result: PathResult {
                    last: start.clone(),
                    statistics: Default::default(),
                    stop: PathStop::Observer,
                    bifurcation: None,
                    warnings: Vec::new(),
                },
                anm_steps: Vec::new(),
                loss_of_ellipticity: None,
                profiles: Vec::new(),
                requested: Vec::new(),
                step_ends: Vec::new(),
                last: Snap::default(),
                interrupted: false,
                passed_perfect_bifurcation: None,
                unreached_vtu_loads: Vec::new(),
                ellipticity_seconds: 0.0,
                recording_seconds: 0.0,
            },
            checks: EllipticityChecks {
                beside,
                pending: None,
            },
        }
    }
}

/// Equilibrium at $`\lambda = 0`$ (from the imperfection's linear `response` when known), then
/// the path to the amplitude target, in `workspace` when given.
fn trace_path<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    factor: &mut SparseFactorization,
    layout: &Layout,
    threshold: &Threshold,
    (response, mut workspace): (Option<&[f64]>, Option<Workspace>),
    quiet: bool,
) -> Result<Trace, Error> {
    let start = start_point(problem, factor, threshold, response, workspace.as_mut())?;
    // The ellipticity checks' own worker, when the path has two or more.
    let pool = (rayon::current_num_threads() >= 2)
        .then(|| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(1)
                .thread_name(|_| "wrinkle-ellipticity".to_string())
                .build()
                .ok()
        })
        .flatten();
    std::thread::scope(|scope| {
        let beside = pool.as_ref().map(|pool| (scope, pool));
        let recorder = PathRecorder::new(scene, problem, layout, threshold, &start, quiet, beside);
        follow_and_record(
            scene,
            problem,
            factor,
            layout,
            threshold,
            (start.clone(), workspace),
            recorder,
        )
    })
}

/// The path of [`trace_path`] from `start` in its workspace, recorded by `recorder`.
fn follow_and_record<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    factor: &mut SparseFactorization,
    layout: &Layout,
    threshold: &Threshold,
    start: (PathState, Option<Workspace>),
    mut recorder: PathRecorder<'_, '_, M>,
) -> Result<Trace, Error> {
    let max_load = (scene.solver.max_load > 0.0).then_some(scene.solver.max_load);
    let options = follow_options(scene, problem, layout, threshold, max_load);
    let FollowedPath {
        mut result,
        anm_steps,
    } = follow_path_in_workspace(problem, start, factor, &options, &mut recorder);
    // The wait for the last check is the path's, and its recording's.
    let clock = Instant::now();
    recorder.collect_ellipticity();
    let waited = clock.elapsed().as_secs_f64();
    recorder.trace.recording_seconds += waited;
    result.statistics.total_seconds += waited;
    let stop = if recorder.trace.interrupted {
        "interrupted by the user".to_string()
    } else if recorder.trace.passed_perfect_bifurcation.is_some() {
        "stopped past λ_c: no imperfection, no wrinkles".to_string()
    } else {
        result.stop.describe()
    };
    recorder
        .progress
        .finish(&format!("{stop} ({} steps)", result.statistics.steps));
    let mut trace = recorder.trace;
    trace.unreached_vtu_loads = recorder.vtu_below_path;
    trace.unreached_vtu_loads.extend(recorder.vtu_requests);
    if scene.output.vtu {
        for snap in trace
            .requested
            .iter_mut()
            .chain(trace.step_ends.iter_mut())
            .chain([&mut trace.last])
        {
            snap.stress_resultants = stress_resultants(problem, layout, &snap.values);
        }
    }
    trace.result = result;
    trace.anm_steps = anm_steps;
    Ok(trace)
}

/// Element means of $`N_X = \partial\psi/\partial u_{,X}`$, $`N_Y = \partial\psi/\partial v_{,Y}`$
/// and $`N_{XY} = \partial\psi/\partial u_{,Y}`$ (N/mm), from the model's own residual kernel:
/// the same definition for every model, whatever its strain contains (the envelope's
/// $`|A|^2`$ terms, the plate's $`w_{,X}^2/2`$).
fn stress_resultants<M: EnergyModel>(
    problem: &Problem<M>,
    layout: &Layout,
    values: &[f64],
) -> Vec<Vec<f64>> {
    use wrinkle_runtime::model::{Derivative, JetEntry};
    let [u, v] = layout.in_plane;
    let entry = |field, derivative| JetEntry { field, derivative };
    problem.assembler.element_mean_conjugates(
        values,
        &[
            entry(u, Derivative::X),
            entry(v, Derivative::Y),
            entry(u, Derivative::Y),
        ],
    )
}

/// The path settings of `wrinkle run`: the method of `solver.method` with its settings, and the
/// landing on `solver.max_amplitude_over_h` (in $`\max|w|/h`$, [`PathObserver::amplitude`])
/// with the arc-length corrector of the Riks settings, whichever the method.
fn follow_options<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
    threshold: &Threshold,
    max_load: Option<f64>,
) -> FollowOptions {
    let critical_load = threshold.critical_load();
    let riks = riks_options(scene, problem, layout, max_load, critical_load);
    let landing_corrector = riks.corrector();
    let method = match scene.solver.method {
        PathMethod::Anm => FollowMethod::Anm(AnmOptions {
            // The threshold's mode starts the eigen-solver of the bifurcation prediction.
            bifurcation_mode_guess: threshold.buckling.modes.first().cloned(),
            // ... and its load is the guess the prediction is shifted towards.
            bifurcation_load_guess: Some(critical_load).filter(|l| l.is_finite()),
            // ... and its amplitude the steps' parameter where the path moves along it.
            mode_parameter: scene
                .solver
                .mode_parameter
                .then(|| threshold.buckling.modes.first().cloned())
                .flatten(),
            ..anm_options(scene, max_load)
        }),
        PathMethod::Riks => FollowMethod::Riks(riks),
    };
    FollowOptions {
        method,
        amplitude_target: Some(scene.solver.max_amplitude_over_thickness),
        landing_corrector,
    }
}

/// The ANM settings the scene's `[solver]` gives (order, tolerances, steps, Padé, the
/// corrector at a thousandth of the residual tolerance), up to `max_load`: shared by the plane
/// and the line paths, which add their own bifurcation settings.
pub(crate) fn anm_options(scene: &Scene, max_load: Option<f64>) -> AnmOptions {
    AnmOptions {
        order: scene.solver.order,
        series_tolerance: scene.solver.series_tolerance,
        residual_tolerance: scene.solver.tolerance,
        max_steps: scene.solver.max_steps,
        max_load,
        pade: scene.solver.pade,
        exponential_map: scene.solver.exponential_map,
        corrector: NewtonOptions {
            tolerance: scene.solver.tolerance * 1e-3,
            max_iterations: 12,
        },
        ..AnmOptions::default()
    }
}

/// Newton–Riks settings of `wrinkle run`.
///
/// A dimensionless arc length, in units of the linear response to λ_c (displacements) and of
/// λ_c (load), so that the step count does not grow with the mesh; the steps adapt to the
/// Newton iterations up to 0.3 of it. A step that converges past the sharp turn of the
/// imperfect branch at the threshold, onto the unstable fundamental branch, is caught by the
/// crossing guard (negative pivots at its end) and halved. The arc length hardly sees wrinkles
/// beside the in-plane displacements: a step may change the deflection (envelope) fields by at
/// most a quarter thickness, so that the knee of the response is resolved.
fn riks_options<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
    max_load: Option<f64>,
    critical_load: f64,
) -> RiksOptions {
    let dofs = problem.dofs();
    let fields = layout.deflection_fields();
    let amplitude_dofs: Vec<usize> = (0..dofs.node_count)
        .flat_map(|node| fields.iter().filter_map(move |&f| dofs.free(node, f)))
        .collect();
    RiksOptions {
        tolerance: scene.solver.tolerance,
        max_steps: scene.solver.max_steps,
        max_load,
        reference_load: Some(critical_load).filter(|l| *l != 0.0 && l.is_finite()),
        load_scale: 1.0 / critical_load.abs().max(f64::MIN_POSITIVE),
        initial_arc_length: 0.05,
        max_arc_length: 0.3,
        amplitude: (!amplitude_dofs.is_empty()).then_some(AmplitudeControl {
            dofs: amplitude_dofs,
            max_change: RIKS_MAX_AMPLITUDE_CHANGE * scene.material.thickness,
        }),
        ..RiksOptions::default()
    }
}

/// `wrinkle run`'s side of the path: the recorder sees every point, measures the amplitude of
/// the landing, and forgets an overshooting last point for the landed one.
impl<M: EnergyModel> PathObserver for PathRecorder<'_, '_, M> {
    fn observe(&mut self, event: &PathEvent) -> PathControl {
        PathRecorder::observe(self, event)
    }

    /// $`\max|w|/h`$ of the physical deflection.
    fn amplitude(&self, state: &PathState) -> f64 {
        self.measured(state).1 / self.scene.material.thickness
    }

    /// An interrupted path is left where it stopped.
    fn wants_landing(&self) -> bool {
        !self.trace.interrupted
    }

    /// Forgets what the overshooting point recorded (its point, the profiles it captured, the
    /// requested states it interpolated, which go back to the requests), then records the
    /// landed point instead: it takes back the requests up to its load.
    fn replace_last(&mut self, kept: &PathState, landed: &PathEvent) {
        // The overshooting point's check first: its loss of ellipticity stays reported, as in
        // place (its `elliptic` goes with the point).
        let clock = Instant::now();
        self.collect_ellipticity();
        self.trace.recording_seconds += clock.elapsed().as_secs_f64();
        let trace = &mut self.trace;
        let overshooting_load = trace.points.pop().map(|point| point.lambda);
        trace
            .profiles
            .retain(|profile| Some(profile.load) != overshooting_load);
        trace
            .step_ends
            .retain(|snap| Some(snap.load) != overshooting_load);
        let beyond = |snap: &Snap| snap.load > kept.load;
        let returned: Vec<f64> = trace
            .requested
            .iter()
            .filter(|snap| beyond(snap))
            .map(|snap| snap.load)
            .collect();
        trace.requested.retain(|snap| !beyond(snap));
        self.vtu_requests.splice(0..0, returned);
        self.previous = Some(kept.clone());
        PathRecorder::observe(self, landed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use wrinkle_runtime::solve::anm::follow_path_anm;

    /// The first predicted bifurcation load and the factorisations of a short ANM path for
    /// each guess of `AnmOptions::bifurcation_load_guess`.
    struct Predictions<'a> {
        scene: &'a Scene,
        guesses: &'a [Option<f64>],
    }

    impl ModelVisitor for Predictions<'_> {
        type Output = (f64, Vec<(Option<f64>, usize)>);
        fn visit<M: EnergyModel>(self, mut model: M) -> Self::Output {
            let scene = self.scene;
            configure_model(scene, &mut model, 1.0).unwrap();
            let layout = layout_of::<M>(scene).unwrap();
            let mut problem = build_problem(scene, model).unwrap();
            let mut factor = analyse(&problem).unwrap();
            let threshold =
                crate::threshold::find_threshold(scene, &mut problem, &mut factor, true).unwrap();
            let (_, response) = add_imperfection(scene, &mut problem, &layout, &threshold).unwrap();
            let critical = threshold.critical_load();
            let outcomes = self
                .guesses
                .iter()
                .map(|factor_of_critical| {
                    let response = response.as_deref();
                    let start =
                        start_point(&problem, &mut factor, &threshold, response, None).unwrap();
                    let options = AnmOptions {
                        max_steps: 6,
                        bifurcation_mode_guess: threshold.buckling.modes.first().cloned(),
                        bifurcation_load_guess: factor_of_critical.map(|f| f * critical),
                        ..AnmOptions::default()
                    };
                    let mut steps = Vec::new();
                    let mut observer = |_: &PathEvent| PathControl::Continue;
                    let result = follow_path_anm(
                        &problem,
                        start,
                        &mut factor,
                        &options,
                        &mut observer,
                        &mut steps,
                    );
                    (
                        steps.iter().find_map(|s| s.predicted_bifurcation),
                        result.statistics.factorizations,
                    )
                })
                .collect();
            (critical, outcomes)
        }
    }

    /// Example 1 on 12 × 6: the ANM's bifurcation prediction is the same load whether its
    /// eigen-solve is unshifted, shifted towards the threshold, or offered a guess beyond the
    /// path's bifurcation (the shifted tangent is indefinite and the unshifted analysis
    /// decides). A guess costs exactly one factorisation more than none, so the shifted
    /// analysis did run — two beyond the bifurcation, where the prediction, on a thread of its
    /// own, then factorises the unshifted tangent too; the predicted load is the threshold to
    /// 1e-4 (the path starts from an imperfect state).
    #[test]
    fn example_one_bifurcation_prediction_does_not_depend_on_the_load_guess() {
        let mut scene = Scene::default();
        for setting in ["mesh.nx=12", "mesh.ny=6"] {
            scene.apply_override(setting).unwrap();
        }
        let guesses = [None, Some(1.0), Some(1.5)];
        let (critical, outcomes) = with_model(
            &scene.model.name,
            Predictions {
                scene: &scene,
                guesses: &guesses,
            },
        )
        .unwrap();
        eprintln!("λ_c {critical:.12e}; (prediction, factorisations): {outcomes:?}");
        let unshifted = outcomes[0].0.expect("a prediction without a guess");
        assert!((unshifted - critical).abs() < 1e-4 * critical);
        for (&(predicted, factorizations), more) in outcomes[1..].iter().zip([1, 2]) {
            let predicted = predicted.expect("a prediction with a guess");
            assert!(
                (predicted - unshifted).abs() < 1e-9 * unshifted,
                "{predicted:e} against {unshifted:e}"
            );
            assert_eq!(factorizations, outcomes[0].1 + more);
        }
    }
}
