//! The truncated Taylor series scalar: closed-form expansions, num-dual derivatives and a
//! seeded property check.

use num_dual::{Dual2_64, Dual3_64, Dual64};
use rand::rngs::StdRng;
use rand::{Rng, SeedableRng};
use wrinkle_runtime::Scalar;
use wrinkle_runtime::series::{MAX_SERIES_LEN, Series, SeriesError};

fn assert_close(actual: f64, expected: f64, tolerance: f64, what: &str) {
    assert!(
        (actual - expected).abs() <= tolerance * expected.abs().max(1.0),
        "{what}: {actual} vs {expected}"
    );
}

fn factorial(n: usize) -> f64 {
    (1..=n).map(|k| k as f64).product()
}

/// Generalised binomial coefficient $`\binom{n}{k}`$ for an integer (possibly negative) n.
fn binomial(n: i32, k: usize) -> f64 {
    (0..k).fold(1.0, |product, j| {
        product * (f64::from(n) - j as f64) / (j as f64 + 1.0)
    })
}

#[test]
fn reciprocal_of_one_minus_a_is_the_geometric_series() {
    let one_minus_a = Series::linear(1.0, -1.0, 12);
    let geometric = one_minus_a.recip();
    assert_eq!(geometric.len(), 12);
    for k in 0..12 {
        assert_close(geometric.coefficient(k), 1.0, 1e-15, "1/(1-a)");
    }
    // Same through division of the constant series by (1 - a), and 1/(1 - a)^2 = sum (k+1) a^k.
    let quotient = Series::constant(1.0, 12) / one_minus_a;
    let square = geometric * geometric;
    for k in 0..12 {
        assert_close(quotient.coefficient(k), 1.0, 1e-15, "1/(1-a) by division");
        assert_close(square.coefficient(k), k as f64 + 1.0, 1e-14, "1/(1-a)^2");
    }
    assert_eq!(geometric.coefficient(12), 0.0);
}

#[test]
fn exponential_series_satisfies_product_identities() {
    let len = 20;
    let exponential =
        Series::from_coefficients(&(0..len).map(|k| 1.0 / factorial(k)).collect::<Vec<_>>())
            .unwrap();
    let reflected = Series::from_coefficients(
        &(0..len)
            .map(|k| (-1.0_f64).powi(k as i32) / factorial(k))
            .collect::<Vec<_>>(),
    )
    .unwrap();
    // exp(a)^2 = exp(2a): coefficients 2^k/k!.
    let doubled = exponential * exponential;
    let squared = exponential.square();
    let cubed = exponential.powi(3);
    for k in 0..len {
        let expected = 2.0_f64.powi(k as i32) / factorial(k);
        assert_close(doubled.coefficient(k), expected, 1e-14, "exp(a)^2");
        assert_close(squared.coefficient(k), expected, 1e-14, "square");
        let expected_cube = 3.0_f64.powi(k as i32) / factorial(k);
        assert_close(cubed.coefficient(k), expected_cube, 1e-13, "exp(a)^3");
    }
    // exp(a) exp(-a) = 1 and 1/exp(a) = exp(-a).
    let unit = exponential * reflected;
    let inverse = exponential.recip();
    for k in 0..len {
        let expected_unit = if k == 0 { 1.0 } else { 0.0 };
        assert!((unit.coefficient(k) - expected_unit).abs() < 1e-15);
        assert_close(
            inverse.coefficient(k),
            reflected.coefficient(k),
            1e-14,
            "1/exp",
        );
    }
    // The Horner sum at a = 0.5 approximates e^0.5 to truncation accuracy.
    assert_close(exponential.evaluate(0.5), 0.5_f64.exp(), 1e-15, "exp(0.5)");
}

#[test]
fn integer_powers_of_one_plus_a_are_binomial() {
    let len = 15;
    let base = Series::linear(1.0, 1.0, len);
    for exponent in [-5, -3, -2, -1, 0, 1, 2, 3, 4, 7, 13] {
        let power = base.powi(exponent);
        // Repeated products (and one reciprocal) as an independent construction.
        let mut repeated = Series::constant(1.0, len);
        for _ in 0..exponent.unsigned_abs() {
            repeated = repeated * base;
        }
        if exponent < 0 {
            repeated = repeated.recip();
        }
        assert_eq!(power.len(), len);
        for k in 0..len {
            let expected = binomial(exponent, k);
            assert_close(power.coefficient(k), expected, 1e-12, "(1+a)^n");
            assert_close(repeated.coefficient(k), expected, 1e-12, "(1+a)^n products");
        }
    }
}

#[test]
fn mixed_lengths_truncate_at_the_longer_operand() {
    let short = Series::from_coefficients(&[1.0, 2.0, 3.0]).unwrap();
    let long = Series::from_coefficients(&[2.0, -1.0, 0.5, 4.0, 1.0]).unwrap();
    // Polynomial product (1 + 2a + 3a^2)(2 - a + 0.5a^2 + 4a^3 + a^4) truncated after a^4.
    let expected_product = [2.0, 3.0, 4.5, 2.0, 10.5];
    for (product, name) in [(short * long, "short*long"), (long * short, "long*short")] {
        assert_eq!(product.len(), 5, "{name}");
        for (k, expected) in expected_product.iter().enumerate() {
            assert_close(product.coefficient(k), *expected, 1e-15, name);
        }
    }
    let sum = short + long;
    let difference = short - long;
    assert_eq!((sum.len(), difference.len()), (5, 5));
    assert_eq!(sum.coefficients(), &[3.0, 1.0, 3.5, 4.0, 1.0]);
    assert_eq!(difference.coefficients(), &[-1.0, 3.0, 2.5, -4.0, -1.0]);
    // A constant from `from_f64` has length 1 and adopts the other length.
    let constant = Series::from_f64(2.0);
    assert_eq!(constant.len(), 1);
    assert_eq!(
        (constant * long).coefficients(),
        &[4.0, -2.0, 1.0, 8.0, 2.0]
    );
    assert_eq!(
        (long - constant).coefficients(),
        &[0.0, -1.0, 0.5, 4.0, 1.0]
    );
    assert_eq!((constant / long).len(), 5);
    // Mixed operations with f64 on the right act on coefficient 0 or on all coefficients.
    assert_eq!((short + 1.0).coefficients(), &[2.0, 2.0, 3.0]);
    assert_eq!((short - 1.0).coefficients(), &[0.0, 2.0, 3.0]);
    assert_eq!((short * 2.0).coefficients(), &[2.0, 4.0, 6.0]);
    assert_eq!((short / 2.0).coefficients(), &[0.5, 1.0, 1.5]);
    assert_eq!((-short).coefficients(), &[-1.0, -2.0, -3.0]);
    assert_eq!(short.real(), 1.0);
    assert_eq!(Series::zero().coefficients(), &[0.0]);
    // Quotient by a longer series: (1 + 2a + 3a^2)/(1 - a) = 1 + 3a + 6a^2 + 6a^3 + ...
    let quotient = short / Series::linear(1.0, -1.0, 5);
    assert_eq!(quotient.coefficients(), &[1.0, 3.0, 6.0, 6.0, 6.0]);
}

#[test]
fn division_by_a_series_without_constant_term_gives_non_finite_coefficients() {
    let numerator = Series::linear(1.0, 1.0, 4);
    let denominator = Series::linear(0.0, 1.0, 4);
    let quotient = numerator / denominator;
    assert!(
        quotient
            .coefficients()
            .iter()
            .all(|value| !value.is_finite())
    );
    assert!(!denominator.recip().coefficient(0).is_finite());
}

#[test]
fn construction_horner_length_changes_and_errors() {
    let mut series = Series::from_coefficients(&[1.0, 2.0, 3.0]).unwrap();
    assert_eq!(series.evaluate(2.0), 17.0);
    assert_eq!(series.derivative().coefficients(), &[2.0, 6.0]);
    series.set_len(5).unwrap();
    assert_eq!(series.coefficients(), &[1.0, 2.0, 3.0, 0.0, 0.0]);
    series.set_coefficient(4, 1.0).unwrap();
    assert_eq!(series.evaluate(2.0), 33.0);
    series.set_len(2).unwrap();
    assert_eq!(series.evaluate(2.0), 5.0);
    series.set_len(4).unwrap();
    assert_eq!(
        series.coefficients(),
        &[1.0, 2.0, 0.0, 0.0],
        "truncated orders reset"
    );
    assert_eq!(series.coefficient(40), 0.0);
    assert_eq!(
        series.set_coefficient(4, 1.0),
        Err(SeriesError::CoefficientOutOfRange { index: 4, len: 4 })
    );
    assert_eq!(
        series.set_len(0),
        Err(SeriesError::LengthOutOfRange {
            requested: 0,
            maximum: MAX_SERIES_LEN
        })
    );
    assert!(series.set_len(MAX_SERIES_LEN + 1).is_err());
    assert!(Series::from_coefficients(&[]).is_err());
    assert!(Series::from_coefficients(&[1.0; MAX_SERIES_LEN + 1]).is_err());
    assert_eq!(
        Series::from_coefficients(&[1.0; MAX_SERIES_LEN])
            .unwrap()
            .len(),
        42
    );
    assert_eq!(Series::constant(3.0, 0).len(), 1);
    assert_eq!(Series::constant(3.0, 100).len(), MAX_SERIES_LEN);
}

/// A rational function written like generated kernel code (constants on the right).
fn rational<S: Scalar>(x: S) -> S {
    (x.powi(3) * 2.0 - x + 0.5) * (x.powi(2) + 1.0).recip() + x.powi(-2) * 0.25
}

#[test]
fn composition_coefficients_match_num_dual_derivatives() {
    let (x0, x1, x2, x3) = (0.7, 1.3, -0.4, 0.9);
    let path = Series::from_coefficients(&[x0, x1, x2, x3]).unwrap();
    let composed = rational(path);

    let first = rational(Dual64::from(x0).derivative());
    let second = rational(Dual2_64::from(x0).derivative());
    let third = rational(Dual3_64::from(x0).derivative());
    let (value, d1, d2, d3) = (third.re, first.eps, second.v2, third.v3);
    assert_close(second.v1, d1, 1e-14, "dual consistency");

    // Faa di Bruno for x(a) = x0 + x1 a + x2 a^2 + x3 a^3.
    assert_close(composed.coefficient(0), value, 1e-14, "order 0");
    assert_close(composed.coefficient(1), d1 * x1, 1e-13, "order 1");
    assert_close(
        composed.coefficient(2),
        d1 * x2 + 0.5 * d2 * x1 * x1,
        1e-13,
        "order 2",
    );
    assert_close(
        composed.coefficient(3),
        d1 * x3 + d2 * x1 * x2 + d3 * x1.powi(3) / 6.0,
        1e-13,
        "order 3",
    );
}

#[test]
fn products_and_quotients_evaluate_to_products_and_quotients_of_values() {
    let mut random = StdRng::seed_from_u64(20140101);
    for _ in 0..200 {
        let left_len = random.random_range(6..=MAX_SERIES_LEN);
        let right_len = random.random_range(6..=MAX_SERIES_LEN);
        let left: Vec<f64> = (0..left_len)
            .map(|_| random.random_range(-1.0..1.0))
            .collect();
        let mut right: Vec<f64> = (0..right_len)
            .map(|_| random.random_range(-0.5..0.5))
            .collect();
        right[0] = random.random_range(1.0..2.0);
        let p = Series::from_coefficients(&left).unwrap();
        let q = Series::from_coefficients(&right).unwrap();
        let parameter: f64 = random.random_range(-0.01..0.01);
        // Truncation after order >= 5 leaves a tail O(|a|^6) <= 1e-11 here.
        let (p_value, q_value) = (p.evaluate(parameter), q.evaluate(parameter));
        let product = (p * q).evaluate(parameter);
        assert!(
            (product - p_value * q_value).abs() < 1e-10,
            "product {product} vs {}",
            p_value * q_value
        );
        let quotient = (p / q).evaluate(parameter);
        assert!(
            (quotient - p_value / q_value).abs() < 1e-9,
            "quotient {quotient} vs {}",
            p_value / q_value
        );
        let combination = (p + q * 3.0 - 1.0).evaluate(parameter);
        assert!((combination - (p_value + 3.0 * q_value - 1.0)).abs() < 1e-13);
        // (p / q) * q reproduces p coefficient by coefficient.
        let recovered = (p / q) * q;
        for k in 0..left_len.max(right_len) {
            assert!(
                (recovered.coefficient(k) - p.coefficient(k)).abs() < 1e-10,
                "order {k}: {} vs {}",
                recovered.coefficient(k),
                p.coefficient(k)
            );
        }
    }
}
