//! The sheared membrane study (`docs/validation.md`, "Sheared membrane"): the Kapton sheet of
//! `examples/scenes/sheared_membrane.toml` followed past its threshold with the plate and the
//! envelope models, and the wrinkles of the **central region** measured at each shear by the
//! program ([`wrinkle::region_measures`]): wave direction, wavelength, number of wrinkles across
//! the centre line, amplitude, and the complex envelope's local wavenumber.
//!
//! ```sh
//! cargo run --release --example sheared_membrane -- [--out DIR] [--shears 0.08,0.1,0.15]
//!     [--models fvk-plate,reference-envelope,complex-envelope] [--set KEY=VALUE]…
//!     [--measure-only true]
//! ```
//!
//! Each model runs into `DIR/MODEL/` (default `out/sheared_membrane_study`) with its fields
//! written at every shear (`output.vtu_loads`), up to the last shear or the scene's amplitude
//! target; the measures are read back from those files, printed as a table and written to
//! `DIR/central_region.csv`. Envelope models run at the scene's `model.direction` (the central
//! field's −45°); `--set` applies to every model (e.g. `--set mesh.nx=120`). With
//! `--measure-only true` nothing runs: the runs already in `DIR` are measured again (the
//! direction read from their `summary.json`).

use std::path::{Path, PathBuf};
use wrinkle::Scene;
use wrinkle::compare::{ModelState, read_state};
use wrinkle::region_measures::{Region, RegionMeasures, measure_region};

/// Default shears (mm of the top edge's displacement).
const SHEARS: [f64; 5] = [0.07, 0.08, 0.1, 0.15, 0.2];
/// Default models.
const MODELS: [&str; 3] = ["fvk-plate", "reference-envelope", "complex-envelope"];
/// $`\max|w|/h`$ below which the central region counts as flat (the wrinkle maps' colour floor).
const FLAT_OVER_THICKNESS: f64 = 1e-2;
/// Sampling step of the measures (mm): a tenth of the shortest wavelength seen (≈ 14 mm).
const SPACING: f64 = 0.5;

struct Options {
    out: PathBuf,
    shears: Vec<f64>,
    models: Vec<String>,
    sets: Vec<String>,
    measure_only: bool,
}

fn options() -> Result<Options, String> {
    let mut options = Options {
        out: PathBuf::from("out/sheared_membrane_study"),
        shears: SHEARS.to_vec(),
        models: MODELS.iter().map(|m| m.to_string()).collect(),
        sets: Vec::new(),
        measure_only: false,
    };
    let mut args = std::env::args().skip(1);
    while let Some(flag) = args.next() {
        let value = args.next().ok_or(format!("{flag} needs a value"))?;
        match flag.as_str() {
            "--out" => options.out = PathBuf::from(value),
            "--shears" => {
                options.shears = value
                    .split(',')
                    .map(|s| {
                        s.trim()
                            .parse::<f64>()
                            .map_err(|e| format!("--shears: {e}"))
                    })
                    .collect::<Result<_, _>>()?
            }
            "--models" => options.models = value.split(',').map(str::to_string).collect(),
            "--set" => options.sets.push(value),
            "--measure-only" => options.measure_only = value == "true",
            other => return Err(format!("unknown option {other}")),
        }
    }
    Ok(options)
}

/// The scene of one model: the shipped scene, its fields at every shear, the path to the last.
fn model_scene(model: &str, options: &Options) -> Result<Scene, wrinkle::Error> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes/sheared_membrane.toml");
    let mut scene = Scene::load(path)?;
    scene.model.name = model.to_string();
    for set in &options.sets {
        scene.apply_override(set)?;
    }
    let last = options.shears.iter().copied().fold(0.0, f64::max);
    scene.output.vtu_loads = options.shears.clone();
    scene.solver.max_load = last;
    scene.validity.accept = vec!["all".into()];
    scene.validate()?;
    Ok(scene)
}

/// The central region: the middle half of the sheet each way.
fn central_region(scene: &Scene) -> Region {
    let (lx, ly) = (scene.geometry.length_x, scene.geometry.length_y);
    Region {
        x: [0.25 * lx, 0.75 * lx],
        y: [0.25 * ly, 0.75 * ly],
    }
}

/// A CSV row; a region whose $`\max|w|`$ is below `flat` (mm) is flat: its direction, wavelength
/// and crests (of a vanishing carrier) are not reported.
fn row(
    model: &str,
    shear: f64,
    measures: Option<RegionMeasures>,
    flat: f64,
    seconds: f64,
) -> String {
    let number =
        |v: Option<f64>, digits: usize| v.map_or("–".to_string(), |v| format!("{v:.digits$}"));
    match measures {
        Some(m) if m.amplitude < flat => {
            format!("{model},{shear},–,–,–,0,{:.2e},–,{seconds:.1}", m.amplitude)
        }
        Some(m) => format!(
            "{model},{shear},{},{:.3},{},{},{},{},{seconds:.1}",
            number(Some(m.direction_degrees), 1),
            m.coherence,
            number(m.wavelength, 2),
            m.wrinkles,
            number(Some(m.amplitude), 4),
            number(m.local_wavenumber.map(|q| std::f64::consts::TAU / q), 2),
        ),
        None => format!("{model},{shear},–,–,–,–,–,–,{seconds:.1}"),
    }
}

/// Runs `model` into `DIR/MODEL/`; its direction (degrees) and wall time (s).
fn run(scene: &Scene, model: &str, options: &Options) -> Result<(f64, f64), wrinkle::Error> {
    let start = std::time::Instant::now();
    let report = wrinkle::run::run(scene, &options.out.join(model), true)?;
    let seconds = start.elapsed().as_secs_f64();
    let threshold = &report.summary.threshold;
    let outcome = &report.summary.outcome;
    eprintln!(
        "{model}: λ_c = {:.5} mm, direction {}° ({}), {} dofs, {seconds:.1} s, {}",
        threshold.critical_load,
        threshold.direction,
        threshold.direction_mode,
        threshold.dofs,
        outcome.reason().unwrap_or(outcome.name()),
    );
    Ok((threshold.direction, seconds))
}

/// The threshold's direction (degrees) recorded in `DIR/summary.json` of an earlier run.
fn recorded_direction(directory: &Path) -> Result<f64, Box<dyn std::error::Error>> {
    let text = std::fs::read_to_string(directory.join("summary.json"))?;
    let summary: serde_json::Value = serde_json::from_str(&text)?;
    summary["threshold"]["direction"]
        .as_f64()
        .ok_or_else(|| format!("no threshold.direction in {}", directory.display()).into())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let options = options()?;
    // Ctrl-C stops the path after its current point and writes what was computed (as `wrinkle
    // run` does); the next model does not start.
    wrinkle::interrupt::install();
    std::fs::create_dir_all(&options.out)?;
    let mut lines = vec![
        "model,shear_mm,direction_deg,coherence,wavelength_mm,wrinkles,amplitude_mm,local_wavelength_mm,run_seconds".to_string(),
    ];
    for model in &options.models {
        let scene = model_scene(model, &options)?;
        let (direction_degrees, seconds) = if options.measure_only {
            (recorded_direction(&options.out.join(model))?, 0.0)
        } else {
            match run(&scene, model, &options) {
                Ok(done) => done,
                // A path that stopped early (interrupted, failed past its threshold) has written
                // the points it completed: measure those.
                Err(error) => {
                    eprintln!("{model}: {error}");
                    (recorded_direction(&options.out.join(model))?, f64::NAN)
                }
            }
        };
        if wrinkle::interrupt::requested() {
            eprintln!("{model}: interrupted; its completed points are written");
        }
        let direction = direction_degrees.to_radians();
        let region = central_region(&scene);
        for &shear in &options.shears {
            let state: Option<ModelState> =
                read_state(&options.out, model, shear, &scene.output.vtu_loads);
            let measures = state
                .and_then(|state| measure_region(&state.snapshot(direction), &region, SPACING));
            let flat = FLAT_OVER_THICKNESS * scene.material.thickness;
            lines.push(row(model, shear, measures, flat, seconds));
        }
    }
    let text = lines.join("\n") + "\n";
    std::fs::write(options.out.join("central_region.csv"), &text)?;
    print!("{text}");
    Ok(())
}
