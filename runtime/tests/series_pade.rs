//! Padé approximants with a common denominator: exactness on rational vector functions,
//! poles, step length, polynomial (degenerate) series.

use wrinkle_runtime::series::{PadeApproximant, PathSeries, SeriesError, series_step_length};

/// A vector rational function $`V(a) = V_0 + \sum_j c_j\, a/(\rho_j - a) + w a`$ (the load is
/// the last component), with its Taylor series up to `order`.
struct RationalPath {
    origin: Vec<f64>,
    poles: Vec<(f64, Vec<f64>)>,
    linear: Vec<f64>,
}

impl RationalPath {
    fn exact(&self, a: f64) -> Vec<f64> {
        let mut value = self.origin.clone();
        for (i, entry) in value.iter_mut().enumerate() {
            *entry += self.linear[i] * a;
            for (radius, direction) in &self.poles {
                *entry += direction[i] * a / (radius - a);
            }
        }
        value
    }

    fn series(&self, order: usize) -> PathSeries {
        let dimension = self.origin.len() - 1;
        let mut displacement = vec![self.origin[..dimension].to_vec()];
        let mut load = vec![self.origin[dimension]];
        for k in 1..=order {
            // a/(rho - a) = sum_{k>=1} (a/rho)^k.
            let mut coefficient: Vec<f64> = if k == 1 {
                self.linear.clone()
            } else {
                vec![0.0; dimension + 1]
            };
            for (radius, direction) in &self.poles {
                for (entry, value) in coefficient.iter_mut().zip(direction) {
                    *entry += value * radius.powi(-(k as i32));
                }
            }
            load.push(coefficient[dimension]);
            coefficient.truncate(dimension);
            displacement.push(coefficient);
        }
        PathSeries::new(displacement, load).unwrap()
    }
}

fn simple_pole(radius: f64) -> RationalPath {
    RationalPath {
        origin: vec![1.0, -0.5, 2.0, 1.0],
        poles: vec![(radius, vec![1.0, -0.5, 2.0, 0.4])],
        linear: vec![0.3, 1.0, -0.2, 0.8],
    }
}

/// Poles at 0.4 and 1.5 in five components (the load last), plus a linear part.
fn two_poles() -> RationalPath {
    RationalPath {
        origin: vec![0.0, 1.0, 0.0, 0.0, 0.5],
        poles: vec![
            (1.5, vec![1.0, 0.0, -1.0, 0.5, 0.2]),
            (0.4, vec![0.0, 2.0, 1.0, -1.0, 0.1]),
        ],
        linear: vec![1.0, 1.0, 0.0, 0.0, 1.0],
    }
}

fn combined(evaluation: (Vec<f64>, f64)) -> Vec<f64> {
    let (mut vector, load) = evaluation;
    vector.push(load);
    vector
}

fn distance(left: &[f64], right: &[f64]) -> f64 {
    left.iter()
        .zip(right)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

fn norm(vector: &[f64]) -> f64 {
    distance(vector, &vec![0.0; vector.len()])
}

#[test]
fn pade_of_a_simple_pole_is_exact_up_to_the_pole() {
    let radius = 0.7;
    let path = simple_pole(radius);
    let series = path.series(12);
    let pade = PadeApproximant::new(&series).unwrap();
    assert_eq!(pade.order(), 12);
    for fraction in [0.1, 0.5, 0.8, 0.95, 0.99] {
        let a = fraction * radius;
        let exact = path.exact(a);
        let pade_error = distance(&combined(pade.evaluate(a)), &exact) / norm(&exact);
        let lower_error = distance(&combined(pade.evaluate_lower(a)), &exact) / norm(&exact);
        assert!(pade_error < 1e-12, "P_N at {fraction} rho: {pade_error}");
        assert!(
            lower_error < 1e-12,
            "P_(N-1) at {fraction} rho: {lower_error}"
        );
        if fraction >= 0.8 {
            let series_error = distance(&combined(series.evaluate(a)), &exact) / norm(&exact);
            assert!(series_error > 1e-3, "the truncated series fails there");
        }
    }
    // Beyond the pole too (the approximant is the rational function itself).
    let exact = path.exact(1.5 * radius);
    assert!(distance(&combined(pade.evaluate(1.5 * radius)), &exact) < 1e-10 * norm(&exact));
}

/// The derivative of $`V(a)`$: $`\sum_j c_j \rho_j/(\rho_j - a)^2 + w`$.
fn exact_derivative(path: &RationalPath, a: f64) -> Vec<f64> {
    let mut value = path.linear.clone();
    for (i, entry) in value.iter_mut().enumerate() {
        for (radius, direction) in &path.poles {
            *entry += direction[i] * radius / ((radius - a) * (radius - a));
        }
    }
    value
}

#[test]
fn pade_derivative_is_the_rational_functions_derivative_where_the_series_diverges() {
    let path = two_poles();
    let series = path.series(14);
    let pade = PadeApproximant::new(&series).unwrap();
    for a in [0.0, 0.1, 0.3, 0.38, 0.6, 1.2] {
        let exact = exact_derivative(&path, a);
        let error = distance(&combined(pade.evaluate_derivative(a)), &exact) / norm(&exact);
        assert!(error < 1e-9, "a = {a}: {error}");
    }
    // Past the pole (0.4) the series' own derivative has nothing to do with the path's.
    let at = 0.6;
    let exact = exact_derivative(&path, at);
    let series_error = distance(&combined(series.evaluate_derivative(at)), &exact) / norm(&exact);
    assert!(series_error > 10.0, "{series_error}");
}

#[test]
fn smallest_positive_pole_is_the_radius_of_convergence() {
    for radius in [0.01, 0.7, 25.0] {
        let pade = PadeApproximant::new(&simple_pole(radius).series(15)).unwrap();
        let pole = pade.smallest_positive_pole().expect("a pole");
        assert!((pole - radius).abs() < 1e-8 * radius, "{pole} vs {radius}");
        assert!(pade.denominator(radius).abs() < 1e-8);
    }
}

#[test]
fn pade_step_length_exceeds_the_series_step_length() {
    let radius = 0.7;
    let series = simple_pole(radius).series(12);
    let pade = PadeApproximant::new(&series).unwrap();
    for epsilon in [1e-4, 1e-6, 1e-8] {
        let series_step = series_step_length(&series, epsilon);
        let pade_step = pade.pade_step_length(epsilon);
        assert!(
            pade_step > 2.0 * series_step,
            "epsilon {epsilon}: Padé {pade_step} vs series {series_step}"
        );
        // The approximant is exact here, so only the pole bound is active: 0.9 rho.
        assert!((pade_step - 0.9 * radius).abs() < 1e-8, "{pade_step}");
        let custom = pade.pade_step_length_with_pole_safety(epsilon, 0.5);
        assert!((custom - 0.5 * radius).abs() < 1e-8, "{custom}");
    }
    assert_eq!(pade.pade_step_length(0.0), 0.0);
    assert_eq!(pade.pade_step_length(f64::NAN), 0.0);
    assert_eq!(pade.pade_step_length_with_pole_safety(1e-6, 1.5), 0.0);
}

#[test]
fn two_poles_give_an_exact_approximant_and_the_nearest_pole() {
    let path = two_poles();
    let series = path.series(14);
    let pade = PadeApproximant::new(&series).unwrap();
    let pole = pade.smallest_positive_pole().unwrap();
    assert!((pole - 0.4).abs() < 1e-8 * 0.4, "{pole}");
    for a in [0.1, 0.3, 0.38, 0.9, 1.2] {
        let exact = path.exact(a);
        let error = distance(&combined(pade.evaluate(a)), &exact) / norm(&exact);
        assert!(error < 1e-10, "a = {a}: {error}");
    }
    let step = pade.pade_step_length(1e-6);
    assert!(step > series_step_length(&series, 1e-6));
    assert!(step <= 0.9 * 0.4 + 1e-12);
}

#[test]
fn polynomial_series_keeps_a_trivial_denominator() {
    let cubic = |a: f64| {
        vec![
            0.5 + a + 0.25 * a.powi(3),
            2.0 * a - a * a,
            -1.0 + 0.5 * a * a + a.powi(3),
            2.0 + a + 0.5 * a * a - 0.25 * a.powi(3),
        ]
    };
    let mut displacement = vec![
        vec![0.5, 0.0, -1.0],
        vec![1.0, 2.0, 0.0],
        vec![0.0, -1.0, 0.5],
        vec![0.25, 0.0, 1.0],
    ];
    let mut load = vec![2.0, 1.0, 0.5, -0.25];
    displacement.resize(9, vec![0.0; 3]);
    load.resize(9, 0.0);
    let series = PathSeries::new(displacement, load).unwrap();
    let pade = PadeApproximant::new(&series).unwrap();
    let denominator = pade.denominator_coefficients();
    assert_eq!(denominator.len(), 8);
    assert_eq!(denominator[0], 1.0);
    assert!(
        denominator[1..].iter().all(|d| *d == 0.0),
        "{denominator:?}"
    );
    assert_eq!(pade.smallest_positive_pole(), None);
    for a in [0.3, 2.0, 10.0] {
        let exact = cubic(a);
        assert!(distance(&combined(pade.evaluate(a)), &exact) < 1e-13 * norm(&exact));
    }
    // Nothing limits the step: the caller caps it.
    assert_eq!(pade.pade_step_length(1e-6), f64::INFINITY);
}

#[test]
fn generic_series_is_matched_to_order_n_minus_one_and_extended() {
    // Components 1/sqrt(1 - a/rho_i) (branch points, not rational): the Padé is not exact but
    // matches the Taylor series and approximates better than it near the singularity.
    let radii = [0.5, 0.8, 1.3, 2.0];
    let order: usize = 10;
    let exact = |a: f64| -> Vec<f64> {
        radii
            .iter()
            .map(|radius| 1.0 / (1.0 - a / radius).sqrt())
            .collect()
    };
    // Taylor coefficients of (1 - x)^(-1/2): binomial(2k, k)/4^k.
    let mut displacement = Vec::new();
    let mut load = Vec::new();
    let mut central = 1.0;
    for k in 0..=order {
        if k > 0 {
            central *= (2 * k - 1) as f64 / (2 * k) as f64;
        }
        let coefficients: Vec<f64> = radii
            .iter()
            .map(|radius| central * radius.powi(-(k as i32)))
            .collect();
        load.push(coefficients[3]);
        displacement.push(coefficients[..3].to_vec());
    }
    let series = PathSeries::new(displacement, load).unwrap();
    let pade = PadeApproximant::new(&series).unwrap();
    // Order of contact: the error behaves like a^N (N = 10), so halving a divides it by
    // about 2^10 (at least 2^9 is required here).
    let error_at = |a: f64| distance(&combined(pade.evaluate(a)), &exact(a));
    let (coarse, fine) = (error_at(0.1), error_at(0.05));
    assert!(coarse < 1e-6, "{coarse}");
    assert!(coarse / fine > 512.0, "{coarse} / {fine}");
    // Near the first branch point the Padé beats the truncated series.
    let a = 0.4;
    let pade_error = error_at(a);
    let series_error = distance(&combined(series.evaluate(a)), &exact(a));
    assert!(
        pade_error < 0.1 * series_error,
        "{pade_error} vs {series_error}"
    );
    // The Padé step is longer than the series step, and the approximant fulfils its own
    // criterion there.
    let epsilon = 1e-6;
    let step = pade.pade_step_length(epsilon);
    assert!(step > series_step_length(&series, epsilon), "{step}");
    let upper = combined(pade.evaluate(step));
    let lower = combined(pade.evaluate_lower(step));
    let origin = exact(0.0);
    assert!(distance(&upper, &lower) <= epsilon * distance(&upper, &origin) * (1.0 + 1e-9));
}

#[test]
fn construction_rejects_short_or_inconsistent_series() {
    let linear = PathSeries::new(vec![vec![0.0], vec![1.0]], vec![0.0, 1.0]).unwrap();
    assert_eq!(
        PadeApproximant::new(&linear).unwrap_err(),
        SeriesError::TooFewOrders {
            required: 2,
            found: 1
        }
    );
    let inconsistent = PathSeries {
        displacement: vec![vec![0.0]; 4],
        load: vec![0.0; 3],
    };
    assert!(matches!(
        PadeApproximant::new(&inconsistent),
        Err(SeriesError::InconsistentOrders { .. })
    ));
}

/// A pole with a negligible residue (relative residue ρ = |R| / (a_p² |V_1|) far below
/// 1e-6 ε, a Froissart-like doublet) disturbs the approximant only in a tiny window around it
/// and does not bound the Padé range; the same pole with a real residue does.
#[test]
fn a_pole_with_a_negligible_residue_does_not_bound_the_pade_range() {
    let path = |residue_scale: f64| RationalPath {
        origin: vec![1.0, -0.5, 2.0, 1.0],
        poles: vec![
            (0.7, vec![1.0, -0.5, 2.0, 0.4]),
            (0.3, vec![0.0, residue_scale, 0.0, residue_scale]),
        ],
        linear: vec![0.3, 1.0, -0.2, 0.8],
    };
    let epsilon = 1e-6;

    // ρ ≈ 1e-14 / (0.3 · 3.7) ≈ 1e-14, below 1e-6 ε = 1e-12: not a bound.
    let spurious = path(1e-14);
    let pade = PadeApproximant::new(&spurious.series(16)).unwrap();
    let pole = pade.smallest_positive_pole().expect("the doublet is seen");
    assert!((pole - 0.3).abs() < 1e-6, "{pole}");
    let step = pade.pade_step_length(epsilon);
    assert!((step - 0.9 * 0.7).abs() < 1e-9, "{step}");
    for a in [0.1, 0.5, 0.6] {
        let exact = spurious.exact(a);
        let error = distance(&combined(pade.evaluate(a)), &exact) / norm(&exact);
        assert!(error < 1e-9, "a = {a}: {error}");
    }

    // The same pole with a residue 1e-3 of the other's bounds the step.
    let genuine = path(1e-3);
    let pade = PadeApproximant::new(&genuine.series(16)).unwrap();
    let pole = pade.smallest_positive_pole().unwrap();
    assert!((pole - 0.3).abs() < 1e-8, "{pole}");
    let step = pade.pade_step_length(epsilon);
    assert!(step <= 0.9 * 0.3 + 1e-12, "{step}");
}
