//! Prints the code `energy_model!` generates for the model(s) declared in a Rust source file.
//!
//! ```text
//! cargo run -p wrinkle-energy --example expand -- models/src/reference_envelope.rs
//! ```
//! Every `energy_model! { … }` invocation of the file is expanded with [`wrinkle_energy::expand`]
//! (what the proc macro returns) and printed as one line of tokens, byte for byte what the
//! compiler receives; pipe it through `rustfmt --edition 2024` to read it. Two expansions of
//! the same file are byte-identical on any machine, at any load and any optimisation level of
//! the engine (`docs/dsl.md`, "Determinism"), so comparing this output compares the kernels.

use std::process::ExitCode;

fn main() -> ExitCode {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: expand <Rust file holding an `energy_model!` invocation>");
        return ExitCode::FAILURE;
    };
    let source = match std::fs::read_to_string(&path) {
        Ok(source) => source,
        Err(error) => {
            eprintln!("cannot read `{path}`: {error}");
            return ExitCode::FAILURE;
        }
    };
    let file = match syn::parse_file(&source) {
        Ok(file) => file,
        Err(error) => {
            eprintln!("`{path}` is not a Rust file: {error}");
            return ExitCode::FAILURE;
        }
    };
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
        .collect();
    if invocations.is_empty() {
        eprintln!("`{path}` holds no `energy_model!` invocation");
        return ExitCode::FAILURE;
    }
    for invocation in invocations {
        println!("{}", wrinkle_energy::expand(invocation.tokens.clone()));
    }
    ExitCode::SUCCESS
}
