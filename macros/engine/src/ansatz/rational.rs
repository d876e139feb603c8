//! Exact rational numbers, the numeric coefficients of the derivation's polynomials.
//!
//! A derivation multiplies literals of the microscopic energy (`0.5`, `12`), binomial
//! coefficients, harmonic indices and factors `2`: exact fractions keep cancellations exact
//! (an imaginary part that must vanish vanishes, a null Lagrangian cancels to the constant 0) and
//! print as written (`1/12`, not `0.08333333333333333`). Numerator and denominator are `i128`;
//! an overflow is an internal limit (a panic of the macro with a message), far beyond the
//! literals and products of an energy density.

use std::cmp::Ordering;
use std::fmt;

/// $`p/q`$ in lowest terms, $`q > 0`$.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Rational {
    numerator: i128,
    denominator: i128,
}

fn greatest_common_divisor(mut a: i128, mut b: i128) -> i128 {
    a = a.abs();
    b = b.abs();
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a
}

const OVERFLOW: &str =
    "rational coefficient overflow in the ansatz derivation (numerator or denominator beyond i128)";

impl Rational {
    /// $`0`$.
    pub const ZERO: Rational = Rational {
        numerator: 0,
        denominator: 1,
    };
    /// $`1`$.
    pub const ONE: Rational = Rational {
        numerator: 1,
        denominator: 1,
    };

    /// $`p/q`$ reduced; panics if $`q = 0`$.
    pub fn new(numerator: i128, denominator: i128) -> Rational {
        assert!(denominator != 0, "rational with a zero denominator");
        let divisor = greatest_common_divisor(numerator, denominator).max(1);
        let sign = if denominator < 0 { -1 } else { 1 };
        Rational {
            numerator: sign * numerator / divisor,
            denominator: sign * denominator / divisor,
        }
    }

    /// The integer $`n`$.
    pub fn integer(value: i128) -> Rational {
        Rational {
            numerator: value,
            denominator: 1,
        }
    }

    /// The exact value of a decimal literal's digits as `syn` gives them (`"0.5"`, `"12"`,
    /// `"1e-3"`, `"2.5E2"`); `None` if it is not a finite decimal or does not fit.
    pub fn from_decimal(digits: &str) -> Option<Rational> {
        let (mantissa, exponent) = match digits.find(['e', 'E']) {
            Some(at) => (&digits[..at], digits[at + 1..].parse::<i32>().ok()?),
            None => (digits, 0),
        };
        let (whole, fraction) = mantissa.split_once('.').unwrap_or((mantissa, ""));
        let all: String = format!("{whole}{fraction}");
        if all.is_empty() || !all.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let numerator: i128 = all.trim_start_matches('0').parse().unwrap_or(0);
        let scale = exponent - i32::try_from(fraction.len()).ok()?;
        let power = 10_i128.checked_pow(scale.unsigned_abs())?;
        Some(if scale >= 0 {
            Rational::integer(numerator.checked_mul(power)?)
        } else {
            Rational::new(numerator, power)
        })
    }

    /// Numerator (carries the sign).
    pub fn numerator(self) -> i128 {
        self.numerator
    }

    /// Denominator (positive).
    pub fn denominator(self) -> i128 {
        self.denominator
    }

    /// Whether the value is $`0`$.
    pub fn is_zero(self) -> bool {
        self.numerator == 0
    }

    /// Whether the value is an integer.
    pub fn is_integer(self) -> bool {
        self.denominator == 1
    }

    /// The nearest `f64`.
    pub fn to_f64(self) -> f64 {
        self.numerator as f64 / self.denominator as f64
    }

    /// $`1/x`$; panics on zero.
    pub fn reciprocal(self) -> Rational {
        Rational::new(self.denominator, self.numerator)
    }

    /// $`x^n`$, $`n \ge 0`$.
    pub fn power(self, exponent: u32) -> Rational {
        (0..exponent).fold(Rational::ONE, |product, _| product * self)
    }
}

impl std::ops::Add for Rational {
    type Output = Rational;
    fn add(self, other: Rational) -> Rational {
        let divisor = greatest_common_divisor(self.denominator, other.denominator);
        let left = other.denominator / divisor;
        let right = self.denominator / divisor;
        let numerator = self
            .numerator
            .checked_mul(left)
            .and_then(|a| {
                other
                    .numerator
                    .checked_mul(right)
                    .and_then(|b| a.checked_add(b))
            })
            .expect(OVERFLOW);
        let denominator = self.denominator.checked_mul(left).expect(OVERFLOW);
        Rational::new(numerator, denominator)
    }
}

impl std::ops::Neg for Rational {
    type Output = Rational;
    fn neg(self) -> Rational {
        Rational {
            numerator: -self.numerator,
            denominator: self.denominator,
        }
    }
}

impl std::ops::Sub for Rational {
    type Output = Rational;
    fn sub(self, other: Rational) -> Rational {
        self + (-other)
    }
}

impl std::ops::Mul for Rational {
    type Output = Rational;
    fn mul(self, other: Rational) -> Rational {
        // Cross-reduce first to keep the products small.
        let a = greatest_common_divisor(self.numerator, other.denominator).max(1);
        let b = greatest_common_divisor(other.numerator, self.denominator).max(1);
        let numerator = (self.numerator / a)
            .checked_mul(other.numerator / b)
            .expect(OVERFLOW);
        let denominator = (self.denominator / b)
            .checked_mul(other.denominator / a)
            .expect(OVERFLOW);
        Rational::new(numerator, denominator)
    }
}

impl Ord for Rational {
    fn cmp(&self, other: &Rational) -> Ordering {
        let left = self
            .numerator
            .checked_mul(other.denominator)
            .expect(OVERFLOW);
        let right = other
            .numerator
            .checked_mul(self.denominator)
            .expect(OVERFLOW);
        left.cmp(&right)
    }
}

impl PartialOrd for Rational {
    fn partial_cmp(&self, other: &Rational) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl fmt::Display for Rational {
    /// `3`, `-1/12`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.denominator == 1 {
            write!(f, "{}", self.numerator)
        } else {
            write!(f, "{}/{}", self.numerator, self.denominator)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn arithmetic_is_exact_and_reduced() {
        let half = Rational::new(1, 2);
        let third = Rational::new(-2, -6);
        assert_eq!(half + third, Rational::new(5, 6));
        assert_eq!(half - half, Rational::ZERO);
        assert_eq!(half * Rational::integer(4), Rational::integer(2));
        assert_eq!(Rational::new(3, -9), Rational::new(-1, 3));
        assert_eq!(Rational::new(-1, 3).reciprocal(), Rational::integer(-3));
        assert_eq!(half.power(3), Rational::new(1, 8));
        assert!(Rational::new(-1, 3) < Rational::ZERO);
        assert_eq!(Rational::new(-1, 12).to_string(), "-1/12");
    }

    #[test]
    fn decimal_literals_convert_exactly() {
        assert_eq!(Rational::from_decimal("0.5"), Some(Rational::new(1, 2)));
        assert_eq!(Rational::from_decimal("12"), Some(Rational::integer(12)));
        assert_eq!(Rational::from_decimal("1e-3"), Some(Rational::new(1, 1000)));
        assert_eq!(
            Rational::from_decimal("2.5E2"),
            Some(Rational::integer(250))
        );
        assert_eq!(Rational::from_decimal("0.125"), Some(Rational::new(1, 8)));
        assert_eq!(Rational::from_decimal("1e400"), None);
    }
}
