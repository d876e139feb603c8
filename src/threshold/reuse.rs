//! A threshold computed before on the same scene, reused by `wrinkle run --threshold FILE`.
//!
//! The wavenumber search is most of a threshold's cost (18 buckling analyses on example 1, of
//! which 4 on the real mesh). A run that follows a `wrinkle buckle --json` of the same scene, or
//! re-runs a scene with other solver or output settings, reads the minimiser $`Q`$ and the
//! critical load from that file and does one analysis at that $`Q`$ (for the mode, the
//! pre-buckling state and the checks), shifted to just below the recorded $`\lambda_c`$.
//!
//! The file is accepted only when it was computed for the same threshold: its echoed scene must
//! equal this one in every key of [`THRESHOLD_SECTIONS`] (the solver, output and validity
//! sections do not enter the threshold). Anything else is a usage error naming the file and the
//! first key that differs (exit 2). A file written before `model.wavenumber_model` existed was
//! computed with its default, [`REFERENCE_MODEL`], and is read as such.

use crate::error::Error;
use crate::scene::{Direction, Scene, Wavenumber};
use serde_json::Value;
use std::path::Path;
use wrinkle_models::REFERENCE_MODEL;

/// The scene sections the threshold depends on.
pub const THRESHOLD_SECTIONS: [&str; 5] = ["geometry", "material", "model", "mesh", "load"];

/// The wavenumber and critical load of an earlier threshold of the same scene.
#[derive(Clone, Debug, PartialEq)]
pub struct PriorThreshold {
    /// The file they were read from (as given on the command line).
    pub file: String,
    /// The minimiser $`Q`$ found there (1/mm).
    pub wavenumber: f64,
    /// The critical load found there (the unit of the scene's load).
    pub critical_load: f64,
    /// The wave direction found there (degrees from X), read for a scene with
    /// `model.direction = "auto"` (whose direction search it replaces too).
    pub direction_degrees: Option<f64>,
}

impl PriorThreshold {
    /// Reads `path` — the JSON printed by `wrinkle buckle --json`, or a run's `summary.json`
    /// (whose `threshold` object is used) — and checks that it belongs to `scene`.
    pub fn read(path: &Path, scene: &Scene) -> Result<Self, Error> {
        let file = path.display().to_string();
        let source = format!("--threshold {file}");
        let fail = |key: &str, message: String| Error::scene(&source, key, message);
        let text =
            crate::input::read_capped_text(path, crate::input::MAX_SUMMARY_BYTES).map_err(|e| {
                let why = match e.kind() {
                    std::io::ErrorKind::FileTooLarge => {
                        "not the output of `wrinkle buckle --json` or a run's summary.json"
                    }
                    _ => "cannot read the file",
                };
                fail("", format!("{why}: {e}"))
            })?;
        let value: Value = serde_json::from_str(&text).map_err(|e| {
            fail(
                "",
                format!("not JSON ({e}): expected the output of `wrinkle buckle --json` or a run's summary.json"),
            )
        })?;
        let recorded = value.get("scene").filter(|s| s.is_object()).ok_or_else(|| {
            fail(
                "",
                "no `scene` object: expected the output of `wrinkle buckle --json` or a run's summary.json".into(),
            )
        })?;
        let recorded = &with_defaults_of_later_keys(recorded);
        let current = scene.echo_json();
        for section in THRESHOLD_SECTIONS {
            if let Some((key, was, now)) =
                first_difference(section, &recorded[section], &current[section])
            {
                return Err(fail(
                    &key,
                    format!(
                        "the threshold in this file was computed for `{key}` = {was}; this scene has {now}"
                    ),
                ));
            }
        }
        if scene.model.wavenumber != Wavenumber::Auto {
            return Err(fail(
                "model.wavenumber",
                "a threshold is reused to skip the wavenumber search, and this scene fixes the wavenumber: run without `--threshold`".into(),
            ));
        }
        let threshold = value.get("threshold").unwrap_or(&value);
        let number = |key: &str| {
            threshold
                .get(key)
                .and_then(Value::as_f64)
                .filter(|v| v.is_finite() && *v > 0.0)
        };
        let wavenumber = number("wavenumber").ok_or_else(|| {
            fail(
                "",
                format!(
                    "no positive `wavenumber` in the file: model `{}` has no wavenumber search to skip",
                    scene.model.name
                ),
            )
        })?;
        let critical_load = number("critical_load")
            .ok_or_else(|| fail("", "no positive `critical_load` in the file".into()))?;
        let direction_degrees = match scene.model.direction {
            Direction::Fixed(_) => None,
            Direction::Auto => Some(
                threshold
                    .get("direction")
                    .and_then(Value::as_f64)
                    .filter(|d| d.is_finite())
                    .ok_or_else(|| fail("", "no `direction` in the file".into()))?,
            ),
        };
        Ok(PriorThreshold {
            file,
            wavenumber,
            critical_load,
            direction_degrees,
        })
    }
}

/// The echoed scene `recorded` with the keys added since it was written set to the values the
/// threshold was computed with: `model.wavenumber_model` = [`REFERENCE_MODEL`].
fn with_defaults_of_later_keys(recorded: &Value) -> Value {
    let mut recorded = recorded.clone();
    if let Some(model) = recorded.get_mut("model").and_then(Value::as_object_mut) {
        model
            .entry("wavenumber_model")
            .or_insert_with(|| Value::from(REFERENCE_MODEL));
    }
    recorded
}

/// The first key (dotted, under `prefix`) where `recorded` and `current` differ, with both
/// values as text (`missing` for an absent key).
fn first_difference(
    prefix: &str,
    recorded: &Value,
    current: &Value,
) -> Option<(String, String, String)> {
    match (recorded, current) {
        (Value::Object(a), Value::Object(b)) => {
            let mut keys: Vec<&String> = a.keys().chain(b.keys()).collect();
            keys.sort();
            keys.dedup();
            keys.into_iter().find_map(|key| {
                first_difference(
                    &format!("{prefix}.{key}"),
                    a.get(key).unwrap_or(&Value::Null),
                    b.get(key).unwrap_or(&Value::Null),
                )
            })
        }
        (a, b) if a == b => None,
        (a, b) => {
            let text = |v: &Value| match v {
                Value::Null => "missing".to_string(),
                other => other.to_string(),
            };
            Some((prefix.to_string(), text(a), text(b)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn first_difference_names_the_nested_key_and_both_values() {
        let a = json!({"nx": 32, "ny": 16, "grading": 1.0});
        let b = json!({"nx": 40, "ny": 16, "grading": 1.0});
        assert_eq!(
            first_difference("mesh", &a, &b),
            Some(("mesh.nx".into(), "32".into(), "40".into()))
        );
        assert_eq!(first_difference("mesh", &a, &a), None);
        let c = json!({"parameters": {"k": 1.0}});
        let d = json!({"parameters": {}});
        assert_eq!(
            first_difference("model", &c, &d),
            Some(("model.parameters.k".into(), "1.0".into(), "missing".into()))
        );
    }
}
