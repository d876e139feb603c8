//! Linear buckling of a line scene (`wrinkle buckle` on a line): the critical load of the
//! model on the scene's beam and its mode, sampled along $`X`$.

use super::layout::LineLayout;
use super::setup::{build_line_problem, configure_line_model, line_layout_of, line_wavenumber};
use super::{line_load_quantity, sample_positions};
use crate::error::Error;
use crate::output::Quantity;
use crate::scene::Scene;
use std::time::Instant;
use wrinkle_models::ModelVisitor;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::{LinearBuckling, LinearBucklingOptions, linear_buckling};

/// Krylov basis of the buckling eigen-solve: a long beam's critical loads cluster
/// (neighbouring wave counts differ by $`4EI(\pi/L)^2`$).
const MAX_KRYLOV: usize = 150;

/// Points $`(X, \text{value})`$ along the beam.
pub type Samples = Vec<(f64, f64)>;

/// The threshold of a line scene.
#[derive(Clone, Debug, serde::Serialize)]
pub struct LineThreshold {
    /// Model name.
    pub model: String,
    /// The element the model runs on (`Line3` or `Hermite2`).
    pub element: String,
    /// Elements along the beam.
    pub elements: usize,
    /// Free dofs.
    pub free_dofs: usize,
    /// Critical load $`\lambda_c`$ (first eigenvalue).
    pub critical_load: f64,
    /// What $`\lambda`$ is (end force in N, or end shortening in mm).
    pub load: Quantity,
    /// The carrier wavenumber $`Q`$ (1/mm).
    pub wavenumber: f64,
    /// Relative eigen-residual of the first mode.
    pub eigen_residual: f64,
    /// The first mode's physical deflection $`(X, w)`$, scaled to a unit peak (written to
    /// `mode_profile.csv`, not to the JSON).
    #[serde(skip)]
    pub mode: Samples,
    /// The first mode's envelope amplitude $`(X, 2|v_1|)`$ on the same scale (envelope
    /// models; empty otherwise).
    #[serde(skip)]
    pub mode_envelope: Samples,
    /// Seconds of the analysis.
    pub seconds: f64,
}

/// The model of a line scene, set up: its problem, layout and the threshold.
pub struct LineSetup<M: EnergyModel> {
    /// The problem (no imperfection).
    pub problem: Problem<M>,
    /// What its fields are.
    pub layout: LineLayout,
    /// The buckling analysis.
    pub buckling: LinearBuckling,
    /// Its summary.
    pub threshold: LineThreshold,
}

/// Builds the problem of `scene` for `model` and buckles it.
pub fn set_up_line<M: EnergyModel>(scene: &Scene, mut model: M) -> Result<LineSetup<M>, Error> {
    let started = Instant::now();
    let layout = line_layout_of::<M>(scene)?;
    let wavenumber = line_wavenumber(scene)?;
    configure_line_model(scene, &mut model, wavenumber)?;
    let problem = build_line_problem(scene, model)?;
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern())
        .map_err(|e| Error::Solver(format!("analysing the tangent: {e}")))?;
    let mut options = LinearBucklingOptions::default();
    options.eigen.max_krylov = MAX_KRYLOV;
    let buckling = linear_buckling(&problem, &mut factor, &options)
        .map_err(|e| Error::Solver(format!("linear buckling: {e}")))?;
    let (mode, mode_envelope) = mode_profiles(scene, &problem, &layout, &buckling, wavenumber);
    let threshold = LineThreshold {
        model: M::SPEC.name.to_string(),
        element: format!("{:?}", problem.assembler.mesh().kind),
        elements: problem.assembler.mesh().element_count(),
        free_dofs: problem.free_count(),
        critical_load: buckling.critical_loads[0],
        load: line_load_quantity(scene),
        wavenumber,
        eigen_residual: buckling.residuals.first().copied().unwrap_or(f64::NAN),
        mode,
        mode_envelope,
        seconds: started.elapsed().as_secs_f64(),
    };
    Ok(LineSetup {
        problem,
        layout,
        buckling,
        threshold,
    })
}

/// The first mode's deflection and envelope amplitude along X, scaled to a unit peak of
/// $`|w|`$.
fn mode_profiles<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &LineLayout,
    buckling: &LinearBuckling,
    wavenumber: f64,
) -> (Samples, Samples) {
    let global = problem.dofs().expand(&buckling.modes[0], 0.0);
    let mesh = problem.assembler.mesh();
    let xs = sample_positions(scene.geometry.length_x, wavenumber);
    let w: Vec<f64> = xs
        .iter()
        .map(|&x| layout.deflection_at(mesh, &global, wavenumber, x))
        .collect();
    let peak = w.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let scale = if peak > 0.0 { 1.0 / peak } else { 1.0 };
    let mode = xs.iter().zip(&w).map(|(&x, &w)| (x, w * scale)).collect();
    let envelope = xs
        .iter()
        .filter_map(|&x| {
            layout
                .envelope_amplitude_at(mesh, &global, x)
                .map(|a| (x, a * scale))
        })
        .collect();
    (mode, envelope)
}

/// `wrinkle buckle` on a line scene.
pub fn buckle_line(scene: &Scene) -> Result<LineThreshold, Error> {
    struct Buckle<'a>(&'a Scene);
    impl ModelVisitor for Buckle<'_> {
        type Output = Result<LineThreshold, Error>;
        fn visit<M: EnergyModel>(self, model: M) -> Self::Output {
            set_up_line(self.0, model).map(|setup| setup.threshold)
        }
    }
    wrinkle_models::with_model(&scene.model.name, Buckle(scene))
        .unwrap_or_else(|| Err(crate::setup::unknown_model(scene)))
}

/// The text `wrinkle buckle` prints for a line scene.
pub fn line_threshold_text(threshold: &LineThreshold) -> String {
    let load = &threshold.load;
    format!(
        "model {} on a line: {} {} elements, {} free dofs\n\
         critical load λ_c = {:.10} {} ({}; eigen-residual {:.1e})\n\
         carrier wavenumber Q = {} 1/mm\n\
         analysis {:.2} s\n",
        threshold.model,
        threshold.elements,
        threshold.element,
        threshold.free_dofs,
        threshold.critical_load,
        load.unit,
        load.description,
        threshold.eigen_residual,
        threshold.wavenumber,
        threshold.seconds
    )
}
