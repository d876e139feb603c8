//! PNG and SVG plots drawn with [`plotters`]: load–response curves ([`plot_response`]), profiles
//! along a line at several loads ([`plot_profiles`]) and heat maps of a scalar over the domain
//! ([`plot_map`]).
//!
//! Every plot is drawn twice by the same code, once on a bitmap (`STEM.png`) and once as vector
//! graphics (`STEM.svg`). Text uses the DejaVu Sans font bundled in `assets/fonts/`, so the
//! pictures look the same on machines without system fonts.

use super::path_table::with_path;
use super::vtu::check_bounds;
use super::{OutputError, check_length, invalid};
use plotters::coord::Shift;
/// Pixel coordinates (plotters' `BackendCoord`).
type BackendCoord = (i32, i32);
use plotters::element::{ComposedElement, DashedPathElement};
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::ffi::OsString;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The bundled font (DejaVu Sans, Bitstream Vera license, see `assets/fonts/LICENSE-DejaVu.txt`).
static FONT_BYTES: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
/// Font family name under which the bundled font is registered.
const FONT: &str = "sans-serif";

/// How a [`Curve`] is drawn.
#[derive(Clone, Debug, PartialEq)]
pub enum CurveStyle {
    /// Solid line through the points.
    Line,
    /// Dashed line through the points (e.g. a closed-form solution).
    Dashed,
    /// A marker at each point, no line.
    Points,
    /// Solid line through the points plus a marker at each of the given points (e.g. the step
    /// end points of an ANM path drawn through its dense output).
    LineWithMarkers(Vec<(f64, f64)>),
}

/// One data series of a plot. Points with a non-finite coordinate are skipped (a line is broken
/// there). An empty label keeps the curve out of the legend.
#[derive(Clone, Debug, PartialEq)]
pub struct Curve {
    /// Legend text.
    pub label: String,
    /// The points $`(x, y)`$ in drawing order.
    pub points: Vec<(f64, f64)>,
    /// Line or markers.
    pub style: CurveStyle,
}

impl Curve {
    /// A solid line.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Curve {
            label: label.into(),
            points,
            style: CurveStyle::Line,
        }
    }

    /// A dashed line.
    pub fn dashed(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Curve {
            label: label.into(),
            points,
            style: CurveStyle::Dashed,
        }
    }

    /// Markers only.
    pub fn points(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Curve {
            label: label.into(),
            points,
            style: CurveStyle::Points,
        }
    }
}

/// A labelled vertical line across the plot, e.g. the bifurcation load or the load at which
/// ellipticity is lost.
#[derive(Clone, Debug, PartialEq)]
pub struct VerticalMarker {
    /// Text written next to the line.
    pub label: String,
    /// Abscissa of the line.
    pub x: f64,
}

/// Plots load–response curves with optional vertical markers to `STEM.png` (1200 × 800 pixels)
/// and `STEM.svg`. The legend goes to the corner of the plot that covers the fewest data.
///
/// Errors: no finite point in any curve, a non-finite marker abscissa, or a failure writing the
/// files.
pub fn plot_response(
    stem: &Path,
    title: &str,
    curves: &[Curve],
    x_label: &str,
    y_label: &str,
    markers: &[VerticalMarker],
) -> io::Result<()> {
    let figure = CurveFigure::new(
        title,
        curves,
        x_label,
        y_label,
        markers,
        Palette::Categorical,
    )?;
    render(stem, (1200, 800), &figure)
}

/// Plots profiles (typically one quantity along a line of the domain at several loads) to
/// `STEM.png` (1200 × 700 pixels) and `STEM.svg`; the curves are coloured along a sequential
/// colour map in the order given, so pass them by increasing load.
///
/// Errors: as [`plot_response`].
pub fn plot_profiles(
    stem: &Path,
    title: &str,
    x_label: &str,
    profiles: &[Curve],
) -> io::Result<()> {
    let figure = CurveFigure::new(title, profiles, x_label, "", &[], Palette::Sequential)?;
    render(stem, (1200, 700), &figure)
}

/// Heat map of a scalar sampled on a regular grid of `nx × ny` cells over
/// `bounds = [x0, x1, y0, y1]` (mm), written to `STEM.png` and `STEM.svg`.
///
/// `values[j * nx + i]` is the value in cell $`(i, j)`$, whose centre is
/// $`(x_0 + (i + \tfrac12)\,\Delta x,\ y_0 + (j + \tfrac12)\,\Delta y)`$ (see
/// [`grid_cell_centres`]). The diverging colour map (blue – white – red) is centred at 0 and
/// symmetric, $`\pm \max |v|`$; a colour bar is drawn on the right. The plot area keeps the
/// aspect ratio of the domain (one millimetre is as long in $`X`$ as in $`Y`$), so long domains
/// give wide images. Non-finite values are drawn grey.
///
/// Errors: bad bounds, `nx` or `ny` zero, `values` of the wrong length, failure writing the files.
pub fn plot_map(
    stem: &Path,
    title: &str,
    bounds: [f64; 4],
    nx: usize,
    ny: usize,
    values: &[f64],
) -> io::Result<()> {
    check_bounds(bounds)?;
    if nx == 0 || ny == 0 {
        return Err(invalid(
            "map grid",
            format!("needs at least one cell in each direction, got {nx} × {ny}"),
        ));
    }
    check_length("map values", nx * ny, values.len())?;
    let figure = MapFigure::new(title, bounds, nx, ny, values);
    render(stem, figure.size(), &figure)
}

/// Centres of the `nx × ny` cells of [`plot_map`], in the order of its `values`
/// (`j * nx + i`).
pub fn grid_cell_centres(bounds: [f64; 4], nx: usize, ny: usize) -> Vec<(f64, f64)> {
    let [x0, x1, y0, y1] = bounds;
    let (dx, dy) = ((x1 - x0) / nx as f64, (y1 - y0) / ny as f64);
    (0..ny)
        .flat_map(|j| {
            (0..nx).map(move |i| (x0 + (i as f64 + 0.5) * dx, y0 + (j as f64 + 0.5) * dy))
        })
        .collect()
}

// ---------------------------------------------------------------------------------------------
// Rendering on both back ends.

type DrawResult<DB> = Result<(), DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// A picture that can be drawn on any plotters back end.
trait Figure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB>;
}

/// `STEM.extension`, keeping any dot already in the stem's file name.
fn with_suffix(stem: &Path, extension: &str) -> PathBuf {
    let mut name = OsString::from(stem.as_os_str());
    name.push(".");
    name.push(extension);
    PathBuf::from(name)
}

fn plotting_error(path: &Path, error: impl std::fmt::Display) -> io::Error {
    OutputError::Library {
        library: "plotters",
        message: format!("{}: {error}", path.display()),
    }
    .into()
}

fn register_bundled_font() -> io::Result<()> {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    let registered =
        *REGISTERED.get_or_init(|| register_font(FONT, FontStyle::Normal, FONT_BYTES).is_ok());
    if registered {
        Ok(())
    } else {
        Err(invalid(
            "bundled font",
            "DejaVuSans.ttf could not be parsed",
        ))
    }
}

fn render(stem: &Path, size: (u32, u32), figure: &impl Figure) -> io::Result<()> {
    register_bundled_font()?;
    let png = with_suffix(stem, "png");
    {
        let root = BitMapBackend::new(&png, size).into_drawing_area();
        figure
            .draw(&root)
            .map_err(|error| plotting_error(&png, error))?;
        root.present()
            .map_err(|error| plotting_error(&png, error))?;
    }
    let svg = with_suffix(stem, "svg");
    {
        let root = plotters_svg::SVGBackend::new(&svg, size).into_drawing_area();
        figure
            .draw(&root)
            .map_err(|error| plotting_error(&svg, error))?;
        root.present()
            .map_err(|error| plotting_error(&svg, error))?;
    }
    fix_embedded_image_type(&svg)
}

/// plotters-svg embeds bitmaps as `data:png;base64,…`, which is not a MIME type; browsers and
/// editors expect `data:image/png;base64,…`.
fn fix_embedded_image_type(svg: &Path) -> io::Result<()> {
    const WRONG: &str = "href=\"data:png;base64,";
    let text = std::fs::read_to_string(svg).map_err(|error| with_path(svg, error))?;
    if text.contains(WRONG) {
        let fixed = text.replace(WRONG, "href=\"data:image/png;base64,");
        std::fs::write(svg, fixed).map_err(|error| with_path(svg, error))?;
    }
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Curves.

const TITLE_SIZE: f64 = 30.0;
const AXIS_DESCRIPTION_SIZE: f64 = 24.0;
const TICK_LABEL_SIZE: f64 = 20.0;
const LEGEND_SIZE: f64 = 20.0;
/// Width reserved for the legend glyph (36 pixels) and the gap before the text.
const LEGEND_GLYPH_AREA: u32 = 50;

/// Colours of curves in a plot.
#[derive(Clone, Copy)]
enum Palette {
    /// Distinct hues (Tableau 10) in order.
    Categorical,
    /// Viridis from dark to light-green, evenly over the curves.
    Sequential,
}

const TABLEAU: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// Viridis at a few stops; interpolated linearly.
const VIRIDIS: [(u8, u8, u8); 6] = [
    (68, 1, 84),
    (65, 68, 135),
    (42, 120, 142),
    (34, 168, 132),
    (122, 209, 81),
    (253, 231, 37),
];

impl Palette {
    fn color(self, index: usize, count: usize) -> RGBColor {
        match self {
            Palette::Categorical => TABLEAU[index % TABLEAU.len()],
            Palette::Sequential => {
                // Stop before the yellow end, which is hard to read on white.
                let t = if count <= 1 {
                    0.0
                } else {
                    0.85 * index as f64 / (count - 1) as f64
                };
                let scaled = t * (VIRIDIS.len() - 1) as f64;
                let k = (scaled.floor() as usize).min(VIRIDIS.len() - 2);
                let s = scaled - k as f64;
                let mix = |a: u8, b: u8| (a as f64 + s * (b as f64 - a as f64)).round() as u8;
                let (a, b) = (VIRIDIS[k], VIRIDIS[k + 1]);
                RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
            }
        }
    }
}

struct CurveFigure<'a> {
    title: &'a str,
    curves: &'a [Curve],
    x_label: &'a str,
    y_label: &'a str,
    markers: &'a [VerticalMarker],
    palette: Palette,
    x_range: (f64, f64),
    y_range: (f64, f64),
}

/// A range `[low, high]` containing the values with the given relative padding; degenerate ranges
/// are widened.
fn padded_range(low: f64, high: f64, pad_low: f64, pad_high: f64) -> (f64, f64) {
    let span = high - low;
    if span > 0.0 {
        (low - pad_low * span, high + pad_high * span)
    } else {
        let half = if low == 0.0 { 1.0 } else { 0.1 * low.abs() };
        (low - half, high + half)
    }
}

fn finite(point: &(f64, f64)) -> bool {
    point.0.is_finite() && point.1.is_finite()
}

impl<'a> CurveFigure<'a> {
    fn new(
        title: &'a str,
        curves: &'a [Curve],
        x_label: &'a str,
        y_label: &'a str,
        markers: &'a [VerticalMarker],
        palette: Palette,
    ) -> io::Result<Self> {
        if let Some(marker) = markers.iter().find(|m| !m.x.is_finite()) {
            return Err(invalid(
                format!("marker `{}`", marker.label),
                format!("abscissa must be finite, got {}", marker.x),
            ));
        }
        let all_points = curves.iter().flat_map(|curve| {
            let extra: &[(f64, f64)] = match &curve.style {
                CurveStyle::LineWithMarkers(marks) => marks,
                _ => &[],
            };
            curve.points.iter().chain(extra).filter(|p| finite(p))
        });
        let (mut x_min, mut x_max, mut y_min, mut y_max) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for &(x, y) in all_points {
            x_min = x_min.min(x);
            x_max = x_max.max(x);
            y_min = y_min.min(y);
            y_max = y_max.max(y);
        }
        if !x_min.is_finite() {
            return Err(invalid("plot", "no curve has a finite point"));
        }
        for marker in markers {
            x_min = x_min.min(marker.x);
            x_max = x_max.max(marker.x);
        }
        Ok(CurveFigure {
            title,
            curves,
            x_label,
            y_label,
            markers,
            palette,
            x_range: padded_range(x_min, x_max, 0.02, 0.02),
            y_range: padded_range(y_min, y_max, 0.04, 0.06),
        })
    }

    /// The legend corner covering the fewest samples of the curves and marker labels, in plot
    /// coordinates normalised to $`[0, 1]^2`$ (y upwards).
    fn legend_position(
        &self,
        occupied: &[(f64, f64)],
        legend_size: (f64, f64),
    ) -> SeriesLabelPosition {
        let (width, height) = (legend_size.0 + 0.03, legend_size.1 + 0.03);
        let candidates = [
            (SeriesLabelPosition::UpperLeft, (0.0, 1.0 - height)),
            (SeriesLabelPosition::UpperRight, (1.0 - width, 1.0 - height)),
            (SeriesLabelPosition::LowerRight, (1.0 - width, 0.0)),
            (SeriesLabelPosition::LowerLeft, (0.0, 0.0)),
        ];
        let mut best = (usize::MAX, SeriesLabelPosition::UpperLeft);
        for (position, (left, bottom)) in candidates {
            let covered = occupied
                .iter()
                .filter(|&&(u, v)| {
                    u >= left && u <= left + width && v >= bottom && v <= bottom + height
                })
                .count();
            if covered < best.0 {
                best = (covered, position);
            }
        }
        best.1
    }

    /// Samples along every curve (lines densified) in normalised plot coordinates.
    fn occupied_samples(&self) -> Vec<(f64, f64)> {
        let normalise = |(x, y): (f64, f64)| {
            (
                (x - self.x_range.0) / (self.x_range.1 - self.x_range.0),
                (y - self.y_range.0) / (self.y_range.1 - self.y_range.0),
            )
        };
        let mut samples = Vec::new();
        for curve in self.curves {
            let points: Vec<(f64, f64)> = curve
                .points
                .iter()
                .filter(|p| finite(p))
                .map(|&p| normalise(p))
                .collect();
            samples.extend(&points);
            if curve.style != CurveStyle::Points {
                for pair in points.windows(2) {
                    let ((u0, v0), (u1, v1)) = (pair[0], pair[1]);
                    let steps = ((u1 - u0).hypot(v1 - v0) / 0.005).ceil().min(1000.0) as usize;
                    for k in 1..steps {
                        let t = k as f64 / steps as f64;
                        samples.push((u0 + t * (u1 - u0), v0 + t * (v1 - v0)));
                    }
                }
            }
        }
        samples
    }
}

/// Draws the marker of [`CurveStyle::Points`] and [`CurveStyle::LineWithMarkers`].
fn marker_element((x, y): (f64, f64), color: RGBColor) -> Circle<(f64, f64), i32> {
    Circle::new((x, y), 4, color.filled())
}

impl Figure for CurveFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(root)
            .caption(self.title, (FONT, TITLE_SIZE))
            .margin(20)
            .margin_right(35)
            .x_label_area_size(70)
            .y_label_area_size(if self.y_label.is_empty() { 80 } else { 105 })
            .build_cartesian_2d(
                self.x_range.0..self.x_range.1,
                self.y_range.0..self.y_range.1,
            )?;
        let tick_style = (FONT, TICK_LABEL_SIZE).into_font();
        let description_style = (FONT, AXIS_DESCRIPTION_SIZE).into_font();
        chart
            .configure_mesh()
            .x_desc(self.x_label)
            .y_desc(self.y_label)
            .label_style(tick_style)
            .axis_desc_style(description_style)
            .light_line_style(RGBColor(240, 240, 240))
            .bold_line_style(RGBColor(210, 210, 210))
            .max_light_lines(1)
            .x_labels(8)
            .y_labels(8)
            .x_label_formatter(&|v| format_coordinate(*v))
            .y_label_formatter(&|v| format_coordinate(*v))
            .draw()?;

        let (pixel_x, pixel_y) = chart.plotting_area().get_pixel_range();
        let plot_width = (pixel_x.end - pixel_x.start) as f64;
        let plot_height = (pixel_y.end - pixel_y.start) as f64;
        let mut occupied = self.occupied_samples();

        // Vertical markers: dashed grey lines, labels stacked at the top of the plot.
        let label_style = (FONT, LEGEND_SIZE).into_font().color(&BLACK);
        let plot_area = chart.plotting_area().strip_coord_spec();
        for (index, marker) in self.markers.iter().enumerate() {
            let top = (marker.x, self.y_range.1);
            let bottom = (marker.x, self.y_range.0);
            chart.draw_series(std::iter::once(DashedPathElement::new(
                vec![bottom, top],
                8,
                6,
                RGBColor(90, 90, 90).stroke_width(2),
            )))?;
            let (text_width, text_height) = root.estimate_text_size(&marker.label, &label_style)?;
            let line_pixel = ((marker.x - self.x_range.0) / (self.x_range.1 - self.x_range.0)
                * plot_width)
                .round() as i32;
            let left = if line_pixel + 8 + text_width as i32 <= plot_width as i32 - 4 {
                line_pixel + 8
            } else {
                line_pixel - 8 - text_width as i32
            };
            let top_pixel = 8 + index as i32 * (text_height as i32 + 10);
            plot_area.draw(&Rectangle::new(
                [
                    (left - 3, top_pixel - 2),
                    (
                        left + text_width as i32 + 3,
                        top_pixel + text_height as i32 + 3,
                    ),
                ],
                WHITE.mix(0.85).filled(),
            ))?;
            plot_area.draw(&Text::new(
                marker.label.clone(),
                (left, top_pixel),
                &label_style,
            ))?;
            // Mark the label box as occupied for the legend placement.
            for i in 0..=10 {
                for j in 0..=4 {
                    let u = (left as f64 + text_width as f64 * i as f64 / 10.0) / plot_width;
                    let v = 1.0
                        - (top_pixel as f64 + text_height as f64 * j as f64 / 4.0) / plot_height;
                    occupied.push((u, v));
                }
            }
        }

        let count = self.curves.len();
        for (index, curve) in self.curves.iter().enumerate() {
            let color = self.palette.color(index, count);
            let segments = finite_runs(&curve.points);
            let line_style = color.stroke_width(2);
            let series_label = match &curve.style {
                CurveStyle::Line | CurveStyle::LineWithMarkers(_) => {
                    let mut annotation = None;
                    for run in &segments {
                        annotation =
                            Some(chart.draw_series(LineSeries::new(run.clone(), line_style))?);
                    }
                    if let CurveStyle::LineWithMarkers(marks) = &curve.style {
                        let marks = marks.iter().filter(|p| finite(p));
                        annotation =
                            Some(chart.draw_series(marks.map(|&p| marker_element(p, color)))?);
                    }
                    annotation
                }
                CurveStyle::Dashed => {
                    let mut annotation = None;
                    for run in &segments {
                        annotation = Some(chart.draw_series(DashedLineSeries::new(
                            run.clone(),
                            12,
                            8,
                            line_style,
                        ))?);
                    }
                    annotation
                }
                CurveStyle::Points => Some(
                    chart.draw_series(
                        curve
                            .points
                            .iter()
                            .filter(|p| finite(p))
                            .map(|&p| marker_element(p, color)),
                    )?,
                ),
            };
            if curve.label.is_empty() {
                continue;
            }
            let Some(annotation) = series_label else {
                continue;
            };
            let style = curve.style.clone();
            annotation
                .label(curve.label.clone())
                .legend(move |(x, y)| legend_glyph::<DB>(&style, (x, y), color));
        }

        let labelled: Vec<&Curve> = self.curves.iter().filter(|c| !c.label.is_empty()).collect();
        if !labelled.is_empty() {
            let legend_style = (FONT, LEGEND_SIZE).into_font().color(&BLACK);
            let mut widest = 0u32;
            for curve in &labelled {
                widest = widest.max(root.estimate_text_size(&curve.label, &legend_style)?.0);
            }
            // Legend box in pixels: glyph (≈ 40), gaps, text; rows of ≈ 1.5 × font size.
            let legend_width = (widest as f64 + LEGEND_GLYPH_AREA as f64 + 40.0) / plot_width;
            let legend_height = (labelled.len() as f64 * 1.5 * LEGEND_SIZE + 20.0) / plot_height;
            let position = self.legend_position(&occupied, (legend_width, legend_height));
            chart
                .configure_series_labels()
                .position(position)
                .margin(12)
                .legend_area_size(LEGEND_GLYPH_AREA)
                .label_font(legend_style)
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(160, 160, 160))
                .draw()?;
        }
        Ok(())
    }
}

/// Runs of consecutive finite points (a non-finite point breaks the line).
fn finite_runs(points: &[(f64, f64)]) -> Vec<Vec<(f64, f64)>> {
    let mut runs = Vec::new();
    let mut current = Vec::new();
    for point in points {
        if finite(point) {
            current.push(*point);
        } else if !current.is_empty() {
            runs.push(std::mem::take(&mut current));
        }
    }
    if !current.is_empty() {
        runs.push(current);
    }
    runs
}

/// Legend sample: two path pieces and a marker, relative to the legend entry's anchor.
type Glyph<DB> = ComposedElement<
    BackendCoord,
    DB,
    PathElement<BackendCoord>,
    ComposedElement<BackendCoord, DB, PathElement<BackendCoord>, Circle<BackendCoord, i32>>,
>;

/// The legend sample of a curve: a 36-pixel line (two dashes when dashed) and/or a marker.
fn legend_glyph<DB: DrawingBackend>(
    style: &CurveStyle,
    (x, y): BackendCoord,
    color: RGBColor,
) -> Glyph<DB> {
    let stroke = color.stroke_width(3);
    let invisible = color.mix(0.0).stroke_width(0);
    let (first, second, radius) = match style {
        CurveStyle::Line => ([(0, 0), (36, 0)], None, 0),
        CurveStyle::Dashed => ([(0, 0), (13, 0)], Some([(23, 0), (36, 0)]), 0),
        CurveStyle::Points => ([(18, 0), (18, 0)], None, 4),
        CurveStyle::LineWithMarkers(_) => ([(0, 0), (36, 0)], None, 4),
    };
    let first_style = if matches!(style, CurveStyle::Points) {
        invisible
    } else {
        stroke
    };
    let second = match second {
        Some(points) => PathElement::new(points.to_vec(), stroke),
        None => PathElement::new(vec![(0, 0), (0, 0)], invisible),
    };
    let marker = if radius > 0 {
        Circle::new((18, 0), radius, color.filled())
    } else {
        Circle::new((18, 0), 0, invisible)
    };
    EmptyElement::at((x, y)) + PathElement::new(first.to_vec(), first_style) + second + marker
}

// ---------------------------------------------------------------------------------------------
// Heat map.

struct MapFigure<'a> {
    title: &'a str,
    bounds: [f64; 4],
    nx: usize,
    ny: usize,
    values: &'a [f64],
    /// Half-range of the colour map, $`\max |v|`$ (1 when all values vanish).
    limit: f64,
    /// Plot area size in pixels, aspect ratio of the domain.
    plot_size: (u32, u32),
}

const MAP_TITLE_HEIGHT: u32 = 60;
const MAP_MARGIN: u32 = 20;
const MAP_Y_LABEL_AREA: u32 = 100;
const MAP_X_LABEL_AREA: u32 = 75;
const MAP_COLOR_BAR_AREA: u32 = 170;

impl<'a> MapFigure<'a> {
    fn new(title: &'a str, bounds: [f64; 4], nx: usize, ny: usize, values: &'a [f64]) -> Self {
        let limit = values
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let aspect = (bounds[1] - bounds[0]) / (bounds[3] - bounds[2]);
        // Wide domains get wide pictures; the height is kept between 160 and 700 pixels where the
        // width allows it.
        let mut width = if aspect >= 3.0 { 1600.0 } else { 1100.0 };
        let mut height = width / aspect;
        if height > 700.0 {
            height = 700.0;
            width = (height * aspect).max(300.0);
        }
        if height < 160.0 {
            height = 160.0;
            width = (height * aspect).min(2400.0);
        }
        MapFigure {
            title,
            bounds,
            nx,
            ny,
            values,
            limit: if limit > 0.0 { limit } else { 1.0 },
            plot_size: (width.round() as u32, height.round() as u32),
        }
    }

    fn size(&self) -> (u32, u32) {
        let (width, height) = self.plot_size;
        (
            MAP_MARGIN + MAP_Y_LABEL_AREA + width + MAP_COLOR_BAR_AREA + MAP_MARGIN,
            MAP_TITLE_HEIGHT + height + MAP_X_LABEL_AREA + MAP_MARGIN,
        )
    }
}

/// Diverging cool–warm colour map (Moreland): $`t \in [-1, 1]`$ from blue through light grey to
/// red.
fn diverging_color(t: f64) -> RGBColor {
    if !t.is_finite() {
        return RGBColor(150, 150, 150);
    }
    let t = t.clamp(-1.0, 1.0);
    let (cold, middle, warm) = (
        (59.0, 76.0, 192.0),
        (242.0, 242.0, 242.0),
        (180.0, 4.0, 38.0),
    );
    let (from, to, s) = if t < 0.0 {
        (middle, cold, -t)
    } else {
        (middle, warm, t)
    };
    let mix = |a: f64, b: f64| (a + s * (b - a)).round() as u8;
    RGBColor(mix(from.0, to.0), mix(from.1, to.1), mix(from.2, to.2))
}

impl Figure for MapFigure<'_> {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<DB> {
        root.fill(&WHITE)?;
        let (title_area, body) = root.split_vertically(MAP_TITLE_HEIGHT);
        let title_style = (FONT, TITLE_SIZE).into_font().color(&BLACK);
        let (title_width, _) = root.estimate_text_size(self.title, &title_style)?;
        let (total_width, _) = root.dim_in_pixel();
        title_area.draw(&Text::new(
            self.title.to_string(),
            ((total_width as i32 - title_width as i32) / 2, 15),
            &title_style,
        ))?;
        let main_width = MAP_MARGIN + MAP_Y_LABEL_AREA + self.plot_size.0;
        let (main, color_bar_area) = body.split_horizontally(main_width);

        let [x0, x1, y0, y1] = self.bounds;
        let mut chart = ChartBuilder::on(&main)
            .margin_left(MAP_MARGIN)
            .margin_bottom(MAP_MARGIN)
            .x_label_area_size(MAP_X_LABEL_AREA)
            .y_label_area_size(MAP_Y_LABEL_AREA)
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let x_ticks = (self.plot_size.0 / 130).clamp(2, 12) as usize;
        let y_ticks = (self.plot_size.1 / 50).clamp(2, 10) as usize;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("X (mm)")
            .y_desc("Y (mm)")
            .label_style((FONT, TICK_LABEL_SIZE))
            .axis_desc_style((FONT, AXIS_DESCRIPTION_SIZE))
            .x_labels(x_ticks)
            .y_labels(y_ticks)
            .x_label_formatter(&|v| format_coordinate(*v))
            .y_label_formatter(&|v| format_coordinate(*v))
            .draw()?;

        // Cells as one raster image of the plot area (embedded as PNG in the SVG file): each
        // pixel takes the colour of the cell containing its centre.
        let (pixel_x, pixel_y) = chart.plotting_area().get_pixel_range();
        let (width, height) = (
            (pixel_x.end - pixel_x.start).max(1) as u32,
            (pixel_y.end - pixel_y.start).max(1) as u32,
        );
        let mut raster = Vec::with_capacity(3 * (width * height) as usize);
        for row in 0..height {
            // Image rows run downwards, Y upwards.
            let y_fraction = 1.0 - (row as f64 + 0.5) / height as f64;
            let j = ((y_fraction * self.ny as f64) as usize).min(self.ny - 1);
            for column in 0..width {
                let x_fraction = (column as f64 + 0.5) / width as f64;
                let i = ((x_fraction * self.nx as f64) as usize).min(self.nx - 1);
                let color = diverging_color(self.values[j * self.nx + i] / self.limit);
                raster.extend([color.0, color.1, color.2]);
            }
        }
        if let Some(image) = BitMapElement::with_owned_buffer((0, 0), (width, height), raster) {
            chart.plotting_area().strip_coord_spec().draw(&image)?;
        }
        // Frame on top of the cells.
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)],
            BLACK.stroke_width(1),
        )))?;

        // Colour bar, aligned with the plot area.
        let mut bar = ChartBuilder::on(&color_bar_area)
            .margin_left(30)
            .margin_right(MAP_COLOR_BAR_AREA - 30 - 30 - 90 + MAP_MARGIN)
            .margin_bottom(MAP_MARGIN)
            .x_label_area_size(MAP_X_LABEL_AREA)
            .right_y_label_area_size(90)
            .build_cartesian_2d(0.0..1.0, -self.limit..self.limit)?;
        let format = |v: &f64| format_tick(*v, self.limit);
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .set_tick_mark_size(LabelAreaPosition::Right, 8)
            .label_style((FONT, TICK_LABEL_SIZE))
            .y_labels(if self.plot_size.1 < 250 { 5 } else { 9 })
            .y_label_formatter(&format)
            .draw()?;
        let levels = 128;
        bar.draw_series((0..levels).map(|k| {
            let a = -self.limit + 2.0 * self.limit * k as f64 / levels as f64;
            let b = -self.limit + 2.0 * self.limit * (k + 1) as f64 / levels as f64;
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                diverging_color(0.5 * (a + b) / self.limit).filled(),
            )
        }))?;
        bar.draw_series(std::iter::once(PathElement::new(
            vec![
                (0.0, -self.limit),
                (1.0, -self.limit),
                (1.0, self.limit),
                (0.0, self.limit),
                (0.0, -self.limit),
            ],
            BLACK.stroke_width(1),
        )))?;
        Ok(())
    }
}

/// Tick text of an axis: plain decimals without trailing zeros (`0.1`, `200`), scientific
/// notation for very small or very large magnitudes.
fn format_coordinate(value: f64) -> String {
    let magnitude = value.abs();
    if magnitude != 0.0 && !(1e-4..1e6).contains(&magnitude) {
        return format!("{value:.3e}");
    }
    let text = format!("{:.6}", value);
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_string()
    } else {
        text.to_string()
    }
}

/// Tick text with as many decimals as the scale needs.
fn format_tick(value: f64, scale: f64) -> String {
    if !(1e-3..1e5).contains(&scale) {
        return format!("{value:.2e}");
    }
    let decimals = (2.0 - scale.log10().floor()).clamp(0.0, 6.0) as usize;
    let text = format!("{value:.decimals$}");
    if text
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        "0".to_string()
    } else {
        text
    }
}
