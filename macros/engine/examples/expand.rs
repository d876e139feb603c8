//! Prints the code `energy_model!` generates for the model(s) declared in a Rust source file.
//!
//! ```text
//! cargo run -p wrinkle-energy --example expand -- models/src/reference_envelope.rs [more.rs …]
//! ```
//! Every `energy_model! { … }` invocation of the files is expanded, in order and in one
//! process as the compiler does for one crate, with [`wrinkle_energy::expand`] (what the proc
//! macro returns), and the returned tokens are printed on one line; pipe them through
//! `rustfmt --edition 2024` to read them. Two expansions of the same file are byte-identical on
//! any machine, at any load and any optimisation level of the engine (`docs/dsl.md`,
//! "Determinism"), so comparing this output compares the kernels.

use std::process::ExitCode;

fn main() -> ExitCode {
    let paths: Vec<String> = std::env::args().skip(1).collect();
    if paths.is_empty() {
        eprintln!("usage: expand <Rust file holding an `energy_model!` invocation> …");
        return ExitCode::FAILURE;
    }
    for path in &paths {
        match invocations(path) {
            Ok(invocations) => {
                for tokens in invocations {
                    println!("{}", wrinkle_energy::expand(tokens));
                }
            }
            Err(message) => {
                eprintln!("{message}");
                return ExitCode::FAILURE;
            }
        }
    }
    ExitCode::SUCCESS
}

/// The tokens inside every `energy_model! { … }` invocation at the top level of `path`.
fn invocations(path: &str) -> Result<Vec<proc_macro2::TokenStream>, String> {
    let source =
        std::fs::read_to_string(path).map_err(|error| format!("cannot read `{path}`: {error}"))?;
    let file = syn::parse_file(&source)
        .map_err(|error| format!("`{path}` is not a Rust file: {error}"))?;
    let invocations: Vec<_> = file
        .items
        .iter()
        .filter_map(|item| match item {
            syn::Item::Macro(item) => Some(&item.mac),
            _ => None,
        })
        .filter(|mac| {
            mac.path
                .segments
                .last()
                .is_some_and(|segment| segment.ident == "energy_model")
        })
        .map(|mac| mac.tokens.clone())
        .collect();
    if invocations.is_empty() {
        return Err(format!("`{path}` holds no `energy_model!` invocation"));
    }
    Ok(invocations)
}
