//! Figures of a run besides the response, the profiles and the whole-domain wrinkle map (those
//! are in [`crate::run_outputs`]): zooms of the wrinkle map on the wrinkled zones of a long
//! domain (the strip's map is a thin ribbon), the pre-buckling membrane forces
//! $`N_X, N_Y`$ that explain where the sheet wrinkles, and the profiles along the user's line
//! (`output.profile_line`: CSV and plot).
//!
//! On a domain that is not the rectangle of its bounding box (a mesh file with a hole or a
//! curved outline) every map is masked: samples outside the mesh are NaN, drawn white, and the
//! mesh's outline is drawn over the field ([`domain_sampler`], [`map_outline`]).
//!
//! Like every writer, nothing here recomputes a result: the states and their stress resultants
//! come from the [`Trace`]; the figures only sample and draw them.

use crate::error::{Error, io_error};
use crate::output::{
    GridField, Profile, ProfilePlot, Quantity, WrinkleMap, plot_profiles, plot_wrinkle_map,
    write_bytes_atomically,
};
use crate::results::{RunContext, Snap, Trace};
use std::path::{Path, PathBuf};
use wrinkle_runtime::fem::Mesh;

/// `value(X, Y)` inside the mesh, NaN outside it (a hole, beyond a curved outline). A
/// structured rectangle fills its bounding box: `value` everywhere, as before masking existed.
pub fn domain_sampler<'a>(
    mesh: &'a Mesh,
    value: impl Fn(f64, f64) -> f64 + 'a,
) -> impl Fn(f64, f64) -> f64 + 'a {
    move |x, y| {
        if mesh.grid.is_some() || mesh.contains([x, y]) {
            value(x, y)
        } else {
            f64::NAN
        }
    }
}

/// The outline a map draws over its field: the mesh's boundary sides (outer outline and
/// holes) for a mesh that is not a structured rectangle, none for one (its frame is the
/// outline).
pub fn map_outline(mesh: &Mesh) -> Vec<[[f64; 2]; 3]> {
    if mesh.grid.is_some() {
        return Vec::new();
    }
    mesh.outline()
        .into_iter()
        .map(|side| side.map(|node| mesh.nodes[node]))
        .collect()
}

/// Zones whose largest $`|w|`$ across the domain exceeds this fraction of the peak are wrinkled.
const ZONE_FRACTION: f64 = 0.1;

/// A domain this many times longer than wide gets zooms of its wrinkled zones.
const RIBBON_ASPECT: f64 = 3.0;

/// At most this many zoomed zones, the strongest first.
const MAX_ZONES: usize = 2;

/// The extra figures with their captions: `wrinkles_zone_K.png/.svg` and
/// `membrane_force_N_X.png/.svg`, `membrane_force_N_Y.png/.svg`.
pub fn write_extra_figures(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Vec<(Vec<PathBuf>, String)>, Error> {
    let mut figures = write_zone_zooms(context, trace, dir)?;
    figures.extend(write_membrane_forces(context, trace, dir)?);
    figures.extend(plot_profile_line(context, trace, dir)?);
    Ok(figures)
}

/// The samples of `output.profile_line` (none if the scene gives no line): arc length $`s`$
/// from the first end and the point, about 16 per wavelength (400 to 4000).
fn profile_line_points(context: &RunContext) -> Vec<(f64, [f64; 2])> {
    let &[x0, y0, x1, y1] = context.scene.output.profile_line.as_slice() else {
        return Vec::new();
    };
    let length = (x1 - x0).hypot(y1 - y0);
    let wavelength = context.threshold.wavelength.unwrap_or(length);
    let count = (16.0 * length / wavelength).clamp(400.0, 4000.0) as usize;
    (0..=count)
        .map(|k| {
            let t = k as f64 / count as f64;
            (t * length, [x0 + t * (x1 - x0), y0 + t * (y1 - y0)])
        })
        .collect()
}

/// The physical deflection $`w/h`$ of `snap` at each point of the line, NaN outside the
/// domain; with `amplitude`, an envelope model's amplitude $`2|w_\text{env}|/h`$ instead
/// (`None` for a plate).
fn along_line(
    context: &RunContext,
    snap: &Snap,
    points: &[(f64, [f64; 2])],
    amplitude: bool,
) -> Option<Vec<f64>> {
    let snapshot = context.snapshot(&snap.values);
    let h = context.scene.material.thickness;
    let value = |point: [f64; 2]| {
        if amplitude {
            snapshot.envelope_amplitude(point).map(|a| a / h)
        } else {
            Some(snapshot.deflection(point) / h)
        }
    };
    points
        .iter()
        .map(|&(_, point)| {
            if context.mesh.contains(point) {
                value(point)
            } else {
                Some(f64::NAN)
            }
        })
        .collect()
}

/// `profile_line.csv`: columns `s_mm`, `x_mm`, `y_mm`, then for each profile load `L` (the
/// loads of the profile plots) `w_over_h_at_L` and, for an envelope model,
/// `amplitude_over_h_at_L`; an empty cell outside the domain. `None` without a line.
pub fn write_profile_line_csv(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Option<PathBuf>, Error> {
    let points = profile_line_points(context);
    if points.is_empty() {
        return Ok(None);
    }
    let load = context.load_quantity();
    let mut header = vec!["s_mm".to_string(), "x_mm".into(), "y_mm".into()];
    let mut columns: Vec<Vec<f64>> = Vec::new();
    for snap in &trace.profiles {
        let at = load.format_value(snap.load).replace(' ', "");
        for (name, amplitude) in [("w_over_h", false), ("amplitude_over_h", true)] {
            if let Some(values) = along_line(context, snap, &points, amplitude) {
                header.push(format!("{name}_at_{at}"));
                columns.push(values);
            }
        }
    }
    let cell = |v: f64| {
        if v.is_nan() {
            String::new()
        } else {
            format!("{v}")
        }
    };
    let mut text = header.join(",") + "\n";
    for (row, &(s, [x, y])) in points.iter().enumerate() {
        let mut cells = vec![format!("{s}"), format!("{x}"), format!("{y}")];
        cells.extend(columns.iter().map(|column| cell(column[row])));
        text += &(cells.join(",") + "\n");
    }
    let path = dir.join("profile_line.csv");
    write_bytes_atomically(&path, text.as_bytes()).map_err(io_error(&path))?;
    Ok(Some(path))
}

/// `profile_line.png|svg`: the physical deflection $`w/h`$ along the line at each profile
/// load, broken where the line leaves the domain.
fn plot_profile_line(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Option<(Vec<PathBuf>, String)>, Error> {
    let points = profile_line_points(context);
    if points.is_empty() || trace.profiles.is_empty() {
        return Ok(None);
    }
    let load = context.load_quantity();
    let profiles = trace
        .profiles
        .iter()
        .filter_map(|snap| {
            let values = along_line(context, snap, &points, false)?;
            Some(Profile {
                label: format!("λ = {}", load.format_value(snap.load)),
                points: points.iter().map(|p| p.0).zip(values).collect(),
            })
        })
        .collect();
    let line = &context.scene.output.profile_line;
    let location = format!(
        "along the line from ({}, {}) to ({}, {}) mm (output.profile_line); s from the first end",
        line[0], line[1], line[2], line[3]
    );
    let stem = dir.join("profile_line");
    let plot = plot_profiles(
        &stem,
        &format!("{}: physical deflection w / h", context.spec.name),
        &ProfilePlot {
            abscissa: Quantity::coordinate("s"),
            ordinate: Quantity::new("deflection", "w / h", ""),
            location: location.clone(),
            profiles,
        },
    )
    .map_err(io_error(&stem))?;
    Ok(Some((plot.files, format!("Profiles {location}"))))
}

/// The intervals along `axis` (0: X, 1: Y) where the largest $`|v|`$ across the other axis
/// exceeds `fraction` of the peak, gaps shorter than `merge` joined, strongest first (by their
/// largest $`|v|`$), at most `count`.
pub fn wrinkled_zones(
    field: &GridField,
    axis: usize,
    fraction: f64,
    merge: f64,
    count: usize,
) -> Vec<(f64, f64)> {
    let (columns, rows) = (field.columns, field.rows);
    let (along, across) = if axis == 0 {
        (columns, rows)
    } else {
        (rows, columns)
    };
    let value = |k: usize, l: usize| {
        let (i, j) = if axis == 0 { (k, l) } else { (l, k) };
        field.values[j * columns + i].abs()
    };
    let section: Vec<f64> = (0..along)
        .map(|k| (0..across).map(|l| value(k, l)).fold(0.0, f64::max))
        .collect();
    let peak = section.iter().cloned().fold(0.0, f64::max);
    if peak.is_nan() || peak <= 0.0 {
        return Vec::new();
    }
    let coordinate = |k: usize| {
        let point = if axis == 0 {
            field.point(k, 0)
        } else {
            field.point(0, k)
        };
        point[axis]
    };
    // (start, end, strongest) of each run above the fraction, gaps below `merge` joined.
    let mut zones: Vec<(f64, f64, f64)> = Vec::new();
    for (k, &v) in section.iter().enumerate() {
        if v < fraction * peak {
            continue;
        }
        let x = coordinate(k);
        match zones.last_mut() {
            Some(zone) if x - zone.1 <= merge => {
                zone.1 = x;
                zone.2 = zone.2.max(v);
            }
            _ => zones.push((x, x, v)),
        }
    }
    zones.sort_by(|a, b| b.2.total_cmp(&a.2));
    zones.truncate(count);
    zones.sort_by(|a, b| a.0.total_cmp(&b.0));
    zones.into_iter().map(|(a, b, _)| (a, b)).collect()
}

/// For a ribbon (a domain [`RIBBON_ASPECT`] times longer than wide): the wrinkle map of each
/// wrinkled zone (at most [`MAX_ZONES`]) with a wavelength of margin, at the last point.
fn write_zone_zooms(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Vec<(Vec<PathBuf>, String)>, Error> {
    let bounds = context.mesh.bounds();
    let (lx, ly) = (bounds[1] - bounds[0], bounds[3] - bounds[2]);
    let axis = if lx >= ly { 0 } else { 1 };
    if lx.max(ly) < RIBBON_ASPECT * lx.min(ly) {
        return Ok(Vec::new());
    }
    let snapshot = context.snapshot(&trace.last.values);
    let wavelength = context.threshold.wavelength.unwrap_or(lx.min(ly) / 4.0);
    let long = if axis == 0 { lx } else { ly };
    let samples = ((8.0 * long / wavelength) as usize).clamp(400, 3000);
    let (columns, rows) = if axis == 0 {
        (samples, 41)
    } else {
        (41, samples)
    };
    let overview = GridField::sample(
        Quantity::deflection(),
        bounds,
        columns,
        rows,
        domain_sampler(context.mesh, |x, y| snapshot.deflection([x, y])),
    );
    let h = context.scene.material.thickness;
    if overview.max_abs() < 1e-2 * h {
        return Ok(Vec::new());
    }
    let zones = wrinkled_zones(&overview, axis, ZONE_FRACTION, 2.0 * wavelength, MAX_ZONES);
    let load = context.load_quantity().format_value(trace.last.load);
    let mut figures = Vec::new();
    for (index, &(start, end)) in zones.iter().enumerate() {
        let low = (start - wavelength).max(bounds[2 * axis]);
        let high = (end + wavelength).min(bounds[2 * axis + 1]);
        let mut zone = bounds;
        zone[2 * axis] = low;
        zone[2 * axis + 1] = high;
        let per_mm = 16.0 / wavelength;
        let count = |length: f64| ((per_mm * length) as usize).clamp(100, 900) + 1;
        let field = GridField::sample(
            Quantity::deflection(),
            zone,
            count(zone[1] - zone[0]),
            count(zone[3] - zone[2]),
            domain_sampler(context.mesh, |x, y| snapshot.deflection([x, y])),
        );
        let name = ["X", "Y"][axis];
        let title = format!(
            "{}: wrinkled zone {} of {}, {name} from {low:.1} to {high:.1} mm, at λ = {load}",
            context.spec.name,
            index + 1,
            zones.len()
        );
        let stem = dir.join(format!("wrinkles_zone_{}", index + 1));
        let map = WrinkleMap::new(field, 1e-2 * h, "10⁻² h")
            .with_peak(snapshot.max_deflection())
            .with_outline(map_outline(context.mesh));
        let plot = plot_wrinkle_map(&stem, &title, &map).map_err(io_error(&stem))?;
        figures.push((
            plot.files,
            format!(
                "Wrinkled zone {} of {} ({name} from {low:.1} to {high:.1} mm), same colour scale as the whole map",
                index + 1,
                zones.len()
            ),
        ));
    }
    Ok(figures)
}

/// The membrane forces $`N_X`$, $`N_Y`$ (element means, N/mm) of the last recorded step end
/// below $`\lambda_c`$ — the pre-buckling state, whose compressed zones are where the sheet
/// wrinkles — on a diverging scale (compression blue, tension red).
fn write_membrane_forces(
    context: &RunContext,
    trace: &Trace,
    dir: &Path,
) -> Result<Vec<(Vec<PathBuf>, String)>, Error> {
    let critical = context.threshold.critical_load();
    let Some(state) = prebuckling_state(&trace.step_ends, critical) else {
        return Ok(Vec::new());
    };
    let mesh = context.mesh;
    let bounds = mesh.bounds();
    let (lx, ly) = (bounds[1] - bounds[0], bounds[3] - bounds[2]);
    let scale = 900.0 / lx.max(ly);
    let (columns, rows) = (
        ((lx * scale) as usize).max(40) + 1,
        ((ly * scale) as usize).max(40) + 1,
    );
    let load = context.load_quantity();
    let mut figures = Vec::new();
    for (component, name) in [(0, "N_X"), (1, "N_Y")] {
        let Some(values) = state.stress_resultants.get(component) else {
            continue;
        };
        let quantity = Quantity::new("membrane force", name, "N/mm");
        let field = GridField::sample(quantity, bounds, columns, rows, |x, y| {
            match mesh.locate([x, y]) {
                Some((element, _)) => values.get(element).copied().unwrap_or(0.0),
                None if mesh.grid.is_some() => 0.0,
                None => f64::NAN,
            }
        });
        let stem = dir.join(format!("membrane_force_{name}"));
        let title = format!(
            "{}: pre-buckling membrane force {name} at λ = {} ({:.2} λ_c); compression < 0",
            context.spec.name,
            load.format_value(state.load),
            state.load / critical
        );
        let (low, high) = field
            .values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &v| {
                (l.min(v), h.max(v))
            });
        let limit = color_limit(low, high);
        let number = |v: f64| crate::output::quantity::format_significant(v, 4);
        let saturated = if limit < low.abs().max(high.abs()) {
            " (beyond it saturated: the scale follows the compression)"
        } else {
            ""
        };
        let caption = format!(
            "{name} from {} to {} N/mm; colour scale ± {} N/mm{saturated}, blue = compression",
            number(low),
            number(high),
            number(limit)
        );
        let map = WrinkleMap::new(field, 0.0, "")
            .with_peak(limit)
            .with_caption(caption)
            .with_outline(map_outline(mesh));
        let plot = plot_wrinkle_map(&stem, &title, &map).map_err(io_error(&stem))?;
        figures.push((
            plot.files,
            format!("Pre-buckling membrane force {name} (element means, N/mm)"),
        ));
    }
    Ok(figures)
}

/// Half-range of the colour scale of a membrane force from `low` to `high`: the largest
/// magnitude, unless the compression ($`-\text{low}`$) is less than a quarter of the tension —
/// then twice the compression, so that the compressed zones (where the sheet wrinkles) are
/// not a pale patch beside a saturated clamp.
fn color_limit(low: f64, high: f64) -> f64 {
    let largest = low.abs().max(high.abs());
    if low < 0.0 && -low < 0.25 * high {
        -2.0 * low
    } else if largest > 0.0 {
        largest
    } else {
        1.0
    }
}

/// The last step end strictly between 0 and `critical` with its stress resultants, else the
/// first step end with a positive load.
fn prebuckling_state(step_ends: &[Snap], critical: f64) -> Option<&Snap> {
    let with_forces = |snap: &&Snap| !snap.stress_resultants.is_empty() && snap.load > 0.0;
    step_ends
        .iter()
        .filter(with_forces)
        .rfind(|snap| snap.load < critical)
        .or_else(|| step_ends.iter().find(with_forces))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two wrinkled zones near the ends of a long strip, found strongest first, reported in
    /// order along the strip; nothing for a flat field.
    #[test]
    fn the_two_wrinkled_zones_of_a_strip_are_found() {
        let field = GridField::sample(
            Quantity::deflection(),
            [0.0, 10.0, 0.0, 100.0],
            11,
            1001,
            |_, y| {
                let bump = |centre: f64, height: f64| {
                    height * (-(y - centre) * (y - centre) / 4.0).exp() * (3.0 * y).cos()
                };
                bump(15.0, 1.0) + bump(85.0, 0.6)
            },
        );
        let zones = wrinkled_zones(&field, 1, 0.1, 2.0, 2);
        assert_eq!(zones.len(), 2, "{zones:?}");
        assert!(zones[0].0 > 8.0 && zones[0].1 < 22.0, "{zones:?}");
        assert!(zones[1].0 > 78.0 && zones[1].1 < 92.0, "{zones:?}");
        let one = wrinkled_zones(&field, 1, 0.1, 2.0, 1);
        assert_eq!(one.len(), 1);
        assert!(one[0].0 < 20.0, "the strongest zone first: {one:?}");
        let flat = GridField::sample(
            Quantity::deflection(),
            [0.0, 1.0, 0.0, 1.0],
            5,
            5,
            |_, _| 0.0,
        );
        assert!(wrinkled_zones(&flat, 0, 0.1, 0.1, 2).is_empty());
    }
}
