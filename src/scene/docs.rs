//! The key tables of `docs/scenes.md`, generated from the schema.
//!
//! Each table sits between the marker comments `<!-- keys SECTION -->` and `<!-- /keys -->`;
//! the prose around them is written by hand. `tests/scene_docs.rs` fails when a table differs
//! from the schema and, with `WRINKLE_BLESS=1`, rewrites the tables in place.

use super::keys::{Alias, KeySpec};
use super::kinds::Written;
use super::schema::{SCHEMA, Scene};

/// The first line of a generated table: `<!-- keys SECTION -->`.
const OPENING: (&str, &str) = ("<!-- keys ", " -->");
/// The line after a generated table.
const CLOSING: &str = "<!-- /keys -->";

/// The Markdown table of the keys of `section` (`geometry`, …): key, meaning, unit, default
/// and accepted values, then the older spellings still read.
pub fn key_table(section: &str) -> String {
    let defaults = Scene::default();
    let mut table = String::from(
        "| key | meaning | unit | default | range |\n|-----|---------|------|---------|-------|\n",
    );
    for spec in SCHEMA.keys_of(section) {
        table.push_str(&key_row(spec, &defaults));
    }
    let prefix = format!("{section}.");
    for alias in SCHEMA.aliases {
        if let Some(name) = alias.key.strip_prefix(&prefix) {
            table.push_str(&alias_row(name, alias));
        }
    }
    table
}

fn key_row(spec: &KeySpec<Scene>, defaults: &Scene) -> String {
    let default = match spec.binding.write(defaults) {
        Written::Inline { text, .. } => format!("`{text}`"),
        Written::Table(entries) => {
            let entries: Vec<String> = entries.iter().map(|(k, v)| format!("{k} = {v}")).collect();
            format!("`{{{}}}`", entries.join(", "))
        }
    };
    let mut range = spec.binding.range();
    if !spec.note.is_empty() {
        range = format!("{range}, {}", spec.note);
    }
    format!(
        "| `{}` | {} | {} | {default} | {} |\n",
        spec.name,
        cell(spec.meaning),
        spec.unit.name,
        cell(&range)
    )
}

fn alias_row(name: &str, alias: &Alias) -> String {
    let target = SCHEMA.spec(alias.target).map_or("–", |spec| spec.unit.name);
    let (target_section, target_name) = alias.target.split_once('.').unwrap_or(("", alias.target));
    let same_section =
        alias.key.split_once('.').map(|(section, _)| section) == Some(target_section);
    let target_name = if same_section {
        target_name
    } else {
        alias.target
    };
    format!(
        "| `{name}` | {} | {target} | – | see `{target_name}` |\n",
        cell(alias.meaning)
    )
}

/// Text as one table cell: its lines joined, `|` escaped (a `\|` already escaped stays).
fn cell(text: &str) -> String {
    let joined = text
        .lines()
        .map(str::trim)
        .filter(|line| !line.is_empty())
        .collect::<Vec<_>>()
        .join(" ");
    let mut escaped = String::with_capacity(joined.len());
    let mut previous = ' ';
    for character in joined.chars() {
        if character == '|' && previous != '\\' {
            escaped.push('\\');
        }
        escaped.push(character);
        previous = character;
    }
    escaped
}

/// `document` with every generated key table replaced by the schema's. Errors: a marker naming
/// no table of the scene, a table without its closing marker, a table of the scene without a
/// marker.
pub fn refresh_key_tables(document: &str) -> Result<String, String> {
    let mut refreshed = String::with_capacity(document.len());
    let mut lines = document.lines();
    let mut seen = Vec::new();
    while let Some(line) = lines.next() {
        refreshed.push_str(line);
        refreshed.push('\n');
        let Some(section) = marked_section(line) else {
            continue;
        };
        if !SCHEMA.sections.contains(&section) {
            return Err(format!("`{line}`: the scene has no table `[{section}]`"));
        }
        if !lines.any(|inner| inner.trim() == CLOSING) {
            return Err(format!("`{line}` is not closed by `{CLOSING}`"));
        }
        refreshed.push_str(&key_table(section));
        refreshed.push_str(CLOSING);
        refreshed.push('\n');
        seen.push(section);
    }
    match SCHEMA
        .sections
        .iter()
        .find(|section| !seen.contains(section))
    {
        Some(missing) => Err(format!(
            "no `{}{missing}{}` marker for the keys of `[{missing}]`",
            OPENING.0, OPENING.1
        )),
        None => Ok(refreshed),
    }
}

/// The section a marker line opens.
fn marked_section(line: &str) -> Option<&str> {
    let inner = line
        .trim()
        .strip_prefix(OPENING.0)?
        .strip_suffix(OPENING.1)?;
    Some(inner.trim())
}
