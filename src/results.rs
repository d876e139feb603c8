//! What a run produced, typed: the solver side ([`crate::run`]) records the path into a
//! [`Trace`] and gathers what it knows in a [`RunContext`]; [`RunSummary::new`] decides the
//! run's result from them — its [`RunOutcome`] and exit code, the threshold with its closed
//! form, the path, the statistics, the notices — before anything is written; the writers
//! ([`crate::run_outputs`]) only serialise them. `compare` and `bench` read the summary's
//! fields ([`RunReport::summary`]).

mod build;
mod summary;

pub use summary::{
    AnmStepRecord, DetectedBifurcation, FINAL_FIELDS_FILE, FINAL_SURFACE_FILE, LossOfEllipticity,
    MAX_FIELDS_FILE_DECIMALS, Memory, PathCounts, RunSummary, Timings, VtuFile, fields_file_at,
};

use crate::error::Error;
use crate::output::{PathPoint, Quantity};
use crate::physics::{Layout, Snapshot};
use crate::scene::{Imperfection, LoadKind, Scene};
use crate::threshold::Threshold;
use std::path::PathBuf;
use wrinkle_runtime::ModelSpec;
use wrinkle_runtime::fem::Mesh;
use wrinkle_runtime::solve::anm::AnmStep;
use wrinkle_runtime::solve::ellipticity::EllipticityReport;
use wrinkle_runtime::solve::path::PathResult;

/// How a run ended, with its exit code (table in `docs/outputs.md`).
#[derive(Clone, Debug, PartialEq)]
pub enum RunOutcome {
    /// The amplitude target was reached (exit 0).
    Reached,
    /// A solver failed; every point computed before was written (exit 1).
    Failed(String),
    /// The path stopped before the target: `max_steps`, `max_load`, or never wrinkled (exit 3).
    Incomplete(String),
    /// The target was reached but a validity check the scene does not accept failed (exit 4).
    Invalid(String),
    /// Interrupted by the user (Ctrl-C) on the path; the completed points were written (exit 130).
    Interrupted(String),
}

impl RunOutcome {
    /// Process exit code of this outcome.
    pub fn exit_code(&self) -> i32 {
        match self {
            RunOutcome::Reached => 0,
            RunOutcome::Failed(_) => 1,
            RunOutcome::Incomplete(_) => 3,
            RunOutcome::Invalid(_) => 4,
            RunOutcome::Interrupted(_) => crate::error::EXIT_INTERRUPTED,
        }
    }

    /// The `outcome` key of `summary.json`.
    pub fn name(&self) -> &'static str {
        match self {
            RunOutcome::Reached => "reached",
            RunOutcome::Failed(_) => "failed",
            RunOutcome::Incomplete(_) => "incomplete",
            RunOutcome::Invalid(_) => "invalid",
            RunOutcome::Interrupted(_) => "interrupted",
        }
    }

    /// The solver failure, if the path ended by one.
    pub fn failure(&self) -> Option<&str> {
        match self {
            RunOutcome::Failed(why) => Some(why),
            _ => None,
        }
    }

    /// The error a run with this outcome ends the process with (its exit code,
    /// [`Error::exit_code`]), its reason followed by `detail`; `None` when the run reached what
    /// was asked.
    pub fn error(&self, detail: &str) -> Option<Error> {
        match self {
            RunOutcome::Reached => None,
            RunOutcome::Failed(why) => Some(Error::Solver(format!("{why} {detail}"))),
            RunOutcome::Incomplete(why) => Some(Error::Incomplete(format!("{why} {detail}"))),
            RunOutcome::Invalid(why) => Some(Error::Invalid(format!("{why} {detail}"))),
            RunOutcome::Interrupted(why) => Some(Error::Interrupted(format!("{why} {detail}"))),
        }
    }

    /// Why the run did not reach what was asked (`None` when it did).
    pub fn reason(&self) -> Option<&str> {
        match self {
            RunOutcome::Reached => None,
            RunOutcome::Failed(why)
            | RunOutcome::Incomplete(why)
            | RunOutcome::Invalid(why)
            | RunOutcome::Interrupted(why) => Some(why),
        }
    }
}

/// What `run` produced: its result and the files that hold it.
#[derive(Debug)]
pub struct RunReport {
    /// The result (`summary.json` without its list of files), with how the run ended.
    pub summary: RunSummary,
    /// Files written.
    pub files: Vec<PathBuf>,
    /// The summary table and the notices as text (what `wrinkle run` prints at the end).
    pub summary_text: String,
}

/// The imperfection a run added to its fixed loads.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AppliedImperfection {
    /// Physical amplitude (mm) of its response on the unloaded sheet.
    pub amplitude: f64,
    /// Its shape: [`Imperfection::Uniform`] or [`Imperfection::Mode`].
    pub shape: Imperfection,
}

/// What the run knows besides its trace: the scene, the model and its problem, the threshold,
/// the costs measured before the outputs.
pub struct RunContext<'a> {
    /// The scene.
    pub scene: &'a Scene,
    /// The model's specification.
    pub spec: &'static ModelSpec,
    /// The fields' meaning.
    pub layout: &'a Layout,
    /// The mesh.
    pub mesh: &'a Mesh,
    /// The threshold found on the same problem.
    pub threshold: &'a Threshold,
    /// Physical amplitude (mm) of the imperfection's response on the unloaded sheet.
    pub imperfection: f64,
    /// The imperfection's shape as used: [`Imperfection::Uniform`] or [`Imperfection::Mode`]
    /// (`solver.imperfection` resolved for the model).
    pub imperfection_shape: Imperfection,
    /// Free unknowns.
    pub dofs: usize,
    /// Seconds before the outputs.
    pub seconds: f64,
    /// Peak resident memory of the process during the run, in bytes (Linux; see
    /// [`crate::memory`]).
    pub peak_memory: Option<u64>,
}

impl RunContext<'_> {
    /// The physical deflection of nodal `values` (the threshold's wavenumber, the scene's
    /// direction).
    pub fn snapshot<'b>(&'b self, values: &'b [f64]) -> Snapshot<'b> {
        Snapshot {
            mesh: self.mesh,
            layout: self.layout,
            values,
            wavenumber: self.threshold.wavenumber.unwrap_or(0.0),
            direction: self.threshold.direction_degrees.to_radians(),
        }
    }

    /// The load $`\lambda`$ of the scene, with its labels and unit.
    pub fn load_quantity(&self) -> Quantity {
        load_quantity(self.scene)
    }
}

/// The load $`\lambda`$ of `scene` with its labels and unit: the biaxial load (N/mm) or the
/// strip's end displacement (mm).
pub fn load_quantity(scene: &Scene) -> Quantity {
    match scene.load.kind {
        LoadKind::Biaxial => Quantity::biaxial_load(),
        LoadKind::Strip => Quantity::end_displacement(),
        LoadKind::Boundaries if crate::setup::load_is_displacement(scene) => {
            Quantity::new("load parameter", "λ", "mm")
        }
        LoadKind::Boundaries => Quantity::new("load parameter", "λ", "N/mm"),
    }
}

/// Displacement snapshots along the path for the profile plots and VTU requests.
#[derive(Default)]
pub struct Snap {
    /// Load.
    pub load: f64,
    /// Nodal values of the whole mesh.
    pub values: Vec<f64>,
    /// Element means of the stress resultants $`N_X, N_Y, N_{XY}`$ (N/mm), for the states
    /// written as VTU (empty otherwise).
    pub stress_resultants: Vec<Vec<f64>>,
}

/// Everything the outputs need from the path.
pub struct Trace {
    /// Path points (dense output included).
    pub points: Vec<PathPoint>,
    /// The solver's result.
    pub result: PathResult,
    /// ANM steps (empty for Riks).
    pub anm_steps: Vec<AnmStep>,
    /// First step end where strong ellipticity failed, with the report.
    pub loss_of_ellipticity: Option<(f64, EllipticityReport)>,
    /// States at increasing amplitude levels (profile plots).
    pub profiles: Vec<Snap>,
    /// States interpolated at the requested `output.vtu_loads`.
    pub requested: Vec<Snap>,
    /// States at the step ends (`output.vtu` only): the `.pvd` time series of the path.
    pub step_ends: Vec<Snap>,
    /// Last state (nodal values of the whole mesh).
    pub last: Snap,
    /// The user interrupted the path (Ctrl-C) after the last point.
    pub interrupted: bool,
    /// Load of the first point past $`\lambda_c`$ of a path without imperfection
    /// (`solver.perturbation = 0`) and without `solver.max_load`, where the run stopped: the
    /// path stays on the fundamental branch, unstable beyond the bifurcation, and never reaches
    /// an amplitude target.
    pub passed_perfect_bifurcation: Option<f64>,
    /// Loads of `output.vtu_loads` the path did not reach (no `fields_load_*.vtu` for them).
    pub unreached_vtu_loads: Vec<f64>,
    /// Seconds in the Legendre–Hadamard checks of the step ends (part of
    /// `recording_seconds`).
    pub ellipticity_seconds: f64,
    /// Seconds in the path's observer: recording every accepted point (amplitudes, profiles,
    /// requested VTU states, progress) and the ellipticity checks. Part of the path's time.
    pub recording_seconds: f64,
}
