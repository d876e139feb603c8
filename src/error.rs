//! The front end's error type and the exit codes it maps to (table in `docs/outputs.md`).
//!
//! Every module of the crate imports [`Error`] from here; `lib.rs` re-exports it for the public
//! API, so that no module reaches up into the crate root for it.

use std::fmt;
use std::path::Path;

/// Every error the front end reports. Each renders as one line (see [`fmt::Display`]) and maps
/// to a process exit code with [`Error::exit_code`].
#[derive(Debug)]
pub enum Error {
    /// A problem with a scene: syntax, unknown key, wrong type, out-of-range value, missing file.
    Scene {
        /// Where the offending input came from: `scene PATH` for a file, `--set KEY=VALUE` for
        /// an override.
        source: String,
        /// Dotted key, e.g. `material.poisson`; empty when the problem is not tied to a key
        /// (a syntax error, a missing file).
        key: String,
        /// What is wrong, e.g. `must satisfy -1 < ν < 0.5, got 0.6`.
        message: String,
    },
    /// Bad command-line usage that the argument parser could not catch.
    Usage(String),
    /// Reading or writing a file (other than the scene itself) failed.
    Io {
        /// The file or directory involved.
        path: String,
        /// The underlying operating-system error.
        error: std::io::Error,
    },
    /// A solver failed (singular tangent, no convergence, …).
    Solver(String),
    /// A requested feature is not implemented yet.
    NotImplemented(String),
    /// The run stopped before what was asked (`max_steps`, `max_load`, never wrinkled).
    Incomplete(String),
    /// The run finished but a validity check of the model failed (scale separation,
    /// ellipticity at the threshold, mode resolution).
    Invalid(String),
    /// The user interrupted the run (Ctrl-C); every point completed before was written.
    Interrupted(String),
}

/// Exit code of an interrupted run (128 + SIGINT, the shell's convention).
pub const EXIT_INTERRUPTED: i32 = 130;

impl Error {
    /// Process exit code (table in `docs/outputs.md`): 2 for scene and usage errors (the input
    /// is wrong), 1 for a failure while computing or writing results, 3 for a run that stopped
    /// before its target, 4 for a result outside the model's validity, 130 when interrupted.
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Scene { .. } | Error::Usage(_) => 2,
            Error::Io { .. } | Error::Solver(_) | Error::NotImplemented(_) => 1,
            Error::Incomplete(_) => 3,
            Error::Invalid(_) => 4,
            Error::Interrupted(_) => EXIT_INTERRUPTED,
        }
    }

    /// Builds a [`Error::Scene`].
    pub fn scene(
        source: impl Into<String>,
        key: impl Into<String>,
        message: impl Into<String>,
    ) -> Self {
        Error::Scene {
            source: source.into(),
            key: key.into(),
            message: message.into(),
        }
    }
}

/// The [`Error::Io`] of an operation on `path`, for `map_err`.
pub fn io_error(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |error| Error::Io {
        path: path.display().to_string(),
        error,
    }
}

/// The error of locking or opening an output directory
/// ([`crate::output::RunDirectory::open`], [`crate::output::DirectoryLock::inside`]): its
/// refusals — another run holds it (kind `WouldBlock`), it cannot be used (kind
/// `InvalidInput`: a file, a symbolic-link loop, the current directory, foreign files under the
/// outputs' names) — are usage errors (exit 2) naming the directory; anything else is an
/// [`Error::Io`].
pub fn output_directory_error(directory: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |error| match error.kind() {
        std::io::ErrorKind::WouldBlock | std::io::ErrorKind::InvalidInput => {
            Error::Usage(error.to_string())
        }
        _ => Error::Io {
            path: directory.display().to_string(),
            error,
        },
    }
}

impl fmt::Display for Error {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Scene {
                source,
                key,
                message,
            } if key.is_empty() => {
                write!(formatter, "{source}: {message}")
            }
            Error::Scene {
                source,
                key,
                message,
            } => {
                write!(formatter, "{source}: key `{key}`: {message}")
            }
            Error::Usage(message) => write!(formatter, "usage: {message}"),
            Error::Io { path, error } => write!(formatter, "{path}: {error}"),
            Error::Solver(message) => write!(formatter, "solver: {message}"),
            Error::NotImplemented(message) => write!(formatter, "not implemented: {message}"),
            Error::Incomplete(message) => write!(formatter, "incomplete: {message}"),
            Error::Invalid(message) => write!(formatter, "outside the model's validity: {message}"),
            Error::Interrupted(message) => write!(formatter, "interrupted: {message}"),
        }
    }
}

// `Error::Scene` has a field named `source` (the origin of the input, a string), which
// `thiserror` would take for the error's cause; the trait is therefore implemented by hand.
impl std::error::Error for Error {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Error::Io { error, .. } => Some(error),
            _ => None,
        }
    }
}
