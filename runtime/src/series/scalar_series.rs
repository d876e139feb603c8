//! The scalar truncated Taylor series [`Series`].

use std::ops::{Add, Div, Mul, Neg, Sub};

use super::SeriesError;
use crate::Scalar;

/// Capacity of a [`Series`]: ANM orders up to 40 need 41 coefficients $`x_0, \dots, x_{40}`$.
pub const MAX_SERIES_LEN: usize = 42;

/// A truncated power series $`x(a) = \sum_{k=0}^{n-1} x_k a^k`$ in the path parameter $`a`$,
/// with $`n`$ = [`Series::len`] live coefficients ($`1 \le n \le`$ [`MAX_SERIES_LEN`]).
///
/// Arithmetic is exact on the live orders: the result of a binary operation has the larger
/// of the two lengths $`n = \max(n_x, n_y)`$ and its coefficients are the Taylor coefficients
/// of orders $`0, \dots, n-1`$ of the exact result (the shorter operand is padded with zero
/// coefficients, i.e. it is taken as a polynomial). In particular
/// * $`(x y)_k = \sum_{j=0}^{k} x_j y_{k-j}`$ (Cauchy product, only over live coefficients),
/// * $`(x / y)_k = \big(x_k - \sum_{j=0}^{k-1} (x/y)_j\, y_{k-j}\big) / y_0`$.
///
/// Division by a series with $`y_0 = 0`$ is not defined as a power series: the coefficients
/// then become infinite or NaN (IEEE semantics), exactly like `f64` division by zero; no
/// panic occurs.
///
/// The value is `Copy` and lives entirely on the stack (no heap allocation), so it can be
/// used at every quadrature point of a kernel evaluation. Coefficients beyond the live
/// length are kept at zero and never read.
#[derive(Clone, Copy, Debug)]
pub struct Series {
    coefficients: [f64; MAX_SERIES_LEN],
    len: usize,
}

impl Default for Series {
    /// The zero series of length 1.
    fn default() -> Self {
        Self::constant(0.0, 1)
    }
}

impl Series {
    /// The constant series $`x(a) = c`$ with `len` live coefficients
    /// $`(c, 0, \dots, 0)`$. `len` is clamped into $`1..=`$ [`MAX_SERIES_LEN`].
    #[inline]
    #[must_use]
    pub fn constant(value: f64, len: usize) -> Self {
        let mut coefficients = [0.0; MAX_SERIES_LEN];
        coefficients[0] = value;
        Self {
            coefficients,
            len: len.clamp(1, MAX_SERIES_LEN),
        }
    }

    /// The zero series with `len` live coefficients (clamped into $`1..=`$
    /// [`MAX_SERIES_LEN`]).
    #[inline]
    #[must_use]
    pub fn zeros(len: usize) -> Self {
        Self::constant(0.0, len)
    }

    /// The series $`x_0 + x_1 a`$ (the path parameter itself when $`x_0 = 0`$, $`x_1 = 1`$)
    /// with `len` live coefficients (clamped into $`2..=`$ [`MAX_SERIES_LEN`]).
    #[inline]
    #[must_use]
    pub fn linear(value: f64, slope: f64, len: usize) -> Self {
        let mut series = Self::constant(value, len.max(2));
        series.coefficients[1] = slope;
        series
    }

    /// The series whose coefficients are `coefficients` ($`x_k`$ = `coefficients[k]`).
    ///
    /// # Errors
    /// [`SeriesError::LengthOutOfRange`] if the slice is empty or longer than
    /// [`MAX_SERIES_LEN`].
    pub fn from_coefficients(coefficients: &[f64]) -> Result<Self, SeriesError> {
        let len = coefficients.len();
        if len == 0 || len > MAX_SERIES_LEN {
            return Err(SeriesError::LengthOutOfRange {
                requested: len,
                maximum: MAX_SERIES_LEN,
            });
        }
        let mut series = Self::zeros(len);
        series.coefficients[..len].copy_from_slice(coefficients);
        Ok(series)
    }

    /// The number of live coefficients $`n`$ (orders $`0, \dots, n-1`$).
    #[inline]
    #[must_use]
    pub fn len(&self) -> usize {
        self.len
    }

    /// Always `false`: a series has at least one live coefficient. Provided for API symmetry
    /// with [`Series::len`].
    #[inline]
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// The coefficient $`x_k`$; zero for $`k \ge n`$ (truncated orders are zero).
    #[inline]
    #[must_use]
    pub fn coefficient(&self, order: usize) -> f64 {
        if order < self.len {
            self.coefficients[order]
        } else {
            0.0
        }
    }

    /// The live coefficients $`(x_0, \dots, x_{n-1})`$.
    #[inline]
    #[must_use]
    pub fn coefficients(&self) -> &[f64] {
        &self.coefficients[..self.len]
    }

    /// Mutable access to the live coefficients $`(x_0, \dots, x_{n-1})`$.
    #[inline]
    pub fn coefficients_mut(&mut self) -> &mut [f64] {
        &mut self.coefficients[..self.len]
    }

    /// Sets $`x_k`$ = `value`.
    ///
    /// # Errors
    /// [`SeriesError::CoefficientOutOfRange`] if $`k \ge n`$ (grow the series with
    /// [`Series::set_len`] first).
    pub fn set_coefficient(&mut self, order: usize, value: f64) -> Result<(), SeriesError> {
        if order >= self.len {
            return Err(SeriesError::CoefficientOutOfRange {
                index: order,
                len: self.len,
            });
        }
        self.coefficients[order] = value;
        Ok(())
    }

    /// Changes the number of live coefficients. Growing appends zero coefficients; shrinking
    /// truncates (the dropped coefficients are reset to zero).
    ///
    /// # Errors
    /// [`SeriesError::LengthOutOfRange`] if `len` is 0 or exceeds [`MAX_SERIES_LEN`].
    pub fn set_len(&mut self, len: usize) -> Result<(), SeriesError> {
        if len == 0 || len > MAX_SERIES_LEN {
            return Err(SeriesError::LengthOutOfRange {
                requested: len,
                maximum: MAX_SERIES_LEN,
            });
        }
        if len < self.len {
            self.coefficients[len..self.len].fill(0.0);
        }
        self.len = len;
        Ok(())
    }

    /// The truncated sum $`\sum_{k=0}^{n-1} x_k a^k`$ (Horner scheme).
    #[inline]
    #[must_use]
    pub fn evaluate(&self, parameter: f64) -> f64 {
        self.coefficients()
            .iter()
            .rev()
            .fold(0.0, |accumulator, &coefficient| {
                accumulator * parameter + coefficient
            })
    }

    /// The derivative series $`x'(a) = \sum_{k=0}^{n-2} (k+1) x_{k+1} a^k`$ (length
    /// $`\max(n-1, 1)`$).
    #[must_use]
    pub fn derivative(&self) -> Self {
        let mut result = Self::zeros(self.len.saturating_sub(1));
        for order in 1..self.len {
            result.coefficients[order - 1] = order as f64 * self.coefficients[order];
        }
        result
    }

    /// $`x^2`$, using the symmetry of the Cauchy product (about half the multiplications
    /// of `x * x`).
    #[inline]
    #[must_use]
    pub fn square(&self) -> Self {
        let len = self.len;
        let x = &self.coefficients;
        let mut result = Self::zeros(len);
        for order in 0..len {
            let mut sum = 0.0;
            // Pairs (j, order - j) with j < order - j, counted twice.
            let half = order.div_ceil(2);
            for j in 0..half {
                sum += x[j] * x[order - j];
            }
            sum *= 2.0;
            if order % 2 == 0 {
                let middle = x[order / 2];
                sum += middle * middle;
            }
            result.coefficients[order] = sum;
        }
        result
    }

    /// $`1/x`$: $`r_0 = 1/x_0`$, $`r_k = -\big(\sum_{j=0}^{k-1} r_j x_{k-j}\big)/x_0`$.
    /// Infinite/NaN coefficients when $`x_0 = 0`$ (see the type documentation).
    #[inline]
    #[must_use]
    pub fn reciprocal(&self) -> Self {
        divide(&Self::constant(1.0, 1), self)
    }

    /// $`x^m`$ by binary exponentiation.
    fn power(&self, exponent: u32) -> Self {
        let mut result = Self::constant(1.0, self.len);
        let mut base = *self;
        let mut remaining = exponent;
        while remaining > 0 {
            if remaining & 1 == 1 {
                result = multiply(&result, &base);
            }
            remaining >>= 1;
            if remaining > 0 {
                base = base.square();
            }
        }
        result
    }

    /// Multiplies every live coefficient by `factor`.
    #[inline]
    fn scaled(mut self, factor: f64) -> Self {
        for coefficient in self.coefficients_mut() {
            *coefficient *= factor;
        }
        self
    }
}

/// The Cauchy product truncated at $`\max(n_x, n_y)`$, summing only over live coefficients.
#[inline]
fn multiply(left: &Series, right: &Series) -> Series {
    if left.len == 1 {
        return right.scaled(left.coefficients[0]);
    }
    if right.len == 1 {
        return left.scaled(right.coefficients[0]);
    }
    let len = left.len.max(right.len);
    let x = &left.coefficients;
    let y = &right.coefficients;
    let mut result = Series::zeros(len);
    for order in 0..len {
        // x_j is live for j < n_x, y_{order-j} is live for order - j < n_y.
        let first = (order + 1).saturating_sub(right.len);
        let last = order.min(left.len - 1);
        let mut sum = 0.0;
        for j in first..=last {
            sum += x[j] * y[order - j];
        }
        result.coefficients[order] = sum;
    }
    result
}

/// The quotient recurrence truncated at $`\max(n_x, n_y)`$.
#[inline]
fn divide(numerator: &Series, denominator: &Series) -> Series {
    if denominator.len == 1 {
        let divisor = denominator.coefficients[0];
        let mut result = *numerator;
        for coefficient in result.coefficients_mut() {
            *coefficient /= divisor;
        }
        return result;
    }
    let len = numerator.len.max(denominator.len);
    let y = &denominator.coefficients;
    let y0 = y[0];
    let mut result = Series::zeros(len);
    for order in 0..len {
        // y_{order-j} is live for order - j < n_y, i.e. j > order - n_y.
        let first = (order + 1).saturating_sub(denominator.len);
        let mut sum = numerator.coefficients[order];
        for j in first..order {
            sum -= result.coefficients[j] * y[order - j];
        }
        result.coefficients[order] = sum / y0;
    }
    result
}

impl Add for Series {
    type Output = Series;
    #[inline]
    fn add(self, right: Series) -> Series {
        let (mut result, other) = if self.len >= right.len {
            (self, right)
        } else {
            (right, self)
        };
        for (target, source) in result.coefficients[..other.len]
            .iter_mut()
            .zip(&other.coefficients[..other.len])
        {
            *target += source;
        }
        result
    }
}

impl Sub for Series {
    type Output = Series;
    #[inline]
    fn sub(self, right: Series) -> Series {
        let len = self.len.max(right.len);
        let mut result = self;
        result.len = len;
        for (target, source) in result.coefficients[..right.len]
            .iter_mut()
            .zip(&right.coefficients[..right.len])
        {
            *target -= source;
        }
        result
    }
}

impl Mul for Series {
    type Output = Series;
    #[inline]
    fn mul(self, right: Series) -> Series {
        multiply(&self, &right)
    }
}

impl Div for Series {
    type Output = Series;
    #[inline]
    fn div(self, right: Series) -> Series {
        divide(&self, &right)
    }
}

impl Neg for Series {
    type Output = Series;
    #[inline]
    fn neg(self) -> Series {
        self.scaled(-1.0)
    }
}

impl Add<f64> for Series {
    type Output = Series;
    #[inline]
    fn add(mut self, right: f64) -> Series {
        self.coefficients[0] += right;
        self
    }
}

impl Sub<f64> for Series {
    type Output = Series;
    #[inline]
    fn sub(mut self, right: f64) -> Series {
        self.coefficients[0] -= right;
        self
    }
}

impl Mul<f64> for Series {
    type Output = Series;
    #[inline]
    fn mul(self, right: f64) -> Series {
        self.scaled(right)
    }
}

impl Div<f64> for Series {
    type Output = Series;
    #[inline]
    fn div(mut self, right: f64) -> Series {
        for coefficient in self.coefficients_mut() {
            *coefficient /= right;
        }
        self
    }
}

impl Scalar for Series {
    /// The constant series of length 1 (it grows when combined with longer series).
    #[inline]
    fn from_f64(value: f64) -> Self {
        Self::constant(value, 1)
    }

    /// The order-0 coefficient $`x_0 = x(0)`$.
    #[inline]
    fn real(&self) -> f64 {
        self.coefficients[0]
    }

    #[inline]
    fn recip(&self) -> Self {
        self.reciprocal()
    }

    /// Specialised for $`n \in \{0, 1, 2, -1\}`$ (a square costs about half a product),
    /// binary exponentiation otherwise.
    #[inline]
    fn powi(&self, exponent: i32) -> Self {
        match exponent {
            0 => Self::constant(1.0, self.len),
            1 => *self,
            2 => self.square(),
            -1 => self.reciprocal(),
            _ if exponent < 0 => self.power(exponent.unsigned_abs()).reciprocal(),
            _ => self.power(exponent.unsigned_abs()),
        }
    }

    #[inline]
    fn zero() -> Self {
        Self::constant(0.0, 1)
    }
}
