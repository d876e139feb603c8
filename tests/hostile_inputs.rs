//! Issue 26, hostile-input sweep: generated cases over scene keys × bad values (NaN, ±inf, 0,
//! −0, ±1e308, ±1e-308, negative, huge, wrong types). Each case is either refused where it
//! enters — exit 2 (a scene error) naming the key itself, before any work — or accepted and then
//! run to the end: `wrinkle run` exits 0, 3 or 4 (never 1, a solver failure, nor a panic), with
//! finite numbers in `summary.json`, and every value not used as given said in a note. One
//! exception: a `model.direction` far from the compression is a valid scene without a
//! threshold, whose search fails with exit 1 saying which direction to set.
//!
//! The sweep in CI checks every case against the schema (in-process, milliseconds) and runs the
//! accepted ones on an 8 × 4 mesh without plots or fields (a few seconds in all); the ignored
//! test `hostile_inputs_sweep_every_key` does the same over every key of the schema
//! (`cargo test --test hostile_inputs -- --ignored`).

use std::path::PathBuf;
use std::process::Command;
use wrinkle::Error;
use wrinkle::scene::Scene;

/// The bad values, as they are written after `--set KEY=`.
const BAD_VALUES: [&str; 16] = [
    "nan",
    "inf",
    "-inf",
    "0",
    "-0.0",
    "1e308",
    "-1e308",
    "1e-308",
    "-1e-308",
    "-1",
    "-1e30",
    "1e30",
    "\"text\"",
    "true",
    "[1]",
    "{ a = 1 }",
];

/// The keys of the CI sweep: each key with a number, a count, or a number in a list, and the
/// model parameters that are spellings of other keys.
const SWEPT_KEYS: [&str; 16] = [
    "geometry.lx",
    "material.young",
    "material.poisson",
    "material.thickness",
    "model.wavenumber",
    "model.direction",
    "model.parameters.young",
    "model.parameters.wavenumber",
    "mesh.nx",
    "mesh.grading",
    "mesh.grading_x",
    "load.tension_y",
    "solver.perturbation",
    "solver.max_load",
    "solver.max_amplitude_over_h",
    "output.profile_line",
];

/// How a case ended.
#[derive(Debug)]
enum Verdict {
    /// Refused with a scene error naming this key.
    Refused(String),
    /// Accepted by the scene.
    Accepted,
}

/// Applies `key=value` to the default scene and validates it.
fn verdict(key: &str, value: &str) -> Verdict {
    let mut scene = Scene::default();
    let result = scene
        .apply_override(&format!("{key}={value}"))
        .and_then(|()| scene.validate());
    match result {
        Ok(()) => Verdict::Accepted,
        Err(Error::Scene { key, .. }) => Verdict::Refused(key),
        Err(other) => Verdict::Refused(format!("not a scene error: {other}")),
    }
}

/// Runs an accepted case and returns what is wrong with it, if anything.
fn run_accepted(key: &str, value: &str, out: &std::path::Path) -> Option<String> {
    let assignment = format!("{key}={value}");
    let mut arguments = vec!["run", "-q"];
    for setting in [
        "mesh.nx=8",
        "mesh.ny=4",
        "output.plots=false",
        "output.surface=false",
        "output.vtu=false",
    ] {
        if !setting.starts_with(&format!("{key}=")) {
            arguments.extend(["--set", setting]);
        }
    }
    arguments.extend(["--set", &assignment]);
    let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(&arguments)
        .arg("--out")
        .arg(out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    let code = output.status.code();
    // Refused once the model is known (an unknown entry of `model.parameters`), naming it.
    if code == Some(2) && stderr.contains(&format!("key `{key}")) {
        return None;
    }
    // A wave vector far from the compression is a valid scene without a threshold: the
    // wavenumber search fails (exit 1) and says which key to change.
    let direction = key.ends_with("direction");
    if code == Some(1) && direction && stderr.contains("set model.direction = 0") {
        return None;
    }
    if !matches!(code, Some(0 | 3 | 4)) {
        return Some(format!("exit {code:?}: {}", stderr.trim()));
    }
    let text = std::fs::read_to_string(out.join("summary.json")).unwrap_or_default();
    let summary: serde_json::Value = match serde_json::from_str(&text) {
        Ok(summary) => summary,
        Err(error) => return Some(format!("summary.json: {error}")),
    };
    let critical = summary["linear_buckling_load"].as_f64();
    if !critical.is_some_and(f64::is_finite) {
        return Some(format!("linear_buckling_load {critical:?}"));
    }
    let path = summary["path"].as_array().cloned().unwrap_or_default();
    let finite = path.iter().all(|point| {
        ["lambda", "max_amplitude_over_h"]
            .iter()
            .all(|column| point[column].as_f64().is_some_and(f64::is_finite))
    });
    if !finite || path.is_empty() {
        return Some("a path point that is not finite".to_string());
    }
    used_as_given(&summary, key, value)
}

/// `None` when the effective scene echoed in `summary` holds `value` under `key` (a spelling of
/// another key is echoed as that key, and not checked here), or a note titled `key` says what
/// was used instead.
fn used_as_given(summary: &serde_json::Value, key: &str, value: &str) -> Option<String> {
    let (section, name) = key.split_once('.')?;
    let echoed = summary["scene"][section].get(name)?;
    let (Some(echoed), Ok(given)) = (echoed.as_f64(), value.parse::<f64>()) else {
        return None;
    };
    let noted = summary["notes"]
        .as_array()
        .is_some_and(|notes| notes.iter().any(|note| note["title"] == key));
    (echoed != given && !noted).then(|| format!("used {echoed} without a note"))
}

/// The sweep over `keys` × [`BAD_VALUES`], running into a directory named after `label`:
/// every failure, one line each.
fn sweep(label: &str, keys: &[&str]) -> Vec<String> {
    let out: PathBuf =
        std::env::temp_dir().join(format!("wrinkle-hostile-{label}-{}", std::process::id()));
    let mut failures = Vec::new();
    let (mut refused, mut accepted) = (0, 0);
    for key in keys {
        for value in BAD_VALUES {
            match verdict(key, value) {
                // A table key (`model.parameters`) names the entry inside it.
                Verdict::Refused(named)
                    if named == *key || named.starts_with(&format!("{key}.")) =>
                {
                    refused += 1
                }
                Verdict::Refused(named) => {
                    failures.push(format!("{key} = {value}: refused naming `{named}`"));
                }
                Verdict::Accepted => {
                    accepted += 1;
                    if let Some(problem) = run_accepted(key, value, &out) {
                        failures.push(format!("{key} = {value}: accepted, then {problem}"));
                    }
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&out);
    eprintln!("{refused} cases refused naming their key, {accepted} accepted and run");
    failures
}

#[test]
fn hostile_inputs_are_refused_naming_the_key_or_run_cleanly() {
    let failures = sweep("ci", &SWEPT_KEYS);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

/// Every value that cannot be a number is refused for every key of the schema that takes one,
/// and nothing panics on any key.
#[test]
fn wrong_types_are_refused_for_every_key() {
    for key in wrinkle::scene::KEYS {
        for value in ["nan", "\"text\"", "{ a = 1 }"] {
            let verdict = std::panic::catch_unwind(|| verdict(key, value));
            let Ok(verdict) = verdict else {
                panic!("{key} = {value}: panicked");
            };
            if let Verdict::Refused(named) = &verdict {
                // A table key may name the entry inside it (`load.boundary.a`).
                let inside = named.starts_with(&format!("{key}."));
                assert!(named == key || inside, "{key} = {value}: named {named}");
            }
        }
    }
}

/// The larger sweep: every key of the schema and every model parameter that spells another key.
#[test]
#[ignore = "runs every accepted case of every key (a minute or so)"]
fn hostile_inputs_sweep_every_key() {
    let mut keys: Vec<&str> = wrinkle::scene::KEYS.to_vec();
    keys.extend([
        "model.parameters.poisson",
        "model.parameters.thickness",
        "model.parameters.direction",
        "solver.max_envelope_over_h",
    ]);
    let failures = sweep("every-key", &keys);
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
