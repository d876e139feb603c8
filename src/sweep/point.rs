//! One point of a sweep, run and recorded: [`run_point`] builds its scene, runs it (`run` or
//! `buckle`) into its own directory `points/COMMAND-HASH/` (named by the content hash of the
//! effective scene, [`super::content_hash`]) and writes its [`PointResult`] there as
//! `point.json`, last — the mark that the point is done. A later sweep over the same directory
//! reads it back instead of running the point again ([`read_done`]).

use super::recipe::{SceneRecipe, content_hash};
use crate::compare::AMPLITUDE_LEVELS;
use crate::error::Error;
use crate::scene::Scene;
use crate::study::load_at_amplitude;
use crate::threshold::{Threshold, ThresholdSummary};
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Name of a point's result file in its directory.
pub const POINT_FILE: &str = "point.json";
/// The folder of a sweep directory that holds one directory per point.
pub const POINTS_DIRECTORY: &str = "points";
/// Largest `point.json` read back (a result is a few kilobytes).
const MAX_POINT_BYTES: u64 = 1 << 20;

/// What a sweep does at each point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepCommand {
    /// `wrinkle run`: threshold and path, with every output of a run.
    #[default]
    Run,
    /// `wrinkle buckle --out`: the threshold only, with the mode and `buckle.json`.
    Buckle,
}

impl SweepCommand {
    /// `run` or `buckle`.
    pub fn name(self) -> &'static str {
        match self {
            SweepCommand::Run => "run",
            SweepCommand::Buckle => "buckle",
        }
    }

    /// Parses `run` or `buckle`.
    pub fn parse(text: &str) -> Result<Self, Error> {
        match text {
            "run" => Ok(SweepCommand::Run),
            "buckle" => Ok(SweepCommand::Buckle),
            other => Err(Error::Usage(format!(
                "sweep command `{other}`: expected `run` or `buckle`"
            ))),
        }
    }
}

/// The result of one point, as `point.json` holds it and the sweep's table shows it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PointResult {
    /// The content hash of the effective scene; empty when the scene could not be made.
    pub hash: String,
    /// The point's directory relative to the sweep's, `points/COMMAND-HASH`; empty when the
    /// scene could not be made.
    pub directory: String,
    /// How the run ended (`reached`, `failed`, `incomplete`, `invalid`, `interrupted`, as
    /// `summary.json`'s `outcome`), or `error` (the scene or the threshold failed: nothing
    /// ran), or `lost` (the process running it ended without a result).
    pub outcome: String,
    /// The exit code `wrinkle run` (or `wrinkle buckle`) would end with; `None` for `lost`.
    pub exit_code: Option<i32>,
    /// Why it did not reach its target, if it did not.
    pub reason: Option<String>,
    /// Registry name of the model.
    pub model: Option<String>,
    /// Free unknowns.
    pub dofs: Option<usize>,
    /// $`\lambda_c`$ of linear buckling.
    pub critical_load: Option<f64>,
    /// Unit of $`\lambda`$.
    pub load_unit: Option<String>,
    /// $`\lambda_c`$ of eq. (42) minimised, where it applies.
    pub closed_form_critical_load: Option<f64>,
    /// $`(\lambda_c - \lambda_c^{(42)})/\lambda_c^{(42)}`$.
    pub closed_form_relative_difference: Option<f64>,
    /// The minimiser $`Q`$ (1/mm) of eq. (42), where it applies.
    pub closed_form_wavenumber: Option<f64>,
    /// Wavenumber $`Q`$ (1/mm) of an envelope model.
    pub wavenumber: Option<f64>,
    /// Wavelength (mm).
    pub wavelength: Option<f64>,
    /// The load where the maximum physical amplitude $`a/h`$ first reaches each of
    /// [`AMPLITUDE_LEVELS`] (runs only; `None` where the path does not reach it).
    pub load_at_amplitude: Vec<Option<f64>>,
    /// Accepted path steps (runs only).
    pub steps: Option<usize>,
    /// The validity checks that failed, accepted by the scene or not.
    pub failed_checks: Vec<String>,
    /// Wall-clock seconds of the point, outputs included.
    pub seconds: f64,
    /// Peak resident memory of the point (bytes; Linux): the process's high-water mark, reset
    /// when the point starts ([`crate::memory`]).
    pub peak_memory_bytes: Option<u64>,
    /// `true` when this sweep read the result of an earlier one instead of running the point.
    pub reused: bool,
}

impl PointResult {
    /// The result of a point whose scene or threshold failed: `error`, with the exit code of
    /// the error.
    pub fn error(hash: &str, directory: &str, error: &Error, seconds: f64) -> Self {
        PointResult {
            outcome: "error".into(),
            exit_code: Some(error.exit_code()),
            reason: Some(error.to_string()),
            ..PointResult::empty(hash, directory, seconds)
        }
    }

    /// The result of a point whose process ended without writing one.
    pub fn lost(hash: &str, directory: &str, why: String, seconds: f64) -> Self {
        PointResult {
            outcome: "lost".into(),
            reason: Some(why),
            ..PointResult::empty(hash, directory, seconds)
        }
    }

    fn empty(hash: &str, directory: &str, seconds: f64) -> Self {
        PointResult {
            hash: hash.into(),
            directory: directory.into(),
            outcome: String::new(),
            exit_code: None,
            reason: None,
            model: None,
            dofs: None,
            critical_load: None,
            load_unit: None,
            closed_form_critical_load: None,
            closed_form_relative_difference: None,
            closed_form_wavenumber: None,
            wavenumber: None,
            wavelength: None,
            load_at_amplitude: vec![None; AMPLITUDE_LEVELS.len()],
            steps: None,
            failed_checks: Vec::new(),
            seconds,
            peak_memory_bytes: None,
            reused: false,
        }
    }

    /// Whether the point has a result a later sweep may reuse: anything but an interrupted
    /// run or a lost process (which ran to no end of their own).
    pub fn is_final(&self) -> bool {
        !matches!(self.outcome.as_str(), "interrupted" | "lost")
    }
}

/// The name of a point's directory: `COMMAND-HASH`.
pub fn point_name(command: SweepCommand, hash: &str) -> String {
    format!("{}-{hash}", command.name())
}

/// The directory of the point `name` in the sweep directory `sweep`.
pub fn point_directory(sweep: &Path, name: &str) -> PathBuf {
    sweep.join(POINTS_DIRECTORY).join(name)
}

/// The final result (see [`PointResult::is_final`]) an earlier sweep left in `directory`
/// for the scene of content hash `hash`, marked as reused; `None` when there is none.
pub fn read_done(directory: &Path, hash: &str) -> Option<PointResult> {
    let mut result = read_point_file(directory)?;
    (result.hash == hash && result.is_final()).then(|| {
        result.reused = true;
        result
    })
}

/// The `point.json` of `directory`, whatever its outcome; `None` when absent or unreadable.
pub fn read_point_file(directory: &Path) -> Option<PointResult> {
    let bytes = crate::input::read_capped(&directory.join(POINT_FILE), MAX_POINT_BYTES).ok()?;
    serde_json::from_slice(&bytes).ok()
}

/// Runs the point of `recipe` with `command` in the sweep directory `sweep` (quietly), or
/// reads back its final result when an earlier sweep left one. Never fails: a scene that
/// cannot be made, a threshold that fails or an output that cannot be written is a result with
/// outcome `error` and the error's reason and exit code.
pub fn run_point(recipe: &SceneRecipe, command: SweepCommand, sweep: &Path) -> PointResult {
    let start = Instant::now();
    let scene = match recipe.build() {
        Ok(scene) => scene,
        Err(error) => return PointResult::error("", "", &error, start.elapsed().as_secs_f64()),
    };
    let hash = content_hash(&scene);
    let name = point_name(command, &hash);
    let directory = point_directory(sweep, &name);
    if let Some(done) = read_done(&directory, &hash) {
        return done;
    }
    let relative = format!("{POINTS_DIRECTORY}/{name}");
    let peak_tracked = crate::memory::reset_peak();
    let computed = match command {
        SweepCommand::Run => run_result(&scene, &directory),
        SweepCommand::Buckle => buckle_result(&scene, &directory),
    };
    let seconds = start.elapsed().as_secs_f64();
    let mut result = match computed {
        Ok(result) => result,
        Err(error) => PointResult::error(&hash, &relative, &error, seconds),
    };
    result.hash = hash;
    result.directory = relative;
    result.seconds = seconds;
    result.peak_memory_bytes = peak_tracked
        .then(crate::memory::peak_resident_bytes)
        .flatten();
    if let Err(error) = write_point_file(&directory, &result) {
        return PointResult::error(&result.hash, &result.directory, &error, seconds);
    }
    result
}

/// Writes `point.json` into `directory` (made if missing), atomically.
fn write_point_file(directory: &Path, result: &PointResult) -> Result<(), Error> {
    std::fs::create_dir_all(directory).map_err(crate::error::io_error(directory))?;
    let path = directory.join(POINT_FILE);
    crate::output::write_json(&path, result).map_err(crate::error::io_error(&path))
}

/// `wrinkle run` of `scene` into `directory`, as a result.
fn run_result(scene: &Scene, directory: &Path) -> Result<PointResult, Error> {
    let report = crate::commands::run(scene, directory, true, None)?;
    let summary = &report.summary;
    let threshold = &summary.threshold;
    Ok(PointResult {
        outcome: summary.outcome.name().into(),
        exit_code: Some(summary.outcome.exit_code()),
        reason: summary.outcome.reason().map(str::to_string),
        load_at_amplitude: AMPLITUDE_LEVELS
            .iter()
            .map(|&level| load_at_amplitude(&summary.path, level))
            .collect(),
        steps: Some(summary.steps),
        ..threshold_result(threshold)
    })
}

/// `wrinkle buckle --out` of `scene` into `directory` (its mode and `buckle.json`), as a
/// result: `reached`, or `invalid` (exit 4) when a validity check the scene does not accept
/// failed.
fn buckle_result(scene: &Scene, directory: &Path) -> Result<PointResult, Error> {
    let describe = |scene: &Scene, threshold: &Threshold| {
        let mut value =
            serde_json::to_value(ThresholdSummary::new(scene, threshold)).unwrap_or_default();
        if let Some(object) = value.as_object_mut() {
            object.insert("scene".into(), scene.echo_json());
        }
        value
    };
    let threshold = crate::commands::buckle_with_outputs(scene, true, directory, &describe)?;
    let failure = threshold.validity_failure(&scene.validity);
    Ok(PointResult {
        outcome: if failure.is_some() {
            "invalid"
        } else {
            "reached"
        }
        .into(),
        exit_code: Some(if failure.is_some() { 4 } else { 0 }),
        reason: failure,
        ..threshold_result(&ThresholdSummary::new(scene, &threshold))
    })
}

/// The threshold's part of a result.
fn threshold_result(threshold: &ThresholdSummary) -> PointResult {
    PointResult {
        model: Some(threshold.model.to_string()),
        dofs: Some(threshold.dofs),
        critical_load: Some(threshold.critical_load),
        load_unit: Some(threshold.load_unit.to_string()),
        closed_form_critical_load: threshold.closed_form.closed_form_critical_load,
        closed_form_relative_difference: threshold.closed_form.closed_form_relative_difference,
        closed_form_wavenumber: threshold.closed_form.closed_form_wavenumber,
        wavenumber: threshold.wavenumber,
        wavelength: threshold.wavelength,
        failed_checks: threshold
            .warnings
            .iter()
            .map(|warning| warning.check.to_string())
            .collect(),
        ..PointResult::empty("", "", 0.0)
    }
}
