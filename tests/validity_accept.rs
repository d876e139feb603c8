//! A result outside the model's validity exits 4 with the check named, unless the scene accepts
//! that check (`validity.accept`); errors about a key set by `--set` name the override.

use std::process::Command;

fn wrinkle(arguments: &[&str]) -> (Option<i32>, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(arguments)
        .output()
        .unwrap();
    (
        output.status.code(),
        String::from_utf8_lossy(&output.stdout).into_owned(),
        String::from_utf8_lossy(&output.stderr).into_owned(),
    )
}

/// Q = 0.05/mm on example 1: a 126 mm wavelength on a 200 mm side, not elliptic anywhere.
#[test]
fn a_fixed_wavenumber_outside_the_model_exits_4_naming_the_checks() {
    let (code, stdout, stderr) = wrinkle(&["buckle", "-q", "--set", "model.wavenumber=0.05"]);
    assert_eq!(code, Some(4), "{stderr}");
    assert!(stdout.contains("warning (scale_separation)"), "{stdout}");
    assert!(stdout.contains("warning (ellipticity)"), "{stdout}");
    assert!(stderr.contains("outside the model's validity"), "{stderr}");
    assert!(stderr.contains("validity.accept"), "{stderr}");
}

#[test]
fn validity_accept_turns_the_warnings_into_notes_and_exits_0() {
    let (code, stdout, stderr) = wrinkle(&[
        "buckle",
        "-q",
        "--set",
        "model.wavenumber=0.05",
        "--set",
        r#"validity.accept=["scale_separation", "ellipticity"]"#,
    ]);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        stdout.contains("note (ellipticity, accepted by validity.accept)"),
        "{stdout}"
    );
    // Accepting one check leaves the other in force.
    let (code, _, stderr) = wrinkle(&[
        "buckle",
        "-q",
        "--set",
        "model.wavenumber=0.05",
        "--set",
        "validity.accept=scale_separation",
    ]);
    assert_eq!(code, Some(4), "{stderr}");
    assert!(stderr.contains("ellipticity"), "{stderr}");
}

#[test]
fn an_unknown_check_name_is_a_scene_error() {
    let (code, _, stderr) = wrinkle(&["buckle", "--set", r#"validity.accept=["bogus"]"#]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(stderr.contains("key `validity.accept`"), "{stderr}");
    assert!(stderr.contains("\"ellipticity\""), "{stderr}");
}

#[test]
fn an_unknown_model_set_by_an_override_names_the_override() {
    let (code, _, stderr) = wrinkle(&["buckle", "--set", "model.name=foo"]);
    assert_eq!(code, Some(2), "{stderr}");
    assert!(
        stderr.contains("--set model.name=foo: key `model.name`"),
        "{stderr}"
    );
    assert!(!stderr.contains("built-in default scene"), "{stderr}");
}
