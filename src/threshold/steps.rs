//! The steps of one threshold ([`ThresholdSteps`]): which analysis the model's capability and
//! the scene call for (a fixed wavenumber, a search, the wavenumber model's $`Q`$, a reused
//! one, a plate's mode), the buckling analysis at a wavenumber with its shifted second attempt,
//! and the notes and hints they leave for the user.

use super::reuse::PriorThreshold;
use super::scene_quantities::{closed_form_load_at, closed_form_threshold, wavenumber_range};
use super::search::{SCAN_POINTS, two_level_search};
use super::wavenumber_model::{CarrierThreshold, WavenumberModel};
use crate::error::Error;
use crate::output::{ProgressSink, SearchProgress};
use crate::scene::{LoadKind, Scene, Wavenumber};
use std::f64::consts::PI;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::eigen::BucklingOptions;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::buckling::{LinearBuckling, LinearBucklingOptions, linear_buckling};
use wrinkle_runtime::solve::ellipticity::EllipticityReport;
use wrinkle_runtime::solve::wavenumber::{
    LOCAL_SHIFT, WavenumberEvaluation, WavenumberSearch, WavenumberSearchOptions,
    ellipticity_at_critical_load, set_model_parameter,
};
use wrinkle_runtime::wavelength::{CarriedBecause, WAVENUMBER_PARAMETER, WavelengthSelection};

/// The linear buckling a threshold settles on, before its validity checks.
pub(super) struct CriticalPoint {
    /// Critical loads, modes, pre-buckling state and rate.
    pub(super) buckling: LinearBuckling,
    /// Strong ellipticity at the critical load.
    pub(super) ellipticity: EllipticityReport,
    /// Load the analysis linearised about.
    pub(super) reference_load: f64,
    /// Wavenumber $`Q`$ of an envelope model.
    pub(super) wavenumber: Option<f64>,
    /// Where $`Q`$ came from ([`super::Threshold::wavenumber_source`]).
    pub(super) source: String,
    /// The wavenumber search, when there was one.
    pub(super) search: Vec<WavenumberEvaluation>,
}

/// The steps of one threshold: its scene, whether progress is shown, the wavenumber model
/// (`None` when the scene's model is that model) and the notes collected for the user.
pub(super) struct ThresholdSteps<'a> {
    pub(super) scene: &'a Scene,
    pub(super) quiet: bool,
    pub(super) wavenumber_model: Option<&'a WavenumberModel>,
    pub(super) notes: Vec<String>,
}

impl ThresholdSteps<'_> {
    /// The critical point by the model's capability and the scene's `model.wavenumber`.
    pub(super) fn critical_point<M: EnergyModel>(
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
        // No search to show: a spinner (or a start line) says what runs from the first second.
        let progress = SearchProgress::new(
            &format!("{}: linear buckling", M::SPEC.name),
            ProgressSink::standard_error(self.quiet),
        );
        progress.evaluation(
            1,
            &format!("{} unknowns, the mode and λ_c", problem.free_count()),
        );
        let (buckling, reference_load) = self.buckling_about_guess(problem, factor, &progress)?;
        progress.evaluation(2, "strong ellipticity at λ_c");
        let ellipticity = ellipticity_at_critical_load(problem, &buckling, reference_load);
        progress.finish(&format!("λ_c = {:.6e}", buckling.critical_loads[0]));
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
            let options = threshold_buckling(shift);
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

/// A hint when the wave vector (`model.direction`) is more than 10° from
/// the direction the load compresses: along X for the biaxial load ($`\lambda = -N_X`$), along
/// Y for the strip (the transverse compression near its middle). An envelope model then sees
/// little or no compression along its carrier — on example 1 the tension $`N_Y`$ outweighs
/// $`\lambda\cos^2\theta`$ already at $`\theta = 57°`$ — and no wavenumber buckles.
fn direction_hint(scene: &Scene) -> String {
    /// Angle between the wave vector and the compression beyond which a failed search names
    /// `model.direction`.
    const DIRECTION_HINT_DEGREES: f64 = 10.0;
    // "auto" chooses the direction itself.
    let Some(degrees) = scene.model.direction.fixed_degrees() else {
        return String::new();
    };
    let theta = degrees.to_radians();
    let (compressed, expected) = match scene.load.kind {
        LoadKind::Biaxial => ("along X (λ = −N_X)", 0.0),
        LoadKind::Strip => ("across the strip, along Y, near its middle", 90.0),
        LoadKind::Boundaries => return String::new(),
    };
    let along = if expected == 0.0 {
        theta.cos().abs()
    } else {
        theta.sin().abs()
    };
    if along < DIRECTION_HINT_DEGREES.to_radians().cos() {
        format!(
            " The {} load compresses the sheet {compressed}, but the wave vector is at model.direction = {}° from X: set model.direction = {expected}{}.",
            scene.load.kind.as_str(),
            degrees,
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

/// Eigen-solver restarts of the first attempt about $`\lambda = 0`$ when a shifted second
/// attempt is possible.
const FIRST_ATTEMPT_RESTARTS: usize = 25;

/// Relative eigen-residual at which the threshold's buckling analyses stop
/// ([`BucklingOptions::tolerance`]; the runtime's default, $`10^{-12}`$, lies below the
/// rounding floor of large plate meshes, $`10^{-10}`$–$`10^{-9}`$, which they then reach only
/// by stagnating). The load factor's error is of the order of its square and the mode's of it
/// over the spectral gap: example 1's plate at 128 × 32 gives the same $`\lambda_c`$ to
/// $`10^{-16}`$ in 28 operator applications instead of 40, the long strip's at 112 × 64 in 16
/// instead of 28. (The wavenumber searches' analyses stop at $`10^{-8}`$ already.)
pub(super) const THRESHOLD_EIGEN_TOLERANCE: f64 = 1e-9;

/// The settings of a threshold's linear buckling about `reference_load`: the runtime's, with
/// the eigen-tolerance [`THRESHOLD_EIGEN_TOLERANCE`].
pub(super) fn threshold_buckling(reference_load: f64) -> LinearBucklingOptions {
    LinearBucklingOptions {
        reference_load,
        eigen: BucklingOptions {
            tolerance: THRESHOLD_EIGEN_TOLERANCE,
            ..BucklingOptions::default()
        },
        ..LinearBucklingOptions::default()
    }
}

/// Fraction of the guessed threshold used as the shift of the second attempt.
const SHIFT_FRACTION: f64 = 0.8;

impl ThresholdSteps<'_> {
    /// Linear buckling about $`\lambda = 0`$; if that fails (a small compressed zone whose
    /// negative end of the spectrum hides behind a large positive one, as in a strip in
    /// tension), again about $`\sigma = 0.8\,\lambda_g`$ with $`\lambda_g`$ the wavenumber
    /// model's threshold on the same scene, estimated
    /// ([`WavenumberModel::critical_load_estimate`]): shift-invert about $`\sigma`$ makes the
    /// wanted load factors the dominant end of the spectrum. The second attempt exists only when there is a
    /// wavenumber model (the scene's model is not that model); the first then spends
    /// [`FIRST_ATTEMPT_RESTARTS`] restarts, not the whole budget. Returns the analysis and the
    /// load it linearised about.
    fn robust_buckling<M: EnergyModel>(
        &mut self,
        problem: &Problem<M>,
        factor: &mut SparseFactorization,
    ) -> Result<(LinearBuckling, f64), Error> {
        let scene = self.scene;
        let mut options = threshold_buckling(0.0);
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
            .and_then(|model| Some((model.name(), model.critical_load_estimate(self.quiet).ok()?)))
            .filter(|(_, load)| load.is_finite() && *load > 0.0);
        let Some((name, guess)) = guess else {
            return Err(Error::Solver(format!(
                "linear buckling: {first}{}",
                poisson_hint(scene)
            )));
        };
        let shift = SHIFT_FRACTION * guess;
        let shifted = threshold_buckling(shift);
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

/// Fractions of a guessed threshold tried, closest first, as the shift of the buckling analysis
/// of a model that resolves its wrinkles on the mesh ([`ThresholdSteps::buckling_about_guess`]).
/// The plate's threshold lies above eq. (42) on example 1 (0.34 % at 128 × 32) and 3.7 % below
/// the reference envelope's on the long strip at 70 × 64: 0.95 is below both.
const GUESS_SHIFT_FRACTIONS: [f64; 2] = [0.95, SHIFT_FRACTION];

/// Smallest fraction of the guess tried as a shift: after [`GUESS_SHIFT_FRACTIONS`], a shift
/// found above the threshold (negative pivots at it) is halved down to this before the analysis
/// about $`\lambda = 0`$. On coarse uniform meshes of the long strip the plate's threshold lies
/// 25–30 % below the reference envelope's (58 × 16: both shifts had negative pivots, and the
/// analysis about 0 did not converge).
const MIN_GUESS_SHIFT_FRACTION: f64 = 0.05;

/// Operator applications over which a wanted eigen-residual that does not halve is taken as its
/// rounding floor in a shifted analysis of [`ThresholdSteps::buckling_about_guess`]
/// ([`BucklingOptions::stagnation_applications`]): close to the threshold the residual falls by
/// well over half in that many applications until it reaches the floor.
const FLOOR_APPLICATIONS: usize = 10;

impl ThresholdSteps<'_> {
    /// A guess of the critical load of a model that resolves its wrinkles on the mesh, and where
    /// it comes from: the minimum of eq. (42) where the closed form applies (free), otherwise
    /// the wavenumber model's threshold on the same scene, estimated once per run
    /// ([`WavenumberModel::critical_load_estimate`]); `None` when there is neither.
    fn threshold_guess(&self) -> Option<(f64, String)> {
        if let Some((load, _)) = closed_form_threshold(self.scene) {
            return Some((load, "the minimum of eq. (42)".into()));
        }
        let model = self.wavenumber_model?;
        let load = model.critical_load_estimate(self.quiet).ok()?;
        (load.is_finite() && load > 0.0)
            .then(|| (load, format!("the threshold of `{}`", model.name())))
    }

    /// Linear buckling shifted about a guess $`\lambda_g`$ of the threshold
    /// ([`Self::threshold_guess`]), at $`\sigma = f\lambda_g`$ for each $`f`$ of
    /// [`GUESS_SHIFT_FRACTIONS`] in turn, then halved while the shift is above the threshold
    /// (down to [`MIN_GUESS_SHIFT_FRACTION`]); about $`\lambda = 0`$ when there is no guess or
    /// no shift is below the threshold.
    ///
    /// Shift-invert about $`\sigma`$ maps the load factors to $`\nu = -1/(\lambda - \sigma)`$:
    /// the compressive end of the spectrum, just above $`\sigma`$, is then its dominant end, and
    /// Lanczos finds it first time. About $`\lambda = 0`$ it need not be: on the long strip, in
    /// tension except for a small compressed zone, the load stiffness is far from definite and
    /// its large positive end (tension stiffening) hides the wanted load factors — 25 restarts
    /// found no negative Ritz value at all. A shift above the threshold is seen before any
    /// eigen-solve: the tangent at $`\sigma`$ then has negative pivots (Sylvester's law), which
    /// costs one pre-buckling state and one factorisation, and the next fraction is tried.
    /// Returns the analysis and the load it linearised about.
    fn buckling_about_guess<M: EnergyModel>(
        &mut self,
        problem: &Problem<M>,
        factor: &mut SparseFactorization,
        progress: &SearchProgress,
    ) -> Result<(LinearBuckling, f64), Error> {
        let mut attempts = Vec::new();
        if let Some((guess, source)) = self.threshold_guess() {
            let mut fractions = GUESS_SHIFT_FRACTIONS.to_vec();
            let mut tried = 0;
            while let Some(&fraction) = fractions.get(tried) {
                tried += 1;
                let shift = fraction * guess;
                progress.evaluation(
                    1,
                    &format!(
                        "{} unknowns, shift-invert about λ = {shift:.6e} ({fraction} × {source})",
                        problem.free_count()
                    ),
                );
                let mut options = threshold_buckling(shift);
                options.eigen.stagnation_applications = Some(FLOOR_APPLICATIONS);
                match linear_buckling(problem, factor, &options) {
                    Ok(buckling) => return Ok((buckling, shift)),
                    Err(error) => attempts.push(format!("about λ = {shift:.6e}: {error}")),
                }
                // The last shift was above the threshold (its tangent had negative pivots, and
                // the factorisation is still that tangent's): half of it is tried next.
                let above = factor.negative_pivots().is_some_and(|count| count > 0);
                let halved = 0.5 * fraction;
                if tried == fractions.len() && above && halved >= MIN_GUESS_SHIFT_FRACTION {
                    fractions.push(halved);
                }
            }
        }
        progress.evaluation(
            1,
            &format!("{} unknowns, about λ = 0", problem.free_count()),
        );
        match linear_buckling(problem, factor, &threshold_buckling(0.0)) {
            Ok(buckling) => Ok((buckling, 0.0)),
            Err(error) => {
                attempts.push(format!("about λ = 0: {error}"));
                Err(Error::Solver(format!(
                    "linear buckling: {}{}",
                    attempts.join("; "),
                    poisson_hint(self.scene)
                )))
            }
        }
    }
}
