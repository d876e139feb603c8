//! Atomic writes leave no temporary file and never a half-written destination; the run
//! directory removes the previous run's files — only those — and lists the files written.

use std::collections::BTreeSet;
use std::io;
use std::path::{Path, PathBuf};
use wrinkle::output::files::{LEGACY_OUTPUT_PATTERNS, TEMPORARY_MARKER};
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

#[test]
fn run_directory_removes_the_previous_run_and_keeps_foreign_files() {
    let dir = scratch_dir("run-directory");
    // The user's own files, including one with an output's extension.
    std::fs::write(dir.join("notes.txt"), "mine").unwrap();
    std::fs::write(dir.join("my_plot.png"), "mine").unwrap();

    // First run: a scene with VTU files at two loads.
    let mut first = RunDirectory::prepare(&dir).unwrap();
    assert!(first.removed().is_empty());
    for name in [
        "path.csv",
        "fields_load_0.1.vtu",
        "fields_load_0.2.vtu",
        "response.png",
    ] {
        write_bytes_atomically(&first.path(name), b"first run").unwrap();
        first.record([first.path(name)]).unwrap();
    }
    let summary = first
        .write_summary(&serde_json::json!({"model": "a"}))
        .unwrap();
    let written: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(summary).unwrap()).unwrap();
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

    // Second run into the same directory: none of the first run's files survive.
    let second = RunDirectory::prepare(&dir).unwrap();
    assert_eq!(
        second.removed().iter().cloned().collect::<BTreeSet<_>>(),
        set(&[
            "path.csv",
            "fields_load_0.1.vtu",
            "fields_load_0.2.vtu",
            "response.png",
            "summary.json"
        ])
    );
    assert_eq!(
        names(&dir),
        set(&["notes.txt", "my_plot.png", "summary.json"]),
        "foreign files stay; summary.json is the new run's interim manifest"
    );
    assert!(second.files().is_empty());
}

#[test]
fn a_run_killed_half_way_is_still_cleaned() {
    let dir = scratch_dir("killed-run");
    let mut first = RunDirectory::prepare(&dir).unwrap();
    write_bytes_atomically(&first.path("path.csv"), b"partial").unwrap();
    first.record(["path.csv"]).unwrap();
    // A temporary file of an interrupted atomic write.
    let leftover = format!(".response.png.123-4{TEMPORARY_MARKER}.png");
    std::fs::write(dir.join(&leftover), "half").unwrap();
    drop(first); // no final summary: the process died

    let second = RunDirectory::prepare(&dir).unwrap();
    assert!(second.removed().contains(&"path.csv".to_string()));
    assert!(second.removed().contains(&leftover));
    assert_eq!(names(&dir), set(&["summary.json"]));
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

    let directory = RunDirectory::prepare(&dir).unwrap();
    assert_eq!(directory.removed(), ["listed.csv"]);
    assert!(root.join("precious.txt").exists());
    assert!(dir.join("sub").join("kept.vtu").exists());
}

#[test]
fn an_older_wrinkle_summary_removes_the_known_outputs_only() {
    let dir = scratch_dir("legacy");
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

    RunDirectory::prepare(&dir).unwrap();
    assert_eq!(
        names(&dir),
        set(&["mesh_study.csv", "fields_mine.vtu", "summary.json"])
    );
}

#[test]
fn a_directory_without_our_summary_loses_nothing() {
    let dir = scratch_dir("foreign");
    for name in ["path.csv", "response.png", "report.html"] {
        std::fs::write(dir.join(name), "not ours").unwrap();
    }
    // A summary.json that is not a wrinkle summary.
    std::fs::write(dir.join("summary.json"), "[1, 2, 3]").unwrap();
    let directory = RunDirectory::prepare(&dir).unwrap();
    assert!(directory.removed().is_empty());
    for name in ["path.csv", "response.png", "report.html"] {
        assert_eq!(std::fs::read_to_string(dir.join(name)).unwrap(), "not ours");
    }
}

#[test]
fn recording_a_file_outside_the_directory_is_an_error() {
    let dir = scratch_dir("record-outside");
    let mut directory = RunDirectory::prepare(&dir.join("run")).unwrap();
    let error = directory.record([dir.join("elsewhere.csv")]).unwrap_err();
    assert_eq!(error.kind(), io::ErrorKind::InvalidInput);
    directory.record(["a.csv", "a.csv", "sub/b.vtu"]).unwrap();
    assert_eq!(directory.files(), ["a.csv", "sub/b.vtu"]);
}
