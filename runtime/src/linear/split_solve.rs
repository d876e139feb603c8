//! Solves with a supernodal $`LL^\top`$ or $`LDL^\top`$ factor on two cores.
//!
//! A forward and backward substitution reads the whole factor once each and does two flops per
//! entry read: it is bound by memory bandwidth, and on this machine two cores reading two halves
//! of the factor get twice the bandwidth of one (docs/benchmarks.md, round eight). The
//! supernodal elimination tree gives the independence: the subtrees hanging below a set of
//! supernodes closed under taking parents (the *top*) touch disjoint unknowns, so they can be
//! substituted at the same time.
//!
//! [`SolveSplit::new`] picks the top and deals the subtrees below it into two groups of about
//! equal factor size, once per symbolic analysis. A solve then runs, with $`x`$ in the factor's
//! order:
//! 1. forward, $`L y = b`$: each group substitutes its subtrees in a copy of $`b`$ of its own,
//!    whose entries of top unknowns start at zero and collect that group's updates
//!    $`-L_{ts} y_s`$; then $`y_t = (b_t + u^{(0)}_t) + u^{(1)}_t`$ and the top is substituted
//!    in order;
//! 2. for $`LDL^\top`$, $`y \leftarrow D^{-1} y`$;
//! 3. backward, $`L^\top x = y`$: the top first, in reverse order, then each group's subtrees in
//!    a copy of their own, copied back.
//!
//! The groups and the order of every operation are fixed by the factor's structure alone: the
//! two groups run one after the other on one thread and side by side on two with the same
//! arithmetic, so the solution is the same to the last bit for any number of threads (it differs
//! at rounding level from faer's own sequential solve, whose top updates are summed in another
//! order). The dense work per supernode is faer's (triangular solve and matrix–vector product,
//! sequential), as in faer's solve.

use faer::linalg::matmul::matmul_with_conj;
use faer::linalg::triangular_solve as triangular;
use faer::sparse::linalg::cholesky::supernodal::{SupernodalLltRef, SymbolicSupernodalCholesky};
use faer::{Accum, Conj, MatMut, MatRef, Par};
use std::ops::Range;

/// Below this many unknowns the solve stays faer's sequential one (a split saves well under a
/// millisecond there, and small scenes keep their bits).
pub const SPLIT_SOLVE_FROM: usize = 20_000;

/// A split is used only when its estimated time (the top plus the larger group, in factor
/// entries) is at most this fraction of the whole factor.
const WORTHWHILE_FRACTION: f64 = 0.8;

/// Subtrees expanded into the top, at most, while searching for a balanced split.
const MAX_EXPANSIONS: usize = 256;

/// The diagonal of the factor's diagonal blocks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Diagonal {
    /// $`L L^\top`$: the diagonal is $`L`$'s.
    Cholesky,
    /// $`L D L^\top`$: $`L`$ has a unit diagonal and the stored diagonal is $`D`$.
    Pivots,
}

/// The two groups of independent subtrees of a supernodal factor and the top above them.
#[derive(Debug)]
pub struct SolveSplit {
    /// Supernodes above the groups, in increasing order (parents after children).
    top: Vec<usize>,
    /// Columns of the top supernodes, in increasing order.
    top_columns: Vec<usize>,
    /// Each group's subtrees as ranges of supernodes (a subtree is contiguous in the factor's
    /// postorder), in increasing order.
    groups: [Vec<Range<usize>>; 2],
    /// Each group's columns, as ranges.
    group_columns: [Vec<Range<usize>>; 2],
    /// Factor entries of the top and of each group (the cost model).
    entries: [usize; 3],
    /// Longest off-diagonal pattern of a supernode (scratch length).
    longest_pattern: usize,
}

/// A split being searched: the top, its entries, and the two groups' subtree roots and entries.
struct Candidate {
    top_entries: usize,
    top: Vec<usize>,
    load: [usize; 2],
    roots: [Vec<usize>; 2],
}

impl Candidate {
    /// Estimated solve time, in factor entries read one after the other: the top and the larger
    /// group.
    fn estimate(&self) -> usize {
        self.top_entries + self.load[0].max(self.load[1])
    }
}

/// Deals `members` (subtree roots with their entries) into two groups, the largest first into
/// the lighter group (ties to the first): the groups' entries and members.
fn deal(members: &[(usize, usize)]) -> ([usize; 2], [Vec<usize>; 2]) {
    let mut sorted = members.to_vec();
    sorted.sort_unstable_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
    let mut load = [0_usize; 2];
    let mut groups: [Vec<usize>; 2] = [Vec::new(), Vec::new()];
    for (root, entries) in sorted {
        let lighter = usize::from(load[1] < load[0]);
        load[lighter] += entries;
        groups[lighter].push(root);
    }
    (load, groups)
}

impl SolveSplit {
    /// The split of `symbolic`'s elimination tree that minimises the top's entries plus the
    /// larger group's, searched by expanding the largest subtree below the top, one at a time;
    /// `None` when no split brings that under [`WORTHWHILE_FRACTION`] of the factor, or when the
    /// supernodes are not in a postorder (each subtree contiguous).
    pub fn new(symbolic: &SymbolicSupernodalCholesky<usize>) -> Option<Self> {
        let count = symbolic.n_supernodes();
        if count < 3 {
            return None;
        }
        let begin = symbolic.supernode_begin();
        let end = symbolic.supernode_end();
        let mut supernode_of_column = vec![0; symbolic.nrows()];
        for s in 0..count {
            supernode_of_column[begin[s]..end[s]].fill(s);
        }
        let values = symbolic.col_ptr_for_val();
        let mut parent = vec![None; count];
        let mut children: Vec<Vec<usize>> = vec![Vec::new(); count];
        let mut subtree_entries: Vec<usize> =
            (0..count).map(|s| values[s + 1] - values[s]).collect();
        let mut subtree_size = vec![1_usize; count];
        let mut first = (0..count).collect::<Vec<_>>();
        let mut longest_pattern = 0;
        for s in 0..count {
            let pattern = symbolic.supernode(s).pattern();
            longest_pattern = longest_pattern.max(pattern.len());
            if let Some(&row) = pattern.first() {
                let p = supernode_of_column[row];
                if p <= s {
                    return None;
                }
                parent[s] = Some(p);
                children[p].push(s);
                subtree_entries[p] += subtree_entries[s];
                subtree_size[p] += subtree_size[s];
                first[p] = first[p].min(first[s]);
            }
        }
        if (0..count).any(|s| s + 1 - first[s] != subtree_size[s]) {
            return None;
        }
        let total: usize = (0..count)
            .filter(|&s| parent[s].is_none())
            .map(|s| subtree_entries[s])
            .sum();
        let own = |s: usize| values[s + 1] - values[s];

        let mut top: Vec<usize> = Vec::new();
        let mut top_entries = 0_usize;
        let mut frontier: Vec<(usize, usize)> = (0..count)
            .filter(|&s| parent[s].is_none())
            .map(|s| (s, subtree_entries[s]))
            .collect();
        let mut best: Option<Candidate> = None;
        for _ in 0..MAX_EXPANSIONS {
            let (load, roots) = deal(&frontier);
            let candidate = Candidate {
                top_entries,
                top: top.clone(),
                load,
                roots,
            };
            if best
                .as_ref()
                .is_none_or(|b| candidate.estimate() < b.estimate())
            {
                best = Some(candidate);
            }
            // Expand the largest subtree of the frontier (the smallest root on ties).
            let Some(position) = (0..frontier.len()).max_by(|&a, &b| {
                frontier[a]
                    .1
                    .cmp(&frontier[b].1)
                    .then(frontier[b].0.cmp(&frontier[a].0))
            }) else {
                break;
            };
            let (root, _) = frontier.swap_remove(position);
            top.push(root);
            top_entries += own(root);
            frontier.extend(children[root].iter().map(|&c| (c, subtree_entries[c])));
            if top_entries >= best.as_ref().map_or(total, Candidate::estimate) {
                break;
            }
        }
        let best = best?;
        if best.estimate() as f64 > WORTHWHILE_FRACTION * total as f64 {
            return None;
        }
        let Candidate {
            top_entries,
            mut top,
            load,
            roots,
        } = best;
        if load[0] == 0 || load[1] == 0 {
            return None;
        }
        top.sort_unstable();
        let top_columns = top.iter().flat_map(|&s| begin[s]..end[s]).collect();
        let ranges = |group: &[usize]| {
            let mut ranges: Vec<Range<usize>> =
                group.iter().map(|&root| first[root]..root + 1).collect();
            ranges.sort_unstable_by_key(|range| range.start);
            ranges
        };
        let groups = [ranges(&roots[0]), ranges(&roots[1])];
        let columns = |group: &[Range<usize>]| {
            group
                .iter()
                .map(|range| begin[range.start]..end[range.end - 1])
                .collect::<Vec<_>>()
        };
        let group_columns = [columns(&groups[0]), columns(&groups[1])];
        Some(Self {
            top,
            top_columns,
            groups,
            group_columns,
            entries: [top_entries, load[0], load[1]],
            longest_pattern,
        })
    }

    /// Factor entries of the top and of the two groups.
    pub fn entries(&self) -> [usize; 3] {
        self.entries
    }

    /// Solves $`A x = b`$ in place in the factor's order (`x` holds $`P b`$ on entry), with the
    /// factor `values` of `symbolic` whose diagonal is `diagonal`.
    pub fn solve_in_place(
        &self,
        symbolic: &SymbolicSupernodalCholesky<usize>,
        values: &[f64],
        diagonal: Diagonal,
        x: &mut [f64],
    ) {
        let factor = SupernodalLltRef::new(symbolic, values);
        let mut scratch = vec![0.0; self.longest_pattern];

        // Forward: the groups in copies of their own, the top's entries collecting updates.
        let [first, second] = self.groups_side_by_side(x, |group, y| {
            for &column in &self.top_columns {
                y[column] = 0.0;
            }
            let mut scratch = vec![0.0; self.longest_pattern];
            for range in &self.groups[group] {
                for s in range.clone() {
                    forward(factor, s, diagonal, y, &mut scratch);
                }
            }
        });
        for &column in &self.top_columns {
            x[column] = (x[column] + first[column]) + second[column];
        }
        drop((first, second));
        for &s in &self.top {
            forward(factor, s, diagonal, x, &mut scratch);
        }

        if diagonal == Diagonal::Pivots {
            for s in 0..symbolic.n_supernodes() {
                let (start, _, diagonal_block, _) = supernode_parts(factor, s);
                for index in 0..diagonal_block.ncols() {
                    x[start + index] *= diagonal_block[(index, index)].recip();
                }
            }
        }

        // Backward: the top first, then the groups in copies of their own.
        for &s in self.top.iter().rev() {
            backward(factor, s, diagonal, x, &mut scratch);
        }
        self.groups_side_by_side(x, |group, y| {
            let mut scratch = vec![0.0; self.longest_pattern];
            for range in self.groups[group].iter().rev() {
                for s in range.clone().rev() {
                    backward(factor, s, diagonal, y, &mut scratch);
                }
            }
        });
    }

    /// Runs `work` on each group's own copy of `x`, the two side by side, and copies each
    /// group's columns back into `x`; returns the copies.
    fn groups_side_by_side(
        &self,
        x: &mut [f64],
        work: impl Fn(usize, &mut [f64]) + Sync,
    ) -> [Vec<f64>; 2] {
        let run = |group: usize| {
            let mut y = x.to_vec();
            work(group, &mut y);
            y
        };
        let (first, second) = rayon::join(|| run(0), || run(1));
        for (group, y) in [&first, &second].into_iter().enumerate() {
            for columns in &self.group_columns[group] {
                x[columns.clone()].copy_from_slice(&y[columns.clone()]);
            }
        }
        [first, second]
    }
}

/// Supernode `s` of `factor`: its first column, its pattern below the diagonal block, the
/// diagonal block and the block below it.
fn supernode_parts<'f>(
    factor: SupernodalLltRef<'f, usize, f64>,
    s: usize,
) -> (usize, &'f [usize], MatRef<'f, f64>, MatRef<'f, f64>) {
    let supernode = factor.supernode(s);
    let block = supernode.val();
    let (diagonal_block, below) = block.split_at_row(block.ncols());
    (
        supernode.start(),
        supernode.pattern(),
        diagonal_block,
        below,
    )
}

/// Forward substitution of supernode `s`: its diagonal block, then the updates
/// $`x_p \mathrel{-}= L_{ps} x_s`$ of the rows of its pattern.
fn forward(
    factor: SupernodalLltRef<'_, usize, f64>,
    s: usize,
    diagonal: Diagonal,
    x: &mut [f64],
    scratch: &mut [f64],
) {
    let (start, pattern, diagonal_block, below) = supernode_parts(factor, s);
    let size = diagonal_block.ncols();
    let mut own = MatMut::from_column_major_slice_mut(&mut x[start..start + size], size, 1);
    diagonal_solve(diagonal_block, diagonal, false, own.as_mut());
    let updates =
        MatMut::from_column_major_slice_mut(&mut scratch[..pattern.len()], pattern.len(), 1);
    matmul_with_conj(
        updates,
        Accum::Replace,
        below,
        Conj::No,
        own.as_ref(),
        Conj::No,
        1.0,
        Par::Seq,
    );
    for (&row, &update) in pattern.iter().zip(scratch.iter()) {
        x[row] -= update;
    }
}

/// Backward substitution of supernode `s`: $`x_s \mathrel{-}= L_{ps}^\top x_p`$ from the rows
/// of its pattern, then its diagonal block transposed.
fn backward(
    factor: SupernodalLltRef<'_, usize, f64>,
    s: usize,
    diagonal: Diagonal,
    x: &mut [f64],
    scratch: &mut [f64],
) {
    let (start, pattern, diagonal_block, below) = supernode_parts(factor, s);
    let size = diagonal_block.ncols();
    for (value, &row) in scratch.iter_mut().zip(pattern) {
        *value = x[row];
    }
    let known = MatRef::from_column_major_slice(&scratch[..pattern.len()], pattern.len(), 1);
    let mut own = MatMut::from_column_major_slice_mut(&mut x[start..start + size], size, 1);
    matmul_with_conj(
        own.as_mut(),
        Accum::Add,
        below.transpose(),
        Conj::No,
        known,
        Conj::No,
        -1.0,
        Par::Seq,
    );
    diagonal_solve(diagonal_block, diagonal, true, own);
}

/// Solves in place with a supernode's diagonal block $`L_{ss}`$, or with $`L_{ss}^\top`$ when
/// `transposed`; its diagonal taken as ones for $`LDL^\top`$ (where it holds $`D`$).
fn diagonal_solve(
    block: MatRef<'_, f64>,
    diagonal: Diagonal,
    transposed: bool,
    own: MatMut<'_, f64>,
) {
    let (conj, par) = (Conj::No, Par::Seq);
    match (diagonal, transposed) {
        (Diagonal::Cholesky, false) => {
            triangular::solve_lower_triangular_in_place_with_conj(block, conj, own, par)
        }
        (Diagonal::Pivots, false) => {
            triangular::solve_unit_lower_triangular_in_place_with_conj(block, conj, own, par)
        }
        (Diagonal::Cholesky, true) => {
            triangular::solve_upper_triangular_in_place_with_conj(block.transpose(), conj, own, par)
        }
        (Diagonal::Pivots, true) => triangular::solve_unit_upper_triangular_in_place_with_conj(
            block.transpose(),
            conj,
            own,
            par,
        ),
    }
}
