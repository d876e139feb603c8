//! Prints the simplification report and the generated code of the reference envelope model.
fn main() {
    let tokens: proc_macro2::TokenStream = std::fs::read_to_string(std::env::args().nth(1).expect("path"))
        .expect("readable")
        .parse()
        .expect("tokens");
    let compiled = wrinkle_energy::analyze(tokens.clone(), &Default::default()).expect("compiles");
    println!("{}", compiled.report);
    println!("{}", wrinkle_energy::expand(tokens));
}
