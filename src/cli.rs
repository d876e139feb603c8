//! The `wrinkle` command line: argument parsing (clap derive) and the subcommands.
//!
//! Every failure prints one line `error: …` on stderr and exits with [`Error::exit_code`]
//! (2 for scene and usage errors, 1 for solver failures); usage errors found by clap exit with 2.

use crate::analytic;
use crate::closed_form;
use crate::commands;
use crate::error::Error;
use crate::output::message_line;
use crate::scene::{LoadKind, Scene};
use crate::threshold::ThresholdSummary;
use clap::{Args, Parser, Subcommand};
use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Multi-scale membrane wrinkling: envelope models, Q8 finite elements, buckling and ANM.
#[derive(Debug, Parser)]
#[command(name = "wrinkle", version, about)]
pub struct Cli {
    /// Worker threads for assembly and the ANM's series sweeps (default: one per core; the
    /// sparse factorisation is sequential). Results do not depend on it: every sum is taken in
    /// an order fixed by the mesh.
    #[arg(long, global = true, value_name = "N", value_parser = clap::value_parser!(u16).range(1..=1024))]
    pub threads: Option<u16>,
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Linear buckling analysis: critical load and wavenumber.
    Buckle {
        /// Scene and overrides.
        #[command(flatten)]
        scene: SceneArguments,
        /// Print exactly one JSON object on stdout instead of a human summary.
        #[arg(long)]
        json: bool,
        /// No progress reports on stderr.
        #[arg(long, short)]
        quiet: bool,
        /// Also write the buckling mode (`mode.vtu`, `mode_surface.vtu`), the wavenumber search
        /// (`wavenumber_search.csv/.png/.svg`) and `buckle.json` into this directory.
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
    },
    /// Path following (ANM or Riks) writing results into an output directory.
    Run {
        /// Scene and overrides.
        #[command(flatten)]
        scene: SceneArguments,
        /// Output directory (overrides `output.directory`).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// Reuse the wavenumber of an earlier threshold of the same scene instead of searching
        /// it again: the JSON of `wrinkle buckle --json` or a run's `summary.json` (checked
        /// against the scene's geometry, material, model, mesh and load).
        #[arg(long, value_name = "FILE")]
        threshold: Option<PathBuf>,
        /// No progress reports on stderr.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Runs the scene with several models into `OUT/MODEL/` and compares thresholds,
    /// wavelengths and loads at given amplitudes (`compare.csv`, `compare.json`, `compare.png`).
    Compare {
        /// Scene and overrides.
        #[command(flatten)]
        scene: SceneArguments,
        /// Comma-separated model names (default: every hand-written registered model of a plane
        /// domain; the DSL-derived models are named explicitly).
        #[arg(long, value_delimiter = ',')]
        models: Vec<String>,
        /// Override a scene key for one model only, `MODEL:KEY=VALUE` (repeatable), e.g.
        /// `--model-set fvk-plate:mesh.nx=128` to resolve the plate's wrinkles while the
        /// envelope models keep the coarse mesh.
        #[arg(long = "model-set", value_name = "MODEL:KEY=VALUE")]
        model_overrides: Vec<String>,
        /// Output directory (default: `output.directory`/compare).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
        /// No progress reports on stderr.
        #[arg(long, short)]
        quiet: bool,
    },
    /// Run time against error: sweeps of mesh, ANM order and series tolerance, each point's
    /// errors against a converged reference of the same model (`bench.csv`, `bench.json`,
    /// `bench.png`). See docs/benchmarks.md.
    Bench {
        /// Scene and overrides.
        #[command(flatten)]
        scene: SceneArguments,
        /// Comma-separated model names (default: reference-envelope).
        #[arg(long, value_delimiter = ',')]
        models: Vec<String>,
        /// Output directory.
        #[arg(long, value_name = "DIR", default_value = "out/bench")]
        out: PathBuf,
        /// Reduced sweep: coarse meshes, two or three points per sweep.
        #[arg(long)]
        quick: bool,
    },
    /// Closed forms of the clamped rectangle in biaxial load (THEORY.md §8): exact minimum of
    /// (42), approximations (44) and (96), Galerkin integrals, amplitude law (61)–(62) and a
    /// converged multi-term Galerkin solution of (55). See docs/analytic.md.
    Analytic {
        /// Scene and overrides.
        #[command(flatten)]
        scene: SceneArguments,
        /// Print exactly one JSON object on stdout instead of a human summary.
        #[arg(long)]
        json: bool,
        /// Also reproduce Table 1 of the paper (printed vs computed, ν = 0.3 and 0).
        #[arg(long)]
        table_1: bool,
    },
    /// List the registered models with their fields and parameters.
    Models {
        /// Print one model in full: its terms and, for a model derived from a microscopic
        /// energy, its provenance and derived energy.
        #[arg(long, value_name = "NAME")]
        show: Option<String>,
    },
    /// Runs the scene over a grid of key values, each point in its own process and directory,
    /// into a table `sweep.csv`; see docs/python.md.
    Sweep(crate::sweep::SweepArguments),
    /// One point of a sweep (run by `sweep`, its scene recipe as JSON on standard input).
    #[command(hide = true)]
    SweepPoint(crate::sweep::SweepPointArguments),
    /// Print the effective scene (defaults, file and overrides merged) as TOML.
    Scene {
        /// Scene and overrides.
        #[command(flatten)]
        scene: SceneArguments,
    },
}

/// A scene file and `--set` overrides, shared by the subcommands.
#[derive(Debug, Args)]
pub struct SceneArguments {
    /// Scene file (TOML); the built-in default scene (the paper's example 1) when omitted.
    #[arg(value_name = "SCENE")]
    pub path: Option<PathBuf>,
    /// Override one scene key, e.g. `--set material.poisson=0.25` (repeatable, applied in order).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub overrides: Vec<String>,
}

impl SceneArguments {
    /// Loads the scene (or the default), applies the overrides in order and validates.
    pub fn resolve(&self) -> Result<Scene, Error> {
        let mut scene = match &self.path {
            Some(path) => Scene::load(path)?,
            None => Scene::default(),
        };
        for assignment in &self.overrides {
            scene.apply_override(assignment)?;
        }
        scene.validate()?;
        Ok(scene)
    }
}

/// Runs the command line given by `arguments` (including the program name) and returns the
/// process exit code. Never panics on bad input.
pub fn main_with_arguments<I, T>(arguments: I) -> i32
where
    I: IntoIterator<Item = T>,
    T: Into<OsString> + Clone,
{
    let cli = match Cli::try_parse_from(arguments) {
        Ok(cli) => cli,
        Err(error) => {
            let printed = error.print();
            return match printed {
                _ if error.use_stderr() => 2,
                // `--help` or `--version` that cannot be written (a full disk): not a success.
                Err(failure) if failure.kind() != std::io::ErrorKind::BrokenPipe => 1,
                _ => 0,
            };
        }
    };
    if let Some(threads) = cli.threads {
        // Only fails when a global pool already exists (a second call in one process, as in
        // tests); the existing pool is then kept.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(usize::from(threads))
            .build_global();
    }
    match execute(&cli.command) {
        Ok(()) => 0,
        Err(error) => {
            message_line(&format!("error: {error}"));
            error.exit_code()
        }
    }
}

/// Executes one subcommand, writing its results on stdout.
pub fn execute(command: &Command) -> Result<(), Error> {
    match command {
        Command::Buckle {
            scene,
            json,
            quiet,
            out,
        } => buckle(&scene.resolve()?, *json, *quiet, out.as_deref()),
        Command::Run {
            scene,
            out,
            threshold,
            quiet,
        } => run(scene, out.as_deref(), threshold.as_deref(), *quiet),
        Command::Compare {
            scene,
            models,
            model_overrides,
            out,
            quiet,
        } => compare(&scene.resolve()?, models, model_overrides, out, *quiet),
        Command::Bench {
            scene,
            models,
            out,
            quick,
        } => {
            let scene = scene.resolve()?;
            let bench = crate::bench::bench(&scene, models, *quick, out)?;
            print_stdout(&crate::bench::bench_table(&bench))?;
            message_line(&format!("benchmark in {}", out.display()));
            Ok(())
        }
        Command::Analytic {
            scene,
            json,
            table_1,
        } => analytic(&scene.resolve()?, *json, *table_1),
        Command::Models { show: None } => print_stdout(&models_listing(&commands::models())),
        Command::Models { show: Some(name) } => print_stdout(&commands::model_details(name)?),
        Command::Sweep(arguments) => crate::sweep::command::sweep(arguments),
        Command::SweepPoint(arguments) => crate::sweep::command::sweep_point(arguments),
        Command::Scene { scene } => print_stdout(&scene.resolve()?.to_toml_string()),
    }
}

/// `wrinkle buckle`: the threshold as JSON or as text; exit 4 when a validity check the scene
/// does not accept failed.
fn buckle(scene: &Scene, json: bool, quiet: bool, out: Option<&Path>) -> Result<(), Error> {
    if scene.geometry.domain == crate::scene::Domain::Line {
        return print_stdout(&crate::line::buckle_command(scene, json, out)?);
    }
    let threshold = match out {
        Some(directory) => {
            let describe = |scene: &Scene, threshold: &crate::threshold::Threshold| {
                let summary = ThresholdSummary::new(scene, threshold);
                serde_json::to_value(buckle_json(scene, &summary)).unwrap_or_default()
            };
            commands::buckle_with_outputs(scene, quiet, directory, &describe)?
        }
        None => commands::buckle(scene, quiet)?,
    };
    let summary = ThresholdSummary::new(scene, &threshold);
    if json {
        print_json(&buckle_json(scene, &summary))?;
    } else {
        print_stdout(&buckle_summary(scene, &summary))?;
    }
    match threshold.validity_failure(&scene.validity) {
        Some(reason) => Err(Error::Invalid(reason)),
        None => Ok(()),
    }
}

/// `wrinkle run`: the scene (`--out` replacing `output.directory`), an earlier threshold to
/// reuse (`--threshold`), the run with Ctrl-C caught.
fn run(
    scene: &SceneArguments,
    out: Option<&Path>,
    threshold: Option<&Path>,
    quiet: bool,
) -> Result<(), Error> {
    let mut scene = scene.resolve()?;
    let prior = threshold
        .map(|file| crate::threshold::PriorThreshold::read(file, &scene))
        .transpose()?;
    if let Some(directory) = out {
        scene.output.directory = directory.display().to_string();
    }
    let directory = PathBuf::from(&scene.output.directory);
    crate::interrupt::install();
    if scene.geometry.domain == crate::scene::Domain::Line {
        let (text, error) = crate::line::run_command(&scene, &directory)?;
        print_stdout(&text)?;
        return error.map_or(Ok(()), Err);
    }
    let report = commands::run(&scene, &directory, quiet, prior.as_ref())?;
    // The summary table goes to stdout whatever the outcome. A closed pipe is not an error; a
    // stdout that cannot be written (a full disk) is, after the run's own failure if it has one.
    let printed = print_stdout(&report.summary_text);
    let written = format!("(outputs written to {})", directory.display());
    if let Some(error) = report.summary.outcome.error(&written) {
        return Err(error);
    }
    printed?;
    message_line(&format!("outputs in {}", directory.display()));
    Ok(())
}

/// `wrinkle compare`: every registered model that runs on the scene's plane domain (roles that
/// give a plane [`Layout`](crate::physics::Layout): in-plane displacements along X and Y — not
/// the beam models of a line) and is written by hand — the models the DSL derives from a
/// microscopic energy ([`ModelSpec::derivation`](wrinkle_runtime::model::ModelSpec::derivation))
/// reproduce hand-written ones or are research variants, compared when named — unless `models`
/// names some.
fn compare(
    scene: &Scene,
    models: &[String],
    model_overrides: &[String],
    out: &Option<PathBuf>,
    quiet: bool,
) -> Result<(), Error> {
    let models_named = models.to_vec();
    let models: Vec<String> = if models.is_empty() {
        crate::compare::default_models()
    } else {
        models.to_vec()
    };
    let directory = out
        .clone()
        .unwrap_or_else(|| PathBuf::from(&scene.output.directory).join("compare"));
    if scene.geometry.domain == crate::scene::Domain::Line {
        let comparison = crate::line::compare_line(scene, &models_named, &directory)?;
        print_stdout(&crate::line::compare::line_comparison_text(&comparison))?;
        message_line(&format!("comparison in {}", directory.display()));
        return Ok(());
    }
    let comparison = crate::compare::compare(scene, &models, model_overrides, &directory, quiet)?;
    // The table goes to stdout whatever the outcome; a model that did not reach what was asked
    // (outside its validity, stopped, failed) ends the command with the comparison's exit code,
    // every result written.
    let printed = print_stdout(&crate::compare::comparison_table(
        &comparison,
        crate::threshold::load_unit(scene),
    ));
    let written = format!(
        "every model's results and the comparison written to {}",
        directory.display()
    );
    if let Some(error) = comparison.error(&written) {
        return Err(error);
    }
    printed?;
    message_line(&format!("comparison in {}", directory.display()));
    Ok(())
}

/// `wrinkle analytic`: the closed forms of the scene, as JSON or as text.
fn analytic(scene: &Scene, json: bool, table_1: bool) -> Result<(), Error> {
    let options = analytic::AnalyticOptions {
        table_1,
        ..analytic::AnalyticOptions::default()
    };
    let report = analytic::analyse(scene, &options)?;
    if json {
        print_stdout(&format!("{}\n", report.to_json(scene)))
    } else {
        print_stdout(&report.summary(scene))
    }
}

/// The `buckle --json` object: the threshold's keys (`docs/outputs.md`) and the effective
/// scene under `scene`.
#[derive(Debug, serde::Serialize)]
pub struct BuckleJson<'a> {
    /// The threshold's keys.
    #[serde(flatten)]
    pub threshold: &'a ThresholdSummary,
    /// The effective scene, as echoed.
    pub scene: serde_json::Value,
}

/// The `buckle --json` object of `threshold`, found on `scene`.
pub fn buckle_json<'a>(scene: &Scene, threshold: &'a ThresholdSummary) -> BuckleJson<'a> {
    BuckleJson {
        threshold,
        scene: scene.echo_json(),
    }
}

/// The human summary printed by `buckle`.
pub fn buckle_summary(scene: &Scene, report: &ThresholdSummary) -> String {
    let critical = report.critical_load;
    let mut lines = vec![
        format!("scene: {}", scene.source),
        format!("model: {} ({} dofs)", report.model, report.dofs),
    ];
    match scene.load.kind {
        LoadKind::Biaxial => lines.push(format!(
            "critical load: λ_c = {critical:.6e} N/mm (N_X = {:.6e} N/mm, N_Y = {} N/mm)",
            -critical, scene.load.tension_y
        )),
        LoadKind::Strip => lines.push(format!(
            "critical load: λ_c = {critical:.6e} mm (end displacement)"
        )),
        LoadKind::Boundaries => lines.push(format!(
            "critical load: λ_c = {critical:.6e} {}",
            crate::threshold::load_unit(scene)
        )),
    }
    match (report.wavenumber, report.wavelength) {
        (Some(q), _) => lines.push(format!(
            "wavenumber: Q = {q:.6e} 1/mm ({}), wavelength 2π/Q = {:.6} mm",
            report.wavenumber_mode,
            closed_form::wavelength(q)
        )),
        (None, Some(l)) => lines.push(format!("wavelength of the mode: {l:.6} mm")),
        (None, None) => {}
    }
    let closed_form = &report.closed_form;
    if let (Some(reference), Some(difference)) = (
        closed_form.closed_form_critical_load,
        closed_form.closed_form_relative_difference,
    ) {
        lines.push(format!(
            "closed form (42), envelope: λ_c = {reference:.6e}, relative difference {difference:+.3e}"
        ));
    }
    lines.push(format!(
        "{} buckling analyses, {:.2} s",
        report.buckling_evaluations, report.seconds
    ));
    for note in &report.notes {
        lines.push(format!("note: {note}"));
    }
    for warning in &report.warnings {
        if scene.validity.accepts(warning.check) {
            lines.push(format!(
                "note ({}, accepted by validity.accept): {}",
                warning.check, warning.message
            ));
        } else {
            lines.push(format!("warning ({}): {}", warning.check, warning.message));
        }
    }
    let mut text = lines.join("\n");
    text.push('\n');
    text
}

/// The `models` listing.
pub fn models_listing(models: &[(String, String, Vec<String>, Vec<String>)]) -> String {
    if models.is_empty() {
        return "no models registered\n".to_string();
    }
    let mut text = String::new();
    for (name, description, fields, parameters) in models {
        text.push_str(&format!(
            "{name}\n    {description}\n    fields: {}\n    parameters: {}\n",
            fields.join(", "),
            parameters.join(", ")
        ));
    }
    text
}

/// Writes `value` as one line of JSON to stdout.
fn print_json(value: &impl serde::Serialize) -> Result<(), Error> {
    let text = serde_json::to_string(value).map_err(|error| Error::Io {
        path: "<stdout>".into(),
        error: error.into(),
    })?;
    print_stdout(&format!("{text}\n"))
}

/// Writes to stdout; a closed pipe (e.g. `| head`) is not an error worth a panic.
fn print_stdout(text: &str) -> Result<(), Error> {
    let mut stdout = std::io::stdout().lock();
    match stdout
        .write_all(text.as_bytes())
        .and_then(|()| stdout.flush())
    {
        Ok(()) => Ok(()),
        Err(error) if error.kind() == std::io::ErrorKind::BrokenPipe => Ok(()),
        Err(error) => Err(Error::Io {
            path: Path::new("<stdout>").display().to_string(),
            error,
        }),
    }
}
