//! Dense vector kernels on `&[f64]`: the dot product, the Euclidean norm and
//! $`y \mathrel{+}= \alpha x`$, shared by the eigen-solver, the Padé approximants and the path
//! solvers.
//!
//! Every sum runs in index order (one accumulator, no unrolling): results are bit-for-bit the
//! same wherever a product is taken, and the same as the loops these functions replaced. A
//! kernel that sums in another order (chunked, pairwise) must be a function of its own with a
//! name that says so, never a silent replacement of these.

/// $`x \cdot y = \sum_i x_i y_i`$, summed in index order (over the shorter length).
pub fn dot(x: &[f64], y: &[f64]) -> f64 {
    x.iter().zip(y).map(|(a, b)| a * b).sum()
}

/// $`\|x\|_2 = \sqrt{x \cdot x}`$ ([`dot`]'s order).
pub fn norm(x: &[f64]) -> f64 {
    dot(x, x).sqrt()
}

/// $`y \mathrel{+}= \alpha x`$ (over the shorter length).
pub fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    for (target, source) in y.iter_mut().zip(x) {
        *target += alpha * source;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The kernels sum in index order: the result is that of the plain loop, bit for bit, even
    /// where reordering would round differently.
    #[test]
    fn sums_run_in_index_order() {
        let x = [1e16, 1.0, -1e16, 1.0];
        let ones = [1.0; 4];
        let mut in_order = 0.0;
        for (a, b) in x.iter().zip(&ones) {
            in_order += a * b;
        }
        assert_eq!(dot(&x, &ones).to_bits(), in_order.to_bits());
        assert_eq!(norm(&[3.0, 4.0]), 5.0);
        let mut y = [1.0, 2.0, 3.0];
        axpy(2.0, &[1.0, 1.0], &mut y);
        assert_eq!(y, [3.0, 4.0, 3.0]);
    }
}
