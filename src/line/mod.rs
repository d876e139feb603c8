//! Line domains (`geometry.kind = "line"`): a beam on $`[0, L]`$ — the paper's
//! one-dimensional prototype (THEORY.md §7, `docs/beam.md`) — through `wrinkle buckle`, `run`
//! and `compare`, with outputs adapted to a line (`docs/outputs.md`, "Line domains").
//!
//! The pipeline is the plane one's, reduced to what a line has: scene → problem
//! ([`setup`]: element by the model's jet, supports and end load by field role, parameter
//! profiles) → linear buckling ([`threshold`]) → a mode-shaped imperfection → the path
//! ([`path`], the runtime's `follow_path`: ANM with or without Padé, or Riks) → results typed
//! here, serialised by [`outputs`]. What a field is comes from its role ([`layout`]); no model
//! is named. Not carried over from the plane: the wavenumber search (a line scene fixes
//! `model.wavenumber`), closed forms and validity checks, the HTML report.

pub mod compare;
pub mod layout;
pub mod outputs;
pub mod path;
pub mod setup;
pub mod threshold;

pub use compare::{LineComparison, compare_line};
pub use layout::{LineDeflection, LineLayout};
pub use path::{LinePathPoint, LineRun, run_line};
pub use threshold::{LineThreshold, buckle_line};

use crate::output::Quantity;
use crate::scene::Scene;
use crate::setup::load_is_displacement;

/// The load parameter of a line scene: an end shortening (mm) when some end displacement is
/// proportional to it, an end force (N) otherwise.
pub fn line_load_quantity(scene: &Scene) -> Quantity {
    if load_is_displacement(scene) {
        Quantity::new("end shortening", "λ", "mm")
    } else {
        Quantity::new("end force", "λ", "N")
    }
}

/// Positions $`X`$ where profiles are sampled: 16 per wavelength $`2\pi/Q`$, at least 401,
/// at most 20 001, ends included.
pub fn sample_positions(length: f64, wavenumber: f64) -> Vec<f64> {
    let wavelengths = length * wavenumber / (2.0 * std::f64::consts::PI);
    let intervals = ((16.0 * wavelengths).ceil() as usize).clamp(400, 20_000);
    (0..=intervals)
        .map(|k| length * k as f64 / intervals as f64)
        .collect()
}

/// `wrinkle buckle` on a line scene: the text (or JSON with `json`) to print; with `out`, the
/// mode (`mode_profile.csv`, `mode_profile.png/.svg`, `mode.vtu`) and `buckle.json` there.
pub fn buckle_command(
    scene: &Scene,
    json: bool,
    out: Option<&std::path::Path>,
) -> Result<String, crate::error::Error> {
    let threshold = buckle_line(scene)?;
    if let Some(directory) = out {
        outputs::write_buckle_files(directory, &threshold)
            .map_err(crate::error::io_error(directory))?;
    }
    Ok(if json {
        serde_json::to_string_pretty(&threshold).unwrap_or_default() + "\n"
    } else {
        threshold::line_threshold_text(&threshold)
    })
}

/// `wrinkle run` on a line scene: runs and writes the run's files into `directory` (a
/// [`crate::output::RunDirectory`]: locked, staged, swapped in whole); returns the text to
/// print and the run's error when it did not reach what was asked (exit 3).
pub fn run_command(
    scene: &Scene,
    directory: &std::path::Path,
) -> Result<(String, Option<crate::error::Error>), crate::error::Error> {
    let io = crate::error::io_error(directory);
    let mut run_directory = crate::output::RunDirectory::open(directory).map_err(io)?;
    let fields = run_directory.path("fields_final.vtu");
    let run = run_line(scene, Some(&fields))?;
    let files = outputs::write_run_files(&run_directory, &run, scene.material.thickness)
        .map_err(crate::error::io_error(directory))?;
    let io = crate::error::io_error(directory);
    run_directory
        .record(files.iter().chain(std::iter::once(&fields)))
        .map_err(io)?;
    let io = crate::error::io_error(directory);
    run_directory.write_summary(&run).map_err(io)?;
    let io = crate::error::io_error(directory);
    run_directory.commit().map_err(io)?;
    let error = (!run.complete).then(|| {
        crate::error::Error::Incomplete(format!(
            "the path stopped before the target ({}); outputs written to {}",
            run.stop_reason,
            directory.display()
        ))
    });
    Ok((path::line_run_text(&run), error))
}
