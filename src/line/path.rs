//! Path following on a line scene (`wrinkle run` on a line): a mode-shaped imperfection, the
//! runtime's `follow_path` (ANM, ANM + Padé, or Riks, as `solver.method` says) to
//! `solver.max_amplitude_over_h` or `solver.max_load`, and the typed result.
//!
//! **Imperfection** (`solver.perturbation`): the load $`F = \varepsilon K_0\varphi`$, with
//! $`K_0`$ the tangent of the unloaded beam and $`\varphi`$ the first buckling mode, scaled so
//! that the physical amplitude it gives on the unloaded beam ($`U = \varepsilon\varphi`$) is
//! `perturbation`·h — the same imperfection for every model.
//!
//! **Amplitudes** of each path point, over the thickness $`h`$ (`material.thickness`): the
//! largest nodal $`|w|`$ of a resolved deflection or $`2|v_1|`$ of an envelope, and the local
//! amplitude at the middle $`X = L/2`$ ([`LineLayout::local_amplitude_at`]).

use super::layout::LineLayout;
use super::sample_positions;
use super::threshold::{LineSetup, LineThreshold, set_up_line};
use crate::error::Error;
use crate::scene::{PathMethod, Scene};
use std::path::Path;
use std::time::Instant;
use wrinkle_models::ModelVisitor;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::anm::AnmOptions;
use wrinkle_runtime::solve::follow::{
    FollowMethod, FollowOptions, PathObserver, follow_path_in_workspace,
};
use wrinkle_runtime::solve::linearization::Workspace;
use wrinkle_runtime::solve::newton::NewtonOptions;
use wrinkle_runtime::solve::path::{PathControl, PathEvent, PathState};
use wrinkle_runtime::solve::riks::RiksOptions;

/// One point of a line path.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct LinePathPoint {
    /// Step index (0 = the start point).
    pub step: usize,
    /// Inside a step (dense output) or a step's end.
    pub interior: bool,
    /// Load parameter $`\lambda`$.
    pub lambda: f64,
    /// Largest physical amplitude over $`h`$.
    pub max_amplitude_over_h: f64,
    /// Local physical amplitude at the middle over $`h`$.
    pub centre_amplitude_over_h: f64,
    /// Relative residual at the point.
    pub residual: f64,
}

/// A sample of the last state along the beam.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ProfileSample {
    /// Position $`X`$ (mm).
    pub x: f64,
    /// Physical deflection over the thickness, $`w/h`$.
    pub deflection_over_h: f64,
    /// The envelope's local amplitude $`2|v_1|/h`$ (envelope models).
    pub envelope_over_h: Option<f64>,
}

/// The result of a line run.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LineRun {
    /// The threshold the run started from.
    pub threshold: LineThreshold,
    /// The path, in order (an overshooting last point replaced by the landed one).
    pub points: Vec<LinePathPoint>,
    /// The last state along the beam.
    pub profile: Vec<ProfileSample>,
    /// Why the path stopped.
    pub stop_reason: String,
    /// Whether it reached what was asked (the amplitude target or `max_load`).
    pub complete: bool,
    /// Accepted steps, factorisations.
    pub steps: usize,
    /// Numeric factorisations of the tangent.
    pub factorizations: usize,
    /// Seconds of the path.
    pub path_seconds: f64,
    /// The last state's free dofs (not serialised).
    #[serde(skip)]
    pub last_state: Vec<f64>,
}

/// `wrinkle run` on a line scene, for the model it names; with `fields_vtu`, the last state's
/// nodal fields are written there ([`super::outputs::write_fields_vtu`]).
pub fn run_line(scene: &Scene, fields_vtu: Option<&Path>) -> Result<LineRun, Error> {
    struct Run<'a>(&'a Scene, Option<&'a Path>);
    impl ModelVisitor for Run<'_> {
        type Output = Result<LineRun, Error>;
        fn visit<M: EnergyModel>(self, model: M) -> Self::Output {
            let setup = set_up_line(self.0, model)?;
            follow_line(self.0, setup, self.1)
        }
    }
    wrinkle_models::with_model(&scene.model.name, Run(scene, fields_vtu))
        .unwrap_or_else(|| Err(crate::setup::unknown_model(scene)))
}

/// Imperfection, start state and path of a set-up line problem; with `fields_vtu`, the last
/// state's nodal fields are written there.
pub fn follow_line<M: EnergyModel>(
    scene: &Scene,
    setup: LineSetup<M>,
    fields_vtu: Option<&Path>,
) -> Result<LineRun, Error> {
    let LineSetup {
        mut problem,
        layout,
        buckling,
        threshold,
    } = setup;
    let thickness = scene.material.thickness;
    add_imperfection(
        scene,
        &mut problem,
        &layout,
        &buckling.modes[0],
        threshold.wavenumber,
    );
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern())
        .map_err(|e| Error::Solver(format!("analysing the tangent: {e}")))?;
    let options = NewtonOptions {
        tolerance: scene.solver.tolerance,
        max_iterations: 20,
    };
    // Newton assembles into the path's own matrix: the first step keeps its factorisation
    // when the tangent at the start is the same (`Workspace::newton`).
    let mut workspace = Workspace::new(&problem, &factor).ok();
    let unloaded = vec![0.0; problem.free_count()];
    let start = Workspace::newton_in(
        workspace.as_mut(),
        &problem,
        unloaded,
        0.0,
        &mut factor,
        &options,
    )
    .map_err(|e| Error::Solver(format!("the unloaded state: {e}")))?;
    let started = Instant::now();
    let mut recorder = Recorder {
        problem: &problem,
        layout: &layout,
        wavenumber: threshold.wavenumber,
        thickness,
        target: scene.solver.max_amplitude_over_thickness,
        points: Vec::new(),
    };
    let start = PathState {
        displacement: start.solution,
        load: 0.0,
    };
    let options = follow_options(scene, threshold.critical_load, &buckling.modes[0]);
    let start = (start, workspace);
    let followed = follow_path_in_workspace(&problem, start, &mut factor, &options, &mut recorder);
    let result = followed.result;
    let reached_amplitude = recorder
        .points
        .last()
        .is_some_and(|p| p.max_amplitude_over_h >= recorder.target * (1.0 - 1e-3));
    let reached_load =
        scene.solver.max_load > 0.0 && result.last.load >= scene.solver.max_load * (1.0 - 1e-9);
    let profile = final_profile(scene, &problem, &layout, &result.last, threshold.wavenumber);
    if let Some(path) = fields_vtu {
        let last = &result.last;
        let wavenumber = threshold.wavenumber;
        let state = (
            last.displacement.as_slice(),
            last.load,
            threshold.load.unit.as_str(),
        );
        super::outputs::write_fields_vtu(path, (&problem, &layout), state, wavenumber)
            .map_err(crate::error::io_error(path))?;
    }
    Ok(LineRun {
        points: recorder.points,
        profile,
        stop_reason: result.stop.describe(),
        complete: reached_amplitude || reached_load,
        steps: result.statistics.steps,
        factorizations: result.statistics.factorizations,
        path_seconds: started.elapsed().as_secs_f64(),
        last_state: result.last.displacement,
        threshold,
    })
}

/// The path's settings; `mode` (the first buckling mode, which shapes the imperfection) is the
/// ANM's step parameter where the path moves along it (`solver.mode_parameter`).
fn follow_options(scene: &Scene, critical_load: f64, mode: &[f64]) -> FollowOptions {
    let max_load = (scene.solver.max_load > 0.0).then_some(scene.solver.max_load);
    let riks = RiksOptions {
        tolerance: scene.solver.tolerance,
        max_steps: scene.solver.max_steps,
        max_load,
        reference_load: Some(critical_load).filter(|l| *l != 0.0 && l.is_finite()),
        initial_arc_length: 0.05,
        max_arc_length: 0.3,
        ..RiksOptions::default()
    };
    let landing_corrector = riks.corrector();
    let method = match scene.solver.method {
        PathMethod::Anm => FollowMethod::Anm(AnmOptions {
            predict_bifurcation: false,
            mode_parameter: scene.solver.mode_parameter.then(|| mode.to_vec()),
            ..crate::run::anm_options(scene, max_load)
        }),
        PathMethod::Riks => FollowMethod::Riks(riks),
    };
    FollowOptions {
        method,
        amplitude_target: Some(scene.solver.max_amplitude_over_thickness),
        landing_corrector,
    }
}

/// Adds $`F = \varepsilon K_0\varphi`$ to the fixed loads (module documentation).
fn add_imperfection<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    layout: &LineLayout,
    mode: &[f64],
    wavenumber: f64,
) {
    let size = scene.solver.perturbation * scene.material.thickness;
    if size == 0.0 {
        return;
    }
    let global = problem.dofs().expand(mode, 0.0);
    let mesh = problem.assembler.mesh();
    let peak = sample_positions(scene.geometry.length_x, wavenumber)
        .into_iter()
        .map(|x| layout.deflection_at(mesh, &global, wavenumber, x).abs())
        .fold(0.0, f64::max);
    if peak <= 0.0 {
        return;
    }
    let mut tangent = problem.new_matrix();
    problem.tangent_into(&vec![0.0; problem.free_count()], 0.0, &mut tangent);
    let mut force = vec![0.0; problem.free_count()];
    tangent.multiply_into(mode, &mut force);
    for (fixed, f) in problem.loads.fixed.iter_mut().zip(&force) {
        *fixed += size / peak * f;
    }
}

/// The last state sampled along the beam.
fn final_profile<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &LineLayout,
    last: &PathState,
    wavenumber: f64,
) -> Vec<ProfileSample> {
    let global = problem.dofs().expand(&last.displacement, last.load);
    let mesh = problem.assembler.mesh();
    let h = scene.material.thickness;
    sample_positions(scene.geometry.length_x, wavenumber)
        .into_iter()
        .map(|x| ProfileSample {
            x,
            deflection_over_h: layout.deflection_at(mesh, &global, wavenumber, x) / h,
            envelope_over_h: layout
                .envelope_amplitude_at(mesh, &global, x)
                .map(|a| a / h),
        })
        .collect()
}

/// Records the path's points and measures their amplitude.
struct Recorder<'a, M: EnergyModel> {
    problem: &'a Problem<M>,
    layout: &'a LineLayout,
    wavenumber: f64,
    thickness: f64,
    target: f64,
    points: Vec<LinePathPoint>,
}

impl<M: EnergyModel> Recorder<'_, M> {
    /// Largest nodal physical amplitude (value components) over $`h`$.
    fn max_amplitude_over_h(&self, state: &PathState) -> f64 {
        let global = self.problem.dofs().expand(&state.displacement, state.load);
        let mesh = self.problem.assembler.mesh();
        let components = mesh.kind.components();
        let nf = self.layout.field_count;
        let value = |node: usize, field: usize| global[(node * nf + field) * components];
        let peak = (0..mesh.nodes.len())
            .map(|node| match self.layout.deflection {
                super::LineDeflection::Resolved { deflection } => value(node, deflection).abs(),
                super::LineDeflection::RealEnvelope { envelope } => {
                    2.0 * value(node, envelope).abs()
                }
                super::LineDeflection::ComplexEnvelope { real, imaginary } => {
                    2.0 * value(node, real).hypot(value(node, imaginary))
                }
            })
            .fold(0.0, f64::max);
        peak / self.thickness
    }

    fn point(&self, event: &PathEvent) -> LinePathPoint {
        let state = event.state;
        let global = self.problem.dofs().expand(&state.displacement, state.load);
        let mesh = self.problem.assembler.mesh();
        let [x0, x1, ..] = mesh.bounds();
        let centre =
            self.layout
                .local_amplitude_at(mesh, &global, self.wavenumber, 0.5 * (x0 + x1));
        LinePathPoint {
            step: event.step,
            interior: event.interior,
            lambda: state.load,
            max_amplitude_over_h: self.max_amplitude_over_h(state),
            centre_amplitude_over_h: centre / self.thickness,
            residual: event.relative_residual,
        }
    }
}

impl<M: EnergyModel> PathObserver for Recorder<'_, M> {
    fn observe(&mut self, event: &PathEvent) -> PathControl {
        let point = self.point(event);
        let done = point.max_amplitude_over_h >= self.target;
        self.points.push(point);
        if done || crate::interrupt::requested() {
            PathControl::Stop
        } else {
            PathControl::Continue
        }
    }

    fn amplitude(&self, state: &PathState) -> f64 {
        self.max_amplitude_over_h(state)
    }

    fn replace_last(&mut self, _kept: &PathState, landed: &PathEvent) {
        self.points.pop();
        let point = self.point(landed);
        self.points.push(point);
    }
}

/// The table `wrinkle run` prints for a line scene.
pub fn line_run_text(run: &LineRun) -> String {
    let threshold = &run.threshold;
    let last = run.points.last();
    format!(
        "model {} on a line: {} {} elements, {} free dofs\n\
         critical load λ_c = {:.10} {} ({})\n\
         last point: λ = {:.8} ({:.5} λ_c), max amplitude {:.4} h, at the middle {:.4} h\n\
         path: {} steps, {} factorisations, {:.2} s; stopped: {}\n",
        threshold.model,
        threshold.elements,
        threshold.element,
        threshold.free_dofs,
        threshold.critical_load,
        threshold.load.unit,
        threshold.load.description,
        last.map_or(f64::NAN, |p| p.lambda),
        last.map_or(f64::NAN, |p| p.lambda / threshold.critical_load),
        last.map_or(f64::NAN, |p| p.max_amplitude_over_h),
        last.map_or(f64::NAN, |p| p.centre_amplitude_over_h),
        run.steps,
        run.factorizations,
        run.path_seconds,
        run.stop_reason
    )
}
