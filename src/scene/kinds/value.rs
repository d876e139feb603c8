//! The two traits of a kind of value — [`ValueKind`] for any key, [`Scalar`] for a key holding
//! one value — and the messages every kind shares.

use crate::scene::text::{describe, toml_string};
use toml::Value;

/// A problem with a value. `entry` is the part of the dotted key below the declared key (a name
/// inside a table such as `model.parameters`), empty for the key itself.
#[derive(Debug)]
pub struct Problem {
    /// Name of the offending entry of a table, empty for the value itself.
    pub entry: String,
    /// What is wrong, e.g. `must be > 0, got -1`.
    pub message: String,
}

impl Problem {
    pub(super) fn here(message: String) -> Self {
        Problem {
            entry: String::new(),
            message,
        }
    }

    pub(super) fn at(entry: &str, message: String) -> Self {
        Problem {
            entry: entry.to_string(),
            message,
        }
    }
}

/// A value as the effective scene writes it.
pub enum Written {
    /// `key = text`, followed by the key's unit as a comment when `unit` is true.
    Inline {
        /// The TOML text of the value.
        text: String,
        /// Whether the key's unit applies to this value (not to `"auto"`).
        unit: bool,
    },
    /// A sub-table `[section.key]` of `name = text` entries, written after the section's inline
    /// keys and omitted when empty.
    Table(Vec<(String, String)>),
}

/// A kind of value a key holds, with everything the schema does with it.
pub trait ValueKind: Sync {
    /// The Rust type of the value.
    type Value;
    /// Reads `value` into `target`: type check and conversion (bounds are [`ValueKind::check`]'s).
    /// A table merges the entries given into `target`.
    fn assign(&self, target: &mut Self::Value, value: &Value) -> Result<(), Problem>;
    /// Whether the value is a table of named entries, each settable as `key.NAME`.
    fn has_entries(&self) -> bool {
        false
    }
    /// Sets the entry `name` of a table (`key.NAME = value`).
    fn assign_entry(
        &self,
        _target: &mut Self::Value,
        name: &str,
        _value: &Value,
    ) -> Result<(), Problem> {
        Err(Problem::at(name, "not a table".to_string()))
    }
    /// Checks the bounds.
    fn check(&self, value: &Self::Value) -> Result<(), Problem>;
    /// The value as the effective-scene TOML writes it.
    fn write(&self, value: &Self::Value) -> Written;
    /// The value in the JSON echo of the scene.
    fn json(&self, value: &Self::Value) -> serde_json::Value;
    /// The accepted values as `docs/scenes.md` states them (Markdown).
    fn range(&self) -> String;
}

/// A kind holding one value (not a table).
pub trait Scalar: Sync {
    /// The Rust type of the value.
    type Value;
    /// Type check and conversion of a TOML value.
    fn read(&self, value: &Value) -> Result<Self::Value, String>;
    /// Checks the bounds.
    fn within_bounds(&self, value: &Self::Value) -> Result<(), String>;
    /// The TOML text of a value.
    fn text(&self, value: &Self::Value) -> String;
    /// Whether the key's unit applies to this value.
    fn unit_applies(&self, _value: &Self::Value) -> bool {
        true
    }
    /// The value in JSON.
    fn json_value(&self, value: &Self::Value) -> serde_json::Value;
    /// The accepted values, for the documentation (Markdown).
    fn bounds_text(&self) -> String;
}

impl<S: Scalar> ValueKind for S {
    type Value = S::Value;

    fn assign(&self, target: &mut S::Value, value: &Value) -> Result<(), Problem> {
        *target = self.read(value).map_err(Problem::here)?;
        Ok(())
    }

    fn check(&self, value: &S::Value) -> Result<(), Problem> {
        self.within_bounds(value).map_err(Problem::here)
    }

    fn write(&self, value: &S::Value) -> Written {
        Written::Inline {
            text: self.text(value),
            unit: self.unit_applies(value),
        }
    }

    fn json(&self, value: &S::Value) -> serde_json::Value {
        self.json_value(value)
    }

    fn range(&self) -> String {
        self.bounds_text()
    }
}

/// `expected one of "a", "b", got …`, or the choice `value` names.
pub(super) fn pick<'a, T: Copy>(value: &Value, choices: &'a [(&'a str, T)]) -> Result<T, String> {
    let quoted: Vec<String> = choices
        .iter()
        .map(|(spelling, _)| format!("\"{spelling}\""))
        .collect();
    let got = match value {
        Value::String(text) => match choices.iter().find(|(spelling, _)| spelling == text) {
            Some((_, choice)) => return Ok(*choice),
            None => toml_string(text),
        },
        other => describe(other),
    };
    Err(format!("expected one of {}, got {got}", quoted.join(", ")))
}

/// The spellings as Markdown code, comma-separated: `` `"a"`, `"b"` ``.
pub(super) fn quoted_list<'a>(spellings: impl Iterator<Item = &'a str>) -> String {
    let quoted: Vec<String> = spellings.map(|name| format!("`\"{name}\"`")).collect();
    quoted.join(", ")
}

/// `item N: message` for the item at `index` of an array.
pub(super) fn item_message(index: usize, message: String) -> String {
    format!("item {index}: {message}")
}
