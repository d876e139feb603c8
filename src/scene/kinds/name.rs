//! Names and switches: a flag, a string, a registered model, one of an enumeration's spellings.

use super::value::{Scalar, pick, quoted_list};
use crate::scene::text::{describe, toml_string};
use std::marker::PhantomData;
use toml::Value;

/// `true` or `false`.
#[derive(Clone, Copy, Debug)]
pub struct Flag;

impl Scalar for Flag {
    type Value = bool;

    fn read(&self, value: &Value) -> Result<bool, String> {
        match value {
            Value::Boolean(flag) => Ok(*flag),
            other => Err(format!(
                "expected a boolean (true or false), got {}",
                describe(other)
            )),
        }
    }

    fn within_bounds(&self, _value: &bool) -> Result<(), String> {
        Ok(())
    }

    fn text(&self, value: &bool) -> String {
        value.to_string()
    }

    fn json_value(&self, value: &bool) -> serde_json::Value {
        serde_json::Value::from(*value)
    }

    fn bounds_text(&self) -> String {
        "boolean".to_string()
    }
}

/// A string, not blank.
#[derive(Clone, Copy, Debug)]
pub struct Text;

fn read_string(value: &Value) -> Result<String, String> {
    match value {
        Value::String(text) => Ok(text.clone()),
        other => Err(format!("expected a string, got {}", describe(other))),
    }
}

impl Scalar for Text {
    type Value = String;

    fn read(&self, value: &Value) -> Result<String, String> {
        read_string(value)
    }

    fn within_bounds(&self, value: &String) -> Result<(), String> {
        if value.trim().is_empty() {
            Err("must not be empty".to_string())
        } else if value.contains('\0') {
            Err("must not contain a NUL character".to_string())
        } else {
            Ok(())
        }
    }

    fn text(&self, value: &String) -> String {
        toml_string(value)
    }

    fn json_value(&self, value: &String) -> serde_json::Value {
        serde_json::Value::from(value.as_str())
    }

    fn bounds_text(&self) -> String {
        "non-empty, no NUL character".to_string()
    }
}

/// The name of a registered model (`wrinkle_models::names()`).
#[derive(Clone, Copy, Debug)]
pub struct ModelName;

impl Scalar for ModelName {
    type Value = String;

    fn read(&self, value: &Value) -> Result<String, String> {
        read_string(value)
    }

    fn within_bounds(&self, value: &String) -> Result<(), String> {
        let names = wrinkle_models::names();
        if value.trim().is_empty() {
            Err("must not be empty".to_string())
        } else if names.contains(&value.as_str()) {
            Ok(())
        } else {
            Err(format!(
                "unknown model `{value}` (models: {})",
                names.join(", ")
            ))
        }
    }

    fn text(&self, value: &String) -> String {
        toml_string(value)
    }

    fn json_value(&self, value: &String) -> serde_json::Value {
        serde_json::Value::from(value.as_str())
    }

    fn bounds_text(&self) -> String {
        let names: Vec<String> = wrinkle_models::names()
            .iter()
            .map(|name| format!("`{name}`"))
            .collect();
        format!("a registered model: {}", names.join(", "))
    }
}

/// An enumeration spelled as strings in a scene (declared with `scene_enum!`).
pub trait Choices: Copy + PartialEq + Sync + 'static {
    /// Every spelling with its value, in documentation order.
    const CHOICES: &'static [(&'static str, Self)];
}

/// One of the spellings of `E`.
pub struct Choice<E>(PhantomData<E>);

/// The kind of a key holding one of the values of `E`.
pub const fn one_of<E: Choices>() -> Choice<E> {
    Choice(PhantomData)
}

impl<E: Choices> Scalar for Choice<E> {
    type Value = E;

    fn read(&self, value: &Value) -> Result<E, String> {
        pick(value, E::CHOICES)
    }

    fn within_bounds(&self, _value: &E) -> Result<(), String> {
        Ok(())
    }

    fn text(&self, value: &E) -> String {
        toml_string(spelling(*value))
    }

    fn json_value(&self, value: &E) -> serde_json::Value {
        serde_json::Value::from(spelling(*value))
    }

    fn bounds_text(&self) -> String {
        quoted_list(E::CHOICES.iter().map(|(spelling, _)| *spelling))
    }
}

fn spelling<E: Choices>(value: E) -> &'static str {
    E::CHOICES
        .iter()
        .find(|(_, choice)| *choice == value)
        .map_or("", |(spelling, _)| spelling)
}
