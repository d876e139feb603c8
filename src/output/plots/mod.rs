//! PNG and SVG plots drawn with [`plotters`]: the response curve ([`plot_response`]), a
//! comparison of several models on one scene ([`plot_comparison`]), profiles along a line
//! ([`plot_profiles`]) and the wrinkle map ([`plot_wrinkle_map`]).
//!
//! Every plot is drawn by the same code on two back ends: `STEM.png` and `STEM.svg`. The PNG is
//! drawn at [`SUPERSAMPLING`] times its size and box-filtered down, which anti-aliases lines and
//! edges (plotters' bitmap back end does not). Text uses the DejaVu Sans font bundled in
//! `assets/fonts/`, so the pictures look the same on machines without system fonts. Legends are
//! drawn outside the data area (below or beside the panels), every axis title carries the unit of
//! its [`super::Quantity`], and the number of tick labels is chosen from the pixel length of the
//! axis and the width of the labels, so they never overlap.
//!
//! Each plot function returns a [`PlotOutput`]: the files written and the [`FigureLayout`]
//! (pixel rectangles of the panels and the legend, axis ranges), which tests use to check
//! ranges and placement.

pub(crate) mod canvas;
mod map;
mod panel;
mod profiles;
mod response;

pub use canvas::SUPERSAMPLING;
pub use map::{WrinkleMap, plot_wrinkle_map};
pub use profiles::{Profile, ProfilePlot, ReferenceLevel, plot_profiles, plot_profiles_with_level};
pub use response::{
    ClosedFormCurve, LoadMarker, MarkerKind, Response, ResponsePoint, plot_comparison,
    plot_response,
};

use std::path::PathBuf;

/// A rectangle in pixels of the (1×) picture: `left, top, right, bottom`, y downwards.
pub type PixelRect = [i32; 4];

/// Where one panel was drawn and what it shows.
#[derive(Clone, Debug, PartialEq)]
pub struct PanelLayout {
    /// Panel title (may be empty).
    pub title: String,
    /// The data area (inside the axes).
    pub plot_area: PixelRect,
    /// Abscissa range `(low, high)` of the data area.
    pub x_range: (f64, f64),
    /// Ordinate range `(low, high)` of the data area.
    pub y_range: (f64, f64),
    /// Axis titles `(x, y)`.
    pub axis_titles: (String, String),
}

/// Where the parts of a figure were drawn.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FigureLayout {
    /// Size of the picture in pixels.
    pub size: (u32, u32),
    /// The panels, left to right.
    pub panels: Vec<PanelLayout>,
    /// The legend box, if any.
    pub legend: Option<PixelRect>,
    /// The colour bar of a map, if any.
    pub color_bar: Option<PixelRect>,
    /// Notes written on the figure (e.g. `not wrinkled (max |w| = … mm)`).
    pub notes: Vec<String>,
}

/// What a plot function wrote.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotOutput {
    /// `STEM.png` and `STEM.svg`.
    pub files: Vec<PathBuf>,
    /// Placement of the panels and legend.
    pub layout: FigureLayout,
}

/// Whether two rectangles overlap (share more than an edge).
pub fn rectangles_overlap(a: PixelRect, b: PixelRect) -> bool {
    a[0] < b[2] && b[0] < a[2] && a[1] < b[3] && b[1] < a[3]
}
