//! The ANM's series machinery checked against finite-difference Taylor coefficients.
//!
//! Source: THEORY.md §10 and ARCHITECTURE.md §4. Model: reference envelope (§4), example 1's
//! material (E 70000, ν 0.3, h 0.05), a 3 × 2 mesh of 400 × 200, Q = 0.235.
//! 1. Along a known quadratic curve $`U(a) = U_0 + aU_1 + a^2U_2`$, $`\lambda(a)`$ likewise, the
//!    residual $`g(a) = R(U(a),\lambda(a))`$ is a polynomial of degree 6 (the residual is cubic in
//!    $`U`$). Its coefficients from the generated kernels run on truncated series must equal those
//!    of a least-squares polynomial fit to `f64` residuals at 13 Chebyshev points (relative 1e-8).
//! 3. The Taylor-mode kernels (the ANM's production path) give the same right-hand sides as the
//!    generic kernels on truncated series, order by order on identical lower orders (relative
//!    1e-12), and the same step series (relative 1e-9 per coefficient, round-off amplified by
//!    the solves).
//! 2. The series of an ANM step satisfies $`R(U(a),\lambda(a)) = O(a^{N+1})`$: halving $`a`$
//!    divides the residual by $`\approx 2^{N+1}`$ (N = 5: 64).
//! 4. A step's series in the amplitude of a mode $`\varphi`$ is the same branch as in the pseudo
//!    arc length: its coefficients meet the parametrisation
//!    ($`\langle U_1,\varphi\rangle = \pm\langle\varphi,\varphi\rangle`$, $`\langle U_k,\varphi\rangle = 0`$),
//!    its residual is far below the path's tolerance over its range, and at equal mode
//!    amplitude the two series give the same load and displacements.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle::scene::Scene;
use wrinkle::setup::{build_problem, configure_model};
use wrinkle_models::ReferenceEnvelope;
use wrinkle_runtime::EnergyModel;
use wrinkle_runtime::linear::factor::SparseFactorization;
use wrinkle_runtime::problem::{Problem, norm};
use wrinkle_runtime::series::{Series, series_step_length};
use wrinkle_runtime::solve::anm::{
    StepOrientation, compute_series, compute_series_generic, compute_series_in_mode,
};
use wrinkle_runtime::solve::newton::{NewtonOptions, newton};
use wrinkle_runtime::solve::path::PathState;

fn problem(perturbation: f64) -> Problem<ReferenceEnvelope> {
    let mut scene = Scene::default();
    for s in ["mesh.nx=3", "mesh.ny=2", "model.wavenumber=0.235"] {
        scene.apply_override(s).unwrap();
    }
    let mut model = ReferenceEnvelope::from_parameters(&[0.0; 5]);
    configure_model(&scene, &mut model, 0.235).unwrap();
    let mut problem = build_problem(&scene, model).unwrap();
    // A small fixed load on every free dof, so that the path leaves the trivial state.
    for f in problem.loads.fixed.iter_mut() {
        *f += perturbation;
    }
    problem
}

/// Least-squares polynomial coefficients (degree `degree`) of samples on [-1, 1].
fn polynomial_fit(a: &[f64], values: &[f64], degree: usize) -> Vec<f64> {
    let m = nalgebra::DMatrix::from_fn(a.len(), degree + 1, |i, j| a[i].powi(j as i32));
    let b = nalgebra::DVector::from_column_slice(values);
    let svd = m.svd(true, true);
    svd.solve(&b, 1e-14).unwrap().iter().copied().collect()
}

#[test]
fn series_residual_matches_taylor_coefficients_along_a_quadratic_curve() {
    let problem = problem(0.0);
    let n = problem.free_count();
    let mut rng = StdRng::seed_from_u64(42);
    // Realistic sizes: displacements ~1e-2 mm, envelope ~h.
    let mut vector = |scale: f64| -> Vec<f64> {
        (0..n)
            .map(|_| scale * rng.random_range(-1.0..1.0))
            .collect()
    };
    let curve = [vector(0.05), vector(0.03), vector(0.02)];
    let load = [0.05, 0.02, -0.01];
    // Series evaluation: coefficients 0..=6 of g.
    let len = 7;
    let free: Vec<Series> = (0..n)
        .map(|i| {
            let mut s = Series::zeros(len);
            for (coefficient, vector) in s.coefficients_mut().iter_mut().zip(&curve) {
                *coefficient = vector[i];
            }
            s
        })
        .collect();
    let mut load_series = Series::zeros(len);
    load_series.coefficients_mut()[..3].copy_from_slice(&load);
    let series_residual = problem.residual(&free, load_series);
    // f64 residuals at Chebyshev points, fitted.
    let points: Vec<f64> = (0..13)
        .map(|j| ((2 * j + 1) as f64 * std::f64::consts::PI / 26.0).cos())
        .collect();
    let samples: Vec<Vec<f64>> = points
        .iter()
        .map(|&a| {
            let u: Vec<f64> = (0..n)
                .map(|i| curve[0][i] + a * curve[1][i] + a * a * curve[2][i])
                .collect();
            problem.residual(&u, load[0] + a * load[1] + a * a * load[2])
        })
        .collect();
    let mut worst: f64 = 0.0;
    for k in 0..len {
        let series_k: Vec<f64> = series_residual.iter().map(|s| s.coefficient(k)).collect();
        let fitted_k: Vec<f64> = (0..n)
            .map(|i| {
                let values: Vec<f64> = samples.iter().map(|r| r[i]).collect();
                polynomial_fit(&points, &values, 8)[k]
            })
            .collect();
        let scale = norm(
            &series_residual
                .iter()
                .map(|s| s.coefficient(0))
                .collect::<Vec<_>>(),
        );
        let diff: Vec<f64> = series_k.iter().zip(&fitted_k).map(|(a, b)| a - b).collect();
        worst = worst.max(norm(&diff) / scale);
    }
    eprintln!("worst relative difference of Taylor coefficients: {worst:e}");
    assert!(
        worst < 1e-8,
        "series residual vs fitted Taylor coefficients: {worst:e}"
    );
}

#[test]
fn anm_series_residual_is_of_order_n_plus_one() {
    let problem = problem(2e-9);
    let n = problem.free_count();
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut matrix = problem.new_matrix();
    let load = 0.08;
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
    problem.tangent_into(&state.displacement, load, &mut matrix);
    factor.factorize(&matrix).unwrap();
    let order = 5;
    let mut tape = problem.assembler.taylor_tape(order);
    let (series, _) = compute_series(&problem, &state, &factor, order, None, &mut tape).unwrap();
    // Find a with residual well above round-off, then halve it.
    let residual_at = |a: f64| {
        let (u, l) = series.evaluate(a);
        norm(&problem.residual(&u, l))
    };
    let mut a = 1e-2;
    while residual_at(a) > 1e-6 * problem.residual_scale(load) {
        a *= 0.5;
    }
    let ratio = residual_at(a) / residual_at(0.5 * a);
    eprintln!("a = {a:e}, residual ratio on halving = {ratio}");
    assert!(
        (40.0..100.0).contains(&ratio),
        "expected ≈ 2^(N+1) = 64, got {ratio}"
    );
}

/// A state near the threshold with a visible envelope (the perturbed path at λ = 0.088).
fn wrinkled_state(problem: &Problem<ReferenceEnvelope>) -> (PathState, SparseFactorization) {
    let n = problem.free_count();
    let mut factor = SparseFactorization::analyze(problem.assembler.pattern()).unwrap();
    let mut matrix = problem.new_matrix();
    let load = 0.088;
    let equilibrium = newton(
        problem,
        vec![0.0; n],
        load,
        &mut factor,
        &mut matrix,
        &NewtonOptions::default(),
    )
    .unwrap();
    problem.tangent_into(&equilibrium.solution, load, &mut matrix);
    factor.factorize(&matrix).unwrap();
    (
        PathState {
            displacement: equilibrium.solution,
            load,
        },
        factor,
    )
}

#[test]
fn taylor_mode_right_hand_sides_equal_the_generic_series_path() {
    let problem = problem(1e-3);
    let (state, factor) = wrinkled_state(&problem);
    let order = 20;
    let mut tape = problem.assembler.taylor_tape(order);
    let (series, _) = compute_series(&problem, &state, &factor, order, None, &mut tape).unwrap();
    // Replay: on the Taylor path's own coefficients, each order's right-hand side both ways.
    let n = problem.free_count();
    problem.taylor_start(&state.displacement, state.load, &mut tape);
    let mut worst: f64 = 0.0;
    for k in 1..=order {
        let taylor = problem.taylor_residual(k, &mut tape);
        let mut free = vec![Series::zeros(k + 1); n];
        for (i, s) in free.iter_mut().enumerate() {
            for (c, u) in s
                .coefficients_mut()
                .iter_mut()
                .zip(&series.displacement[..k])
            {
                *c = u[i];
            }
        }
        let mut load = Series::zeros(k + 1);
        load.coefficients_mut()[..k].copy_from_slice(&series.load[..k]);
        let generic: Vec<f64> = problem
            .residual(&free, load)
            .iter()
            .map(|r| r.coefficient(k))
            .collect();
        let scale = norm(&generic).max(1e-300);
        let difference: f64 = taylor
            .iter()
            .zip(&generic)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt();
        if k >= 2 {
            worst = worst.max(difference / scale);
        }
        problem.taylor_commit(k, &series.displacement[k], series.load[k], &mut tape);
    }
    eprintln!("worst relative difference of right-hand sides: {worst:e}");
    assert!(worst < 1e-12, "Taylor mode vs generic series: {worst:e}");
    // The step series themselves.
    let (generic, _) = compute_series_generic(&problem, &state, &factor, order, None).unwrap();
    let mut worst_series: f64 = 0.0;
    for k in 1..=order {
        let scale = norm(&series.displacement[k]) + series.load[k].abs();
        let difference = norm(
            &series.displacement[k]
                .iter()
                .zip(&generic.displacement[k])
                .map(|(a, b)| a - b)
                .collect::<Vec<_>>(),
        ) + (series.load[k] - generic.load[k]).abs();
        worst_series = worst_series.max(difference / scale);
    }
    eprintln!("worst relative difference of step coefficients: {worst_series:e}");
    assert!(worst_series < 1e-9, "step series differ: {worst_series:e}");
}

#[test]
fn series_in_a_mode_amplitude_is_the_arc_length_branch_reparametrised() {
    let problem = problem(1e-3);
    let (state, factor) = wrinkled_state(&problem);
    let n = problem.free_count();
    let order = 20;
    let mut tape = problem.assembler.taylor_tape(order);
    let (arc, u_hat) = compute_series(&problem, &state, &factor, order, None, &mut tape).unwrap();
    // A mode with a part along the load tangent and a part across it.
    let mut rng = StdRng::seed_from_u64(7);
    let scale = norm(&u_hat) / (n as f64).sqrt();
    let mode: Vec<f64> = u_hat
        .iter()
        .map(|u| u + 0.5 * scale * rng.random_range(-1.0..1.0))
        .collect();
    let orientation = StepOrientation {
        previous_direction: None,
        mode: Some(&mode),
    };
    let (by_mode, _, used) =
        compute_series_in_mode(&problem, &state, &factor, order, orientation, &mut tape).unwrap();
    assert!(used, "the load tangent has a part along the mode");
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let mode_norm2 = dot(&mode, &mode);
    // 1. The parametrisation: a is the change of the mode's amplitude.
    let u = &by_mode.displacement;
    assert!(
        (dot(&u[1], &mode).abs() - mode_norm2).abs() <= 1e-10 * mode_norm2,
        "<U_1, φ> = {}, |φ|² = {mode_norm2}",
        dot(&u[1], &mode)
    );
    for (k, u_k) in u.iter().enumerate().skip(2) {
        let projection = dot(u_k, &mode) / (norm(u_k) * mode_norm2.sqrt());
        assert!(
            projection.abs() <= 1e-10,
            "order {k}: cosine {projection:e}"
        );
    }
    // 2. The series solves the equations over its range: at half of it the relative residual is
    // far below the path's tolerance (1e-6), and it grows past the range.
    let residual_at = |a: f64| {
        let (u, l) = by_mode.evaluate(a);
        norm(&problem.residual(&u, l)) / problem.residual_scale(state.load)
    };
    let a = 0.5 * series_step_length(&by_mode, 1e-7);
    eprintln!(
        "mode series: range {:e}, residual at half of it {:e}, at four times it {:e}",
        2.0 * a,
        residual_at(a),
        residual_at(8.0 * a)
    );
    assert!(residual_at(a) <= 1e-9, "residual {:e}", residual_at(a));
    assert!(
        residual_at(8.0 * a) > 1e-6,
        "the series' range is not where its accuracy ends"
    );
    // 3. The same branch: at the arc-length parameter b of equal mode amplitude (bisection on
    // the arc series, whose amplitude is monotone there) the two series agree.
    let amplitude = |b: f64| {
        let (u, _) = arc.evaluate(b);
        let change: Vec<f64> = u
            .iter()
            .zip(&state.displacement)
            .map(|(x, y)| x - y)
            .collect();
        dot(&change, &mode) / mode_norm2
    };
    let sign = dot(&u[1], &mode).signum() * dot(&arc.displacement[1], &mode).signum();
    let target = sign * a;
    let range = series_step_length(&arc, 1e-7);
    let (mut low, mut high) = if target > 0.0 {
        (0.0, range)
    } else {
        (-range, 0.0)
    };
    assert!(
        (amplitude(low) - target) * (amplitude(high) - target) <= 0.0,
        "amplitude {target:e} outside the arc series' range {range:e}"
    );
    for _ in 0..200 {
        let mid = 0.5 * (low + high);
        if (amplitude(low) - target) * (amplitude(mid) - target) <= 0.0 {
            high = mid;
        } else {
            low = mid;
        }
    }
    let b = 0.5 * (low + high);
    let (u_mode, load_mode) = by_mode.evaluate(a);
    let (u_arc, load_arc) = arc.evaluate(b);
    assert!(
        (load_mode - load_arc).abs() <= 1e-9 * state.load,
        "λ in the mode's amplitude {load_mode}, in the arc length {load_arc}"
    );
    let difference: Vec<f64> = u_mode.iter().zip(&u_arc).map(|(x, y)| x - y).collect();
    let moved: Vec<f64> = u_arc
        .iter()
        .zip(&state.displacement)
        .map(|(x, y)| x - y)
        .collect();
    assert!(
        norm(&difference) <= 1e-7 * norm(&moved),
        "displacements differ by {:e} of the step's {:e}",
        norm(&difference),
        norm(&moved)
    );
}
