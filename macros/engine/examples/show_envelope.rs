//! Prints the simplification report and the generated Rust code of a model declaration.
//!
//! ```text
//! cargo run -p wrinkle-energy --example show_envelope -- model.txt
//! ```
//! where `model.txt` holds the body of an `energy_model!` invocation.

use std::process::ExitCode;

fn main() -> ExitCode {
    let Some(path) = std::env::args().nth(1) else {
        eprintln!("usage: show_envelope <file holding a model declaration>");
        return ExitCode::FAILURE;
    };
    let text = match std::fs::read_to_string(&path) {
        Ok(text) => text,
        Err(error) => {
            eprintln!("cannot read `{path}`: {error}");
            return ExitCode::FAILURE;
        }
    };
    let tokens: proc_macro2::TokenStream = match text.parse() {
        Ok(tokens) => tokens,
        Err(error) => {
            eprintln!("`{path}` is not a Rust token stream: {error}");
            return ExitCode::FAILURE;
        }
    };
    match wrinkle_energy::analyze(tokens.clone(), &Default::default()) {
        Ok(compiled) => {
            println!("{}", compiled.report);
            println!("{}", wrinkle_energy::expand(tokens));
            ExitCode::SUCCESS
        }
        Err(errors) => {
            for error in errors {
                eprintln!("{path}: error: {error}");
            }
            ExitCode::FAILURE
        }
    }
}
