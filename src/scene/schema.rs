//! The scene schema: every key declared once — name, Rust field, type, default, kind (with its
//! bounds), unit and meaning — and the few checks that involve more than one key.
//!
//! Everything else follows from these declarations (`declare.rs` expands them): the structs and
//! their defaults, TOML and `--set` parsing, validation, the unknown-key suggestion, [`KEYS`],
//! the effective-scene TOML and JSON, and the key tables of `docs/scenes.md` (regenerated with
//! `WRINKLE_BLESS=1 cargo test --test scene_docs`). **A new key is one declaration here** plus
//! its use.

use super::declare::{scene_enum, scene_schema};
use super::keys::{Alias, Schema, Unit};
use super::kinds::{
    AutoOrNumber, Boundary, BoundarySpec, ChoiceList, Count, Flag, Float, FloatList, ModelName,
    OptionalPath, PointTable, Scalar, Table, Text, number_or_auto, one_of,
};
use std::collections::BTreeMap;
use toml::Value;
use wrinkle_models::REFERENCE_MODEL;
use wrinkle_runtime::fem::mesh::{AxisGrading, RefinedEnds};

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

/// Shortest and longest side accepted (mm): a nanometre to a thousand kilometres. Lengths enter
/// the stiffness squared and to the fourth power (the bending of a wave over an element); inside
/// this window neither overflows nor underflows.
pub const LENGTH_RANGE: (f64, f64) = (1e-6, 1e9);

/// Largest ratio of the longer to the shorter side of any element, grading included: the
/// eigen-solver's work grows with it (`mesh.nx = 100000, mesh.ny = 1` made elements 50 000
/// times longer than wide and never finished its wavenumber search), and a Q8 element that
/// stretched approximates nothing.
pub const MAX_ELEMENT_ASPECT_RATIO: f64 = 50.0;

/// The edges and corners of the rectangle that `mesh.refine_toward` may name.
pub const REFINE_TARGETS: &[&str] = &[
    "left",
    "right",
    "bottom",
    "top",
    "bottom_left",
    "bottom_right",
    "top_left",
    "top_right",
];

/// Largest `solver.max_steps`: each step costs at least one factorisation.
pub const MAX_STEPS: usize = 10_000;

/// Largest number of `output.vtu_loads` (each writes a file of the whole mesh).
pub const MAX_VTU_LOADS: usize = 100;

/// The validity checks a scene may accept (`validity.accept`), as reported in `check` of each
/// warning (docs/outputs.md); `"all"` accepts every one.
pub const VALIDITY_CHECKS: &[&str] = &[
    "scale_separation",
    "ellipticity",
    "mode_resolution",
    "well_posedness",
];

scene_schema! {
    /// The rectangle $`[0, L_X] \times [0, L_Y]`$ (mm).
    [geometry] Geometry {
        /// length $`L_X`$ along X
        lx => length_x: f64 = 400.0,
            Float::at_least(LENGTH_RANGE.0).at_most(LENGTH_RANGE.1), Unit::MM;
        /// width $`L_Y`$ along Y
        ly => length_y: f64 = 200.0,
            Float::at_least(LENGTH_RANGE.0).at_most(LENGTH_RANGE.1), Unit::MM;
        /// `"plane"`: the rectangle (or `mesh.file`); `"line"`: the segment $`[0, L_X]`$ of a
        /// beam (`lx` its length, `ly` unused), ends `left` and `right`, line models only
        /// (`docs/beam.md`, "The CLI on a line")
        kind => domain: Domain = Domain::Plane, one_of::<Domain>(), Unit::NONE;
    }

    /// Isotropic linear elastic sheet.
    [material] Material {
        /// Young's modulus $`E`$
        young => young_modulus: f64 = 70000.0, Float::above(0.0), Unit::MPA,
            note "and the stiffnesses $`Eh/(1-\\nu^2)`$ and $`Eh^3/(12(1-\\nu^2))`$ within 1e-60 … 1e60, \
                  the tension strain $`N_Y/(Eh)`$ at most 1";
        /// Poisson's ratio $`\nu`$
        poisson => poisson_ratio: f64 = 0.3,
            Float::at_least(-0.99).below(0.5).named("ν").because(
                "ν → −1 makes the in-plane problem singular"
            ),
            Unit::NONE;
        /// thickness $`h`$
        thickness => thickness: f64 = 0.05, Float::above(0.0), Unit::MM,
            note "and $`10^{-9} \\le h/\\min(L_X, L_Y) \\le 1`$";
    }

    /// Which model to solve, and its free parameters.
    [model] ModelChoice {
        /// model to solve (`wrinkle models` lists them with their fields and parameters)
        name => name: String = REFERENCE_MODEL.to_string(), ModelName, Unit::NONE;
        /// wavenumber $`Q`$ of the wrinkles, or `"auto"`: the critical load is minimised over
        /// $`Q`$ on a log scan of every wavelength from $`20h`$ to the shorter side, then refined
        /// (a biaxial scene with waves along X starts from the minimiser of eq. (42) instead of
        /// scanning, and scans only if no minimum lies near it). `pure-membrane` (no wavelength
        /// selection) and `complex-envelope` (a free phase) take the reference envelope's
        /// minimiser and say so; a plate has no wavenumber and ignores the key (with a note)
        wavenumber => wavenumber: Wavenumber = Wavenumber::Auto,
            number_or_auto::<Wavenumber>(Float::above(0.0)), Unit::PER_MM,
            note "a wavelength $`2\\pi/Q`$ from $`h`$ to $`10^6\\max(L_X, L_Y)`$";
        /// the model whose minimisation of $`\lambda_c(Q)`$ gives the wavenumber $`Q`$ to models
        /// that do not select their own (a complex envelope, the pure membrane) or whose
        /// $`\lambda_c(Q)`$ has no minimum in the search range, and the shift guess of a
        /// buckling analysis that fails about $`\lambda = 0`$ (a plate, a strip in tension); it
        /// must select its own wavelength (an envelope with gradient and no phase). Its
        /// threshold is computed once per run, only when needed (for a shift guess, only its
        /// critical load to 1e-3: the search's global level on the half mesh and one analysis
        /// on the mesh); a run of this model itself uses none
        wavenumber_model => wavenumber_model: String = REFERENCE_MODEL.to_string(),
            ModelName, Unit::NONE;
        /// angle of the wave vector from the X axis (example 2 uses 90), or `"auto"`: the angle
        /// where the threshold is lowest, searched from the principal compression direction of
        /// the pre-buckling state where the first mode lives, to 0.1° (a plate reads it from
        /// its mode; `complex-envelope` and `pure-membrane` take the `wavenumber_model`'s);
        /// the summary says which angle was chosen and how
        direction => direction: Direction = Direction::Fixed(0.0),
            number_or_auto::<Direction>(Float::at_least(-360.0).at_most(360.0)),
            Unit::DEGREES_FROM_X;
        /// model parameters by name, the table `[model.parameters]` (below)
        parameters => parameters: BTreeMap<String, f64> = BTreeMap::new(),
            Table::of(Float::finite(), "model parameters"), Unit::NONE;
        /// parameters declared `[varying]` as piecewise-linear functions of X, the table
        /// `[model.profiles]`: `NAME = [[X0, p0], [X1, p1], …]`, constant beyond the first and
        /// last points (line domains; `docs/dsl.md`)
        profiles => profiles: BTreeMap<String, Vec<[f64; 2]>> = BTreeMap::new(),
            Table::of(PointTable, "parameter profiles"), Unit::NONE;
    }

    /// Structured Q8 mesh of the rectangle.
    [mesh] MeshSpec {
        /// elements along X
        nx => elements_x: usize = 32,
            Count::between(1, MAX_ELEMENTS_PER_SIDE), Unit::NONE,
            note "and nx·ny ≤ 120000 (about the largest mesh that fits in 24 GiB), every element \
                  at most 50 times longer than wide (grading included)";
        /// elements along Y
        ny => elements_y: usize = 16, Count::between(1, MAX_ELEMENTS_PER_SIDE), Unit::NONE;
        /// ratio of the largest to the smallest element size along X and Y (geometric
        /// sizes); the smallest elements are at the edges named by `refine_toward` (by default
        /// every edge: clamped-edge layers are thin)
        grading => grading: f64 = 1.0, Float::at_least(1.0).at_most(MAX_ELEMENT_ASPECT_RATIO),
            Unit::NONE;
        /// the grading along X alone, or `"auto"`: `grading`
        grading_x => grading_x: AxisRatio = AxisRatio::Auto,
            number_or_auto::<AxisRatio>(Float::at_least(1.0).at_most(MAX_ELEMENT_ASPECT_RATIO)),
            Unit::NONE;
        /// the grading along Y alone, or `"auto"`: `grading`
        grading_y => grading_y: AxisRatio = AxisRatio::Auto,
            number_or_auto::<AxisRatio>(Float::at_least(1.0).at_most(MAX_ELEMENT_ASPECT_RATIO)),
            Unit::NONE;
        /// edges and corners the smallest elements sit at: `left`, `right` refine X toward
        /// $`X = 0`$, $`L_X`$, `bottom`, `top` refine Y toward $`Y = 0`$, $`L_Y`$, a corner
        /// (`bottom_left` …) both of its edges (a structured mesh refines toward a corner through
        /// its two edges: the smallest elements are at the corner); `"edges"`: all four. An axis
        /// with neither end named is uniform
        refine_toward => refine_toward: Vec<String> = vec!["edges".to_string()],
            ChoiceList::new(REFINE_TARGETS, "edges", "edge and corner names"), Unit::NONE,
            note "a grading along an axis with neither end named is an error";
        /// a Gmsh MSH 4.1 file (ASCII or binary) of 8-node quadrilaterals, relative to the
        /// scene file, whose physical groups name the boundaries; `""`: the structured
        /// rectangle of `geometry` with `nx`, `ny`, `grading` (which a file ignores)
        file => file: String = String::new(), OptionalPath, Unit::NONE;
    }

    /// Loading.
    [load] LoadSpec {
        /// `"biaxial"`: example 1 — tension $`N_Y`$ fixed on $`Y = 0, L_Y`$, load
        /// $`\lambda = -N_X`$ (compression on $`X = 0, L_X`$). `"strip"`: example 2 — short
        /// sides clamped, $`\lambda`$ = prescribed end displacement. Both are presets of
        /// `load.boundary` conditions (`docs/scenes.md`, "Boundaries"). `"boundaries"`: no
        /// preset, only `load.boundary`
        kind => kind: LoadKind = LoadKind::Biaxial, one_of::<LoadKind>(), Unit::NONE;
        /// tension $`N_Y`$ (biaxial only; the strip ignores it, with a note)
        tension_y => tension_y: f64 = 10.0, Float::at_least(0.0), Unit::N_PER_MM,
            note "and the tension strain $`N_Y/(Eh)`$ at most 1";
        /// conditions on named boundaries, the tables `[load.boundary.NAME]` (below): an
        /// entry replaces, part by part (`transverse`, `in_plane`), what the preset `kind`
        /// puts on that boundary; with `kind = "boundaries"` they are the whole problem
        boundary => boundary: BTreeMap<String, BoundarySpec> = BTreeMap::new(),
            Table::of(Boundary, "boundary names"), Unit::NONE;
    }

    /// Settings of the path following used by `wrinkle run`.
    [solver] SolverSpec {
        /// ANM truncation order $`N`$
        order => order: usize = 20, Count::between(2, 40), Unit::NONE;
        /// $`\varepsilon`$ in the step length $`a_{max} = (\varepsilon\|U_1\|/\|U_N\|)^{1/(N-1)}`$
        series_tolerance => series_tolerance: f64 = 1e-7,
            Float::at_least(1e-14).at_most(MAX_SERIES_TOLERANCE).because(
                "a looser series lets a step run past the validity of its truncation; a tighter \
                 one than round-off only shortens the steps"
            ),
            Unit::NONE;
        /// relative residual accepted at every point (Newton correction beyond it)
        tolerance => tolerance: f64 = 1e-6,
            Float::at_least(1e-15).at_most(1e-2).because(
                "a looser residual is not an equilibrium; a tighter one than 1e-15 no double \
                 precision solution reaches"
            ),
            Unit::NONE;
        /// maximum number of steps
        max_steps => max_steps: usize = 200, Count::between(1, MAX_STEPS), Unit::NONE;
        /// stop at this load $`\lambda`$ (the ANM evaluates its series there; Riks' first step
        /// end past it is moved back onto it by arc-length corrections); `0` = no limit
        max_load => max_load: f64 = 0.0, Float::at_least(0.0), Unit::LOAD;
        /// stop when the maximum **physical** wrinkle amplitude over the thickness reaches
        /// this: $`\max|w|/h`$ for a plate, $`2\max|w_\text{env}|/h`$ for envelope models; the
        /// path's first point past it (a Riks step end, or the ANM's next dense-output point)
        /// is moved back onto it — along the ANM step's own series, or by arc-length
        /// corrections — so that the last point lies within $`10^{-3}`$ relative above it
        max_amplitude_over_h => max_amplitude_over_thickness: f64 = 4.0,
            Float::above(0.0).at_most(100.0).because(
                "the models hold for moderate rotations, a few thicknesses of deflection"
            ),
            Unit::NONE, note "and above 2 × `perturbation`";
        /// size of the imperfection that selects the wrinkled branch (shape: `imperfection`),
        /// in thicknesses of the physical amplitude it gives on the unloaded sheet. `0`: the
        /// perfect problem, whose path stays flat on the fundamental branch past the
        /// bifurcation (unstable there) and never wrinkles: without `max_load` the run stops at
        /// its first point past $`\lambda_c`$ and says so (exit 3, `outcome_reason`); with
        /// `max_load` it follows that branch to the load asked
        perturbation => perturbation: f64 = 1e-4,
            Float::at_least(0.0).at_most(1.0).because(
                "an imperfection of more than a thickness is a wrinkled sheet, not a perturbation"
            ),
            Unit::NONE,
            note "either 0 or at least 1e-12 (smaller is the perfect problem to round-off)";
        /// `"uniform"`: the paper's uniform transverse load on the envelope,
        /// $`f = \text{perturbation}\cdot h\,DQ^4`$ (envelope models only); `"mode"`: a load
        /// shaped like the first buckling mode, $`F = \varepsilon K_0\varphi`$ ($`K_0`$ the
        /// tangent of the unloaded state), scaled so that the physical amplitude it gives on
        /// the unloaded sheet is `perturbation`·h — the same imperfection for every model;
        /// `"auto"`: uniform for envelope models, mode for the plate. `"uniform"` asked of a
        /// model without a wavenumber (the plate) is the mode, with a note; `summary.json`'s
        /// `imperfection_shape` records the shape used
        imperfection => imperfection: Imperfection = Imperfection::Auto,
            one_of::<Imperfection>(), Unit::NONE;
        /// use Padé approximants (common denominator) to lengthen ANM steps beyond the plain
        /// series' range; a Padé-lengthened step whose end has more negative pivots than its
        /// start (it jumped over a critical point) is redone with the series' range (a series
        /// step, in both methods, with half its length, up to 4 times). `false`: the classical
        /// ANM. The default is the fastest method measured on every registered model
        /// (`docs/benchmarks.md`)
        pade => pade: bool = true, Flag, Unit::NONE;
        /// re-expand an ANM step's series in $`s = \ln(1 + a/R)`$ when its last orders
        /// alternate (a singularity behind the step, at $`a = -R`$: past the knee of an
        /// imperfect path, the imperfect bifurcation left behind). That singularity limits the
        /// plain series and Padé alike to a fraction of the distance the path has come from it;
        /// in $`s`$ it is gone. The step takes the longest of the series', Padé's and this
        /// range; an end on the map must meet a tenth of the residual tolerance (`tolerance`),
        /// and one that misses it, or crosses a critical point, is shortened like a Padé end.
        /// `false`: series and Padé only (docs/benchmarks.md, "Round ten")
        exponential_map => exponential_map: bool = true, Flag, Unit::NONE;
        /// parametrise an ANM step by the change of the buckling mode's amplitude,
        /// $`a = \langle U - U_0, \varphi\rangle/\langle\varphi,\varphi\rangle`$ ($`\varphi`$ the
        /// threshold's first mode, which shapes the imperfection), where the step starts
        /// stable (no negative pivot) and its load tangent has a part along the mode (cosine
        /// at least $`10^{-3}`$); elsewhere, and when `false`, by the pseudo arc length.
        /// Through the knee of an imperfect path the load is a simple function of the mode's
        /// amplitude, with one singularity behind the step
        /// (which `exponential_map` removes), where the arc length turns with the path and
        /// adds singularities of its own: fewer steps (docs/benchmarks.md, "Round eleven").
        /// The step lengths of `summary.json`'s `anm_steps` are in the step's own parameter
        mode_parameter => mode_parameter: bool = true, Flag, Unit::NONE;
        /// `"anm"` (Asymptotic Numerical Method) or `"riks"` (Newton–Riks arc-length baseline:
        /// spherical constraint, a dimensionless arc length in units of the linear response to
        /// $`\lambda_c`$ and of $`\lambda_c`$, at most 0.3 and adapted to the Newton iterations;
        /// a step whose end has a negative pivot after a stable start, with the load still
        /// rising, jumped over the bifurcation and is halved, up to 12 times; a step changes
        /// the deflection (envelope) fields by at most $`h/4`$, so that the knee is resolved
        /// where the in-plane displacements dominate the arc length; `order`,
        /// `series_tolerance`, `pade`, `exponential_map` and `mode_parameter` unused)
        method => method: PathMethod = PathMethod::Anm, one_of::<PathMethod>(), Unit::NONE;
    }

    /// What `wrinkle run` writes.
    [output] OutputSpec {
        /// output directory (`--out DIR` overrides it): locked while a run writes it (a second
        /// run into it fails at once), written beside it and swapped in whole
        /// (docs/outputs.md)
        directory => directory: String = "out".to_string(), Text, Unit::NONE;
        /// loads $`\lambda`$ at which the fields are written as VTU (`fields_load_L.vtu`, with
        /// as many decimals as keep the names distinct); a load the path does not reach, below
        /// its start or beyond its end, gets no file and a note
        vtu_loads => vtu_loads: Vec<f64> = Vec::new(),
            FloatList::of(Float::finite()), Unit::LOAD,
            note "at most 100 loads, no two equal";
        /// draw plots (PNG and SVG, embedded in `report.html`)
        plots => plots: bool = true, Flag, Unit::NONE;
        /// a line `[X0, Y0, X1, Y1]` (mm) to sample the wrinkles along, from $`(X_0, Y_0)`$
        /// to $`(X_1, Y_1)`$: `profile_line.csv` (the physical deflection, and an envelope
        /// model's amplitude, at each profile load; empty cells outside the domain) and, with
        /// `plots`, `profile_line.png|svg`; `[]`: none
        profile_line => profile_line: Vec<f64> = Vec::new(),
            FloatList::of(Float::finite()), Unit::MM,
            note "empty or 4 numbers, the two ends distinct";
        /// write the nodal fields (`fields_final.vtu`, `fields_load_L.vtu`) with the stress
        /// resultants
        vtu => vtu: bool = true, Flag, Unit::NONE;
        /// write the reconstructed physical surface on a fine grid (`surface_final.vtu`; the
        /// largest output of envelope models)
        surface => surface: bool = true, Flag, Unit::NONE;
    }

    /// Which validity checks a scene accepts, table `[validity]`.
    [validity] ValiditySpec {
        /// checks whose failure is still reported (as a note) but does not make the exit code 4
        accept => accept: Vec<String> = Vec::new(),
            ChoiceList::new(VALIDITY_CHECKS, "all", "check names"), Unit::NONE;
    }
}

/// Other spellings of keys, still read: the older `solver.max_envelope_over_h`, and the standard
/// model parameters of `[model.parameters]`, each the key it is filled from (so that it is
/// validated, stored and echoed as that key, and every use of the value — the closed forms,
/// the imperfection, $`\max|w|/h`$ — sees the same number as the model).
static ALIASES: &[Alias] = &[
    Alias {
        key: "solver.max_envelope_over_h",
        target: "solver.max_amplitude_over_h",
        meaning: "the older key: sets `max_amplitude_over_h` to twice its value (the physical \
                  amplitude of an envelope model is $`2|w_\\text{env}|`$)",
        convert: |value| number(value).map(|half| Value::Float(2.0 * half)),
    },
    Alias {
        key: "model.parameters.young",
        target: "material.young",
        meaning: "the model parameter `young`: another spelling of `material.young`",
        convert: |value| number(value).map(Value::Float),
    },
    Alias {
        key: "model.parameters.poisson",
        target: "material.poisson",
        meaning: "the model parameter `poisson`: another spelling of `material.poisson`",
        convert: |value| number(value).map(Value::Float),
    },
    Alias {
        key: "model.parameters.thickness",
        target: "material.thickness",
        meaning: "the model parameter `thickness`: another spelling of `material.thickness`",
        convert: |value| number(value).map(Value::Float),
    },
    Alias {
        key: "model.parameters.wavenumber",
        target: "model.wavenumber",
        meaning: "the model parameter `wavenumber`: another spelling of a fixed \
                  `model.wavenumber`",
        convert: |value| number(value).map(Value::Float),
    },
    Alias {
        key: "model.parameters.direction",
        target: "model.direction",
        meaning: "the model parameter `direction`, in radians: sets `model.direction` to its value \
                  in degrees",
        convert: |value| number(value).map(|radians| Value::Float(radians.to_degrees())),
    },
];

/// A finite number (an integer is taken as a float), for the conversions of [`ALIASES`].
fn number(value: &Value) -> Result<f64, String> {
    let number = Float::finite().read(value)?;
    Float::finite().within_bounds(&number).map(|()| number)
}

/// The scene schema: the tables, the keys of [`KEYS`] and the aliases.
pub(super) static SCHEMA: Schema<Scene> = Schema {
    sections: SECTIONS,
    keys: KEY_SPECS,
    aliases: ALIASES,
};

/// Wavenumber $`Q`$ of the wrinkles.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Wavenumber {
    /// Chosen by the solver (critical wavenumber of the closed form or a scan).
    Auto,
    /// Prescribed $`Q`$ (1/mm).
    Fixed(f64),
}

impl AutoOrNumber for Wavenumber {
    const AUTO: Self = Wavenumber::Auto;

    fn fixed(number: f64) -> Self {
        Wavenumber::Fixed(number)
    }

    fn number(self) -> Option<f64> {
        match self {
            Wavenumber::Auto => None,
            Wavenumber::Fixed(number) => Some(number),
        }
    }
}

/// Direction of the wave vector of the wrinkles (`model.direction`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Direction {
    /// Chosen where the threshold is lowest (`crate::threshold`'s direction search).
    Auto,
    /// Prescribed angle from X (degrees).
    Fixed(f64),
}

impl Direction {
    /// The prescribed angle in degrees, `None` for `"auto"`.
    pub fn fixed_degrees(self) -> Option<f64> {
        self.number()
    }
}

impl AutoOrNumber for Direction {
    const AUTO: Self = Direction::Auto;

    fn fixed(number: f64) -> Self {
        Direction::Fixed(number)
    }

    fn number(self) -> Option<f64> {
        match self {
            Direction::Auto => None,
            Direction::Fixed(number) => Some(number),
        }
    }
}

scene_enum! {
    /// Kind of loading.
    pub enum LoadKind {
        /// Example 1: tension $`N_Y`$ fixed, load $`\lambda = -N_X`$ (compression, N/mm).
        Biaxial = "biaxial",
        /// Example 2: short sides clamped, $`\lambda`$ = prescribed end displacement (mm).
        Strip = "strip",
        /// No preset: the conditions and loads of `load.boundary` only.
        Boundaries = "boundaries",
    }
}

scene_enum! {
    /// The domain of a scene (`geometry.kind`).
    pub enum Domain {
        /// A plane sheet: the rectangle of `geometry`, or a mesh file.
        Plane = "plane",
        /// A beam: the segment $`[0, L_X]`$ with ends `left` and `right`.
        Line = "line",
    }
}

scene_enum! {
    /// Path-following method.
    pub enum PathMethod {
        /// Asymptotic Numerical Method (THEORY.md §10).
        Anm = "anm",
        /// Riks arc-length continuation (baseline).
        Riks = "riks",
    }
}

scene_enum! {
    /// Shape of the imperfection that selects the wrinkled branch (`solver.imperfection`).
    pub enum Imperfection {
        /// Uniform for envelope models (the paper's runs), mode-shaped for the others.
        Auto = "auto",
        /// A uniform transverse load on the envelope, $`f = \text{perturbation}\cdot h\,DQ^4`$
        /// (envelope models only; the shape of every run before mode-shaped imperfections
        /// existed).
        Uniform = "uniform",
        /// A load shaped like the first buckling mode, $`F = \varepsilon K_0\varphi`$.
        Mode = "mode",
    }
}

/// The grading ratio along one axis (`mesh.grading_x`, `mesh.grading_y`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum AxisRatio {
    /// `mesh.grading`.
    Auto,
    /// This ratio.
    Fixed(f64),
}

impl AutoOrNumber for AxisRatio {
    const AUTO: Self = AxisRatio::Auto;

    fn fixed(number: f64) -> Self {
        AxisRatio::Fixed(number)
    }

    fn number(self) -> Option<f64> {
        match self {
            AxisRatio::Auto => None,
            AxisRatio::Fixed(number) => Some(number),
        }
    }
}

impl MeshSpec {
    /// The structured rectangle's grading along X and Y: the ratio of `grading_x`,
    /// `grading_y` (or `grading`) toward the ends `refine_toward` names.
    pub fn axis_gradings(&self) -> [AxisGrading; 2] {
        let named = |name: &str| {
            self.refine_toward
                .iter()
                .any(|target| target == "edges" || target.split('_').any(|part| part == name))
        };
        let ends = |start: &str, end: &str| match (named(start), named(end)) {
            (true, true) => RefinedEnds::Both,
            (true, false) => RefinedEnds::Start,
            (false, true) => RefinedEnds::End,
            (false, false) => RefinedEnds::Neither,
        };
        let ratio = |axis: AxisRatio| axis.number().unwrap_or(self.grading);
        [
            AxisGrading {
                ratio: ratio(self.grading_x),
                ends: ends("left", "right"),
            },
            AxisGrading {
                ratio: ratio(self.grading_y),
                ends: ends("bottom", "top"),
            },
        ]
    }
}

impl ValiditySpec {
    /// Whether a failed `check` is accepted by the scene.
    pub fn accepts(&self, check: &str) -> bool {
        self.accept
            .iter()
            .any(|name| name == "all" || name == check)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_alias_sets_a_declared_key() {
        for alias in ALIASES {
            assert!(SCHEMA.spec(alias.target).is_some(), "{}", alias.key);
        }
    }

    #[test]
    fn the_mesh_note_states_the_element_limit() {
        let note = SCHEMA.spec("mesh.nx").unwrap().note;
        assert!(note.contains(&MAX_ELEMENTS.to_string()), "{note}");
    }

    #[test]
    fn keys_are_the_declarations_in_order() {
        let declared: Vec<&str> = KEY_SPECS.iter().map(|spec| spec.key).collect();
        assert_eq!(declared, KEYS);
    }
}
