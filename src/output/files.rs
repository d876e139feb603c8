//! Atomic writes ([`write_atomically`]) and the names of a run's files; the run directory that
//! holds them is [`super::RunDirectory`] (`run_directory.rs`).
//!
//! A reader never sees a half-written output: every writer of [`crate::output`] writes a
//! temporary file in the destination's directory (`.NAME.PID-N.wrinkle-tmp[.EXT]`), flushes it to
//! disk and renames it over the destination, which is atomic on one file system.

use super::{OutputError, invalid};
use std::ffi::OsString;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Marker in the names of temporary files (`.NAME.PID-N.wrinkle-tmp[.EXT]`);
/// [`super::RunDirectory`] removes leftovers of interrupted writes by this marker.
pub const TEMPORARY_MARKER: &str = ".wrinkle-tmp";

/// Name of the summary file whose `files` key lists the outputs of a run.
pub const SUMMARY_FILE: &str = "summary.json";

/// Output names of the `wrinkle run` versions that did not list their files in `summary.json`
/// (`*` matches any characters). Used only when such a summary is found, see
/// [`super::RunDirectory`].
pub const LEGACY_OUTPUT_PATTERNS: [&str; 14] = [
    "summary.json",
    "path.csv",
    "scene.toml",
    "report.html",
    "fields_final.vtu",
    "surface_final.vtu",
    "fields_load_*.vtu",
    "response.png",
    "response.svg",
    "profiles_*.png",
    "profiles_*.svg",
    "wrinkles.png",
    "wrinkles.svg",
    "comparison.*",
];

/// Prefixes an I/O error with the file it concerns.
pub(super) fn with_path(path: &Path, error: io::Error) -> io::Error {
    io::Error::new(error.kind(), format!("{}: {error}", path.display()))
}

/// A temporary path beside `path`: same directory, hidden, unique in this process, keeping the
/// extension (some encoders choose the format from it).
fn temporary_path(path: &Path) -> io::Result<PathBuf> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let name = path
        .file_name()
        .ok_or_else(|| invalid("output path", format!("`{}` names no file", path.display())))?;
    let mut temporary = OsString::from(".");
    temporary.push(name);
    temporary.push(format!(
        ".{}-{}{TEMPORARY_MARKER}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    ));
    if let Some(extension) = path.extension() {
        temporary.push(".");
        temporary.push(extension);
    }
    Ok(path.with_file_name(temporary))
}

/// Writes `path` atomically through a writer: `write` fills a temporary file in the same
/// directory, which is flushed to disk and renamed over `path`. On any error the temporary file
/// is removed and `path` is left as it was. Errors name `path`.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    write_atomically_via_path(path, |temporary| {
        let file = File::create_new(temporary)?;
        let mut writer = BufWriter::new(file);
        write(&mut writer)?;
        let file = writer
            .into_inner()
            .map_err(io::IntoInnerError::into_error)?;
        file.sync_all()
    })
}

/// Writes `bytes` to `path` atomically (see [`write_atomically`]).
pub fn write_bytes_atomically(path: &Path, bytes: &[u8]) -> io::Result<()> {
    write_atomically(path, |writer| writer.write_all(bytes))
}

/// Atomic write for encoders that want a file name rather than a writer (plotters' bitmap
/// back end): `write` creates the temporary file it is given (same directory and extension as
/// `path`), which is then flushed to disk and renamed over `path`.
pub fn write_atomically_via_path(
    path: &Path,
    write: impl FnOnce(&Path) -> io::Result<()>,
) -> io::Result<()> {
    let temporary = temporary_path(path)?;
    let result = write(&temporary)
        .and_then(|()| File::open(&temporary)?.sync_all())
        .and_then(|()| fs::rename(&temporary, path));
    if result.is_err() {
        // The temporary file may not exist (the writer failed before creating it).
        let _ = fs::remove_file(&temporary);
    }
    result.map_err(|error| {
        // Invalid input keeps its typed inner error (callers may downcast it).
        if error
            .get_ref()
            .is_some_and(|inner| inner.is::<OutputError>())
        {
            error
        } else {
            with_path(path, error)
        }
    })
}

/// Writes a value as JSON, pretty-printed, atomically.
pub fn write_json(path: &Path, value: &impl serde::Serialize) -> io::Result<()> {
    write_atomically(path, |writer| {
        serde_json::to_writer_pretty(&mut *writer, value)?;
        writer.write_all(b"\n")
    })
}

/// A non-empty relative path of normal components only (no `..`, `.`, root or prefix).
pub(super) fn is_plain_relative(path: &Path) -> bool {
    path.components().next().is_some()
        && path.components().all(|c| matches!(c, Component::Normal(_)))
}

/// Glob match with `*` (any run of characters) as the only wildcard.
pub(super) fn matches(pattern: &str, name: &str) -> bool {
    match pattern.split_once('*') {
        None => pattern == name,
        Some((prefix, rest)) => {
            let Some(tail) = name.strip_prefix(prefix) else {
                return false;
            };
            (0..=tail.len())
                .filter(|&k| tail.is_char_boundary(k))
                .any(|k| matches(rest, &tail[k..]))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::matches;

    #[test]
    fn glob_patterns() {
        assert!(matches("fields_load_*.vtu", "fields_load_0.100000.vtu"));
        assert!(!matches("fields_load_*.vtu", "fields_load_0.1.vtk"));
        assert!(matches("comparison.*", "comparison.png"));
        assert!(matches("path.csv", "path.csv"));
        assert!(!matches("path.csv", "my_path.csv"));
    }
}
