//! Scene files: what to compute, on which geometry, with which model, mesh, load and solver.
//!
//! A scene is a TOML document whose keys are all optional; missing keys take the values of the
//! paper's example 1 (THEORY.md §9), see [`Scene::default`]. Single keys can be overridden from
//! the command line with `--set KEY=VALUE` ([`Scene::apply_override`]). Parsing walks the TOML
//! table by hand so that every error names the dotted key and where the input came from:
//!
//! ```text
//! scene examples/scenes/x.toml: key `material.poisson`: must satisfy -1 < ν < 0.5, got 0.6
//! --set mesh.nx=0: key `mesh.nx`: must be an integer between 1 and 100000, got 0
//! ```
//!
//! The reference of every key is `docs/scenes.md`.

use crate::closed_form::ClampedRectangle;
use crate::error::Error;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;
use toml::Value;

/// Source name of a scene that was not read from a file.
pub const BUILT_IN_SOURCE: &str = "<built-in default scene>";

/// Largest element count accepted along one side of the mesh.
pub const MAX_ELEMENTS_PER_SIDE: usize = 100_000;

/// Largest total element count $`n_x n_y`$: about 2.5 million unknowns for a five-field plate,
/// whose sparse factor fills the 24 GiB of the reference machine. Larger meshes are refused
/// before anything is allocated.
pub const MAX_ELEMENTS: usize = 120_000;

/// Largest accepted `solver.series_tolerance`: the step length
/// $`(\varepsilon\|U_1\|/\|U_N\|)^{1/(N-1)}`$ grows without bound with $`\varepsilon`$ (1e300 gave
/// λ = −2.3e290 with "residual 0"; 1e-3 stepped over the bifurcation onto another branch).
/// `wrinkle bench` measured 1e-4 … 1e-9 at the same accuracy.
pub const MAX_SERIES_TOLERANCE: f64 = 1e-4;

/// Largest scene file read (a scene is a few hundred bytes; this stops `/dev/zero`).
pub const MAX_SCENE_BYTES: u64 = 1 << 20;

/// Shape of the imperfection that selects the wrinkled branch (`solver.imperfection`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Imperfection {
    /// Uniform for envelope models (the paper's runs), mode-shaped for the others.
    Auto,
    /// A uniform transverse load on the envelope, $`f = \text{perturbation}\cdot h\,DQ^4`$
    /// (envelope models only; the shape of every run before mode-shaped imperfections existed).
    Uniform,
    /// A load shaped like the first buckling mode, $`F = \varepsilon K_0\varphi`$.
    Mode,
}

impl Imperfection {
    /// The scene spelling.
    pub fn as_str(self) -> &'static str {
        match self {
            Imperfection::Auto => "auto",
            Imperfection::Uniform => "uniform",
            Imperfection::Mode => "mode",
        }
    }
}

/// Tables a scene may contain.
const SECTIONS: &[&str] = &[
    "geometry", "material", "model", "mesh", "load", "solver", "output", "validity",
];

/// The validity checks a scene may accept (`validity.accept`), as reported in `check` of each
/// warning (docs/outputs.md); `"all"` accepts every one.
pub const VALIDITY_CHECKS: &[&str] = &[
    "scale_separation",
    "ellipticity",
    "mode_resolution",
    "well_posedness",
];

/// Every leaf key a scene may contain, in document order (`model.parameters` is a table of
/// free-form names).
pub const KEYS: &[&str] = &[
    "geometry.lx",
    "geometry.ly",
    "material.young",
    "material.poisson",
    "material.thickness",
    "model.name",
    "model.wavenumber",
    "model.direction",
    "model.parameters",
    "mesh.nx",
    "mesh.ny",
    "mesh.grading",
    "load.kind",
    "load.tension_y",
    "solver.order",
    "solver.series_tolerance",
    "solver.tolerance",
    "solver.max_steps",
    "solver.max_load",
    "solver.max_amplitude_over_h",
    "solver.perturbation",
    "solver.imperfection",
    "solver.pade",
    "solver.method",
    "output.directory",
    "output.vtu_loads",
    "output.plots",
    "output.vtu",
    "output.surface",
    "validity.accept",
];

/// The rectangle $`[0, L_X] \times [0, L_Y]`$ (mm).
#[derive(Clone, Debug, PartialEq)]
pub struct Geometry {
    /// $`L_X`$ (mm), key `geometry.lx`.
    pub length_x: f64,
    /// $`L_Y`$ (mm), key `geometry.ly`.
    pub length_y: f64,
}

/// Isotropic linear elastic sheet.
#[derive(Clone, Debug, PartialEq)]
pub struct Material {
    /// Young's modulus $`E`$ (MPa), key `material.young`.
    pub young_modulus: f64,
    /// Poisson's ratio $`\nu`$, key `material.poisson`.
    pub poisson_ratio: f64,
    /// Thickness $`h`$ (mm), key `material.thickness`.
    pub thickness: f64,
}

/// Wavenumber $`Q`$ of the wrinkles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Wavenumber {
    /// Chosen by the solver (critical wavenumber of the closed form or a scan).
    Auto,
    /// Prescribed $`Q`$ (1/mm).
    Fixed(f64),
}

/// Which model to solve, and its free parameters.
#[derive(Clone, Debug, PartialEq)]
pub struct ModelChoice {
    /// Registry name, key `model.name` (validated against the registry by the commands).
    pub name: String,
    /// Key `model.wavenumber`: a number (1/mm) or `"auto"`.
    pub wavenumber: Wavenumber,
    /// Angle of the wave vector from the X axis (degrees), key `model.direction`.
    pub direction_degrees: f64,
    /// Extra model parameters by name, table `model.parameters`.
    pub parameters: BTreeMap<String, f64>,
}

/// Structured Q8 mesh of the rectangle.
#[derive(Clone, Debug, PartialEq)]
pub struct MeshSpec {
    /// Elements along X, key `mesh.nx`.
    pub elements_x: usize,
    /// Elements along Y, key `mesh.ny`.
    pub elements_y: usize,
    /// Ratio of the largest to the smallest element size ($`\ge 1`$; smallest at the edges),
    /// key `mesh.grading`.
    pub grading: f64,
}

/// Kind of loading.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LoadKind {
    /// Example 1: tension $`N_Y`$ fixed, load $`\lambda = -N_X`$ (compression, N/mm).
    Biaxial,
    /// Example 2: short sides clamped, $`\lambda`$ = prescribed end displacement (mm).
    Strip,
}

impl LoadKind {
    /// The scene spelling of this kind.
    pub fn as_str(self) -> &'static str {
        match self {
            LoadKind::Biaxial => "biaxial",
            LoadKind::Strip => "strip",
        }
    }
}

/// Loading.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadSpec {
    /// Key `load.kind`.
    pub kind: LoadKind,
    /// Tension $`N_Y`$ (N/mm), biaxial only, key `load.tension_y`.
    pub tension_y: f64,
}

/// Path-following method.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PathMethod {
    /// Asymptotic Numerical Method (THEORY.md §10).
    Anm,
    /// Riks arc-length continuation (baseline).
    Riks,
}

impl PathMethod {
    /// The scene spelling of this method.
    pub fn as_str(self) -> &'static str {
        match self {
            PathMethod::Anm => "anm",
            PathMethod::Riks => "riks",
        }
    }
}

/// Settings of the path following used by `wrinkle run`.
#[derive(Clone, Debug, PartialEq)]
pub struct SolverSpec {
    /// Truncation order $`N`$ of the series, key `solver.order`.
    pub order: usize,
    /// $`\varepsilon`$ in $`a_{max} = (\varepsilon\|U_1\|/\|U_N\|)^{1/(N-1)}`$, key
    /// `solver.series_tolerance`.
    pub series_tolerance: f64,
    /// Relative residual accepted at every point, key `solver.tolerance`.
    pub tolerance: f64,
    /// Maximum number of steps, key `solver.max_steps`.
    pub max_steps: usize,
    /// Stop at this load $`\lambda`$; 0 means no limit. Key `solver.max_load`.
    pub max_load: f64,
    /// Stop when the maximum physical wrinkle amplitude over the thickness reaches this value,
    /// key `solver.max_amplitude_over_h` (the older key `solver.max_envelope_over_h` sets it to
    /// twice its value: the physical amplitude of an envelope model is $`2|w_\text{env}|`$).
    pub max_amplitude_over_thickness: f64,
    /// Size of the imperfection that selects the wrinkled branch, key `solver.perturbation`: a
    /// fixed transverse load shaped like the first buckling mode, $`F = \varepsilon K_0\varphi`$
    /// ($`K_0`$ the tangent of the unloaded state), scaled so that the physical wrinkle amplitude
    /// it gives on the unloaded sheet is `perturbation` thicknesses.
    pub perturbation: f64,
    /// Shape of the imperfection, key `solver.imperfection`: `"auto"` (uniform for envelope
    /// models, mode-shaped for the others), `"uniform"` or `"mode"`.
    pub imperfection: Imperfection,
    /// Use Padé approximants to lengthen ANM steps, key `solver.pade` (default `true`: the
    /// fastest method measured on every registered model, `docs/benchmarks.md`).
    pub pade: bool,
    /// Key `solver.method`.
    pub method: PathMethod,
}

/// What `wrinkle run` writes.
#[derive(Clone, Debug, PartialEq)]
pub struct OutputSpec {
    /// Output directory, key `output.directory`.
    pub directory: String,
    /// Loads $`\lambda`$ at which fields are written as VTU, key `output.vtu_loads`.
    pub vtu_loads: Vec<f64>,
    /// Whether to draw plots (and embed them in `report.html`), key `output.plots`.
    pub plots: bool,
    /// Whether to write the nodal fields at the end of the path (`fields_final.vtu`) and at
    /// `vtu_loads`, key `output.vtu`.
    pub vtu: bool,
    /// Whether to write the reconstructed physical surface (`surface_final.vtu`, a grid refined
    /// to resolve the wrinkles of envelope models), key `output.surface`.
    pub surface: bool,
}

/// Which validity checks a scene accepts, table `[validity]`.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ValiditySpec {
    /// Checks (names of [`VALIDITY_CHECKS`], or `"all"`) whose failure is still reported but
    /// does not make the exit code non-zero, key `validity.accept`.
    pub accept: Vec<String>,
}

impl ValiditySpec {
    /// Whether a failed `check` is accepted by the scene.
    pub fn accepts(&self, check: &str) -> bool {
        self.accept
            .iter()
            .any(|name| name == "all" || name == check)
    }
}

/// A complete, validated description of one computation.
#[derive(Clone, Debug)]
pub struct Scene {
    /// Table `[geometry]`.
    pub geometry: Geometry,
    /// Table `[material]`.
    pub material: Material,
    /// Table `[model]`.
    pub model: ModelChoice,
    /// Table `[mesh]`.
    pub mesh: MeshSpec,
    /// Table `[load]`.
    pub load: LoadSpec,
    /// Table `[solver]`.
    pub solver: SolverSpec,
    /// Table `[output]`.
    pub output: OutputSpec,
    /// Table `[validity]`.
    pub validity: ValiditySpec,
    /// File the scene was read from, or [`BUILT_IN_SOURCE`].
    pub source: String,
    /// Keys set by `--set`, each with the assignment that set it last: an error about such a
    /// key names the override, not the file ([`Scene::origin_of`]).
    pub overridden: BTreeMap<String, String>,
}

/// Two scenes are equal when they describe the same computation: where their keys were set
/// ([`Scene::overridden`]) does not matter.
impl PartialEq for Scene {
    fn eq(&self, other: &Self) -> bool {
        self.geometry == other.geometry
            && self.material == other.material
            && self.model == other.model
            && self.mesh == other.mesh
            && self.load == other.load
            && self.solver == other.solver
            && self.output == other.output
            && self.validity == other.validity
            && self.source == other.source
    }
}

impl Default for Scene {
    /// The paper's example 1 (THEORY.md §9): clamped 400 × 200 mm rectangle, $`h = 0.05`$ mm,
    /// $`E = 70000`$ MPa, $`\nu = 0.3`$, $`N_Y = 10`$ N/mm, reference envelope model.
    fn default() -> Self {
        Scene {
            geometry: Geometry {
                length_x: 400.0,
                length_y: 200.0,
            },
            material: Material {
                young_modulus: 70000.0,
                poisson_ratio: 0.3,
                thickness: 0.05,
            },
            model: ModelChoice {
                name: "reference-envelope".to_string(),
                wavenumber: Wavenumber::Auto,
                direction_degrees: 0.0,
                parameters: BTreeMap::new(),
            },
            mesh: MeshSpec {
                elements_x: 32,
                elements_y: 16,
                grading: 1.0,
            },
            load: LoadSpec {
                kind: LoadKind::Biaxial,
                tension_y: 10.0,
            },
            solver: SolverSpec {
                order: 20,
                series_tolerance: 1e-7,
                tolerance: 1e-6,
                max_steps: 200,
                max_load: 0.0,
                max_amplitude_over_thickness: 4.0,
                perturbation: 1e-4,
                imperfection: Imperfection::Auto,
                pade: true,
                method: PathMethod::Anm,
            },
            output: OutputSpec {
                directory: "out".to_string(),
                vtu_loads: Vec::new(),
                plots: true,
                vtu: true,
                surface: true,
            },
            validity: ValiditySpec::default(),
            source: BUILT_IN_SOURCE.to_string(),
            overridden: BTreeMap::new(),
        }
    }
}

/// A problem with one key, before it is attributed to a source.
struct KeyError {
    key: String,
    message: String,
}

impl KeyError {
    fn new(key: &str, message: impl Into<String>) -> Self {
        KeyError {
            key: key.to_string(),
            message: message.into(),
        }
    }
}

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
        scene
            .apply_table("", &table)
            .map_err(|error| Error::scene(&origin, error.key, error.message))?;
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
        let mut bytes = Vec::new();
        std::io::Read::read_to_end(
            &mut std::io::Read::take(
                std::fs::File::open(path).map_err(cannot)?,
                MAX_SCENE_BYTES + 1,
            ),
            &mut bytes,
        )
        .map_err(cannot)?;
        if bytes.len() as u64 > MAX_SCENE_BYTES {
            return Err(Error::scene(
                format!("scene {name}"),
                "",
                format!("larger than {MAX_SCENE_BYTES} bytes: not a scene file"),
            ));
        }
        let text = String::from_utf8(bytes).map_err(|e| {
            Error::scene(format!("scene {name}"), "", format!("not UTF-8 text: {e}"))
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
        updated
            .apply_value(key, &value)
            .map_err(|error| Error::scene(&origin, error.key, error.message))?;
        updated.overridden.insert(key.to_string(), origin);
        *self = updated;
        Ok(())
    }

    /// Where `key` was set: `--set KEY=VALUE` when an override set it (or its table), otherwise
    /// `scene SOURCE`. Errors found after parsing (validation, an unknown model, a solver
    /// refusing a value) are attributed with it.
    pub fn origin_of(&self, key: &str) -> String {
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
    /// the parser). Errors are attributed to `scene SOURCE`.
    pub fn validate(&self) -> Result<(), Error> {
        for key in KEYS {
            self.check_key(key)
                .map_err(|message| Error::scene(self.origin_of(key), *key, message))?;
        }
        let elements = self.mesh.elements_x.saturating_mul(self.mesh.elements_y);
        if elements > MAX_ELEMENTS {
            return Err(Error::scene(
                self.origin_of("mesh.nx"),
                "mesh.nx",
                format!(
                    "mesh.nx × mesh.ny = {} × {} = {elements} elements is more than the {MAX_ELEMENTS} this tool solves in 24 GiB",
                    self.mesh.elements_x, self.mesh.elements_y
                ),
            ));
        }
        for (name, value) in &self.model.parameters {
            if !value.is_finite() {
                let key = format!("model.parameters.{name}");
                return Err(Error::scene(
                    self.origin_of(&key),
                    key,
                    format!("must be a finite number, got {value}"),
                ));
            }
        }
        Ok(())
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
        let mut text = String::new();
        let source = toml_string(&self.source);
        let _ = writeln!(text, "# Effective wrinkle scene (source: {source})");
        text.push_str("\n[geometry]\n");
        let _ = writeln!(text, "lx = {}  # mm", toml_float(self.geometry.length_x));
        let _ = writeln!(text, "ly = {}  # mm", toml_float(self.geometry.length_y));
        text.push_str("\n[material]\n");
        let _ = writeln!(
            text,
            "young = {}  # MPa",
            toml_float(self.material.young_modulus)
        );
        let _ = writeln!(
            text,
            "poisson = {}",
            toml_float(self.material.poisson_ratio)
        );
        let _ = writeln!(
            text,
            "thickness = {}  # mm",
            toml_float(self.material.thickness)
        );
        text.push_str("\n[model]\n");
        let _ = writeln!(text, "name = {}", toml_string(&self.model.name));
        match self.model.wavenumber {
            Wavenumber::Auto => text.push_str("wavenumber = \"auto\"\n"),
            Wavenumber::Fixed(value) => {
                let _ = writeln!(text, "wavenumber = {}  # 1/mm", toml_float(value));
            }
        }
        let _ = writeln!(
            text,
            "direction = {}  # degrees from X",
            toml_float(self.model.direction_degrees)
        );
        if !self.model.parameters.is_empty() {
            text.push_str("\n[model.parameters]\n");
            for (name, value) in &self.model.parameters {
                let _ = writeln!(text, "{} = {}", toml_key(name), toml_float(*value));
            }
        }
        text.push_str("\n[mesh]\n");
        let _ = writeln!(text, "nx = {}", self.mesh.elements_x);
        let _ = writeln!(text, "ny = {}", self.mesh.elements_y);
        let _ = writeln!(text, "grading = {}", toml_float(self.mesh.grading));
        text.push_str("\n[load]\n");
        let _ = writeln!(text, "kind = \"{}\"", self.load.kind.as_str());
        let _ = writeln!(
            text,
            "tension_y = {}  # N/mm",
            toml_float(self.load.tension_y)
        );
        text.push_str("\n[solver]\n");
        let solver = &self.solver;
        let _ = writeln!(text, "order = {}", solver.order);
        let _ = writeln!(
            text,
            "series_tolerance = {}",
            toml_float(solver.series_tolerance)
        );
        let _ = writeln!(text, "tolerance = {}", toml_float(solver.tolerance));
        let _ = writeln!(text, "max_steps = {}", solver.max_steps);
        let _ = writeln!(text, "max_load = {}", toml_float(solver.max_load));
        let _ = writeln!(
            text,
            "max_amplitude_over_h = {}",
            toml_float(solver.max_amplitude_over_thickness)
        );
        let _ = writeln!(text, "perturbation = {}", toml_float(solver.perturbation));
        let _ = writeln!(text, "imperfection = \"{}\"", solver.imperfection.as_str());
        let _ = writeln!(text, "pade = {}", solver.pade);
        let _ = writeln!(text, "method = \"{}\"", solver.method.as_str());
        text.push_str("\n[output]\n");
        let _ = writeln!(text, "directory = {}", toml_string(&self.output.directory));
        let loads: Vec<String> = self
            .output
            .vtu_loads
            .iter()
            .map(|load| toml_float(*load))
            .collect();
        let _ = writeln!(text, "vtu_loads = [{}]", loads.join(", "));
        let _ = writeln!(text, "plots = {}", self.output.plots);
        let _ = writeln!(text, "vtu = {}", self.output.vtu);
        let _ = writeln!(text, "surface = {}", self.output.surface);
        text.push_str("\n[validity]\n");
        let accepted: Vec<String> = self
            .validity
            .accept
            .iter()
            .map(|name| toml_string(name))
            .collect();
        let _ = writeln!(text, "accept = [{}]", accepted.join(", "));
        text
    }

    /// The effective scene as JSON, with the scene's key names (plus `source`).
    pub fn echo_json(&self) -> serde_json::Value {
        let wavenumber = match self.model.wavenumber {
            Wavenumber::Auto => serde_json::Value::from("auto"),
            Wavenumber::Fixed(value) => serde_json::Value::from(value),
        };
        serde_json::json!({
            "source": self.source,
            "geometry": { "lx": self.geometry.length_x, "ly": self.geometry.length_y },
            "material": {
                "young": self.material.young_modulus,
                "poisson": self.material.poisson_ratio,
                "thickness": self.material.thickness,
            },
            "model": {
                "name": self.model.name,
                "wavenumber": wavenumber,
                "direction": self.model.direction_degrees,
                "parameters": self.model.parameters,
            },
            "mesh": {
                "nx": self.mesh.elements_x,
                "ny": self.mesh.elements_y,
                "grading": self.mesh.grading,
            },
            "load": { "kind": self.load.kind.as_str(), "tension_y": self.load.tension_y },
            "solver": {
                "order": self.solver.order,
                "series_tolerance": self.solver.series_tolerance,
                "tolerance": self.solver.tolerance,
                "max_steps": self.solver.max_steps,
                "max_load": self.solver.max_load,
                "max_amplitude_over_h": self.solver.max_amplitude_over_thickness,
                "perturbation": self.solver.perturbation,
                "imperfection": self.solver.imperfection.as_str(),
                "pade": self.solver.pade,
                "method": self.solver.method.as_str(),
            },
            "output": {
                "directory": self.output.directory,
                "vtu_loads": self.output.vtu_loads,
                "plots": self.output.plots,
                "vtu": self.output.vtu,
                "surface": self.output.surface,
            },
            "validity": { "accept": self.validity.accept },
        })
    }

    /// Applies every entry of `table`, whose keys are relative to `prefix` (empty at the root).
    fn apply_table(&mut self, prefix: &str, table: &toml::Table) -> Result<(), KeyError> {
        for (name, value) in table {
            let key = if prefix.is_empty() {
                name.clone()
            } else {
                format!("{prefix}.{name}")
            };
            self.apply_value(&key, value)?;
        }
        Ok(())
    }

    /// Sets one dotted key (a section or `model.parameters` takes a table) and checks its range.
    /// `model.parameters.NAME = number`.
    fn apply_parameter(&mut self, key: &str, name: &str, value: &Value) -> Result<(), KeyError> {
        if name.contains('.') {
            return Err(KeyError::new(
                key,
                "model parameters are plain names (no nested tables)",
            ));
        }
        let number = number(value).map_err(|message| KeyError::new(key, message))?;
        if !number.is_finite() {
            return Err(KeyError::new(
                key,
                format!("must be a finite number, got {number}"),
            ));
        }
        self.model.parameters.insert(name.to_string(), number);
        Ok(())
    }

    /// The `solver.*`, `output.*` and `validity.*` keys (what `wrinkle run` does with the
    /// problem).
    fn apply_run_key(&mut self, key: &str, value: &Value) -> Result<(), KeyError> {
        let error = |message: String| KeyError::new(key, message);
        match key {
            "solver.order" => self.solver.order = count(value, 2, 40).map_err(error)?,
            "solver.series_tolerance" => {
                self.solver.series_tolerance = number(value).map_err(error)?
            }
            "solver.tolerance" => self.solver.tolerance = number(value).map_err(error)?,
            "solver.max_steps" => {
                self.solver.max_steps = count(value, 1, usize::MAX).map_err(error)?
            }
            "solver.max_load" => self.solver.max_load = number(value).map_err(error)?,
            "solver.max_amplitude_over_h" => {
                self.solver.max_amplitude_over_thickness = number(value).map_err(error)?
            }
            "solver.max_envelope_over_h" => {
                self.solver.max_amplitude_over_thickness = 2.0 * number(value).map_err(error)?
            }
            "solver.perturbation" => self.solver.perturbation = number(value).map_err(error)?,
            "solver.imperfection" => {
                self.solver.imperfection =
                    match choice(value, &["auto", "uniform", "mode"]).map_err(error)? {
                        "uniform" => Imperfection::Uniform,
                        "mode" => Imperfection::Mode,
                        _ => Imperfection::Auto,
                    }
            }
            "solver.pade" => self.solver.pade = boolean(value).map_err(error)?,
            "solver.method" => {
                self.solver.method = match choice(value, &["anm", "riks"]).map_err(error)? {
                    "anm" => PathMethod::Anm,
                    _ => PathMethod::Riks,
                }
            }
            "output.directory" => self.output.directory = string(value).map_err(error)?,
            "output.vtu_loads" => {
                let Value::Array(items) = value else {
                    return Err(KeyError::new(
                        key,
                        format!("expected an array of numbers, got {}", describe(value)),
                    ));
                };
                self.output.vtu_loads = items
                    .iter()
                    .enumerate()
                    .map(|(index, item)| {
                        number(item).map_err(|message| format!("item {index}: {message}"))
                    })
                    .collect::<Result<_, _>>()
                    .map_err(error)?;
            }
            "output.plots" => self.output.plots = boolean(value).map_err(error)?,
            "output.vtu" => self.output.vtu = boolean(value).map_err(error)?,
            "output.surface" => self.output.surface = boolean(value).map_err(error)?,
            "validity.accept" => self.validity.accept = accepted_checks(value).map_err(error)?,
            _ => return Err(KeyError::new(key, unknown_key_message(key))),
        }
        Ok(())
    }

    fn apply_value(&mut self, key: &str, value: &Value) -> Result<(), KeyError> {
        if SECTIONS.contains(&key) || key == "model.parameters" {
            return match value {
                Value::Table(table) => self.apply_table(key, table),
                other => Err(KeyError::new(
                    key,
                    format!("expected a table, got {}", describe(other)),
                )),
            };
        }
        if let Some(name) = key.strip_prefix("model.parameters.") {
            return self.apply_parameter(key, name, value);
        }
        let error = |message: String| KeyError::new(key, message);
        match key {
            "geometry.lx" => self.geometry.length_x = number(value).map_err(error)?,
            "geometry.ly" => self.geometry.length_y = number(value).map_err(error)?,
            "material.young" => self.material.young_modulus = number(value).map_err(error)?,
            "material.poisson" => self.material.poisson_ratio = number(value).map_err(error)?,
            "material.thickness" => self.material.thickness = number(value).map_err(error)?,
            "model.name" => self.model.name = string(value).map_err(error)?,
            "model.wavenumber" => {
                self.model.wavenumber = match value {
                    Value::String(text) if text == "auto" => Wavenumber::Auto,
                    Value::Integer(_) | Value::Float(_) => {
                        Wavenumber::Fixed(number(value).map_err(error)?)
                    }
                    other => {
                        return Err(KeyError::new(
                            key,
                            format!(
                                "expected a number > 0 (1/mm) or \"auto\", got {}",
                                describe(other)
                            ),
                        ));
                    }
                }
            }
            "model.direction" => self.model.direction_degrees = number(value).map_err(error)?,
            "mesh.nx" => {
                self.mesh.elements_x = count(value, 1, MAX_ELEMENTS_PER_SIDE).map_err(error)?
            }
            "mesh.ny" => {
                self.mesh.elements_y = count(value, 1, MAX_ELEMENTS_PER_SIDE).map_err(error)?
            }
            "mesh.grading" => self.mesh.grading = number(value).map_err(error)?,
            "load.kind" => {
                self.load.kind = match choice(value, &["biaxial", "strip"]).map_err(error)? {
                    "biaxial" => LoadKind::Biaxial,
                    _ => LoadKind::Strip,
                }
            }
            "load.tension_y" => self.load.tension_y = number(value).map_err(error)?,
            _ if ["solver.", "output.", "validity."]
                .iter()
                .any(|prefix| key.starts_with(prefix)) =>
            {
                self.apply_run_key(key, value)?
            }
            _ => return Err(KeyError::new(key, unknown_key_message(key))),
        }
        self.check_key(key)
            .map_err(|message| KeyError::new(key, message))
    }

    /// Range check of one leaf key of [`KEYS`] on the current values.
    fn check_key(&self, key: &str) -> Result<(), String> {
        match key {
            "geometry.lx" => positive(self.geometry.length_x),
            "geometry.ly" => positive(self.geometry.length_y),
            "material.young" => positive(self.material.young_modulus),
            "material.poisson" => {
                let poisson = self.material.poisson_ratio;
                if poisson > -1.0 && poisson < 0.5 {
                    Ok(())
                } else {
                    Err(format!("must satisfy -1 < ν < 0.5, got {poisson}"))
                }
            }
            "material.thickness" => positive(self.material.thickness),
            "model.name" => non_empty(&self.model.name),
            "model.wavenumber" => match self.model.wavenumber {
                Wavenumber::Auto => Ok(()),
                Wavenumber::Fixed(value) => positive(value),
            },
            "model.direction" => finite(self.model.direction_degrees),
            "mesh.nx" => count_in_range(self.mesh.elements_x, 1, MAX_ELEMENTS_PER_SIDE),
            "mesh.ny" => count_in_range(self.mesh.elements_y, 1, MAX_ELEMENTS_PER_SIDE),
            "mesh.grading" => at_least(self.mesh.grading, 1.0),
            "load.tension_y" => at_least(self.load.tension_y, 0.0),
            "solver.order" => count_in_range(self.solver.order, 2, 40),
            "solver.series_tolerance" => {
                let tolerance = self.solver.series_tolerance;
                if tolerance > 0.0 && tolerance <= MAX_SERIES_TOLERANCE {
                    Ok(())
                } else {
                    Err(format!(
                        "must be > 0 and at most {MAX_SERIES_TOLERANCE:e} (a looser series lets a step run past the validity of its truncation), got {tolerance:e}"
                    ))
                }
            }
            "solver.tolerance" => positive(self.solver.tolerance),
            "solver.max_steps" => count_in_range(self.solver.max_steps, 1, usize::MAX),
            "solver.max_load" => at_least(self.solver.max_load, 0.0),
            "solver.max_amplitude_over_h" | "solver.max_envelope_over_h" => {
                positive(self.solver.max_amplitude_over_thickness)
            }
            "solver.perturbation" => at_least(self.solver.perturbation, 0.0),
            "output.directory" => non_empty(&self.output.directory),
            "output.vtu_loads" => {
                self.output
                    .vtu_loads
                    .iter()
                    .enumerate()
                    .try_for_each(|(index, load)| {
                        finite(*load).map_err(|message| format!("item {index}: {message}"))
                    })
            }
            _ => Ok(()),
        }
    }
}

/// One-line description of a TOML syntax error with its line and column.
fn syntax_message(text: &str, error: &toml::de::Error) -> String {
    let message = error.message().trim().replace('\n', " ");
    match error.span() {
        Some(span) => {
            let offset = span.start.min(text.len());
            let before = &text[..offset];
            let line = before.matches('\n').count() + 1;
            let column = before
                .rsplit('\n')
                .next()
                .map_or(0, |tail| tail.chars().count())
                + 1;
            format!("TOML syntax error at line {line}, column {column}: {message}")
        }
        None => format!("TOML syntax error: {message}"),
    }
}

/// Parses the value of a `--set` override.
fn parse_override_value(text: &str) -> Result<Value, String> {
    if text.is_empty() {
        return Err("missing value after `=`".to_string());
    }
    match text.parse::<Value>() {
        Ok(value) => Ok(value),
        Err(_) if is_bare_word(text) => Ok(Value::String(text.to_string())),
        Err(error) => Err(format!(
            "`{text}` is not a TOML value ({}); quote strings, e.g. '\"text\"'",
            error.message().trim().replace('\n', " ")
        )),
    }
}

/// A word that can stand for a string without quotes: starts with a letter, then letters,
/// digits, `-` or `_`.
fn is_bare_word(text: &str) -> bool {
    let mut characters = text.chars();
    characters
        .next()
        .is_some_and(|first| first.is_ascii_alphabetic())
        && characters.all(|character| {
            character.is_ascii_alphanumeric() || character == '-' || character == '_'
        })
}

/// How a TOML value is named in error messages.
fn describe(value: &Value) -> String {
    match value {
        Value::String(text) => format!("string {}", toml_string(text)),
        Value::Integer(number) => format!("integer {number}"),
        Value::Float(number) => format!("float {number}"),
        Value::Boolean(flag) => format!("boolean {flag}"),
        Value::Datetime(datetime) => format!("datetime {datetime}"),
        Value::Array(_) => "an array".to_string(),
        Value::Table(_) => "a table".to_string(),
    }
}

fn number(value: &Value) -> Result<f64, String> {
    match value {
        Value::Float(number) => Ok(*number),
        Value::Integer(number) => Ok(*number as f64),
        other => Err(format!("expected a number, got {}", describe(other))),
    }
}

/// `validity.accept`: an array of names from [`VALIDITY_CHECKS`] or `"all"` (a single string
/// is taken as a one-element array).
fn accepted_checks(value: &Value) -> Result<Vec<String>, String> {
    let items: Vec<&Value> = match value {
        Value::Array(items) => items.iter().collect(),
        single @ Value::String(_) => vec![single],
        other => {
            return Err(format!(
                "expected an array of check names, got {}",
                describe(other)
            ));
        }
    };
    let mut names: Vec<&str> = VALIDITY_CHECKS.to_vec();
    names.push("all");
    items
        .into_iter()
        .enumerate()
        .map(|(index, item)| {
            choice(item, &names)
                .map(str::to_string)
                .map_err(|message| format!("item {index}: {message}"))
        })
        .collect()
}

fn string(value: &Value) -> Result<String, String> {
    match value {
        Value::String(text) => Ok(text.clone()),
        other => Err(format!("expected a string, got {}", describe(other))),
    }
}

fn boolean(value: &Value) -> Result<bool, String> {
    match value {
        Value::Boolean(flag) => Ok(*flag),
        other => Err(format!(
            "expected a boolean (true or false), got {}",
            describe(other)
        )),
    }
}

fn choice<'a>(value: &Value, choices: &[&'a str]) -> Result<&'a str, String> {
    let quoted: Vec<String> = choices
        .iter()
        .map(|choice| format!("\"{choice}\""))
        .collect();
    match value {
        Value::String(text) => choices
            .iter()
            .find(|choice| **choice == text)
            .copied()
            .ok_or_else(|| {
                format!(
                    "expected one of {}, got {}",
                    quoted.join(", "),
                    toml_string(text)
                )
            }),
        other => Err(format!(
            "expected one of {}, got {}",
            quoted.join(", "),
            describe(other)
        )),
    }
}

fn count(value: &Value, minimum: usize, maximum: usize) -> Result<usize, String> {
    let Value::Integer(number) = value else {
        return Err(format!("expected an integer, got {}", describe(value)));
    };
    usize::try_from(*number)
        .ok()
        .filter(|count| (minimum..=maximum).contains(count))
        .ok_or_else(|| range_message(minimum, maximum, *number))
}

fn count_in_range(count: usize, minimum: usize, maximum: usize) -> Result<(), String> {
    if (minimum..=maximum).contains(&count) {
        Ok(())
    } else {
        Err(range_message(minimum, maximum, count))
    }
}

fn range_message(minimum: usize, maximum: usize, got: impl std::fmt::Display) -> String {
    if maximum == usize::MAX {
        format!("must be an integer ≥ {minimum}, got {got}")
    } else {
        format!("must be an integer between {minimum} and {maximum}, got {got}")
    }
}

fn finite(value: f64) -> Result<(), String> {
    if value.is_finite() {
        Ok(())
    } else {
        Err(format!("must be a finite number, got {value}"))
    }
}

fn positive(value: f64) -> Result<(), String> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(format!("must be > 0, got {value}"))
    }
}

fn at_least(value: f64, minimum: f64) -> Result<(), String> {
    if value.is_finite() && value >= minimum {
        Ok(())
    } else {
        Err(format!("must be ≥ {minimum}, got {value}"))
    }
}

fn non_empty(text: &str) -> Result<(), String> {
    if text.trim().is_empty() {
        Err("must not be empty".to_string())
    } else {
        Ok(())
    }
}

/// Message for an unknown key, with the closest valid key when one is near.
fn unknown_key_message(key: &str) -> String {
    let candidates = KEYS.iter().chain(SECTIONS.iter()).copied();
    let best = candidates
        .map(|candidate| (edit_distance(key, candidate), candidate))
        .min_by_key(|(distance, _)| *distance);
    match best {
        Some((distance, candidate)) if distance <= (key.len() / 3).max(2) => {
            format!("unknown key; did you mean `{candidate}`?")
        }
        _ => {
            let section = key.split('.').next().unwrap_or(key);
            if SECTIONS.contains(&section) {
                let keys: Vec<&str> = KEYS
                    .iter()
                    .filter_map(|known| known.strip_prefix(section)?.strip_prefix('.'))
                    .collect();
                format!("unknown key; `[{section}]` accepts {}", keys.join(", "))
            } else {
                format!("unknown key; the tables are {}", SECTIONS.join(", "))
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

/// A float written so that TOML reads it back as the same float.
fn toml_float(value: f64) -> String {
    if value.is_finite() {
        format!("{value:?}")
    } else if value.is_nan() {
        "nan".to_string()
    } else if value > 0.0 {
        "inf".to_string()
    } else {
        "-inf".to_string()
    }
}

/// A TOML basic string literal.
fn toml_string(text: &str) -> String {
    Value::String(text.to_string()).to_string()
}

/// A TOML key, bare when possible.
fn toml_key(name: &str) -> String {
    if !name.is_empty()
        && name.chars().all(|character| {
            character.is_ascii_alphanumeric() || character == '-' || character == '_'
        })
    {
        name.to_string()
    } else {
        toml_string(name)
    }
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

    #[test]
    fn floats_round_trip_through_toml_text() {
        for value in [400.0, 0.05, 1e-7, 0.1 + 0.2, -3.5e12, 0.0] {
            let parsed: Value = toml_float(value).parse().unwrap();
            assert_eq!(number(&parsed).unwrap(), value);
        }
    }
}
