//! The response curve of one model ([`plot_response`]: the whole path, and the post-buckling part
//! against $`\lambda/\lambda_c`$) and the comparison of several models on one scene
//! ([`plot_comparison`]).

use super::PlotOutput;
use super::canvas::{
    BUCKLING_COLOR, CATEGORICAL, CLOSED_FORM_COLOR, Dash, ELLIPTICITY_COLOR, LegendEntry, render,
};
use super::panel::{Axis, LegendPlacement, Line, Panel, PanelFigure, VerticalLine};
use crate::output::invalid;
use crate::output::quantity::{Quantity, format_significant};
use plotters::style::RGBColor;
use std::io;
use std::path::Path;

/// One point of a traced path, in physical terms.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ResponsePoint {
    /// Load parameter $`\lambda`$ (in the unit of [`Response::load`]).
    pub load: f64,
    /// Largest physical amplitude over the thickness, $`\max|w|/h`$ (for envelope models twice
    /// the envelope, THEORY §3).
    pub max_amplitude_over_h: f64,
    /// Local physical amplitude at the centre over the thickness, when the caller has it.
    pub centre_amplitude_over_h: Option<f64>,
    /// `true` at the end point of a solver step (drawn as a dot); `false` for dense output.
    pub step_end: bool,
}

/// A closed-form amplitude as a function of the load ratio: points
/// $`(\lambda/\lambda_c,\ a/h)`$ with $`a`$ the *physical* amplitude.
#[derive(Clone, Debug, PartialEq)]
pub struct ClosedFormCurve {
    /// Legend text, e.g. `"one-mode closed form, eq. (62)"`.
    pub label: String,
    /// $`(\lambda/\lambda_c, a/h)`$ by increasing ratio.
    pub points: Vec<(f64, f64)>,
}

/// What a [`LoadMarker`] marks (sets its colour and dash).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MarkerKind {
    /// The linear buckling load $`\lambda_c`$.
    LinearBuckling,
    /// The first load at which the model loses ellipticity.
    LossOfEllipticity,
    /// Anything else (e.g. a bifurcation detected on the path).
    Other,
}

/// A vertical line at a load, with a short tag above the frame and a full legend text.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadMarker {
    /// What it marks.
    pub kind: MarkerKind,
    /// Load $`\lambda`$ (unit of [`Response::load`]).
    pub load: f64,
    /// A few characters written above the frame at the line, e.g. `"λ_c"`.
    pub tag: String,
    /// Legend text, e.g. `"linear buckling λ_c = 0.089521 N/mm"`.
    pub label: String,
}

impl LoadMarker {
    /// The linear buckling load: tag `λ_c`, legend `linear buckling λ_c = … UNIT`.
    pub fn linear_buckling(critical_load: f64, load: &Quantity) -> Self {
        LoadMarker {
            kind: MarkerKind::LinearBuckling,
            load: critical_load,
            tag: "λ_c".into(),
            label: format!("linear buckling λ_c = {}", load.format_value(critical_load)),
        }
    }

    /// The first loss of ellipticity, with the violated fraction of the area when known.
    pub fn loss_of_ellipticity(at: f64, area_fraction: Option<f64>, load: &Quantity) -> Self {
        let area = area_fraction
            .map(|f| format!(" on {} % of the area", format_significant(100.0 * f, 2)))
            .unwrap_or_default();
        LoadMarker {
            kind: MarkerKind::LossOfEllipticity,
            load: at,
            tag: "ellipticity lost".into(),
            label: format!("loss of ellipticity at λ = {}{area}", load.format_value(at)),
        }
    }

    /// Any other marker.
    pub fn new(load: f64, tag: impl Into<String>, label: impl Into<String>) -> Self {
        LoadMarker {
            kind: MarkerKind::Other,
            load,
            tag: tag.into(),
            label: label.into(),
        }
    }

    fn style(&self) -> (RGBColor, Dash) {
        match self.kind {
            MarkerKind::LinearBuckling => (BUCKLING_COLOR, Dash::Short),
            MarkerKind::LossOfEllipticity => (ELLIPTICITY_COLOR, Dash::Dashed),
            MarkerKind::Other => (RGBColor(0, 128, 128), Dash::Short),
        }
    }
}

/// The load–amplitude response of one model on one scene, already in physical terms.
#[derive(Clone, Debug, PartialEq)]
pub struct Response {
    /// Model name (titles and comparison legends).
    pub model: String,
    /// The load $`\lambda`$: its name and unit label the load axis.
    pub load: Quantity,
    /// The plotted amplitude (ordinate title), by default
    /// [`Quantity::max_amplitude_over_thickness`].
    pub amplitude: Quantity,
    /// Legend text of the largest amplitude.
    pub max_label: String,
    /// Legend text of the amplitude at the centre.
    pub centre_label: String,
    /// Critical load $`\lambda_c`$ (finite, positive): the ratio axis is $`\lambda/\lambda_c`$.
    pub critical_load: f64,
    /// The path, by increasing step.
    pub points: Vec<ResponsePoint>,
    /// Closed form drawn dashed, when it applies.
    pub closed_form: Option<ClosedFormCurve>,
    /// Vertical markers (linear buckling, loss of ellipticity, …).
    pub markers: Vec<LoadMarker>,
    /// Why this response is not a valid result of its model (a failed validity check: an
    /// ill-posed model, an unresolved mode), `None` when it is. A comparison draws it grey and
    /// dashed, says why in the legend, and does not fit its axes to it.
    pub caveat: Option<String>,
}

impl Response {
    /// A response with the default amplitude labels, no closed form and no marker.
    pub fn new(
        model: impl Into<String>,
        load: Quantity,
        critical_load: f64,
        points: Vec<ResponsePoint>,
    ) -> Self {
        Response {
            model: model.into(),
            load,
            amplitude: Quantity::max_amplitude_over_thickness(),
            max_label: "max |w| / h, finite elements (● step ends)".into(),
            centre_label: "|w| / h at the centre".into(),
            critical_load,
            points,
            closed_form: None,
            markers: Vec::new(),
            caveat: None,
        }
    }

    /// Marks the response as not a valid result of its model, saying why (see
    /// [`Response::caveat`]).
    pub fn with_caveat(mut self, caveat: impl Into<String>) -> Self {
        self.caveat = Some(caveat.into());
        self
    }

    /// Adds the closed form.
    pub fn with_closed_form(mut self, curve: ClosedFormCurve) -> Self {
        self.closed_form = Some(curve);
        self
    }

    /// Adds a marker.
    pub fn with_marker(mut self, marker: LoadMarker) -> Self {
        self.markers.push(marker);
        self
    }

    /// Load of the last finite point.
    pub fn final_load(&self) -> Option<f64> {
        self.points
            .iter()
            .rev()
            .find(|p| p.load.is_finite() && p.max_amplitude_over_h.is_finite())
            .map(|p| p.load)
    }

    fn validate(&self) -> io::Result<()> {
        if !(self.critical_load.is_finite() && self.critical_load > 0.0) {
            return Err(invalid(
                format!("response of `{}`", self.model),
                format!(
                    "critical load must be finite and positive, got {}",
                    self.critical_load
                ),
            ));
        }
        if self.final_load().is_none() {
            return Err(invalid(
                format!("response of `{}`", self.model),
                "no finite path point",
            ));
        }
        if let Some(marker) = self.markers.iter().find(|m| !m.load.is_finite()) {
            return Err(invalid(
                format!("marker `{}`", marker.label),
                format!("load must be finite, got {}", marker.load),
            ));
        }
        Ok(())
    }

    /// Ratio $`\lambda/\lambda_c`$ of the last point.
    fn final_ratio(&self) -> f64 {
        self.final_load().unwrap_or(0.0) / self.critical_load
    }

    fn max_points(&self, ratio: bool) -> Vec<(f64, f64)> {
        let scale = self.abscissa_scale(ratio);
        self.points
            .iter()
            .map(|p| (p.load * scale, p.max_amplitude_over_h))
            .collect()
    }

    fn step_ends(&self, ratio: bool) -> Vec<(f64, f64)> {
        let scale = self.abscissa_scale(ratio);
        self.points
            .iter()
            .filter(|p| p.step_end)
            .map(|p| (p.load * scale, p.max_amplitude_over_h))
            .collect()
    }

    fn centre_points(&self, ratio: bool) -> Vec<(f64, f64)> {
        let scale = self.abscissa_scale(ratio);
        self.points
            .iter()
            .filter_map(|p| p.centre_amplitude_over_h.map(|a| (p.load * scale, a)))
            .collect()
    }

    fn closed_form_points(&self, ratio: bool) -> Vec<(f64, f64)> {
        let factor = if ratio { 1.0 } else { self.critical_load };
        self.closed_form
            .iter()
            .flat_map(|c| c.points.iter().map(|&(r, a)| (r * factor, a)))
            .collect()
    }

    fn abscissa_scale(&self, ratio: bool) -> f64 {
        if ratio { 1.0 / self.critical_load } else { 1.0 }
    }
}

/// Lower end of the post-buckling panel, as $`\lambda/\lambda_c`$.
pub const ZOOM_START_RATIO: f64 = 0.9;

/// Pixel width of the response and comparison figures.
const WIDE_FIGURE: f64 = 1500.0;
const PANEL_HEIGHT: f64 = 560.0;

/// Colour of the largest amplitude and of the amplitude at the centre.
const MAX_COLOR: RGBColor = CATEGORICAL[0];
const CENTRE_COLOR: RGBColor = CATEGORICAL[1];

/// Plots `response` to `STEM.png` and `STEM.svg`: on the left the whole path (amplitude against
/// the load, with its unit), on the right the post-buckling part against $`\lambda/\lambda_c`$
/// over $`[0.9, \lambda_\text{end}/\lambda_c]`$; the closed form (dashed) where given, dots at the
/// step ends, the markers as vertical lines tagged above the frame; the legend below the panels.
///
/// Errors: no finite point, a critical load that is not finite and positive, a non-finite marker,
/// a failure writing the files.
pub fn plot_response(stem: &Path, title: &str, response: &Response) -> io::Result<PlotOutput> {
    response.validate()?;
    let mut legend = vec![LegendEntry {
        label: response.max_label.clone(),
        color: MAX_COLOR,
        dash: Dash::Solid,
        width: 2.5,
        marker: true,
    }];
    if response
        .points
        .iter()
        .any(|p| p.centre_amplitude_over_h.is_some())
    {
        legend.push(LegendEntry {
            label: response.centre_label.clone(),
            color: CENTRE_COLOR,
            dash: Dash::Solid,
            width: 2.0,
            marker: false,
        });
    }
    if let Some(curve) = &response.closed_form {
        legend.push(LegendEntry {
            label: curve.label.clone(),
            color: CLOSED_FORM_COLOR,
            dash: Dash::Dashed,
            width: 2.0,
            marker: false,
        });
    }
    for marker in &response.markers {
        let (color, dash) = marker.style();
        legend.push(LegendEntry {
            label: marker.label.clone(),
            color,
            dash,
            width: 1.8,
            marker: false,
        });
    }
    let whole = response_panel(response, false);
    let zoom = response_panel(response, true);
    let figure = PanelFigure {
        title: title.to_string(),
        panels: vec![whole, zoom],
        legend,
        placement: LegendPlacement::Below,
        width: WIDE_FIGURE,
        panel_height: PANEL_HEIGHT,
    };
    render(stem, &figure)
}

/// The whole path against the load (`ratio = false`) or the post-buckling part against
/// $`\lambda/\lambda_c`$ (`ratio = true`).
fn response_panel(response: &Response, ratio: bool) -> Panel {
    let mut lines = vec![Line {
        points: response.max_points(ratio),
        color: MAX_COLOR,
        dash: Dash::Solid,
        width: 2.5,
        dots: response.step_ends(ratio),
    }];
    let centre = response.centre_points(ratio);
    if !centre.is_empty() {
        lines.push(Line {
            points: centre,
            color: CENTRE_COLOR,
            dash: Dash::Solid,
            width: 2.0,
            dots: Vec::new(),
        });
    }
    let closed = response.closed_form_points(ratio);
    if !closed.is_empty() {
        lines.push(Line {
            points: closed,
            color: CLOSED_FORM_COLOR,
            dash: Dash::Dashed,
            width: 2.0,
            dots: Vec::new(),
        });
    }
    let scale = response.abscissa_scale(ratio);
    let verticals = response
        .markers
        .iter()
        .map(|marker| {
            let (color, dash) = marker.style();
            VerticalLine {
                x: marker.load * scale,
                color,
                dash,
                tag: marker.tag.clone(),
            }
        })
        .collect();
    let x_range = if ratio {
        zoom_range(response.final_ratio())
    } else {
        let loads = response
            .points
            .iter()
            .map(|p| p.load)
            .chain(response.markers.iter().map(|m| m.load));
        let (low, high) = finite_extent(loads);
        padded((low.min(0.0), high), 0.0, 0.02)
    };
    let y_range = amplitude_range(&lines, x_range);
    let (title, x_title) = if ratio {
        (
            format!("post-buckling: λ ≥ {ZOOM_START_RATIO} λ_c"),
            "load ratio λ / λ_c".to_string(),
        )
    } else {
        ("whole path".to_string(), response.load.axis_title())
    };
    Panel {
        title,
        x: Axis {
            title: x_title,
            range: x_range,
        },
        y: Axis {
            title: response.amplitude.axis_title(),
            range: y_range,
        },
        lines,
        verticals,
    }
}

/// $`[0.9, r_\text{end}]`$ with a little room on the right; at least up to 1.1 when the path
/// ends before the threshold.
fn zoom_range(final_ratio: f64) -> (f64, f64) {
    let end = final_ratio.max(1.1);
    (ZOOM_START_RATIO, end + 0.03 * (end - ZOOM_START_RATIO))
}

/// Ordinate range covering every line inside the abscissa range, from 0 (or below when values
/// are negative) with 8 % room at the top.
fn amplitude_range(lines: &[Line], x_range: (f64, f64)) -> (f64, f64) {
    let values = lines.iter().flat_map(|line| {
        line.points
            .iter()
            .filter(|p| p.0 >= x_range.0 && p.0 <= x_range.1)
            .map(|p| p.1)
    });
    let (low, high) = finite_extent(values);
    let (low, high) = (low.min(0.0), high.max(0.0));
    if high - low <= 0.0 {
        (0.0, 1.0)
    } else {
        padded((low, high), if low < 0.0 { 0.04 } else { 0.0 }, 0.08)
    }
}

fn finite_extent(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(low, high), v| {
            (low.min(v), high.max(v))
        })
}

/// `(low, high)` widened by fractions of its span; a degenerate range is widened to be usable.
fn padded((low, high): (f64, f64), below: f64, above: f64) -> (f64, f64) {
    if !(low.is_finite() && high.is_finite()) {
        return (0.0, 1.0);
    }
    let span = high - low;
    if span > 0.0 {
        (low - below * span, high + above * span)
    } else {
        let half = if low == 0.0 { 1.0 } else { 0.1 * low.abs() };
        (low - half, high + half)
    }
}

/// Plots the responses of several models on one scene to `STEM.png` and `STEM.svg`: the largest
/// amplitude against the load (left; each model's $`\lambda_c`$ as a dotted line in its colour)
/// and against each model's own $`\lambda/\lambda_c`$ over $`[0.9, \max r_\text{end}]`$ (right);
/// one colour per model, the legend below. A response with a [`Response::caveat`] is drawn grey
/// and dashed with the caveat in its legend entry, and the axes are fitted to the valid
/// responses only (when there is one): an ill-posed model that runs away at a fraction of the
/// others' loads does not squeeze them.
///
/// Errors: no response, or one that [`plot_response`] would reject; all responses must share
/// the load quantity's unit.
pub fn plot_comparison(stem: &Path, title: &str, responses: &[Response]) -> io::Result<PlotOutput> {
    let first = comparable(responses)?;
    let figure = PanelFigure {
        title: title.to_string(),
        panels: vec![
            comparison_against_load(first, responses),
            comparison_against_ratio(first, responses),
        ],
        legend: comparison_legend(responses),
        placement: LegendPlacement::Below,
        width: WIDE_FIGURE,
        panel_height: PANEL_HEIGHT,
    };
    render(stem, &figure)
}

/// The first of `responses`, once each is valid and all share its load unit.
fn comparable(responses: &[Response]) -> io::Result<&Response> {
    let Some(first) = responses.first() else {
        return Err(invalid("comparison", "needs at least one response"));
    };
    for response in responses {
        response.validate()?;
        if response.load.unit != first.load.unit {
            return Err(invalid(
                "comparison",
                format!(
                    "load units differ: `{}` for {} and `{}` for {}",
                    first.load.unit, first.model, response.load.unit, response.model
                ),
            ));
        }
    }
    Ok(first)
}

/// The colour of the `index`-th model of a comparison (grey for a response with a caveat).
fn comparison_color(index: usize, response: &Response) -> RGBColor {
    if response.caveat.is_some() {
        CAVEAT_COLOR
    } else {
        CATEGORICAL[index % CATEGORICAL.len()]
    }
}

/// The colour of a response that is not a valid result of its model.
const CAVEAT_COLOR: RGBColor = RGBColor(150, 150, 150);

/// The line style of a response: dashed when it has a caveat.
fn comparison_dash(response: &Response) -> Dash {
    if response.caveat.is_some() {
        Dash::Dashed
    } else {
        Dash::Solid
    }
}

/// The responses the axes are fitted to: the valid ones, or all when none is valid.
fn fitted(responses: &[Response]) -> Vec<&Response> {
    let valid: Vec<&Response> = responses.iter().filter(|r| r.caveat.is_none()).collect();
    if valid.is_empty() {
        responses.iter().collect()
    } else {
        valid
    }
}

/// One entry per model with its $`\lambda_c`$, then the thresholds' dotted lines.
fn comparison_legend(responses: &[Response]) -> Vec<LegendEntry> {
    let mut legend: Vec<LegendEntry> = responses
        .iter()
        .enumerate()
        .map(|(index, response)| LegendEntry {
            label: format!(
                "{} (λ_c = {}){}",
                response.model,
                response.load.format_value(response.critical_load),
                response
                    .caveat
                    .as_ref()
                    .map_or(String::new(), |caveat| format!(" — not valid: {caveat}"))
            ),
            color: comparison_color(index, response),
            dash: comparison_dash(response),
            width: 2.5,
            marker: response.caveat.is_none(),
        })
        .collect();
    legend.push(LegendEntry {
        label: "λ_c of each model (left), λ = λ_c (right)".into(),
        color: BUCKLING_COLOR,
        dash: Dash::Short,
        width: 1.6,
        marker: false,
    });
    legend
}

/// Each model's largest amplitude against the load (`ratio` false) or its own
/// $`\lambda/\lambda_c`$ (`ratio` true), in its colour with its step ends.
fn comparison_lines(responses: &[Response], ratio: bool) -> Vec<Line> {
    responses
        .iter()
        .enumerate()
        .map(|(index, response)| Line {
            points: response.max_points(ratio),
            color: comparison_color(index, response),
            dash: comparison_dash(response),
            width: if response.caveat.is_some() { 1.8 } else { 2.5 },
            dots: if response.caveat.is_some() {
                Vec::new()
            } else {
                response.step_ends(ratio)
            },
        })
        .collect()
}

/// The left panel: amplitudes against the load, each model's $`\lambda_c`$ dotted.
fn comparison_against_load(first: &Response, responses: &[Response]) -> Panel {
    let (low, high) = finite_extent(fitted(responses).into_iter().flat_map(|r| {
        r.points
            .iter()
            .map(|p| p.load)
            .chain(std::iter::once(r.critical_load))
    }));
    let load_range = padded((low.min(0.0), high), 0.0, 0.02);
    let lines = comparison_lines(responses, false);
    Panel {
        title: "against the load".into(),
        x: Axis {
            title: first.load.axis_title(),
            range: load_range,
        },
        y: Axis {
            title: first.amplitude.axis_title(),
            range: amplitude_range(&lines, load_range),
        },
        lines,
        verticals: responses
            .iter()
            .enumerate()
            .map(|(index, response)| VerticalLine {
                x: response.critical_load,
                color: comparison_color(index, response),
                dash: Dash::Short,
                tag: String::new(),
            })
            .collect(),
    }
}

/// The right panel: amplitudes against each model's $`\lambda/\lambda_c`$ from
/// [`ZOOM_START_RATIO`].
fn comparison_against_ratio(first: &Response, responses: &[Response]) -> Panel {
    let ratio_range = zoom_range(
        fitted(responses)
            .into_iter()
            .map(Response::final_ratio)
            .fold(f64::NEG_INFINITY, f64::max),
    );
    let lines = comparison_lines(responses, true);
    Panel {
        title: format!("against each model's λ / λ_c (≥ {ZOOM_START_RATIO})"),
        x: Axis {
            title: "load ratio λ / λ_c".into(),
            range: ratio_range,
        },
        y: Axis {
            title: first.amplitude.axis_title(),
            range: amplitude_range(&lines, ratio_range),
        },
        lines,
        verticals: vec![VerticalLine {
            x: 1.0,
            color: BUCKLING_COLOR,
            dash: Dash::Short,
            tag: "λ = λ_c".into(),
        }],
    }
}
