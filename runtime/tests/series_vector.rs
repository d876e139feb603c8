//! Vector series of an ANM step: evaluation, validation, classical step length and the
//! geometric-series (bifurcation) indicator.

use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_runtime::series::{PathSeries, SeriesError, geometric_ratio, series_step_length};

/// Taylor series of $`U(a) = v/(1 - a/\rho) + w a`$, $`\lambda(a) = 1 + c\,a/(\rho - a) + \mu a`$
/// up to order `order`.
fn simple_pole_series(radius: f64, order: usize) -> PathSeries {
    let v = [1.0, -0.5, 2.0];
    let w = [0.3, 1.0, -0.2];
    let (c, mu) = (0.4, 0.8);
    let mut displacement = vec![v.to_vec()];
    let mut load = vec![1.0];
    for k in 1..=order {
        let scale = radius.powi(-(k as i32));
        let extra = if k == 1 { 1.0 } else { 0.0 };
        displacement.push((0..3).map(|i| v[i] * scale + extra * w[i]).collect());
        load.push(c * scale + extra * mu);
    }
    PathSeries::new(displacement, load).unwrap()
}

/// $`U(a) = U_0 + a U_1 + a^2 U_2 + a^3 U_3`$ padded with zero orders up to `order`.
fn cubic_series(order: usize) -> PathSeries {
    let mut displacement = vec![
        vec![0.5, 0.0, -1.0],
        vec![1.0, 2.0, 0.0],
        vec![0.0, -1.0, 0.5],
        vec![0.25, 0.0, 1.0],
    ];
    let mut load = vec![2.0, 1.0, 0.5, -0.25];
    displacement.resize(order + 1, vec![0.0; 3]);
    load.resize(order + 1, 0.0);
    PathSeries::new(displacement, load).unwrap()
}

#[test]
fn evaluation_and_derivative_match_the_polynomial() {
    let series = cubic_series(6);
    assert_eq!((series.order(), series.dimension()), (6, 3));
    let a: f64 = 0.7;
    let (u, lambda) = series.evaluate(a);
    let (du, dlambda) = series.evaluate_derivative(a);
    let expected_u = [
        0.5 + a + 0.25 * a.powi(3),
        2.0 * a - a * a,
        -1.0 + 0.5 * a * a + a.powi(3),
    ];
    let expected_du = [1.0 + 0.75 * a * a, 2.0 - 2.0 * a, a + 3.0 * a * a];
    for i in 0..3 {
        assert!((u[i] - expected_u[i]).abs() < 1e-14);
        assert!((du[i] - expected_du[i]).abs() < 1e-14);
    }
    assert!((lambda - (2.0 + a + 0.5 * a * a - 0.25 * a.powi(3))).abs() < 1e-14);
    assert!((dlambda - (1.0 + a - 0.75 * a * a)).abs() < 1e-14);
}

#[test]
fn validation_reports_inconsistent_series() {
    assert_eq!(
        PathSeries::new(vec![], vec![]),
        Err(SeriesError::EmptySeries)
    );
    assert_eq!(
        PathSeries::new(vec![vec![0.0; 2]; 3], vec![0.0; 2]),
        Err(SeriesError::InconsistentOrders {
            displacement_orders: 3,
            load_orders: 2
        })
    );
    assert_eq!(
        PathSeries::new(vec![vec![0.0; 2], vec![0.0; 3]], vec![0.0; 2]),
        Err(SeriesError::DimensionMismatch {
            order: 1,
            expected: 2,
            found: 3
        })
    );
    assert_eq!(
        PathSeries::new(vec![vec![0.0; 2], vec![f64::NAN, 0.0]], vec![0.0; 2]),
        Err(SeriesError::NonFinite { order: 1 })
    );
    // Evaluation of inconsistent public fields does not panic.
    let broken = PathSeries {
        displacement: vec![vec![1.0, 2.0], vec![1.0]],
        load: vec![3.0],
    };
    assert_eq!(broken.evaluate(2.0), (vec![3.0, 2.0], 3.0));
}

#[test]
fn series_step_length_follows_the_closed_form() {
    // ||V_1|| = 3 (U_1 = (2, 2), lambda_1 = 1) and ||V_5|| = 5 (U_5 = (3, 0), lambda_5 = 4).
    let mut displacement = vec![vec![0.0, 0.0], vec![2.0, 2.0]];
    let mut load = vec![0.0, 1.0];
    for _ in 2..5 {
        displacement.push(vec![0.1, -0.2]);
        load.push(0.3);
    }
    displacement.push(vec![3.0, 0.0]);
    load.push(4.0);
    let series = PathSeries::new(displacement.clone(), load.clone()).unwrap();
    let epsilon = 1e-6;
    let expected = (epsilon * 3.0 / 5.0_f64).powf(1.0 / 4.0);
    assert!((series_step_length(&series, epsilon) - expected).abs() < 1e-15);

    // Trailing zero orders: the last non-zero order (5) is used.
    displacement.extend(vec![vec![0.0, 0.0]; 3]);
    load.extend([0.0; 3]);
    let padded = PathSeries::new(displacement, load).unwrap();
    assert!((series_step_length(&padded, epsilon) - expected).abs() < 1e-15);

    // A linear series is exact everywhere; bad epsilon gives no step.
    let linear = PathSeries::new(
        vec![vec![0.0, 0.0], vec![1.0, 0.0], vec![0.0, 0.0]],
        vec![0.0, 0.0, 0.0],
    )
    .unwrap();
    assert_eq!(series_step_length(&linear, epsilon), f64::INFINITY);
    assert_eq!(series_step_length(&series, 0.0), 0.0);
    assert_eq!(series_step_length(&series, f64::NAN), 0.0);
    assert_eq!(series_step_length(&series, -1.0), 0.0);
}

#[test]
fn geometric_ratio_finds_the_radius_of_a_simple_pole() {
    for radius in [0.05, 0.7, 3.0] {
        let series = simple_pole_series(radius, 15);
        let estimate = geometric_ratio(&series).expect("geometric series");
        assert!(
            (estimate - radius).abs() < 1e-12 * radius,
            "{estimate} vs {radius}"
        );
        // The classical step stays well inside the radius of convergence.
        assert!(series_step_length(&series, 1e-6) < 0.5 * radius);
    }
}

#[test]
fn geometric_ratio_rejects_non_geometric_series() {
    // Polynomial: the last orders vanish.
    assert_eq!(geometric_ratio(&cubic_series(8)), None);
    // Alternating series (pole at negative a).
    assert_eq!(geometric_ratio(&simple_pole_series(-0.7, 12)), None);
    // Random coefficients: not collinear.
    let mut random = StdRng::seed_from_u64(7);
    let displacement: Vec<Vec<f64>> = (0..=10)
        .map(|_| (0..6).map(|_| random.random_range(-1.0..1.0)).collect())
        .collect();
    let load: Vec<f64> = (0..=10).map(|_| random.random_range(-1.0..1.0)).collect();
    let series = PathSeries::new(displacement, load).unwrap();
    assert_eq!(geometric_ratio(&series), None);
    // Collinear but not geometric (norm ratio changes from order to order).
    let mut displacement = vec![vec![0.0, 0.0]];
    let mut load = vec![0.0];
    for k in 1..=6 {
        let scale = if k % 2 == 0 { 1.0 } else { 3.0 };
        displacement.push(vec![scale, 2.0 * scale]);
        load.push(0.0);
    }
    let collinear = PathSeries::new(displacement, load).unwrap();
    assert_eq!(geometric_ratio(&collinear), None);
    // Too short.
    let short = PathSeries::new(vec![vec![1.0], vec![1.0]], vec![0.0, 1.0]).unwrap();
    assert_eq!(geometric_ratio(&short), None);
}
