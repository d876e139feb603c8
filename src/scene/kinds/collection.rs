//! Collections: an array of numbers, an array of names, a table of named values.

use super::number::Float;
use super::value::{Problem, Scalar, ValueKind, Written, item_message, pick, quoted_list};
use crate::scene::text::{describe, toml_float, toml_key, toml_string};
use std::collections::BTreeMap;
use toml::Value;

/// An array of numbers, each within the bounds of `item`.
#[derive(Clone, Copy, Debug)]
pub struct FloatList {
    item: Float,
}

impl FloatList {
    /// An array whose items are of kind `item`.
    pub const fn of(item: Float) -> Self {
        FloatList { item }
    }
}

impl Scalar for FloatList {
    type Value = Vec<f64>;

    fn read(&self, value: &Value) -> Result<Vec<f64>, String> {
        let Value::Array(items) = value else {
            return Err(format!(
                "expected an array of numbers, got {}",
                describe(value)
            ));
        };
        let read = |(index, item)| self.item.read(item).map_err(|m| item_message(index, m));
        items.iter().enumerate().map(read).collect()
    }

    fn within_bounds(&self, value: &Vec<f64>) -> Result<(), String> {
        value.iter().enumerate().try_for_each(|(index, item)| {
            self.item
                .within_bounds(item)
                .map_err(|m| item_message(index, m))
        })
    }

    fn text(&self, value: &Vec<f64>) -> String {
        let items: Vec<String> = value.iter().map(|item| toml_float(*item)).collect();
        format!("[{}]", items.join(", "))
    }

    fn json_value(&self, value: &Vec<f64>) -> serde_json::Value {
        serde_json::Value::from(value.clone())
    }

    fn bounds_text(&self) -> String {
        match self.item.condition() {
            condition if condition.is_empty() => "array of finite numbers".to_string(),
            condition => format!("array of numbers {condition}"),
        }
    }
}

/// An array of names, each one of `choices` or the `wildcard` (a single string is taken as a
/// one-item array).
#[derive(Clone, Copy, Debug)]
pub struct ChoiceList {
    choices: &'static [&'static str],
    wildcard: &'static str,
    noun: &'static str,
}

impl ChoiceList {
    /// Names from `choices` or `wildcard`; `noun` names them in messages (`check names`).
    pub const fn new(
        choices: &'static [&'static str],
        wildcard: &'static str,
        noun: &'static str,
    ) -> Self {
        ChoiceList {
            choices,
            wildcard,
            noun,
        }
    }

    fn spellings(&self) -> Vec<(&'static str, &'static str)> {
        let all = self.choices.iter().chain(std::iter::once(&self.wildcard));
        all.map(|name| (*name, *name)).collect()
    }
}

impl Scalar for ChoiceList {
    type Value = Vec<String>;

    fn read(&self, value: &Value) -> Result<Vec<String>, String> {
        let items: Vec<&Value> = match value {
            Value::Array(items) => items.iter().collect(),
            single @ Value::String(_) => vec![single],
            other => {
                let got = describe(other);
                return Err(format!("expected an array of {}, got {got}", self.noun));
            }
        };
        let spellings = self.spellings();
        let read = |(index, item)| {
            pick(item, &spellings)
                .map(str::to_string)
                .map_err(|message| item_message(index, message))
        };
        items.into_iter().enumerate().map(read).collect()
    }

    fn within_bounds(&self, value: &Vec<String>) -> Result<(), String> {
        let spellings = self.spellings();
        value.iter().enumerate().try_for_each(|(index, name)| {
            let item = Value::String(name.clone());
            pick(&item, &spellings)
                .map(|_| ())
                .map_err(|message| item_message(index, message))
        })
    }

    fn text(&self, value: &Vec<String>) -> String {
        let items: Vec<String> = value.iter().map(|name| toml_string(name)).collect();
        format!("[{}]", items.join(", "))
    }

    fn json_value(&self, value: &Vec<String>) -> serde_json::Value {
        serde_json::Value::from(value.clone())
    }

    fn bounds_text(&self) -> String {
        let spellings = self.spellings();
        format!(
            "array of {}",
            quoted_list(spellings.iter().map(|(name, _)| *name))
        )
    }
}

/// A table of free-form names, each holding a value of kind `item` (`model.parameters`).
pub struct Table<S> {
    item: S,
    noun: &'static str,
}

impl<S: Scalar> Table<S> {
    /// Entries of kind `item`; `noun` names them in messages (`model parameters`).
    pub const fn of(item: S, noun: &'static str) -> Self {
        Table { item, noun }
    }
}

impl<S: Scalar> ValueKind for Table<S> {
    type Value = BTreeMap<String, S::Value>;

    fn assign(&self, target: &mut Self::Value, value: &Value) -> Result<(), Problem> {
        let Value::Table(entries) = value else {
            return Err(Problem::here(format!(
                "expected a table, got {}",
                describe(value)
            )));
        };
        entries
            .iter()
            .try_for_each(|(name, value)| self.assign_entry(target, name, value))
    }

    fn has_entries(&self) -> bool {
        true
    }

    fn assign_entry(
        &self,
        target: &mut Self::Value,
        name: &str,
        value: &Value,
    ) -> Result<(), Problem> {
        if name.contains('.') {
            let message = format!("{} are plain names (no nested tables)", self.noun);
            return Err(Problem::at(name, message));
        }
        let item = self
            .item
            .read(value)
            .map_err(|message| Problem::at(name, message))?;
        target.insert(name.to_string(), item);
        Ok(())
    }

    fn check(&self, value: &Self::Value) -> Result<(), Problem> {
        value.iter().try_for_each(|(name, item)| {
            self.item
                .within_bounds(item)
                .map_err(|message| Problem::at(name, message))
        })
    }

    fn write(&self, value: &Self::Value) -> Written {
        let entries = value.iter();
        Written::Table(
            entries
                .map(|(name, item)| (toml_key(name), self.item.text(item)))
                .collect(),
        )
    }

    fn json(&self, value: &Self::Value) -> serde_json::Value {
        let entries = value.iter();
        serde_json::Value::Object(
            entries
                .map(|(name, item)| (name.clone(), self.item.json_value(item)))
                .collect(),
        )
    }

    fn range(&self) -> String {
        format!("`NAME = value`, each {}", self.item.bounds_text())
    }
}
