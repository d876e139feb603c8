//! Gauss–Legendre rules on the reference line $`[-1, 1]`$ and square $`[-1, 1]^2`$.
//!
//! The $`n`$-point rule integrates polynomials of degree $`2n - 1`$ exactly. Points are stored
//! as $`(\xi, \eta)`$ for every element; a line element's rule has $`\eta = 0`$.

/// Points and weights of a quadrature rule on an element's reference domain.
#[derive(Clone, Debug, PartialEq)]
pub struct GaussRule {
    /// Points $`(\xi, \eta)`$ ($`\eta = 0`$ on the reference line).
    pub points: Vec<[f64; 2]>,
    /// Weights (they sum to the reference measure: 2 on the line, 4 on the square).
    pub weights: Vec<f64>,
}

impl GaussRule {
    /// One-dimensional Gauss–Legendre points and weights on $`[-1, 1]`$ with `n` ∈ 1..=5
    /// points (exact for degree $`2n - 1`$).
    ///
    /// # Panics
    /// For `n` outside 1..=5.
    pub fn legendre(n: usize) -> (Vec<f64>, Vec<f64>) {
        match n {
            1 => (vec![0.0], vec![2.0]),
            2 => {
                let a = 1.0 / 3f64.sqrt();
                (vec![-a, a], vec![1.0, 1.0])
            }
            3 => {
                let a = (3.0f64 / 5.0).sqrt();
                (vec![-a, 0.0, a], vec![5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0])
            }
            4 => {
                // ±√(3/7 ∓ (2/7)√(6/5)), weights (18 ± √30)/36.
                let root = (6.0f64 / 5.0).sqrt();
                let inner = (3.0 / 7.0 - 2.0 / 7.0 * root).sqrt();
                let outer = (3.0 / 7.0 + 2.0 / 7.0 * root).sqrt();
                let (w_inner, w_outer) =
                    ((18.0 + 30f64.sqrt()) / 36.0, (18.0 - 30f64.sqrt()) / 36.0);
                (
                    vec![-outer, -inner, inner, outer],
                    vec![w_outer, w_inner, w_inner, w_outer],
                )
            }
            5 => {
                // 0 and ±⅓√(5 ∓ 2√(10/7)), weights 128/225 and (322 ± 13√70)/900.
                let root = (10.0f64 / 7.0).sqrt();
                let inner = (5.0 - 2.0 * root).sqrt() / 3.0;
                let outer = (5.0 + 2.0 * root).sqrt() / 3.0;
                let (w_inner, w_outer) = (
                    (322.0 + 13.0 * 70f64.sqrt()) / 900.0,
                    (322.0 - 13.0 * 70f64.sqrt()) / 900.0,
                );
                (
                    vec![-outer, -inner, 0.0, inner, outer],
                    vec![w_outer, w_inner, 128.0 / 225.0, w_inner, w_outer],
                )
            }
            _ => panic!("GaussRule::legendre supports 1 to 5 points, got {n}"),
        }
    }

    /// The `n`-point rule on the reference line, points $`(\xi, 0)`$.
    pub fn line(n: usize) -> Self {
        let (x, w) = Self::legendre(n);
        GaussRule {
            points: x.into_iter().map(|xi| [xi, 0.0]).collect(),
            weights: w,
        }
    }

    /// The `n × n` tensor rule on the reference square ($`\xi`$ fastest).
    pub fn square(n: usize) -> Self {
        let (x, w) = Self::legendre(n);
        let mut points = Vec::with_capacity(n * n);
        let mut weights = Vec::with_capacity(n * n);
        for j in 0..n {
            for i in 0..n {
                points.push([x[i], x[j]]);
                weights.push(w[i] * w[j]);
            }
        }
        GaussRule { points, weights }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn n_point_rules_integrate_degree_2n_minus_1_exactly() {
        for n in 1..=5 {
            let (x, w) = GaussRule::legendre(n);
            for degree in 0..2 * n {
                let integral: f64 = x
                    .iter()
                    .zip(&w)
                    .map(|(x, w)| w * x.powi(degree as i32))
                    .sum();
                let exact = if degree % 2 == 1 {
                    0.0
                } else {
                    2.0 / (degree as f64 + 1.0)
                };
                assert!((integral - exact).abs() < 1e-14, "n = {n}, degree {degree}");
            }
        }
    }
}
