//! `bench.png|svg`: relative error against total run time, log–log, one panel per compared
//! quantity and one series per sweep and path method (and model), each point tagged with the
//! setting it varies.
//!
//! Both axes are logarithmic with a tenth of a decade of room beyond the data, so that no point
//! sits on an axis, and ticks at whole decades (and at 2 and 5 times them on an axis shorter
//! than three decades). Each point's tag is placed beside it without covering another point or
//! tag ([`tag_placement`]); a tag with no free place is left out, the legend and the line's
//! order (coarse to fine) still say which point it is.
//!
//! Drawn in the house style of [`crate::output::plots`] (the bundled DejaVu Sans font, the
//! Tableau colours, a supersampled PNG and an SVG, the legend below the panels). Those helpers
//! are private to that module, so the few needed here are restated; a point with zero error
//! (the reference itself, or $`\lambda_c`$ at a fixed wavenumber) has no place on a log axis
//! and is left out.

mod tag_placement;

use super::plan::{Method, Sweep};
use super::rows::{Bench, BenchRow};
use crate::output::{write_atomically_via_path, write_bytes_atomically};
use plotters::coord::Shift;
use plotters::coord::combinators::WithKeyPoints;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::io;
use std::path::{Path, PathBuf};

/// The font of every plot (DejaVu Sans, Bitstream Vera license, `assets/fonts/`).
use crate::output::plots::canvas::FONT_BYTES;
const FONT: &str = "sans-serif";
/// The PNG is drawn this many times larger and box-filtered down (anti-aliasing).
const SUPERSAMPLING: u32 = 3;
const WIDTH: u32 = 1500;
const PANEL_HEIGHT: u32 = 560;
const TITLE_BAND: f64 = 50.0;
const LEGEND_ROW: f64 = 30.0;

/// Tableau 10, as in the other plots.
const COLORS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];
const CLOSED_FORM_COLOR: RGBColor = RGBColor(60, 60, 60);

/// One polyline of `(time, error)` points with a tag per point, in the order of the sweep.
struct Series {
    label: String,
    /// The sweep it shows (`None`: the comparison with the closed form).
    sweep: Option<Sweep>,
    color: RGBColor,
    dashed: bool,
    points: Vec<(f64, f64, String)>,
}

/// One panel: a title and its series.
struct Panel {
    title: &'static str,
    series: Vec<Series>,
}

type Draw<T, DB> = Result<T, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

fn tag(row: &BenchRow) -> String {
    match row.sweep {
        Sweep::Mesh | Sweep::Reference => format!("{}×{}", row.settings.nx, row.settings.ny),
        Sweep::Order => format!("N={}", row.settings.order),
        Sweep::Tolerance => format!("{:.0e}", row.settings.series_tolerance),
    }
}

/// The series of one quantity: per model, the mesh sweep of every method, then the order and
/// tolerance sweeps of each ANM variant (those the bench ran). Colours follow the series' order,
/// the same in every panel.
fn sweep_series(bench: &Bench, error: fn(&BenchRow) -> Option<f64>) -> Vec<Series> {
    let mut models: Vec<&str> = bench.rows.iter().map(|r| r.model.as_str()).collect();
    models.dedup();
    let several = models.len() > 1;
    let mut series = Vec::new();
    for model in &models {
        let combinations = Method::ALL
            .into_iter()
            .map(|method| (Sweep::Mesh, method))
            .chain(
                [Sweep::Order, Sweep::Tolerance]
                    .into_iter()
                    .flat_map(|sweep| Method::ALL.into_iter().map(move |m| (sweep, m))),
            );
        for (sweep, method) in combinations {
            let rows: Vec<&BenchRow> = bench
                .rows
                .iter()
                .filter(|r| r.model == *model && r.sweep == sweep && r.settings.method == method)
                .collect();
            if rows.is_empty() {
                continue;
            }
            let points = rows
                .iter()
                .filter_map(|r| Some((r.time_total?, error(r)?, tag(r))))
                .filter(|(t, e, _)| *t > 0.0 && *e > 0.0)
                .collect();
            let name = match sweep {
                Sweep::Mesh => "mesh nx×ny",
                Sweep::Order => "order N",
                _ => "series tolerance ε",
            };
            let name = format!("{}: {name}", method.label());
            series.push(Series {
                label: if several {
                    format!("{model}, {name}")
                } else {
                    name
                },
                sweep: Some(sweep),
                color: COLORS[series.len() % COLORS.len()],
                dashed: false,
                points,
            });
        }
    }
    series
}

/// The three panels. The λ_c panel shows the mesh sweep only: the order and tolerance sweeps
/// solve the same buckling problem as the reference (same mesh, same fixed wavenumber), so their
/// λ_c errors are round-off by construction.
fn panels(bench: &Bench) -> Vec<Panel> {
    let mut critical = sweep_series(bench, |r| r.errors.error_critical_load);
    critical.retain(|s| s.sweep == Some(Sweep::Mesh));
    if bench.closed_form_critical_load.is_some() {
        // The reference row comes first in the table: sort coarse (fast) to fine (slow).
        let mut points: Vec<(f64, f64, String)> = bench
            .rows
            .iter()
            .filter(|r| matches!(r.sweep, Sweep::Mesh | Sweep::Reference))
            .filter(|r| r.settings.method == Method::AnmPade)
            .filter_map(|r| {
                Some((
                    r.time_total?,
                    r.errors.error_critical_load_closed_form?,
                    tag(r),
                ))
            })
            .filter(|(t, e, _)| *t > 0.0 && *e > 0.0)
            .collect();
        points.sort_by(|a, b| a.0.total_cmp(&b.0));
        critical.push(Series {
            label: "mesh, against eq. (42)".into(),
            sweep: None,
            color: CLOSED_FORM_COLOR,
            dashed: true,
            points,
        });
    }
    vec![
        Panel {
            title: "critical load λ_c",
            series: critical,
        },
        Panel {
            title: "load at a/h = 1",
            series: sweep_series(bench, |r| r.errors.error_load_at_amplitude_1),
        },
        Panel {
            title: "a/h at λ = 1.1 λ_c",
            series: sweep_series(bench, |r| r.errors.error_amplitude_at_1_1),
        },
    ]
}

/// Writes `STEM.png` (supersampled) and `STEM.svg`; returns the files.
pub fn plot_bench(stem: &Path, bench: &Bench) -> io::Result<Vec<PathBuf>> {
    register_font(FONT, FontStyle::Normal, FONT_BYTES)
        .map_err(|_| io::Error::other("bundled font DejaVuSans.ttf could not be parsed"))?;
    let panels = panels(bench);
    let legend: Vec<(String, RGBColor, bool)> = panels
        .iter()
        .flat_map(|p| &p.series)
        .map(|s| (s.label.clone(), s.color, s.dashed))
        .fold(Vec::new(), |mut all, entry| {
            if !all
                .iter()
                .any(|e: &(String, RGBColor, bool)| e.0 == entry.0)
            {
                all.push(entry);
            }
            all
        });
    let height = (TITLE_BAND + PANEL_HEIGHT as f64 + 20.0 + LEGEND_ROW * legend_rows(&legend))
        .round() as u32;
    let title = format!(
        "Relative error against run time{}",
        if bench.quick { " (quick sweep)" } else { "" }
    );
    let figure = Figure {
        title,
        panels,
        legend,
        size: (WIDTH, height),
    };
    let png = stem.with_extension("png");
    let (big_width, big_height) = (WIDTH * SUPERSAMPLING, height * SUPERSAMPLING);
    let mut big = vec![255u8; 3 * (big_width * big_height) as usize];
    {
        let root =
            BitMapBackend::with_buffer(&mut big, (big_width, big_height)).into_drawing_area();
        figure
            .draw(&root, SUPERSAMPLING as f64)
            .map_err(io::Error::other)?;
        root.present().map_err(io::Error::other)?;
    }
    let small = downsample(&big, big_width, big_height);
    write_atomically_via_path(&png, |temporary| {
        let root = BitMapBackend::new(temporary, (WIDTH, height)).into_drawing_area();
        let image = BitMapElement::with_owned_buffer((0, 0), (WIDTH, height), small)
            .ok_or_else(|| io::Error::other("bitmap buffer of the wrong size"))?;
        root.draw(&image).map_err(io::Error::other)?;
        root.present().map_err(io::Error::other)
    })?;
    let svg = stem.with_extension("svg");
    let mut text = String::new();
    {
        let root =
            plotters_svg::SVGBackend::with_string(&mut text, (WIDTH, height)).into_drawing_area();
        figure.draw(&root, 1.0).map_err(io::Error::other)?;
        root.present().map_err(io::Error::other)?;
    }
    write_bytes_atomically(&svg, text.as_bytes())?;
    Ok(vec![png, svg])
}

/// Averages each `SUPERSAMPLING²` block of an RGB image.
fn downsample(pixels: &[u8], width: u32, height: u32) -> Vec<u8> {
    let factor = SUPERSAMPLING as usize;
    let (width, height) = (width as usize, height as usize);
    let mut small = Vec::with_capacity(3 * width * height / (factor * factor));
    for row in 0..height / factor {
        for column in 0..width / factor {
            let mut sum = [0usize; 3];
            for dy in 0..factor {
                for dx in 0..factor {
                    let start = 3 * ((row * factor + dy) * width + column * factor + dx);
                    for (c, total) in sum.iter_mut().enumerate() {
                        *total += pixels[start + c] as usize;
                    }
                }
            }
            small.extend(sum.map(|t| ((t + factor * factor / 2) / (factor * factor)) as u8));
        }
    }
    small
}

/// Legend entries per row: four.
fn legend_rows(legend: &[(String, RGBColor, bool)]) -> f64 {
    legend.len().div_ceil(4).max(1) as f64
}

struct Figure {
    title: String,
    panels: Vec<Panel>,
    legend: Vec<(String, RGBColor, bool)>,
    size: (u32, u32),
}

/// A logarithmic axis: its bounds, the ticks that carry a label, and the lighter grid lines.
struct LogAxis {
    low: f64,
    high: f64,
    ticks: Vec<f64>,
    light: Vec<f64>,
}

/// Room left beyond the data on a log axis, in decades.
const AXIS_ROOM_DECADES: f64 = 0.1;

/// The axis around the positive values: [`AXIS_ROOM_DECADES`] of room each side, bounds
/// rounded outward to half decades, at least one decade long; labelled ticks at $`10^k`$, and
/// at $`2\cdot 10^k`$ and $`5\cdot 10^k`$ when it is shorter than three decades; light lines at
/// the other multiples.
fn log_axis(values: impl Iterator<Item = f64>) -> LogAxis {
    let (low, high) = values
        .filter(|v| v.is_finite() && *v > 0.0)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    let (mut low, mut high) = if low.is_finite() {
        (
            (2.0 * (low.log10() - AXIS_ROOM_DECADES)).floor() / 2.0,
            (2.0 * (high.log10() + AXIS_ROOM_DECADES)).ceil() / 2.0,
        )
    } else {
        (-3.0, 0.0)
    };
    while high - low < 1.0 {
        low -= 0.5;
        high += 0.5;
    }
    let labelled: &[f64] = if high - low < 3.0 {
        &[1.0, 2.0, 5.0]
    } else {
        &[1.0]
    };
    let (mut ticks, mut light) = (Vec::new(), Vec::new());
    for decade in (low.floor() as i32)..=(high.ceil() as i32) {
        for multiple in 1..10 {
            // Written from its decimal text, so that 1e-5 is the literal, not 10^-5 rounded.
            let value: f64 = format!("{multiple}e{decade}").parse().unwrap_or(f64::NAN);
            let logarithm = value.log10();
            if logarithm < low - 1e-9 || logarithm > high + 1e-9 {
                continue;
            }
            if labelled.contains(&(multiple as f64)) {
                ticks.push(value);
            } else {
                light.push(value);
            }
        }
    }
    LogAxis {
        low: 10f64.powf(low),
        high: 10f64.powf(high),
        ticks,
        light,
    }
}

impl LogAxis {
    /// The axis as plotters' coordinate, with its own ticks.
    fn coordinate(&self) -> WithKeyPoints<LogCoord<f64>> {
        (self.low..self.high)
            .log_scale()
            .with_key_points(self.ticks.clone())
            .with_light_points(self.light.clone())
    }
}

/// Tick text of the time axis: plain decimals between 0.01 and 10⁴, else `1e-5` style.
fn time_tick(value: f64) -> String {
    if (1e-2..1e4).contains(&value) {
        let decimals = (-value.log10().floor()).max(0.0) as usize;
        format!("{value:.decimals$}")
    } else {
        format!("{value:.0e}")
    }
}

/// Tick text of the error axis: `1e-5` style, `1` for one, `2e-5` for a multiple.
fn error_tick(value: f64) -> String {
    if (value - 1.0).abs() < 1e-12 {
        "1".to_string()
    } else {
        format!("{value:.0e}")
    }
}

impl Figure {
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, scale: f64) -> Draw<(), DB> {
        let px = |length: f64| (length * scale).round() as i32;
        let font = |size: f64| (FONT, size * scale).into_font();
        root.fill(&WHITE)?;
        let (title_width, _) = root.estimate_text_size(&self.title, &font(26.0).color(&BLACK))?;
        root.draw(&Text::new(
            self.title.clone(),
            (
                px(self.size.0 as f64 / 2.0) - title_width as i32 / 2,
                px(12.0),
            ),
            font(26.0).color(&BLACK),
        ))?;
        let (_, below) = root.split_vertically(px(TITLE_BAND));
        let (row, legend_area) = below.split_vertically(px(PANEL_HEIGHT as f64));
        let time_axis = log_axis(
            self.panels
                .iter()
                .flat_map(|p| &p.series)
                .flat_map(|s| s.points.iter().map(|p| p.0)),
        );
        for (panel, area) in self.panels.iter().zip(row.split_evenly((1, 3)).iter()) {
            self.draw_panel(area, panel, &time_axis, scale)?;
        }
        for (index, (label, color, dashed)) in self.legend.iter().enumerate() {
            let column = (index % 4) as f64;
            let line = (index / 4) as f64;
            let x = 60.0 + column * (self.size.0 as f64 - 120.0) / 4.0;
            let y = 12.0 + line * LEGEND_ROW;
            let style = color.stroke_width((2.5 * scale).round() as u32);
            let sample = vec![(px(x), px(y)), (px(x + 50.0), px(y))];
            if *dashed {
                legend_area.draw(&DashedPathElement::new(sample, px(12.0), px(7.0), style))?;
            } else {
                legend_area.draw(&PathElement::new(sample, style))?;
                legend_area.draw(&Circle::new((px(x + 25.0), px(y)), px(4.5), color.filled()))?;
            }
            legend_area.draw(&Text::new(
                label.clone(),
                (px(x + 60.0), px(y - 10.0)),
                font(18.0).color(&BLACK),
            ))?;
        }
        Ok(())
    }

    fn draw_panel<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        panel: &Panel,
        time_axis: &LogAxis,
        scale: f64,
    ) -> Draw<(), DB> {
        let px = |length: f64| (length * scale).round() as i32;
        let font = |size: f64| (FONT, size * scale).into_font();
        let error_axis = log_axis(
            panel
                .series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.1)),
        );
        let mut chart = ChartBuilder::on(area)
            .caption(panel.title, font(21.0))
            .margin(px(14.0))
            .x_label_area_size(px(56.0))
            .y_label_area_size(px(80.0))
            .build_cartesian_2d(time_axis.coordinate(), error_axis.coordinate())?;
        chart
            .configure_mesh()
            .x_desc("total run time (s)")
            .y_desc("relative error")
            .label_style(font(17.0).color(&RGBColor(40, 40, 40)))
            .axis_desc_style(font(20.0).color(&BLACK))
            .bold_line_style(RGBColor(222, 222, 222).stroke_width(scale.round() as u32))
            .light_line_style(RGBColor(244, 244, 244).stroke_width(scale.round() as u32))
            .axis_style(RGBColor(60, 60, 60).stroke_width(scale.round() as u32))
            .x_label_formatter(&|v| time_tick(*v))
            .y_label_formatter(&|v| error_tick(*v))
            .draw()?;
        for series in &panel.series {
            draw_series(&mut chart, series, scale)?;
        }
        draw_tags(&chart, panel, scale)?;
        if panel.series.iter().all(|s| s.points.is_empty()) {
            let (width, height) = area.dim_in_pixel();
            area.draw(&Text::new(
                "no non-zero errors",
                (width as i32 / 2 - px(80.0), height as i32 / 2),
                font(18.0).color(&RGBColor(120, 120, 120)),
            ))?;
        }
        Ok(())
    }
}

/// The log–log chart of a panel.
type LogChart<'a, DB> =
    ChartContext<'a, DB, Cartesian2d<WithKeyPoints<LogCoord<f64>>, WithKeyPoints<LogCoord<f64>>>>;

/// One series on `chart`: its line in the order of the sweep (coarse to fine, low to high
/// order, loose to tight, so the line shows what each step of the setting buys and costs) and
/// its points, or a dashed line without points.
fn draw_series<DB: DrawingBackend>(
    chart: &mut LogChart<'_, DB>,
    series: &Series,
    scale: f64,
) -> Draw<(), DB> {
    let px = |length: f64| (length * scale).round() as i32;
    let style = series.color.stroke_width((2.5 * scale).round() as u32);
    let line: Vec<(f64, f64)> = series.points.iter().map(|p| (p.0, p.1)).collect();
    if series.dashed {
        chart.draw_series(DashedLineSeries::new(line, px(12.0), px(7.0), style))?;
    } else {
        // Segment by segment: plotters mitres the joins of a wide polyline, which draws long
        // spikes where a sweep turns back sharply.
        chart.draw_series(
            line.windows(2)
                .map(|pair| PathElement::new(vec![pair[0], pair[1]], style)),
        )?;
        chart.draw_series(
            series
                .points
                .iter()
                .map(|p| Circle::new((p.0, p.1), px(4.5), series.color.filled())),
        )?;
    }
    Ok(())
}

/// The tags of the panel's points (not of a dashed series), each where
/// [`tag_placement::place_tags`] finds room, in the colour of its series.
fn draw_tags<DB: DrawingBackend>(
    chart: &LogChart<'_, DB>,
    panel: &Panel,
    scale: f64,
) -> Draw<(), DB> {
    let font = (FONT, 14.0 * scale).into_font();
    let plot = chart.plotting_area().strip_coord_spec();
    let base = plot.get_base_pixel();
    let pixel = |p: &(f64, f64, String)| {
        let (x, y) = chart.backend_coord(&(p.0, p.1));
        ((x - base.0) as f64, (y - base.1) as f64)
    };
    let (width, height) = plot.dim_in_pixel();
    let markers: Vec<(f64, f64)> = panel
        .series
        .iter()
        .filter(|s| !s.dashed)
        .flat_map(|s| s.points.iter().map(pixel))
        .collect();
    let segments: Vec<tag_placement::Segment> = panel
        .series
        .iter()
        .flat_map(|s| {
            s.points
                .windows(2)
                .map(|pair| (pixel(&pair[0]), pixel(&pair[1])))
        })
        .collect();
    let mut tags = Vec::new();
    let mut texts = Vec::new();
    for series in panel.series.iter().filter(|s| !s.dashed) {
        for point in &series.points {
            let (w, h) = plot.estimate_text_size(&point.2, &font.clone().color(&BLACK))?;
            tags.push((pixel(point), (w as f64, h as f64)));
            texts.push((point.2.clone(), series.color));
        }
    }
    let scene = tag_placement::Scene {
        bounds: tag_placement::Rectangle {
            left: 0.0,
            top: 0.0,
            right: width as f64,
            bottom: height as f64,
        },
        markers: &markers,
        marker_radius: 7.0 * scale,
        segments: &segments,
    };
    let corners = tag_placement::place_tags(&scene, &tags);
    for ((text, color), corner) in texts.into_iter().zip(corners) {
        if let Some((left, top)) = corner {
            plot.draw(&Text::new(
                text,
                (left.round() as i32, top.round() as i32),
                font.clone().color(&color),
            ))?;
        }
    }
    Ok(())
}
