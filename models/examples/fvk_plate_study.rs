//! Measurements behind the `fvk-plate` model: Kirchhoff-limit accuracy of the shear
//! integration, spurious zero-energy modes, and linear buckling of the paper's example 1.
//!
//! ```text
//! cargo run -p wrinkle-models --release --example fvk_plate_study -- kirchhoff [variant]
//! cargo run -p wrinkle-models --release --example fvk_plate_study -- spectrum
//! cargo run -p wrinkle-models --release --example fvk_plate_study -- newton-floor NX NY GX GY
//! cargo run -p wrinkle-models --release --example fvk_plate_study -- timing NX NY GX GY
//! cargo run -p wrinkle-models --release --example fvk_plate_study -- report
//! cargo run -p wrinkle-models --release --example fvk_plate_study -- buckling VARIANT NX NY GX GY [...]
//! ```
//!
//! `variant` is `reduced` (the registered model: shear with 2×2 Gauss), `full` (3×3), or
//! `lsv-reduced:ALPHA` / `lsv-full:ALPHA` (Lyly–Stenberg–Vihinen stabilised shear with
//! coefficient `h²/(h² + α h_e²)`). `buckling` takes groups of four numbers: elements along X
//! and Y, and the gradings along X and Y (largest/smallest element size).

#[path = "../tests/fvk_plate_support/mod.rs"]
mod support;

use std::time::Instant;
use support::*;
use wrinkle_runtime::EnergyModel;

const RATIOS: [f64; 3] = [100.0, 1000.0, 10000.0];
/// Mesh sizes of the Kirchhoff tables (override with `FVK_MESHES="4 8 16"`).
fn meshes() -> Vec<usize> {
    std::env::var("FVK_MESHES").map_or(vec![2, 4, 6, 8, 12, 16, 24, 32], |list| {
        list.split_whitespace()
            .map(|n| n.parse().unwrap())
            .collect()
    })
}

fn kirchhoff_table<M: EnergyModel>(label: &str, make: impl Fn(f64, usize) -> M) {
    println!("## {label}");
    println!("support | L/h | n | w_c D/(qL^4) | error % | factorisation");
    for (support, reference) in [
        (Support::Clamped, CLAMPED_CENTRE),
        (Support::SimplySupported, SIMPLY_SUPPORTED_CENTRE),
    ] {
        for ratio in RATIOS {
            for n in meshes() {
                let (w, kind) = centre_deflection(make(1.0 / ratio, n), n, support);
                println!(
                    "{support:?} | {ratio:.0} | {n} | {w:.8} | {:+.4} | {kind:?}",
                    100.0 * (w / reference - 1.0)
                );
            }
        }
    }
}

fn kirchhoff(variant: &str) {
    match variant.split_once(':') {
        None if variant == "reduced" => {
            kirchhoff_table(variant, |h, _| plate(h));
        }
        None if variant == "full" => {
            kirchhoff_table(variant, |h, _| model::<FvkPlateFullShear>(h, &[]));
        }
        Some(("lsv-reduced", alpha)) => {
            let alpha: f64 = alpha.parse().unwrap();
            kirchhoff_table(variant, |h, n| {
                model::<FvkPlateStabilisedReduced>(
                    h,
                    &[
                        ("element_size", 2f64.sqrt() / n as f64),
                        ("stabilisation", alpha),
                    ],
                )
            });
        }
        Some(("lsv-full", alpha)) => {
            let alpha: f64 = alpha.parse().unwrap();
            kirchhoff_table(variant, |h, n| {
                model::<FvkPlateStabilisedFull>(
                    h,
                    &[
                        ("element_size", 2f64.sqrt() / n as f64),
                        ("stabilisation", alpha),
                    ],
                )
            });
        }
        _ => panic!("unknown variant {variant}"),
    }
}

fn count_below(values: &[f64], threshold: f64) -> usize {
    values.iter().filter(|v| v.abs() < threshold).count()
}

fn spectrum_of<M: EnergyModel>(label: &str, make: impl Fn(f64) -> M) {
    for ratio in [10.0, 1000.0] {
        for n in [1, 2, 4] {
            let problem = free_square_plate(make(1.0 / ratio), n);
            let values = scaled_spectrum(&problem, &vec![0.0; problem.free_count()], 0.0);
            let largest = values[values.len() - 1];
            let zero = count_below(&values, 1e-10 * largest);
            let next = values[zero];
            println!(
                "{label} | free | L/h {ratio:.0} | {n}x{n} | dofs {} | zero eigenvalues {zero} | \
                 smallest {:.3e} | first non-zero / largest {:.3e}",
                values.len(),
                values[0].abs() / largest,
                next / largest
            );
        }
    }
    for support in [Support::Clamped, Support::SimplySupported] {
        for ratio in RATIOS {
            for n in [2, 4, 8] {
                let problem = square_plate(make(1.0 / ratio), n, support, 1.0);
                let values = scaled_spectrum(&problem, &vec![0.0; problem.free_count()], 0.0);
                let largest = values[values.len() - 1];
                println!(
                    "{label} | {support:?} | L/h {ratio:.0} | {n}x{n} | dofs {} | λ_min/λ_max {:.3e} | \
                     below 1e-10: {}",
                    values.len(),
                    values[0] / largest,
                    count_below(&values, 1e-10 * largest)
                );
            }
        }
    }
}

/// Spurious-mode probes of example 1's pre-buckling tangent $`A = K_t(U_0, 0)`$: dense
/// spectrum on small meshes, inverse iteration on a production mesh.
fn buckling_spectrum() {
    use wrinkle_runtime::linear::factor::SparseFactorization;
    use wrinkle_runtime::solve::newton::{NewtonOptions, newton};
    let prebuckling = |problem: &wrinkle_runtime::problem::Problem<wrinkle_models::FvkPlate>| {
        let n = problem.free_count();
        let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
        let mut a = problem.new_matrix();
        let options = NewtonOptions {
            tolerance: 1e-6,
            ..NewtonOptions::default()
        };
        let pre = newton(problem, vec![0.0; n], 0.0, &mut factor, &mut a, &options).unwrap();
        problem.tangent_into(&pre.solution, 0.0, &mut a);
        let kind = factor.factorize(&a).unwrap();
        (pre.solution, kind)
    };
    for (nx, ny, gy) in [(8, 4, 1.0), (16, 6, 10.0), (24, 8, 10.0)] {
        let problem = example1(
            plate(EXAMPLE1_THICKNESS),
            rectangle(EXAMPLE1_LX, EXAMPLE1_LY, nx, ny, 1.0, gy),
        );
        let (state, kind) = prebuckling(&problem);
        let values = scaled_spectrum(&problem, &state, 0.0);
        let largest = values[values.len() - 1];
        println!(
            "example 1 | {nx}x{ny} grading Y {gy} | dofs {} | {kind:?} | λ_min/λ_max {:.3e} | \
             below 1e-10: {} | five smallest / λ_max {:?}",
            values.len(),
            values[0] / largest,
            count_below(&values, 1e-10 * largest),
            values[..5]
                .iter()
                .map(|v| format!("{:.2e}", v / largest))
                .collect::<Vec<_>>()
        );
    }
    // Prestressed by N_Y only, the lowest mode is nearly a string in Y:
    // μ₁ ≈ N_Y π²/L_Y² (plus bending and the clamped layers).
    let string = EXAMPLE1_TENSION * (std::f64::consts::PI / EXAMPLE1_LY).powi(2);
    for (nx, ny, gy) in [(24, 8, 10.0), (160, 30, 10.0)] {
        let mesh = rectangle(EXAMPLE1_LX, EXAMPLE1_LY, nx, ny, 1.0, gy);
        let problem = example1(plate(EXAMPLE1_THICKNESS), mesh.clone());
        let mass = example1(model::<PlateMass>(EXAMPLE1_THICKNESS, &[]), mesh);
        let (state, kind) = prebuckling(&problem);
        let (mu, change) = lowest_mass_eigenvalue(&problem, &mass, &state, 0.0, 60);
        println!(
            "example 1 | {nx}x{ny} grading Y {gy} | dofs {} | {kind:?} | μ₁ {mu:.5e} \
             (string N_Y π²/L_Y² {string:.5e}, ratio {:.4}, last change {change:.1e})",
            problem.free_count(),
            mu / string
        );
    }
}

fn spectrum() {
    spectrum_of("reduced", plate);
    spectrum_of("full", |h| model::<FvkPlateFullShear>(h, &[]));
    // Lowest eigenvalue of K φ = μ M φ (M: deflection mass) against the Kirchhoff plate's:
    // μ₁ L⁴/D = 35.985² (clamped, Leissa) and (2π²)² (simply supported).
    for (support, reference) in [
        (Support::Clamped, 35.985f64.powi(2)),
        (
            Support::SimplySupported,
            (2.0 * std::f64::consts::PI.powi(2)).powi(2),
        ),
    ] {
        for ratio in RATIOS {
            for n in [8, 16, 32, 48] {
                let h = 1.0 / ratio;
                let problem = square_plate(plate(h), n, support, 1.0);
                let mass = square_plate(model::<PlateMass>(h, &[]), n, support, 1.0);
                let zero = vec![0.0; problem.free_count()];
                let (mu, change) = lowest_mass_eigenvalue(&problem, &mass, &zero, 0.0, 60);
                let scaled = mu / bending_stiffness(h);
                println!(
                    "reduced | {support:?} | L/h {ratio:.0} | {n}x{n} | μ₁ L⁴/D {scaled:.3} \
                     (Kirchhoff {reference:.1}, ratio {:.4}, last change {change:.1e})",
                    scaled / reference
                );
            }
        }
    }
    buckling_spectrum();
}

fn buckling_row<M: EnergyModel>(model: M, nx: usize, ny: usize, gx: f64, gy: f64) {
    let start = Instant::now();
    let mesh = rectangle(EXAMPLE1_LX, EXAMPLE1_LY, nx, ny, gx, gy);
    let problem = example1(model, mesh);
    let result = buckle(&problem);
    let elapsed = start.elapsed().as_secs_f64();
    let profile = profile_along_x(&problem, &result.modes[0], 0.5 * EXAMPLE1_LY);
    let crossings = zero_crossings(&profile);
    let length = wavelength(&crossings, 0.25 * EXAMPLE1_LX, 0.75 * EXAMPLE1_LX);
    println!(
        "{nx} | {ny} | {gx} | {gy} | {} | {:.7} | {} | {:.4} | {:.1e} | {} | {elapsed:.2}",
        problem.free_count(),
        result.critical_loads[0],
        crossings.len() + 1,
        length,
        result.residuals[0],
        result.eigen_iterations,
    );
}

fn buckling(variant: &str, arguments: &[String]) {
    println!("## {variant}");
    println!(
        "nx | ny | grading X | grading Y | free dofs | λ_c | half-waves | wavelength (mm) | \
         eigen residual | A⁻¹B applications | time (s)"
    );
    for group in arguments.chunks(4) {
        let nx: usize = group[0].parse().unwrap();
        let ny: usize = group[1].parse().unwrap();
        let gx: f64 = group[2].parse().unwrap();
        let gy: f64 = group[3].parse().unwrap();
        let h = EXAMPLE1_THICKNESS;
        // Element diameter of a uniform mesh (the stabilised variants assume gx = gy = 1).
        let size = ((EXAMPLE1_LX / nx as f64).powi(2) + (EXAMPLE1_LY / ny as f64).powi(2)).sqrt();
        match variant.split_once(':') {
            None if variant == "reduced" => buckling_row(plate(h), nx, ny, gx, gy),
            None if variant == "full" => {
                buckling_row(model::<FvkPlateFullShear>(h, &[]), nx, ny, gx, gy)
            }
            Some(("lsv-reduced", alpha)) => {
                let extra = [
                    ("element_size", size),
                    ("stabilisation", alpha.parse().unwrap()),
                ];
                buckling_row(
                    model::<FvkPlateStabilisedReduced>(h, &extra),
                    nx,
                    ny,
                    gx,
                    gy,
                )
            }
            Some(("lsv-full", alpha)) => {
                let extra = [
                    ("element_size", size),
                    ("stabilisation", alpha.parse().unwrap()),
                ];
                buckling_row(model::<FvkPlateStabilisedFull>(h, &extra), nx, ny, gx, gy)
            }
            _ => panic!("unknown variant {variant}"),
        }
    }
}

/// Pre-buckling Newton at λ = 0 iteration by iteration: relative residual and the per-field
/// residual norms (a round-off floor shows as a residual that stops decreasing).
fn newton_floor(arguments: &[String]) {
    use wrinkle_runtime::linear::factor::SparseFactorization;
    let (nx, ny): (usize, usize) = (arguments[0].parse().unwrap(), arguments[1].parse().unwrap());
    let (gx, gy): (f64, f64) = (arguments[2].parse().unwrap(), arguments[3].parse().unwrap());
    let mesh = rectangle(EXAMPLE1_LX, EXAMPLE1_LY, nx, ny, gx, gy);
    let problem = example1(plate(EXAMPLE1_THICKNESS), mesh);
    let n = problem.free_count();
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut matrix = problem.new_matrix();
    let mut u = vec![0.0; n];
    for iteration in 0..4 {
        let (residual, relative) = problem.residual_with_relative(&u, 0.0);
        let mut per_field = [0.0f64; 5];
        for (i, r) in residual.iter().enumerate() {
            per_field[problem.dofs().global_of_free(i) % 5] += r * r;
        }
        let per_field: Vec<String> = per_field
            .iter()
            .map(|v| format!("{:.2e}", v.sqrt()))
            .collect();
        println!("iteration {iteration}: relative {relative:.3e}, |R| per field {per_field:?}");
        problem.tangent_into(&u, 0.0, &mut matrix);
        let kind = factor.factorize(&matrix).unwrap();
        let mut step: Vec<f64> = residual.iter().map(|r| -r).collect();
        factor.solve_in_place(&mut step).unwrap();
        u.iter_mut().zip(&step).for_each(|(a, b)| *a += b);
        if iteration == 0 {
            println!(
                "factorisation {kind:?}, max |u| {:.3e}",
                u.iter().fold(0.0f64, |m, v| m.max(v.abs()))
            );
        }
    }
}

/// Process CPU time (user + system, all threads) in seconds, from `/proc/self/stat` (Linux);
/// on a shared machine it is steadier than the wall clock.
fn cpu_seconds() -> f64 {
    let stat = std::fs::read_to_string("/proc/self/stat").unwrap_or_default();
    let after_name = stat.rsplit_once(')').map_or("", |(_, rest)| rest);
    let fields: Vec<&str> = after_name.split_whitespace().collect();
    let ticks = |i: usize| {
        fields
            .get(i)
            .and_then(|v| v.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    // Fields 14 and 15 of stat (utime, stime) are 11 and 12 after the name; 100 ticks/s.
    (ticks(11) + ticks(12)) / 100.0
}

/// Wall-clock and CPU time of each phase of one linear-buckling solve of example 1.
fn timing(arguments: &[String]) {
    use wrinkle_runtime::linear::factor::SparseFactorization;
    use wrinkle_runtime::solve::buckling::LinearBucklingOptions;
    use wrinkle_runtime::solve::newton::{NewtonOptions, newton};
    let (nx, ny): (usize, usize) = (arguments[0].parse().unwrap(), arguments[1].parse().unwrap());
    let (gx, gy): (f64, f64) = (arguments[2].parse().unwrap(), arguments[3].parse().unwrap());
    let mut clock = (Instant::now(), cpu_seconds());
    let mut lap = |what: &str| {
        let now = (Instant::now(), cpu_seconds());
        println!(
            "{what}: wall {:.3} s, cpu {:.2} s",
            (now.0 - clock.0).as_secs_f64(),
            now.1 - clock.1
        );
        clock = now;
    };
    let total = (Instant::now(), cpu_seconds());
    let mesh = rectangle(EXAMPLE1_LX, EXAMPLE1_LY, nx, ny, gx, gy);
    let problem = example1(plate(EXAMPLE1_THICKNESS), mesh);
    let n = problem.free_count();
    lap(&format!("mesh, dofs, pattern ({n} free dofs)"));
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    lap(&format!(
        "symbolic analysis (factor nnz {})",
        factor.factor_nnz()
    ));
    let mut a = problem.new_matrix();
    let options = NewtonOptions {
        tolerance: 1e-6,
        ..NewtonOptions::default()
    };
    let pre = newton(&problem, vec![0.0; n], 0.0, &mut factor, &mut a, &options).unwrap();
    lap(&format!(
        "pre-buckling Newton ({} iterations)",
        pre.iterations
    ));
    problem.tangent_into(&pre.solution, 0.0, &mut a);
    lap("one tangent assembly (f64)");
    factor.factorize(&a).unwrap();
    lap("one numeric factorisation");
    let mut rate = problem.load_derivative(&pre.solution, 0.0);
    factor.solve_in_place(&mut rate).unwrap();
    lap("load derivative (dual residual) + one solve");
    let mut b = problem.new_matrix();
    problem.tangent_derivative_into(&pre.solution, 0.0, &rate, 1.0, &mut b);
    lap("geometric stiffness (dual tangent)");
    let mut buckling_options = LinearBucklingOptions::default();
    buckling_options.newton.tolerance = 1e-6;
    if let Ok(tolerance) = std::env::var("FVK_EIGEN_TOLERANCE") {
        buckling_options.eigen.tolerance = tolerance.parse().unwrap();
    }
    let result =
        wrinkle_runtime::solve::buckling::linear_buckling(&problem, &mut factor, &buckling_options)
            .unwrap();
    lap(&format!(
        "whole linear_buckling (λ_c {:.7}, {} A⁻¹B applications)",
        result.critical_loads[0], result.eigen_iterations
    ));
    println!(
        "total: wall {:.2} s, cpu {:.2} s",
        total.0.elapsed().as_secs_f64(),
        cpu_seconds() - total.1
    );
}

fn main() {
    let arguments: Vec<String> = std::env::args().skip(1).collect();
    match arguments.first().map(String::as_str) {
        Some("kirchhoff") => {
            kirchhoff(arguments.get(1).map_or("reduced", String::as_str));
        }
        Some("spectrum") => spectrum(),
        Some("newton-floor") => newton_floor(&arguments[1..]),
        Some("timing") => timing(&arguments[1..]),
        Some("report") => println!("{}", wrinkle_models::FvkPlate::SPEC.simplification_report),
        Some("buckling") => buckling(&arguments[1], &arguments[2..]),
        _ => eprintln!(
            "usage: fvk_plate_study kirchhoff [variant] | spectrum | buckling VARIANT NX NY GX GY ... | \
             newton-floor NX NY GX GY | timing NX NY GX GY | report"
        ),
    }
}
