//! The checks that involve more than one key: the mesh's size and shape, the thickness against
//! the sides, the wavenumber against both, the imperfection against the amplitude target, the
//! VTU loads as a set, and the products that feed the stiffness.
//!
//! **Derived products.** Each key is within its own bounds, but what the solver sees are
//! products: the membrane stiffness $`A = Eh/(1-\nu^2)`$, the bending stiffness
//! $`D = Eh^3/(12(1-\nu^2))`$, the tension strain $`N_Y/(Eh)`$. They are computed here in
//! logarithms (so that the check itself cannot overflow) and must lie in
//! [`STIFFNESS_RANGE`] (the strain at most [`MAX_TENSION_STRAIN`]); otherwise the error names
//! the key that drives the product out — among its factors, the one farthest from its default
//! in the failing direction (`material.young = 1e308` is named for $`A = \infty`$, not the
//! thickness) — instead of a NaN in a matrix entry far downstream.

use super::keys::KeyError;
use super::schema::{
    LoadKind, MAX_ELEMENT_ASPECT_RATIO, MAX_ELEMENTS, MAX_VTU_LOADS, Scene, Wavenumber,
};
use super::text::short_number;
use std::f64::consts::PI;
use wrinkle_runtime::fem::mesh::{AxisGrading, RefinedEnds};

/// Window (in the scene's units, N/mm and N·mm) of the membrane and bending stiffnesses: their
/// squares and their products with lengths and wavenumbers to the fourth stay far inside the
/// range of double precision.
pub const STIFFNESS_RANGE: (f64, f64) = (1e-60, 1e60);

/// Largest tension strain $`N_Y/(Eh)`$: the models are small-strain theories.
pub const MAX_TENSION_STRAIN: f64 = 1.0;

/// Window of $`h/\min(L_X, L_Y)`$: a sheet, not a block, and thick enough that the wavenumber
/// search's range (wavelengths from $`20h`$ to the shorter side) spans at most nine decades.
pub const THICKNESS_RATIO_RANGE: (f64, f64) = (1e-9, 1.0);

/// Longest wavelength of a fixed `model.wavenumber`, in lengths of the longer side.
pub const MAX_WAVELENGTH_OVER_SIDE: f64 = 1e6;

/// Smallest non-zero `solver.perturbation`: below it the imperfection is lost in round-off
/// and the run is the perfect problem without saying so.
pub const MIN_PERTURBATION: f64 = 1e-12;

/// Every check across keys, in the order of the keys they concern.
pub(super) fn check_across_keys(scene: &Scene) -> Result<(), KeyError> {
    check_stiffness(scene)?;
    check_thickness_ratio(scene)?;
    check_wavenumber(scene)?;
    check_domain(scene)?;
    check_tension(scene)?;
    check_imperfection(scene)?;
    check_vtu_loads(scene)?;
    check_profile_line(scene)
}

/// One factor of a derived product: the key it comes from and its base-10 logarithm, now and
/// at the key's default.
struct Factor {
    key: &'static str,
    log10: f64,
    default_log10: f64,
}

impl Factor {
    /// The factor `value^power` of `key` (its default `default`).
    fn power(key: &'static str, value: f64, default: f64, power: f64) -> Factor {
        Factor {
            key,
            log10: power * value.log10(),
            default_log10: power * default.log10(),
        }
    }
}

/// A derived product, in logarithms.
struct Product {
    /// What it is, with its formula, e.g. `the membrane stiffness E h/(1−ν²)`.
    name: &'static str,
    /// Its unit.
    unit: &'static str,
    /// Its factors; the product is $`10^{\sum \log_{10}}`$ times `constant`.
    factors: Vec<Factor>,
    /// The constant factor (1/12 for $`D`$).
    constant: f64,
    /// Why the window is what it is, quoted in the error.
    why: &'static str,
}

impl Product {
    fn log10(&self) -> f64 {
        self.constant.log10() + self.factors.iter().map(|f| f.log10).sum::<f64>()
    }

    /// An error naming the factor that drives the product above `maximum` (`too_large`) or
    /// below `minimum`, when it is out of `[minimum, maximum]`.
    fn within(&self, scene: &Scene, minimum: f64, maximum: f64) -> Result<(), KeyError> {
        let log10 = self.log10();
        let too_large = log10 > maximum.log10();
        if !too_large && log10 >= minimum.log10() {
            return Ok(());
        }
        let shift = |factor: &&Factor| factor.log10 - factor.default_log10;
        let driver = if too_large {
            self.factors
                .iter()
                .max_by(|a, b| shift(a).total_cmp(&shift(b)))
        } else {
            self.factors
                .iter()
                .min_by(|a, b| shift(a).total_cmp(&shift(b)))
        };
        let key = driver.map_or("material.young", |factor| factor.key);
        let (side, bound) = if too_large {
            ("above", maximum)
        } else {
            ("below", minimum)
        };
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        Err(KeyError::new(
            &scene.spelling_of(key),
            format!(
                "makes {} = {}{unit}, {side} {}: {}",
                self.name,
                power_of_ten(log10),
                short_number(bound),
                self.why
            ),
        ))
    }
}

/// $`10^{x}`$ as text, also where it is not a double (`1e400`).
fn power_of_ten(log10: f64) -> String {
    let value = 10f64.powf(log10);
    if value.is_finite() && value > 0.0 {
        format!("{value:.3e}")
    } else {
        let exponent = log10.floor();
        format!("{:.3}e{exponent}", 10f64.powf(log10 - exponent))
    }
}

/// Why the stiffnesses are bounded, quoted in the error.
const STIFFNESS_WHY: &str = "the stiffness matrix squares and multiplies it by lengths and wavenumbers to the fourth, which must stay inside double precision (the stiffnesses are kept within 1e-60 … 1e60)";

/// The membrane and bending stiffnesses within [`STIFFNESS_RANGE`].
fn check_stiffness(scene: &Scene) -> Result<(), KeyError> {
    let default = Scene::default();
    let (material, initial) = (&scene.material, &default.material);
    let young = |power| {
        Factor::power(
            "material.young",
            material.young_modulus,
            initial.young_modulus,
            power,
        )
    };
    let thickness = |power| {
        Factor::power(
            "material.thickness",
            material.thickness,
            initial.thickness,
            power,
        )
    };
    let squeeze = |nu: f64| 1.0 - nu * nu;
    let poisson = || {
        let (now, then) = (
            squeeze(material.poisson_ratio),
            squeeze(initial.poisson_ratio),
        );
        Factor::power("material.poisson", now, then, -1.0)
    };
    let membrane = Product {
        name: "the membrane stiffness E h/(1−ν²)",
        unit: "N/mm",
        factors: vec![young(1.0), thickness(1.0), poisson()],
        constant: 1.0,
        why: STIFFNESS_WHY,
    };
    let bending = Product {
        name: "the bending stiffness D = E h³/(12(1−ν²))",
        unit: "N·mm",
        factors: vec![young(1.0), thickness(3.0), poisson()],
        constant: 1.0 / 12.0,
        why: STIFFNESS_WHY,
    };
    let (minimum, maximum) = STIFFNESS_RANGE;
    membrane.within(scene, minimum, maximum)?;
    bending.within(scene, minimum, maximum)
}

/// $`h/\min(L_X, L_Y)`$ within [`THICKNESS_RATIO_RANGE`].
fn check_thickness_ratio(scene: &Scene) -> Result<(), KeyError> {
    let shorter = scene.geometry.length_x.min(scene.geometry.length_y);
    let ratio = scene.material.thickness / shorter;
    let (minimum, maximum) = THICKNESS_RATIO_RANGE;
    if (minimum..=maximum).contains(&ratio) {
        return Ok(());
    }
    let side = if scene.geometry.length_x <= scene.geometry.length_y {
        "geometry.lx"
    } else {
        "geometry.ly"
    };
    let default = Scene::default();
    let thickness_shift = (scene.material.thickness / default.material.thickness).log10();
    let side_shift = (shorter / default.geometry.length_y).log10();
    let thickness_drives = if ratio > maximum {
        thickness_shift >= -side_shift
    } else {
        thickness_shift <= -side_shift
    };
    let key = if thickness_drives {
        "material.thickness"
    } else {
        side
    };
    Err(KeyError::new(
        &scene.spelling_of(key),
        format!(
            "the thickness over the shorter side, h/min(L_X, L_Y) = {} / {} = {:.3e}, must lie between {} (below it the wavenumber search spans more than nine decades) and {} (a sheet, not a block)",
            short_number(scene.material.thickness),
            short_number(shorter),
            ratio,
            short_number(minimum),
            short_number(maximum)
        ),
    ))
}

/// A fixed wavelength $`2\pi/Q`$ between $`h`$ and [`MAX_WAVELENGTH_OVER_SIDE`] times the longer
/// side.
fn check_wavenumber(scene: &Scene) -> Result<(), KeyError> {
    let Wavenumber::Fixed(q) = scene.model.wavenumber else {
        return Ok(());
    };
    let wavelength = 2.0 * PI / q;
    let thickness = scene.material.thickness;
    let longest = scene.geometry.length_x.max(scene.geometry.length_y) * MAX_WAVELENGTH_OVER_SIDE;
    if wavelength >= thickness && wavelength <= longest {
        return Ok(());
    }
    Err(KeyError::new(
        &scene.spelling_of("model.wavenumber"),
        format!(
            "Q = {} 1/mm is a wavelength 2π/Q = {wavelength:.3e} mm; it must lie between the thickness h = {} mm and {} times the longer side ({longest:.3e} mm)",
            short_number(q),
            short_number(thickness),
            short_number(MAX_WAVELENGTH_OVER_SIDE)
        ),
    ))
}

/// At most [`MAX_ELEMENTS`] elements, none longer than [`MAX_ELEMENT_ASPECT_RATIO`] times its
/// width.
/// A plane's mesh ([`check_mesh`]); profiles only on a line (the plane pipeline does not apply
/// them yet).
fn check_domain(scene: &Scene) -> Result<(), KeyError> {
    match scene.geometry.domain {
        super::Domain::Plane if !scene.model.profiles.is_empty() => Err(KeyError::new(
            "model.profiles",
            "parameter profiles are applied on line domains (geometry.kind = \"line\") only",
        )),
        super::Domain::Plane => check_mesh(scene),
        super::Domain::Line => Ok(()),
    }
}

fn check_mesh(scene: &Scene) -> Result<(), KeyError> {
    let (elements_x, elements_y) = (scene.mesh.elements_x, scene.mesh.elements_y);
    let elements = elements_x.saturating_mul(elements_y);
    if elements > MAX_ELEMENTS {
        return Err(KeyError::new(
            "mesh.nx",
            format!(
                "mesh.nx × mesh.ny = {elements_x} × {elements_y} = {elements} elements is more than the {MAX_ELEMENTS} this tool solves in 24 GiB"
            ),
        ));
    }
    check_grading_ends(scene)?;
    let [grading_x, grading_y] = scene.mesh.axis_gradings();
    let sizes = |length: f64, count: usize, grading: AxisGrading| {
        let breakpoints = grading.breakpoints(length, count);
        let widths = breakpoints.windows(2).map(|pair| pair[1] - pair[0]);
        widths.fold((f64::INFINITY, 0.0f64), |(low, high), w| {
            (low.min(w), high.max(w))
        })
    };
    let (shortest_x, longest_x) = sizes(scene.geometry.length_x, elements_x, grading_x);
    let (shortest_y, longest_y) = sizes(scene.geometry.length_y, elements_y, grading_y);
    let along_x = longest_x / shortest_y;
    let along_y = longest_y / shortest_x;
    let aspect = along_x.max(along_y);
    if aspect <= MAX_ELEMENT_ASPECT_RATIO * (1.0 + 1e-12) {
        return Ok(());
    }
    let given = |key: &str, ratio: f64| ratio > 1.0 && scene.was_given(key);
    let key = if given("mesh.grading_x", grading_x.ratio) {
        "mesh.grading_x"
    } else if given("mesh.grading_y", grading_y.ratio) {
        "mesh.grading_y"
    } else if given("mesh.grading", scene.mesh.grading) {
        "mesh.grading"
    } else if along_x >= along_y {
        "mesh.nx"
    } else {
        "mesh.ny"
    };
    Err(KeyError::new(
        key,
        format!(
            "the {} × {} mesh of the {} × {} mm rectangle (grading {}) has elements {aspect:.3e} times longer than wide; at most {} is solved (more elements along the long side of the elements, or fewer across)",
            elements_x,
            elements_y,
            short_number(scene.geometry.length_x),
            short_number(scene.geometry.length_y),
            grading_text(grading_x.ratio, grading_y.ratio),
            short_number(MAX_ELEMENT_ASPECT_RATIO)
        ),
    ))
}

/// `1.5`, or `1.5 along X, 3 along Y` when the axes differ.
fn grading_text(along_x: f64, along_y: f64) -> String {
    if along_x == along_y {
        short_number(along_x)
    } else {
        format!(
            "{} along X, {} along Y",
            short_number(along_x),
            short_number(along_y)
        )
    }
}

/// A grading above 1 along an axis that `mesh.refine_toward` does not refine (neither of its
/// ends named) would be silently ignored: an error naming the grading key.
fn check_grading_ends(scene: &Scene) -> Result<(), KeyError> {
    let gradings = scene.mesh.axis_gradings();
    let axes = [
        ("mesh.grading_x", "X", "left", "right"),
        ("mesh.grading_y", "Y", "bottom", "top"),
    ];
    for (grading, (key, axis, start, end)) in gradings.iter().zip(axes) {
        if grading.ratio <= 1.0 || grading.ends != RefinedEnds::Neither {
            continue;
        }
        let key = if scene.was_given(key) {
            key
        } else {
            "mesh.grading"
        };
        return Err(KeyError::new(
            key,
            format!(
                "grading {} along {axis}, but mesh.refine_toward = {:?} names neither `{start}` nor `{end}` (nor a corner on them): it would refine nothing along {axis}; name an end, or set mesh.grading_{} = 1",
                short_number(grading.ratio),
                scene.mesh.refine_toward,
                axis.to_lowercase()
            ),
        ));
    }
    Ok(())
}

/// The tension strain $`N_Y/(Eh)`$ of the biaxial load at most [`MAX_TENSION_STRAIN`].
fn check_tension(scene: &Scene) -> Result<(), KeyError> {
    if scene.load.kind != LoadKind::Biaxial || scene.load.tension_y == 0.0 {
        return Ok(());
    }
    let default = Scene::default();
    let strain = Product {
        name: "the tension strain N_Y/(E h)",
        unit: "",
        factors: vec![
            Factor::power(
                "load.tension_y",
                scene.load.tension_y,
                default.load.tension_y,
                1.0,
            ),
            Factor::power(
                "material.young",
                scene.material.young_modulus,
                default.material.young_modulus,
                -1.0,
            ),
            Factor::power(
                "material.thickness",
                scene.material.thickness,
                default.material.thickness,
                -1.0,
            ),
        ],
        constant: 1.0,
        why: "the models are small-strain theories",
    };
    strain.within(scene, 0.0, MAX_TENSION_STRAIN)
}

/// A perturbation of 0 (the perfect problem) or at least [`MIN_PERTURBATION`], and an
/// imperfection (of nominal physical amplitude at most $`2\,\text{perturbation}\cdot h`$)
/// below the amplitude target.
fn check_imperfection(scene: &Scene) -> Result<(), KeyError> {
    let solver = &scene.solver;
    let perturbation = solver.perturbation;
    if perturbation > 0.0 && perturbation < MIN_PERTURBATION {
        return Err(KeyError::new(
            "solver.perturbation",
            format!(
                "must be 0 (the perfect problem) or at least {}: an imperfection of {} thicknesses is lost in round-off, got {}",
                short_number(MIN_PERTURBATION),
                short_number(perturbation),
                short_number(perturbation)
            ),
        ));
    }
    let target = solver.max_amplitude_over_thickness;
    if 2.0 * perturbation < target {
        return Ok(());
    }
    let key = if scene.was_given("solver.max_amplitude_over_h") {
        scene.spelling_of("solver.max_amplitude_over_h")
    } else {
        "solver.perturbation".to_string()
    };
    Err(KeyError::new(
        &key,
        format!(
            "the amplitude target max |w|/h = {} is not above the imperfection (solver.perturbation = {}, a physical amplitude of up to 2 × {} thicknesses): the unloaded sheet would already be at the target",
            short_number(target),
            short_number(perturbation),
            short_number(perturbation)
        ),
    ))
}

/// `output.profile_line`: none, or two distinct end points.
fn check_profile_line(scene: &Scene) -> Result<(), KeyError> {
    let line = &scene.output.profile_line;
    let message = match line.len() {
        0 => return Ok(()),
        4 if line[0] == line[2] && line[1] == line[3] => format!(
            "both ends are ({}, {}) mm: a line needs two distinct end points",
            short_number(line[0]),
            short_number(line[1])
        ),
        4 => return Ok(()),
        count => format!(
            "{count} numbers given; a line is [X0, Y0, X1, Y1] (mm), 4 numbers, or [] for none"
        ),
    };
    Err(KeyError::new("output.profile_line", message))
}

/// At most [`MAX_VTU_LOADS`] loads, no two equal (they would write one file).
fn check_vtu_loads(scene: &Scene) -> Result<(), KeyError> {
    let loads = &scene.output.vtu_loads;
    if loads.len() > MAX_VTU_LOADS {
        return Err(KeyError::new(
            "output.vtu_loads",
            format!(
                "{} loads asked, at most {MAX_VTU_LOADS} (each writes the fields of the whole mesh)",
                loads.len()
            ),
        ));
    }
    for (index, load) in loads.iter().enumerate() {
        if let Some(first) = loads[..index].iter().position(|other| other == load) {
            return Err(KeyError::new(
                "output.vtu_loads",
                format!(
                    "item {index}: {} repeats item {first}: each load writes one file",
                    short_number(*load)
                ),
            ));
        }
    }
    Ok(())
}
