//! Physics glue between scenes and the runtime: each command picks the scene's model from the
//! registry (monomorphised through [`ModelVisitor`]), builds the problem and calls a solver.

use crate::Error;
use crate::scene::{LoadKind, Scene, Wavenumber};
use crate::setup::{build_problem, configure_model};
use serde_json::json;
use std::path::Path;
use std::time::Instant;
use wrinkle_models::{ModelVisitor, with_model};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::brent::minimize_scalar;
use wrinkle_runtime::solve::buckling::{LinearBuckling, LinearBucklingOptions, linear_buckling};
use wrinkle_runtime::solve::ellipticity::{EllipticityReport, legendre_hadamard};

/// Result of a linear buckling analysis (`wrinkle buckle`).
#[derive(Clone, Debug)]
pub struct BuckleReport {
    /// Registry name of the model that was solved.
    pub model: String,
    /// Critical load $`\lambda_c`$ (N/mm for the biaxial load, mm for the strip).
    pub critical_load: f64,
    /// Wavenumber $`Q`$ used (1/mm).
    pub wavenumber: f64,
    /// Number of unknowns after constraints.
    pub dofs: usize,
    /// Wavelength $`2\pi/Q`$ (mm).
    pub wavelength: f64,
    /// Closed-form critical load (THEORY.md §8, eq. 42) when one exists for the scene.
    pub closed_form_critical_load: Option<f64>,
    /// Extra model- or solver-specific results, merged into the JSON output.
    pub details: serde_json::Value,
}

/// The scene error for a `model.name` that is not in the registry.
pub(crate) fn unknown_model(scene: &Scene) -> Error {
    crate::setup::scene_error(
        scene,
        "model.name",
        format!(
            "unknown model `{}` (models: {})",
            scene.model.name,
            wrinkle_models::names().join(", ")
        ),
    )
}

fn solver_error(e: impl std::fmt::Display) -> Error {
    Error::Solver(e.to_string())
}

/// A starting guess for the wavenumber: eq. (44) from the scene's tension (biaxial) or from
/// a nominal transverse stress $`10^{-3}E`$ over the width (strip), which the scan then refines.
pub fn wavenumber_guess(scene: &Scene) -> f64 {
    let rectangle = scene.clamped_rectangle();
    match scene.load.kind {
        LoadKind::Biaxial if scene.load.tension_y > 0.0 => rectangle.approximate_wavenumber(),
        _ => {
            let nu = scene.material.poisson_ratio;
            let h = scene.material.thickness;
            let width = scene.geometry.length_x.min(scene.geometry.length_y);
            (12.0 * std::f64::consts::PI.powi(2) * (1.0 - nu * nu)).powf(0.25) / (h * width).sqrt()
                * 1e-3f64.powf(0.25)
        }
    }
}

/// Legendre–Hadamard check of the state at the first critical load (pre-buckling state
/// extrapolated linearly to $`\lambda_c`$).
fn ellipticity_at_critical<M: EnergyModel>(
    problem: &Problem<M>,
    buckling: &LinearBuckling,
    reference_load: f64,
) -> EllipticityReport {
    let mu = buckling.critical_loads[0] - reference_load;
    let state: Vec<f64> = buckling
        .prebuckling
        .iter()
        .zip(&buckling.prebuckling_rate)
        .map(|(u, r)| u + mu * r)
        .collect();
    legendre_hadamard(problem, &state, buckling.critical_loads[0])
}

/// Critical load of `problem` at wavenumber `q` (the model is re-parameterised in place; the
/// pattern and symbolic factorisation are reused).
fn critical_load_at<M: EnergyModel>(
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    q: f64,
    options: &LinearBucklingOptions,
) -> Result<LinearBuckling, Error> {
    let mut model = problem.assembler.model().clone();
    model
        .set_parameter("wavenumber", q)
        .map_err(Error::Solver)?;
    problem.assembler.set_model(model);
    linear_buckling(problem, factor, options).map_err(solver_error)
}

/// Area fraction of the domain where the Legendre–Hadamard condition may fail at a buckling
/// load before that load is rejected as a mesh-scale mode. Failures at isolated points (the
/// stress singularities at clamped–free corners) do not disqualify a wavenumber; a failure over
/// the bulk, as when $`\lambda > 6DQ^2`$ makes the envelope equation hyperbolic, does.
pub const SPURIOUS_MODE_AREA_FRACTION: f64 = 1e-2;

/// The critical load at `q` if the model is still strongly elliptic there, else $`+\infty`$:
/// beyond the loss of ellipticity the lowest discrete eigenvalue is a mesh-scale mode, not a
/// threshold of the model.
fn valid_critical_load<M: EnergyModel>(
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    q: f64,
    options: &LinearBucklingOptions,
) -> Result<f64, Error> {
    let buckling = critical_load_at(problem, factor, q, options)?;
    let report = ellipticity_at_critical(problem, &buckling, options.reference_load);
    Ok(if report.violated_fraction <= SPURIOUS_MODE_AREA_FRACTION {
        buckling.critical_loads[0]
    } else {
        f64::INFINITY
    })
}

/// Minimises the critical load over $`Q`$: a log-scan over a factor 4 either side of `guess`,
/// then Brent in the best bracket. Returns $`(Q^*, \lambda_c, \text{evaluations})`$.
fn minimise_over_wavenumber<M: EnergyModel>(
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    guess: f64,
    options: &LinearBucklingOptions,
) -> Result<(f64, LinearBuckling, usize), Error> {
    let scan: Vec<f64> = (0..9)
        .map(|k| guess * 2f64.powf((k as f64 - 4.0) / 2.0))
        .collect();
    let mut values = Vec::with_capacity(scan.len());
    for &q in &scan {
        values.push(valid_critical_load(problem, factor, q, options).unwrap_or(f64::INFINITY));
    }
    let best = (0..scan.len())
        .min_by(|&a, &b| values[a].total_cmp(&values[b]))
        .expect("scan is not empty");
    if !values[best].is_finite() {
        return Err(Error::Solver(format!(
            "no buckling load for any wavenumber in [{:.4e}, {:.4e}] 1/mm",
            scan[0],
            scan[scan.len() - 1]
        )));
    }
    let low = if best == 0 {
        scan[0] / 2.0
    } else {
        scan[best - 1]
    };
    let high = if best + 1 == scan.len() {
        scan[best] * 2.0
    } else {
        scan[best + 1]
    };
    let minimum = minimize_scalar(
        |q| {
            Ok::<f64, Error>(
                valid_critical_load(problem, factor, q, options).unwrap_or(f64::INFINITY),
            )
        },
        low,
        high,
        1e-8 * scan[best],
        200,
    )?;
    let buckling = critical_load_at(problem, factor, minimum.argument, options)?;
    Ok((
        minimum.argument,
        buckling,
        scan.len() + minimum.evaluations + 1,
    ))
}

struct BuckleVisitor<'a> {
    scene: &'a Scene,
}

impl ModelVisitor for BuckleVisitor<'_> {
    type Output = Result<BuckleReport, Error>;

    fn visit<M: EnergyModel>(self, mut model: M) -> Self::Output {
        let scene = self.scene;
        let start = Instant::now();
        let has_wavenumber = M::SPEC.parameter_index("wavenumber").is_some();
        let initial_q = match scene.model.wavenumber {
            Wavenumber::Fixed(q) => q,
            Wavenumber::Auto => wavenumber_guess(scene),
        };
        configure_model(scene, &mut model, initial_q)?;
        let mut problem = build_problem(scene, model, 0.0)?;
        let mut factor = SparseFactorization::analyze(problem.assembler.pattern())
            .map_err(|e| Error::Solver(format!("symbolic analysis of the tangent: {e}")))?;
        let options = LinearBucklingOptions::default();
        let (q, buckling, evaluations) = match (scene.model.wavenumber, has_wavenumber) {
            (Wavenumber::Auto, true) => {
                minimise_over_wavenumber(&mut problem, &mut factor, initial_q, &options)?
            }
            _ => {
                let b = linear_buckling(&problem, &mut factor, &options).map_err(solver_error)?;
                (initial_q, b, 1)
            }
        };
        let critical = buckling.critical_loads[0];
        let ellipticity = ellipticity_at_critical(&problem, &buckling, options.reference_load);
        let rectangle = scene.clamped_rectangle();
        let closed_form = (scene.load.kind == LoadKind::Biaxial
            && M::SPEC.name == "reference-envelope"
            && scene.model.direction_degrees == 0.0)
            .then(|| rectangle.critical_point())
            .flatten();
        let details = json!({
            "load_kind": scene.load.kind.as_str(),
            "n_x": if scene.load.kind == LoadKind::Biaxial { Some(-critical) } else { None },
            "eigen_residual": buckling.residuals[0],
            "eigen_iterations": buckling.eigen_iterations,
            "buckling_evaluations": evaluations,
            "wavenumber_mode": match scene.model.wavenumber { Wavenumber::Auto => "auto", Wavenumber::Fixed(_) => "fixed" },
            "closed_form_wavenumber": closed_form.map(|(_, q)| q),
            "closed_form_relative_difference": closed_form.map(|(l, _)| (critical - l) / l),
            "elliptic_at_threshold": ellipticity.elliptic,
            "ellipticity_margin": ellipticity.worst_margin,
            "ellipticity_worst_location": ellipticity.location,
            "ellipticity_worst_field": ellipticity.field,
            "ellipticity_violated_area_fraction": ellipticity.violated_fraction,
            "elements": scene.mesh.elements_x * scene.mesh.elements_y,
            "kernel_calls_per_assembly": problem.assembler.kernel_calls(),
            "seconds": start.elapsed().as_secs_f64(),
        });
        Ok(BuckleReport {
            model: M::SPEC.name.to_string(),
            critical_load: critical,
            wavenumber: q,
            dofs: problem.free_count(),
            wavelength: 2.0 * std::f64::consts::PI / q,
            closed_form_critical_load: closed_form.map(|(l, _)| l),
            details,
        })
    }
}

/// Linear buckling analysis of a scene.
pub fn buckle(scene: &Scene) -> Result<BuckleReport, Error> {
    with_model(&scene.model.name, BuckleVisitor { scene })
        .unwrap_or_else(|| Err(unknown_model(scene)))
}

/// Path following of a scene, writing its outputs into `output_directory`. A path that ends by
/// a solver failure is an `Err` too, but only after every output computed so far was written.
pub fn run(scene: &Scene, output_directory: &Path) -> Result<crate::run::RunReport, Error> {
    let report = crate::run::run(scene, output_directory)?;
    if let Some(failure) = &report.failure {
        return Err(Error::Solver(format!(
            "{failure} (points computed so far written to {})",
            output_directory.display()
        )));
    }
    Ok(report)
}

/// The model registry: `(name, description, fields, parameters)` for every model.
pub fn models() -> Vec<(String, String, Vec<String>, Vec<String>)> {
    wrinkle_models::catalogue()
        .into_iter()
        .map(|s| {
            (
                s.name.to_string(),
                s.description.to_string(),
                s.fields.iter().map(|f| f.to_string()).collect(),
                s.parameters.iter().map(|p| p.to_string()).collect(),
            )
        })
        .collect()
}
