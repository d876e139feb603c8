//! Vector series of one ANM step: $`U(a) = U_0 + \sum_{k=1}^{N} a^k U_k`$,
//! $`\lambda(a) = \lambda_0 + \sum_{k=1}^{N} a^k \lambda_k`$, the classical step length and the
//! geometric-series (bifurcation) indicator.

use super::SeriesError;
use crate::linear::vector::dot;

/// Minimal cosine between $`(U_{N-1}, \lambda_{N-1})`$ and $`(U_N, \lambda_N)`$ for
/// [`geometric_ratio`] to report a geometric series.
pub const GEOMETRIC_COSINE_THRESHOLD: f64 = 0.99;

/// Maximal relative difference between the two last norm ratios
/// $`\lVert V_{N-2}\rVert/\lVert V_{N-1}\rVert`$ and
/// $`\lVert V_{N-1}\rVert/\lVert V_N\rVert`$ for [`geometric_ratio`] to report a geometric
/// series.
pub const GEOMETRIC_RATIO_TOLERANCE: f64 = 0.1;

/// The series of one ANM step: `displacement[k]` $`= U_k`$ and `load[k]` $`= \lambda_k`$ for
/// $`k = 0, \dots, N`$, i.e.
/// ```math
/// U(a) = U_0 + \sum_{k=1}^{N} a^k U_k, \qquad \lambda(a) = \lambda_0 + \sum_{k=1}^{N} a^k \lambda_k ,
/// ```
/// where the path parameter satisfies $`\langle U_k, U_1\rangle + \lambda_k \lambda_1 = 0`$ for
/// $`k \ge 2`$ (THEORY.md §10), or, in the amplitude of a mode $`\varphi`$,
/// $`\langle U_k, \varphi\rangle = 0`$
/// ([`AnmOptions::mode_parameter`](crate::solve::anm::AnmOptions)). Norms of coefficients
/// include the load component:
/// $`\lVert V_k \rVert = \big(\lVert U_k\rVert^2 + \lambda_k^2\big)^{1/2}`$ with
/// $`V_k = (U_k, \lambda_k)`$.
///
/// The fields are public; [`PathSeries::new`] / [`PathSeries::validate`] check consistency
/// (same number of displacement and load coefficients, equal dimensions, finite values).
/// The evaluation methods never panic on inconsistent data: missing entries count as zero.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PathSeries {
    /// $`U_0, U_1, \dots, U_N`$.
    pub displacement: Vec<Vec<f64>>,
    /// $`\lambda_0, \lambda_1, \dots, \lambda_N`$.
    pub load: Vec<f64>,
}

impl PathSeries {
    /// Builds and validates a path series.
    ///
    /// # Errors
    /// See [`PathSeries::validate`].
    pub fn new(displacement: Vec<Vec<f64>>, load: Vec<f64>) -> Result<Self, SeriesError> {
        let series = Self { displacement, load };
        series.validate()?;
        Ok(series)
    }

    /// Checks that the series is usable.
    ///
    /// # Errors
    /// * [`SeriesError::EmptySeries`] without $`U_0`$,
    /// * [`SeriesError::InconsistentOrders`] if `displacement` and `load` differ in length,
    /// * [`SeriesError::DimensionMismatch`] if some $`U_k`$ differs in dimension from $`U_0`$,
    /// * [`SeriesError::NonFinite`] for a NaN or infinite coefficient.
    pub fn validate(&self) -> Result<(), SeriesError> {
        if self.displacement.is_empty() {
            return Err(SeriesError::EmptySeries);
        }
        if self.displacement.len() != self.load.len() {
            return Err(SeriesError::InconsistentOrders {
                displacement_orders: self.displacement.len(),
                load_orders: self.load.len(),
            });
        }
        let expected = self.displacement[0].len();
        for (order, (vector, load)) in self.displacement.iter().zip(&self.load).enumerate() {
            if vector.len() != expected {
                return Err(SeriesError::DimensionMismatch {
                    order,
                    expected,
                    found: vector.len(),
                });
            }
            if !load.is_finite() || vector.iter().any(|value| !value.is_finite()) {
                return Err(SeriesError::NonFinite { order });
            }
        }
        Ok(())
    }

    /// The truncation order $`N`$ (number of coefficients minus one; 0 for an empty series).
    #[must_use]
    pub fn order(&self) -> usize {
        self.displacement
            .len()
            .max(self.load.len())
            .saturating_sub(1)
    }

    /// The number of displacement unknowns (dimension of $`U_0`$).
    #[must_use]
    pub fn dimension(&self) -> usize {
        self.displacement.first().map_or(0, Vec::len)
    }

    /// $`\lVert V_k \rVert = \big(\lVert U_k\rVert^2 + \lambda_k^2\big)^{1/2}`$ (0 beyond the
    /// truncation order).
    #[must_use]
    pub fn coefficient_norm(&self, order: usize) -> f64 {
        let displacement = self
            .displacement
            .get(order)
            .map_or(0.0, |vector| dot(vector, vector));
        let load = self.load.get(order).copied().unwrap_or(0.0);
        (displacement + load * load).sqrt()
    }

    /// $`\langle V_i, V_j\rangle = \langle U_i, U_j\rangle + \lambda_i \lambda_j`$.
    #[must_use]
    pub fn coefficient_dot(&self, first: usize, second: usize) -> f64 {
        let displacement = match (self.displacement.get(first), self.displacement.get(second)) {
            (Some(left), Some(right)) => dot(left, right),
            _ => 0.0,
        };
        let load = self.load.get(first).copied().unwrap_or(0.0)
            * self.load.get(second).copied().unwrap_or(0.0);
        displacement + load
    }

    /// $`(U(a), \lambda(a))`$ by the Horner scheme.
    #[must_use]
    pub fn evaluate(&self, parameter: f64) -> (Vec<f64>, f64) {
        let mut displacement = vec![0.0; self.dimension()];
        for vector in self.displacement.iter().rev() {
            for (target, value) in displacement.iter_mut().zip(vector) {
                *target = *target * parameter + value;
            }
        }
        let load = self
            .load
            .iter()
            .rev()
            .fold(0.0, |accumulator, value| accumulator * parameter + value);
        (displacement, load)
    }

    /// $`(U'(a), \lambda'(a)) = \sum_{k=1}^{N} k a^{k-1} (U_k, \lambda_k)`$ by the Horner
    /// scheme.
    #[must_use]
    pub fn evaluate_derivative(&self, parameter: f64) -> (Vec<f64>, f64) {
        let mut displacement = vec![0.0; self.dimension()];
        for (order, vector) in self.displacement.iter().enumerate().skip(1).rev() {
            for (target, value) in displacement.iter_mut().zip(vector) {
                *target = *target * parameter + order as f64 * value;
            }
        }
        let load = self
            .load
            .iter()
            .enumerate()
            .skip(1)
            .rev()
            .fold(0.0, |accumulator, (order, value)| {
                accumulator * parameter + order as f64 * value
            });
        (displacement, load)
    }
}

/// The classical ANM step length (THEORY.md §10)
/// ```math
/// a_{\max} = \left(\varepsilon \,\frac{\lVert V_1 \rVert}{\lVert V_m \rVert}\right)^{1/(m-1)},
/// \qquad V_k = (U_k, \lambda_k),
/// ```
/// with $`m = N`$, or, when $`V_N = 0`$, the last order $`m \ge 2`$ with $`V_m \ne 0`$. It makes
/// the last retained term $`a^m V_m`$ smaller than $`\varepsilon`$ times the first-order term.
///
/// Special cases (never a panic):
/// * all $`V_k = 0`$ for $`k \ge 2`$ (or $`N \le 1`$): the series is linear and exact on the
///   whole line, `f64::INFINITY` is returned and the caller caps the step;
/// * $`V_1 = 0`$: `0.0`;
/// * `epsilon` not positive or not finite: `0.0`.
#[must_use]
pub fn series_step_length(series: &PathSeries, epsilon: f64) -> f64 {
    let norms: Vec<f64> = (0..=series.order())
        .map(|order| series.coefficient_norm(order))
        .collect();
    step_length_from_norms(&norms, epsilon)
}

/// The formula of [`series_step_length`] from the norms `norms[k]` $`= \lVert V_k\rVert`$,
/// $`k = 0, \dots, N`$.
pub(crate) fn step_length_from_norms(norms: &[f64], epsilon: f64) -> f64 {
    if !(epsilon > 0.0 && epsilon.is_finite()) {
        return 0.0;
    }
    let last_nonzero = norms
        .iter()
        .enumerate()
        .skip(2)
        .rev()
        .find(|(_, norm)| **norm > 0.0);
    let Some((last_order, &last_norm)) = last_nonzero else {
        return f64::INFINITY;
    };
    let first_norm = norms[1];
    if first_norm == 0.0 || !first_norm.is_finite() || !last_norm.is_finite() {
        return 0.0;
    }
    (epsilon * first_norm / last_norm).powf(1.0 / (last_order - 1) as f64)
}

/// Detects a geometric series in the last orders, the ANM signature of a nearby bifurcation
/// (or limit point): if $`V_k \approx c\,\rho^{-k} \varphi`$ then
/// $`\lVert V_{k+1} \rVert / \lVert V_k \rVert \to 1/\rho`$ and consecutive coefficients are
/// collinear. Returns the radius estimate
/// $`\rho \approx \lVert V_{N-1}\rVert / \lVert V_N \rVert`$ when
/// * $`N \ge 2`$ and $`V_{N-1} \neq 0`$, $`V_N \ne 0`$,
/// * $`\cos\angle(V_{N-1}, V_N) > `$ [`GEOMETRIC_COSINE_THRESHOLD`] (same direction: the
///   singularity lies ahead, at positive $`a = \rho`$; an alternating series, i.e. a
///   singularity at negative $`a`$, is not reported),
/// * for $`N \ge 3`$, the previous ratio $`\lVert V_{N-2}\rVert/\lVert V_{N-1}\rVert`$ agrees
///   with $`\rho`$ within the relative tolerance [`GEOMETRIC_RATIO_TOLERANCE`],
///
/// and `None` otherwise (e.g. for a polynomial whose last orders vanish).
#[must_use]
pub fn geometric_ratio(series: &PathSeries) -> Option<f64> {
    let order = series.order();
    if order < 2 {
        return None;
    }
    let last_norm = series.coefficient_norm(order);
    let previous_norm = series.coefficient_norm(order - 1);
    let usable = |norm: f64| norm > 0.0 && norm.is_finite();
    if !(usable(last_norm) && usable(previous_norm)) {
        return None;
    }
    let cosine = series.coefficient_dot(order - 1, order) / (previous_norm * last_norm);
    // Written so that a NaN cosine is rejected.
    let collinear = cosine > GEOMETRIC_COSINE_THRESHOLD;
    if !collinear {
        return None;
    }
    let radius = previous_norm / last_norm;
    if order >= 3 {
        let earlier_norm = series.coefficient_norm(order - 2);
        let earlier_radius = earlier_norm / previous_norm;
        let consistent = (earlier_radius - radius).abs() <= GEOMETRIC_RATIO_TOLERANCE * radius;
        if !consistent {
            return None;
        }
    }
    Some(radius)
}

/// The order $`N \ge 2`$ of a valid series.
pub(super) fn checked_order(series: &PathSeries) -> Result<usize, SeriesError> {
    series.validate()?;
    let order = series.order();
    if order < 2 {
        return Err(SeriesError::TooFewOrders {
            required: 2,
            found: order,
        });
    }
    Ok(order)
}
