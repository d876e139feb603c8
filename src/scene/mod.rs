//! Scene files: what to compute, on which geometry, with which model, mesh, load and solver.
//!
//! A scene is a TOML document whose keys are all optional; missing keys take the values of the
//! paper's example 1 (THEORY.md §9), see [`Scene::default`]. Single keys can be overridden from
//! the command line with `--set KEY=VALUE` ([`Scene::apply_override`]). Parsing walks the TOML
//! table by hand so that every error names the dotted key and where the input came from:
//!
//! ```text
//! scene examples/scenes/x.toml: key `material.poisson`: must satisfy -0.99 ≤ ν < 0.5 (ν → −1 makes the in-plane problem singular), got 0.6
//! --set mesh.nx=0: key `mesh.nx`: must be an integer between 1 and 100000, got 0
//! ```
//!
//! Every key is declared once, in `schema.rs` (name, field, type, default, kind with bounds,
//! unit, meaning); the structs, defaults, parsing, validation, printing and the key tables of
//! `docs/scenes.md` all come from that declaration. The modules, each importing only the ones
//! before it: `text` (TOML text in and out), `kinds` (kinds of values: read, check, write,
//! document), `keys` (a key's declaration bound to its field; setting a dotted key),
//! `declare` (the macros), `schema` (the declarations), `docs` (the Markdown key tables); this
//! module reads files and overrides, validates, and prints the effective scene.

mod across;
mod declare;
mod docs;
mod keys;
mod kinds;
mod schema;
mod text;

pub use across::{
    MAX_TENSION_STRAIN, MAX_WAVELENGTH_OVER_SIDE, MIN_PERTURBATION, STIFFNESS_RANGE,
    THICKNESS_RATIO_RANGE,
};
pub use docs::{key_table, refresh_key_tables};
pub use keys::Given;
pub use kinds::{BoundarySpec, Component, InPlane, Transverse};
pub use schema::{
    AxisRatio, BUILT_IN_SOURCE, Direction, Domain, Geometry, Imperfection, KEYS, LENGTH_RANGE,
    LoadKind, LoadSpec, MAX_ELEMENT_ASPECT_RATIO, MAX_ELEMENTS, MAX_ELEMENTS_PER_SIDE,
    MAX_SERIES_TOLERANCE, MAX_STEPS, MAX_VTU_LOADS, Material, MeshSpec, ModelChoice, OutputSpec,
    PathMethod, REFINE_TARGETS, SECTIONS, Scene, SolverSpec, VALIDITY_CHECKS, ValiditySpec,
    Wavenumber,
};

use crate::closed_form::ClampedRectangle;
use crate::error::Error;
use across::check_across_keys;
use keys::KeyError;
use kinds::Written;
use schema::SCHEMA;
use std::fmt::Write as _;
use std::path::Path;
use text::{parse_override_value, syntax_message, toml_string};

/// Largest scene file read (a scene is a few hundred bytes; this stops `/dev/zero`).
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

impl Scene {
    /// Parses a scene from TOML text. `source_name` (usually the file path) is stored in
    /// [`Scene::source`] and quoted in errors. The result is validated.
    pub fn from_toml_str(text: &str, source_name: &str) -> Result<Scene, Error> {
        let origin = format!("scene {source_name}");
        let table: toml::Table = text.parse().map_err(|error: toml::de::Error| {
            Error::scene(&origin, "", syntax_message(text, &error))
        })?;
        let mut scene = Scene {
            source: source_name.to_string(),
            ..Scene::default()
        };
        let mut assigned = Vec::new();
        SCHEMA
            .apply_table(&mut scene, "", &table, &mut assigned)
            .map_err(|error| Error::scene(&origin, error.key, error.message))?;
        scene.record_given(assigned, &origin)?;
        scene.validate()?;
        Ok(scene)
    }

    /// Reads and parses a scene file.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene, Error> {
        let path = path.as_ref();
        let name = path.display().to_string();
        let cannot = |error: std::io::Error| {
            Error::scene(
                format!("scene {name}"),
                "",
                format!("cannot read file: {error}"),
            )
        };
        let text = crate::input::read_capped_text(path, MAX_SCENE_BYTES).map_err(|error| {
            match error.kind() {
                std::io::ErrorKind::FileTooLarge => Error::scene(
                    format!("scene {name}"),
                    "",
                    format!("{error}: not a scene file"),
                ),
                std::io::ErrorKind::InvalidData => {
                    Error::scene(format!("scene {name}"), "", error.to_string())
                }
                _ => cannot(error),
            }
        })?;
        Scene::from_toml_str(&text, &name)
    }

    /// Applies one `KEY=VALUE` override. The value is parsed as a TOML value (`0.6`, `"auto"`,
    /// `true`, `[1, 2]`, `{ q = 1.0 }`); a bare word such as `auto` or `strip` is taken as a
    /// string. Errors are attributed to `--set KEY=VALUE`.
    pub fn apply_override(&mut self, assignment: &str) -> Result<(), Error> {
        let origin = format!("--set {assignment}");
        let Some((key, text)) = assignment.split_once('=') else {
            return Err(Error::scene(origin, "", "expected KEY=VALUE"));
        };
        let key = key.trim();
        let text = text.trim();
        if key.is_empty() || key.split('.').any(str::is_empty) {
            return Err(Error::scene(
                origin,
                "",
                "expected KEY=VALUE with a dotted key such as material.poisson",
            ));
        }
        let value =
            parse_override_value(text).map_err(|message| Error::scene(&origin, key, message))?;
        // Apply to a copy so that a rejected override leaves the scene unchanged.
        let mut updated = self.clone();
        let mut assigned = Vec::new();
        SCHEMA
            .apply(&mut updated, key, &value, &mut assigned)
            .map_err(|error| Error::scene(&origin, error.key, error.message))?;
        updated.record_given(assigned, &origin)?;
        updated.overridden.insert(key.to_string(), origin);
        *self = updated;
        Ok(())
    }

    /// Records the keys a file or an override set ([`Scene::given`]); a key given before
    /// under another spelling (a key and its alias, in one file or across a file and `--set`) is
    /// an error naming both: the two would silently set one value.
    fn record_given(&mut self, assigned: Vec<keys::Assigned>, origin: &str) -> Result<(), Error> {
        for keys::Assigned { target, spelling } in assigned {
            if let Some(before) = self.given.get(&target)
                && before.spelling != spelling
            {
                return Err(Error::scene(
                    origin,
                    &spelling,
                    format!(
                        "sets `{target}`, which `{}` ({}) sets too: give one of the two",
                        before.spelling, before.origin
                    ),
                ));
            }
            let origin = origin.to_string();
            self.given.insert(target, Given { spelling, origin });
        }
        Ok(())
    }

    /// Whether `key` was given by the scene file or `--set` (not left at its default).
    pub fn was_given(&self, key: &str) -> bool {
        self.given.contains_key(key)
    }

    /// `key` as the user wrote it: its older alias when that is what set it
    /// (`model.parameters.young` for `material.young`), otherwise `key` itself.
    pub fn spelling_of(&self, key: &str) -> String {
        self.given
            .get(key)
            .map_or_else(|| key.to_string(), |given| given.spelling.clone())
    }

    /// Where `key` was set: the file or `--set KEY=VALUE` that gave it (or its table), otherwise
    /// `scene SOURCE`. Errors found after parsing (validation, an unknown model, a solver
    /// refusing a value) are attributed with it.
    pub fn origin_of(&self, key: &str) -> String {
        if let Some(given) = self.given.get(key) {
            return given.origin.clone();
        }
        let set_by = |prefix: &str| {
            key == prefix
                || key
                    .strip_prefix(prefix)
                    .is_some_and(|rest| rest.starts_with('.'))
        };
        self.overridden
            .iter()
            .filter(|(prefix, _)| set_by(prefix))
            .max_by_key(|(prefix, _)| prefix.len())
            .map(|(_, origin)| origin.clone())
            .unwrap_or_else(|| format!("scene {}", self.source))
    }

    /// Checks every range constraint (values set through the struct fields bypass the checks of
    /// the parser). Errors are attributed to where the key was set ([`Scene::origin_of`]).
    pub fn validate(&self) -> Result<(), Error> {
        SCHEMA
            .check(self)
            .and_then(|()| check_across_keys(self))
            .map_err(|KeyError { key, message }| Error::scene(self.origin_of(&key), key, message))
    }

    /// The closed-form problem of THEORY.md §8 with this scene's geometry, material and
    /// tension $`N_Y`$ (meaningful for the biaxial load).
    pub fn clamped_rectangle(&self) -> ClampedRectangle {
        ClampedRectangle {
            length_x: self.geometry.length_x,
            length_y: self.geometry.length_y,
            thickness: self.material.thickness,
            young_modulus: self.material.young_modulus,
            poisson_ratio: self.material.poisson_ratio,
            tension_y: self.load.tension_y,
        }
    }

    /// The effective scene as TOML (every key, commented units), suitable for writing next to
    /// outputs; parsing it gives back an equal scene.
    pub fn to_toml_string(&self) -> String {
        let source = toml_string(&self.source);
        let mut text = format!("# Effective wrinkle scene (source: {source})\n");
        for section in SCHEMA.sections {
            self.write_section(&mut text, section);
        }
        text
    }

    /// `[section]` with its keys, then its tables (`[model.parameters]`) when not empty.
    fn write_section(&self, text: &mut String, section: &str) {
        let _ = write!(text, "\n[{section}]\n");
        let mut tables = Vec::new();
        for spec in SCHEMA.keys_of(section) {
            match spec.binding.write(self) {
                Written::Inline { text: value, unit } if unit && !spec.unit.comment.is_empty() => {
                    let _ = writeln!(text, "{} = {value}  # {}", spec.name, spec.unit.comment);
                }
                Written::Inline { text: value, .. } => {
                    let _ = writeln!(text, "{} = {value}", spec.name);
                }
                Written::Table(entries) if !entries.is_empty() => tables.push((spec.key, entries)),
                Written::Table(_) => {}
            }
        }
        for (key, entries) in tables {
            let _ = write!(text, "\n[{key}]\n");
            for (name, value) in entries {
                let _ = writeln!(text, "{name} = {value}");
            }
        }
    }

    /// The effective scene as JSON, with the scene's key names (plus `source`).
    pub fn echo_json(&self) -> serde_json::Value {
        let mut echo = serde_json::Map::new();
        echo.insert("source".to_string(), self.source.clone().into());
        for section in SCHEMA.sections {
            let keys = SCHEMA.keys_of(section);
            let table = keys.map(|spec| (spec.name.to_string(), spec.binding.json(self)));
            echo.insert(section.to_string(), table.collect());
        }
        serde_json::Value::Object(echo)
    }
}
