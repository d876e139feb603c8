//! Profiles of a quantity along a line of the domain ([`plot_profiles`]), typically the physical
//! deflection or amplitude through the maximum of the wrinkles at several loads.

use super::PlotOutput;
use super::canvas::{Dash, LEGEND_SIZE, LegendEntry, render, sequential_color, text_size};
use super::panel::{Axis, LegendPlacement, Line, Panel, PanelFigure};
use crate::output::invalid;
use crate::output::quantity::Quantity;
use plotters::style::RGBColor;
use std::io;
use std::path::Path;

/// One sampled profile, e.g. at one load.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// Legend text, e.g. `"λ = 0.0950 N/mm (1.06 λ_c)"`.
    pub label: String,
    /// $`(s, v)`$: position along the line and value, in drawing order.
    pub points: Vec<(f64, f64)>,
}

/// Profiles along one line of the domain.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfilePlot {
    /// Position along the line, e.g. [`Quantity::coordinate`]`("X")`.
    pub abscissa: Quantity,
    /// The plotted quantity, e.g. [`Quantity::deflection_over_thickness`].
    pub ordinate: Quantity,
    /// Where the line is, written under the title, e.g.
    /// `"along X at Y = 37.5 mm (through the maximum)"`.
    pub location: String,
    /// The profiles, coloured dark to light in this order (pass them by increasing load).
    pub profiles: Vec<Profile>,
}

const FIGURE_WIDTH: f64 = 1400.0;
const PANEL_HEIGHT: f64 = 560.0;

/// A horizontal reference line of a profile plot (e.g. the carrier wavenumber $`Q`$ under the
/// local wavenumber, or the minimum of $`\lambda_c(Q)`$): its ordinate and legend text.
#[derive(Clone, Debug, PartialEq)]
pub struct ReferenceLevel {
    /// Ordinate of the line.
    pub value: f64,
    /// Legend text, e.g. `"carrier Q = 0.23543 /mm"`.
    pub label: String,
}

/// Plots `plot` to `STEM.png` and `STEM.svg`: one panel (title: `title`, then the location), the
/// profiles coloured along viridis, the legend in a column to the right of the panel.
///
/// The ordinate starts at 0 unless every value lies far from it (all of one sign, the smallest
/// magnitude above a quarter of the largest): then it spans the data, so that a variation of a
/// few percent (a local wavenumber of 0.23–0.26 /mm) fills the panel instead of a tenth of it.
///
/// Errors: no profile with a finite point, a failure writing the files.
pub fn plot_profiles(stem: &Path, title: &str, plot: &ProfilePlot) -> io::Result<PlotOutput> {
    plot_profiles_with_level(stem, title, plot, None)
}

/// [`plot_profiles`] with a dashed horizontal `level` (kept inside the ordinate's range) and
/// its legend entry.
pub fn plot_profiles_with_level(
    stem: &Path,
    title: &str,
    plot: &ProfilePlot,
    level: Option<&ReferenceLevel>,
) -> io::Result<PlotOutput> {
    let (x_range, y_range) = profile_ranges(plot, level.map(|l| l.value))?;
    let count = plot.profiles.len();
    let mut lines: Vec<Line> = plot
        .profiles
        .iter()
        .enumerate()
        .map(|(index, profile)| Line {
            points: profile.points.clone(),
            color: sequential_color(index, count),
            dash: Dash::Solid,
            width: 2.2,
            dots: Vec::new(),
        })
        .collect();
    let mut legend = profile_legend(plot);
    if let Some(level) = level {
        lines.push(Line {
            points: vec![(x_range.0, level.value), (x_range.1, level.value)],
            color: LEVEL_COLOR,
            dash: Dash::Dashed,
            width: 1.8,
            dots: Vec::new(),
        });
        legend.push(LegendEntry {
            label: level.label.clone(),
            color: LEVEL_COLOR,
            dash: Dash::Dashed,
            width: 1.8,
            marker: false,
        });
    }
    let widest = legend
        .iter()
        .map(|entry| text_size(&entry.label, LEGEND_SIZE).0)
        .fold(0.0, f64::max);
    let legend_width = (widest + 90.0).min(0.4 * FIGURE_WIDTH);
    let figure = PanelFigure {
        title: title.to_string(),
        panels: vec![Panel {
            title: plot.location.clone(),
            x: Axis {
                title: plot.abscissa.axis_title(),
                range: x_range,
            },
            y: Axis {
                title: plot.ordinate.axis_title(),
                range: y_range,
            },
            lines,
            verticals: Vec::new(),
        }],
        legend,
        placement: LegendPlacement::Right {
            width: legend_width,
        },
        width: FIGURE_WIDTH,
        panel_height: PANEL_HEIGHT,
    };
    render(stem, &figure)
}

/// Colour of a reference level.
const LEVEL_COLOR: RGBColor = RGBColor(200, 30, 30);

/// The abscissa range of the finite points, and the ordinate range from 0 (or below) with 6 %
/// room — or around the data when it lies far from 0 (see [`plot_profiles`]) — including
/// `level`; an error when no profile has a finite point.
fn profile_ranges(plot: &ProfilePlot, level: Option<f64>) -> io::Result<((f64, f64), (f64, f64))> {
    let finite = plot
        .profiles
        .iter()
        .flat_map(|p| &p.points)
        .filter(|p| p.0.is_finite() && p.1.is_finite());
    let (mut x_low, mut x_high, mut y_low, mut y_high) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in finite {
        x_low = x_low.min(x);
        x_high = x_high.max(x);
        y_low = y_low.min(y);
        y_high = y_high.max(y);
    }
    if let Some(level) = level.filter(|l| l.is_finite()) {
        y_low = y_low.min(level);
        y_high = y_high.max(level);
    }
    if !x_low.is_finite() {
        return Err(invalid("profiles", "no profile has a finite point"));
    }
    let x_range = if x_high > x_low {
        (x_low, x_high)
    } else {
        (x_low - 1.0, x_high + 1.0)
    };
    let far_from_zero =
        (y_low > 0.0 && y_low > 0.25 * y_high) || (y_high < 0.0 && -y_high > 0.25 * -y_low);
    if far_from_zero && y_high > y_low {
        let room = 0.08 * (y_high - y_low);
        return Ok((x_range, (y_low - room, y_high + room)));
    }
    let (y_low, y_high) = (y_low.min(0.0), y_high.max(0.0));
    let span = y_high - y_low;
    let y_range = if span > 0.0 {
        (
            y_low - if y_low < 0.0 { 0.06 * span } else { 0.0 },
            y_high + 0.06 * span,
        )
    } else {
        (-1.0, 1.0)
    };
    Ok((x_range, y_range))
}

/// One entry per labelled profile, in its colour.
fn profile_legend(plot: &ProfilePlot) -> Vec<LegendEntry> {
    let count = plot.profiles.len();
    plot.profiles
        .iter()
        .enumerate()
        .filter(|(_, profile)| !profile.label.is_empty())
        .map(|(index, profile)| LegendEntry {
            label: profile.label.clone(),
            color: sequential_color(index, count),
            dash: Dash::Solid,
            width: 2.5,
            marker: false,
        })
        .collect()
}
