use std::sync::Arc;
use std::f64::consts::PI;
use wrinkle_runtime::linear::*;
fn grid(nx: usize, ny: usize) -> SparseMatrix {
    let n = nx * ny; let index = |i: usize, j: usize| j * nx + i; let mut entries = Vec::new();
    for j in 0..ny { for i in 0..nx { if i + 1 < nx { entries.push((index(i + 1, j), index(i, j))); } if j + 1 < ny { entries.push((index(i, j + 1), index(i, j))); } } }
    let pattern = Arc::new(SparsityPattern::from_symmetric_entries(n, entries.clone()).unwrap());
    let mut m = SparseMatrix::zeros(pattern); let d = if ny == 1 { 2.0 } else { 4.0 };
    for k in 0..n { m.add_to(k, k, d).unwrap(); }
    for (r, c) in entries { m.add_to(r, c, -1.0).unwrap(); m.add_to(c, r, -1.0).unwrap(); }
    m
}
#[test]
fn probe() {
    for (nx, ny, modes) in [(125usize, 80usize, 3usize), (125, 80, 1), (400, 1, 1), (2000, 1, 2), (300, 30, 5)] {
        let a = grid(nx, ny);
        let mut b = SparseMatrix::zeros(a.pattern.clone());
        for k in 0..a.dimension() { b.add_to(k, k, -1.0).unwrap(); }
        let mut f = SparseFactorization::analyze(&a.pattern).unwrap(); f.factorize(&a).unwrap();
        let t = std::time::Instant::now();
        let s = smallest_positive_buckling(&a, &f, &b, &BucklingOptions{modes, ..Default::default()}).unwrap();
        let ev = |j: usize, k: usize| { let y = if ny == 1 { 0.0 } else { 2.0 - 2.0 * (k as f64 * PI / (ny as f64 + 1.0)).cos() }; 2.0 - 2.0 * (j as f64 * PI / (nx as f64 + 1.0)).cos() + y };
        let mut ex: Vec<f64> = (1..=6).flat_map(|j| (1..=6).map(move |k| (j, k))).filter(|(_, k)| ny > 1 || *k == 1).map(|(j, k)| ev(j, k)).collect();
        ex.sort_by(f64::total_cmp);
        for (k, m) in s.modes.iter().enumerate() {
            println!("{nx}x{ny} k={k} rel err={:e} res={:e} iters={} t={:?}", (m.load_factor-ex[k])/ex[k], m.residual, s.iterations, t.elapsed());
        }
    }
}
