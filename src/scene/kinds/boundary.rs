//! What a named boundary is held by: the transverse condition (by field role) and the in-plane
//! condition or load, each constant or proportional to the load parameter $`\lambda`$ — the
//! entries of `load.boundary` — and the optional mesh file of `mesh.file`.
//!
//! ```toml
//! [load.boundary.bottom]
//! transverse = "clamped"                 # "clamped", "simply_supported" or "free"
//! in_plane = "fixed"                     # "fixed" or "free", or a table:
//! [load.boundary.top]
//! transverse = "clamped"
//! in_plane = { displacement = [0.0, 0.05], displacement_per_load = [1.0, 0.0] }
//! [load.boundary.left]
//! in_plane = { traction_per_load = [-1.0, 0.0] }   # (normal, tangential), N/mm per unit λ
//! [load.boundary.right_middle]
//! in_plane = { displacement = ["free", 0.0] }      # a roller: v = 0, u free
//! ```

use super::value::Scalar;
use crate::scene::text::{describe, toml_float, toml_string};
use toml::Value;

/// What the transverse fields satisfy on a boundary, by role (documented in `docs/scenes.md`,
/// "Boundaries"): every field but the in-plane displacements is zero when clamped; the
/// deflection-like fields (deflection, envelopes, mean deflection) only when simply supported,
/// rotations free; nothing when free.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Transverse {
    /// Every transverse field zero.
    Clamped,
    /// Deflection, envelopes and mean deflection zero; rotations free.
    SimplySupported,
    /// No condition.
    Free,
}

impl Transverse {
    const CHOICES: [(&'static str, Transverse); 3] = [
        ("clamped", Transverse::Clamped),
        ("simply_supported", Transverse::SimplySupported),
        ("free", Transverse::Free),
    ];

    /// The scene spelling.
    pub fn as_str(self) -> &'static str {
        Self::CHOICES
            .iter()
            .find(|(_, choice)| *choice == self)
            .map_or("free", |(name, _)| name)
    }
}

/// One component of a prescribed displacement: free, or $`g_0 + \lambda g_1`$ (mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Component {
    /// Not prescribed.
    Free,
    /// $`g_0 + \lambda g_1`$.
    Prescribed {
        /// $`g_0`$ (mm).
        value: f64,
        /// $`g_1`$ (mm per unit of $`\lambda`$).
        per_load: f64,
    },
}

/// What holds a boundary in its plane.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum InPlane {
    /// Nothing (no traction either).
    Free,
    /// $`u = v = 0`$.
    Fixed,
    /// Prescribed displacement, per component ($`u`$ along X, $`v`$ along Y).
    Displacement([Component; 2]),
    /// Traction per unit length, (normal along the outward normal, tangential), N/mm:
    /// $`\mathbf t_0 + \lambda\mathbf t_1`$.
    Traction {
        /// $`(t_n, t_s)`$ fixed.
        value: [f64; 2],
        /// $`(t_n, t_s)`$ per unit of $`\lambda`$.
        per_load: [f64; 2],
    },
}

/// The conditions of one named boundary; a missing part leaves the preset's (or free).
#[derive(Clone, Copy, Debug, PartialEq, Default)]
pub struct BoundarySpec {
    /// Transverse condition.
    pub transverse: Option<Transverse>,
    /// In-plane condition or load.
    pub in_plane: Option<InPlane>,
}

/// The kind of a `load.boundary` entry.
#[derive(Clone, Copy, Debug)]
pub struct Boundary;

const IN_PLANE_KEYS: [&str; 4] = [
    "displacement",
    "displacement_per_load",
    "traction",
    "traction_per_load",
];

fn read_transverse(value: &Value) -> Result<Transverse, String> {
    super::value::pick(value, &Transverse::CHOICES).map_err(|m| format!("transverse: {m}"))
}

/// A pair of displacement components, each a number or `"free"`.
fn read_components(key: &str, value: &Value) -> Result<[Option<f64>; 2], String> {
    let items = match value {
        Value::Array(items) if items.len() == 2 => items,
        other => {
            return Err(format!(
                "in_plane.{key}: expected [X, Y] (two numbers or \"free\"), got {}",
                describe(other)
            ));
        }
    };
    let mut out = [None; 2];
    for (slot, item) in out.iter_mut().zip(items) {
        *slot = match item {
            Value::Float(x) if x.is_finite() => Some(*x),
            Value::Integer(i) => Some(*i as f64),
            Value::String(s) if s == "free" => None,
            other => {
                return Err(format!(
                    "in_plane.{key}: each component is a finite number (mm) or \"free\", got {}",
                    describe(other)
                ));
            }
        };
    }
    Ok(out)
}

/// A (normal, tangential) traction pair.
fn read_traction(key: &str, value: &Value) -> Result<[f64; 2], String> {
    let pair = read_components(key, value).map_err(|_| {
        format!(
            "in_plane.{key}: expected [normal, tangential] (two finite numbers, N/mm), got {}",
            describe(value)
        )
    })?;
    match pair {
        [Some(normal), Some(tangential)] => Ok([normal, tangential]),
        _ => Err(format!(
            "in_plane.{key}: a traction has no free component (use 0)"
        )),
    }
}

fn read_in_plane_table(table: &toml::Table) -> Result<InPlane, String> {
    if let Some(key) = table.keys().find(|k| !IN_PLANE_KEYS.contains(&k.as_str())) {
        return Err(format!(
            "in_plane: unknown key `{key}` (keys: {})",
            IN_PLANE_KEYS.join(", ")
        ));
    }
    let displacement = ["displacement", "displacement_per_load"].map(|k| table.get(k));
    let traction = ["traction", "traction_per_load"].map(|k| table.get(k));
    let has_displacement = displacement.iter().any(Option::is_some);
    if has_displacement && traction.iter().any(Option::is_some) {
        return Err(
            "in_plane: a displacement and a traction on one boundary; give one (a \
                    component's traction where the displacement is prescribed is a reaction)"
                .to_string(),
        );
    }
    if has_displacement {
        let read = |k: usize| {
            displacement[k]
                .map(|v| read_components(["displacement", "displacement_per_load"][k], v))
                .transpose()
        };
        let (value, per_load) = (read(0)?, read(1)?);
        let mut components = [Component::Free; 2];
        for (c, component) in components.iter_mut().enumerate() {
            let parts = (value.map(|v| v[c]), per_load.map(|v| v[c]));
            *component = match parts {
                (Some(Some(_)), Some(None)) | (Some(None), Some(Some(_))) => {
                    return Err(format!(
                        "in_plane: component {} is \"free\" in one of displacement and \
                         displacement_per_load and a number in the other",
                        ["X", "Y"][c]
                    ));
                }
                (Some(None), _) | (None, Some(None)) => Component::Free,
                (a, b) => Component::Prescribed {
                    value: a.flatten().unwrap_or(0.0),
                    per_load: b.flatten().unwrap_or(0.0),
                },
            };
        }
        return Ok(InPlane::Displacement(components));
    }
    if traction.iter().all(Option::is_none) {
        return Err(format!(
            "in_plane: an empty table; give one of {}",
            IN_PLANE_KEYS.join(", ")
        ));
    }
    let read = |k: usize| {
        traction[k]
            .map(|v| read_traction(["traction", "traction_per_load"][k], v))
            .transpose()
            .map(|pair| pair.unwrap_or([0.0; 2]))
    };
    Ok(InPlane::Traction {
        value: read(0)?,
        per_load: read(1)?,
    })
}

fn read_in_plane(value: &Value) -> Result<InPlane, String> {
    match value {
        Value::String(s) if s == "fixed" => Ok(InPlane::Fixed),
        Value::String(s) if s == "free" => Ok(InPlane::Free),
        Value::Table(table) => read_in_plane_table(table),
        other => Err(format!(
            "in_plane: expected \"fixed\", \"free\" or a table of {}, got {}",
            IN_PLANE_KEYS.join(", "),
            describe(other)
        )),
    }
}

fn component_text(component: Component, part: usize) -> String {
    match component {
        Component::Free => toml_string("free"),
        Component::Prescribed { value, per_load } => toml_float([value, per_load][part]),
    }
}

fn in_plane_text(in_plane: InPlane) -> String {
    match in_plane {
        InPlane::Free => toml_string("free"),
        InPlane::Fixed => toml_string("fixed"),
        InPlane::Displacement(c) => format!(
            "{{ displacement = [{}, {}], displacement_per_load = [{}, {}] }}",
            component_text(c[0], 0),
            component_text(c[1], 0),
            component_text(c[0], 1),
            component_text(c[1], 1)
        ),
        InPlane::Traction { value, per_load } => format!(
            "{{ traction = [{}, {}], traction_per_load = [{}, {}] }}",
            toml_float(value[0]),
            toml_float(value[1]),
            toml_float(per_load[0]),
            toml_float(per_load[1])
        ),
    }
}

fn component_json(component: Component, part: usize) -> serde_json::Value {
    match component {
        Component::Free => "free".into(),
        Component::Prescribed { value, per_load } => [value, per_load][part].into(),
    }
}

fn in_plane_json(in_plane: InPlane) -> serde_json::Value {
    match in_plane {
        InPlane::Free => "free".into(),
        InPlane::Fixed => "fixed".into(),
        InPlane::Displacement(c) => serde_json::json!({
            "displacement": [component_json(c[0], 0), component_json(c[1], 0)],
            "displacement_per_load": [component_json(c[0], 1), component_json(c[1], 1)],
        }),
        InPlane::Traction { value, per_load } => serde_json::json!({
            "traction": value,
            "traction_per_load": per_load,
        }),
    }
}

impl Scalar for Boundary {
    type Value = BoundarySpec;

    fn read(&self, value: &Value) -> Result<BoundarySpec, String> {
        let Value::Table(table) = value else {
            return Err(format!(
                "expected a table with `transverse` and/or `in_plane`, got {}",
                describe(value)
            ));
        };
        if let Some(key) = table
            .keys()
            .find(|k| *k != "transverse" && *k != "in_plane")
        {
            return Err(format!(
                "unknown key `{key}` (a boundary takes `transverse` and `in_plane`)"
            ));
        }
        if table.is_empty() {
            return Err("an empty boundary table; give `transverse` and/or `in_plane`".into());
        }
        Ok(BoundarySpec {
            transverse: table.get("transverse").map(read_transverse).transpose()?,
            in_plane: table.get("in_plane").map(read_in_plane).transpose()?,
        })
    }

    fn within_bounds(&self, _value: &BoundarySpec) -> Result<(), String> {
        Ok(())
    }

    fn text(&self, value: &BoundarySpec) -> String {
        let mut parts = Vec::new();
        if let Some(transverse) = value.transverse {
            parts.push(format!("transverse = {}", toml_string(transverse.as_str())));
        }
        if let Some(in_plane) = value.in_plane {
            parts.push(format!("in_plane = {}", in_plane_text(in_plane)));
        }
        format!("{{ {} }}", parts.join(", "))
    }

    fn json_value(&self, value: &BoundarySpec) -> serde_json::Value {
        let mut object = serde_json::Map::new();
        if let Some(transverse) = value.transverse {
            object.insert("transverse".into(), transverse.as_str().into());
        }
        if let Some(in_plane) = value.in_plane {
            object.insert("in_plane".into(), in_plane_json(in_plane));
        }
        serde_json::Value::Object(object)
    }

    fn bounds_text(&self) -> String {
        "`transverse` = `\"clamped\"`, `\"simply_supported\"` or `\"free\"`; `in_plane` = \
         `\"fixed\"`, `\"free\"` or a table of `displacement`, `displacement_per_load` \
         (`[X, Y]`, mm, a number or `\"free\"` each) or `traction`, `traction_per_load` \
         (`[normal, tangential]`, N/mm)"
            .to_string()
    }
}

/// A file path, or empty for none (`mesh.file`).
#[derive(Clone, Copy, Debug)]
pub struct OptionalPath;

impl Scalar for OptionalPath {
    type Value = String;

    fn read(&self, value: &Value) -> Result<String, String> {
        match value {
            Value::String(text) => Ok(text.clone()),
            other => Err(format!(
                "expected a string (a path), got {}",
                describe(other)
            )),
        }
    }

    fn within_bounds(&self, _value: &String) -> Result<(), String> {
        Ok(())
    }

    fn text(&self, value: &String) -> String {
        toml_string(value)
    }

    fn json_value(&self, value: &String) -> serde_json::Value {
        serde_json::Value::from(value.as_str())
    }

    fn bounds_text(&self) -> String {
        "a path relative to the scene file, or `\"\"`".to_string()
    }
}
