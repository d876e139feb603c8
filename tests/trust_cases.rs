//! Issue 26, "Trust, round two": the command-line cases of the issue, one test each, named after
//! the case (the scene keys refused at their source are in `scene_trust.rs`, the run directory's
//! lock and kills in `run_directory_cli.rs`).
//!
//! Source: issue 26 ("Silent nonsense", "Lost or mixed outputs", "Unbounded work", "Errors that
//! do not name the cause", "Work before validation"). Scenes: the default example 1 on small
//! meshes (8 × 4 or 16 × 8 elements, no plots or surface) so that each run takes a fraction of a
//! second.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// A fresh, empty directory for one test.
fn scratch(test: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-trust-{test}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn wrinkle(arguments: &[&str]) -> Command {
    let mut command = Command::new(env!("CARGO_BIN_EXE_wrinkle"));
    command.args(arguments);
    command
}

fn stderr(output: &Output) -> String {
    String::from_utf8_lossy(&output.stderr).into_owned()
}

/// `--set` arguments of a quick run: a coarse mesh, no plots, no surface.
const QUICK: [&str; 8] = [
    "--set",
    "mesh.nx=16",
    "--set",
    "mesh.ny=8",
    "--set",
    "output.plots=false",
    "--set",
    "output.surface=false",
];

/// `wrinkle run -q QUICK extra --out DIRECTORY`.
fn quick_run(directory: &Path, extra: &[&str]) -> Output {
    let mut arguments = vec!["run", "-q"];
    arguments.extend(QUICK);
    arguments.extend(extra);
    wrinkle(&arguments)
        .arg("--out")
        .arg(directory)
        .output()
        .unwrap()
}

fn summary(directory: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(directory.join("summary.json")).unwrap()).unwrap()
}

/// The `detail` of every note of a summary with `title`.
fn notes_titled(summary: &serde_json::Value, title: &str) -> Vec<String> {
    summary["notes"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|note| note["title"] == title)
        .map(|note| note["detail"].as_str().unwrap().to_string())
        .collect()
}

/// Issue: a run whose summary table cannot be written to stdout (`> /dev/full`) exited 0 while
/// `buckle` exited 1. Every command now fails (exit 1) naming `<stdout>`; a run still writes its
/// outputs.
#[cfg(target_os = "linux")]
#[test]
fn stdout_that_cannot_be_written_fails_every_command() {
    let dir = scratch("dev-full");
    let run_dir = dir.join("run");
    let compare_dir = dir.join("compare");
    let run_dir_text = run_dir.display().to_string();
    let compare_dir_text = compare_dir.display().to_string();
    let small = ["--set", "mesh.nx=8", "--set", "mesh.ny=4"];
    let mut commands: Vec<Vec<&str>> = vec![
        vec!["models"],
        vec!["scene"],
        vec!["analytic"],
        vec!["analytic", "--json"],
        vec!["buckle", "-q"],
        vec!["buckle", "-q", "--json"],
        vec!["run", "-q", "--out", &run_dir_text],
        vec![
            "compare",
            "-q",
            "--models",
            "reference-envelope",
            "--out",
            &compare_dir_text,
        ],
    ];
    for command in &mut commands[4..] {
        command.extend(small);
    }
    for arguments in &commands {
        let full = std::fs::OpenOptions::new()
            .write(true)
            .open("/dev/full")
            .unwrap();
        let output = wrinkle(arguments).stdout(full).output().unwrap();
        let text = stderr(&output);
        assert_eq!(output.status.code(), Some(1), "{arguments:?}: {text}");
        assert!(text.contains("<stdout>"), "{arguments:?}: {text}");
    }
    assert!(run_dir.join("summary.json").is_file());
    // `--help` that cannot be written is not a success either.
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let output = wrinkle(&["--help"]).stdout(full).output().unwrap();
    assert_eq!(output.status.code(), Some(1));
    // A closed pipe is still not an error.
    let output = wrinkle(&["models"]).stdout(Stdio::null()).output().unwrap();
    assert_eq!(output.status.code(), Some(0));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A standard error that cannot be written loses the messages, but is not a panic (it was:
/// `eprintln!` panics, exit 101) and changes no exit code.
#[cfg(target_os = "linux")]
#[test]
fn stderr_that_cannot_be_written_is_not_a_panic() {
    let dir = scratch("dev-full-stderr");
    let mut arguments = vec!["run"];
    arguments.extend(QUICK);
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let output = wrinkle(&arguments)
        .arg("--out")
        .arg(dir.join("run"))
        .stderr(full)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0));
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let output = wrinkle(&["buckle", "--set", "material.young=-1"])
        .stderr(full)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue: two `output.vtu_loads` that print the same in the file name (`[1e-7, 2e-7]`) wrote one
/// file over the other and listed it twice. Each now has its own file, listed once.
#[test]
fn vtu_loads_that_print_alike_get_distinct_file_names() {
    let dir = scratch("vtu-names");
    let output = quick_run(&dir, &["--set", "output.vtu_loads=[1e-7, 2e-7]"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let summary = summary(&dir);
    let files: Vec<&str> = summary["vtu"]
        .as_array()
        .unwrap()
        .iter()
        .map(|file| file["file"].as_str().unwrap())
        .collect();
    assert_eq!(
        files,
        [
            "fields_final.vtu",
            "fields_load_0.0000001.vtu",
            "fields_load_0.0000002.vtu"
        ]
    );
    for file in &files {
        assert!(dir.join(file).is_file(), "{file}");
    }
    // The names of the golden scenes stay as they were; beyond 12 decimals, scientific notation.
    use wrinkle::results::fields_file_at;
    let loads = [0.09, 0.1, 1.0];
    assert_eq!(fields_file_at(0.09, &loads), "fields_load_0.090000.vtu");
    let tiny = [1e-300, 2e-300];
    assert_eq!(fields_file_at(2e-300, &tiny), "fields_load_2e-300.vtu");
    let negative = [-1e-7];
    assert_eq!(
        fields_file_at(-1e-7, &negative),
        "fields_load_-0.0000001.vtu"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue: `solver.imperfection = "uniform"` on the plate silently used the mode shape and the
/// summary still said `uniform`. The run says so in a note (terminal and `summary.json`) and
/// records the shape it used.
#[test]
fn uniform_imperfection_on_the_plate_is_noted_and_recorded() {
    let dir = scratch("uniform-plate");
    let output = quick_run(
        &dir,
        &[
            "--set",
            "model.name=fvk-plate",
            "--set",
            "solver.imperfection=uniform",
            "--set",
            "solver.max_amplitude_over_h=0.5",
            "--set",
            "validity.accept=[\"all\"]",
        ],
    );
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(stdout.contains("note: solver.imperfection:"), "{stdout}");
    let plate = summary(&dir);
    assert_eq!(plate["imperfection_shape"], "mode");
    let notes = notes_titled(&plate, "solver.imperfection");
    assert_eq!(notes.len(), 1, "{notes:?}");
    assert!(
        notes[0].contains("\"mode\" imperfection was used"),
        "{notes:?}"
    );
    // An envelope model uses what it is asked, without a note.
    let output = quick_run(&dir, &["--set", "solver.imperfection=uniform"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let envelope = summary(&dir);
    assert_eq!(envelope["imperfection_shape"], "uniform");
    assert!(notes_titled(&envelope, "solver.imperfection").is_empty());
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue: "a requested value that is dropped or replaced without a note" — a VTU load below
/// the path's first load (a negative one) was dropped silently; it is now listed in
/// `unreached_vtu_loads` with a note, as a load beyond the path's end already was.
#[test]
fn vtu_load_below_the_path_is_noted() {
    let dir = scratch("vtu-below");
    let output = quick_run(&dir, &["--set", "output.vtu_loads=[-0.1, 0.05, 5.0]"]);
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let summary = summary(&dir);
    assert_eq!(
        summary["unreached_vtu_loads"],
        serde_json::json!([-0.1, 5.0])
    );
    let notes = notes_titled(&summary, "output.vtu_loads");
    assert_eq!(notes.len(), 2, "{notes:?}");
    assert!(
        notes[0].contains("below the path's first load"),
        "{notes:?}"
    );
    assert!(notes[1].contains("not reached"), "{notes:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue: `--threshold /dev/urandom` read the file whole (24 GB before the kernel killed it).
/// Every file read has a cap; an endless one is refused once past it, naming the file.
#[cfg(unix)]
#[test]
fn threshold_file_that_never_ends_is_refused_at_its_cap() {
    let dir = scratch("threshold-endless");
    let start = Instant::now();
    let output = wrinkle(&["run", "-q", "--threshold", "/dev/zero", "--out"])
        .arg(dir.join("run"))
        .output()
        .unwrap();
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("--threshold /dev/zero"), "{text}");
    assert!(text.contains("larger than 256 MiB"), "{text}");
    assert!(start.elapsed() < Duration::from_secs(60));
    assert!(!dir.join("run").exists(), "refused before any work");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue: a symbolic-link loop as `--out` said "File exists". It is now refused before any
/// work, saying what it is.
#[cfg(unix)]
#[test]
fn symlink_loop_as_out_is_named() {
    let dir = scratch("symlink-loop");
    let (first, second) = (dir.join("loop1"), dir.join("loop2"));
    std::os::unix::fs::symlink(&second, &first).unwrap();
    std::os::unix::fs::symlink(&first, &second).unwrap();
    let output = quick_run(&first, &[]);
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("symbolic link that leads nowhere"), "{text}");
    assert!(text.contains("loop1"), "{text}");
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue: `compare --models reference-envelope,` blamed the scene's `model.name`, and
/// `--models reference-envelope,nope` ran the first model to the end before rejecting `nope`.
/// The list — empty, unknown and repeated entries — and every model's overrides are checked
/// before any work: exit 2 naming the entry, nothing written.
#[test]
fn compare_model_list_is_checked_before_any_work() {
    let dir = scratch("compare-list");
    let out = dir.join("compare");
    for (models, expected) in [
        ("reference-envelope,", "entry 2 (``) is empty"),
        ("reference-envelope,,pure-membrane", "entry 2 (``) is empty"),
        ("reference-envelope,nope", "entry 2 (`nope`): unknown model"),
        (
            "reference-envelope,pure-membrane,reference-envelope",
            "entry 3 (`reference-envelope`) repeats entry 1",
        ),
    ] {
        let start = Instant::now();
        let output = wrinkle(&["compare", "-q", "--models", models, "--out"])
            .arg(&out)
            .output()
            .unwrap();
        let text = stderr(&output);
        assert_eq!(output.status.code(), Some(2), "{models}: {text}");
        assert!(text.contains(expected), "{models}: {text}");
        assert!(!text.contains("model.name"), "{models}: {text}");
        assert!(start.elapsed() < Duration::from_secs(10), "{models}");
        assert!(!out.exists(), "{models}: nothing is written");
    }
    // An override that only the second model's scene refuses stops the comparison before the
    // first model runs.
    let output = wrinkle(&[
        "compare",
        "-q",
        "--models",
        "reference-envelope,pure-membrane",
        "--model-set",
        "pure-membrane:mesh.nx=0",
        "--out",
    ])
    .arg(&out)
    .output()
    .unwrap();
    let text = stderr(&output);
    assert_eq!(output.status.code(), Some(2), "{text}");
    assert!(text.contains("mesh.nx"), "{text}");
    assert!(!out.exists());
    // The same list check guards `bench`.
    let output = wrinkle(&[
        "bench",
        "--quick",
        "--models",
        "reference-envelope,",
        "--out",
    ])
    .arg(&out)
    .output()
    .unwrap();
    assert_eq!(output.status.code(), Some(2), "{}", stderr(&output));
    assert!(stderr(&output).contains("entry 2 (``) is empty"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// "A requested value that is dropped without a note": `load.tension_y` given to the strip
/// load, which has no tension, was ignored silently; the threshold (and so `buckle` and every
/// run) now says so in a note.
#[test]
fn tension_given_to_the_strip_is_noted() {
    let output = wrinkle(&[
        "buckle",
        "-q",
        "--json",
        "--set",
        "load.kind=strip",
        "--set",
        "model.direction=90",
        "--set",
        "load.tension_y=5",
        "--set",
        "mesh.nx=16",
        "--set",
        "mesh.ny=8",
    ])
    .output()
    .unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let threshold: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let notes = threshold["notes"].to_string();
    assert!(notes.contains("`load.tension_y` = 5 is ignored"), "{notes}");
}

/// The ANM's settings given with Riks are not used: each is named in a note.
#[test]
fn anm_settings_given_to_riks_are_noted() {
    let output = wrinkle(&[
        "buckle",
        "-q",
        "--json",
        "--set",
        "solver.method=riks",
        "--set",
        "solver.order=10",
        "--set",
        "solver.pade=false",
        "--set",
        "mesh.nx=16",
        "--set",
        "mesh.ny=8",
    ])
    .output()
    .unwrap();
    assert_eq!(output.status.code(), Some(0), "{}", stderr(&output));
    let threshold: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
    let notes = threshold["notes"].to_string();
    assert!(notes.contains("`solver.order` is ignored"), "{notes}");
    assert!(notes.contains("`solver.pade` is ignored"), "{notes}");
    assert!(!notes.contains("series_tolerance"), "{notes}");
}
