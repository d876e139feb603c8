//! Taylor-coefficient recurrences of the generated Taylor-mode kernels.
//!
//! A Taylor-mode kernel computes the order-$`k`$ coefficient of every jet-dependent
//! intermediate of a residual from the lower-order coefficients kept on a per-point *tape*.
//! The tape is a table with one row per order and one column (*slot*) per stored intermediate:
//! coefficient $`x_j`$ of slot $`s`$ is `tape[j * stride + s]`. Order $`k`$ reads rows
//! $`0..k`$ — a contiguous prefix — and writes row $`k`$. Only products, quotients and
//! reciprocals read the history; these functions are their order-$`k`$ rules. Each costs
//! $`O(k)`$, so a whole ANM step of order $`N`$ costs $`O(N^2)`$ per intermediate.

/// The rows of orders $`0..=k`$ of a tape with `stride` slots per row.
#[inline(always)]
fn rows(tape: &[f64], stride: usize, k: usize) -> std::slice::ChunksExact<'_, f64> {
    tape[..(k + 1) * stride].chunks_exact(stride)
}

/// The *histories* of `P` recurrences at order $`k`$ on a tape of `stride` slots per row:
/// $`h_p = \sum_{j=1}^{k-1} x_j\, y_{k-j}`$ for each slot pair $`(x, y) = `$ `pairs[p]` — the
/// part of a product's $`(x\,y)_k`$ (or of a quotient's or reciprocal's recurrence) that reads
/// rows $`1..k-1`$ only, i.e. what is known before any order-$`k`$ value of the sweep. The
/// generated `taylor_predict` computes them all first and then adds the terms with row $`k`$
/// and row 0 ($`x_0 y_k + x_k y_0`$) instruction by instruction.
///
/// One pass over the rows with `P` independent sums: a row pair is read once for all
/// recurrences, and the sums do not wait on each other (one [`product`] at a time is a chain
/// of dependent additions, latency-bound).
#[inline(always)]
pub fn histories<const P: usize>(
    tape: &[f64],
    stride: usize,
    k: usize,
    pairs: &[(usize, usize); P],
) -> [f64; P] {
    assert!(
        pairs.iter().all(|&(x, y)| x < stride && y < stride),
        "slot outside the row"
    );
    let mut sums = [0.0; P];
    for j in 1..k {
        let x = &tape[j * stride..][..stride];
        let y = &tape[(k - j) * stride..][..stride];
        for (sum, &(a, b)) in sums.iter_mut().zip(pairs) {
            *sum += x[a] * y[b];
        }
    }
    sums
}

/// $`(a\,b)_k = \sum_{j=0}^{k} a_j\, b_{k-j}`$ of slots `a` and `b` (rows $`0..=k`$ on the tape).
#[inline(always)]
pub fn product(tape: &[f64], stride: usize, a: usize, b: usize, k: usize) -> f64 {
    assert!(a < stride && b < stride, "slot outside the row");
    let rows = rows(tape, stride, k);
    let mut sum = 0.0;
    for (x, y) in rows.clone().zip(rows.rev()) {
        sum += x[a] * y[b];
    }
    sum
}

/// $`(a^2)_k = \sum_{j=0}^{k} a_j\, a_{k-j}`$ of slot `a`, summing each pair once.
#[inline(always)]
pub fn square(tape: &[f64], stride: usize, a: usize, k: usize) -> f64 {
    assert!(a < stride, "slot outside the row");
    let rows = rows(tape, stride, k);
    let half = k.div_ceil(2);
    let mut sum = 0.0;
    // a_j a_{k-j} for j < ⌈k/2⌉: the first `half` rows against the last `half` reversed.
    for (x, y) in rows.clone().zip(rows.rev()).take(half) {
        sum += x[a] * y[a];
    }
    sum *= 2.0;
    if k.is_multiple_of(2) {
        let middle = tape[(k / 2) * stride + a];
        sum += middle * middle;
    }
    sum
}

/// $`(a/b)_k = \big(a_k - \sum_{j=1}^{k} b_j\, c_{k-j}\big)/b_0`$ with $`c = a/b`$, from the
/// order-$`k`$ coefficient $`a_k`$ of the numerator, the divisor's slot `b` (rows $`0..=k`$)
/// and the quotient's slot `c` (rows $`0..k`$).
#[inline(always)]
pub fn quotient(a_k: f64, tape: &[f64], stride: usize, b: usize, c: usize, k: usize) -> f64 {
    assert!(b < stride && c < stride, "slot outside the row");
    let rows = rows(tape, stride, k);
    let mut sum = a_k;
    for (x, y) in rows.clone().skip(1).zip(rows.rev().skip(1)) {
        sum -= x[b] * y[c];
    }
    sum / tape[b]
}

/// $`(1/b)_k = -\big(\sum_{j=1}^{k} b_j\, r_{k-j}\big)/b_0`$ with $`r = 1/b`$, $`k \ge 1`$.
#[inline(always)]
pub fn reciprocal(tape: &[f64], stride: usize, b: usize, r: usize, k: usize) -> f64 {
    quotient(0.0, tape, stride, b, r, k)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn histories_are_the_products_without_their_first_and_last_terms() {
        const S: usize = 3;
        let series = [
            [1.5, -0.5, 0.25, 2.0, -1.0, 0.75],
            [2.0, 0.75, -1.25, 0.5, 0.125, -3.0],
            [-1.0, 0.5, 4.0, -0.25, 1.0, 2.5],
        ];
        let mut tape = vec![0.0; series[0].len() * S];
        for (s, coefficients) in series.iter().enumerate() {
            for (j, &c) in coefficients.iter().enumerate() {
                tape[j * S + s] = c;
            }
        }
        let pairs = [(0, 1), (2, 2), (1, 0), (2, 0)];
        for k in 0..series[0].len() {
            let h = histories(&tape, S, k, &pairs);
            for (p, &(x, y)) in pairs.iter().enumerate() {
                let direct: f64 = (1..k).map(|j| series[x][j] * series[y][k - j]).sum();
                assert_eq!(h[p], direct, "pair {p} at order {k}");
                if k >= 1 {
                    let full = h[p] + series[x][0] * series[y][k] + series[x][k] * series[y][0];
                    assert!((full - product(&tape, S, x, y, k)).abs() <= 1e-14);
                }
            }
        }
    }

    #[test]
    fn recurrences_match_polynomial_arithmetic() {
        let a = [1.5, -0.5, 0.25, 2.0, -1.0];
        let b = [2.0, 0.75, -1.25, 0.5, 0.125];
        // Rows of four slots: a, the quotient c = a / b, b, the reciprocal r = 1 / b.
        const STRIDE: usize = 4;
        const A: usize = 0;
        const C: usize = 1;
        const B: usize = 2;
        const R: usize = 3;
        let mut tape = vec![f64::NAN; a.len() * STRIDE];
        for k in 0..a.len() {
            tape[k * STRIDE + A] = a[k];
            tape[k * STRIDE + B] = b[k];
        }
        // Cauchy product by definition.
        for k in 0..a.len() {
            let direct: f64 = (0..=k).map(|j| a[j] * b[k - j]).sum();
            assert_eq!(product(&tape, STRIDE, A, B, k), direct);
            let direct: f64 = (0..=k).map(|j| a[j] * a[k - j]).sum();
            let square = square(&tape, STRIDE, A, k);
            assert!((square - direct).abs() <= 1e-15 * direct.abs().max(1.0));
        }
        // c = a / b satisfies c * b = a coefficient by coefficient; r * b = 1. Row k of c and
        // r is not read before it is written (it starts as NaN).
        tape[C] = a[0] / b[0];
        tape[R] = 1.0 / b[0];
        for k in 0..a.len() {
            if k > 0 {
                tape[k * STRIDE + C] = quotient(a[k], &tape, STRIDE, B, C, k);
                tape[k * STRIDE + R] = reciprocal(&tape, STRIDE, B, R, k);
            }
            assert!((product(&tape, STRIDE, C, B, k) - a[k]).abs() < 1e-14);
            let one = if k == 0 { 1.0 } else { 0.0 };
            assert!((product(&tape, STRIDE, R, B, k) - one).abs() < 1e-14);
        }
    }
}
