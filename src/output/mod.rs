//! Output writers of `wrinkle run`: the traced path as CSV (and JSON through [`serde`]), finite
//! element fields and the reconstructed wrinkled surface as VTK `.vtu` files for ParaView, PNG and
//! SVG plots, and a progress bar on standard error.
//!
//! Outputs never recompute physics: every writer takes numbers that the solvers already produced
//! (path points, nodal values, an envelope interpolant) and only formats them.
//!
//! All writers return [`std::io::Result`]. Input that cannot be written (mismatched lengths,
//! non-finite bounds, empty grids, …) is reported as an [`std::io::Error`] of kind
//! [`std::io::ErrorKind::InvalidInput`] whose inner error is an [`OutputError`], so callers can
//! either print it as one line or downcast it.
//!
//! * [`path_table`] — [`PathPoint`] and [`write_path_csv`].
//! * [`vtu`] — [`write_fields_vtu`] (Q8 mesh, VTK cell type 23) and [`write_surface_vtu`]
//!   (structured Quad4 grid with $`z = w(X, Y)`$).
//! * [`plots`] — [`plot_response`], [`plot_profiles`], [`plot_map`].
//! * [`progress`] — [`Progress`].

pub mod path_table;
pub mod plots;
pub mod progress;
pub mod vtu;

pub use path_table::{PATH_CSV_COLUMNS, PathPoint, write_path_csv, write_path_csv_to};
pub use plots::{
    Curve, CurveStyle, VerticalMarker, grid_cell_centres, plot_map, plot_profiles, plot_response,
};
pub use progress::Progress;
pub use vtu::{write_fields_vtu, write_surface_vtu};

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
