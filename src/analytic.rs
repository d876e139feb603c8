//! The `wrinkle analytic` command: every closed-form result of the clamped rectangle in biaxial
//! load (THEORY.md §8) for one scene, plus a converged multi-term Galerkin solution of the
//! post-bifurcation stress-function problem (55) and, on request, the paper's Table 1.
//!
//! [`analyse`] checks that the scene has a closed form and computes an [`AnalyticReport`];
//! [`AnalyticReport::to_json`] and [`AnalyticReport::summary`] print it. The meaning, unit and
//! equation of every JSON key is listed in `docs/analytic.md`.

use crate::closed_form::stress_function::{self, StressFunctionConvergence};
use crate::closed_form::{self, ClampedRectangle, GalerkinIntegrals};
use crate::error::Error;
use crate::scene::{Direction, LoadKind, Scene, Wavenumber};
use serde_json::{Value, json};
use std::fmt::Write as _;

/// The only registered model whose linearised envelope equation is (32), i.e. that has the
/// closed forms of THEORY.md §8: the registry's reference model (THEORY.md §4).
pub const CLOSED_FORM_MODEL: &str = wrinkle_models::REFERENCE_MODEL;

/// Load ratios $`\lambda/\lambda_c`$ of the amplitude curve: $`1, 1.05, \ldots, 2`$.
pub const AMPLITUDE_CURVE_POINTS: usize = 21;

/// Table 1 of the paper: $`N_Y`$ (N/mm), printed $`N_X^{wr}`$ (N/mm), printed
/// $`L_X/\ell_{wr}`$, printed $`a/h`$ at $`N_X = 2N_X^{wr}`$; $`L_X = L_Y = 200`$ mm,
/// $`h = 0.05`$ mm, $`E = 70000`$ MPa, printed $`\nu = 0`$.
// 6.28 is the printed L_X/ℓ of the first row, not an approximation of τ.
#[allow(clippy::approx_constant)]
pub const TABLE_ONE_PRINTED: [(f64, f64, f64, f64); 4] = [
    (5.0, -0.064, 6.28, 1.66),
    (10.0, -0.090, 7.48, 1.66),
    (15.0, -0.110, 8.28, 1.66),
    (20.0, -0.127, 8.90, 1.66),
];

/// What [`analyse`] computes besides the scene's own results.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnalyticOptions {
    /// Also reproduce the paper's Table 1 (independent of the scene).
    pub table_1: bool,
    /// Largest number of Galerkin basis functions per direction for (55).
    pub max_terms_per_direction: usize,
    /// Relative change of $`C`$ at which the Galerkin sequence stops (twice in a row).
    pub relative_tolerance: f64,
}

impl Default for AnalyticOptions {
    fn default() -> Self {
        AnalyticOptions {
            table_1: false,
            max_terms_per_direction: stress_function::DEFAULT_MAX_TERMS_PER_DIRECTION,
            relative_tolerance: stress_function::DEFAULT_RELATIVE_TOLERANCE,
        }
    }
}

/// Closed-form results for one clamped rectangle.
#[derive(Clone, Debug, PartialEq)]
pub struct AnalyticReport {
    /// The rectangle the formulas were evaluated for.
    pub rectangle: ClampedRectangle,
    /// $`D`$ (N·mm).
    pub bending_stiffness: f64,
    /// Exact minimum $`\lambda_c`$ of (42) (N/mm).
    pub critical_load_exact: f64,
    /// Its minimiser $`Q_c`$ (1/mm).
    pub wavenumber_exact: f64,
    /// $`\lambda_0 = 2DQ_{wr}^2`$ of (44) (N/mm).
    pub critical_load_eq44: f64,
    /// $`Q_{wr}`$ of (44) (1/mm).
    pub wavenumber_eq44: f64,
    /// $`|\sigma_X^{wr}|`$ of (44) (MPa).
    pub wrinkling_stress_eq44: f64,
    /// $`|\sigma_X^{wr2}|`$ of (96) (MPa).
    pub wrinkling_stress_eq96: f64,
    /// $`\lambda(Q)`$ of (42) at the scene's fixed `model.wavenumber`, if it is fixed (N/mm).
    pub critical_load_at_scene_wavenumber: Option<f64>,
    /// $`I_1(\alpha), \ldots, I_4`$ in closed form.
    pub integrals: GalerkinIntegrals,
    /// One-term $`C(\alpha)`$ of (62).
    pub amplitude_coefficient: f64,
    /// Multi-term Galerkin solutions of (55).
    pub convergence: StressFunctionConvergence,
    /// Table 1, when requested.
    pub table_1: Option<Vec<TableOneRow>>,
}

/// One row of Table 1, printed and computed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TableOneRow {
    /// $`N_Y`$ (N/mm).
    pub tension_y: f64,
    /// Printed $`N_X^{wr}`$ (N/mm).
    pub printed_n_x: f64,
    /// $`N_X^{wr} = -\lambda_c`$, exact minimum of (42), $`\nu = 0.3`$ (N/mm).
    pub n_x: f64,
    /// The same with the printed $`\nu = 0`$ (N/mm).
    pub n_x_poisson_zero: f64,
    /// Printed $`L_X/\ell_{wr}`$.
    pub printed_length_x_over_wavelength: f64,
    /// $`L_X Q_c/(2\pi)`$, $`\nu = 0.3`$.
    pub length_x_over_wavelength: f64,
    /// The same with $`\nu = 0`$.
    pub length_x_over_wavelength_poisson_zero: f64,
    /// Printed envelope $`a/h`$ at $`N_X = 2N_X^{wr}`$.
    pub printed_amplitude: f64,
    /// One-term (62) at $`\lambda/\lambda_c = 2`$: $`C(1)`$, $`\nu = 0.3`$.
    pub amplitude_one_term: f64,
    /// Converged Galerkin solution of (55) at $`\lambda/\lambda_c = 2`$, $`\nu = 0.3`$.
    pub amplitude_converged: f64,
    /// One-term (62) with the ratio taken to $`\lambda_0`$ of (44) instead of the exact
    /// $`\lambda_c`$: $`C(1)\sqrt{2\lambda_c/\lambda_0 - 1}`$, $`\nu = 0.3`$.
    pub amplitude_one_term_eq44_reference: f64,
}

/// The clamped rectangle of a scene that has a closed form, or a scene error naming the key
/// that rules it out (`load.kind`, `model.name`, `model.direction`, `load.tension_y`).
pub fn closed_form_rectangle(scene: &Scene) -> Result<ClampedRectangle, Error> {
    if scene.load.kind != LoadKind::Biaxial {
        return Err(Error::scene(
            scene.origin_of("load.kind"),
            "load.kind",
            format!(
                "the analytic command needs \"biaxial\" (the clamped rectangle of THEORY.md §8); \
                 \"{}\" has no closed form",
                scene.load.kind.as_str()
            ),
        ));
    }
    if scene.model.name != CLOSED_FORM_MODEL {
        return Err(Error::scene(
            scene.origin_of("model.name"),
            "model.name",
            format!(
                "the closed forms (42)–(62) are those of \"{CLOSED_FORM_MODEL}\"; model \"{}\" \
                 has none",
                scene.model.name
            ),
        ));
    }
    if scene.model.direction != Direction::Fixed(0.0) {
        return Err(Error::scene(
            scene.origin_of("model.direction"),
            "model.direction",
            format!(
                "the closed forms assume the wave vector along X (0 degrees), got {}",
                scene
                    .model
                    .direction
                    .fixed_degrees()
                    .map_or_else(|| "\"auto\"".to_string(), |d| d.to_string())
            ),
        ));
    }
    let rectangle = scene.clamped_rectangle();
    if rectangle.critical_point().is_none() {
        let threshold = rectangle.bending_stiffness() * std::f64::consts::PI.powi(2)
            / rectangle.length_x.powi(2)
            * (6.0 * (rectangle.length_y / rectangle.length_x).powi(2) + 2.0);
        return Err(Error::scene(
            scene.origin_of("load.tension_y"),
            "load.tension_y",
            format!(
                "(42) has a wrinkling minimum only for N_Y > {threshold:.6e} N/mm, got {}",
                rectangle.tension_y
            ),
        ));
    }
    Ok(rectangle)
}

/// Computes every closed-form result for `scene` (see the module documentation).
pub fn analyse(scene: &Scene, options: &AnalyticOptions) -> Result<AnalyticReport, Error> {
    let rectangle = closed_form_rectangle(scene)?;
    let (critical_load_exact, wavenumber_exact) = rectangle
        .critical_point()
        .expect("checked by closed_form_rectangle");
    let convergence = converge(&rectangle, options)?;
    let table_1 = if options.table_1 {
        Some(table_one(options)?)
    } else {
        None
    };
    Ok(AnalyticReport {
        rectangle,
        bending_stiffness: rectangle.bending_stiffness(),
        critical_load_exact,
        wavenumber_exact,
        critical_load_eq44: rectangle.approximate_critical_load(),
        wavenumber_eq44: rectangle.approximate_wavenumber(),
        wrinkling_stress_eq44: rectangle.approximate_wrinkling_stress(),
        wrinkling_stress_eq96: rectangle.corrected_wrinkling_stress(),
        critical_load_at_scene_wavenumber: match scene.model.wavenumber {
            Wavenumber::Fixed(wavenumber) => Some(rectangle.neutral_curve(wavenumber)),
            Wavenumber::Auto => None,
        },
        integrals: closed_form::galerkin_integrals(rectangle.aspect_ratio()),
        amplitude_coefficient: rectangle.amplitude_coefficient(),
        convergence,
        table_1,
    })
}

fn converge(
    rectangle: &ClampedRectangle,
    options: &AnalyticOptions,
) -> Result<StressFunctionConvergence, Error> {
    stress_function::converge(
        rectangle.aspect_ratio(),
        rectangle.poisson_ratio,
        options.max_terms_per_direction,
        options.relative_tolerance,
    )
    .map_err(Error::Solver)
}

/// Table 1 recomputed: exact minimum of (42) with $`\nu = 0.3`$ and $`\nu = 0`$, and the
/// envelope $`a/h`$ at $`\lambda/\lambda_c = 2`$, one-term and converged.
pub fn table_one(options: &AnalyticOptions) -> Result<Vec<TableOneRow>, Error> {
    let rectangle = |tension_y: f64, poisson_ratio: f64| ClampedRectangle {
        length_x: 200.0,
        length_y: 200.0,
        thickness: 0.05,
        young_modulus: 70000.0,
        poisson_ratio,
        tension_y,
    };
    let converged = converge(&rectangle(10.0, 0.3), options)?
        .converged()
        .amplitude_coefficient;
    let mut rows = Vec::new();
    for (tension_y, printed_n_x, printed_ratio, printed_amplitude) in TABLE_ONE_PRINTED {
        let used = rectangle(tension_y, 0.3);
        let zero = rectangle(tension_y, 0.0);
        let (load, wavenumber) = used.critical_point().expect("Table 1 wrinkles");
        let (load_zero, wavenumber_zero) = zero.critical_point().expect("Table 1 wrinkles");
        let one_term = used.amplitude_coefficient();
        rows.push(TableOneRow {
            tension_y,
            printed_n_x,
            n_x: -load,
            n_x_poisson_zero: -load_zero,
            printed_length_x_over_wavelength: printed_ratio,
            length_x_over_wavelength: used.length_x / closed_form::wavelength(wavenumber),
            length_x_over_wavelength_poisson_zero: zero.length_x
                / closed_form::wavelength(wavenumber_zero),
            printed_amplitude,
            amplitude_one_term: one_term * (2.0f64 - 1.0).sqrt(),
            amplitude_converged: converged * (2.0f64 - 1.0).sqrt(),
            amplitude_one_term_eq44_reference: one_term
                * (2.0 * load / used.approximate_critical_load() - 1.0).sqrt(),
        });
    }
    Ok(rows)
}

impl AnalyticReport {
    /// $`h\,|\sigma_X^{wr2}|`$ of (96) (N/mm).
    pub fn critical_load_eq96(&self) -> f64 {
        self.wrinkling_stress_eq96 * self.rectangle.thickness
    }

    /// Converged $`C`$ of the multi-term Galerkin solution of (55).
    pub fn amplitude_coefficient_converged(&self) -> f64 {
        self.convergence.converged().amplitude_coefficient
    }

    /// $`(\lambda/\lambda_c,\ a/h)`$ on [`AMPLITUDE_CURVE_POINTS`] equally spaced ratios from 1
    /// to 2, $`a/h = C\sqrt{\lambda/\lambda_c - 1}`$ (62), `a` the envelope amplitude.
    pub fn amplitude_curve(&self, coefficient: f64) -> Vec<[f64; 2]> {
        (0..AMPLITUDE_CURVE_POINTS)
            .map(|index| {
                let ratio = 1.0 + index as f64 / (AMPLITUDE_CURVE_POINTS - 1) as f64;
                [ratio, coefficient * (ratio - 1.0).sqrt()]
            })
            .collect()
    }

    /// The report as one JSON object (keys documented in `docs/analytic.md`).
    pub fn to_json(&self, scene: &Scene) -> Value {
        let r = &self.rectangle;
        let wavelength_exact = closed_form::wavelength(self.wavenumber_exact);
        let one_term = self.amplitude_coefficient;
        let converged = self.amplitude_coefficient_converged();
        let physical = |curve: Vec<[f64; 2]>| -> Vec<[f64; 2]> {
            curve.into_iter().map(|[x, a]| [x, 2.0 * a]).collect()
        };
        let changes = stress_function::relative_changes(&self.convergence.solutions);
        let convergence: Vec<Value> = self
            .convergence
            .solutions
            .iter()
            .enumerate()
            .map(|(index, solution)| {
                json!({
                    "terms_per_direction": solution.terms_per_direction,
                    "terms": solution.terms,
                    "load_integral": solution.load_integral,
                    "amplitude_coefficient": solution.amplitude_coefficient,
                    "relative_change": index.checked_sub(1).map(|previous| changes[previous]),
                })
            })
            .collect();
        json!({
            "model": CLOSED_FORM_MODEL,
            "load_kind": LoadKind::Biaxial.as_str(),
            "bending_stiffness": self.bending_stiffness,
            "aspect_ratio": r.aspect_ratio(),
            "critical_load_exact": self.critical_load_exact,
            "n_x_exact": -self.critical_load_exact,
            "wavenumber_exact": self.wavenumber_exact,
            "wavelength_exact": wavelength_exact,
            "length_x_over_wavelength": r.length_x / wavelength_exact,
            "critical_load_eq44": self.critical_load_eq44,
            "wavenumber_eq44": self.wavenumber_eq44,
            "wavelength_eq44": closed_form::wavelength(self.wavenumber_eq44),
            "length_x_over_wavelength_eq44": r.length_x / closed_form::wavelength(self.wavenumber_eq44),
            "wrinkling_stress_eq44": self.wrinkling_stress_eq44,
            "wrinkling_stress_exact": self.critical_load_exact / r.thickness,
            "critical_load_eq96": self.critical_load_eq96(),
            "wrinkling_stress_eq96": self.wrinkling_stress_eq96,
            "critical_load_at_scene_wavenumber": self.critical_load_at_scene_wavenumber,
            "galerkin_integrals": {
                "i1": self.integrals.i1,
                "i2": self.integrals.i2,
                "i3": self.integrals.i3,
                "i4": self.integrals.i4,
            },
            "amplitude_coefficient": one_term,
            "amplitude_coefficient_converged": converged,
            "amplitude_coefficient_convergence": convergence,
            "amplitude_coefficient_convergence_stop": self.convergence.stop.as_str(),
            "amplitude_coefficient_convergence_tolerance": self.convergence.relative_tolerance,
            "amplitude_curve": self.amplitude_curve(one_term),
            "amplitude_curve_physical": physical(self.amplitude_curve(one_term)),
            "amplitude_curve_converged": self.amplitude_curve(converged),
            "table_1": self.table_1.as_ref().map(|rows| table_one_json(rows)),
            "scene": scene.echo_json(),
        })
    }

    /// The human summary: a table of thresholds with units, the Galerkin convergence and the
    /// amplitude curve (and Table 1 when computed).
    pub fn summary(&self, scene: &Scene) -> String {
        let r = &self.rectangle;
        let mut text = String::new();
        let _ = writeln!(
            text,
            "scene: {}\nclamped rectangle (THEORY.md §8): L_X = {} mm, L_Y = {} mm, h = {} mm, \
             E = {} MPa, ν = {}, N_Y = {} N/mm\nD = {:.6e} N·mm, α = L_Y/L_X = {}\n",
            scene.source,
            r.length_x,
            r.length_y,
            r.thickness,
            r.young_modulus,
            r.poisson_ratio,
            r.tension_y,
            self.bending_stiffness,
            r.aspect_ratio()
        );
        self.write_thresholds(&mut text);
        self.write_amplitudes(&mut text);
        if let Some(rows) = &self.table_1 {
            write_table_one(&mut text, rows);
        }
        text
    }

    fn write_thresholds(&self, text: &mut String) {
        let r = &self.rectangle;
        let exact_wavelength = closed_form::wavelength(self.wavenumber_exact);
        let eq44_wavelength = closed_form::wavelength(self.wavenumber_eq44);
        let _ = writeln!(
            text,
            "wrinkling threshold        {:>16} {:>16} {:>16}",
            "exact min (42)", "approx. (44)", "corrected (96)"
        );
        let row = |text: &mut String, name: &str, values: [Option<f64>; 3]| {
            let cells: Vec<String> = values
                .iter()
                .map(|value| value.map_or("–".to_string(), |v| format!("{v:.9e}")))
                .collect();
            let _ = writeln!(
                text,
                "{name:<26} {:>16} {:>16} {:>16}",
                cells[0], cells[1], cells[2]
            );
        };
        row(
            text,
            "λ_c = −N_X (N/mm)",
            [
                Some(self.critical_load_exact),
                Some(self.critical_load_eq44),
                Some(self.critical_load_eq96()),
            ],
        );
        row(
            text,
            "|σ_X| (MPa)",
            [
                Some(self.critical_load_exact / r.thickness),
                Some(self.wrinkling_stress_eq44),
                Some(self.wrinkling_stress_eq96),
            ],
        );
        row(
            text,
            "Q (1/mm)",
            [
                Some(self.wavenumber_exact),
                Some(self.wavenumber_eq44),
                None,
            ],
        );
        row(
            text,
            "wavelength 2π/Q (mm)",
            [Some(exact_wavelength), Some(eq44_wavelength), None],
        );
        row(
            text,
            "L_X / wavelength",
            [
                Some(r.length_x / exact_wavelength),
                Some(r.length_x / eq44_wavelength),
                None,
            ],
        );
        if let Some(load) = self.critical_load_at_scene_wavenumber {
            let _ = writeln!(
                text,
                "(42) at the scene's fixed wavenumber: λ = {load:.9e} N/mm"
            );
        }
    }

    fn write_amplitudes(&self, text: &mut String) {
        let i = &self.integrals;
        let _ = writeln!(
            text,
            "\nGalerkin integrals (closed form, dimensionless): I_1 = {:.12e}, I_2 = {:.12e}, \
             I_3 = {}, I_4 = {:.12e}",
            i.i1, i.i2, i.i3, i.i4
        );
        let _ = writeln!(
            text,
            "amplitude coefficient C (dimensionless; a/h = C √(λ/λ_c − 1), a = envelope):\n  \
             one-term (62): {:.10}\n  converged Galerkin of (55): {:.10} ({}, {} terms)",
            self.amplitude_coefficient,
            self.amplitude_coefficient_converged(),
            self.convergence.stop.as_str(),
            self.convergence.converged().terms
        );
        let _ = writeln!(
            text,
            "  {:>6} {:>22} {:>16} {:>14}",
            "terms", "J (replaces I2·I4/I1)", "C", "rel. change"
        );
        let changes = stress_function::relative_changes(&self.convergence.solutions);
        for (index, solution) in self.convergence.solutions.iter().enumerate() {
            let change = index.checked_sub(1).map_or("–".to_string(), |previous| {
                format!("{:.2e}", changes[previous])
            });
            let _ = writeln!(
                text,
                "  {:>6} {:>22.15e} {:>16.12} {:>14}",
                solution.terms, solution.load_integral, solution.amplitude_coefficient, change
            );
        }
        let _ = writeln!(
            text,
            "\namplitude curve (62): envelope a/h (dimensionless); the physical peak deflection is 2a"
        );
        let _ = writeln!(
            text,
            "  {:>7} {:>16} {:>16} {:>16}",
            "λ/λ_c", "a/h one-term", "2a/h physical", "a/h converged"
        );
        let converged = self.amplitude_curve(self.amplitude_coefficient_converged());
        for (point, converged_point) in self
            .amplitude_curve(self.amplitude_coefficient)
            .iter()
            .zip(&converged)
            .step_by(2)
        {
            let _ = writeln!(
                text,
                "  {:>7.3} {:>16.6} {:>16.6} {:>16.6}",
                point[0],
                point[1],
                2.0 * point[1],
                converged_point[1]
            );
        }
    }
}

fn table_one_json(rows: &[TableOneRow]) -> Value {
    let rows: Vec<Value> = rows
        .iter()
        .map(|row| {
            json!({
                "tension_y": row.tension_y,
                "printed_n_x_wr": row.printed_n_x,
                "n_x_wr": row.n_x,
                "n_x_wr_poisson_zero": row.n_x_poisson_zero,
                "printed_length_x_over_wavelength": row.printed_length_x_over_wavelength,
                "length_x_over_wavelength": row.length_x_over_wavelength,
                "length_x_over_wavelength_poisson_zero": row.length_x_over_wavelength_poisson_zero,
                "printed_amplitude_over_thickness": row.printed_amplitude,
                "amplitude_over_thickness_one_term": row.amplitude_one_term,
                "amplitude_over_thickness_converged": row.amplitude_converged,
                "amplitude_over_thickness_one_term_eq44_reference": row.amplitude_one_term_eq44_reference,
            })
        })
        .collect();
    json!({
        "geometry": { "lx": 200.0, "ly": 200.0 },
        "material": { "young": 70000.0, "thickness": 0.05, "poisson_printed": 0.0, "poisson_used": 0.3 },
        "note": "N_X^wr and L_X/ℓ are reproduced with ν = 0.3, not the printed ν = 0; a/h is the envelope amplitude at N_X = 2 N_X^wr",
        "rows": rows,
    })
}

fn write_table_one(text: &mut String, rows: &[TableOneRow]) {
    let _ = writeln!(
        text,
        "\nTable 1 of the paper (L_X = L_Y = 200 mm, h = 0.05 mm, E = 70000 MPa): printed vs \
         computed; the table says ν = 0 but is reproduced with ν = 0.3"
    );
    let _ = writeln!(
        text,
        "  {:>4} | {:>7} {:>9} {:>9} | {:>6} {:>7} {:>7} | {:>5} {:>8} {:>9}",
        "N_Y",
        "N_X^wr",
        "ν = 0.3",
        "ν = 0",
        "L_X/ℓ",
        "ν = 0.3",
        "ν = 0",
        "a/h",
        "one-term",
        "converged"
    );
    let _ = writeln!(
        text,
        "  {:>4} | {:>7} {:>9} {:>9} | {:>6} {:>7} {:>7} | {:>5} {:>8} {:>9}",
        "N/mm", "printed", "N/mm", "N/mm", "print.", "", "", "print", "ν = 0.3", "ν = 0.3"
    );
    for row in rows {
        let _ = writeln!(
            text,
            "  {:>4} | {:>7.3} {:>9.5} {:>9.5} | {:>6.2} {:>7.4} {:>7.4} | {:>5.2} {:>8.4} {:>9.4}",
            row.tension_y,
            row.printed_n_x,
            row.n_x,
            row.n_x_poisson_zero,
            row.printed_length_x_over_wavelength,
            row.length_x_over_wavelength,
            row.length_x_over_wavelength_poisson_zero,
            row.printed_amplitude,
            row.amplitude_one_term,
            row.amplitude_converged
        );
    }
}
