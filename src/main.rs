//! The `wrinkle` binary: see [`wrinkle::cli`].

fn main() {
    std::process::exit(wrinkle::cli::main_with_arguments(std::env::args_os()));
}
