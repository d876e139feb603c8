//! Prints, for every registered model, why each term's e-graph simplification stopped and its
//! sizes (the `simplification_report` the macro embeds in the model's `ModelSpec`).
//!
//! `cargo run -p wrinkle-models --example simplification_report` (add `--release` to see what a
//! release build's macro decided: the report is fixed when the model crate is compiled).

fn main() {
    for spec in wrinkle_models::catalogue() {
        println!("model `{}`:", spec.name);
        print!("{}", spec.simplification_report);
    }
}
