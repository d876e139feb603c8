//! The `wrinkle` command line: argument parsing (clap derive) and the subcommands.
//!
//! Every failure prints one line `error: …` on stderr and exits with [`Error::exit_code`]
//! (2 for scene and usage errors, 1 for solver failures); usage errors found by clap exit with 2.

use crate::Error;
use crate::analytic;
use crate::closed_form;
use crate::commands;
use crate::scene::{LoadKind, Scene};
use clap::{Args, Parser, Subcommand};
use std::ffi::OsString;
use std::io::Write;
use std::path::{Path, PathBuf};

/// Multi-scale membrane wrinkling: envelope models, Q8 finite elements, buckling and ANM.
#[derive(Debug, Parser)]
#[command(name = "wrinkle", version, about)]
pub struct Cli {
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
    },
    /// Path following (ANM or Riks) writing results into an output directory.
    Run {
        /// Scene and overrides.
        #[command(flatten)]
        scene: SceneArguments,
        /// Output directory (overrides `output.directory`).
        #[arg(long, value_name = "DIR")]
        out: Option<PathBuf>,
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
    Models,
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
            let _ = error.print();
            return if error.use_stderr() { 2 } else { 0 };
        }
    };
    match execute(&cli.command) {
        Ok(()) => 0,
        Err(error) => {
            eprintln!("error: {error}");
            error.exit_code()
        }
    }
}

/// Executes one subcommand, writing its results on stdout.
pub fn execute(command: &Command) -> Result<(), Error> {
    match command {
        Command::Buckle { scene, json } => {
            let scene = scene.resolve()?;
            let report = commands::buckle(&scene)?;
            if *json {
                print_stdout(&format!("{}\n", buckle_json(&scene, &report)))
            } else {
                print_stdout(&buckle_summary(&scene, &report))
            }
        }
        Command::Run { scene, out } => {
            let mut scene = scene.resolve()?;
            if let Some(directory) = out {
                scene.output.directory = directory.display().to_string();
            }
            let directory = PathBuf::from(&scene.output.directory);
            let report = commands::run(&scene, &directory)?;
            let s = &report.summary;
            println!(
                "{}: {} steps, {} factorisations, linear buckling load {:.6e}, detected bifurcation {}, {}",
                s["model"].as_str().unwrap_or(""),
                s["steps"],
                s["statistics"]["factorizations"],
                s["linear_buckling_load"].as_f64().unwrap_or(f64::NAN),
                s["detected_bifurcation"]["load"],
                s["stop"].as_str().unwrap_or("")
            );
            eprintln!("run finished; outputs in {}", directory.display());
            Ok(())
        }
        Command::Analytic {
            scene,
            json,
            table_1,
        } => {
            let scene = scene.resolve()?;
            let options = analytic::AnalyticOptions {
                table_1: *table_1,
                ..analytic::AnalyticOptions::default()
            };
            let report = analytic::analyse(&scene, &options)?;
            if *json {
                print_stdout(&format!("{}\n", report.to_json(&scene)))
            } else {
                print_stdout(&report.summary(&scene))
            }
        }
        Command::Models => print_stdout(&models_listing(&commands::models())),
        Command::Scene { scene } => print_stdout(&scene.resolve()?.to_toml_string()),
    }
}

/// The `buckle --json` object: the report's keys, `details` merged in (without overwriting the
/// report's own keys), and the effective scene under `scene`.
pub fn buckle_json(scene: &Scene, report: &commands::BuckleReport) -> serde_json::Value {
    let mut object = serde_json::Map::new();
    if let serde_json::Value::Object(details) = &report.details {
        object.extend(details.clone());
    } else if !report.details.is_null() {
        object.insert("details".to_string(), report.details.clone());
    }
    object.insert("model".to_string(), report.model.clone().into());
    object.insert(
        "critical_load".to_string(),
        json_number(report.critical_load),
    );
    object.insert("wavenumber".to_string(), json_number(report.wavenumber));
    object.insert("wavelength".to_string(), json_number(report.wavelength));
    object.insert("dofs".to_string(), report.dofs.into());
    object.insert(
        "closed_form_critical_load".to_string(),
        report
            .closed_form_critical_load
            .map_or(serde_json::Value::Null, json_number),
    );
    object.insert("scene".to_string(), scene.echo_json());
    serde_json::Value::Object(object)
}

/// A JSON number, or `null` for a non-finite value (JSON has no NaN or infinity).
fn json_number(value: f64) -> serde_json::Value {
    serde_json::Number::from_f64(value).map_or(serde_json::Value::Null, serde_json::Value::Number)
}

/// The human summary printed by `buckle`.
pub fn buckle_summary(scene: &Scene, report: &commands::BuckleReport) -> String {
    let mut lines = vec![
        format!("scene: {}", scene.source),
        format!("model: {} ({} dofs)", report.model, report.dofs),
    ];
    match scene.load.kind {
        LoadKind::Biaxial => {
            lines.push(format!(
                "critical load: λ_c = {:.6e} N/mm (N_X = {:.6e} N/mm, N_Y = {} N/mm)",
                report.critical_load, -report.critical_load, scene.load.tension_y
            ));
        }
        LoadKind::Strip => {
            lines.push(format!(
                "critical load: λ_c = {:.6e} mm (end displacement)",
                report.critical_load
            ));
        }
    }
    lines.push(format!(
        "wavenumber: Q = {:.6e} 1/mm, wavelength 2π/Q = {:.6} mm",
        report.wavenumber,
        closed_form::wavelength(report.wavenumber)
    ));
    if let Some(reference) = report.closed_form_critical_load {
        let difference = (report.critical_load - reference) / reference;
        lines.push(format!(
            "closed form (42): λ_c = {reference:.6e}, relative difference {difference:+.3e}"
        ));
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
