//! Compile-fail tests of `energy_model!` diagnostics (trybuild). Only compile-fail cases live
//! here: trybuild checks them with `cargo check`, so the runtime's dependencies are type-checked,
//! never compiled to machine code, in trybuild's own target folder. Compile-pass cases are
//! ordinary integration tests (`tests/minimal_models.rs`).
//!
//! Every case's `main` uses its model (`from_parameters`, `energy`, `SPEC`) as an application
//! would, so each `.stderr` shows that a declaration error adds no error at the uses: the
//! macro emits a stand-in for the model beside its errors.

#[test]
fn diagnostics_point_at_the_offending_tokens() {
    let cases = trybuild::TestCases::new();
    cases.compile_fail("tests/ui/*.rs");
}
