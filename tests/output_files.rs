//! Atomic writes leave no temporary file and never a half-written destination; the run
//! directory is written beside itself and swapped in whole, replaces the previous run's files —
//! only those — lists the files written, finishes or undoes what a killed run left, and lets one
//! run at a time in.

use std::collections::BTreeSet;
use std::io;
use std::path::{Path, PathBuf};
use wrinkle::output::files::{LEGACY_OUTPUT_PATTERNS, TEMPORARY_MARKER};
use wrinkle::output::run_directory::{RETIRED_SUFFIX, STAGING_MARKER, STAGING_SUFFIX};
use wrinkle::output::{RunDirectory, write_atomically, write_bytes_atomically};

fn scratch_dir(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-files-{}-{test}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn names(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

fn set(items: &[&str]) -> BTreeSet<String> {
    items.iter().map(|s| s.to_string()).collect()
}

#[test]
fn atomic_write_replaces_the_file_and_leaves_no_temporary_file() {
    let dir = scratch_dir("atomic");
    let file = dir.join("path.csv");
    write_bytes_atomically(&file, b"first\n").unwrap();
    write_atomically(&file, |writer| {
        writer.write_all(b"second")?;
        writer.write_all(b" version\n")
    })
    .unwrap();
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "second version\n");
    assert_eq!(names(&dir), set(&["path.csv"]));
}

#[test]
fn failed_atomic_write_keeps_the_old_file_and_removes_the_temporary_one() {
    let dir = scratch_dir("atomic-failure");
    let file = dir.join("summary.json");
    write_bytes_atomically(&file, b"{\"old\": true}").unwrap();
    let error = write_atomically(&file, |writer| {
        writer.write_all(b"{\"half\": ")?;
        Err(io::Error::other("the encoder gave up"))
    })
    .unwrap_err();
    assert!(error.to_string().contains("the encoder gave up"), "{error}");
    assert!(error.to_string().contains("summary.json"), "{error}");
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "{\"old\": true}");
    assert_eq!(names(&dir), set(&["summary.json"]));
}

/// A run of `names` (each file holding `content`) into `directory`, committed.
fn commit_run(directory: &Path, names: &[&str], content: &str) -> Vec<String> {
    let mut run = RunDirectory::open(directory).unwrap();
    for name in names {
        write_bytes_atomically(&run.path(name), content.as_bytes()).unwrap();
        run.record([run.path(name)]).unwrap();
    }
    run.write_summary(&serde_json::json!({"model": content}))
        .unwrap();
    let replaced = run.replaced().to_vec();
    run.commit().unwrap();
    replaced
}

/// The sibling `.out{suffix}` of `dir/out`.
fn sibling(dir: &Path, suffix: &str) -> PathBuf {
    dir.join(format!(".out{suffix}"))
}

#[test]
fn run_directory_replaces_the_previous_run_and_keeps_foreign_files() {
    let root = scratch_dir("run-directory");
    let dir = root.join("out");
    std::fs::create_dir_all(&dir).unwrap();
    // The user's own files, including one with an output's extension.
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    std::fs::write(dir.join("my_plot.png"), "mine").unwrap();

    // First run: a scene with VTU files at two loads.
    let first = [
        "path.csv",
        "fields_load_0.1.vtu",
        "fields_load_0.2.vtu",
        "response.png",
    ];
    assert!(commit_run(&dir, &first, "first").is_empty());
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    assert_eq!(
        written["files"],
        serde_json::json!([
            "path.csv",
            "fields_load_0.1.vtu",
            "fields_load_0.2.vtu",
            "response.png",
            "summary.json"
        ])
    );

    // Second run into the same directory: until it commits, the first run is untouched;
    // then none of its files survive, and the user's do.
    let mut second = RunDirectory::open(&dir).unwrap();
    assert_eq!(
        second.replaced().iter().cloned().collect::<BTreeSet<_>>(),
        set(&[
            "path.csv",
            "fields_load_0.1.vtu",
            "fields_load_0.2.vtu",
            "response.png",
            "summary.json"
        ])
    );
    write_bytes_atomically(&second.path("path.csv"), b"second").unwrap();
    second.record(["path.csv"]).unwrap();
    assert_eq!(
        std::fs::read_to_string(dir.join("path.csv")).unwrap(),
        "first"
    );
    second.write_summary(&serde_json::json!({})).unwrap();
    second.commit().unwrap();
    assert_eq!(
        names(&dir),
        set(&["notes.txt", "my_plot.png", "path.csv", "summary.json"]),
    );
    assert_eq!(
        std::fs::read_to_string(dir.join("path.csv")).unwrap(),
        "second"
    );
    // Only the lock file stays beside the directory.
    assert_eq!(names(&root), set(&["out", ".out.wrinkle-lock"]));
}

#[test]
fn a_run_that_ends_without_commit_leaves_the_previous_run() {
    let root = scratch_dir("no-commit");
    let dir = root.join("out");
    commit_run(&dir, &["path.csv"], "first");
    let failed = RunDirectory::open(&dir).unwrap();
    write_bytes_atomically(&failed.path("path.csv"), b"partial").unwrap();
    drop(failed);
    assert_eq!(names(&dir), set(&["path.csv", "summary.json"]));
    assert_eq!(
        std::fs::read_to_string(dir.join("path.csv")).unwrap(),
        "first"
    );
    assert!(!sibling(&root, STAGING_SUFFIX).exists());
}

#[test]
fn a_run_killed_while_writing_is_cleaned_by_the_next() {
    let root = scratch_dir("killed-run");
    let dir = root.join("out");
    commit_run(&dir, &["path.csv"], "first");
    // What a kill while writing leaves: a staging directory still marked incomplete, and a
    // temporary file of an interrupted atomic write in the directory itself (older versions).
    let staging = sibling(&root, STAGING_SUFFIX);
    std::fs::create_dir(&staging).unwrap();
    std::fs::write(staging.join(STAGING_MARKER), "").unwrap();
    std::fs::write(staging.join("path.csv"), "partial").unwrap();
    let leftover = format!(".response.png.123-4{TEMPORARY_MARKER}.png");
    std::fs::write(dir.join(&leftover), "half").unwrap();

    let replaced = commit_run(&dir, &["response.png"], "second");
    assert_eq!(replaced, ["path.csv", "summary.json"]);
    assert!(!staging.exists());
    assert_eq!(names(&dir), set(&["response.png", "summary.json"]));
}

#[test]
fn a_run_killed_between_the_two_renames_is_finished_by_the_next() {
    let root = scratch_dir("killed-swap");
    let dir = root.join("out");
    commit_run(&dir, &["path.csv"], "first");
    // The fallback swap renames the old directory aside, then the new one in.
    let retired = sibling(&root, RETIRED_SUFFIX);
    std::fs::rename(&dir, &retired).unwrap();
    std::fs::write(retired.join("notes.txt"), "mine").unwrap();
    let staging = sibling(&root, STAGING_SUFFIX);
    std::fs::create_dir(&staging).unwrap();
    std::fs::write(staging.join("path.csv"), "second").unwrap();
    let manifest = serde_json::json!({"model": "second", "files": ["path.csv", "summary.json"]});
    std::fs::write(staging.join("summary.json"), manifest.to_string()).unwrap();

    let run = RunDirectory::open(&dir).unwrap();
    assert_eq!(run.replaced(), ["path.csv", "summary.json"]);
    assert_eq!(run.notes().len(), 1, "{:?}", run.notes());
    assert_eq!(
        std::fs::read_to_string(dir.join("path.csv")).unwrap(),
        "second"
    );
    assert_eq!(names(&dir), set(&["notes.txt", "path.csv", "summary.json"]));
    assert!(!retired.exists());
}

#[test]
fn a_run_killed_after_the_swap_hands_back_the_users_files() {
    let root = scratch_dir("killed-after-swap");
    let dir = root.join("out");
    commit_run(&dir, &["path.csv"], "first");
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    // After the exchange, the old run (with the user's file) sits in the staging name.
    let staging = sibling(&root, STAGING_SUFFIX);
    std::fs::rename(&dir, &staging).unwrap();
    std::fs::create_dir(&dir).unwrap();
    std::fs::write(dir.join("path.csv"), "second").unwrap();
    let manifest = serde_json::json!({"model": "second", "files": ["path.csv", "summary.json"]});
    std::fs::write(dir.join("summary.json"), manifest.to_string()).unwrap();

    drop(RunDirectory::open(&dir).unwrap());
    assert_eq!(names(&dir), set(&["notes.txt", "path.csv", "summary.json"]));
    assert_eq!(
        std::fs::read_to_string(dir.join("path.csv")).unwrap(),
        "second"
    );
    assert!(!staging.exists());
}

#[test]
fn one_run_at_a_time_holds_the_directory() {
    let root = scratch_dir("lock");
    let dir = root.join("out");
    let first = RunDirectory::open(&dir).unwrap();
    let error = RunDirectory::open(&dir).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::WouldBlock);
    let message = error.to_string();
    assert!(message.contains("another wrinkle run"), "{message}");
    assert!(
        message.contains(&std::process::id().to_string()),
        "{message}"
    );
    drop(first);
    RunDirectory::open(&dir).unwrap();
}

#[test]
fn listed_names_outside_the_directory_are_never_removed() {
    let root = scratch_dir("outside");
    let dir = root.join("out");
    std::fs::create_dir_all(dir.join("sub")).unwrap();
    std::fs::write(root.join("precious.txt"), "keep").unwrap();
    std::fs::write(dir.join("sub").join("kept.vtu"), "keep").unwrap();
    std::fs::write(dir.join("listed.csv"), "old run").unwrap();
    let absolute = root.join("precious.txt").display().to_string();
    let summary = serde_json::json!({
        "files": ["../precious.txt", absolute, "sub", "listed.csv", "", ".", "sub/../../precious.txt"]
    });
    std::fs::write(dir.join("summary.json"), summary.to_string()).unwrap();

    assert_eq!(commit_run(&dir, &[], "new"), ["listed.csv"]);
    assert!(root.join("precious.txt").exists());
    assert!(dir.join("sub").join("kept.vtu").exists());
    assert_eq!(names(&dir), set(&["sub", "summary.json"]));
}

#[test]
fn an_older_wrinkle_summary_removes_the_known_outputs_only() {
    let root = scratch_dir("legacy");
    let dir = root.join("out");
    std::fs::create_dir_all(&dir).unwrap();
    let known = [
        "path.csv",
        "scene.toml",
        "fields_final.vtu",
        "surface_final.vtu",
        "fields_load_0.095000.vtu",
        "response.png",
        "response.svg",
        "profiles_x.png",
        "profiles_y.svg",
        "wrinkles.png",
    ];
    for name in known {
        std::fs::write(dir.join(name), "old").unwrap();
    }
    std::fs::write(dir.join("mesh_study.csv"), "mine").unwrap();
    std::fs::write(dir.join("fields_mine.vtu"), "mine").unwrap();
    let legacy = serde_json::json!({"model": "reference-envelope", "scene": {}, "path": []});
    std::fs::write(dir.join("summary.json"), legacy.to_string()).unwrap();
    assert!(LEGACY_OUTPUT_PATTERNS.contains(&"fields_load_*.vtu"));

    commit_run(&dir, &[], "new");
    assert_eq!(
        names(&dir),
        set(&["mesh_study.csv", "fields_mine.vtu", "summary.json"])
    );
}

#[test]
fn a_directory_whose_files_a_run_would_replace_is_refused_untouched() {
    let root = scratch_dir("foreign");
    let dir = root.join("out");
    std::fs::create_dir_all(&dir).unwrap();
    for name in ["path.csv", "response.png", "report.html"] {
        std::fs::write(dir.join(name), "not ours").unwrap();
    }
    // A summary.json that is not a wrinkle summary.
    std::fs::write(dir.join("summary.json"), "[1, 2, 3]").unwrap();
    let error = RunDirectory::open(&dir).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    let message = error.to_string();
    assert!(
        message.contains("path.csv") && message.contains("summary.json"),
        "{message}"
    );
    for name in ["path.csv", "response.png", "report.html"] {
        assert_eq!(std::fs::read_to_string(dir.join(name)).unwrap(), "not ours");
    }
    assert_eq!(names(&root), set(&["out", ".out.wrinkle-lock"]));
}

#[test]
fn what_cannot_be_swapped_in_is_refused() {
    let root = scratch_dir("refused");
    let file = root.join("file");
    std::fs::write(&file, "").unwrap();
    let error = RunDirectory::open(&file).unwrap_err();
    assert!(error.to_string().contains("not a directory"), "{error}");
    #[cfg(unix)]
    {
        let (first, second) = (root.join("loop1"), root.join("loop2"));
        std::os::unix::fs::symlink(&second, &first).unwrap();
        std::os::unix::fs::symlink(&first, &second).unwrap();
        let error = RunDirectory::open(&first).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
        assert!(error.to_string().contains("symbolic link"), "{error}");
    }
}

#[test]
fn commit_needs_the_summary() {
    let root = scratch_dir("no-summary");
    let run = RunDirectory::open(&root.join("out")).unwrap();
    let error = run.commit().unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    assert!(!root.join("out").exists());
}

#[test]
fn recording_a_file_outside_the_directory_is_an_error() {
    let dir = scratch_dir("record-outside");
    let mut directory = RunDirectory::open(&dir.join("run")).unwrap();
    let error = directory.record([dir.join("elsewhere.csv")]).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    directory.record(["a.csv", "a.csv", "sub/b.vtu"]).unwrap();
    assert_eq!(directory.files(), ["a.csv", "sub/b.vtu"]);
}
