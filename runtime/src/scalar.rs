//! The scalar abstraction every generated kernel is generic over.
//!
//! Generated energy, residual and tangent kernels are straight-line code written against
//! [`Scalar`]. The same code therefore runs on
//! * `f64` (production assembly),
//! * `num-dual` numbers (`Dual64`, `HyperDual64`, …; independent derivative checks and the
//!   directional derivative of the tangent used as geometric stiffness),
//! * the truncated Taylor series of the Asymptotic Numerical Method.
//!
//! Conventions the code generator follows (and that implementors may rely on):
//! * a constant or a parameter-only sub-expression is an `f64` and always appears on the
//!   **right** of a mixed operation (`x * c`, `x + c`, `x - c`, `x / c`), never `c * x`
//!   (num-dual implements only the former);
//! * `c - x` is emitted as `-x + c`, and `c / x` as `x.recip() * c`.

use std::fmt::Debug;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// A number type the generated kernels can run on.
///
/// $`\mathbb{S}`$ must be a commutative ring over $`\mathbb{R}`$ with a reciprocal; `real`
/// returns the value part (the order-0 coefficient for series and dual numbers).
pub trait Scalar:
    Copy
    + Debug
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<Output = Self>
    + Div<Output = Self>
    + Neg<Output = Self>
    + Add<f64, Output = Self>
    + Sub<f64, Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
{
    /// Embeds a real constant.
    fn from_f64(value: f64) -> Self;
    /// The value part: the number itself for `f64`, the real part of a dual number, the
    /// order-0 coefficient of a series.
    fn real(&self) -> f64;
    /// $`x^{-1}`$.
    fn recip(&self) -> Self;
    /// $`x^n`$ for an integer `n` (negative allowed).
    fn powi(&self, n: i32) -> Self {
        if n < 0 {
            return self.powi(-n).recip();
        }
        // Binary exponentiation: exact for the small integer powers energies use.
        let mut result = Self::from_f64(1.0);
        let mut base = *self;
        let mut k = n as u32;
        while k > 0 {
            if k & 1 == 1 {
                result = result * base;
            }
            k >>= 1;
            if k > 0 {
                base = base * base;
            }
        }
        result
    }
    /// $`0`$.
    fn zero() -> Self {
        Self::from_f64(0.0)
    }
}

/// Every `num-dual` number over `f64` (and `f64` itself, which is a `DualNum`) is a [`Scalar`].
impl<T> Scalar for T
where
    T: num_dual::DualNum<Primitive = f64> + Copy + Send + Sync,
{
    #[inline(always)]
    fn from_f64(value: f64) -> Self {
        T::from(value)
    }
    #[inline(always)]
    fn real(&self) -> f64 {
        self.re()
    }
    #[inline(always)]
    fn recip(&self) -> Self {
        num_dual::DualNum::recip(self)
    }
    #[inline(always)]
    fn powi(&self, n: i32) -> Self {
        num_dual::DualNum::powi(self, n)
    }
}
