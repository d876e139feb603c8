//! Measures of the wrinkles in a rectangular region of a state, the same for every model: all
//! are read off the **physical deflection** $`w(\mathbf X)`$ ([`Snapshot::deflection`]: the
//! plate's $`w`$, or the envelope's $`2\,\mathrm{Re}\big(w_1 e^{iQ\,\mathbf e\cdot\mathbf X}\big)`$
//! rebuilt with its carrier), sampled on a grid fine enough for the carrier.
//!
//! * **direction** of the wave vector: the principal axis of the structure tensor
//!   $`\mathbf J = \int_R \nabla w\,\nabla w^T\,dA`$ (largest eigenvalue), an axis in
//!   $`(-90°, 90°]`$ from X; its **coherence** $`(j_1 - j_2)/(j_1 + j_2)`$ is 1 for straight
//!   parallel wrinkles and 0 for no preferred direction;
//! * **wavelength** along that direction through the region's centre: twice the mean distance
//!   between consecutive sign changes of $`w`$ (where $`|w|`$ reaches 10 % of its largest value
//!   on the line, so that flat parts do not count);
//! * **amplitude**: $`\max_R |w|`$;
//! * **wrinkles**: the crests crossed along the horizontal line through the region's centre over
//!   the whole domain — the count of Wong & Pellegrino's photographs — i.e. the number of
//!   half-waves with $`w > 0`$ whose peak reaches 10 % of the line's largest $`|w|`$;
//! * for a complex envelope, the **local wavenumber** $`Q + \partial_e \arg w_1`$ at the centre
//!   ([`Snapshot::local_wavenumber`]).

use crate::physics::Snapshot;

/// A rectangle $`[x_0, x_1] \times [y_0, y_1]`$ (mm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Region {
    /// $`[x_0, x_1]`$.
    pub x: [f64; 2],
    /// $`[y_0, y_1]`$.
    pub y: [f64; 2],
}

impl Region {
    /// The centre of the region.
    pub fn centre(&self) -> [f64; 2] {
        [0.5 * (self.x[0] + self.x[1]), 0.5 * (self.y[0] + self.y[1])]
    }
}

/// The measures of the module documentation.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct RegionMeasures {
    /// Wave-vector direction (degrees from X).
    pub direction_degrees: f64,
    /// Coherence of the direction (0 … 1).
    pub coherence: f64,
    /// Wavelength along the direction through the centre (mm); `None` below two sign changes.
    pub wavelength: Option<f64>,
    /// $`\max_R|w|`$ (mm).
    pub amplitude: f64,
    /// Crests along the horizontal line through the centre, whole domain.
    pub wrinkles: usize,
    /// Local wavenumber of a complex envelope at the centre (1/mm).
    pub local_wavenumber: Option<f64>,
}

/// Fraction of the largest $`|w|`$ on a line below which a sign change or crest is not counted.
const FLAT_FRACTION: f64 = 0.1;

/// The measures of `snapshot` in `region`, sampled every `spacing` mm (a tenth of the shortest
/// wavelength expected, at most); `None` when $`w`$ vanishes there.
pub fn measure_region(
    snapshot: &Snapshot,
    region: &Region,
    spacing: f64,
) -> Option<RegionMeasures> {
    let (direction_degrees, coherence, amplitude) = structure(snapshot, region, spacing)?;
    let theta = direction_degrees.to_radians();
    let centre = region.centre();
    // Along the direction, within the region (the longest chord through the centre).
    let half = half_chord(region, theta);
    let along = line_samples(snapshot, centre, [theta.cos(), theta.sin()], half, spacing);
    let bounds = snapshot.mesh.bounds();
    let across = line_samples(
        snapshot,
        [0.5 * (bounds[0] + bounds[1]), centre[1]],
        [1.0, 0.0],
        0.5 * (bounds[1] - bounds[0]),
        spacing,
    );
    Some(RegionMeasures {
        direction_degrees,
        coherence,
        wavelength: wavelength_of(&along, spacing),
        amplitude,
        wrinkles: crests(&across),
        local_wavenumber: snapshot.local_wavenumber(centre, spacing),
    })
}

/// Direction (degrees), coherence and $`\max|w|`$ from the structure tensor over the region.
fn structure(snapshot: &Snapshot, region: &Region, spacing: f64) -> Option<(f64, f64, f64)> {
    let nx = ((region.x[1] - region.x[0]) / spacing).ceil().max(2.0) as usize;
    let ny = ((region.y[1] - region.y[0]) / spacing).ceil().max(2.0) as usize;
    let (dx, dy) = (
        (region.x[1] - region.x[0]) / nx as f64,
        (region.y[1] - region.y[0]) / ny as f64,
    );
    let grid: Vec<Vec<f64>> = (0..=ny)
        .map(|j| {
            (0..=nx)
                .map(|i| {
                    let point = [region.x[0] + i as f64 * dx, region.y[0] + j as f64 * dy];
                    snapshot.deflection(point)
                })
                .collect()
        })
        .collect();
    let (mut jxx, mut jyy, mut jxy, mut amplitude) = (0.0, 0.0, 0.0, 0.0f64);
    for j in 0..ny {
        for i in 0..nx {
            // Cell-centred differences of the four corners.
            let (a, b, c, d) = (
                grid[j][i],
                grid[j][i + 1],
                grid[j + 1][i],
                grid[j + 1][i + 1],
            );
            let wx = 0.5 * ((b - a) + (d - c)) / dx;
            let wy = 0.5 * ((c - a) + (d - b)) / dy;
            jxx += wx * wx;
            jyy += wy * wy;
            jxy += wx * wy;
            amplitude = amplitude
                .max(a.abs())
                .max(b.abs())
                .max(c.abs())
                .max(d.abs());
        }
    }
    let trace = jxx + jyy;
    if !(trace > 0.0 && trace.is_finite()) {
        return None;
    }
    let radius = (0.5 * (jxx - jyy)).hypot(jxy);
    let mut degrees = (0.5 * (2.0 * jxy).atan2(jxx - jyy)).to_degrees();
    if degrees <= -90.0 {
        degrees += 180.0;
    }
    Some((degrees, 2.0 * radius / trace, amplitude))
}

/// Half the chord of `region` through its centre along the angle `theta`.
fn half_chord(region: &Region, theta: f64) -> f64 {
    let (c, s) = (theta.cos().abs(), theta.sin().abs());
    let hx = 0.5 * (region.x[1] - region.x[0]);
    let hy = 0.5 * (region.y[1] - region.y[0]);
    let to_x = if c > 0.0 { hx / c } else { f64::INFINITY };
    let to_y = if s > 0.0 { hy / s } else { f64::INFINITY };
    to_x.min(to_y)
}

/// $`w`$ every `spacing` along `centre + t·direction`, $`t \in [-half, half]`$.
fn line_samples(
    snapshot: &Snapshot,
    centre: [f64; 2],
    direction: [f64; 2],
    half: f64,
    spacing: f64,
) -> Vec<f64> {
    let count = (2.0 * half / spacing).floor() as usize;
    (0..=count)
        .map(|k| {
            let t = -half + k as f64 * spacing;
            snapshot.deflection([centre[0] + t * direction[0], centre[1] + t * direction[1]])
        })
        .collect()
}

/// Twice the mean distance between consecutive sign changes of `samples` (spaced `spacing`)
/// beyond [`FLAT_FRACTION`] of their largest $`|w|`$; `None` below two.
fn wavelength_of(samples: &[f64], spacing: f64) -> Option<f64> {
    let largest = samples.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    let floor = FLAT_FRACTION * largest;
    // Signs of the samples above the floor, with their positions.
    let signed: Vec<(f64, bool)> = samples
        .iter()
        .enumerate()
        .filter(|(_, w)| w.abs() >= floor && largest > 0.0)
        .map(|(k, w)| (k as f64 * spacing, *w > 0.0))
        .collect();
    let changes: Vec<f64> = signed
        .windows(2)
        .filter(|pair| pair[0].1 != pair[1].1)
        .map(|pair| 0.5 * (pair[0].0 + pair[1].0))
        .collect();
    (changes.len() >= 2)
        .then(|| 2.0 * (changes[changes.len() - 1] - changes[0]) / (changes.len() - 1) as f64)
}

/// Half-waves with $`w > 0`$ whose peak reaches [`FLAT_FRACTION`] of the largest $`|w|`$.
fn crests(samples: &[f64]) -> usize {
    let largest = samples.iter().fold(0.0f64, |m, w| m.max(w.abs()));
    if largest <= 0.0 {
        return 0;
    }
    let floor = FLAT_FRACTION * largest;
    let mut count = 0;
    let mut peak: f64 = 0.0;
    for &w in samples {
        if w > 0.0 {
            peak = peak.max(w);
        } else {
            if peak >= floor {
                count += 1;
            }
            peak = 0.0;
        }
    }
    count + usize::from(peak >= floor)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn a_sampled_cosine_gives_its_wavelength_and_crests() {
        let spacing = 0.1;
        let samples: Vec<f64> = (0..=1000)
            .map(|k| (2.0 * PI * k as f64 * spacing / 12.5).cos())
            .collect();
        let wavelength = wavelength_of(&samples, spacing).unwrap();
        assert!((wavelength - 12.5).abs() < 0.05, "{wavelength}");
        // 100 mm of cos(2πx/12.5): crests at 0, 12.5, …, 100: 9.
        assert_eq!(crests(&samples), 9);
    }

    #[test]
    fn the_half_chord_stays_inside_the_region() {
        let region = Region {
            x: [0.0, 100.0],
            y: [0.0, 50.0],
        };
        assert!((half_chord(&region, 0.0) - 50.0).abs() < 1e-12);
        assert!((half_chord(&region, PI / 2.0) - 25.0).abs() < 1e-12);
        assert!((half_chord(&region, -PI / 4.0) - 25.0 * 2f64.sqrt()).abs() < 1e-9);
    }
}
