//! Taylor-coefficient recurrences of the generated Taylor-mode kernels.
//!
//! A Taylor-mode kernel computes the order-$`k`$ coefficient of every jet-dependent
//! intermediate of a residual from the lower-order coefficients kept on a per-point *tape*
//! (one slice of coefficients $`x_0, \dots, x_k`$ per stored intermediate). Only products,
//! quotients and reciprocals read the history; these functions are their order-$`k`$ rules.
//! Each costs $`O(k)`$, so a whole ANM step of order $`N`$ costs $`O(N^2)`$ per intermediate.

/// $`(a\,b)_k = \sum_{j=0}^{k} a_j\, b_{k-j}`$ (`a` and `b` hold at least $`k+1`$ coefficients).
#[inline(always)]
pub fn product(a: &[f64], b: &[f64], k: usize) -> f64 {
    let mut sum = 0.0;
    for (x, y) in a[..=k].iter().zip(b[..=k].iter().rev()) {
        sum += x * y;
    }
    sum
}

/// $`(a^2)_k = \sum_{j=0}^{k} a_j\, a_{k-j}`$, summing each pair once.
#[inline(always)]
pub fn square(a: &[f64], k: usize) -> f64 {
    let a = &a[..=k];
    let half = k.div_ceil(2);
    let mut sum = 0.0;
    // a_j a_{k-j} for j < ⌈k/2⌉: the first `half` entries against the last `half` reversed.
    for (x, y) in a[..half].iter().zip(a[k + 1 - half..].iter().rev()) {
        sum += x * y;
    }
    sum *= 2.0;
    if k.is_multiple_of(2) {
        sum += a[k / 2] * a[k / 2];
    }
    sum
}

/// $`(a/b)_k = \big(a_k - \sum_{j=1}^{k} b_j\, c_{k-j}\big)/b_0`$ with $`c = a/b`$, from the
/// order-$`k`$ coefficient $`a_k`$ of the numerator, the divisor's coefficients $`b_0..b_k`$
/// and the quotient's $`c_0..c_{k-1}`$.
#[inline(always)]
pub fn quotient(a_k: f64, b: &[f64], c: &[f64], k: usize) -> f64 {
    let mut sum = a_k;
    for (x, y) in b[1..=k].iter().zip(c[..k].iter().rev()) {
        sum -= x * y;
    }
    sum / b[0]
}

/// $`(1/b)_k = -\big(\sum_{j=1}^{k} b_j\, r_{k-j}\big)/b_0`$ with $`r = 1/b`$, $`k \ge 1`$.
#[inline(always)]
pub fn reciprocal(b: &[f64], r: &[f64], k: usize) -> f64 {
    quotient(0.0, b, r, k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recurrences_match_polynomial_arithmetic() {
        let a = [1.5, -0.5, 0.25, 2.0, -1.0];
        let b = [2.0, 0.75, -1.25, 0.5, 0.125];
        // Cauchy product by definition.
        for k in 0..a.len() {
            let direct: f64 = (0..=k).map(|j| a[j] * b[k - j]).sum();
            assert_eq!(product(&a, &b, k), direct);
            let direct: f64 = (0..=k).map(|j| a[j] * a[k - j]).sum();
            assert!((square(&a, k) - direct).abs() <= 1e-15 * direct.abs().max(1.0));
        }
        // c = a / b satisfies c * b = a coefficient by coefficient; r * b = 1.
        let mut c = vec![0.0; a.len()];
        let mut r = vec![0.0; a.len()];
        r[0] = 1.0 / b[0];
        for k in 0..a.len() {
            c[k] = quotient(a[k], &b, &c, k);
            if k > 0 {
                r[k] = reciprocal(&b, &r, k);
            }
            assert!((product(&c, &b, k) - a[k]).abs() < 1e-14);
            let one = if k == 0 { 1.0 } else { 0.0 };
            assert!((product(&r, &b, k) - one).abs() < 1e-14);
        }
    }
}
