//! Python values, as JSON from the Python layer, into TOML: a scene given as a `dict` becomes
//! TOML text that the scene parser reads as if from a file (same keys, same errors), and a
//! value of a grid or an override becomes the `VALUE` of `KEY=VALUE`.

use serde_json::Value as Json;
use toml::Value as Toml;

/// A JSON value as a TOML value; `key` (dotted) names it in errors. `null` has no TOML form.
pub fn toml_value(json: &Json, key: &str) -> Result<Toml, String> {
    Ok(match json {
        Json::Null => return Err(format!("key `{key}`: None has no TOML value")),
        Json::Bool(flag) => Toml::Boolean(*flag),
        Json::Number(number) => match number.as_i64() {
            Some(integer) => Toml::Integer(integer),
            None => Toml::Float(number.as_f64().unwrap_or(f64::NAN)),
        },
        Json::String(text) => Toml::String(text.clone()),
        Json::Array(items) => Toml::Array(
            items
                .iter()
                .enumerate()
                .map(|(i, item)| toml_value(item, &format!("{key}[{i}]")))
                .collect::<Result<_, _>>()?,
        ),
        Json::Object(entries) => Toml::Table(toml_table(entries, key)?),
    })
}

/// A JSON object as a TOML table; a dotted entry (`"load.tension_y": 5`) is nested
/// (`[load] tension_y = 5`). `prefix` is the dotted key of the object itself (`""` at the top).
pub fn toml_table(
    entries: &serde_json::Map<String, Json>,
    prefix: &str,
) -> Result<toml::Table, String> {
    let mut table = toml::Table::new();
    for (name, value) in entries {
        let key = if prefix.is_empty() {
            name.clone()
        } else {
            format!("{prefix}.{name}")
        };
        let parts: Vec<&str> = name.split('.').collect();
        if parts.iter().any(|part| part.is_empty()) {
            return Err(format!("key `{key}`: an empty part in a dotted key"));
        }
        let mut target = &mut table;
        for part in &parts[..parts.len() - 1] {
            let entry = target
                .entry(part.to_string())
                .or_insert_with(|| Toml::Table(toml::Table::new()));
            target = match entry {
                Toml::Table(inner) => inner,
                _ => return Err(format!("key `{key}`: `{part}` is already a value")),
            };
        }
        let value = toml_value(value, &key)?;
        merge(target, parts[parts.len() - 1], value, &key)?;
    }
    Ok(table)
}

/// Inserts `value` under `name`, merging tables given twice (`{"load": {...}, "load.kind": ..}`);
/// a value given twice is an error naming `key`.
fn merge(table: &mut toml::Table, name: &str, value: Toml, key: &str) -> Result<(), String> {
    match (table.get_mut(name), value) {
        (None, value) => {
            table.insert(name.to_string(), value);
            Ok(())
        }
        (Some(Toml::Table(existing)), Toml::Table(more)) => {
            for (inner, value) in more {
                merge(existing, &inner, value, &format!("{key}.{inner}"))?;
            }
            Ok(())
        }
        (Some(_), _) => Err(format!("key `{key}` is given twice")),
    }
}

/// The TOML text of a scene given as a JSON object.
pub fn scene_text(json: &str) -> Result<String, String> {
    let value: Json = serde_json::from_str(json).map_err(|e| e.to_string())?;
    let Json::Object(entries) = value else {
        return Err("a scene dict must be a mapping of keys to values".into());
    };
    let table = toml_table(&entries, "")?;
    toml::to_string(&table).map_err(|e| e.to_string())
}

/// The TOML text of one value (the `VALUE` of `KEY=VALUE`).
pub fn value_text(json: &str, key: &str) -> Result<String, String> {
    let value: Json = serde_json::from_str(json).map_err(|e| e.to_string())?;
    Ok(toml_value(&value, key)?.to_string())
}
