//! Files of a run: atomic writes ([`write_atomically`]) and the run directory ([`RunDirectory`]),
//! which removes the previous run's outputs before anything is written and lists every file the
//! current run wrote (the `files` key of `summary.json`).
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

/// Marker in the names of temporary files (`.NAME.PID-N.wrinkle-tmp[.EXT]`); [`RunDirectory`]
/// removes leftovers of interrupted writes by this marker.
pub const TEMPORARY_MARKER: &str = ".wrinkle-tmp";

/// Name of the summary file whose `files` key lists the outputs of a run.
pub const SUMMARY_FILE: &str = "summary.json";

/// Output names of the `wrinkle run` versions that did not list their files in `summary.json`
/// (`*` matches any characters). Used only when such a summary is found, see [`RunDirectory`].
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
fn with_path(path: &Path, error: io::Error) -> io::Error {
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

/// The output directory of one run.
///
/// [`RunDirectory::prepare`] removes the files of the previous run before anything is written,
/// so a directory never mixes two runs, and never removes a file that `wrinkle` did not write:
///
/// * the files listed under the `files` key of the previous `summary.json`;
/// * if that summary has no `files` key but is a summary of an older `wrinkle run` (an object with
///   `model` and `scene` keys), the files matching [`LEGACY_OUTPUT_PATTERNS`];
/// * leftover temporary files of interrupted atomic writes ([`TEMPORARY_MARKER`]).
///
/// Listed names are only honoured when they are relative paths inside the directory (no `..`, no
/// absolute path, no symbolic link leading out); anything else in the directory is kept.
///
/// Each [`RunDirectory::record`] rewrites `summary.json` as an interim manifest
/// (`{"complete": false, "files": [...]}`), so that even a run killed half-way leaves a
/// directory the next run can clean; [`RunDirectory::write_summary`] writes the final summary
/// with the complete list.
#[derive(Debug)]
pub struct RunDirectory {
    root: PathBuf,
    written: Vec<String>,
    removed: Vec<String>,
}

impl RunDirectory {
    /// Creates `root` if needed and removes the previous run's outputs (see the type's
    /// documentation). The names removed are available from [`RunDirectory::removed`].
    pub fn prepare(root: &Path) -> io::Result<Self> {
        fs::create_dir_all(root).map_err(|error| with_path(root, error))?;
        let mut directory = RunDirectory {
            root: root.to_path_buf(),
            written: Vec::new(),
            removed: Vec::new(),
        };
        for name in directory.previous_outputs()? {
            let path = root.join(&name);
            match fs::remove_file(&path) {
                Ok(()) => directory.removed.push(name),
                Err(error) if error.kind() == io::ErrorKind::NotFound => {}
                Err(error) => return Err(with_path(&path, error)),
            }
        }
        directory.write_manifest()?;
        Ok(directory)
    }

    /// The directory.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// `root/name`.
    pub fn path(&self, name: impl AsRef<Path>) -> PathBuf {
        self.root.join(name)
    }

    /// The previous run's files removed by [`RunDirectory::prepare`], relative to the root.
    pub fn removed(&self) -> &[String] {
        &self.removed
    }

    /// Every file recorded so far, relative to the root, in the order written.
    pub fn files(&self) -> &[String] {
        &self.written
    }

    /// Records files written into the directory (each once) and rewrites the interim manifest.
    ///
    /// Errors: a path outside the directory (kind [`io::ErrorKind::InvalidInput`]), or failing to
    /// write the manifest.
    pub fn record<P: AsRef<Path>>(&mut self, paths: impl IntoIterator<Item = P>) -> io::Result<()> {
        for path in paths {
            let name = self.relative_name(path.as_ref())?;
            if !self.written.contains(&name) {
                self.written.push(name);
            }
        }
        self.write_manifest()
    }

    /// Writes `summary` (serialised as a JSON object, without a `files` key) as `summary.json`
    /// with the key `files` set to every recorded file plus `summary.json` itself, and returns
    /// its path.
    ///
    /// Errors: `summary` does not serialise as an object, or the file cannot be written.
    pub fn write_summary(&mut self, summary: &impl serde::Serialize) -> io::Result<PathBuf> {
        /// The summary's keys and `files`.
        #[derive(serde::Serialize)]
        struct WithFiles<'a, S> {
            #[serde(flatten)]
            summary: &'a S,
            files: &'a [String],
        }
        let path = self.path(SUMMARY_FILE);
        if !self.written.iter().any(|name| name == SUMMARY_FILE) {
            self.written.push(SUMMARY_FILE.to_string());
        }
        let with_files = WithFiles {
            summary,
            files: &self.written,
        };
        write_json(&path, &with_files)?;
        Ok(path)
    }

    fn write_manifest(&self) -> io::Result<()> {
        let mut files = self.written.clone();
        if !files.iter().any(|name| name == SUMMARY_FILE) {
            files.push(SUMMARY_FILE.to_string());
        }
        let manifest = serde_json::json!({ "complete": false, "files": files });
        write_json(&self.path(SUMMARY_FILE), &manifest)
    }

    /// `path` relative to the root, `/`-separated; it must lie inside the root.
    fn relative_name(&self, path: &Path) -> io::Result<String> {
        let relative = path.strip_prefix(&self.root).unwrap_or(path);
        if !is_plain_relative(relative) {
            return Err(invalid(
                "output file",
                format!(
                    "`{}` is not a file inside the run directory `{}`",
                    path.display(),
                    self.root.display()
                ),
            ));
        }
        Ok(relative
            .components()
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect::<Vec<_>>()
            .join("/"))
    }

    /// Names (relative to the root) of the previous run's files that may be removed.
    fn previous_outputs(&self) -> io::Result<Vec<String>> {
        let mut names = Vec::new();
        let entries = fs::read_dir(&self.root).map_err(|error| with_path(&self.root, error))?;
        let mut present = Vec::new();
        for entry in entries {
            let entry = entry.map_err(|error| with_path(&self.root, error))?;
            if entry.file_type().map(|t| t.is_file()).unwrap_or(false) {
                present.push(entry.file_name().to_string_lossy().into_owned());
            }
        }
        names.extend(
            present
                .iter()
                .filter(|name| name.starts_with('.') && name.contains(TEMPORARY_MARKER))
                .cloned(),
        );
        let summary_path = self.path(SUMMARY_FILE);
        let Ok(text) = fs::read_to_string(&summary_path) else {
            return Ok(names);
        };
        let Ok(serde_json::Value::Object(summary)) = serde_json::from_str(&text) else {
            // Not a summary of ours: leave everything.
            return Ok(names);
        };
        if let Some(files) = summary.get("files").and_then(|f| f.as_array()) {
            for name in files.iter().filter_map(|f| f.as_str()) {
                if self.is_removable(name) {
                    names.push(name.to_string());
                }
            }
        } else if summary.contains_key("model") && summary.contains_key("scene") {
            names.extend(
                present
                    .iter()
                    .filter(|name| LEGACY_OUTPUT_PATTERNS.iter().any(|p| matches(p, name)))
                    .cloned(),
            );
        }
        Ok(names)
    }

    /// A listed name may be removed if it is a plain relative path to a regular file whose
    /// parent directory resolves inside the root.
    fn is_removable(&self, name: &str) -> bool {
        let relative = Path::new(name);
        if !is_plain_relative(relative) {
            return false;
        }
        let path = self.root.join(relative);
        let Ok(metadata) = fs::symlink_metadata(&path) else {
            return false;
        };
        if !metadata.is_file() {
            return false;
        }
        let (Some(parent), Ok(root)) = (path.parent(), fs::canonicalize(&self.root)) else {
            return false;
        };
        fs::canonicalize(parent)
            .map(|parent| parent.starts_with(root))
            .unwrap_or(false)
    }
}

/// Writes a value as JSON, pretty-printed, atomically.
pub fn write_json(path: &Path, value: &impl serde::Serialize) -> io::Result<()> {
    write_atomically(path, |writer| {
        serde_json::to_writer_pretty(&mut *writer, value)?;
        writer.write_all(b"\n")
    })
}

/// A non-empty relative path of normal components only (no `..`, `.`, root or prefix).
fn is_plain_relative(path: &Path) -> bool {
    path.components().next().is_some()
        && path.components().all(|c| matches!(c, Component::Normal(_)))
}

/// Glob match with `*` (any run of characters) as the only wildcard.
fn matches(pattern: &str, name: &str) -> bool {
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
