//! Numbers: a finite float within bounds, a count, a number or `"auto"`.

use super::value::Scalar;
use crate::scene::text::{describe, short_number, toml_float};
use std::marker::PhantomData;
use toml::Value;

/// One end of an interval.
#[derive(Clone, Copy, Debug)]
pub enum Bound {
    /// No bound on this side.
    Unbounded,
    /// The end is excluded.
    Open(f64),
    /// The end is included.
    Closed(f64),
}

/// A finite float within bounds. Messages and documentation read `> 0`, `≥ 1`,
/// `-1 < ν < 0.5` (with a [`Float::named`] symbol) or `> 0 and at most 0.0001`.
#[derive(Clone, Copy, Debug)]
pub struct Float {
    lower: Bound,
    upper: Bound,
    symbol: &'static str,
    reason: &'static str,
}

impl Float {
    /// Any finite number.
    pub const fn finite() -> Self {
        Float {
            lower: Bound::Unbounded,
            upper: Bound::Unbounded,
            symbol: "",
            reason: "",
        }
    }

    /// A finite number $`> \text{minimum}`$.
    pub const fn above(minimum: f64) -> Self {
        Float {
            lower: Bound::Open(minimum),
            ..Float::finite()
        }
    }

    /// A finite number $`\ge \text{minimum}`$.
    pub const fn at_least(minimum: f64) -> Self {
        Float {
            lower: Bound::Closed(minimum),
            ..Float::finite()
        }
    }

    /// Also $`< \text{maximum}`$.
    pub const fn below(self, maximum: f64) -> Self {
        Float {
            upper: Bound::Open(maximum),
            ..self
        }
    }

    /// Also $`\le \text{maximum}`$.
    pub const fn at_most(self, maximum: f64) -> Self {
        Float {
            upper: Bound::Closed(maximum),
            ..self
        }
    }

    /// Names the value in the condition of a two-sided interval: `-1 < ν < 0.5`.
    pub const fn named(self, symbol: &'static str) -> Self {
        Float { symbol, ..self }
    }

    /// Why the bounds are what they are, quoted in the message and the documentation.
    pub const fn because(self, reason: &'static str) -> Self {
        Float { reason, ..self }
    }

    fn admits(&self, value: f64) -> bool {
        let above = match self.lower {
            Bound::Unbounded => true,
            Bound::Open(minimum) => value > minimum,
            Bound::Closed(minimum) => value >= minimum,
        };
        let below = match self.upper {
            Bound::Unbounded => true,
            Bound::Open(maximum) => value < maximum,
            Bound::Closed(maximum) => value <= maximum,
        };
        value.is_finite() && above && below
    }

    /// The condition, e.g. `> 0`, `-1 < ν < 0.5`, `> 0 and at most 0.0001`; empty when the
    /// number need only be finite.
    pub(super) fn condition(&self) -> String {
        // Bounds far from 1 read better as powers of ten (`1e-6`, not `0.000001`).
        let number = |value: f64| {
            let magnitude = value.abs();
            if magnitude >= 1e6 || (magnitude > 0.0 && magnitude < 1e-4) {
                format!("{value:e}")
            } else {
                short_number(value)
            }
        };
        if !self.symbol.is_empty() {
            let lower = match self.lower {
                Bound::Open(minimum) => format!("{} < ", number(minimum)),
                Bound::Closed(minimum) => format!("{} ≤ ", number(minimum)),
                Bound::Unbounded => String::new(),
            };
            let upper = match self.upper {
                Bound::Open(maximum) => format!(" < {}", number(maximum)),
                Bound::Closed(maximum) => format!(" ≤ {}", number(maximum)),
                Bound::Unbounded => String::new(),
            };
            return format!("{lower}{}{upper}", self.symbol);
        }
        let lower = match self.lower {
            Bound::Open(minimum) => Some(format!("> {}", number(minimum))),
            Bound::Closed(minimum) => Some(format!("≥ {}", number(minimum))),
            Bound::Unbounded => None,
        };
        let upper = match self.upper {
            Bound::Open(maximum) => Some(format!("< {}", number(maximum))),
            Bound::Closed(maximum) => Some(format!("at most {}", number(maximum))),
            Bound::Unbounded => None,
        };
        let parts: Vec<String> = lower.into_iter().chain(upper).collect();
        parts.join(" and ")
    }

    fn reason_text(&self) -> String {
        if self.reason.is_empty() {
            String::new()
        } else {
            format!(" ({})", self.reason)
        }
    }
}

impl Scalar for Float {
    type Value = f64;

    fn read(&self, value: &Value) -> Result<f64, String> {
        match value {
            Value::Float(number) => Ok(*number),
            Value::Integer(number) => Ok(*number as f64),
            other => Err(format!("expected a number, got {}", describe(other))),
        }
    }

    fn within_bounds(&self, value: &f64) -> Result<(), String> {
        if self.admits(*value) {
            return Ok(());
        }
        let (condition, got) = (self.condition(), short_number(*value));
        let reason = self.reason_text();
        Err(if condition.is_empty() {
            format!("must be a finite number{reason}, got {got}")
        } else if self.symbol.is_empty() {
            format!("must be {condition}{reason}, got {got}")
        } else {
            format!("must satisfy {condition}{reason}, got {got}")
        })
    }

    fn text(&self, value: &f64) -> String {
        toml_float(*value)
    }

    fn json_value(&self, value: &f64) -> serde_json::Value {
        serde_json::Value::from(*value)
    }

    fn bounds_text(&self) -> String {
        let condition = self.condition();
        let condition = if condition.is_empty() {
            "finite".to_string()
        } else {
            condition
        };
        format!("{condition}{}", self.reason_text())
    }
}

/// A non-negative integer (a count) between two bounds.
#[derive(Clone, Copy, Debug)]
pub struct Count {
    minimum: usize,
    maximum: usize,
}

impl Count {
    /// An integer in `minimum ..= maximum`.
    pub const fn between(minimum: usize, maximum: usize) -> Self {
        Count { minimum, maximum }
    }

    fn out_of_range(&self, got: impl std::fmt::Display) -> String {
        format!(
            "must be an integer between {} and {}, got {got}",
            self.minimum, self.maximum
        )
    }
}

impl Scalar for Count {
    type Value = usize;

    fn read(&self, value: &Value) -> Result<usize, String> {
        let Value::Integer(number) = value else {
            return Err(format!("expected an integer, got {}", describe(value)));
        };
        usize::try_from(*number)
            .ok()
            .filter(|count| (self.minimum..=self.maximum).contains(count))
            .ok_or_else(|| self.out_of_range(number))
    }

    fn within_bounds(&self, value: &usize) -> Result<(), String> {
        if (self.minimum..=self.maximum).contains(value) {
            Ok(())
        } else {
            Err(self.out_of_range(value))
        }
    }

    fn text(&self, value: &usize) -> String {
        value.to_string()
    }

    fn json_value(&self, value: &usize) -> serde_json::Value {
        serde_json::Value::from(*value)
    }

    fn bounds_text(&self) -> String {
        format!("integer {} … {}", self.minimum, self.maximum)
    }
}

/// A value that is either `"auto"` or a number ([`crate::scene::Wavenumber`]).
pub trait AutoOrNumber: Copy + Sync + 'static {
    /// The value `"auto"` stands for.
    const AUTO: Self;
    /// A prescribed number.
    fn fixed(number: f64) -> Self;
    /// The prescribed number, `None` for `"auto"`.
    fn number(self) -> Option<f64>;
}

/// A number within bounds, or `"auto"`.
pub struct NumberOrAuto<T> {
    number: Float,
    marker: PhantomData<fn() -> T>,
}

/// The kind of a key holding a number within `number`'s bounds, or `"auto"`.
pub const fn number_or_auto<T: AutoOrNumber>(number: Float) -> NumberOrAuto<T> {
    NumberOrAuto {
        number,
        marker: PhantomData,
    }
}

impl<T: AutoOrNumber> Scalar for NumberOrAuto<T> {
    type Value = T;

    fn read(&self, value: &Value) -> Result<T, String> {
        match value {
            Value::String(text) if text == "auto" => Ok(T::AUTO),
            Value::Integer(_) | Value::Float(_) => self.number.read(value).map(T::fixed),
            other => Err(format!(
                "expected a number {} or \"auto\", got {}",
                self.number.condition(),
                describe(other)
            )),
        }
    }

    fn within_bounds(&self, value: &T) -> Result<(), String> {
        value
            .number()
            .map_or(Ok(()), |number| self.number.within_bounds(&number))
    }

    fn text(&self, value: &T) -> String {
        value
            .number()
            .map_or_else(|| "\"auto\"".to_string(), toml_float)
    }

    fn unit_applies(&self, value: &T) -> bool {
        value.number().is_some()
    }

    fn json_value(&self, value: &T) -> serde_json::Value {
        value
            .number()
            .map_or_else(|| serde_json::Value::from("auto"), serde_json::Value::from)
    }

    fn bounds_text(&self) -> String {
        format!("{} or `\"auto\"`", self.number.bounds_text())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn message(kind: &Float, value: f64) -> String {
        kind.within_bounds(&value).unwrap_err()
    }

    #[test]
    fn float_bounds_read_as_the_scene_errors_always_did() {
        assert_eq!(message(&Float::above(0.0), -1.0), "must be > 0, got -1");
        assert_eq!(message(&Float::at_least(1.0), 0.5), "must be ≥ 1, got 0.5");
        let finite = Float::finite();
        assert_eq!(
            message(&finite, f64::NAN),
            "must be a finite number, got NaN"
        );
        let poisson = Float::above(-1.0).below(0.5).named("ν");
        assert_eq!(message(&poisson, 0.6), "must satisfy -1 < ν < 0.5, got 0.6");
        let tolerance = Float::above(0.0).at_most(1e-4).because("why");
        assert_eq!(
            message(&tolerance, 1e300),
            "must be > 0 and at most 0.0001 (why), got 1e300"
        );
        assert!(Float::above(0.0).within_bounds(&f64::INFINITY).is_err());
        assert!(tolerance.within_bounds(&1e-4).is_ok());
    }

    #[test]
    fn counts_name_their_range() {
        let count = Count::between(2, 40);
        assert_eq!(
            count.read(&Value::Integer(41)).unwrap_err(),
            "must be an integer between 2 and 40, got 41"
        );
        assert_eq!(
            Count::between(1, 10).within_bounds(&0).unwrap_err(),
            "must be an integer between 1 and 10, got 0"
        );
        assert_eq!(
            count.read(&Value::Float(2.5)).unwrap_err(),
            "expected an integer, got float 2.5"
        );
    }
}
