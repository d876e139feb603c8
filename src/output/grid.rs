//! A scalar field sampled on a regular grid of points over a rectangle ([`GridField`]): the
//! physical deflection for the wrinkle map ([`super::plot_wrinkle_map`]) and the surface file
//! ([`super::write_surface_vtu`]). The caller samples; the writers only draw and format.

use super::quantity::Quantity;
use super::{check_length, invalid};
use std::io;

/// Values of one quantity at the points of a regular `columns × rows` grid covering
/// `bounds = [x0, x1, y0, y1]` (mm), edges included:
/// $`X_i = x_0 + i\,(x_1 - x_0)/(\text{columns} - 1)`$,
/// $`Y_j = y_0 + j\,(y_1 - y_0)/(\text{rows} - 1)`$, value of point $`(i, j)`$ at
/// `values[j * columns + i]`.
#[derive(Clone, Debug, PartialEq)]
pub struct GridField {
    /// What the values are (labels the colour bar; its symbol names the VTU array).
    pub quantity: Quantity,
    /// `[x0, x1, y0, y1]`, finite with `x0 < x1`, `y0 < y1`.
    pub bounds: [f64; 4],
    /// Points along $`X`$ (at least 2).
    pub columns: usize,
    /// Points along $`Y`$ (at least 2).
    pub rows: usize,
    /// `columns × rows` values, row after row (constant $`Y`$ in a row).
    pub values: Vec<f64>,
}

impl GridField {
    /// Samples `value(X, Y)` at the grid points.
    pub fn sample(
        quantity: Quantity,
        bounds: [f64; 4],
        columns: usize,
        rows: usize,
        value: impl Fn(f64, f64) -> f64,
    ) -> Self {
        let mut field = GridField {
            quantity,
            bounds,
            columns,
            rows,
            values: Vec::with_capacity(columns * rows),
        };
        for j in 0..rows {
            for i in 0..columns {
                let [x, y] = field.point(i, j);
                field.values.push(value(x, y));
            }
        }
        field
    }

    /// Coordinates of grid point $`(i, j)`$.
    pub fn point(&self, i: usize, j: usize) -> [f64; 2] {
        let [x0, x1, y0, y1] = self.bounds;
        let fraction = |k: usize, n: usize| {
            if n > 1 {
                k as f64 / (n - 1) as f64
            } else {
                0.0
            }
        };
        [
            x0 + (x1 - x0) * fraction(i, self.columns),
            y0 + (y1 - y0) * fraction(j, self.rows),
        ]
    }

    /// $`\max |v|`$ over the finite values (0 when there are none).
    pub fn max_abs(&self) -> f64 {
        self.values
            .iter()
            .filter(|v| v.is_finite())
            .fold(0.0, |m, v| m.max(v.abs()))
    }

    /// The grid point of largest $`|v|`$: `(i, j, value)`; `None` when no value is finite.
    pub fn max_abs_point(&self) -> Option<(usize, usize, f64)> {
        let (index, value) = self
            .values
            .iter()
            .enumerate()
            .filter(|(_, v)| v.is_finite())
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
        Some((index % self.columns, index / self.columns, *value))
    }

    /// Bilinear interpolation at normalised coordinates $`(s, t) \in [0, 1]^2`$ of the
    /// rectangle. A sample that is NaN marks a point outside the domain (a hole, or beyond a
    /// curved outline): where the nearest of the four samples is NaN the result is NaN; where
    /// only others are, the finite ones are weighted alone (their bilinear weights rescaled to
    /// sum to 1), so that the domain's edge is not eaten by a cell's width.
    pub(crate) fn interpolate_normalised(&self, s: f64, t: f64) -> f64 {
        let u = s.clamp(0.0, 1.0) * (self.columns - 1) as f64;
        let v = t.clamp(0.0, 1.0) * (self.rows - 1) as f64;
        let (i, j) = (
            (u.floor() as usize).min(self.columns - 2),
            (v.floor() as usize).min(self.rows - 2),
        );
        let (a, b) = (u - i as f64, v - j as f64);
        let at = |i: usize, j: usize| self.values[j * self.columns + i];
        let corners = [
            (at(i, j), (1.0 - a) * (1.0 - b)),
            (at(i + 1, j), a * (1.0 - b)),
            (at(i, j + 1), (1.0 - a) * b),
            (at(i + 1, j + 1), a * b),
        ];
        if corners.iter().all(|(value, _)| !value.is_nan()) {
            return (1.0 - b) * ((1.0 - a) * at(i, j) + a * at(i + 1, j))
                + b * ((1.0 - a) * at(i, j + 1) + a * at(i + 1, j + 1));
        }
        let nearest = at(i + usize::from(a > 0.5), j + usize::from(b > 0.5));
        if nearest.is_nan() {
            return f64::NAN;
        }
        let (sum, weight) = corners
            .iter()
            .filter(|(value, _)| !value.is_nan())
            .fold((0.0, 0.0), |(sum, weight), (value, w)| {
                (sum + w * value, weight + w)
            });
        if weight > 0.0 { sum / weight } else { nearest }
    }

    /// Checks the invariants (bounds, at least 2 × 2 points, length of `values`).
    pub fn validate(&self) -> io::Result<()> {
        let [x0, x1, y0, y1] = self.bounds;
        if !(self.bounds.iter().all(|b| b.is_finite()) && x0 < x1 && y0 < y1) {
            return Err(invalid(
                "grid bounds",
                format!("need finite x0 < x1 and y0 < y1, got {:?}", self.bounds),
            ));
        }
        if self.columns < 2 || self.rows < 2 {
            return Err(invalid(
                "grid",
                format!(
                    "needs at least 2 × 2 points, got {} × {}",
                    self.columns, self.rows
                ),
            ));
        }
        check_length("grid values", self.columns * self.rows, self.values.len())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sampling_order_and_interpolation() {
        let field = GridField::sample(
            Quantity::deflection(),
            [0.0, 2.0, 0.0, 1.0],
            3,
            2,
            |x, y| x + 10.0 * y,
        );
        assert_eq!(field.values, vec![0.0, 1.0, 2.0, 10.0, 11.0, 12.0]);
        assert_eq!(field.point(2, 1), [2.0, 1.0]);
        assert!((field.interpolate_normalised(0.25, 0.5) - 5.5).abs() < 1e-12);
        assert_eq!(field.max_abs_point(), Some((2, 1, 12.0)));
    }

    /// NaN marks points outside the domain: blank where the nearest sample is outside, the
    /// finite samples alone beside it.
    #[test]
    fn samples_outside_the_domain_stay_blank_and_do_not_leak() {
        let field = GridField::sample(
            Quantity::deflection(),
            [0.0, 1.0, 0.0, 1.0],
            2,
            2,
            |x, y| {
                if x > 0.5 && y > 0.5 {
                    f64::NAN
                } else {
                    1.0 + x
                }
            },
        );
        assert!(field.interpolate_normalised(0.9, 0.9).is_nan());
        let near_left = field.interpolate_normalised(0.1, 0.6);
        assert!((near_left - 1.1 / 1.0).abs() < 0.2, "{near_left}");
        assert!(near_left.is_finite());
        assert_eq!(field.max_abs(), 2.0);
    }
}
