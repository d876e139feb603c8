//! Labels of physical quantities as data: what a number is, its symbol and its unit. Every axis,
//! colour bar, table cell and progress line of the outputs is labelled from a [`Quantity`] that
//! the caller passes, so the writers know nothing about a particular model or load.

use std::fmt;

/// A named physical quantity: `description` (`"physical deflection"`), `symbol` (`"w"`) and
/// `unit` (`"mm"`, empty for a ratio such as $`\max|w|/h`$).
///
/// [`Quantity::axis_title`] gives `"physical deflection w (mm)"`.
#[derive(Clone, Debug, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub struct Quantity {
    /// Words, e.g. `"load"`; may be empty.
    pub description: String,
    /// Symbol, e.g. `"λ = −N_X"`; may be empty.
    pub symbol: String,
    /// Unit, e.g. `"N/mm"`; empty for a dimensionless quantity.
    pub unit: String,
}

impl Quantity {
    /// A quantity from its three parts.
    pub fn new(
        description: impl Into<String>,
        symbol: impl Into<String>,
        unit: impl Into<String>,
    ) -> Self {
        Quantity {
            description: description.into(),
            symbol: symbol.into(),
            unit: unit.into(),
        }
    }

    /// The load of the biaxial case, $`\lambda = -N_X`$ in N/mm (compression positive).
    pub fn biaxial_load() -> Self {
        Quantity::new("load", "λ = −N_X", "N/mm")
    }

    /// The load of a strip pulled by its ends: $`\lambda`$ = the end displacement in mm.
    pub fn end_displacement() -> Self {
        Quantity::new("end displacement", "λ", "mm")
    }

    /// The physical deflection $`w`$ in mm (for envelope models, twice the envelope times the
    /// carrier wave, THEORY §3).
    pub fn deflection() -> Self {
        Quantity::new("physical deflection", "w", "mm")
    }

    /// The physical deflection over the thickness, $`w/h`$ (dimensionless).
    pub fn deflection_over_thickness() -> Self {
        Quantity::new("physical deflection", "w / h", "")
    }

    /// The largest physical amplitude over the thickness, $`\max|w|/h`$ (dimensionless).
    pub fn max_amplitude_over_thickness() -> Self {
        Quantity::new("physical amplitude", "max |w| / h", "")
    }

    /// The local physical amplitude at the centre over the thickness (dimensionless).
    pub fn centre_amplitude_over_thickness() -> Self {
        Quantity::new("amplitude at the centre", "|w| / h", "")
    }

    /// A coordinate in mm, e.g. `Quantity::coordinate("X")`.
    pub fn coordinate(symbol: impl Into<String>) -> Self {
        Quantity::new("", symbol, "mm")
    }

    /// Description and symbol, e.g. `"load λ = −N_X"`.
    pub fn name(&self) -> String {
        match (self.description.is_empty(), self.symbol.is_empty()) {
            (false, false) => format!("{} {}", self.description, self.symbol),
            (false, true) => self.description.clone(),
            (true, _) => self.symbol.clone(),
        }
    }

    /// `"name (unit)"`, or the name alone when the quantity is dimensionless.
    pub fn axis_title(&self) -> String {
        if self.unit.is_empty() {
            self.name()
        } else {
            format!("{} ({})", self.name(), self.unit)
        }
    }

    /// The shortest label: the symbol if any, else the description.
    pub fn short_name(&self) -> &str {
        if self.symbol.is_empty() {
            &self.description
        } else {
            &self.symbol
        }
    }

    /// `value` with five significant digits and the unit, e.g. `"0.089521 N/mm"`.
    pub fn format_value(&self, value: f64) -> String {
        let number = format_significant(value, 5);
        if self.unit.is_empty() {
            number
        } else {
            format!("{number} {}", self.unit)
        }
    }
}

impl fmt::Display for Quantity {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        formatter.write_str(&self.axis_title())
    }
}

/// `value` rounded to `digits` significant digits, in plain decimal notation for magnitudes in
/// $`[10^{-4}, 10^{6})`$ and scientific notation otherwise; trailing zeros are kept (they are
/// significant).
pub fn format_significant(value: f64, digits: usize) -> String {
    let digits = digits.max(1);
    if value == 0.0 {
        return "0".to_string();
    }
    if !value.is_finite() {
        return format!("{value}");
    }
    let magnitude = value.abs();
    if !(1e-4..1e6).contains(&magnitude) {
        return format!("{:.*e}", digits - 1, value);
    }
    let exponent = magnitude.log10().floor() as i32;
    let decimals = (digits as i32 - 1 - exponent).max(0) as usize;
    let text = format!("{value:.decimals$}");
    // Rounding may carry into one more digit (9.99996 → 10.0000): drop one decimal then.
    let significant = text
        .trim_start_matches('-')
        .trim_start_matches(['0', '.'])
        .chars()
        .filter(char::is_ascii_digit)
        .count();
    if significant > digits && decimals > 0 {
        format!("{value:.*}", decimals - 1)
    } else {
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn titles_have_units_unless_dimensionless() {
        assert_eq!(
            Quantity::biaxial_load().axis_title(),
            "load λ = −N_X (N/mm)"
        );
        assert_eq!(
            Quantity::max_amplitude_over_thickness().axis_title(),
            "physical amplitude max |w| / h"
        );
        assert_eq!(Quantity::coordinate("X").axis_title(), "X (mm)");
    }

    #[test]
    fn significant_digits() {
        assert_eq!(format_significant(0.0895213338, 5), "0.089521");
        assert_eq!(format_significant(2.0, 3), "2.00");
        assert_eq!(format_significant(-123.456, 4), "-123.5");
        assert_eq!(format_significant(9.99996, 5), "10.000");
        assert_eq!(format_significant(1.5e-7, 3), "1.50e-7");
        assert_eq!(
            Quantity::biaxial_load().format_value(0.0895213),
            "0.089521 N/mm"
        );
    }
}
