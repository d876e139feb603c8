//! Compile-fail and compile-pass tests of `energy_model!` diagnostics (trybuild).

#[test]
fn diagnostics_point_at_the_offending_tokens() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/*.rs");
    cases.pass("tests/ui_pass/*.rs");
}
