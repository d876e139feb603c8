//! Where one ANM step's time goes, on the paper's example 1 with the reference envelope model.
//!
//! `cargo run --release -p wrinkle-models --example step_profile -- NX NY ORDER`
//! (default 32 16 20). Prints the cost of each part of a step at a wrinkled state near the
//! threshold: tangent assembly, factorisation, one solve, the Taylor-mode series (whole step),
//! the generic Series path, a residual check, and the tape size.

use std::sync::Arc;
use std::time::Instant;
use wrinkle_models::ReferenceEnvelope;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::fem::{BodyLoad, DirichletCondition, EdgeTraction, Loads, Mesh};
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::Problem;
use wrinkle_runtime::solve::anm::{compute_series, compute_series_generic};
use wrinkle_runtime::solve::newton::{NewtonOptions, newton};
use wrinkle_runtime::solve::path::PathState;

fn example_one(nx: usize, ny: usize) -> Problem<ReferenceEnvelope> {
    let model = ReferenceEnvelope::new(70000.0, 0.3, 0.05, 0.235_434_6, 0.0);
    let mesh = Arc::new(Mesh::rectangle(400.0, 200.0, nx, ny, 1.0).unwrap());
    let fixed = DirichletCondition::fixed;
    let mut conditions = vec![
        fixed("centre", 0),
        fixed("centre", 1),
        fixed("right_middle", 1),
    ];
    for edge in ["left", "right", "bottom", "top"] {
        conditions.push(fixed(edge, 2));
    }
    let tractions: Vec<EdgeTraction> = [
        ("left", [1.0, 0.0], true),
        ("right", [-1.0, 0.0], true),
        ("bottom", [0.0, -10.0], false),
        ("top", [0.0, 10.0], false),
    ]
    .into_iter()
    .map(|(edge, traction, proportional)| EdgeTraction {
        edge: edge.into(),
        fields: [0, 1],
        traction,
        proportional,
    })
    .collect();
    let loads = Loads {
        tractions,
        body_loads: vec![BodyLoad {
            field: 2,
            value: 1e-7,
            proportional: false,
        }],
        ..Loads::default()
    };
    Problem::new(model, mesh, &conditions, &loads).unwrap()
}

fn time<T>(label: &str, repeat: usize, mut f: impl FnMut() -> T) -> (T, f64) {
    let start = Instant::now();
    let mut out = f();
    for _ in 1..repeat {
        out = f();
    }
    let seconds = start.elapsed().as_secs_f64() / repeat as f64;
    println!("{label:<44} {:>10.3} ms", 1e3 * seconds);
    (out, seconds)
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().expect("integer arguments"))
        .collect();
    let (nx, ny, order) = (
        *args.first().unwrap_or(&32),
        *args.get(1).unwrap_or(&16),
        *args.get(2).unwrap_or(&20),
    );
    let problem = example_one(nx, ny);
    let n = problem.free_count();
    println!(
        "example 1, {nx}×{ny} Q8, {n} dofs, order {order}, {} threads",
        rayon::current_num_threads()
    );
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut matrix = problem.new_matrix();
    let load = 0.0893;
    let equilibrium = newton(
        &problem,
        vec![0.0; n],
        load,
        &mut factor,
        &mut matrix,
        &NewtonOptions::default(),
    )
    .unwrap();
    let state = PathState {
        displacement: equilibrium.solution,
        load,
    };
    time("tangent assembly", 5, || {
        problem.tangent_into(&state.displacement, load, &mut matrix)
    });
    let (_, factorisation) = time("factorisation", 5, || factor.factorize(&matrix).unwrap());
    println!(
        "  kind {:?}, factor nnz {}",
        factor.kind(),
        factor.factor_nnz()
    );
    let rhs = vec![1.0; n];
    time("one solve", 20, || {
        let mut x = rhs.clone();
        factor.solve_in_place(&mut x).unwrap();
        x
    });
    for (name, threshold) in [
        (
            "simplicial",
            wrinkle_runtime::linear::factor::SupernodalThreshold::FORCE_SIMPLICIAL,
        ),
        (
            "supernodal",
            wrinkle_runtime::linear::factor::SupernodalThreshold::FORCE_SUPERNODAL,
        ),
    ] {
        let mut other =
            SparseFactorization::analyze_with_threshold(problem.assembler.pattern(), threshold)
                .unwrap();
        time(&format!("  factorisation, {name}"), 5, || {
            other.factorize(&matrix).unwrap()
        });
        time(&format!("  one solve, {name}"), 20, || {
            let mut x = rhs.clone();
            other.solve_in_place(&mut x).unwrap();
            x
        });
    }
    time("residual with field-balanced scale", 5, || {
        problem.residual_with_relative(&state.displacement, load)
    });
    time("Legendre–Hadamard check", 5, || {
        wrinkle_runtime::solve::ellipticity::legendre_hadamard(&problem, &state.displacement, load)
    });
    let mut tape = problem.assembler.taylor_tape(order);
    println!("  Taylor tape: {:.1} MB", tape.bytes() as f64 / 1e6);
    let (_, taylor) = time("series, Taylor mode (whole step)", 3, || {
        compute_series(&problem, &state, &factor, order, None, &mut tape).unwrap()
    });
    let (_, generic) = time("series, generic Series path (whole step)", 1, || {
        compute_series_generic(&problem, &state, &factor, order, None).unwrap()
    });
    println!(
        "series speed-up {:.1}×; Taylor series / factorisation = {:.2}",
        generic / taylor,
        taylor / factorisation
    );
    let mut tape = problem.assembler.taylor_tape(order);
    problem.taylor_start(&state.displacement, load, &mut tape);
    time("  taylor_start", 5, || {
        problem.taylor_start(&state.displacement, load, &mut tape)
    });
    // A middle order of the step (the tape holds orders up to `order`).
    let middle = (order / 2).max(1);
    time(&format!("  taylor_residual (order {middle})"), 5, || {
        problem.taylor_residual(middle, &mut tape)
    });
    let increment = vec![1e-3; n];
    time(&format!("  taylor_commit (order {middle})"), 5, || {
        problem.taylor_commit(middle, &increment, 0.0, &mut tape)
    });
    time(
        &format!(
            "  taylor_commit_then_residual (orders {middle}, {})",
            middle + 1
        ),
        5,
        || problem.taylor_commit_then_residual(middle, &increment, 0.0, &mut tape),
    );
    let _ = ReferenceEnvelope::SPEC;
}
