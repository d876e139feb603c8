//! Compile-fail tests of `energy_model!` diagnostics (trybuild). Only compile-fail cases live
//! here: trybuild checks them with `cargo check`, so the runtime's dependencies are type-checked,
//! never compiled to machine code, in trybuild's own target folder. Compile-pass cases are
//! ordinary integration tests (`tests/minimal_models.rs`).

#[test]
fn diagnostics_point_at_the_offending_tokens() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/*.rs");
}
