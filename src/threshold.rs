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

mod reuse;
mod wavenumber_model;

pub use reuse::{PriorThreshold, THRESHOLD_SECTIONS};
pub use wavenumber_model::{CarrierThreshold, WAVENUMBER_MODEL_KEY, WavenumberModel};

use crate::error::Error;
use crate::output::{ProgressSink, SearchProgress};
use crate::physics::{Layout, Snapshot, wavelength_along_line};
use crate::scene::{LoadKind, Scene, Wavenumber};
use crate::setup::{build_problem, configure_model, layout_of, unknown_model};
use serde_json::json;
use std::f64::consts::PI;
use wrinkle_models::{ModelVisitor, with_model};
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::{LinearBuckling, LinearBucklingOptions, linear_buckling};
use wrinkle_runtime::solve::ellipticity::EllipticityReport;
use wrinkle_runtime::solve::wavenumber::{
    LOCAL_SHIFT, LocalGuess, WavenumberEvaluation, WavenumberSearch, WavenumberSearchOptions,
    ellipticity_at_critical_load, minimise_critical_load, set_model_parameter,
};
use wrinkle_runtime::wavelength::{CarriedBecause, WAVENUMBER_PARAMETER, WavelengthSelection};

/// Shortest wavelength an envelope model accepts, in thicknesses.
pub const MIN_WAVELENGTH_OVER_THICKNESS: f64 = 20.0;
/// Fewest wavelengths across the shorter side of the domain for an envelope model's scale
/// separation.
pub const MIN_WAVES_PER_DOMAIN: f64 = 4.0;
/// Area fraction where strong ellipticity may fail at the threshold (stress singularities at
/// clamped–free corners) before the threshold is flagged.
pub const MAX_NON_ELLIPTIC_FRACTION: f64 = 1e-2;
/// Fewest Q8 elements per wavelength for a resolved plate mode.
pub const MIN_ELEMENTS_PER_WAVELENGTH: f64 = 8.0;

/// A validity check that failed.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ValidityWarning {
    /// Short identifier: `scale_separation`, `ellipticity`, `mode_resolution`.
    pub check: &'static str,
    /// What was found and what it means.
    pub message: String,
}

/// The threshold of a scene and how it was found.
#[derive(Clone, Debug)]
pub struct Threshold {
    /// Registry name of the model.
    pub model: &'static str,
    /// Linear buckling at the threshold (critical loads, modes, pre-buckling state and rate).
    pub buckling: LinearBuckling,
    /// Strong ellipticity at the threshold.
    pub ellipticity: EllipticityReport,
    /// Load the buckling analysis linearised about (0, or a shift, see `robust_buckling`).
    pub reference_load: f64,
    /// Wavenumber $`Q`$ (1/mm) of an envelope model.
    pub wavenumber: Option<f64>,
    /// Wavelength (mm): $`2\pi/Q`$, or read from the plate's mode.
    pub wavelength: Option<f64>,
    /// `"fixed"`, `"auto"` (minimised), `"auto (MODEL)"` (the minimiser of `MODEL`, the scene's
    /// `model.wavenumber_model`), `"auto (reused)"` or `"mode"` (plate).
    pub wavenumber_source: String,
    /// Linear buckling analyses done.
    pub evaluations: usize,
    /// The wavenumber search, when there was one.
    pub search: Vec<WavenumberEvaluation>,
    /// Notes for the user (a parameter not used, where the wavenumber came from).
    pub notes: Vec<String>,
    /// Failed validity checks.
    pub warnings: Vec<ValidityWarning>,
    /// Free unknowns.
    pub dofs: usize,
    /// Seconds spent.
    pub seconds: f64,
}

impl Threshold {
    /// Critical load $`\lambda_c`$.
    pub fn critical_load(&self) -> f64 {
        self.buckling.critical_loads[0]
    }

    /// The first failed validity check the scene does not accept (`validity.accept`), as the
    /// reason of exit code 4 — shared by `buckle` and `run`.
    pub fn validity_failure(&self, validity: &crate::scene::ValiditySpec) -> Option<String> {
        self.warnings
            .iter()
            .find(|w| !validity.accepts(w.check))
            .map(|w| {
                format!(
                    "{}: {} (`validity.accept = [\"{}\"]` accepts it)",
                    w.check, w.message, w.check
                )
            })
    }
}

/// Wavenumber range $`[2\pi/L_\min, 2\pi/(20h)]`$ (1/mm) the search scans.
pub fn wavenumber_range(scene: &Scene) -> (f64, f64) {
    let shortest = scene.geometry.length_x.min(scene.geometry.length_y);
    let thickness = scene.material.thickness;
    let low = 2.0 * PI / shortest;
    let high = 2.0 * PI / (MIN_WAVELENGTH_OVER_THICKNESS * thickness);
    (low, high.max(4.0 * low))
}

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
pub fn find_threshold_with<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &ThresholdOptions,
) -> Result<Threshold, Error> {
    let start = std::time::Instant::now();
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
        notes: Vec::new(),
    };
    let found = steps.critical_point(problem, factor, options.prior)?;
    let wavelength = match found.wavenumber {
        Some(q) => Some(2.0 * PI / q),
        None => mode_wavelength(scene, problem, &layout, &found.buckling),
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
        search: found.search,
        notes: steps.notes,
        warnings: Vec::new(),
        dofs: problem.free_count(),
        seconds: 0.0,
    };
    threshold.warnings = validity_warnings(scene, &layout, &threshold);
    threshold.warnings.extend(well_posedness_beyond(
        problem,
        &threshold.buckling,
        threshold.reference_load,
    ));
    threshold.seconds = start.elapsed().as_secs_f64();
    Ok(threshold)
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

/// The linear buckling a threshold settles on, before its validity checks.
struct CriticalPoint {
    /// Critical loads, modes, pre-buckling state and rate.
    buckling: LinearBuckling,
    /// Strong ellipticity at the critical load.
    ellipticity: EllipticityReport,
    /// Load the analysis linearised about.
    reference_load: f64,
    /// Wavenumber $`Q`$ of an envelope model.
    wavenumber: Option<f64>,
    /// Where $`Q`$ came from ([`Threshold::wavenumber_source`]).
    source: String,
    /// The wavenumber search, when there was one.
    search: Vec<WavenumberEvaluation>,
}

/// The steps of one threshold: its scene, whether progress is shown, the wavenumber model
/// (`None` when the scene's model is that model) and the notes collected for the user.
struct ThresholdSteps<'a> {
    scene: &'a Scene,
    quiet: bool,
    wavenumber_model: Option<&'a WavenumberModel>,
    notes: Vec<String>,
}

impl ThresholdSteps<'_> {
    /// The critical point by the model's capability and the scene's `model.wavenumber`.
    fn critical_point<M: EnergyModel>(
        &mut self,
        problem: &mut Problem<M>,
        factor: &mut SparseFactorization,
        prior: Option<&PriorThreshold>,
    ) -> Result<CriticalPoint, Error> {
        let wavenumber = self.scene.model.wavenumber;
        match (M::SPEC.wavelength_selection(), wavenumber, prior) {
            (WavelengthSelection::ResolvedByMesh, _, _) => self.resolved_by_mesh(problem, factor),
            (_, Wavenumber::Fixed(q), _) => {
                // Shifted about eq. (42) at this Q where it applies (`closed_form_load_at`).
                let guess = closed_form_load_at(self.scene, q);
                let (buckling, ellipticity, shift) =
                    self.buckle_at_wavenumber(problem, factor, q, guess)?;
                Ok(critical_point(buckling, ellipticity, shift, q, "fixed"))
            }
            (_, Wavenumber::Auto, Some(prior)) => self.reused(problem, factor, prior),
            (WavelengthSelection::Carried(because), Wavenumber::Auto, None) => {
                self.carried(problem, factor, because)
            }
            (WavelengthSelection::OwnMinimum, Wavenumber::Auto, None) => {
                self.search_wavenumber(problem, factor)
            }
        }
    }

    /// A plate: no wavenumber; its wavelength is read from the mode.
    fn resolved_by_mesh<M: EnergyModel>(
        &mut self,
        problem: &mut Problem<M>,
        factor: &mut SparseFactorization,
    ) -> Result<CriticalPoint, Error> {
        if matches!(self.scene.model.wavenumber, Wavenumber::Fixed(_)) {
            self.notes.push(format!(
                "model `{}` has no wavenumber: `model.wavenumber` is ignored (its wrinkles are resolved by the mesh)",
                M::SPEC.name
            ));
        }
        let (buckling, reference_load) = self.robust_buckling(problem, factor)?;
        let ellipticity = ellipticity_at_critical_load(problem, &buckling, reference_load);
        Ok(CriticalPoint {
            buckling,
            ellipticity,
            reference_load,
            wavenumber: None,
            source: "mode".into(),
            search: Vec::new(),
        })
    }

    /// One analysis at the wavenumber of an earlier threshold of the same scene.
    fn reused<M: EnergyModel>(
        &mut self,
        problem: &mut Problem<M>,
        factor: &mut SparseFactorization,
        prior: &PriorThreshold,
    ) -> Result<CriticalPoint, Error> {
        let q = prior.wavenumber;
        let (buckling, ellipticity, shift) =
            self.buckle_at_wavenumber(problem, factor, q, Some(prior.critical_load))?;
        self.notes.push(format!(
            "Q = {q:.9e} 1/mm is reused from {} (the minimiser found there for this scene): one analysis at that Q instead of the wavenumber search",
            prior.file
        ));
        Ok(critical_point(
            buckling,
            ellipticity,
            shift,
            q,
            "auto (reused)",
        ))
    }

    /// The wavenumber model and its threshold, computed once; an error when there is none
    /// (the scene's model is the wavenumber model, which selects its own wavelength).
    fn carrier(&self) -> Result<(&str, CarrierThreshold), Error> {
        let model = self.wavenumber_model.ok_or_else(|| {
            Error::Solver(format!(
                "model `{}` is its own `model.wavenumber_model` and does not select its own wavelength",
                self.scene.model.name
            ))
        })?;
        Ok((model.name(), model.threshold(self.quiet)?))
    }

    /// The wavenumber model's $`Q`$ as the carrier of a model that has no wavelength selection
    /// of its own (no envelope gradient) or a free phase, and the linear buckling at it.
    fn carried<M: EnergyModel>(
        &mut self,
        problem: &mut Problem<M>,
        factor: &mut SparseFactorization,
        because: CarriedBecause,
    ) -> Result<CriticalPoint, Error> {
        let (name, carrier) = self.carrier()?;
        let q = carrier.wavenumber;
        let source = format!("auto ({name})");
        self.notes.push(match because {
            CarriedBecause::Phase => format!(
                "model `{}` has a phase: its local wavenumber Q + ∂arg(w1) is free, and its bending (a second-order expansion about Q) is only valid near the carrier Q, so λ_c(Q) has no meaningful minimum of its own; Q = {q:.6e} 1/mm is the {name} minimiser on the same scene",
                M::SPEC.name
            ),
            CarriedBecause::NoEnvelopeGradient => format!(
                "model `{}` has no gradient of its envelope, hence no wavelength selection of its own (its threshold D Q² falls with Q); Q = {q:.6e} 1/mm is the {name} minimiser on the same scene",
                M::SPEC.name
            ),
        });
        // The wavenumber model's threshold is within a fraction of a per cent of this model's
        // at the same Q (example 1: 8.9521e-2 against 8.9519e-2 for the complex envelope): the
        // analysis is shifted about it.
        let (buckling, ellipticity, shift) =
            self.buckle_at_wavenumber(problem, factor, q, Some(carrier.critical_load))?;
        Ok(critical_point(buckling, ellipticity, shift, q, &source))
    }

    /// Linear buckling of `problem` with its wavenumber set to `q` ([`Self::robust_buckling`]),
    /// the ellipticity at the threshold, and the load the analysis linearised about. With a
    /// guess of the critical load the analysis is first shifted to [`LOCAL_SHIFT`] times the
    /// guess (one factorisation and a few Lanczos iterations when the tangent there is still
    /// positive definite, so that no critical load lies below the shift), and falls back to the
    /// unshifted analysis otherwise.
    fn buckle_at_wavenumber<M: EnergyModel>(
        &mut self,
        problem: &mut Problem<M>,
        factor: &mut SparseFactorization,
        q: f64,
        load_guess: Option<f64>,
    ) -> Result<(LinearBuckling, EllipticityReport, f64), Error> {
        set_model_parameter(problem, WAVENUMBER_PARAMETER, q)
            .map_err(|e| Error::Solver(e.to_string()))?;
        if let Some(guess) = load_guess {
            let shift = LOCAL_SHIFT * guess;
            let options = LinearBucklingOptions {
                reference_load: shift,
                ..LinearBucklingOptions::default()
            };
            if let Ok(buckling) = linear_buckling(problem, factor, &options)
                && factor.negative_pivots() == Some(0)
            {
                let ellipticity = ellipticity_at_critical_load(problem, &buckling, shift);
                return Ok((buckling, ellipticity, shift));
            }
        }
        let (buckling, shift) = self.robust_buckling(problem, factor)?;
        let ellipticity = ellipticity_at_critical_load(problem, &buckling, shift);
        Ok((buckling, ellipticity, shift))
    }
}

/// A [`CriticalPoint`] at the wavenumber `q`, found without a search.
fn critical_point(
    buckling: LinearBuckling,
    ellipticity: EllipticityReport,
    reference_load: f64,
    q: f64,
    source: &str,
) -> CriticalPoint {
    CriticalPoint {
        buckling,
        ellipticity,
        reference_load,
        wavenumber: Some(q),
        source: source.into(),
        search: Vec::new(),
    }
}

/// Relative accuracy of $`Q`$ on the coarse mesh of the two-level search.
const COARSE_RELATIVE_TOLERANCE: f64 = 1e-2;
/// Relative accuracy of $`Q`$ on the real mesh: $`\lambda_c`$ is flat to second order at its
/// minimum, $`\delta\lambda_c/\lambda_c \approx 2(\delta Q/Q)^2`$ on eq. (42) near the
/// optimum, so $`2\cdot10^{-4}`$ in $`Q`$ is about $`10^{-7}`$ in $`\lambda_c`$ (measured on example
/// 1: $`10^{-3}`$ gave $`1.4\cdot10^{-6}`$, above the mesh error $`10^{-6}`$).
const FINE_RELATIVE_TOLERANCE: f64 = 2e-4;
/// Log-spaced points of the global scan.
const SCAN_POINTS: usize = 17;
/// Half-width (as a factor) of the bracket around the coarse minimiser searched on the real mesh
/// when the local search does not bracket the minimum.
const LOCAL_BRACKET: f64 = 1.1;
/// Relative distance of the first neighbours of the coarse minimiser on the real mesh: twice the
/// coarse tolerance, which also covers the coarse-to-fine shift of the minimiser (0.35 % on
/// example 1 from 16 × 8 to 32 × 16).
const LOCAL_STEP: f64 = 2e-2;

/// The coarse mesh of the two-level wavenumber search: half the elements each way; `None` when
/// the mesh has fewer than 16 × 8 elements (then the search runs on the mesh itself). The
/// buckling mode of an envelope model is a smooth envelope, so half the elements put the coarse
/// minimiser within the local bracket ([`LOCAL_BRACKET`]) of the fine one.
fn coarse_scene(scene: &Scene) -> Option<Scene> {
    let (nx, ny) = (scene.mesh.elements_x, scene.mesh.elements_y);
    (nx >= 16 && ny >= 8).then(|| {
        let mut coarse = scene.clone();
        coarse.mesh.elements_x = nx / 2;
        coarse.mesh.elements_y = ny / 2;
        coarse
    })
}

impl ThresholdSteps<'_> {
    /// The wavenumber search of a model that selects its own wavelength; the wavenumber
    /// model's $`Q`$ instead when its $`\lambda_c(Q)`$ falls to the long-wavelength end of the
    /// range (no selection after all), or the long-wavelength note when the model is the
    /// wavenumber model itself.
    fn search_wavenumber<M: EnergyModel>(
        &mut self,
        problem: &mut Problem<M>,
        factor: &mut SparseFactorization,
    ) -> Result<CriticalPoint, Error> {
        let range = wavenumber_range(self.scene);
        let search = self.observed_search(problem, factor, range)?;
        let at_lower_end = search.parameter <= range.0 * 1.05;
        if !at_lower_end || self.wavenumber_model.is_none() {
            if at_lower_end {
                self.notes
                    .push(long_wavelength_end_note(self.scene, search.parameter));
            }
            return Ok(CriticalPoint {
                buckling: search.buckling,
                ellipticity: search.ellipticity,
                reference_load: search.reference_load,
                wavenumber: Some(search.parameter),
                source: "auto".into(),
                search: search.evaluations,
            });
        }
        // No wavelength selection: λ_c(Q) falls to the end of the range.
        let (name, carrier) = self.carrier()?;
        let (q, source) = (carrier.wavenumber, format!("auto ({name})"));
        self.notes.push(format!(
            "model `{}` has no wavelength selection of its own (its critical load falls with Q down to the end of the range, {:.3e} 1/mm); Q = {q:.6e} 1/mm is taken from the {name} minimisation on the same scene",
            M::SPEC.name, range.0
        ));
        let (buckling, ellipticity, shift) = self.buckle_at_wavenumber(problem, factor, q, None)?;
        Ok(CriticalPoint {
            search: search.evaluations,
            ..critical_point(buckling, ellipticity, shift, q, &source)
        })
    }

    /// [`two_level_search`] over `range` with its progress on standard error and its failure
    /// explained (the range in wavelengths, the direction and Poisson hints).
    fn observed_search<M: EnergyModel>(
        &self,
        problem: &mut Problem<M>,
        factor: &mut SparseFactorization,
        range: (f64, f64),
    ) -> Result<WavenumberSearch, Error> {
        let options = WavenumberSearchOptions {
            range,
            scan_points: SCAN_POINTS,
            ..WavenumberSearchOptions::default()
        };
        let progress = SearchProgress::new(
            &format!("{}: wavenumber search", M::SPEC.name),
            ProgressSink::standard_error(self.quiet),
        );
        let mut count = 0;
        let mut observer = |e: &WavenumberEvaluation| {
            count += 1;
            progress.evaluation(count, &evaluation_text(e));
        };
        let scene = self.scene;
        let hints = format!("{}{}", direction_hint(scene), poisson_hint(scene));
        let fail = |e: String| {
            Error::Solver(format!(
                "wavenumber search of `{}` over Q in [{:.3e}, {:.3e}] 1/mm (wavelengths from {:.3e} to {:.3e} mm): {e}. \
                 Hint: check that the load compresses the sheet and that the thickness and tension are physical.{hints}",
                M::SPEC.name,
                range.0,
                range.1,
                2.0 * PI / range.1,
                2.0 * PI / range.0
            ))
        };
        let search = two_level_search(scene, problem, factor, &options, &mut observer).map_err(
            |e| match e {
                Error::Solver(message) => fail(message),
                other => other,
            },
        )?;
        progress.finish(&format!(
            "Q = {:.6e}/mm, λ_c = {:.6e}",
            search.parameter, search.buckling.critical_loads[0]
        ));
        Ok(search)
    }
}

/// One evaluation of the wavenumber search as a progress line.
fn evaluation_text(e: &WavenumberEvaluation) -> String {
    match (e.critical_load, &e.rejected) {
        (Some(load), _) => format!("Q = {:.5e}/mm, λ_c = {load:.6e}", e.parameter),
        (None, Some(reason)) => format!(
            "Q = {:.5e}/mm rejected: {}",
            e.parameter,
            reason.split(':').next().unwrap_or(reason)
        ),
        _ => format!("Q = {:.5e}/mm", e.parameter),
    }
}

/// Why a model that selects its own wavelength — the reference envelope, whose $`\lambda_c(Q)`$
/// is eq. (42) — can still find its minimum at the long-wavelength end of the search: in eq.
/// (42), written $`\lambda(s) = (Ds^2 + as + b)/(s + c)`$ in $`s = Q^2`$, the minimiser is
/// $`s^* = -c + \sqrt{c^2 + (b - ac)/D}`$, which is below $`(2\pi/L_\min)^2`$ when the tension
/// is weak or the compressed side short, and does not exist when
/// $`N_Y \le D\pi^2/L_X^2\,(6L_Y^2/L_X^2 + 2)`$: then the sheet buckles in one global bulge,
/// not in wrinkles, and the $`Q`$ where the search stopped depends on the mesh (measured on
/// $`L_Y/L_X = 10`$: 0.154 N/mm on 12 × 12, 0.137 on 24 × 24).
fn long_wavelength_end_note(scene: &Scene, q: f64) -> String {
    let detail = match closed_form_threshold(scene) {
        Some((_, exact)) => format!(
            "eq. 42's minimiser on this rectangle is Q = {exact:.4e} 1/mm (wavelength {:.4e} mm)",
            2.0 * PI / exact
        ),
        None if scene.load.kind == LoadKind::Biaxial => {
            "eq. 42 has no minimum on this rectangle: the tension N_Y is at most Dπ²/L_X²·(6L_Y²/L_X² + 2), so λ(Q) falls all the way to Q = 0".to_string()
        }
        None => "the closed form does not apply to this load".to_string(),
    };
    format!(
        "λ_c(Q) still falls at the long-wavelength end of the search (Q = {q:.4e} 1/mm, wavelength {:.4e} mm, the shorter side is {} mm): no wrinkle wavelength is selected inside the domain — {detail}; the sheet buckles globally rather than wrinkling, and the reported Q and λ_c depend on where the search stopped (mesh-dependent)",
        2.0 * PI / q,
        scene.geometry.length_x.min(scene.geometry.length_y)
    )
}

/// A hint when the wave vector (`model.direction`) is far from the direction the load
/// compresses: along X for the biaxial load ($`\lambda = -N_X`$), along Y for the strip (the
/// transverse compression near its middle). An envelope model then sees no compression along
/// its carrier, and no wavenumber buckles.
fn direction_hint(scene: &Scene) -> String {
    let theta = scene.model.direction_degrees.to_radians();
    let (compressed, expected) = match scene.load.kind {
        LoadKind::Biaxial => ("along X (λ = −N_X)", 0.0),
        LoadKind::Strip => ("across the strip, along Y, near its middle", 90.0),
    };
    let along = if expected == 0.0 {
        theta.cos().abs()
    } else {
        theta.sin().abs()
    };
    if along < 0.5 {
        format!(
            " The {} load compresses the sheet {compressed}, but the wave vector is at model.direction = {}° from X: set model.direction = {expected}{}.",
            scene.load.kind.as_str(),
            scene.model.direction_degrees,
            if scene.load.kind == LoadKind::Strip {
                " (as examples/scenes/long_strip.toml does)"
            } else {
                ""
            }
        )
    } else {
        String::new()
    }
}

/// A hint for auxetic sheets, $`\nu \le -0.9`$ (empty otherwise): the in-plane problem is nearly
/// singular there and Newton stalls at round-off; measured on example 1 at 32 × 16, ν = −0.99
/// is solved and ν = −0.999 stalls at a relative residual of 1.2e-6 (tolerance 1e-8).
fn poisson_hint(scene: &Scene) -> String {
    let nu = scene.material.poisson_ratio;
    if nu <= -0.9 {
        format!(
            " With ν = {nu} the in-plane problem is nearly singular (area modulus E/(2(1−ν)) against shear modulus E/(2(1+ν)), ratio 1:{:.0}): Newton stalls at round-off more than 100 times above its tolerance; ν ≥ −0.99 is solved on example 1 at 32 × 16 (finer meshes are worse conditioned).",
            (1.0 - nu) / (1.0 + nu)
        )
    } else {
        String::new()
    }
}

/// The global search on a half mesh, then the local refinement on `problem` (module
/// documentation); on the problem itself when its mesh is already coarse.
fn two_level_search<M: EnergyModel>(
    scene: &Scene,
    problem: &mut Problem<M>,
    factor: &mut SparseFactorization,
    options: &WavenumberSearchOptions,
    observer: &mut dyn FnMut(&WavenumberEvaluation),
) -> Result<WavenumberSearch, Error> {
    let solve_error = |e: wrinkle_runtime::solve::SolveError| Error::Solver(e.to_string());
    let options = &closed_form_start(scene, options);
    let coarse = coarse_scene(scene);
    let mut direct_evaluations = Vec::new();
    if let (Some(_), Some(guess)) = (&coarse, options.local_guess) {
        // The closed form's minimiser is within 1.3e-4 of the FE one on example 1 from 6 × 4 to
        // 40 × 20 elements, closer than the half mesh's (1 %): the real mesh refines from it
        // directly, as it would from the half mesh's. No minimum bracketed near it, or one at
        // the edge of the ±10 % bracket, means this model's minimum is elsewhere (another
        // model than the one eq. (42) solves): then the two-level search, as before.
        let local = WavenumberSearchOptions {
            scan_after_local: false,
            ..fine_options(options, guess.parameter, None)
        };
        let (low, high) = local.range;
        let mut record = |evaluation: &WavenumberEvaluation| {
            direct_evaluations.push(evaluation.clone());
            observer(evaluation)
        };
        match minimise_critical_load(problem, factor, &local, &mut record) {
            Ok(found)
                if found.parameter > low * (1.0 + LOCAL_STEP)
                    && found.parameter < high / (1.0 + LOCAL_STEP) =>
            {
                return Ok(found);
            }
            // Kept in the count: the analyses of the attempt were done.
            _ => {}
        }
    }
    let mut search = match coarse {
        None => minimise_critical_load(problem, factor, options, observer).map_err(solve_error)?,
        Some(coarse) => {
            // Global scan (or a local search from the closed form) on the coarse mesh, then a
            // local refinement on the real one.
            let mut coarse_problem = build_problem(&coarse, problem.assembler.model().clone())?;
            let mut coarse_factor = analyse(&coarse_problem)?;
            let coarse_options = WavenumberSearchOptions {
                relative_tolerance: COARSE_RELATIVE_TOLERANCE,
                ..options.clone()
            };
            let first = minimise_critical_load(
                &mut coarse_problem,
                &mut coarse_factor,
                &coarse_options,
                observer,
            )
            .map_err(solve_error)?;
            let local = fine_options(
                options,
                first.parameter,
                first.buckling.critical_loads.first().copied(),
            );
            let mut fine =
                minimise_critical_load(problem, factor, &local, observer).map_err(solve_error)?;
            let mut evaluations = first.evaluations;
            evaluations.append(&mut fine.evaluations);
            fine.evaluations = evaluations;
            fine
        }
    };
    if !direct_evaluations.is_empty() {
        direct_evaluations.append(&mut search.evaluations);
        search.evaluations = direct_evaluations;
    }
    Ok(search)
}

/// The real mesh's local refinement about `q` (a minimiser found on the half mesh, or the
/// closed form's): parabolic steps from `q` ± [`LOCAL_STEP`] to [`FINE_RELATIVE_TOLERANCE`],
/// within ±10 % ([`LOCAL_BRACKET`]); `load_guess` (when given) replaces `options`' guess.
fn fine_options(
    options: &WavenumberSearchOptions,
    q: f64,
    load_guess: Option<f64>,
) -> WavenumberSearchOptions {
    WavenumberSearchOptions {
        range: (q / LOCAL_BRACKET, q * LOCAL_BRACKET),
        scan_points: 3,
        relative_tolerance: FINE_RELATIVE_TOLERANCE,
        load_guess: load_guess.or(options.load_guess),
        local_guess: Some(LocalGuess {
            parameter: q,
            relative_step: LOCAL_STEP,
        }),
        ..options.clone()
    }
}

/// Relative distance of the first neighbours of the closed-form minimiser in a search that
/// starts from it (`closed_form_start`). The FE minimiser of the reference envelope lies within
/// 1.3e-4 of it on example 1 from 6 × 4 to 40 × 20 elements (the mesh error shifts $`\lambda_c`$
/// nearly uniformly in $`Q`$); ±3 % brackets it with a wide margin for other models and scenes,
/// and the first parabola's vertex is then within the half mesh's 1 % tolerance.
const CLOSED_FORM_STEP: f64 = 3e-2;

/// `options` with the search started from the closed-form threshold (eq. (42) minimised) when
/// the scene has one inside the searched range: a local search about its $`Q`$, shifted about
/// its $`\lambda_c`$, instead of the global scan. The closed form solves the reference envelope
/// on a clamped rectangle under biaxial load, the scenes it applies to; the local search falls
/// back to the global scan when it cannot bracket a minimum near the guess (a model whose
/// $`\lambda_c(Q)`$ differs, or none at all), so the guess only decides where the search
/// starts, never what it finds. With a half mesh, the real mesh is first searched directly from
/// the closed form (`two_level_search`): 3 analyses on example 1 at 40 × 20, against 18 with the
/// global scan and 6 with the half mesh started from the closed form.
fn closed_form_start(scene: &Scene, options: &WavenumberSearchOptions) -> WavenumberSearchOptions {
    let (low, high) = options.range;
    match closed_form_threshold(scene) {
        Some((load, q)) if q > low && q < high && load.is_finite() && load > 0.0 => {
            WavenumberSearchOptions {
                load_guess: Some(load),
                local_guess: Some(LocalGuess {
                    parameter: q,
                    relative_step: CLOSED_FORM_STEP,
                }),
                ..options.clone()
            }
        }
        _ => options.clone(),
    }
}

/// Eigen-solver restarts of the first attempt about $`\lambda = 0`$ when a shifted second
/// attempt is possible.
const FIRST_ATTEMPT_RESTARTS: usize = 25;

/// Fraction of the guessed threshold used as the shift of the second attempt.
const SHIFT_FRACTION: f64 = 0.8;

impl ThresholdSteps<'_> {
    /// Linear buckling about $`\lambda = 0`$; if that fails (a small compressed zone whose
    /// negative end of the spectrum hides behind a large positive one, as in a strip in
    /// tension), again about $`\sigma = 0.8\,\lambda_g`$ with $`\lambda_g`$ the wavenumber
    /// model's threshold on the same scene: shift-invert about $`\sigma`$ makes the wanted load
    /// factors the dominant end of the spectrum. The second attempt exists only when there is a
    /// wavenumber model (the scene's model is not that model); the first then spends
    /// [`FIRST_ATTEMPT_RESTARTS`] restarts, not the whole budget. Returns the analysis and the
    /// load it linearised about.
    fn robust_buckling<M: EnergyModel>(
        &mut self,
        problem: &Problem<M>,
        factor: &mut SparseFactorization,
    ) -> Result<(LinearBuckling, f64), Error> {
        let scene = self.scene;
        let mut options = LinearBucklingOptions::default();
        if self.wavenumber_model.is_some() {
            // A second attempt exists: do not spend the whole restart budget on the first.
            options.eigen.max_restarts = FIRST_ATTEMPT_RESTARTS;
        }
        let first = match linear_buckling(problem, factor, &options) {
            Ok(buckling) => return Ok((buckling, 0.0)),
            Err(error) => error,
        };
        let guess = self
            .wavenumber_model
            .and_then(|model| Some((model.name(), model.threshold(self.quiet).ok()?)))
            .filter(|(_, carrier)| {
                carrier.critical_load.is_finite() && carrier.critical_load > 0.0
            });
        let Some((name, carrier)) = guess else {
            return Err(Error::Solver(format!(
                "linear buckling: {first}{}",
                poisson_hint(scene)
            )));
        };
        let guess = carrier.critical_load;
        let shift = SHIFT_FRACTION * guess;
        let shifted = LinearBucklingOptions {
            reference_load: shift,
            ..LinearBucklingOptions::default()
        };
        let buckling = linear_buckling(problem, factor, &shifted).map_err(|second| {
            Error::Solver(format!(
                "linear buckling: about λ = 0: {first}; about λ = {shift:.6e} (0.8 × the threshold of `{name}`, model.wavenumber_model): {second}{}",
                poisson_hint(scene)
            ))
        })?;
        self.notes.push(format!(
            "linear buckling about λ = 0 did not converge ({first}); solved about λ = {shift:.6e} (0.8 × the threshold {guess:.6e} of `{name}`, model.wavenumber_model)"
        ));
        Ok((buckling, shift))
    }
}

/// Symbolic analysis of the tangent's pattern.
pub fn analyse<M: EnergyModel>(problem: &Problem<M>) -> Result<SparseFactorization, Error> {
    SparseFactorization::analyze(problem.assembler.pattern())
        .map_err(|e| Error::Solver(format!("symbolic analysis of the tangent: {e}")))
}

/// The plate's wavelength, read from its first mode along the line through the mode's largest
/// deflection in the wave direction.
fn mode_wavelength<M: EnergyModel>(
    scene: &Scene,
    problem: &Problem<M>,
    layout: &Layout,
    buckling: &LinearBuckling,
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
        direction: scene.model.direction_degrees.to_radians(),
    };
    let length = 2.0 * scene.geometry.length_x.hypot(scene.geometry.length_y);
    wavelength_along_line(&snapshot, [peak[0], peak[1]], length)
}

/// Load factor, relative to $`\lambda_c`$, at which the fundamental branch is checked for
/// pointwise well-posedness.
pub const WELL_POSEDNESS_LOAD_RATIO: f64 = 1.05;

/// A model without gradient stiffness in a transverse field (the pure membrane) is ill-posed
/// beyond its threshold: the fundamental branch at $`1.05\lambda_c`$ is pointwise unstable over
/// most of the area at once, so there is no length scale and the post-buckling solution depends
/// on the mesh. Checked on the fundamental state extrapolated to $`1.05\lambda_c`$.
fn well_posedness_beyond<M: EnergyModel>(
    problem: &Problem<M>,
    buckling: &LinearBuckling,
    reference_load: f64,
) -> Option<ValidityWarning> {
    let load = WELL_POSEDNESS_LOAD_RATIO * buckling.critical_loads[0];
    let state = buckling.state_at(reference_load, load);
    let report = wrinkle_runtime::solve::ellipticity::legendre_hadamard(problem, &state, load);
    let worst = report
        .gradient_free
        .iter()
        .filter(|f| !f.stable)
        .max_by(|a, b| a.violated_fraction.total_cmp(&b.violated_fraction))?;
    (worst.violated_fraction > 0.5).then(|| ValidityWarning {
        check: "well_posedness",
        message: format!(
            "field `{}` has no gradient stiffness and is pointwise unstable over {:.0} % of the area just beyond the threshold (λ = {WELL_POSEDNESS_LOAD_RATIO} λ_c): the model is ill-posed there — no length scale, post-buckling results depend on the mesh",
            worst.field,
            100.0 * worst.violated_fraction
        ),
    })
}

/// A count below a limit, with two decimals rounded down, so that a count just below the limit
/// is never printed as the limit itself (7.994 was shown as "8.0 … (at least 8)").
fn below_limit_text(value: f64) -> String {
    format!("{:.2}", (100.0 * value).floor() / 100.0)
}

/// The validity checks of the module documentation.
fn validity_warnings(
    scene: &Scene,
    layout: &Layout,
    threshold: &Threshold,
) -> Vec<ValidityWarning> {
    let mut warnings = Vec::new();
    let h = scene.material.thickness;
    let shortest = scene.geometry.length_x.min(scene.geometry.length_y);
    if let (Some(l), true) = (threshold.wavelength, layout.is_envelope()) {
        if l > shortest / MIN_WAVES_PER_DOMAIN {
            warnings.push(ValidityWarning {
                check: "scale_separation",
                message: format!(
                    "wavelength {l:.4e} mm is not small against the domain (shorter side {shortest} mm, at most 1/{MIN_WAVES_PER_DOMAIN} of it): the envelope model's slowly-varying assumption does not hold"
                ),
            });
        }
        if l < MIN_WAVELENGTH_OVER_THICKNESS * h {
            warnings.push(ValidityWarning {
                check: "scale_separation",
                message: format!(
                    "wavelength {l:.4e} mm is below {MIN_WAVELENGTH_OVER_THICKNESS} thicknesses (h = {h} mm): outside thin-plate theory"
                ),
            });
        }
    }
    let e = &threshold.ellipticity;
    if e.violated_fraction > MAX_NON_ELLIPTIC_FRACTION {
        warnings.push(ValidityWarning {
            check: "ellipticity",
            message: format!(
                "not strongly elliptic at the threshold over {:.1} % of the area (worst at ({:.4}, {:.4}) mm, field `{}`): the critical load is a mesh-scale mode, not a threshold of the model",
                100.0 * e.violated_fraction, e.location[0], e.location[1], e.field
            ),
        });
    }
    if let (Some(l), false) = (threshold.wavelength, layout.is_envelope()) {
        // Element size along the wave direction (X, or Y for waves along Y as in the strip).
        let theta = scene.model.direction_degrees.to_radians();
        let (element, axis) = if theta.sin().abs() > theta.cos().abs() {
            (scene.geometry.length_y / scene.mesh.elements_y as f64, "Y")
        } else {
            (scene.geometry.length_x / scene.mesh.elements_x as f64, "X")
        };
        let per_wavelength = l / element;
        if per_wavelength < MIN_ELEMENTS_PER_WAVELENGTH {
            warnings.push(ValidityWarning {
                check: "mode_resolution",
                message: format!(
                    "{} elements per wavelength ({l:.4e} mm) along {axis}: the plate's mode is not resolved (at least {MIN_ELEMENTS_PER_WAVELENGTH}; refine mesh.n{})",
                    below_limit_text(per_wavelength),
                    axis.to_lowercase()
                ),
            });
        }
    }
    warnings
}

/// Summary of a threshold as JSON (keys documented in `docs/outputs.md`).
pub fn threshold_json(scene: &Scene, threshold: &Threshold) -> serde_json::Value {
    let critical = threshold.critical_load();
    let closed_form = closed_form_threshold(scene);
    json!({
        "model": threshold.model,
        "critical_load": critical,
        "load_kind": scene.load.kind.as_str(),
        "load_unit": load_unit(scene),
        "n_x": (scene.load.kind == LoadKind::Biaxial).then_some(-critical),
        "wavenumber": threshold.wavenumber,
        "wavelength": threshold.wavelength,
        "wavenumber_mode": threshold.wavenumber_source,
        "dofs": threshold.dofs,
        "elements": scene.mesh.elements_x * scene.mesh.elements_y,
        "buckling_evaluations": threshold.evaluations,
        "eigen_residual": threshold.buckling.residuals[0],
        "eigen_iterations": threshold.buckling.eigen_iterations,
        "closed_form_critical_load": closed_form.map(|(l, _)| l),
        "closed_form_wavenumber": closed_form.map(|(_, q)| q),
        "closed_form_relative_difference": closed_form.map(|(l, _)| (critical - l) / l),
        "elliptic_at_threshold": threshold.ellipticity.elliptic,
        "ellipticity_margin": threshold.ellipticity.worst_margin,
        "ellipticity_worst_location": threshold.ellipticity.location,
        "ellipticity_worst_field": threshold.ellipticity.field,
        "ellipticity_violated_area_fraction": threshold.ellipticity.violated_fraction,
        "notes": threshold.notes,
        "warnings": threshold.warnings,
        "seconds": threshold.seconds,
    })
}

/// Unit of the load $`\lambda`$: N/mm (biaxial) or mm (strip).
pub fn load_unit(scene: &Scene) -> &'static str {
    match scene.load.kind {
        LoadKind::Biaxial => "N/mm",
        LoadKind::Strip => "mm",
    }
}

/// The closed-form threshold (THEORY.md §8, eq. 42 minimised) and its wavenumber when the scene
/// is a clamped rectangle under biaxial load with waves along X.
pub fn closed_form_threshold(scene: &Scene) -> Option<(f64, f64)> {
    (scene.load.kind == LoadKind::Biaxial && scene.model.direction_degrees == 0.0)
        .then(|| scene.clamped_rectangle().critical_point())
        .flatten()
}

/// The critical load of eq. (42) at the wavenumber `q` (the neutral curve), where the closed
/// form applies to the scene ([`closed_form_threshold`]): a guess the analysis at a fixed $`Q`$
/// is shifted about (0.98 times it, kept only when the tangent there has no negative pivot, so
/// a guess above the model's own threshold costs one factorisation and changes nothing). On
/// example 1 at 40 × 20 it takes the analysis from 55 Lanczos operator applications to 16.
fn closed_form_load_at(scene: &Scene, q: f64) -> Option<f64> {
    closed_form_threshold(scene)?;
    Some(scene.clamped_rectangle().neutral_curve(q)).filter(|l| l.is_finite() && *l > 0.0)
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_count_just_below_the_resolution_limit_is_not_printed_as_the_limit() {
        // 120 × 30 elements on example 1's 400 mm: 26.649 mm / 3.333 mm = 7.9947 elements.
        assert_eq!(below_limit_text(26.649_139 / (400.0 / 120.0)), "7.99");
        assert_eq!(below_limit_text(6.4), "6.40");
        assert_eq!(below_limit_text(2.0), "2.00");
        assert_eq!(below_limit_text(7.999_999), "7.99");
    }
}
