//! Fill-reducing orderings of a symmetric pattern: **nested dissection** by level-structure
//! separators (George, 1973; George & Liu, *Computer Solution of Large Sparse Positive Definite
//! Systems*, 1981, ch. 8), on the quotient graph of the pattern's supervariables.
//!
//! A finite-element pattern couples every unknown of a node with the same set of unknowns: the
//! columns of one node are identical. Those columns are merged into one **supervariable** (weight
//! = their number), so that the graph dissected has one vertex per node (a fifth or a third of
//! the unknowns) and a separator never splits a node. Then, recursively on each connected part:
//!
//! 1. a pseudo-peripheral vertex $`r`$ (repeated breadth-first searches from the last level's
//!    vertex of least degree, until the eccentricity stops growing);
//! 2. the level structure $`L_0 = \{r\}, L_1, \dots`$ of a breadth-first search from $`r`$;
//! 3. the level $`L_m`$ where the cumulative weight first reaches half the part's, and as the
//!    separator $`S`$ the vertices of $`L_m`$ that have a neighbour in $`L_{m+1}`$ (the others
//!    join the first half): removing $`S`$ leaves $`A = L_{<m} \cup (L_m\setminus S)`$ and
//!    $`B = L_{>m}`$ with no edge between them;
//! 4. $`A`$ and $`B`$ are ordered first (recursively), $`S`$ last.
//!
//! Parts of at most [`LEAF_WEIGHT`] unknowns are ordered as their search visited them. On a
//! $`k\times k`$ grid the factor then has $`O(k^2\log k)`$ entries and costs $`O(k^3)`$
//! operations, against the $`O(k^3)`$ entries a band ordering gives; minimum-degree orderings
//! (AMD) are close on small meshes and fall behind as they grow. The ordering depends only on
//! the pattern (no randomness, no threads): the same pattern gives the same permutation.

use super::pattern::SparsityPattern;
use std::collections::HashMap;

/// Parts of at most this many unknowns are not dissected further.
pub const LEAF_WEIGHT: usize = 256;

/// The quotient graph: supervariables (groups of columns with identical patterns), their
/// weights and adjacency in CSR form.
struct Quotient {
    /// Columns of each supervariable, in increasing order.
    members: Vec<Vec<usize>>,
    offsets: Vec<usize>,
    neighbours: Vec<usize>,
}

impl Quotient {
    fn new(pattern: &SparsityPattern) -> Self {
        let n = pattern.dimension();
        let mut members: Vec<Vec<usize>> = Vec::new();
        let mut by_rows: HashMap<&[usize], usize> = HashMap::new();
        let group_of: Vec<usize> = (0..n)
            .map(|column| {
                let group = *by_rows
                    .entry(pattern.rows_of_column(column))
                    .or_insert_with(|| {
                        members.push(Vec::new());
                        members.len() - 1
                    });
                members[group].push(column);
                group
            })
            .collect();
        let mut offsets = Vec::with_capacity(members.len() + 1);
        offsets.push(0);
        let mut neighbours = Vec::new();
        let mut seen = vec![usize::MAX; members.len()];
        for (group, columns) in members.iter().enumerate() {
            seen[group] = group;
            for &row in pattern.rows_of_column(columns[0]) {
                let other = group_of[row];
                if seen[other] != group {
                    seen[other] = group;
                    neighbours.push(other);
                }
            }
            offsets.push(neighbours.len());
        }
        Self {
            members,
            offsets,
            neighbours,
        }
    }

    fn len(&self) -> usize {
        self.members.len()
    }

    fn neighbours(&self, v: usize) -> &[usize] {
        &self.neighbours[self.offsets[v]..self.offsets[v + 1]]
    }

    fn weight(&self, v: usize) -> usize {
        self.members[v].len()
    }
}

/// Work arrays of the dissection, indexed by supervariable.
struct Dissection<'q> {
    graph: &'q Quotient,
    /// The part a vertex belongs to now (vertices outside the part being split are skipped).
    part: Vec<usize>,
    /// Breadth-first level of a vertex in the current search (`usize::MAX`: not reached).
    level: Vec<usize>,
    next_part: usize,
    /// Supervariables in elimination order.
    order: Vec<usize>,
}

impl Dissection<'_> {
    /// Breadth-first search from `root` inside part `label`: the visited vertices in order and
    /// the start of every level in that list.
    fn search(&mut self, root: usize, label: usize) -> (Vec<usize>, Vec<usize>) {
        let mut visited = vec![root];
        let mut starts = vec![0];
        self.level[root] = 0;
        let mut head = 0;
        while head < visited.len() {
            let end = visited.len();
            let depth = self.level[visited[head]];
            for i in head..end {
                let v = visited[i];
                for &w in self.graph.neighbours(v) {
                    if self.part[w] == label && self.level[w] == usize::MAX {
                        self.level[w] = depth + 1;
                        visited.push(w);
                    }
                }
            }
            head = end;
            if visited.len() > end {
                starts.push(end);
            }
        }
        (visited, starts)
    }

    fn clear_levels(&mut self, visited: &[usize]) {
        for &v in visited {
            self.level[v] = usize::MAX;
        }
    }

    /// A pseudo-peripheral vertex of the component of `start` in part `label`, with its level
    /// structure (levels left set; the caller clears them).
    fn peripheral_search(&mut self, start: usize, label: usize) -> (Vec<usize>, Vec<usize>) {
        let mut root = start;
        let (mut visited, mut starts) = self.search(root, label);
        // Bounded: the eccentricity grows strictly at every accepted restart.
        for _ in 0..8 {
            let last = &visited[*starts.last().unwrap()..];
            let candidate = *last
                .iter()
                .min_by_key(|&&v| (self.graph.neighbours(v).len(), v))
                .unwrap();
            if candidate == root {
                break;
            }
            self.clear_levels(&visited);
            let (next_visited, next_starts) = self.search(candidate, label);
            if next_starts.len() > starts.len() {
                root = candidate;
                visited = next_visited;
                starts = next_starts;
            } else {
                self.clear_levels(&next_visited);
                let again = self.search(root, label);
                visited = again.0;
                starts = again.1;
                break;
            }
        }
        (visited, starts)
    }

    /// Orders the part `label`, whose vertices are `vertices`, appending to `self.order`.
    fn dissect(&mut self, vertices: Vec<usize>, label: usize) {
        // Separators wait until both halves before them are ordered: a stack of pending tasks.
        enum Task {
            Part(Vec<usize>, usize),
            Emit(Vec<usize>),
        }
        let mut tasks = vec![Task::Part(vertices, label)];
        while let Some(task) = tasks.pop() {
            let (vertices, label) = match task {
                Task::Emit(separator) => {
                    self.order.extend(separator);
                    continue;
                }
                Task::Part(vertices, label) => (vertices, label),
            };
            let weight: usize = vertices.iter().map(|&v| self.graph.weight(v)).sum();
            let (visited, starts) = self.peripheral_search(vertices[0], label);
            if visited.len() < vertices.len() {
                // Several components: the one searched, and the rest as a part of its own.
                let rest_label = self.new_label();
                let rest: Vec<usize> = vertices
                    .iter()
                    .copied()
                    .filter(|&v| self.level[v] == usize::MAX)
                    .collect();
                for &v in &rest {
                    self.part[v] = rest_label;
                }
                self.clear_levels(&visited);
                let here = self.new_label();
                for &v in &visited {
                    self.part[v] = here;
                }
                tasks.push(Task::Part(rest, rest_label));
                tasks.push(Task::Part(visited, here));
                continue;
            }
            if weight <= LEAF_WEIGHT || starts.len() < 3 {
                self.clear_levels(&visited);
                self.order.extend(visited);
                continue;
            }
            // The level where the cumulative weight reaches half, kept off the first and last.
            let mut cumulative = 0;
            let mut middle = 1;
            for (m, &start) in starts.iter().enumerate() {
                let end = starts.get(m + 1).copied().unwrap_or(visited.len());
                cumulative += visited[start..end]
                    .iter()
                    .map(|&v| self.graph.weight(v))
                    .sum::<usize>();
                if 2 * cumulative >= weight {
                    middle = m;
                    break;
                }
            }
            let middle = middle.clamp(1, starts.len() - 2);
            let (first, second) = (self.new_label(), self.new_label());
            let mut a = Vec::new();
            let mut b = Vec::new();
            let mut separator = Vec::new();
            for &v in &visited {
                let depth = self.level[v];
                if depth < middle {
                    a.push(v);
                } else if depth > middle {
                    b.push(v);
                } else if self
                    .graph
                    .neighbours(v)
                    .iter()
                    .any(|&w| self.part[w] == label && self.level[w] == middle + 1)
                {
                    separator.push(v);
                } else {
                    a.push(v);
                }
            }
            self.clear_levels(&visited);
            for &v in &a {
                self.part[v] = first;
            }
            for &v in &b {
                self.part[v] = second;
            }
            for &v in &separator {
                self.part[v] = usize::MAX;
            }
            tasks.push(Task::Emit(separator));
            if !b.is_empty() {
                tasks.push(Task::Part(b, second));
            }
            if !a.is_empty() {
                tasks.push(Task::Part(a, first));
            }
        }
    }

    fn new_label(&mut self) -> usize {
        self.next_part += 1;
        self.next_part
    }
}

/// The nested-dissection elimination order of `pattern`: `order[k]` is the column eliminated
/// `k`-th. A permutation of `0..n`.
pub fn nested_dissection(pattern: &SparsityPattern) -> Vec<usize> {
    let graph = Quotient::new(pattern);
    let vertices: Vec<usize> = (0..graph.len()).collect();
    let mut dissection = Dissection {
        graph: &graph,
        part: vec![0; graph.len()],
        level: vec![usize::MAX; graph.len()],
        next_part: 0,
        order: Vec::with_capacity(graph.len()),
    };
    if !vertices.is_empty() {
        dissection.dissect(vertices, 0);
    }
    dissection
        .order
        .iter()
        .flat_map(|&v| graph.members[v].iter().copied())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nested_dissection_is_a_permutation_that_keeps_a_nodes_unknowns_together() {
        let pattern = rectangle(40, 40, 3);
        let order = nested_dissection(&pattern);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..pattern.dimension()).collect::<Vec<_>>());
        for chunk in order.chunks(3) {
            assert_eq!(chunk[0] / 3, chunk[2] / 3, "{chunk:?}");
        }
        assert_eq!(order, nested_dissection(&pattern), "deterministic");
    }

    /// The pattern of a `kx × ky` grid of nodes with `dofs` unknowns each (bilinear elements).
    fn rectangle(kx: usize, ky: usize, dofs: usize) -> SparsityPattern {
        let mut elements = Vec::new();
        for i in 0..ky - 1 {
            for j in 0..kx - 1 {
                let nodes = [
                    i * kx + j,
                    i * kx + j + 1,
                    (i + 1) * kx + j,
                    (i + 1) * kx + j + 1,
                ];
                let list: Vec<Option<usize>> = nodes
                    .iter()
                    .flat_map(|&n| (0..dofs).map(move |d| Some(n * dofs + d)))
                    .collect();
                elements.push(list);
            }
        }
        SparsityPattern::from_element_dofs(kx * ky * dofs, elements.iter().map(Vec::as_slice))
    }

    /// Factorisation work and solution of a diagonally dominant system on `pattern` with
    /// `ordering`.
    fn work_and_solution(
        pattern: &std::sync::Arc<SparsityPattern>,
        ordering: crate::linear::factor::OrderingChoice,
    ) -> (f64, Vec<f64>) {
        use crate::linear::factor::{SparseFactorization, SupernodalThreshold};
        use crate::linear::pattern::SparseMatrix;
        let n = pattern.dimension();
        let mut matrix = SparseMatrix::zeros(pattern.clone());
        for column in 0..n {
            let rows = pattern.rows_of_column(column);
            for &row in rows {
                let value = if row == column {
                    rows.len() as f64
                } else {
                    -0.5 - 0.1 * ((row + column) % 3) as f64 / 3.0
                };
                matrix.add_to(row, column, value).unwrap();
            }
        }
        let mut x: Vec<f64> = (0..n).map(|i| ((i * 7919) % 101) as f64 - 50.0).collect();
        let mut factor =
            SparseFactorization::analyze_with(pattern, SupernodalThreshold::AUTO, ordering)
                .unwrap();
        factor.factorize(&matrix).unwrap();
        factor.solve_in_place(&mut x).unwrap();
        (factor.work(), x)
    }

    /// Every ordering solves the same system to the same solution, and the default
    /// ([`OrderingChoice::Cheaper`]) takes the one of least work. On these bilinear grids
    /// (9-point coupling) the level structures from a corner are L-shaped, their separators
    /// longer than a side, and AMD is the cheaper (measured here: 4:1 grid 240 × 60, 28 800
    /// unknowns: AMD 1.98e8, dissection 4.07e8); on Q8 plate meshes the dissection can be the
    /// cheaper (example 1's 128 × 32: 6.6e9 against 1.17e10, docs/benchmarks.md).
    #[test]
    fn every_ordering_gives_the_same_solution_and_the_cheaper_one_is_taken() {
        use crate::linear::factor::OrderingChoice;
        use std::sync::Arc;
        for (kx, ky) in [(240, 60), (60, 60)] {
            let pattern = Arc::new(rectangle(kx, ky, 2));
            let (amd_work, amd) = work_and_solution(&pattern, OrderingChoice::Amd);
            let (nd_work, nd) = work_and_solution(&pattern, OrderingChoice::NestedDissection);
            let (cheaper_work, cheaper) = work_and_solution(&pattern, OrderingChoice::Cheaper);
            eprintln!("{kx} × {ky}: work AMD {amd_work:.3e}, nested dissection {nd_work:.3e}");
            assert!(amd_work > 0.0 && nd_work > 0.0);
            if pattern.dimension() >= crate::linear::factor::DISSECTION_FROM {
                assert_eq!(cheaper_work, nd_work.min(amd_work));
            } else {
                assert_eq!(cheaper_work, amd_work, "AMD alone on small patterns");
            }
            let scale = amd.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            for ((a, b), c) in amd.iter().zip(&nd).zip(&cheaper) {
                assert!((a - b).abs() < 1e-10 * scale, "{a} vs {b}");
                assert!((a - c).abs() < 1e-10 * scale, "{a} vs {c}");
            }
        }
    }

    #[test]
    fn disconnected_parts_are_all_ordered() {
        // Two separate grids side by side in one pattern.
        let one = rectangle(20, 20, 2);
        let n = one.dimension();
        let mut elements: Vec<Vec<Option<usize>>> = Vec::new();
        for column in 0..n {
            for &row in one.rows_of_column(column) {
                elements.push(vec![Some(row), Some(column)]);
                elements.push(vec![Some(row + n), Some(column + n)]);
            }
        }
        let two = SparsityPattern::from_element_dofs(2 * n, elements.iter().map(Vec::as_slice));
        let mut order = nested_dissection(&two);
        order.sort_unstable();
        assert_eq!(order, (0..2 * n).collect::<Vec<_>>());
    }
}
