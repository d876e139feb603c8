//! Output writers: the traced path as CSV (and JSON through [`serde`]), finite element fields
//! and sampled surfaces as VTK `.vtu` files for ParaView, PNG and SVG plots, the self-contained
//! HTML report, progress on standard error, and the run directory that holds them.
//!
//! Outputs never recompute physics: every writer takes plain data that the solvers and the
//! pipeline already produced (path points, nodal values, sampled fields, critical loads) and only
//! formats it. Labels — quantity names, symbols and units — are data too ([`Quantity`]), so the
//! same writers serve every model and load (the biaxial load in N/mm, the strip's end
//! displacement in mm).
//!
//! Every file is written atomically ([`files::write_atomically`]); a run's files are written into
//! the staging directory of a [`RunDirectory`] (locked: one run at a time), listed in its
//! `summary.json` and swapped in whole at the end.
//!
//! All writers return [`std::io::Result`]. Input that cannot be written (mismatched lengths,
//! non-finite bounds, empty grids, …) is reported as an [`std::io::Error`] of kind
//! [`std::io::ErrorKind::InvalidInput`] whose inner error is an [`OutputError`], so callers can
//! either print it as one line or downcast it.
//!
//! * [`quantity`] — [`Quantity`]: description, symbol, unit.
//! * [`files`] — [`write_atomically`] and the names of a run's files.
//! * [`run_directory`] — [`RunDirectory`]: the lock, the staging directory, the swap;
//!   [`DirectoryLock`]: the lock alone, for the directories of `compare` and `bench`.
//! * [`path_table`] — [`PathPoint`] and [`write_path_csv`].
//! * [`grid`] — [`GridField`]: a field sampled on a regular grid.
//! * [`vtu`] — [`write_fields_vtu`] (Q8 mesh, VTK cell type 23) and [`write_surface_vtu`], both
//!   with [`FieldData`] (the load and its unit) and extra [`PointArray`]s.
//! * [`pvd`] — [`write_pvd`]: a ParaView collection of `.vtu` files over the load.
//! * [`plots`] — [`plot_response`], [`plot_comparison`], [`plot_profiles`],
//!   [`plot_wrinkle_map`].
//! * [`report`] — [`write_report`]: `report.html` with the summary, warnings, plots and scene.
//! * [`progress`] — [`Progress`] toward a target, [`SearchProgress`] for searches.
//!
//! # Example: what a pipeline does with the results of a run
//!
//! ```
//! use wrinkle::output::{
//!     FieldData, LoadMarker, Quantity, Report, ReportFigure, Response, ResponsePoint,
//!     RunDirectory, SummaryTable, plot_response, write_report,
//! };
//! # fn main() -> std::io::Result<()> {
//! # let out = std::env::temp_dir().join(format!("wrinkle-doc-{}", std::process::id()));
//! // Locks the directory (a second run into it fails at once); the outputs go beside it.
//! let mut directory = RunDirectory::open(&out)?;
//! // Physical amplitudes (twice the envelope for envelope models), loads in N/mm.
//! let load = Quantity::biaxial_load();
//! let critical = 0.0895;
//! let points = (0..=40)
//!     .map(|k| {
//!         let lambda = 0.003 * k as f64;
//!         ResponsePoint {
//!             load: lambda,
//!             max_amplitude_over_h: 8.0 * (lambda / critical - 1.0).max(0.0).sqrt(),
//!             centre_amplitude_over_h: None,
//!             step_end: k % 5 == 0,
//!         }
//!     })
//!     .collect();
//! let response = Response::new("reference-envelope", load.clone(), critical, points)
//!     .with_marker(LoadMarker::linear_buckling(critical, &load));
//! let plot = plot_response(&directory.path("response"), "Example 1", &response)?;
//! directory.record(&plot.files)?;
//! // The load and its unit go into every VTU file as field data:
//! let _field_data = FieldData::load(0.12, &load.unit);
//!
//! let summary = SummaryTable {
//!     model: "reference-envelope".into(),
//!     method: "ANM".into(),
//!     dofs: 4704,
//!     wavenumber: Some(0.2354),
//!     wavelength: Some(26.69),
//!     load: load.clone(),
//!     critical_load: Some(critical),
//!     closed_form_critical_load: None,
//!     closed_form_source: String::new(),
//!     final_load: Some(0.12),
//!     final_amplitude_over_h: Some(4.6),
//!     target_amplitude_over_h: Some(4.0),
//!     thickness: Some(0.05),
//!     steps: 8,
//!     factorizations: 9,
//!     seconds: 1.5,
//!     peak_memory_bytes: Some(80_000_000),
//!     stop: "stop criterion reached".into(),
//!     reached_target: true,
//! };
//! eprint!("{}", summary.to_text()); // the terminal table
//! let mut report = Report::from_summary(&summary);
//! report.figures.push(ReportFigure::png(&plot.files[0], "Response"));
//! let report_path = directory.path("report.html");
//! directory.record([&report_path])?;
//! report.files = directory.files().to_vec();
//! write_report(&report_path, &report)?;
//! // Last: summary.json with `files`, the list of everything written; then the swap, which
//! // replaces the previous run's files (only those it listed) and keeps everything else.
//! directory.write_summary(&serde_json::json!({ "model": "reference-envelope" }))?;
//! let out = directory.commit()?;
//! # std::fs::remove_dir_all(&out)?;
//! # let lock = format!(".{}.wrinkle-lock", out.file_name().unwrap().to_string_lossy());
//! # std::fs::remove_file(out.with_file_name(lock))?;
//! # Ok(())
//! # }
//! ```

pub mod files;
pub mod grid;
pub mod path_table;
pub mod plots;
pub mod progress;
pub mod pvd;
pub mod quantity;
pub mod report;
pub mod run_directory;
pub mod vtu;

pub use files::{write_atomically, write_atomically_via_path, write_bytes_atomically, write_json};
pub use grid::GridField;
pub use path_table::{PATH_CSV_COLUMNS, PathPoint, write_path_csv, write_path_csv_to};
pub use plots::{
    ClosedFormCurve, FigureLayout, LoadMarker, MarkerKind, PanelLayout, PlotOutput, Profile,
    ProfilePlot, ReferenceLevel, Response, ResponsePoint, WrinkleMap, plot_comparison,
    plot_profiles, plot_profiles_with_level, plot_response, plot_wrinkle_map,
};
pub use progress::{Progress, ProgressSink, ProgressTarget, SearchProgress, message_line};
pub use pvd::{SeriesEntry, write_pvd};
pub use quantity::Quantity;
pub use report::{
    Report, ReportFigure, Severity, SummaryRow, SummaryTable, Warning, format_rows, write_report,
};
pub use run_directory::{DirectoryLock, RunDirectory};
pub use vtu::{
    FieldData, FieldValue, PointArray, write_fields_vtu, write_fields_vtu_with_cells,
    write_surface_vtu,
};

use std::io;

/// Why an output could not be written (wrapped in an [`io::Error`] of kind
/// [`io::ErrorKind::InvalidInput`], or [`io::ErrorKind::Other`] for a failing library).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OutputError {
    /// Two sizes that must agree do not.
    #[error("{what}: expected {expected} values, got {actual}")]
    LengthMismatch {
        /// Which array.
        what: String,
        /// The required length.
        expected: usize,
        /// The length given.
        actual: usize,
    },
    /// A value that must be finite (or positive, or ordered) is not.
    #[error("{what}: {message}")]
    InvalidValue {
        /// Which quantity.
        what: String,
        /// What is wrong with it.
        message: String,
    },
    /// An element refers to a node that does not exist.
    #[error("element {element} refers to node {node}, but the mesh has {node_count} nodes")]
    NodeOutOfRange {
        /// Element index.
        element: usize,
        /// The offending node index.
        node: usize,
        /// Number of nodes of the mesh.
        node_count: usize,
    },
    /// Two data arrays of one file share a name (ParaView would show only one).
    #[error("array name `{0}` is used twice (or is empty)")]
    BadArrayName(String),
    /// A library used to encode the output failed.
    #[error("{library}: {message}")]
    Library {
        /// The library (`vtkio`, `plotters`).
        library: &'static str,
        /// Its error message.
        message: String,
    },
}

impl From<OutputError> for io::Error {
    fn from(error: OutputError) -> io::Error {
        let kind = match error {
            OutputError::Library { .. } => io::ErrorKind::Other,
            _ => io::ErrorKind::InvalidInput,
        };
        io::Error::new(kind, error)
    }
}

/// Shorthand for an [`OutputError::InvalidValue`] as an [`io::Error`].
pub(crate) fn invalid(what: impl Into<String>, message: impl Into<String>) -> io::Error {
    OutputError::InvalidValue {
        what: what.into(),
        message: message.into(),
    }
    .into()
}

/// Shorthand for an [`OutputError::LengthMismatch`] as an [`io::Error`], or `Ok` when the lengths
/// agree.
pub(crate) fn check_length(
    what: impl Into<String>,
    expected: usize,
    actual: usize,
) -> io::Result<()> {
    if expected == actual {
        Ok(())
    } else {
        Err(OutputError::LengthMismatch {
            what: what.into(),
            expected,
            actual,
        }
        .into())
    }
}
