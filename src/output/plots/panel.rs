//! One panel of curves: axes with titles and non-overlapping tick labels, lines clipped to the
//! data area, step-end dots, vertical marker lines with short tags above the frame.

use super::canvas::{
    AXIS_TITLE_SIZE, Dash, DrawResult, FRAME_COLOR, Figure, LegendEntry, PANEL_TITLE_SIZE, Scale,
    TAG_SIZE, TICK_SIZE, TITLE_SIZE, draw_centred_text, draw_legend, draw_vertical_title,
    format_tick, legend_rows, text_size,
};
use super::{FigureLayout, PanelLayout};
use plotters::coord::Shift;
use plotters::coord::ranged1d::Ranged;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;

/// An axis: its title (with the unit) and its range.
#[derive(Clone, Debug)]
pub(crate) struct Axis {
    pub title: String,
    pub range: (f64, f64),
}

/// A polyline with optional dots (e.g. at the step ends of a path).
#[derive(Clone, Debug)]
pub(crate) struct Line {
    pub points: Vec<(f64, f64)>,
    pub color: RGBColor,
    pub dash: Dash,
    pub width: f64,
    pub dots: Vec<(f64, f64)>,
}

/// A vertical line across the data area with a short tag above the frame.
#[derive(Clone, Debug)]
pub(crate) struct VerticalLine {
    pub x: f64,
    pub color: RGBColor,
    pub dash: Dash,
    pub tag: String,
}

/// Everything one panel shows.
#[derive(Clone, Debug)]
pub(crate) struct Panel {
    pub title: String,
    pub x: Axis,
    pub y: Axis,
    pub lines: Vec<Line>,
    pub verticals: Vec<VerticalLine>,
}

/// Height of the band above the data area holding the panel title.
const TITLE_BAND: f64 = 32.0;
/// Height of one row of marker tags.
const TAG_ROW: f64 = 20.0;
/// Space below the data area for tick labels and the axis title.
const X_LABEL_AREA: f64 = 66.0;
const RIGHT_MARGIN: f64 = 18.0;
/// Left edge of the (rotated) ordinate title.
const Y_TITLE_LEFT: f64 = 6.0;
/// Smallest gap between two horizontal tick labels.
const TICK_LABEL_GAP: f64 = 22.0;
const DOT_RADIUS: f64 = 4.5;

/// The tick labels chosen for an axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Ticks {
    /// The hint given to plotters (at most this many labels).
    pub count: usize,
    /// Decimals of the labels (`None`: scientific notation).
    pub decimals: Option<usize>,
    /// Widest label, 1× pixels.
    pub label_width: f64,
    /// Magnitude below which a tick is zero (a millionth of the axis span): a key point such as
    /// $`-1.08\cdot10^{-19}`$, rounding noise of the range's arithmetic, is labelled `0`.
    pub zero: f64,
}

impl Ticks {
    /// The label of the tick at `value`.
    pub fn label(&self, value: f64) -> String {
        let value = if value.abs() < self.zero { 0.0 } else { value };
        format_tick(value, self.decimals)
    }
}

/// The most tick labels (at most 12) that fit along `length` pixels without overlapping:
/// horizontally, neighbouring labels keep [`TICK_LABEL_GAP`] between them; vertically, two
/// label heights apart.
pub(crate) fn choose_ticks(range: (f64, f64), length: f64, horizontal: bool) -> Ticks {
    let coordinate = RangedCoordf64::from(range.0..range.1);
    let span = range.1 - range.0;
    let zero = 1e-6 * span.abs();
    let mut fallback = None;
    for count in (2..=12).rev() {
        let points: Vec<f64> = coordinate
            .key_points(count)
            .into_iter()
            .map(|v| if v.abs() < zero { 0.0 } else { v })
            .collect();
        let decimals = tick_decimals(&points);
        let mut ticks = Ticks {
            count,
            decimals,
            label_width: 0.0,
            zero,
        };
        ticks.label_width = points
            .iter()
            .map(|&v| text_size(&ticks.label(v), TICK_SIZE).0)
            .fold(0.0, f64::max);
        fallback = Some(ticks);
        if points.len() < 2 {
            continue;
        }
        let spacing = length * (points[1] - points[0]).abs() / span;
        let needed = if horizontal {
            ticks.label_width + TICK_LABEL_GAP
        } else {
            2.0 * TICK_SIZE
        };
        if spacing >= needed {
            return ticks;
        }
    }
    fallback.unwrap_or(Ticks {
        count: 2,
        decimals: Some(0),
        label_width: 0.0,
        zero,
    })
}

/// Fewest decimals that write every tick exactly (to a millionth of the spacing); scientific
/// notation for very large or very small magnitudes.
fn tick_decimals(points: &[f64]) -> Option<usize> {
    let largest = points.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    if largest >= 1e5 || (largest > 0.0 && largest < 1e-3) {
        return None;
    }
    let step = match points {
        [a, b, ..] => (b - a).abs(),
        _ => largest.max(1.0),
    };
    if step == 0.0 || !step.is_finite() {
        return Some(0);
    }
    let mut decimals = (-step.log10() - 1e-9).ceil().max(0.0) as usize;
    while decimals < 9
        && points.iter().any(|&v| {
            let text = format!("{v:.decimals$}");
            text.parse::<f64>()
                .map(|back| (back - v).abs() > 1e-6 * step)
                .unwrap_or(true)
        })
    {
        decimals += 1;
    }
    Some(decimals)
}

fn finite(point: &(f64, f64)) -> bool {
    point.0.is_finite() && point.1.is_finite()
}

/// The part of segment `a`–`b` inside the box (Liang–Barsky), `None` if it misses the box.
fn clip_segment(
    a: (f64, f64),
    b: (f64, f64),
    x: (f64, f64),
    y: (f64, f64),
) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-dx, a.0 - x.0),
        (dx, x.1 - a.0),
        (-dy, a.1 - y.0),
        (dy, y.1 - a.1),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
        }
    }
    if t0 > t1 {
        return None;
    }
    let at = |t: f64| {
        if t == 0.0 {
            a
        } else if t == 1.0 {
            b
        } else {
            (a.0 + t * dx, a.1 + t * dy)
        }
    };
    Some((at(t0), at(t1)))
}

/// The runs of a polyline inside the box; non-finite points break the line.
pub(crate) fn clip_polyline(
    points: &[(f64, f64)],
    x: (f64, f64),
    y: (f64, f64),
) -> Vec<Vec<(f64, f64)>> {
    let mut runs = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    let mut flush = |current: &mut Vec<(f64, f64)>| {
        if current.len() >= 2 {
            runs.push(std::mem::take(current));
        } else {
            current.clear();
        }
    };
    for pair in points.windows(2) {
        let (a, b) = (pair[0], pair[1]);
        if !finite(&a) || !finite(&b) {
            flush(&mut current);
            continue;
        }
        match clip_segment(a, b, x, y) {
            Some((p, q)) => {
                if current.last() != Some(&p) {
                    flush(&mut current);
                    current.push(p);
                }
                current.push(q);
                if q != b {
                    flush(&mut current);
                }
            }
            None => flush(&mut current),
        }
    }
    flush(&mut current);
    runs
}

fn inside(point: &(f64, f64), x: (f64, f64), y: (f64, f64)) -> bool {
    finite(point) && (x.0..=x.1).contains(&point.0) && (y.0..=y.1).contains(&point.1)
}

/// Draws `panel` filling `area`; returns its layout in back-end pixels (absolute).
pub(crate) fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    scale: Scale,
) -> DrawResult<PanelLayout, DB> {
    let mut chart = draw_axes(area, panel, scale)?;
    draw_data(&mut chart, panel, scale)?;
    let (pixel_x, pixel_y) = chart.plotting_area().get_pixel_range();
    let base = area.get_base_pixel();
    let plot_left = (pixel_x.start - base.0) as f64 / scale.0;
    let plot_right = (pixel_x.end - base.0) as f64 / scale.0;
    let plot_top = (pixel_y.start - base.1) as f64 / scale.0;
    let plot_bottom = (pixel_y.end - base.1) as f64 / scale.0;
    draw_vertical_title(
        area,
        &panel.y.title,
        (Y_TITLE_LEFT, 0.5 * (plot_top + plot_bottom)),
        scale,
    )?;
    draw_tags(
        area,
        panel,
        &chart,
        (plot_left, plot_right, plot_top),
        scale,
    )?;
    if !panel.title.is_empty() {
        draw_centred_text(
            area,
            &panel.title,
            PANEL_TITLE_SIZE,
            (0.5 * (plot_left + plot_right), 4.0),
            BLACK,
            scale,
        )?;
    }
    Ok(PanelLayout {
        title: panel.title.clone(),
        plot_area: [pixel_x.start, pixel_y.start, pixel_x.end, pixel_y.end],
        x_range: panel.x.range,
        y_range: panel.y.range,
        axis_titles: (panel.x.title.clone(), panel.y.title.clone()),
    })
}

/// The chart of `panel` on `area` with its grid, ticks and the x axis' title: room on top for
/// the panel's title and the verticals' tags, on the left for the y ticks and title.
fn draw_axes<'a, DB: DrawingBackend>(
    area: &'a DrawingArea<DB, Shift>,
    panel: &Panel,
    scale: Scale,
) -> DrawResult<Chart<'a, DB>, DB> {
    let (width, height) = area.dim_in_pixel();
    let (width, height) = (width as f64 / scale.0, height as f64 / scale.0);
    let tag_rows = if panel.verticals.iter().any(|v| !v.tag.is_empty()) {
        2.0
    } else {
        0.0
    };
    let top = TITLE_BAND + tag_rows * TAG_ROW + 4.0;
    let y_ticks = choose_ticks(panel.y.range, height - top - X_LABEL_AREA, false);
    let y_label_area = Y_TITLE_LEFT + AXIS_TITLE_SIZE + 12.0 + y_ticks.label_width + 14.0;
    let x_ticks = choose_ticks(panel.x.range, width - y_label_area - RIGHT_MARGIN, true);
    let (x_range, y_range) = (panel.x.range, panel.y.range);
    let mut chart = ChartBuilder::on(area)
        .margin_top(scale.px(top))
        .margin_right(scale.px(RIGHT_MARGIN))
        .x_label_area_size(scale.px(X_LABEL_AREA))
        .y_label_area_size(scale.px(y_label_area))
        .build_cartesian_2d(x_range.0..x_range.1, y_range.0..y_range.1)?;
    let x_format = |v: &f64| x_ticks.label(*v);
    let y_format = |v: &f64| y_ticks.label(*v);
    chart
        .configure_mesh()
        .x_desc(panel.x.title.as_str())
        .label_style(scale.font(TICK_SIZE).color(&RGBColor(40, 40, 40)))
        .axis_desc_style(scale.font(AXIS_TITLE_SIZE).color(&BLACK))
        .bold_line_style(scale.stroke(RGBColor(222, 222, 222), 1.0))
        .light_line_style(scale.stroke(RGBColor(244, 244, 244), 1.0))
        .max_light_lines(1)
        .axis_style(scale.stroke(FRAME_COLOR, 1.0))
        .set_all_tick_mark_size(scale.px(6.0))
        .x_labels(x_ticks.count)
        .y_labels(y_ticks.count)
        .x_label_formatter(&x_format)
        .y_label_formatter(&y_format)
        .draw()?;
    Ok(chart)
}

/// The verticals, the lines clipped to the box with their dots, and the frame on top.
fn draw_data<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    panel: &Panel,
    scale: Scale,
) -> DrawResult<(), DB> {
    let (x_range, y_range) = (panel.x.range, panel.y.range);
    for vertical in &panel.verticals {
        if (x_range.0..=x_range.1).contains(&vertical.x) {
            draw_polyline(
                chart,
                &[(vertical.x, y_range.0), (vertical.x, y_range.1)],
                vertical.color,
                vertical.dash,
                1.6,
                scale,
            )?;
        }
    }
    for line in &panel.lines {
        for run in clip_polyline(&line.points, x_range, y_range) {
            draw_polyline(chart, &run, line.color, line.dash, line.width, scale)?;
        }
        let dots = spaced_dots(chart, &line.dots, (x_range, y_range), scale);
        chart.draw_series(
            dots.into_iter()
                .map(|p| Circle::new(p, scale.px(DOT_RADIUS), line.color.filled())),
        )?;
    }
    // Frame on top of everything.
    chart.draw_series(std::iter::once(PathElement::new(
        vec![
            (x_range.0, y_range.0),
            (x_range.1, y_range.0),
            (x_range.1, y_range.1),
            (x_range.0, y_range.1),
            (x_range.0, y_range.0),
        ],
        scale.stroke(FRAME_COLOR, 1.2),
    )))?;
    Ok(())
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The dots inside the data area, skipping any that would overlap the previous one drawn (a
/// path of hundreds of short steps would otherwise become a thick smear).
fn spaced_dots<DB: DrawingBackend>(
    chart: &Chart<'_, DB>,
    dots: &[(f64, f64)],
    (x_range, y_range): ((f64, f64), (f64, f64)),
    scale: Scale,
) -> Vec<(f64, f64)> {
    let gap = (2.5 * DOT_RADIUS * scale.0).powi(2);
    let mut last: Option<(i32, i32)> = None;
    let mut kept = Vec::new();
    for dot in dots.iter().filter(|p| inside(p, x_range, y_range)) {
        let pixel = chart.backend_coord(dot);
        let far = last.is_none_or(|(x, y)| {
            let (dx, dy) = ((pixel.0 - x) as f64, (pixel.1 - y) as f64);
            dx * dx + dy * dy >= gap
        });
        if far {
            kept.push(*dot);
            last = Some(pixel);
        }
    }
    kept
}

fn draw_polyline<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    points: &[(f64, f64)],
    color: RGBColor,
    dash: Dash,
    width: f64,
    scale: Scale,
) -> DrawResult<(), DB> {
    let style = scale.stroke(color, width);
    match dash.pattern() {
        None => {
            chart.draw_series(LineSeries::new(points.iter().copied(), style))?;
        }
        Some((dash, gap)) => {
            chart.draw_series(DashedLineSeries::new(
                points.iter().copied(),
                scale.px(dash),
                scale.px(gap),
                style,
            ))?;
        }
    }
    Ok(())
}

/// Tags of the vertical lines, centred on their line just above the frame, moved up one row when
/// they would overlap a tag already placed.
fn draw_tags<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    panel: &Panel,
    chart: &Chart<'_, DB>,
    (plot_left, plot_right, plot_top): (f64, f64, f64),
    scale: Scale,
) -> DrawResult<(), DB> {
    let base = area.get_base_pixel();
    let mut placed: Vec<(f64, f64, usize)> = Vec::new();
    for vertical in &panel.verticals {
        let x_range = panel.x.range;
        if vertical.tag.is_empty() || !(x_range.0..=x_range.1).contains(&vertical.x) {
            continue;
        }
        let pixel = chart.backend_coord(&(vertical.x, panel.y.range.1)).0;
        let x = (pixel - base.0) as f64 / scale.0;
        let (width, _) = text_size(&vertical.tag, TAG_SIZE);
        let left = (x - 0.5 * width)
            .max(plot_left - 10.0)
            .min(plot_right + 10.0 - width);
        let right = left + width;
        let row = (0..2)
            .find(|&row| {
                placed
                    .iter()
                    .all(|&(l, r, k)| k != row || right + 6.0 < l || left > r + 6.0)
            })
            .unwrap_or(1);
        placed.push((left, right, row));
        let top = plot_top - 4.0 - (row as f64 + 1.0) * TAG_ROW + 2.0;
        area.draw(&Text::new(
            vertical.tag.clone(),
            (scale.px(left), scale.px(top)),
            scale.font(TAG_SIZE).color(&vertical.color),
        ))?;
    }
    Ok(())
}

/// Where the legend of a [`PanelFigure`] goes: below the panels (rows centred) or in a column
/// of the given width to their right. Either way outside every data area.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum LegendPlacement {
    Below,
    Right { width: f64 },
}

/// A title, panels side by side, and a legend outside them.
#[derive(Clone, Debug)]
pub(crate) struct PanelFigure {
    pub title: String,
    pub panels: Vec<Panel>,
    pub legend: Vec<LegendEntry>,
    pub placement: LegendPlacement,
    pub width: f64,
    pub panel_height: f64,
}

const FIGURE_TITLE_BAND: f64 = 50.0;
const FIGURE_BOTTOM_MARGIN: f64 = 14.0;
const LEGEND_TOP_GAP: f64 = 6.0;

impl PanelFigure {
    fn legend_height(&self) -> f64 {
        match self.placement {
            _ if self.legend.is_empty() => 0.0,
            LegendPlacement::Below => {
                LEGEND_TOP_GAP + legend_rows(&self.legend, self.legend_max_width()).1.1
            }
            LegendPlacement::Right { .. } => 0.0,
        }
    }

    /// Widest legend box: the figure less a margin on each side (below), or the column.
    fn legend_max_width(&self) -> f64 {
        match self.placement {
            LegendPlacement::Below => self.width - 60.0,
            LegendPlacement::Right { width } => width,
        }
    }

    fn panels_width(&self) -> f64 {
        match self.placement {
            LegendPlacement::Right { width } if !self.legend.is_empty() => {
                self.width - width - 16.0
            }
            _ => self.width,
        }
    }
}

impl Figure for PanelFigure {
    fn size(&self) -> (u32, u32) {
        let height =
            FIGURE_TITLE_BAND + self.panel_height + self.legend_height() + FIGURE_BOTTOM_MARGIN;
        (self.width.round() as u32, height.round() as u32)
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: Scale,
    ) -> DrawResult<FigureLayout, DB> {
        root.fill(&WHITE)?;
        draw_centred_text(
            root,
            &self.title,
            TITLE_SIZE,
            (0.5 * self.width, 12.0),
            BLACK,
            scale,
        )?;
        let (_, below_title) = root.split_vertically(scale.px(FIGURE_TITLE_BAND));
        let (panels_row, rest) = below_title.split_vertically(scale.px(self.panel_height));
        let (panels_area, side) = panels_row.split_horizontally(scale.px(self.panels_width()));
        let mut layout = FigureLayout::default();
        let count = self.panels.len().max(1);
        let areas = panels_area.split_evenly((1, count));
        for (panel, area) in self.panels.iter().zip(&areas) {
            let panel_layout = draw_panel(area, panel, scale)?;
            layout.panels.push(PanelLayout {
                plot_area: scale.logical_rect(panel_layout.plot_area),
                ..panel_layout
            });
        }
        if !self.legend.is_empty() {
            let frame = match self.placement {
                LegendPlacement::Below => {
                    let (legend_area, _) = rest.split_horizontally(scale.px(self.width));
                    draw_legend(
                        &legend_area,
                        &self.legend,
                        (LEGEND_TOP_GAP, self.legend_max_width()),
                        scale,
                    )?
                }
                LegendPlacement::Right { .. } => {
                    let top = layout
                        .panels
                        .first()
                        .map(|p| (p.plot_area[1] as f64 - FIGURE_TITLE_BAND).max(0.0))
                        .unwrap_or(0.0);
                    draw_legend(&side, &self.legend, (top, self.legend_max_width()), scale)?
                }
            };
            layout.legend = Some(scale.logical_rect(frame));
        }
        Ok(layout)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_keeps_the_inside_and_breaks_at_the_edges() {
        let runs = clip_polyline(
            &[(0.0, 0.0), (2.0, 2.0), (4.0, 0.0), (6.0, 2.0)],
            (1.0, 5.0),
            (0.0, 1.5),
        );
        assert_eq!(runs.len(), 2);
        assert_eq!(runs[0], vec![(1.0, 1.0), (1.5, 1.5)]);
        assert_eq!(runs[1], vec![(2.5, 1.5), (4.0, 0.0), (5.0, 1.0)]);
    }

    #[test]
    fn tick_decimals_write_every_tick_exactly() {
        assert_eq!(tick_decimals(&[0.08, 0.085, 0.09]), Some(3));
        assert_eq!(tick_decimals(&[0.0, 0.25, 0.5]), Some(2));
        assert_eq!(tick_decimals(&[0.0, 50.0, 100.0]), Some(0));
        assert_eq!(tick_decimals(&[0.0, 2e-4, 4e-4]), None);
    }

    /// The colour bar of a "not wrinkled" map spans ±(threshold) ≈ ±5·10⁻⁴ mm: the key point
    /// at the middle, rounding noise such as −1.08·10⁻¹⁹, is labelled `0`.
    #[test]
    fn rounding_noise_at_zero_is_labelled_zero() {
        let ticks = choose_ticks((-5e-4, 5e-4), 400.0, false);
        assert_eq!(ticks.label(-1.08e-19), "0");
        assert_eq!(ticks.label(2e-4), "2.00e-4");
        let coordinate = RangedCoordf64::from(-5e-4..5e-4);
        for point in coordinate.key_points(ticks.count) {
            assert!(
                !ticks.label(point).contains("e-1"),
                "{}",
                ticks.label(point)
            );
        }
    }

    #[test]
    fn fewer_ticks_on_short_axes() {
        let long = choose_ticks((0.0, 0.123456), 1200.0, true);
        let short = choose_ticks((0.0, 0.123456), 200.0, true);
        assert!(short.count < long.count, "{short:?} {long:?}");
    }
}
