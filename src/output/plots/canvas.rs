//! Rendering on both back ends (supersampled PNG, SVG), the bundled font, the pixel scale, the
//! colours and the legend, shared by every plot.

use super::{FigureLayout, PixelRect, PlotOutput};
use crate::output::files::{write_atomically_via_path, write_bytes_atomically};
use crate::output::{OutputError, invalid};
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::{FontDesc, FontStyle, FontTransform, register_font};
use rayon::prelude::*;
use std::ffi::OsString;
use std::io;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The PNG is drawn at this many times its size in each direction, then each block of
/// `SUPERSAMPLING × SUPERSAMPLING` pixels is averaged into one (anti-aliasing).
pub const SUPERSAMPLING: u32 = 3;

/// The bundled font (DejaVu Sans, Bitstream Vera license, see `assets/fonts/LICENSE-DejaVu.txt`).
/// The bundled font (DejaVu Sans), shared by every plot of the crate.
pub(crate) static FONT_BYTES: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
/// Font family name under which the bundled font is registered.
pub(crate) const FONT: &str = "sans-serif";

/// Text sizes in (1×) pixels.
pub(crate) const TITLE_SIZE: f64 = 26.0;
pub(crate) const PANEL_TITLE_SIZE: f64 = 21.0;
pub(crate) const AXIS_TITLE_SIZE: f64 = 20.0;
pub(crate) const TICK_SIZE: f64 = 17.0;
pub(crate) const LEGEND_SIZE: f64 = 18.0;
pub(crate) const TAG_SIZE: f64 = 16.0;

pub(crate) type DrawResult<T, DB> =
    Result<T, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;

/// Pixels per (1×) pixel of the back end being drawn on: [`SUPERSAMPLING`] for the PNG, 1 for
/// the SVG. Every length of a figure goes through it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Scale(pub f64);

impl Scale {
    /// A length in back-end pixels.
    pub fn px(self, length: f64) -> i32 {
        (length * self.0).round() as i32
    }

    /// A length in back-end pixels, at least 1.
    pub fn upx(self, length: f64) -> u32 {
        (length * self.0).round().max(1.0) as u32
    }

    /// A back-end length back in 1× pixels.
    pub fn logical(self, pixels: i32) -> i32 {
        (pixels as f64 / self.0).round() as i32
    }

    /// A rectangle in back-end pixels back in 1× pixels.
    pub fn logical_rect(self, rect: PixelRect) -> PixelRect {
        rect.map(|v| self.logical(v))
    }

    /// The bundled font at `size` (1×) pixels.
    pub fn font(self, size: f64) -> FontDesc<'static> {
        (FONT, size * self.0).into_font()
    }

    /// A solid stroke `width` (1×) pixels wide.
    pub fn stroke(self, color: RGBColor, width: f64) -> ShapeStyle {
        color.stroke_width(self.upx(width))
    }
}

/// Size of `text` in (1×) pixels at `size`, measured with the bundled font.
pub(crate) fn text_size(text: &str, size: f64) -> (f64, f64) {
    // Measured at 10× and scaled back, so that rounding does not grow with the text length.
    let _ = register_bundled_font();
    match (FONT, 10.0 * size).into_font().box_size(text) {
        Ok((width, height)) => (width as f64 / 10.0, height as f64 / 10.0),
        Err(_) => (0.6 * size * text.chars().count() as f64, size),
    }
}

/// A picture drawn the same way on any plotters back end.
pub(crate) trait Figure {
    /// Size in (1×) pixels.
    fn size(&self) -> (u32, u32);
    /// Draws on `root`, lengths multiplied by `scale`; returns where the parts went, in
    /// back-end pixels.
    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        scale: Scale,
    ) -> DrawResult<FigureLayout, DB>;
}

/// `STEM.extension`, keeping any dot already in the stem's file name.
fn with_suffix(stem: &Path, extension: &str) -> PathBuf {
    let mut name = OsString::from(stem.as_os_str());
    name.push(".");
    name.push(extension);
    PathBuf::from(name)
}

fn plotting_error(error: impl std::fmt::Display) -> io::Error {
    OutputError::Library {
        library: "plotters",
        message: error.to_string(),
    }
    .into()
}

pub(crate) fn register_bundled_font() -> io::Result<()> {
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

/// Draws `figure` into `STEM.png` (supersampled) and `STEM.svg`, each written atomically.
pub(crate) fn render(stem: &Path, figure: &impl Figure) -> io::Result<PlotOutput> {
    register_bundled_font()?;
    let (width, height) = figure.size();
    let png = with_suffix(stem, "png");
    let factor = SUPERSAMPLING;
    let (big_width, big_height) = (width * factor, height * factor);
    let mut big = vec![255u8; 3 * (big_width * big_height) as usize];
    {
        let root =
            BitMapBackend::with_buffer(&mut big, (big_width, big_height)).into_drawing_area();
        figure
            .draw(&root, Scale(factor as f64))
            .map_err(plotting_error)?;
        root.present().map_err(plotting_error)?;
    }
    let small = downsample(&big, big_width, big_height, factor);
    drop(big);
    write_atomically_via_path(&png, |temporary| {
        let root = BitMapBackend::new(temporary, (width, height)).into_drawing_area();
        let image = BitMapElement::with_owned_buffer((0, 0), (width, height), small)
            .ok_or_else(|| plotting_error("bitmap buffer of the wrong size"))?;
        root.draw(&image).map_err(plotting_error)?;
        root.present().map_err(plotting_error)
    })?;

    let svg = with_suffix(stem, "svg");
    let mut text = String::new();
    let layout = {
        let root =
            plotters_svg::SVGBackend::with_string(&mut text, (width, height)).into_drawing_area();
        let layout = figure.draw(&root, Scale(1.0)).map_err(plotting_error)?;
        root.present().map_err(plotting_error)?;
        layout
    };
    // plotters-svg embeds bitmaps as `data:png;base64,…`, which is not a MIME type; browsers and
    // editors expect `data:image/png;base64,…`.
    let text = text.replace("href=\"data:png;base64,", "href=\"data:image/png;base64,");
    write_bytes_atomically(&svg, text.as_bytes())?;
    Ok(PlotOutput {
        files: vec![png, svg],
        layout: FigureLayout {
            size: (width, height),
            ..layout
        },
    })
}

/// Averages each `factor × factor` block of an RGB image (rounded to nearest); a partial block
/// at the right or bottom edge is dropped. Rows of the small image are independent, so they are
/// averaged in parallel; the result does not depend on the thread count.
fn downsample(pixels: &[u8], width: u32, height: u32, factor: u32) -> Vec<u8> {
    let (width, factor) = (width as usize, factor as usize);
    let small_width = width / factor;
    let small_height = height as usize / factor;
    let count = (factor * factor) as u32;
    let mut small = vec![0u8; 3 * small_width * small_height];
    small
        .par_chunks_mut(3 * small_width.max(1))
        .enumerate()
        .for_each_init(
            || vec![0u32; 3 * small_width],
            |sums, (row, out)| {
                sums.fill(0);
                for dy in 0..factor {
                    let start = 3 * (row * factor + dy) * width;
                    let line = &pixels[start..start + 3 * small_width * factor];
                    for (sum, block) in sums.chunks_exact_mut(3).zip(line.chunks_exact(3 * factor))
                    {
                        for pixel in block.chunks_exact(3) {
                            sum[0] += pixel[0] as u32;
                            sum[1] += pixel[1] as u32;
                            sum[2] += pixel[2] as u32;
                        }
                    }
                }
                for (value, total) in out.iter_mut().zip(sums.iter()) {
                    *value = ((total + count / 2) / count) as u8;
                }
            },
        );
    small
}

// ---------------------------------------------------------------------------------------------
// Colours.

/// Tableau 10, in order: distinct hues for models or series.
pub(crate) const CATEGORICAL: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
];

/// Colour of marker lines: linear buckling (dark grey) and loss of ellipticity (purple).
pub(crate) const BUCKLING_COLOR: RGBColor = RGBColor(80, 80, 80);
pub(crate) const ELLIPTICITY_COLOR: RGBColor = RGBColor(148, 40, 150);
pub(crate) const CLOSED_FORM_COLOR: RGBColor = RGBColor(20, 20, 20);
pub(crate) const FRAME_COLOR: RGBColor = RGBColor(60, 60, 60);

/// Viridis at a few stops; interpolated linearly.
const VIRIDIS: [(u8, u8, u8); 6] = [
    (68, 1, 84),
    (65, 68, 135),
    (42, 120, 142),
    (34, 168, 132),
    (122, 209, 81),
    (253, 231, 37),
];

/// Colour `index` of `count` along viridis, stopping before the yellow end (hard to read on
/// white).
pub(crate) fn sequential_color(index: usize, count: usize) -> RGBColor {
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

/// Diverging cool–warm colour map (Moreland): $`t \in [-1, 1]`$ from blue through light grey to
/// red; grey for a non-finite value.
pub(crate) fn diverging_color(t: f64) -> RGBColor {
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

// ---------------------------------------------------------------------------------------------
// Line styles and the legend.

/// Dash pattern of a line.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Dash {
    Solid,
    /// Long dashes (closed forms).
    Dashed,
    /// Short dashes (marker lines).
    Short,
}

impl Dash {
    /// `(dash, gap)` lengths in (1×) pixels.
    pub fn pattern(self) -> Option<(f64, f64)> {
        match self {
            Dash::Solid => None,
            // Both patterns fill the legend sample (50 pixels) with whole dashes.
            Dash::Dashed => Some((12.0, 7.0)),
            Dash::Short => Some((6.0, 5.0)),
        }
    }
}

/// What a legend entry shows before its text.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct LegendEntry {
    pub label: String,
    pub color: RGBColor,
    pub dash: Dash,
    pub width: f64,
    /// A filled dot in the middle of the sample line.
    pub marker: bool,
}

const LEGEND_SAMPLE: f64 = 50.0;
const LEGEND_GAP: f64 = 8.0;
const LEGEND_ENTRY_SPACING: f64 = 30.0;
const LEGEND_ROW_HEIGHT: f64 = 28.0;
const LEGEND_PADDING: f64 = 10.0;

/// Entries laid out in rows no wider than `width`: the rows (indices) and the size of the box.
pub(crate) fn legend_rows(entries: &[LegendEntry], width: f64) -> (Vec<Vec<usize>>, (f64, f64)) {
    let mut rows: Vec<Vec<usize>> = Vec::new();
    let mut row_width = 0.0;
    let mut widest: f64 = 0.0;
    for (index, entry) in entries.iter().enumerate() {
        let entry_width = entry_width(entry);
        let extra = if rows.last().is_some_and(|row| !row.is_empty()) {
            LEGEND_ENTRY_SPACING + entry_width
        } else {
            entry_width
        };
        match rows.last_mut() {
            Some(row) if row_width + extra <= width - 2.0 * LEGEND_PADDING => {
                row.push(index);
                row_width += extra;
            }
            _ => {
                rows.push(vec![index]);
                row_width = entry_width;
            }
        }
        widest = widest.max(row_width);
    }
    let size = (
        widest + 2.0 * LEGEND_PADDING,
        rows.len() as f64 * LEGEND_ROW_HEIGHT + 2.0 * LEGEND_PADDING - 4.0,
    );
    (rows, size)
}

fn entry_width(entry: &LegendEntry) -> f64 {
    LEGEND_SAMPLE + LEGEND_GAP + text_size(&entry.label, LEGEND_SIZE).0
}

/// Draws the legend in rows no wider than `max_width`, centred horizontally in `area` at `top`
/// (1× pixels from the top of `area`), with a light frame. Returns the frame in back-end pixels
/// (absolute).
pub(crate) fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[LegendEntry],
    (top, max_width): (f64, f64),
    scale: Scale,
) -> DrawResult<PixelRect, DB> {
    let (area_width, _) = area.dim_in_pixel();
    let area_width = area_width as f64 / scale.0;
    let (rows, (box_width, box_height)) = legend_rows(entries, max_width.min(area_width));
    let left = ((area_width - box_width) / 2.0).max(0.0);
    let frame = [
        scale.px(left),
        scale.px(top),
        scale.px(left + box_width),
        scale.px(top + box_height),
    ];
    area.draw(&Rectangle::new(
        [(frame[0], frame[1]), (frame[2], frame[3])],
        scale.stroke(RGBColor(190, 190, 190), 1.0),
    ))?;
    let font = scale.font(LEGEND_SIZE).color(&BLACK);
    for (row_index, row) in rows.iter().enumerate() {
        let row_width: f64 = row.iter().map(|&i| entry_width(&entries[i])).sum::<f64>()
            + LEGEND_ENTRY_SPACING * (row.len().saturating_sub(1)) as f64;
        let mut x = left + (box_width - row_width) / 2.0;
        let middle = top + LEGEND_PADDING + (row_index as f64 + 0.5) * LEGEND_ROW_HEIGHT - 2.0;
        for &index in row {
            let entry = &entries[index];
            draw_sample(area, entry, (x, middle), scale)?;
            let (_, text_height) = text_size(&entry.label, LEGEND_SIZE);
            area.draw(&Text::new(
                entry.label.clone(),
                (
                    scale.px(x + LEGEND_SAMPLE + LEGEND_GAP),
                    scale.px(middle - 0.5 * text_height - 1.0),
                ),
                &font,
            ))?;
            x += entry_width(entry) + LEGEND_ENTRY_SPACING;
        }
    }
    let base = area.get_base_pixel();
    Ok([
        frame[0] + base.0,
        frame[1] + base.1,
        frame[2] + base.0,
        frame[3] + base.1,
    ])
}

/// The sample of a legend entry, a line of [`LEGEND_SAMPLE`] pixels starting at `(x, y)`.
fn draw_sample<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entry: &LegendEntry,
    (x, y): (f64, f64),
    scale: Scale,
) -> DrawResult<(), DB> {
    let style = scale.stroke(entry.color, entry.width);
    let (start, end) = ((x, y), (x + LEGEND_SAMPLE, y));
    let start = (scale.px(start.0), scale.px(start.1));
    let end = (scale.px(end.0), scale.px(end.1));
    match entry.dash.pattern() {
        None => area.draw(&PathElement::new(vec![start, end], style))?,
        Some((dash, gap)) => area.draw(&DashedPathElement::new(
            vec![start, end],
            scale.px(dash),
            scale.px(gap),
            style,
        ))?,
    }
    if entry.marker {
        area.draw(&Circle::new(
            (scale.px(x + 0.5 * LEGEND_SAMPLE), scale.px(y)),
            scale.px(4.5),
            entry.color.filled(),
        ))?;
    }
    Ok(())
}

/// Draws `text` rotated a quarter turn (reading upwards), its left edge at `left` and centred
/// vertically at `middle` (1× pixels of `area`): the title of a vertical axis.
pub(crate) fn draw_vertical_title<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    (left, middle): (f64, f64),
    scale: Scale,
) -> DrawResult<(), DB> {
    let (width, _) = text_size(text, AXIS_TITLE_SIZE);
    // With `Rotate270` plotters maps glyph pixel (x, y) to (y, −x): the text runs upwards from
    // its anchor and its height extends to the right.
    area.draw(&Text::new(
        text.to_string(),
        (scale.px(left), scale.px(middle + 0.5 * width)),
        scale
            .font(AXIS_TITLE_SIZE)
            .color(&BLACK)
            .transform(FontTransform::Rotate270),
    ))?;
    Ok(())
}

/// Draws `text` centred horizontally at `x`, its top at `top` (1× pixels of `area`).
pub(crate) fn draw_centred_text<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    size: f64,
    (x, top): (f64, f64),
    color: RGBColor,
    scale: Scale,
) -> DrawResult<(), DB> {
    let (width, _) = text_size(text, size);
    // Centred on `x`, but never starting left of the area (a long title is shifted right
    // rather than cut at the left edge).
    let left = (x - 0.5 * width).max(4.0);
    area.draw(&Text::new(
        text.to_string(),
        (scale.px(left), scale.px(top)),
        scale.font(size).color(&color),
    ))?;
    Ok(())
}

// ---------------------------------------------------------------------------------------------
// Numbers.

/// Tick text with a fixed number of decimals (`decimals = None`: scientific notation with three
/// significant digits); `-0` is written `0`.
pub(crate) fn format_tick(value: f64, decimals: Option<usize>) -> String {
    let text = match decimals {
        Some(decimals) => format!("{value:.decimals$}"),
        None => {
            if value == 0.0 {
                "0".to_string()
            } else {
                format!("{value:.2e}")
            }
        }
    };
    if text
        .trim_start_matches('-')
        .chars()
        .all(|c| c == '0' || c == '.')
    {
        text.trim_start_matches('-').to_string()
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The block average written out pixel by pixel, with the edge blocks dropped.
    fn block_average(pixels: &[u8], width: u32, height: u32, factor: u32) -> Vec<u8> {
        let mut small = Vec::new();
        for row in 0..height / factor {
            for column in 0..width / factor {
                for channel in 0..3 {
                    let mut total = 0u32;
                    for dy in 0..factor {
                        for dx in 0..factor {
                            let (y, x) = (row * factor + dy, column * factor + dx);
                            total += pixels[(3 * (y * width + x) + channel) as usize] as u32;
                        }
                    }
                    let count = factor * factor;
                    small.push(((total + count / 2) / count) as u8);
                }
            }
        }
        small
    }

    #[test]
    fn downsample_is_the_rounded_block_average_with_partial_edge_blocks_dropped() {
        // 17 × 11 pixels: neither side a multiple of 3 or 2. A deterministic scramble of bytes.
        let (width, height) = (17u32, 11u32);
        let pixels: Vec<u8> = (0..3 * width * height)
            .map(|i| (i.wrapping_mul(2_654_435_761) >> 13) as u8)
            .collect();
        for factor in [1, 2, 3] {
            let small = downsample(&pixels, width, height, factor);
            assert_eq!(
                small,
                block_average(&pixels, width, height, factor),
                "factor {factor}"
            );
            assert_eq!(small.len() as u32, 3 * (width / factor) * (height / factor));
        }
        // A block of one colour keeps it exactly.
        let uniform = vec![200u8; 3 * 9 * 6];
        assert!(downsample(&uniform, 9, 6, 3).iter().all(|&v| v == 200));
    }
}
