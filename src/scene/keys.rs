//! The schema's machinery, whatever record it describes: a key's declaration ([`KeySpec`]) bound
//! to its field by accessors, older spellings of keys ([`Alias`]), and a [`Schema`] that sets a
//! dotted key from a TOML value, checks every key, and suggests the closest key for a typo.
//!
//! The declarations themselves are in `schema.rs`; this module does not know the scene.

use super::kinds::{Problem, ValueKind, Written};
use toml::Value;

/// A key's unit: the `unit` column of `docs/scenes.md`, and the comment after the key in the
/// effective-scene TOML (none when empty).
#[derive(Clone, Copy, Debug)]
pub struct Unit {
    /// As the documentation writes it.
    pub name: &'static str,
    /// The comment after the value in the effective scene (`# mm`); empty for none.
    pub comment: &'static str,
}

impl Unit {
    /// No unit (a ratio, a count, a name, a switch).
    pub const NONE: Unit = Unit {
        name: "–",
        comment: "",
    };
    /// Millimetres.
    pub const MM: Unit = Unit {
        name: "mm",
        comment: "mm",
    };
    /// Megapascals (N/mm²).
    pub const MPA: Unit = Unit {
        name: "MPa",
        comment: "MPa",
    };
    /// A force per length, N/mm (stress resultants).
    pub const N_PER_MM: Unit = Unit {
        name: "N/mm",
        comment: "N/mm",
    };
    /// A wavenumber, 1/mm.
    pub const PER_MM: Unit = Unit {
        name: "1/mm",
        comment: "1/mm",
    };
    /// An angle measured from the X axis.
    pub const DEGREES_FROM_X: Unit = Unit {
        name: "degrees",
        comment: "degrees from X",
    };
    /// The unit of the load parameter $`\lambda`$ (N/mm for the biaxial load, mm for the strip).
    pub const LOAD: Unit = Unit {
        name: "as λ",
        comment: "",
    };
}

/// A problem with one dotted key, before it is attributed to where the input came from.
#[derive(Debug)]
pub struct KeyError {
    /// The dotted key, e.g. `material.poisson` or `model.parameters.delta`.
    pub key: String,
    /// What is wrong.
    pub message: String,
}

impl KeyError {
    /// A problem with `key`.
    pub fn new(key: &str, message: impl Into<String>) -> Self {
        KeyError {
            key: key.to_string(),
            message: message.into(),
        }
    }
}

/// What the schema does with the field of a record `R` that a key is bound to.
pub trait Binding<R>: Sync {
    /// Sets the field from a TOML value (a table merges its entries).
    fn assign(&self, record: &mut R, value: &Value) -> Result<(), Problem>;
    /// Whether the field is a table whose entries are set as `key.NAME`.
    fn has_entries(&self) -> bool;
    /// Sets the entry `name` of a table field.
    fn assign_entry(&self, record: &mut R, name: &str, value: &Value) -> Result<(), Problem>;
    /// Checks the field's bounds.
    fn check(&self, record: &R) -> Result<(), Problem>;
    /// The field as the effective-scene TOML writes it.
    fn write(&self, record: &R) -> Written;
    /// The field in the JSON echo.
    fn json(&self, record: &R) -> serde_json::Value;
    /// The accepted values, for the documentation.
    fn range(&self) -> String;
}

/// A key of kind `K` bound to a field of `R` by two accessors; the compiler checks that the
/// field has the kind's type.
pub struct Field<R, K: ValueKind> {
    /// How the value is read, checked, written and documented.
    pub kind: K,
    /// The field.
    pub get: fn(&R) -> &K::Value,
    /// The field, to set it.
    pub get_mut: fn(&mut R) -> &mut K::Value,
}

impl<R, K: ValueKind> Binding<R> for Field<R, K> {
    fn assign(&self, record: &mut R, value: &Value) -> Result<(), Problem> {
        self.kind.assign((self.get_mut)(record), value)
    }

    fn has_entries(&self) -> bool {
        self.kind.has_entries()
    }

    fn assign_entry(&self, record: &mut R, name: &str, value: &Value) -> Result<(), Problem> {
        self.kind.assign_entry((self.get_mut)(record), name, value)
    }

    fn check(&self, record: &R) -> Result<(), Problem> {
        self.kind.check((self.get)(record))
    }

    fn write(&self, record: &R) -> Written {
        self.kind.write((self.get)(record))
    }

    fn json(&self, record: &R) -> serde_json::Value {
        self.kind.json((self.get)(record))
    }

    fn range(&self) -> String {
        self.kind.range()
    }
}

/// The declaration of one key: where it lives, what it means, and its binding to a field.
pub struct KeySpec<R: 'static> {
    /// The table it belongs to, e.g. `material`.
    pub section: &'static str,
    /// Its name in that table, e.g. `poisson`.
    pub name: &'static str,
    /// The dotted key, e.g. `material.poisson`.
    pub key: &'static str,
    /// Its unit.
    pub unit: Unit,
    /// What it means (Markdown, one line per line of its doc comment).
    pub meaning: &'static str,
    /// Constraints involving other keys, appended to the documented range (empty for none).
    pub note: &'static str,
    /// The field it sets, with its kind.
    pub binding: &'static dyn Binding<R>,
}

impl<R> KeySpec<R> {
    /// The [`KeyError`] of a problem found under this key (the entry of a table appended).
    fn error(&self, problem: Problem) -> KeyError {
        if problem.entry.is_empty() {
            KeyError::new(self.key, problem.message)
        } else {
            KeyError::new(&format!("{}.{}", self.key, problem.entry), problem.message)
        }
    }
}

/// One key a value set: the declared key or table entry it set (`target`), and how the input
/// spelled it (`spelling`: the key itself, or an older alias such as
/// `solver.max_envelope_over_h` for `solver.max_amplitude_over_h`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Assigned {
    /// The dotted key set, e.g. `material.young` or `model.parameters.delta`.
    pub target: String,
    /// The dotted key as written.
    pub spelling: String,
}

/// How and where a key was given ([`Scene::given`](crate::scene::Scene::given)).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Given {
    /// The dotted key as written (the key itself or an older alias).
    pub spelling: String,
    /// Where: `scene PATH` or `--set KEY=VALUE`.
    pub origin: String,
}

/// An older spelling of a key, still read: it converts its value and sets `target`.
pub struct Alias {
    /// The older dotted key, e.g. `solver.max_envelope_over_h`.
    pub key: &'static str,
    /// The key it sets.
    pub target: &'static str,
    /// What it means (Markdown).
    pub meaning: &'static str,
    /// Its value to the value of `target`.
    pub convert: fn(&Value) -> Result<Value, String>,
}

/// Every key of a record `R`: its tables in order, its keys, and its aliases.
pub struct Schema<R: 'static> {
    /// The tables, in document order.
    pub sections: &'static [&'static str],
    /// The keys, in document order.
    pub keys: &'static [KeySpec<R>],
    /// Older spellings still read.
    pub aliases: &'static [Alias],
}

impl<R> Schema<R> {
    /// The declaration of `key`.
    pub fn spec(&self, key: &str) -> Option<&'static KeySpec<R>> {
        self.keys.iter().find(|spec| spec.key == key)
    }

    /// The keys of `section`, in document order.
    pub fn keys_of<'a>(&self, section: &'a str) -> impl Iterator<Item = &'static KeySpec<R>> + 'a {
        self.keys.iter().filter(move |spec| spec.section == section)
    }

    /// Applies every entry of `table`, whose keys are relative to `prefix` (empty at the root);
    /// each key set is appended to `assigned`.
    pub fn apply_table(
        &self,
        record: &mut R,
        prefix: &str,
        table: &toml::Table,
        assigned: &mut Vec<Assigned>,
    ) -> Result<(), KeyError> {
        for (name, value) in table {
            let key = if prefix.is_empty() {
                name.clone()
            } else {
                format!("{prefix}.{name}")
            };
            self.apply(record, &key, value, assigned)?;
        }
        Ok(())
    }

    /// Sets one dotted key — a table, a key, an alias or an entry of a table — and checks the
    /// bounds of what it set. Every key set is appended to `assigned` (a table sets each of its
    /// entries, one by one, so that an entry that is an alias — `model.parameters.young` — sets
    /// its target).
    pub fn apply(
        &self,
        record: &mut R,
        key: &str,
        value: &Value,
        assigned: &mut Vec<Assigned>,
    ) -> Result<(), KeyError> {
        let spec = self.spec(key);
        let entries_of = spec.filter(|spec| spec.binding.has_entries());
        if self.sections.contains(&key) || entries_of.is_some() {
            return match value {
                Value::Table(table) => self.apply_table(record, key, table, assigned),
                other => Err(KeyError::new(
                    key,
                    format!("expected a table, got {}", super::text::describe(other)),
                )),
            };
        }
        let assign = |target: &str| Assigned {
            target: target.to_string(),
            spelling: key.to_string(),
        };
        if let Some(spec) = spec {
            let binding = spec.binding;
            binding.assign(record, value).map_err(|p| spec.error(p))?;
            binding.check(record).map_err(|p| spec.error(p))?;
            assigned.push(assign(spec.key));
            return Ok(());
        }
        if let Some(alias) = self.aliases.iter().find(|alias| alias.key == key) {
            self.apply_alias(record, alias, value)?;
            assigned.push(assign(alias.target));
            return Ok(());
        }
        let entry = self.keys.iter().find_map(|spec| {
            let name = key.strip_prefix(spec.key)?.strip_prefix('.')?;
            spec.binding.has_entries().then_some((spec, name))
        });
        if let Some((spec, name)) = entry {
            let binding = spec.binding;
            binding
                .assign_entry(record, name, value)
                .map_err(|p| spec.error(p))?;
            binding.check(record).map_err(|p| spec.error(p))?;
            assigned.push(assign(key));
            return Ok(());
        }
        Err(KeyError::new(key, self.unknown_key_message(key)))
    }

    /// Sets the target of `alias`; problems are reported under the alias' key.
    fn apply_alias(&self, record: &mut R, alias: &Alias, value: &Value) -> Result<(), KeyError> {
        let error = |message: String| KeyError::new(alias.key, message);
        let target = self
            .spec(alias.target)
            .ok_or_else(|| error(format!("alias of the unknown key `{}`", alias.target)))?;
        let converted = (alias.convert)(value).map_err(error)?;
        let as_target =
            |problem: Problem| error(format!("as `{}`: {}", target.key, problem.message));
        let binding = target.binding;
        binding.assign(record, &converted).map_err(as_target)?;
        binding.check(record).map_err(as_target)
    }

    /// Checks the bounds of every key, in document order.
    pub fn check(&self, record: &R) -> Result<(), KeyError> {
        self.keys
            .iter()
            .try_for_each(|spec| spec.binding.check(record).map_err(|p| spec.error(p)))
    }

    /// Message for an unknown key, with the closest valid key when one is near.
    pub fn unknown_key_message(&self, key: &str) -> String {
        let keys = self.keys.iter().map(|spec| spec.key);
        let candidates = keys.chain(self.sections.iter().copied());
        let best = candidates
            .map(|candidate| (edit_distance(key, candidate), candidate))
            .min_by_key(|(distance, _)| *distance);
        match best {
            Some((distance, candidate)) if distance <= (key.len() / 3).max(2) => {
                format!("unknown key; did you mean `{candidate}`?")
            }
            _ => {
                let section = key.split('.').next().unwrap_or(key);
                if self.sections.contains(&section) {
                    let names: Vec<&str> = self.keys_of(section).map(|spec| spec.name).collect();
                    format!("unknown key; `[{section}]` accepts {}", names.join(", "))
                } else {
                    format!("unknown key; the tables are {}", self.sections.join(", "))
                }
            }
        }
    }
}

/// Levenshtein distance between two strings (in characters).
fn edit_distance(first: &str, second: &str) -> usize {
    let second: Vec<char> = second.chars().collect();
    let mut previous: Vec<usize> = (0..=second.len()).collect();
    for (row, first_character) in first.chars().enumerate() {
        let mut current = vec![row + 1; second.len() + 1];
        for (column, second_character) in second.iter().enumerate() {
            let substitution = previous[column] + usize::from(first_character != *second_character);
            current[column + 1] = substitution
                .min(previous[column + 1] + 1)
                .min(current[column] + 1);
        }
        previous = current;
    }
    previous[second.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn edit_distance_counts_single_edits() {
        assert_eq!(edit_distance("poison", "poisson"), 1);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
    }
}
