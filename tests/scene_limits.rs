//! Inputs a new user tried that used to run away: a series tolerance of 1e300, a mesh of
//! 10¹⁰ elements (a 320 GB allocation), a scene read from `/dev/zero`. Each is now a scene error
//! (exit 2) naming the key, before anything is allocated.

use std::process::Command;

fn wrinkle(arguments: &[&str]) -> (Option<i32>, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .output()
        .unwrap();
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

#[test]
fn series_tolerance_of_1e300_is_refused_with_its_key() {
    let (code, stderr) = wrinkle(&["run", "--set", "solver.series_tolerance=1e300"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("solver.series_tolerance"), "{stderr}");
    assert!(stderr.contains("at most"), "{stderr}");
}

#[test]
fn a_mesh_beyond_memory_is_refused_before_allocation() {
    let (code, stderr) = wrinkle(&[
        "buckle",
        "--set",
        "mesh.nx=100000",
        "--set",
        "mesh.ny=100000",
    ]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("mesh.nx") && stderr.contains("elements"),
        "{stderr}"
    );
}

#[cfg(unix)]
#[test]
fn a_scene_from_dev_zero_is_refused_after_a_bounded_read() {
    let (code, stderr) = wrinkle(&["scene", "/dev/zero"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("not a scene file"), "{stderr}");
}
