//! The exponential change of path parameter that removes a singularity behind a step.
//!
//! Past the knee of an imperfect path, the series of an ANM step is limited by a singularity
//! **behind** its start, at $`a = -R`$: the imperfect bifurcation the path left (for the
//! imperfect pitchfork $`(1-\lambda)\xi - c\,\xi^3 = \lambda\varepsilon`$ the load
//! $`\lambda(\xi) = (\xi - c\xi^3)/(\xi + \varepsilon)`$ has its pole at $`\xi = -\varepsilon`$).
//! The coefficients then alternate, $`V_k \approx c\,(-R)^{-k}\varphi`$, and every step can only
//! reach a fraction of $`R`$, the distance it has come from the bifurcation: the amplitude
//! about doubles per step, whatever the order or the Padé approximant. On example 1's plate at
//! 128 × 32, steps 4 to 8 of 12 show such tails ($`R`$ = 0.022, 0.041, 0.064, 0.107, 0.232, each
//! step's Padé range about 0.6 $`R`$); with the map, steps 4 and 5 reach 2.6 and 2.3 $`R`$ and the
//! path takes 10 steps (docs/benchmarks.md, "Round ten").
//!
//! The change of parameter
//! ```math
//! a = R\,(e^{s} - 1), \qquad s = \ln(1 + a/R)
//! ```
//! sends $`a = -R`$ to $`s = -\infty`$: an algebraic singularity there,
//! $`(a + R)^p = R^p e^{p s}`$, or a logarithmic one, $`\ln(a+R) = \ln R + s`$, becomes entire
//! in $`s`$. The series in $`s`$ is then limited only by the other singularities, mapped to
//! $`s^* = \ln(1 + a^*/R)`$: a pole ahead at $`a^* = A`$ stays at the same place along the path,
//! and one behind at the distance $`R`$ is gone. Its coefficients follow from those in $`a`$
//! without any further solve ([`compose`]):
//! ```math
//! W_n = \sum_{k=1}^{n} c_{n,k}\,R^k\,V_k, \qquad (e^s - 1)^k = \sum_{n\ge k} c_{n,k}\,s^n
//! \quad\big(c_{n,k} = k!\,S(n,k)/n!\big),
//! ```
//! exact up to the truncation order: $`W_n`$ depends on $`V_1, \dots, V_n`$ only. The step's
//! range in $`s`$ is the classical one ([`series_step_length`] of the $`W_n`$), and in $`a`$,
//! $`R\,(e^{s_{\max}} - 1)`$.

use super::SeriesError;
use super::vector_series::{
    GEOMETRIC_RATIO_TOLERANCE, PathSeries, checked_order, series_step_length,
};
use crate::linear::vector::axpy;
use rayon::prelude::*;

/// Largest cosine between consecutive last coefficients $`V_{k-1}, V_k`$ (for
/// $`k = N-1, N`$) for [`singularity_behind`] to report a singularity behind: they must point
/// opposite ways.
pub const ALTERNATING_COSINE_THRESHOLD: f64 = -0.99;

/// Detects a singularity behind the step's start in the last orders of `series`: if
/// $`V_k \approx c\,(-R)^{-k}\varphi`$, consecutive coefficients point opposite ways and
/// $`\lVert V_{k-1}\rVert / \lVert V_k\rVert \to R`$. Returns
/// $`R \approx \lVert V_{N-1}\rVert / \lVert V_N\rVert`$ when $`N \ge 3`$, the cosines of
/// $`(V_{N-2}, V_{N-1})`$ and $`(V_{N-1}, V_N)`$ are both below
/// [`ALTERNATING_COSINE_THRESHOLD`], and the two last ratios agree within
/// [`GEOMETRIC_RATIO_TOLERANCE`]; `None` otherwise (a zero or non-finite coefficient, a
/// singularity ahead, several singularities at similar distances).
#[must_use]
pub fn singularity_behind(series: &PathSeries) -> Option<f64> {
    let order = series.order();
    if order < 3 {
        return None;
    }
    let norms: Vec<f64> = (order - 2..=order)
        .map(|k| series.coefficient_norm(k))
        .collect();
    if !norms.iter().all(|n| *n > 0.0 && n.is_finite()) {
        return None;
    }
    // Written so that a NaN cosine is rejected.
    let alternating = |k: usize, norms: (f64, f64)| {
        series.coefficient_dot(k - 1, k) / (norms.0 * norms.1) < ALTERNATING_COSINE_THRESHOLD
    };
    if !(alternating(order - 1, (norms[0], norms[1])) && alternating(order, (norms[1], norms[2]))) {
        return None;
    }
    let radius = norms[1] / norms[2];
    let earlier = norms[0] / norms[1];
    ((earlier - radius).abs() <= GEOMETRIC_RATIO_TOLERANCE * radius && radius.is_finite())
        .then_some(radius)
}

/// `powers[k][n]` $`= [t^n]\,g(t)^k`$ for $`0 \le k, n \le N`$ (`order`), for a series $`g`$
/// with $`g(0) = 0`$ (so that `powers[k][n] = 0` for $`n < k`$).
fn scalar_powers(inner: &[f64], order: usize) -> Vec<Vec<f64>> {
    let mut powers = vec![vec![0.0; order + 1]; order + 1];
    powers[0][0] = 1.0;
    for k in 1..=order {
        for n in k..=order {
            powers[k][n] = (k - 1..n)
                .map(|j| powers[k - 1][j] * inner.get(n - j).copied().unwrap_or(0.0))
                .sum();
        }
    }
    powers
}

/// The coefficients of $`R\,(e^s - 1) = \sum_{m \ge 1} R\,s^m/m!`$ up to `order`.
fn exponential_map_series(radius: f64, order: usize) -> Vec<f64> {
    let mut coefficients = vec![0.0; order + 1];
    let mut factorial = 1.0;
    for (m, c) in coefficients.iter_mut().enumerate().skip(1) {
        factorial *= m as f64;
        *c = radius / factorial;
    }
    coefficients
}

/// The vector series $`V(g(t)) = V_0 + \sum_{n=1}^N t^n \sum_{k=1}^n [t^n]g^k\,V_k`$ of
/// `series` composed with the scalar series $`g`$ (`inner`, $`g(0) = 0`$), truncated at the
/// same order: exact to that order, since its order-$`n`$ coefficient depends on
/// $`V_1, \dots, V_n`$ only. Each coefficient is its own sum in a fixed order (the same on any
/// number of threads).
fn compose(series: &PathSeries, inner: &[f64]) -> PathSeries {
    let order = series.order();
    let powers = scalar_powers(inner, order);
    let dimension = series.dimension();
    let coefficient = |n: usize| -> (Vec<f64>, f64) {
        let mut displacement = vec![0.0; dimension];
        let mut load = 0.0;
        let terms = powers.iter().zip(&series.displacement).zip(&series.load);
        for ((power, vector), coefficient) in terms.take(n + 1).skip(1) {
            let weight = power[n];
            axpy(weight, vector, &mut displacement);
            load += weight * coefficient;
        }
        (displacement, load)
    };
    let (mut displacement, mut load): (Vec<Vec<f64>>, Vec<f64>) =
        (1..=order).into_par_iter().map(coefficient).unzip();
    displacement.insert(0, series.displacement[0].clone());
    load.insert(0, series.load[0]);
    PathSeries { displacement, load }
}

/// A step's series re-expanded in $`s = \ln(1 + a/R)`$ (see the module's documentation):
/// evaluated at the path parameter $`a > -R`$ of the original series.
#[derive(Clone, Debug)]
pub struct ExponentialMap {
    radius: f64,
    mapped: PathSeries,
}

impl ExponentialMap {
    /// The series $`W_n`$ in $`s`$ of `series` (in $`a`$) with the singularity at
    /// $`a = -`$`radius` sent to $`s = -\infty`$. Each $`W_n`$ is its own sum in a fixed order
    /// (the same on any number of threads).
    ///
    /// # Errors
    /// Those of [`PathSeries::validate`], [`SeriesError::TooFewOrders`] for $`N < 2`$, and
    /// [`SeriesError::NonFinite`] when `radius` is not positive and finite or a mapped
    /// coefficient overflows.
    pub fn new(series: &PathSeries, radius: f64) -> Result<Self, SeriesError> {
        let order = checked_order(series)?;
        if !(radius > 0.0 && radius.is_finite()) {
            return Err(SeriesError::NonFinite { order: 0 });
        }
        let mapped = compose(series, &exponential_map_series(radius, order));
        mapped.validate()?;
        Ok(Self { radius, mapped })
    }

    /// The distance $`R`$ of the singularity behind the step's start.
    #[must_use]
    pub fn radius(&self) -> f64 {
        self.radius
    }

    /// The series $`W_n`$ in $`s`$.
    #[must_use]
    pub fn mapped(&self) -> &PathSeries {
        &self.mapped
    }

    /// $`s = \ln(1 + a/R)`$ ($`-\infty`$ at and behind the singularity).
    #[must_use]
    pub fn mapped_parameter(&self, parameter: f64) -> f64 {
        let ratio = parameter / self.radius;
        if ratio > -1.0 {
            ratio.ln_1p()
        } else {
            f64::NEG_INFINITY
        }
    }

    /// The range in $`a`$ of the classical criterion on the mapped series:
    /// $`R\,(e^{s_{\max}} - 1)`$ with $`s_{\max}`$ from [`series_step_length`] (infinite when
    /// the mapped series is linear).
    #[must_use]
    pub fn step_length(&self, epsilon: f64) -> f64 {
        let range = series_step_length(&self.mapped, epsilon);
        self.radius * range.exp_m1()
    }

    /// $`(U(a), \lambda(a))`$ through the mapped series at $`s(a)`$.
    #[must_use]
    pub fn evaluate(&self, parameter: f64) -> (Vec<f64>, f64) {
        self.mapped.evaluate(self.mapped_parameter(parameter))
    }

    /// $`(U'(a), \lambda'(a)) = (W'(s), \lambda_W'(s))\,/\,(R + a)`$.
    #[must_use]
    pub fn evaluate_derivative(&self, parameter: f64) -> (Vec<f64>, f64) {
        let (mut displacement, load) = self
            .mapped
            .evaluate_derivative(self.mapped_parameter(parameter));
        let scale = 1.0 / (self.radius + parameter);
        displacement.iter_mut().for_each(|v| *v *= scale);
        (displacement, load * scale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The scalar series of $`f(a)`$ as a one-dimensional path series (the load component is
    /// $`f`$ too).
    fn scalar_series(coefficients: &[f64]) -> PathSeries {
        PathSeries::new(
            coefficients.iter().map(|c| vec![*c]).collect(),
            coefficients.to_vec(),
        )
        .unwrap()
    }

    #[test]
    fn exponential_powers_are_stirling_numbers_over_factorials() {
        let powers = scalar_powers(&exponential_map_series(1.0, 6), 6);
        let table: Vec<Vec<f64>> = (0..=6)
            .map(|n| (0..=6).map(|k| powers[k][n]).collect())
            .collect();
        // (e^s − 1)^2 = s^2 + s^3 + 7/12 s^4 + 1/4 s^5 + 31/360 s^6
        let expected = [1.0, 1.0, 7.0 / 12.0, 0.25, 31.0 / 360.0];
        for (n, e) in (2..=6).zip(expected) {
            assert!((table[n][2] - e).abs() < 1e-15, "n = {n}: {}", table[n][2]);
        }
        // c_{n,n} = 1, c_{n,1} = 1/n!
        assert!((1..=6).all(|n| (table[n][n] - 1.0).abs() < 1e-15));
        assert!((table[5][1] - 1.0 / 120.0).abs() < 1e-16);
    }

    /// $`f(a) = 1/(1 + a/R)`$ (a pole behind at $`-R`$) becomes $`e^{-s}`$: the mapped
    /// coefficients are $`(-1)^n/n!`$ and the truncated mapped series is accurate far beyond
    /// $`R`$, where the series in $`a`$ diverges.
    #[test]
    fn pole_behind_becomes_entire() {
        let radius: f64 = 0.5;
        let order = 20;
        let coefficients: Vec<f64> = (0..=order)
            .map(|k| (-1.0f64 / radius).powi(k as i32))
            .collect();
        let series = scalar_series(&coefficients);
        assert!((singularity_behind(&series).unwrap() - radius).abs() < 1e-12);
        let map = ExponentialMap::new(&series, radius).unwrap();
        let mut factorial = 1.0;
        for n in 1..=order {
            factorial *= n as f64;
            let expected = (-1.0f64).powi(n as i32) / factorial;
            assert!(
                (map.mapped().load[n] - expected).abs() < 1e-13,
                "W_{n} = {} against {expected}",
                map.mapped().load[n]
            );
        }
        let range = map.step_length(1e-7);
        assert!(range > 5.0 * radius, "range {range}");
        for a in [0.1, 1.0, range] {
            let exact = 1.0 / (1.0 + a / radius);
            let (u, load) = map.evaluate(a);
            assert!((load - exact).abs() < 1e-6 && (u[0] - exact).abs() < 1e-6);
            let (du, dload) = map.evaluate_derivative(a);
            let slope = -1.0 / (radius * (1.0 + a / radius).powi(2));
            assert!((dload - slope).abs() < 1e-6 * slope.abs().max(1.0));
            assert!((du[0] - slope).abs() < 1e-6 * slope.abs().max(1.0));
        }
    }

    /// A square-root branch point behind, $`\sqrt{1 + a/R}`$, is $`e^{s/2}`$.
    #[test]
    fn branch_point_behind_becomes_entire() {
        let radius = 2.0;
        let order = 16;
        // binomial series of (1 + x)^{1/2}, x = a/R
        let mut coefficients = vec![1.0];
        for k in 1..=order {
            let previous = coefficients[k - 1];
            coefficients.push(previous * (0.5 - (k - 1) as f64) / k as f64 / radius);
        }
        let map = ExponentialMap::new(&scalar_series(&coefficients), radius).unwrap();
        for a in [3.0, 10.0, 30.0] {
            let (_, value) = map.evaluate(a);
            let exact = (1.0 + a / radius).sqrt();
            assert!(
                (value - exact).abs() < 1e-6 * exact,
                "{a}: {value} vs {exact}"
            );
        }
    }

    #[test]
    fn singularity_ahead_or_mixed_is_not_behind() {
        let ahead: Vec<f64> = (0..=10).map(|k| 2.0f64.powi(k)).collect();
        assert_eq!(singularity_behind(&scalar_series(&ahead)), None);
        let polynomial = [1.0, 2.0, 0.0, 0.0];
        assert_eq!(singularity_behind(&scalar_series(&polynomial)), None);
        let irregular = [1.0, -1.0, 1.0, -3.0, 1.0];
        assert_eq!(singularity_behind(&scalar_series(&irregular)), None);
    }

    #[test]
    fn bad_radius_is_an_error_not_a_nan() {
        let series = scalar_series(&[1.0, -1.0, 1.0]);
        assert!(ExponentialMap::new(&series, 0.0).is_err());
        assert!(ExponentialMap::new(&series, f64::NAN).is_err());
        let map = ExponentialMap::new(&series, 1.0).unwrap();
        assert_eq!(map.mapped_parameter(-2.0), f64::NEG_INFINITY);
    }
}
