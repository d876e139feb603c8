//! The wrinkle map ([`plot_wrinkle_map`]): a sampled field (the physical deflection) over the
//! domain on a symmetric diverging colour scale that does not invent wrinkles.

use super::canvas::{
    AXIS_TITLE_SIZE, DrawResult, FRAME_COLOR, Figure, Scale, TICK_SIZE, TITLE_SIZE,
    diverging_color, draw_centred_text, draw_vertical_title, render, text_size,
};
use super::panel::choose_ticks;
use super::{FigureLayout, PanelLayout, PlotOutput};
use crate::output::grid::GridField;
use crate::output::invalid;
use crate::output::quantity::{Quantity, format_significant};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::io;
use std::path::Path;

/// A field to draw as a wrinkle map.
#[derive(Clone, Debug, PartialEq)]
pub struct WrinkleMap {
    /// The sampled field (its quantity labels the colour bar).
    pub field: GridField,
    /// Smallest half-range of the colour scale, in the field's unit (e.g. $`10^{-3} h`$): the
    /// scale is $`\pm\max(\max|v|, \text{threshold})`$, and below it the map says "not wrinkled".
    pub threshold: f64,
    /// How the threshold was chosen, e.g. `"10⁻³ h"` (written after its value).
    pub threshold_label: String,
    /// Abscissa, default `X (mm)`.
    pub x_axis: Quantity,
    /// Ordinate, default `Y (mm)`.
    pub y_axis: Quantity,
    /// The field's largest $`|v|`$ when it is known exactly (e.g. the run's
    /// $`\max|w| = \max(|w_0| + 2|A|)`$ at the nodes of an envelope model), so that the map states
    /// the same number as the summary; `None`: the largest sample of `field`, which can miss a
    /// crest that falls between two samples.
    pub peak: Option<f64>,
    /// The note under the title when the caller words it (e.g. for a field that is not a
    /// deflection); `None`: [`WrinkleMap::note`] writes the largest value and the threshold.
    pub caption: Option<String>,
    /// The domain's boundary as quadratic segments `[end, end, middle]` (mm), drawn over the
    /// field when the domain is not the rectangle of the axes (a hole, a curved outline;
    /// samples outside it are NaN and left white). Empty: only the frame.
    pub outline: Vec<[[f64; 2]; 3]>,
}

impl WrinkleMap {
    /// A map of `field` with the given threshold and the default axes `X (mm)`, `Y (mm)`.
    pub fn new(field: GridField, threshold: f64, threshold_label: impl Into<String>) -> Self {
        WrinkleMap {
            field,
            threshold,
            threshold_label: threshold_label.into(),
            x_axis: Quantity::coordinate("X"),
            y_axis: Quantity::coordinate("Y"),
            peak: None,
            caption: None,
            outline: Vec::new(),
        }
    }

    /// The same map with the domain's boundary drawn ([`WrinkleMap::outline`]).
    pub fn with_outline(mut self, outline: Vec<[[f64; 2]; 3]>) -> Self {
        self.outline = outline;
        self
    }

    /// The same map with the note under the title worded by the caller.
    pub fn with_caption(mut self, caption: impl Into<String>) -> Self {
        self.caption = Some(caption.into());
        self
    }

    /// The same map with its exact largest $`|v|`$ ([`WrinkleMap::peak`]).
    pub fn with_peak(mut self, peak: f64) -> Self {
        self.peak = Some(peak);
        self
    }

    /// The largest $`|v|`$: [`WrinkleMap::peak`] when known, the largest sample otherwise.
    pub fn max_abs(&self) -> f64 {
        self.peak.unwrap_or_else(|| self.field.max_abs())
    }

    /// Whether the largest $`|v|`$ is below the threshold.
    pub fn is_flat(&self) -> bool {
        self.max_abs() < self.threshold
    }

    /// Half-range of the colour scale: $`\max(\max|v|, \text{threshold})`$ (1 if both vanish).
    pub fn color_limit(&self) -> f64 {
        let limit = self.max_abs().max(self.threshold);
        if limit > 0.0 { limit } else { 1.0 }
    }

    /// The note written under the title.
    pub fn note(&self) -> String {
        if let Some(caption) = &self.caption {
            return caption.clone();
        }
        let quantity = &self.field.quantity;
        let max = self.max_abs();
        let value = |v: f64, digits: usize| {
            let number = format_significant(v, digits);
            if quantity.unit.is_empty() {
                number
            } else {
                format!("{number} {}", quantity.unit)
            }
        };
        let threshold = format!(
            "{}{}",
            value(self.threshold, 2),
            if self.threshold_label.is_empty() {
                String::new()
            } else {
                format!(" = {}", self.threshold_label)
            }
        );
        if self.is_flat() {
            format!(
                "not wrinkled (max |{}| = {} < threshold {threshold})",
                quantity.short_name(),
                value(max, 3)
            )
        } else {
            format!(
                "max |{}| = {}; colour scale ± max(|{}|, {threshold})",
                quantity.short_name(),
                value(max, 4),
                quantity.short_name()
            )
        }
    }
}

const TITLE_BAND: f64 = 84.0;
const MARGIN: f64 = 20.0;
const X_LABEL_AREA: f64 = 66.0;
const COLOR_BAR_WIDTH: f64 = 28.0;
const COLOR_BAR_GAP: f64 = 30.0;

struct MapFigure<'a> {
    title: &'a str,
    map: &'a WrinkleMap,
    note: String,
    limit: f64,
    /// Data area size in (1×) pixels, with the aspect ratio of the domain.
    plot_size: (f64, f64),
    y_label_area: f64,
    color_bar_area: f64,
}

impl<'a> MapFigure<'a> {
    fn new(title: &'a str, map: &'a WrinkleMap) -> Self {
        let [x0, x1, y0, y1] = map.field.bounds;
        let aspect = (x1 - x0) / (y1 - y0);
        // About 1000 pixels wide; long domains get wider pictures (at most 1300 pixels) and a
        // data area at least 180 pixels high, tall domains at most 600 pixels high.
        let mut width: f64 = 1000.0;
        let mut height = width / aspect;
        if height > 600.0 {
            height = 600.0;
            width = (height * aspect).max(320.0);
        }
        if height < 180.0 {
            height = 180.0;
            width = (height * aspect).min(1300.0);
        }
        let limit = map.color_limit();
        let y_ticks = choose_ticks((y0, y1), height, false);
        let bar_ticks = choose_ticks((-limit, limit), height, false);
        MapFigure {
            title,
            map,
            note: map.note(),
            limit,
            plot_size: (width.round(), height.round()),
            y_label_area: 6.0 + AXIS_TITLE_SIZE + 12.0 + y_ticks.label_width + 14.0,
            color_bar_area: COLOR_BAR_GAP
                + COLOR_BAR_WIDTH
                + 10.0
                + bar_ticks.label_width
                + 16.0
                + AXIS_TITLE_SIZE
                + 10.0,
        }
    }
}

impl Figure for MapFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let (width, height) = self.plot_size;
        let title_width = text_size(self.title, TITLE_SIZE)
            .0
            .max(text_size(&self.note, AXIS_TITLE_SIZE).0)
            + 2.0 * MARGIN;
        let total =
            (MARGIN + self.y_label_area + width + self.color_bar_area + MARGIN).max(title_width);
        (
            total.round() as u32,
            (TITLE_BAND + height + X_LABEL_AREA + MARGIN).round() as u32,
        )
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: Scale,
    ) -> DrawResult<FigureLayout, DB> {
        root.fill(&WHITE)?;
        let total_width = self.size().0 as f64;
        draw_centred_text(
            root,
            self.title,
            TITLE_SIZE,
            (0.5 * total_width, 12.0),
            BLACK,
            scale,
        )?;
        let note_color = if self.map.is_flat() {
            RGBColor(170, 20, 20)
        } else {
            RGBColor(60, 60, 60)
        };
        draw_centred_text(
            root,
            &self.note,
            AXIS_TITLE_SIZE,
            (0.5 * total_width, 48.0),
            note_color,
            scale,
        )?;
        let (width, _) = self.plot_size;
        let used = MARGIN + self.y_label_area + width + self.color_bar_area + MARGIN;
        let left_offset = ((total_width - used) / 2.0).max(0.0);
        let (_, body) = root.split_vertically(scale.px(TITLE_BAND));
        let (_, body) = body.split_horizontally(scale.px(left_offset));
        let main_width = MARGIN + self.y_label_area + width;
        let (main, bar_area) = body.split_horizontally(scale.px(main_width));
        let panel = self.draw_field(&main, scale)?;
        let color_bar = self.draw_color_bar(&bar_area, scale)?;
        if self.map.is_flat() {
            self.draw_flat_notice(root, &panel, scale)?;
        }
        Ok(FigureLayout {
            panels: vec![PanelLayout {
                plot_area: scale.logical_rect(panel.plot_area),
                ..panel
            }],
            color_bar: Some(scale.logical_rect(color_bar)),
            notes: vec![self.note.clone()],
            ..FigureLayout::default()
        })
    }
}

impl MapFigure<'_> {
    /// Axes and the field as one raster image of the data area (embedded as PNG in the SVG
    /// file), each pixel the bilinear interpolation of the samples at its centre.
    fn draw_field<DB: DrawingBackend>(
        &self,
        main: &DrawingArea<DB, Shift>,
        scale: Scale,
    ) -> DrawResult<PanelLayout, DB> {
        let field = &self.map.field;
        let [x0, x1, y0, y1] = field.bounds;
        let (width, height) = self.plot_size;
        let mut chart = ChartBuilder::on(main)
            .margin_left(scale.px(MARGIN))
            .margin_bottom(scale.px(MARGIN))
            .x_label_area_size(scale.px(X_LABEL_AREA))
            .y_label_area_size(scale.px(self.y_label_area))
            .build_cartesian_2d(x0..x1, y0..y1)?;
        let x_ticks = choose_ticks((x0, x1), width, true);
        let y_ticks = choose_ticks((y0, y1), height, false);
        let x_format = |v: &f64| x_ticks.label(*v);
        let y_format = |v: &f64| y_ticks.label(*v);
        let (x_title, y_title) = (self.map.x_axis.axis_title(), self.map.y_axis.axis_title());
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(x_title.as_str())
            .label_style(scale.font(TICK_SIZE).color(&RGBColor(40, 40, 40)))
            .axis_desc_style(scale.font(AXIS_TITLE_SIZE).color(&BLACK))
            .axis_style(scale.stroke(FRAME_COLOR, 1.0))
            .set_all_tick_mark_size(scale.px(6.0))
            .x_labels(x_ticks.count)
            .y_labels(y_ticks.count)
            .x_label_formatter(&x_format)
            .y_label_formatter(&y_format)
            .draw()?;
        let (pixel_x, pixel_y) = chart.plotting_area().get_pixel_range();
        let base = main.get_base_pixel();
        let middle = 0.5 * (pixel_y.start + pixel_y.end - 2 * base.1) as f64 / scale.0;
        draw_vertical_title(main, &y_title, (MARGIN + 6.0, middle), scale)?;
        let (columns, rows) = (
            (pixel_x.end - pixel_x.start).max(1) as u32,
            (pixel_y.end - pixel_y.start).max(1) as u32,
        );
        let raster = self.raster(columns, rows, scale);
        if let Some(image) = BitMapElement::with_owned_buffer((0, 0), (columns, rows), raster) {
            chart.plotting_area().strip_coord_spec().draw(&image)?;
        }
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1), (x0, y0)],
            scale.stroke(FRAME_COLOR, 1.2),
        )))?;
        // Each quadratic boundary segment as 8 chords of its parabola.
        chart.draw_series(self.map.outline.iter().map(|&[a, b, m]| {
            let along = |s: f64| {
                let (na, nb, nm) = (0.5 * s * (s - 1.0), 0.5 * s * (s + 1.0), 1.0 - s * s);
                let point = |k: usize| na * a[k] + nb * b[k] + nm * m[k];
                (point(0), point(1))
            };
            let points: Vec<(f64, f64)> = (0..=8).map(|k| along(-1.0 + 0.25 * k as f64)).collect();
            PathElement::new(points, scale.stroke(FRAME_COLOR, 1.0))
        }))?;
        Ok(PanelLayout {
            title: String::new(),
            plot_area: [pixel_x.start, pixel_y.start, pixel_x.end, pixel_y.end],
            x_range: (x0, x1),
            y_range: (y0, y1),
            axis_titles: (x_title, y_title),
        })
    }

    /// The data area's pixels, `columns × rows` RGB from the top row down. The field is smooth
    /// on the scale of a (1×) pixel, so it is evaluated once per block of `scale × scale`
    /// back-end pixels, at the block's centre, and the colour fills the block: the
    /// supersampled PNG costs what the SVG's 1× raster does (a ninth). After the PNG's
    /// averaging each pixel has the colour of the field near its centre, as in the SVG (where
    /// the data area does not start on the 1× grid, a pixel blends two neighbouring blocks).
    fn raster(&self, columns: u32, rows: u32, scale: Scale) -> Vec<u8> {
        let field = &self.map.field;
        let block = (scale.0.round() as u32).max(1);
        let (block_columns, block_rows) = (columns.div_ceil(block), rows.div_ceil(block));
        let centre = |index: u32, count: u32| {
            ((index * block) as f64 + 0.5 * block as f64).min(count as f64 - 0.5) / count as f64
        };
        let mut line = Vec::with_capacity(3 * columns as usize);
        let mut raster = Vec::with_capacity(3 * (columns * rows) as usize);
        for block_row in 0..block_rows {
            // Image rows run downwards, Y upwards.
            let t = 1.0 - centre(block_row, rows);
            line.clear();
            for block_column in 0..block_columns {
                let s = centre(block_column, columns);
                let value = field.interpolate_normalised(s, t);
                // Outside the domain (NaN): white, apart from the grey of a zero deflection.
                let color = if value.is_nan() {
                    WHITE
                } else {
                    diverging_color(value / self.limit)
                };
                let width = block.min(columns - block_column * block);
                for _ in 0..width {
                    line.extend([color.0, color.1, color.2]);
                }
            }
            for _ in 0..block.min(rows - block_row * block) {
                raster.extend_from_slice(&line);
            }
        }
        raster
    }

    /// The colour bar beside the data area, with ticks and the quantity's title (rotated).
    fn draw_color_bar<DB: DrawingBackend>(
        &self,
        area: &DrawingArea<DB, Shift>,
        scale: Scale,
    ) -> DrawResult<[i32; 4], DB> {
        let limit = self.limit;
        let (_, height) = self.plot_size;
        let ticks = choose_ticks((-limit, limit), height, false);
        let tick_label_area = ticks.label_width + 16.0;
        let right_margin = self.color_bar_area - COLOR_BAR_GAP - COLOR_BAR_WIDTH - tick_label_area;
        let mut bar = ChartBuilder::on(area)
            .margin_left(scale.px(COLOR_BAR_GAP))
            .margin_right(scale.px(right_margin))
            .margin_bottom(scale.px(MARGIN))
            .x_label_area_size(scale.px(X_LABEL_AREA))
            .right_y_label_area_size(scale.px(tick_label_area))
            .build_cartesian_2d(0.0..1.0, -limit..limit)?;
        let format = |v: &f64| ticks.label(*v);
        bar.configure_mesh()
            .disable_mesh()
            .disable_x_axis()
            .axis_style(scale.stroke(FRAME_COLOR, 1.0))
            .set_tick_mark_size(LabelAreaPosition::Right, scale.px(6.0))
            .label_style(scale.font(TICK_SIZE).color(&RGBColor(40, 40, 40)))
            .y_labels(ticks.count)
            .y_label_formatter(&format)
            .draw()?;
        let levels = 256;
        bar.draw_series((0..levels).map(|k| {
            let a = -limit + 2.0 * limit * k as f64 / levels as f64;
            let b = -limit + 2.0 * limit * (k + 1) as f64 / levels as f64;
            Rectangle::new(
                [(0.0, a), (1.0, b)],
                diverging_color(0.5 * (a + b) / limit).filled(),
            )
        }))?;
        bar.draw_series(std::iter::once(PathElement::new(
            vec![
                (0.0, -limit),
                (1.0, -limit),
                (1.0, limit),
                (0.0, limit),
                (0.0, -limit),
            ],
            scale.stroke(FRAME_COLOR, 1.0),
        )))?;
        let (pixel_x, pixel_y) = bar.plotting_area().get_pixel_range();
        // The quantity and its unit, rotated, to the right of the tick labels.
        let base = area.get_base_pixel();
        let x = (pixel_x.end - base.0) as f64 / scale.0 + tick_label_area + 4.0;
        let middle = 0.5 * (pixel_y.start + pixel_y.end - 2 * base.1) as f64 / scale.0;
        draw_vertical_title(
            area,
            &self.map.field.quantity.axis_title(),
            (x, middle),
            scale,
        )?;
        Ok([pixel_x.start, pixel_y.start, pixel_x.end, pixel_y.end])
    }

    /// "not wrinkled" in a box in the middle of the data area.
    fn draw_flat_notice<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        panel: &PanelLayout,
        scale: Scale,
    ) -> DrawResult<(), DB> {
        let [left, top, right, bottom] = panel.plot_area;
        let centre = (
            0.5 * (left + right) as f64 / scale.0,
            0.5 * (top + bottom) as f64 / scale.0,
        );
        let text = "not wrinkled";
        let size = 1.5 * TITLE_SIZE;
        let (width, height) = text_size(text, size);
        root.draw(&Rectangle::new(
            [
                (
                    scale.px(centre.0 - 0.5 * width - 16.0),
                    scale.px(centre.1 - 0.5 * height - 12.0),
                ),
                (
                    scale.px(centre.0 + 0.5 * width + 16.0),
                    scale.px(centre.1 + 0.5 * height + 14.0),
                ),
            ],
            WHITE.mix(0.9).filled(),
        ))?;
        draw_centred_text(
            root,
            text,
            size,
            (centre.0, centre.1 - 0.5 * height),
            RGBColor(170, 20, 20),
            scale,
        )
    }
}

/// Plots the wrinkle map to `STEM.png` and `STEM.svg`.
///
/// The data area keeps the aspect ratio of the domain; each pixel shows the bilinear
/// interpolation of the samples. The diverging colour scale (blue – grey – red) is symmetric
/// about 0 with half-range $`\max(\max|v|, \text{threshold})`$, so a field far below the
/// threshold is drawn pale instead of at full contrast; it is then marked "not wrinkled" and the
/// note under the title gives $`\max|v|`$. The colour bar carries the quantity and its unit.
///
/// Errors: an invalid grid (see [`GridField::validate`]), a threshold that is negative or not
/// finite, a failure writing the files.
pub fn plot_wrinkle_map(stem: &Path, title: &str, map: &WrinkleMap) -> io::Result<PlotOutput> {
    map.field.validate()?;
    if !(map.threshold.is_finite() && map.threshold >= 0.0) {
        return Err(invalid(
            "wrinkle map threshold",
            format!("must be finite and non-negative, got {}", map.threshold),
        ));
    }
    render(stem, &MapFigure::new(title, map))
}
