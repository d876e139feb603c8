//! The wrinkling threshold of a scene: linear buckling of the problem, minimised over the
//! wavenumber for envelope models (`model.wavenumber = "auto"`), with the validity checks that
//! say whether the number can be trusted.
//!
//! **Wavenumber range.** The search scans $`\lambda_c(Q)`$ over the whole range where an
//! envelope model is meaningful — wavelengths $`\ell = 2\pi/Q`$ between
//! [`MIN_WAVELENGTH_OVER_THICKNESS`]$`\,h`$ and the shorter side of the domain — then refines
//! the best bracket (`wrinkle_runtime::solve::wavenumber`). **Two levels**: the global scan and
//! a refinement to 1 % in $`Q`$ run on a mesh with half the elements each way; the real mesh then
//! only refines around that minimiser (successive parabolic interpolation from it and its
//! neighbours at ±2 %, falling back to 3 scan points within ±10 % and Brent when the minimum is
//! not bracketed there), to $`2\cdot10^{-4}`$ in $`Q`$ — $`\lambda_c`$ is flat to second order
//! there, so that is about $`10^{-7}`$ in $`\lambda_c`$. **Closed-form start**: where eq. (42)
//! has a minimum inside the range (a biaxial scene with waves along X, the clamped rectangle
//! of THEORY.md §8), the real mesh is searched directly from that minimum, as it would be from
//! the half mesh's (±2 %, shifted about the closed-form $`\lambda_c`$). When no minimum is
//! bracketed there, or the one found lies at the edge of the ±10 % bracket (a model whose
//! $`\lambda_c(Q)`$ is not the one eq. (42) solves), the two-level search runs as above, its
//! half mesh starting locally from the closed form ±3 % (`closed_form_start`) and falling back
//! to the scan: the closed form decides where the search starts, not what it finds.
//!
//! **Where the wavenumber comes from** follows from the model's capability, derived from its
//! roles and jet (`wrinkle_runtime::wavelength`), never from its name: a model that selects its
//! own wavelength is searched as above; a model that does not (an envelope without gradient, the
//! pure membrane; a complex envelope, whose phase moves the local wavenumber freely) takes the
//! minimiser of the scene's `model.wavenumber_model` (default the registry's reference
//! envelope), and so does a searched model whose $`\lambda_c(Q)`$ keeps falling to the end of the
//! range — a note says so each time; a plate has no wavenumber. The wavenumber model's threshold
//! is computed at most once per run, when first needed ([`WavenumberModel`]); it also gives the
//! shift of a second buckling attempt when the first, about $`\lambda = 0`$, fails. When the
//! scene's model *is* the wavenumber model there is none: nothing falls back, and a minimum at
//! the long-wavelength end gets its own note.
//!
//! **Reuse.** `wrinkle run --threshold FILE` replaces the search by one analysis at the $`Q`$ of
//! an earlier threshold of the same scene ([`PriorThreshold`], [`ThresholdOptions::prior`]).
//!
//! **Validity checks** (warnings in the summary, exit code 4 unless the scene accepts them):
//! * scale separation of envelope models: $`\ell \le L_\min /`$ [`MIN_WAVES_PER_DOMAIN`] and
//!   $`\ell \ge`$ [`MIN_WAVELENGTH_OVER_THICKNESS`]$`\,h`$;
//! * strong ellipticity at the threshold (area fraction where the Legendre–Hadamard condition
//!   fails at most [`MAX_NON_ELLIPTIC_FRACTION`]);
//! * mode resolution of the plate: at least [`MIN_ELEMENTS_PER_WAVELENGTH`] elements per
//!   wavelength along the wave direction;
//! * well-posedness beyond the threshold: a field without gradient stiffness (the pure
//!   membrane's envelope) that is pointwise unstable over most of the area at
//!   [`WELL_POSEDNESS_LOAD_RATIO`]$`\,\lambda_c`$ on the fundamental branch.

mod direction;
mod result;
mod reuse;
mod scene_quantities;
mod search;
mod steps;
mod summary;
mod validity;
mod wavenumber_model;

pub use result::{Threshold, ValidityWarning};
pub use reuse::{PriorThreshold, THRESHOLD_SECTIONS};
pub use scene_quantities::{closed_form_threshold, load_unit, wavenumber_range};
pub use summary::{ClosedFormComparison, ThresholdSummary};
pub use validity::{
    MAX_NON_ELLIPTIC_FRACTION, MIN_ELEMENTS_PER_WAVELENGTH, MIN_WAVELENGTH_OVER_THICKNESS,
    MIN_WAVES_PER_DOMAIN, WELL_POSEDNESS_LOAD_RATIO,
};
pub use wavenumber_model::{CarrierThreshold, WAVENUMBER_MODEL_KEY, WavenumberModel};

use crate::error::Error;
use crate::physics::{Layout, Snapshot, wavelength_along_line};
use crate::scene::{Direction, LoadKind, PathMethod, Scene, Wavenumber};
use crate::setup::{build_problem, configure_model, layout_of, unknown_model};
use std::f64::consts::PI;
use steps::ThresholdSteps;
use validity::{ModeOnMesh, validity_warnings, well_posedness_beyond};
use wrinkle_models::{ModelVisitor, with_model};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::LinearBuckling;

/// How a threshold is found, besides its scene.
#[derive(Clone, Copy, Debug, Default)]
pub struct ThresholdOptions<'a> {
    /// No progress on standard error.
    pub quiet: bool,
    /// The wavenumber of an earlier threshold of the same scene, reused instead of the search
    /// (`--threshold FILE`, [`PriorThreshold`]).
    pub prior: Option<&'a PriorThreshold>,
    /// A wavenumber model shared with other runs (`wrinkle compare`), used when it computes the
    /// same threshold as this scene's own ([`WavenumberModel::same_as`]); otherwise the scene's
    /// is made here.
    pub wavenumber_model: Option<&'a WavenumberModel>,
}

/// Finds the threshold of `problem` (built from `scene`, parameters set). For an envelope
/// model with `wavenumber = "auto"` the model in `problem` is left at the minimiser.
pub fn find_threshold<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    quiet: bool,
) -> Result<Threshold, Error> {
    let options = ThresholdOptions {
        quiet,
        ..ThresholdOptions::default()
    };
    find_threshold_with(scene, problem, factor, &options)
}

/// [`find_threshold`] with its [`ThresholdOptions`]: an earlier threshold's wavenumber reused,
/// a wavenumber model shared with other runs.
///
/// What the wavenumber is follows from the model's capability
/// ([`ModelSpec::wavelength_selection`](wrinkle_runtime::ModelSpec::wavelength_selection)) and
/// the scene: a fixed `model.wavenumber`; the minimiser of $`\lambda_c(Q)`$ for a model that
/// selects its own; the minimiser of `model.wavenumber_model` for one that does not; none for
/// a model that resolves its wrinkles on the mesh.
///
/// With `model.direction = "auto"` the wave direction is chosen first (module `direction`): the
/// threshold is then that of the scene with the direction fixed at the chosen angle.
pub fn find_threshold_with<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &ThresholdOptions,
) -> Result<Threshold, Error> {
    match scene.model.direction {
        Direction::Fixed(_) => fixed_direction_threshold(scene, problem, factor, options),
        Direction::Auto => direction::auto_direction_threshold(scene, problem, factor, options),
    }
}

/// [`find_threshold_with`] for a scene whose `model.direction` is an angle.
fn fixed_direction_threshold<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &ThresholdOptions,
) -> Result<Threshold, Error> {
    let start = std::time::Instant::now();
    let direction = scene.model.direction.fixed_degrees().unwrap_or(0.0);
    let layout = layout_of::<M>(scene)?;
    require_free_primary_dofs(scene, problem, &layout, M::SPEC.fields[layout.primary])?;
    let own = WavenumberModel::of(scene)?;
    let wavenumber_model = own.as_ref().map(|own| match options.wavenumber_model {
        Some(shared) if shared.same_as(own) => shared,
        _ => own,
    });
    let mut steps = ThresholdSteps {
        scene,
        quiet: options.quiet,
        wavenumber_model,
        notes: unused_keys_notes(scene),
    };
    let found = steps.critical_point(problem, factor, options.prior)?;
    let wavelength = match found.wavenumber {
        Some(q) => Some(2.0 * PI / q),
        None => mode_wavelength(scene, problem, &layout, &found.buckling, direction),
    };
    let mut threshold = Threshold {
        model: M::SPEC.name,
        evaluations: found.search.len().max(1),
        buckling: found.buckling,
        ellipticity: found.ellipticity,
        reference_load: found.reference_load,
        wavenumber: found.wavenumber,
        wavelength,
        wavenumber_source: found.source,
        direction_degrees: direction,
        direction_source: "fixed".into(),
        search: found.search,
        notes: steps.notes,
        warnings: Vec::new(),
        dofs: problem.free_count(),
        seconds: 0.0,
    };
    threshold.warnings = threshold_checks(scene, problem, &layout, &threshold);
    threshold.seconds = start.elapsed().as_secs_f64();
    Ok(threshold)
}

/// The failed validity checks of `threshold` (module documentation), found on `problem`.
fn threshold_checks<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
    threshold: &Threshold,
) -> Vec<ValidityWarning> {
    let mode = mode_on_mesh(problem, layout, &threshold.buckling);
    let mut warnings = validity_warnings(scene, layout, threshold, &mode);
    warnings.extend(well_posedness_beyond(
        problem,
        &threshold.buckling,
        threshold.reference_load,
    ));
    warnings
}

/// A scene error naming `mesh.nx` when the primary field (the deflection or envelope) has no
/// free dof: on a 1 × 1 Q8 mesh every node lies on the clamped boundary, so $`w \equiv 0`$ and
/// there is nothing to buckle. Without this check the eigen-solver reports "no positive
/// buckling load factor … the load does not compress the structure", the wrong reason.
fn require_free_primary_dofs<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
    field: &str,
) -> Result<(), Error> {
    let dofs = problem.dofs();
    let free = (0..problem.free_count())
        .filter(|&i| dofs.global_of_free(i) % layout.field_count == layout.primary)
        .count();
    if free > 0 {
        return Ok(());
    }
    Err(Error::scene(
        format!("scene {}", scene.source),
        "mesh.nx",
        format!(
            "a {} × {} mesh leaves no free value of `{field}`: every Q8 node lies on the clamped boundary, so there is no mode to buckle; use at least 2 elements along one side",
            scene.mesh.elements_x, scene.mesh.elements_y
        ),
    ))
}

/// Symbolic analysis of the tangent's pattern.
pub fn analyse<M: EnergyModel>(problem: &Problem<M>) -> Result<SparseFactorization, Error> {
    SparseFactorization::analyze(problem.assembler.pattern())
        .map_err(|e| Error::Solver(format!("symbolic analysis of the tangent: {e}")))
}

/// The primary field of the first buckling mode at the nodes, for the mode-resolution check.
fn mode_on_mesh<'a, M: EnergyModel>(
    problem: &'a Problem<M>,
    layout: &Layout,
    buckling: &LinearBuckling,
) -> ModeOnMesh<'a> {
    let mesh = problem.assembler.mesh();
    let nodal = buckling.modes.first().map_or_else(Vec::new, |mode| {
        let values = problem.dofs().expand_increment(mode, 0.0);
        values
            .chunks_exact(layout.field_count)
            .map(|node| node[layout.primary])
            .collect()
    });
    ModeOnMesh { mesh, nodal }
}

/// The plate's wavelength, read from its first mode along the line through the mode's largest
/// deflection in the wave direction (`direction`, degrees from X).
fn mode_wavelength<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
    buckling: &LinearBuckling,
    direction: f64,
) -> Option<f64> {
    let mode = buckling.modes.first()?;
    let mesh = problem.assembler.mesh();
    let values = problem.dofs().expand_increment(mode, 0.0);
    let nf = layout.field_count;
    let peak = (0..mesh.nodes.len())
        .max_by(|&a, &b| {
            values[a * nf + layout.primary]
                .abs()
                .total_cmp(&values[b * nf + layout.primary].abs())
        })
        .map(|n| mesh.nodes[n])?;
    let snapshot = Snapshot {
        mesh,
        layout,
        values: &values,
        wavenumber: 0.0,
        direction: direction.to_radians(),
    };
    let length = 2.0 * scene.geometry.length_x.hypot(scene.geometry.length_y);
    wavelength_along_line(&snapshot, [peak[0], peak[1]], length)
}

struct ThresholdVisitor<'a> {
    scene: &'a Scene,
    quiet: bool,
}

impl ModelVisitor for ThresholdVisitor<'_> {
    type Output = Result<Threshold, Error>;
    fn visit<M: EnergyModel>(self, mut model: M) -> Self::Output {
        let q = match self.scene.model.wavenumber {
            Wavenumber::Fixed(q) => q,
            Wavenumber::Auto => 1.0,
        };
        configure_model(self.scene, &mut model, q)?;
        let mut problem = build_problem(self.scene, model)?;
        let mut factor = analyse(&problem)?;
        find_threshold(self.scene, &mut problem, &mut factor, self.quiet)
    }
}

/// Linear buckling analysis of a scene (`wrinkle buckle`).
pub fn buckle(scene: &Scene, quiet: bool) -> Result<Threshold, Error> {
    with_model(&scene.model.name, ThresholdVisitor { scene, quiet })
        .unwrap_or_else(|| Err(unknown_model(scene)))
}

/// Notes for keys the scene gives that it does not use: `load.tension_y` under the strip load
/// (example 2 has no tension); the ANM's settings (`solver.order`, `solver.series_tolerance`,
/// `solver.pade`, `solver.exponential_map`, `solver.mode_parameter`) under Riks, which has no
/// series.
fn unused_keys_notes(scene: &Scene) -> Vec<String> {
    let mut notes = Vec::new();
    if scene.solver.method == PathMethod::Riks {
        for key in [
            "solver.order",
            "solver.series_tolerance",
            "solver.pade",
            "solver.exponential_map",
            "solver.mode_parameter",
        ] {
            if scene.was_given(key) {
                notes.push(format!(
                    "`{key}` is ignored: it sets the ANM's series, and `solver.method = \"riks\"` has none"
                ));
            }
        }
    }
    if scene.load.kind == LoadKind::Strip && scene.was_given("load.tension_y") {
        notes.push(format!(
            "`load.tension_y` = {} is ignored: the strip load (`load.kind = \"strip\"`) has no tension",
            scene.load.tension_y
        ));
    }
    notes
}
