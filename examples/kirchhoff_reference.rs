//! Kirchhoff-plate reference for the linear buckling of a clamped rectangle (independent of the
//! project's finite elements): `tests/support/kirchhoff_spectral.rs`.
//!
//! ```text
//! cargo run --release --example kirchhoff_reference -- [LX LY H E NU T DEGREE_X DEGREE_Y]
//! ```
//! Defaults: the paper's example 1 (400 200 0.05 70000 0.3 10) at degrees 120 × 80.

#[path = "../tests/support/kirchhoff_spectral.rs"]
mod kirchhoff_spectral;

use kirchhoff_spectral::clamped_rectangle_buckling;
use std::time::Instant;

fn main() {
    let defaults = ["400", "200", "0.05", "70000", "0.3", "10", "120", "80"];
    let args: Vec<String> = std::env::args().skip(1).collect();
    let arg = |i: usize| args.get(i).map(String::as_str).unwrap_or(defaults[i]);
    let number = |i: usize| arg(i).parse::<f64>().expect("a number");
    let degree = |i: usize| arg(i).parse::<usize>().expect("a degree");
    let start = Instant::now();
    let result = clamped_rectangle_buckling(
        number(0),
        number(1),
        number(2),
        number(3),
        number(4),
        number(5),
        degree(6),
        degree(7),
    );
    let seconds = start.elapsed().as_secs_f64();
    println!("degrees {} x {}: {seconds:.2} s", degree(6), degree(7));
    for (symmetry, load) in &result.class_loads {
        println!("  class {symmetry}: lambda = {load:.12e}");
    }
    let critical = &result.critical;
    println!(
        "critical: lambda_c = {:.12e} ({}); on the line Y = {}: {} half-waves, wavelength {:?} mm",
        result.critical_load,
        result.symmetry,
        result.line_y,
        result.half_waves_midline,
        result.wavelength
    );
    println!(
        "  {} unknowns, {} Lanczos steps, residual {:.1e}, Rayleigh quotient {:.12e}, Gaussian term / bending {:.1e}",
        critical.unknowns,
        critical.lanczos_steps,
        critical.relative_residual,
        critical.rayleigh_quotient,
        critical.gaussian_ratio
    );
}
