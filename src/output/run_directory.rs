//! The directory of one run ([`RunDirectory`]): one run at a time, written beside it and swapped
//! in whole, so that after a kill at any moment the directory holds the previous run or the new
//! one, each complete and consistent with its manifest (the `files` of its `summary.json`).
//!
//! For an output directory `PARENT/NAME`:
//!
//! 1. **Lock.** [`RunDirectory::open`] takes an exclusive lock (`flock`) on
//!    `PARENT/.NAME.wrinkle-lock` — a small file that stays, holding the PID of the last run —
//!    before any work. A second run into the same directory fails at once (it does not wait),
//!    naming the PID that holds it. The operating system releases the lock when its process
//!    ends, however it ends: there are no stale locks.
//! 2. **Recover** what a killed predecessor left (below), then **check** the directory: it may
//!    hold a previous run and files of yours, but no file of yours with the name of an output
//!    (`path.csv`, `summary.json`, …) that no run listed — the new run would replace it.
//! 3. **Stage.** The run writes every output, `summary.json` last, into the fresh sibling
//!    `PARENT/.NAME.wrinkle-new` (marked as incomplete by a file `.wrinkle-staging` until
//!    `summary.json` is in).
//! 4. **Swap.** [`RunDirectory::commit`] exchanges the staging directory and `PARENT/NAME` in
//!    one atomic `renameat2(RENAME_EXCHANGE)` (Linux; elsewhere, or where the file system
//!    refuses it, two renames through `PARENT/.NAME.wrinkle-old`, which a kill between them
//!    leaves for the next run to finish), then moves your files from the old directory into
//!    the new one and removes the old run's files.
//!
//! **Recovery**, under the lock: a directory `PARENT/NAME` missing beside a complete staging
//! directory (a kill between the two renames) is finished; then every leftover sibling
//! (`.NAME.wrinkle-new`, `.NAME.wrinkle-old`) is emptied — an incomplete staging directory
//! removed whole; from an old run directory, the files its run wrote are removed and anything
//! else (yours) is moved back into `PARENT/NAME`. A file wrinkle did not write is never removed.
//!
//! Which files a run wrote: those listed under `files` in its `summary.json`; if that summary is
//! a wrinkle summary, also any file named like an output ([`OUTPUT_PATTERNS`], written by a run
//! killed before it listed them) — for a summary of a `wrinkle run` that did not list its files
//! (an object with `model` and `scene`) these are all there is; and leftover temporary files of
//! atomic writes ([`TEMPORARY_MARKER`]). Listed names count only as plain relative names of
//! regular files (no `..`, no absolute path, no directory, no symbolic link).

use super::files::{
    LEGACY_OUTPUT_PATTERNS, SUMMARY_FILE, TEMPORARY_MARKER, is_plain_relative, matches, with_path,
    write_json,
};
use super::invalid;
use crate::input::{MAX_SUMMARY_BYTES, read_capped};
use std::collections::BTreeSet;
use std::ffi::OsString;
use std::fs::{self, File, OpenOptions};
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};

/// Every output name of a run, `*` matching any characters: the legacy outputs and
/// `local_wavenumber.*`. A file so named in a run directory with a wrinkle summary is the run's
/// own even when the summary does not list it.
pub const OUTPUT_PATTERNS: [&str; 20] = [
    LEGACY_OUTPUT_PATTERNS[0],
    LEGACY_OUTPUT_PATTERNS[1],
    LEGACY_OUTPUT_PATTERNS[2],
    LEGACY_OUTPUT_PATTERNS[3],
    LEGACY_OUTPUT_PATTERNS[4],
    LEGACY_OUTPUT_PATTERNS[5],
    LEGACY_OUTPUT_PATTERNS[6],
    LEGACY_OUTPUT_PATTERNS[7],
    LEGACY_OUTPUT_PATTERNS[8],
    LEGACY_OUTPUT_PATTERNS[9],
    LEGACY_OUTPUT_PATTERNS[10],
    LEGACY_OUTPUT_PATTERNS[11],
    LEGACY_OUTPUT_PATTERNS[12],
    LEGACY_OUTPUT_PATTERNS[13],
    "local_wavenumber.*",
    "*.pvd",
    "membrane_force_*.png",
    "membrane_force_*.svg",
    "wrinkles_zone_*.png",
    "wrinkles_zone_*.svg",
];

/// The folder of a run directory that holds the path's time series (`series/*.vtu`, listed in
/// the summary as `series/NAME`): the run's own, with every file in it, when the directory holds
/// a wrinkle summary.
pub const SERIES_DIRECTORY: &str = "series";

/// Suffix of the lock file `PARENT/.NAME.wrinkle-lock`.
pub const LOCK_SUFFIX: &str = ".wrinkle-lock";
/// Suffix of the staging directory `PARENT/.NAME.wrinkle-new`.
pub const STAGING_SUFFIX: &str = ".wrinkle-new";
/// Suffix of the old run directory between the two renames of the fallback swap.
pub const RETIRED_SUFFIX: &str = ".wrinkle-old";
/// The file that marks a staging directory as incomplete (removed once `summary.json` is in).
pub const STAGING_MARKER: &str = ".wrinkle-staging";

/// Name of the lock file inside a directory locked with [`DirectoryLock::inside`].
pub const DIRECTORY_LOCK_FILE: &str = ".wrinkle-lock";

/// An exclusive lock on an output directory that is not swapped in whole (the directories of
/// `wrinkle compare` and `wrinkle bench`, which hold one run directory per model or point):
/// the file [`DIRECTORY_LOCK_FILE`] inside it, held until dropped. A second command into the
/// same directory fails at once, like a second run ([`RunDirectory::open`]).
#[derive(Debug)]
pub struct DirectoryLock {
    _lock: File,
}

impl DirectoryLock {
    /// Creates `directory` if needed (with its parents) and locks it.
    ///
    /// Errors: another command holds the lock (kind [`io::ErrorKind::WouldBlock`], naming its
    /// PID); `directory` exists and is not a directory, or is a symbolic link leading nowhere
    /// (kind [`io::ErrorKind::InvalidInput`]); any I/O error, naming its path.
    pub fn inside(directory: &Path) -> io::Result<Self> {
        if let Ok(metadata) = fs::symlink_metadata(directory) {
            if metadata.file_type().is_symlink() && fs::metadata(directory).is_err() {
                return Err(invalid(
                    "output directory",
                    format!(
                        "`{}` is a symbolic link that leads nowhere (a loop, or a missing target)",
                        directory.display()
                    ),
                ));
            }
            if !directory.is_dir() {
                return Err(invalid(
                    "output directory",
                    format!("`{}` exists and is not a directory", directory.display()),
                ));
            }
        }
        fs::create_dir_all(directory).map_err(|error| with_path(directory, error))?;
        let lock = lock(&directory.join(DIRECTORY_LOCK_FILE), directory)?;
        Ok(DirectoryLock { _lock: lock })
    }
}

/// The output directory of one run (module documentation): locked, staged, swapped in whole.
#[derive(Debug)]
pub struct RunDirectory {
    root: PathBuf,
    staging: PathBuf,
    _lock: File,
    written: Vec<String>,
    replaced: Vec<String>,
    notes: Vec<String>,
    committed: bool,
}

impl RunDirectory {
    /// Locks `root` (created if needed, with its parents), recovers what a killed run left,
    /// checks it, and creates the staging directory the run writes into.
    ///
    /// Errors: another run holds the lock (kind [`io::ErrorKind::WouldBlock`]); `root` is not a
    /// directory, a symbolic link leading nowhere, the current directory, or holds a file that
    /// is not a run's under an output's name (kind [`io::ErrorKind::InvalidInput`]); any I/O
    /// error, naming its path.
    pub fn open(root: &Path) -> io::Result<Self> {
        let (parent, name) = resolve(root)?;
        let root = parent.join(&name);
        let lock = lock(&sibling(&parent, &name, LOCK_SUFFIX), &root)?;
        let mut notes = Vec::new();
        recover(&parent, &name, &mut notes)?;
        let previous = if root.is_dir() {
            let contents = RunContents::read(&root)?;
            contents.refuse_clashes(&root)?;
            contents.listed
        } else {
            Vec::new()
        };
        let staging = sibling(&parent, &name, STAGING_SUFFIX);
        fs::create_dir(&staging).map_err(|error| with_path(&staging, error))?;
        let marker = staging.join(STAGING_MARKER);
        File::create(&marker).map_err(|error| with_path(&marker, error))?;
        Ok(RunDirectory {
            root,
            staging,
            _lock: lock,
            written: Vec::new(),
            replaced: previous,
            notes,
            committed: false,
        })
    }

    /// The directory (its canonical path), where the outputs are once committed.
    pub fn root(&self) -> &Path {
        &self.root
    }

    /// The staging directory the outputs are written into before [`RunDirectory::commit`].
    pub fn staging(&self) -> &Path {
        &self.staging
    }

    /// `name` in the staging directory: where to write the output `name`.
    pub fn path(&self, name: impl AsRef<Path>) -> PathBuf {
        self.staging.join(name)
    }

    /// The previous run's files, which [`RunDirectory::commit`] replaces (relative names).
    pub fn replaced(&self) -> &[String] {
        &self.replaced
    }

    /// What recovering from a killed run did (empty when nothing was left), for the notes.
    pub fn notes(&self) -> &[String] {
        &self.notes
    }

    /// Every file recorded so far, relative to the directory, in the order written.
    pub fn files(&self) -> &[String] {
        &self.written
    }

    /// Records files written into the staging directory (each once), given as paths from
    /// [`RunDirectory::path`] or as relative names.
    ///
    /// Errors: a path outside the directory (kind [`io::ErrorKind::InvalidInput`]).
    pub fn record<P: AsRef<Path>>(&mut self, paths: impl IntoIterator<Item = P>) -> io::Result<()> {
        for path in paths {
            let name = self.relative_name(path.as_ref())?;
            if !self.written.contains(&name) {
                self.written.push(name);
            }
        }
        Ok(())
    }

    /// Writes `summary` (serialised as a JSON object, without a `files` key) as `summary.json`
    /// with the key `files` set to every recorded file plus `summary.json` itself, and returns
    /// its path (in the staging directory).
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

    /// Swaps the staged run in (module documentation) and returns the directory. The previous
    /// run's files are gone, yours are kept.
    ///
    /// Errors: no `summary.json` was written (kind [`io::ErrorKind::InvalidInput`]; nothing is
    /// swapped), or an I/O error.
    pub fn commit(mut self) -> io::Result<PathBuf> {
        if !self.staging.join(SUMMARY_FILE).is_file() {
            return Err(invalid(
                "run directory",
                "commit before write_summary: a run directory without its summary.json",
            ));
        }
        File::open(&self.staging)
            .and_then(|directory| directory.sync_all())
            .map_err(|error| with_path(&self.staging, error))?;
        let marker = self.staging.join(STAGING_MARKER);
        fs::remove_file(&marker).map_err(|error| with_path(&marker, error))?;
        let old = swap_in(&self.staging, &self.root)?;
        self.committed = true;
        if let Some(old) = old {
            discard(&old, &self.root, &mut self.notes)?;
        }
        Ok(self.root.clone())
    }

    /// `path` relative to the directory (or to its staging directory), `/`-separated; it must
    /// lie inside.
    fn relative_name(&self, path: &Path) -> io::Result<String> {
        let relative = path
            .strip_prefix(&self.staging)
            .or_else(|_| path.strip_prefix(&self.root))
            .unwrap_or(path);
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
        let components = relative.components();
        let parts: Vec<String> = components
            .map(|c| c.as_os_str().to_string_lossy().into_owned())
            .collect();
        Ok(parts.join("/"))
    }
}

impl Drop for RunDirectory {
    /// A run that ends without [`RunDirectory::commit`] (an error before its outputs) leaves
    /// the directory as it was: the staging directory is removed.
    fn drop(&mut self) {
        if !self.committed {
            let _ = fs::remove_dir_all(&self.staging);
        }
    }
}

/// `PARENT/.NAME{suffix}`.
fn sibling(parent: &Path, name: &OsString, suffix: &str) -> PathBuf {
    let mut file = OsString::from(".");
    file.push(name);
    file.push(suffix);
    parent.join(file)
}

/// The canonical parent and the name of `root`, creating the parent if needed; refuses what
/// cannot be swapped (module documentation of [`RunDirectory::open`]).
fn resolve(root: &Path) -> io::Result<(PathBuf, OsString)> {
    let shown = root.display();
    let real = match fs::symlink_metadata(root) {
        Ok(metadata) => {
            let real = fs::canonicalize(root).map_err(|error| {
                if metadata.file_type().is_symlink() {
                    invalid(
                        "output directory",
                        format!("`{shown}` is a symbolic link that leads nowhere (a loop, or a missing target): {error}"),
                    )
                } else {
                    with_path(root, error)
                }
            })?;
            if !real.is_dir() {
                return Err(invalid(
                    "output directory",
                    format!("`{shown}` exists and is not a directory"),
                ));
            }
            real
        }
        Err(error) if error.kind() == io::ErrorKind::NotFound => {
            let parent = match root.parent() {
                Some(parent) if !parent.as_os_str().is_empty() => parent,
                _ => Path::new("."),
            };
            fs::create_dir_all(parent).map_err(|error| with_path(parent, error))?;
            let parent = fs::canonicalize(parent).map_err(|error| with_path(parent, error))?;
            let name = root.file_name().ok_or_else(|| {
                invalid("output directory", format!("`{shown}` names no directory"))
            })?;
            parent.join(name)
        }
        Err(error) => return Err(with_path(root, error)),
    };
    let current = std::env::current_dir().and_then(fs::canonicalize);
    if current.is_ok_and(|current| current == real) {
        return Err(invalid(
            "output directory",
            format!(
                "`{shown}` is the current directory, which a run cannot replace: run from its parent, or name a subdirectory"
            ),
        ));
    }
    match (real.parent(), real.file_name()) {
        (Some(parent), Some(name)) => Ok((parent.to_path_buf(), name.to_os_string())),
        _ => Err(invalid(
            "output directory",
            format!("`{shown}` is the root of the file system"),
        )),
    }
}

/// Opens and locks `path` (exclusive, without waiting) and writes this process's PID in it.
fn lock(path: &Path, root: &Path) -> io::Result<File> {
    let mut file = OpenOptions::new()
        .create(true)
        .truncate(false)
        .read(true)
        .write(true)
        .open(path)
        .map_err(|error| with_path(path, error))?;
    match file.try_lock() {
        Ok(()) => {}
        Err(fs::TryLockError::WouldBlock) => {
            let mut holder = String::new();
            let _ = Read::by_ref(&mut file).take(32).read_to_string(&mut holder);
            let holder = holder.trim();
            let process = if holder.is_empty() {
                "another process".to_string()
            } else {
                format!("process {holder}")
            };
            return Err(io::Error::new(
                io::ErrorKind::WouldBlock,
                format!(
                    "another wrinkle run ({process}) is writing into `{}` (it holds the lock `{}`): wait for it to end, or choose another output directory",
                    root.display(),
                    path.display()
                ),
            ));
        }
        Err(fs::TryLockError::Error(error)) => return Err(with_path(path, error)),
    }
    let pid = std::process::id().to_string();
    file.set_len(0)
        .and_then(|()| file.write_all(pid.as_bytes()))
        .map_err(|error| with_path(path, error))?;
    Ok(file)
}

/// Finishes or undoes what a killed run left beside `PARENT/NAME` (module documentation).
fn recover(parent: &Path, name: &OsString, notes: &mut Vec<String>) -> io::Result<()> {
    let root = parent.join(name);
    let staging = sibling(parent, name, STAGING_SUFFIX);
    let retired = sibling(parent, name, RETIRED_SUFFIX);
    let exists = |path: &Path| fs::symlink_metadata(path).is_ok();
    if !exists(&root) {
        let complete =
            staging.join(SUMMARY_FILE).is_file() && !exists(&staging.join(STAGING_MARKER));
        let finished = if complete { &staging } else { &retired };
        if finished.is_dir() {
            fs::rename(finished, &root).map_err(|error| with_path(finished, error))?;
            notes.push(format!(
                "a run killed while swapping its outputs in left `{}` aside: {}",
                root.display(),
                if complete {
                    "its complete new run was put in place"
                } else {
                    "the previous run was put back"
                }
            ));
        }
    }
    for leftover in [staging, retired] {
        if exists(&leftover) {
            discard(&leftover, &root, notes)?;
        }
    }
    Ok(())
}

/// Empties and removes the leftover directory `old`: a staging directory whole; from an old
/// run directory, the files its run wrote are removed and everything else is moved into `into`.
/// What cannot be moved (a name taken in `into`) stays, and `old` with it, with a note.
fn discard(old: &Path, into: &Path, notes: &mut Vec<String>) -> io::Result<()> {
    if fs::symlink_metadata(old.join(STAGING_MARKER)).is_ok() {
        return fs::remove_dir_all(old).map_err(|error| with_path(old, error));
    }
    let contents = RunContents::read(old)?;
    let mut kept = Vec::new();
    for entry in contents.entries {
        let path = old.join(&entry);
        if contents.series_is_ours && entry == SERIES_DIRECTORY && path.is_dir() {
            fs::remove_dir_all(&path).map_err(|error| with_path(&path, error))?;
            continue;
        }
        if contents.ours.contains(&entry) {
            match fs::remove_file(&path) {
                Err(error) if error.kind() != io::ErrorKind::NotFound => {
                    return Err(with_path(&path, error));
                }
                _ => {}
            }
            continue;
        }
        let destination = into.join(&entry);
        if into.is_dir() && fs::symlink_metadata(&destination).is_err() {
            fs::rename(&path, &destination).map_err(|error| with_path(&path, error))?;
        } else {
            kept.push(entry);
        }
    }
    if kept.is_empty() {
        return fs::remove_dir(old).map_err(|error| with_path(old, error));
    }
    notes.push(format!(
        "`{}` was kept: it holds {} that no run wrote and whose names are taken in `{}`",
        old.display(),
        kept.join(", "),
        into.display()
    ));
    Ok(())
}

/// Puts `staging` in the place of `root` and returns where the old `root` went (to be
/// discarded), `None` when there was none.
fn swap_in(staging: &Path, root: &Path) -> io::Result<Option<PathBuf>> {
    if fs::symlink_metadata(root).is_err() {
        fs::rename(staging, root).map_err(|error| with_path(root, error))?;
        return Ok(None);
    }
    if exchange(staging, root)? {
        return Ok(Some(staging.to_path_buf()));
    }
    let (parent, name) = match (root.parent(), root.file_name()) {
        (Some(parent), Some(name)) => (parent, name.to_os_string()),
        _ => return Err(invalid("output directory", "no parent to swap in")),
    };
    let retired = sibling(parent, &name, RETIRED_SUFFIX);
    fs::rename(root, &retired).map_err(|error| with_path(root, error))?;
    fs::rename(staging, root).map_err(|error| with_path(root, error))?;
    Ok(Some(retired))
}

/// Exchanges two directories atomically (`renameat2(RENAME_EXCHANGE)`); `Ok(false)` when the
/// system or the file system cannot.
#[cfg(target_os = "linux")]
fn exchange(first: &Path, second: &Path) -> io::Result<bool> {
    use std::ffi::CString;
    use std::os::unix::ffi::OsStrExt;
    let text = |path: &Path| {
        CString::new(path.as_os_str().as_bytes())
            .map_err(|_| invalid("output directory", "a path with a NUL byte"))
    };
    let (first_text, second_text) = (text(first)?, text(second)?);
    // SAFETY: both arguments are NUL-terminated strings that live across the call; the
    // system call reads them and nothing else.
    let result = unsafe {
        libc::syscall(
            libc::SYS_renameat2,
            libc::AT_FDCWD,
            first_text.as_ptr(),
            libc::AT_FDCWD,
            second_text.as_ptr(),
            libc::RENAME_EXCHANGE,
        )
    };
    if result == 0 {
        return Ok(true);
    }
    let error = io::Error::last_os_error();
    match error.raw_os_error() {
        Some(libc::EINVAL | libc::ENOSYS | libc::EOPNOTSUPP) => Ok(false),
        _ => Err(with_path(second, error)),
    }
}

/// Exchanges two directories atomically where the system can; here it cannot.
#[cfg(not(target_os = "linux"))]
fn exchange(_first: &Path, _second: &Path) -> io::Result<bool> {
    Ok(false)
}

/// What a run directory holds: its entries, which of them its run wrote, and the files its
/// summary lists.
struct RunContents {
    /// Every entry (files, directories, links), by name.
    entries: Vec<String>,
    /// The entries a run wrote (module documentation).
    ours: BTreeSet<String>,
    /// The names under `files` in its `summary.json` that are the run's regular files.
    listed: Vec<String>,
    /// Whether [`SERIES_DIRECTORY`] is the run's (a wrinkle summary is there): removed whole.
    series_is_ours: bool,
}

impl RunContents {
    fn read(directory: &Path) -> io::Result<Self> {
        let mut entries = Vec::new();
        let mut regular = BTreeSet::new();
        let listing = fs::read_dir(directory).map_err(|error| with_path(directory, error))?;
        for entry in listing {
            let entry = entry.map_err(|error| with_path(directory, error))?;
            let name = entry.file_name().to_string_lossy().into_owned();
            if entry.file_type().is_ok_and(|kind| kind.is_file()) {
                regular.insert(name.clone());
            }
            entries.push(name);
        }
        entries.sort();
        let mut ours: BTreeSet<String> = regular
            .iter()
            .filter(|name| name.starts_with('.') && name.contains(TEMPORARY_MARKER))
            .cloned()
            .collect();
        let summary = read_summary(&directory.join(SUMMARY_FILE))?;
        let listed: Vec<String> = summary
            .as_ref()
            .and_then(|summary| summary.get("files"))
            .and_then(|files| files.as_array())
            .into_iter()
            .flatten()
            .filter_map(|name| name.as_str())
            .filter(|name| is_plain_relative(Path::new(name)) && regular.contains(*name))
            .map(str::to_string)
            .collect();
        let is_wrinkle_summary = summary.as_ref().is_some_and(|summary| {
            summary.contains_key("files")
                || (summary.contains_key("model") && summary.contains_key("scene"))
        });
        if is_wrinkle_summary {
            ours.extend(listed.iter().cloned());
            ours.extend(
                regular
                    .iter()
                    .filter(|name| OUTPUT_PATTERNS.iter().any(|p| matches(p, name)))
                    .cloned(),
            );
        }
        Ok(RunContents {
            entries,
            ours,
            listed,
            series_is_ours: is_wrinkle_summary,
        })
    }

    /// An error naming the files not written by a run whose names a run writes.
    fn refuse_clashes(&self, root: &Path) -> io::Result<()> {
        let clashes: Vec<&str> = self
            .entries
            .iter()
            .filter(|name| !self.ours.contains(*name))
            .filter(|name| OUTPUT_PATTERNS.iter().any(|p| matches(p, name)))
            .map(String::as_str)
            .collect();
        if clashes.is_empty() {
            return Ok(());
        }
        Err(invalid(
            "output directory",
            format!(
                "`{}` holds {} that no wrinkle run listed, under the names of a run's outputs: a run would replace them; move them away or choose another output directory",
                root.display(),
                clashes.join(", ")
            ),
        ))
    }
}

/// The JSON object in `path`, `None` when there is no such file, it is larger than
/// [`MAX_SUMMARY_BYTES`] or it is not a JSON object.
fn read_summary(path: &Path) -> io::Result<Option<serde_json::Map<String, serde_json::Value>>> {
    let text = match read_capped(path, MAX_SUMMARY_BYTES) {
        Ok(text) => text,
        Err(error)
            if matches!(
                error.kind(),
                io::ErrorKind::NotFound | io::ErrorKind::FileTooLarge
            ) =>
        {
            return Ok(None);
        }
        Err(error) => return Err(with_path(path, error)),
    };
    match serde_json::from_slice(&text) {
        Ok(serde_json::Value::Object(summary)) => Ok(Some(summary)),
        _ => Ok(None),
    }
}
