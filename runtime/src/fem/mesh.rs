//! Meshes: nodes, elements of one [`ElementKind`], and named boundary sets.
//!
//! A mesh is filled the same way whatever makes it — the structured generators here
//! ([`Mesh::rectangle`] of Q8 elements, [`Mesh::line`] of line elements) or a mesh file:
//! [`Mesh::new`] checks the connectivity, then [`Mesh::insert_edge_set`] and
//! [`Mesh::insert_point_set`] name the boundaries (a file's physical groups of dimension 1
//! and 0). Elements may be unstructured and the domain may have holes: nothing below assumes a
//! rectangle except the optional [`StructuredGrid`], a faster point location.
//!
//! **Boundary sets.** An *edge set* is a list of quadratic segments `[end, end, middle]` (the
//! facets of a plane element); a *point set* is a list of nodes (a corner, the end of a beam, a
//! point that removes a rigid motion). Conditions and loads name them; their nodes are
//! [`Mesh::boundary_nodes`].

use super::element::{Element, ElementKind, with_element};
use super::mesh_bins::ElementBins;
use std::collections::BTreeMap;

/// A mesh of elements of one kind with named boundary sets.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// The element every cell is.
    pub kind: ElementKind,
    /// Node coordinates $`(X, Y)`$ ($`Y = 0`$ on a line mesh).
    pub nodes: Vec<[f64; 2]>,
    /// Element connectivity, [`ElementKind::nodes`] entries per element, each element's nodes
    /// in the element's order (VTK order for Q8: corners counter-clockwise, then mid-sides).
    pub connectivity: Vec<usize>,
    /// Named edge sets of a plane mesh, each a list of 3-node segments `[end, end, middle]`.
    pub edges: BTreeMap<String, Vec<[usize; 3]>>,
    /// Named point sets (end points of a line, points that remove rigid-body motions).
    pub points: BTreeMap<String, Vec<usize>>,
    /// Element boundaries of a structured mesh (`None` for a general mesh): point location
    /// is then a binary search per axis instead of a scan of the elements.
    pub grid: Option<StructuredGrid>,
    /// The bins that locate points on a general mesh, built at its first [`Mesh::locate`].
    pub(crate) bins: std::sync::OnceLock<ElementBins>,
}

/// The tensor-product layout of a mesh made by [`Mesh::rectangle`] (element `ey * nx + ex`
/// covers $`[x_{e_x}, x_{e_x+1}] \times [y_{e_y}, y_{e_y+1}]`$ and is an affine rectangle) or
/// by [`Mesh::line`] (element `e` covers $`[x_e, x_{e+1}]`$; `ys` is empty).
#[derive(Clone, Debug, PartialEq)]
pub struct StructuredGrid {
    /// Element boundaries along X (`nx + 1`, increasing).
    pub xs: Vec<f64>,
    /// Element boundaries along Y (`ny + 1`, increasing; empty for a line).
    pub ys: Vec<f64>,
}

impl StructuredGrid {
    /// The interval of `breaks` containing `x` and the local coordinate in $`[-1, 1]`$.
    fn interval(breaks: &[f64], x: f64) -> Option<(usize, f64)> {
        let (first, last) = (breaks[0], breaks[breaks.len() - 1]);
        let slack = 1e-10 * (last - first);
        if !(x >= first - slack && x <= last + slack) {
            return None;
        }
        let count = breaks.len() - 1;
        let i = breaks.partition_point(|&b| b <= x).clamp(1, count) - 1;
        let local = 2.0 * (x - breaks[i]) / (breaks[i + 1] - breaks[i]) - 1.0;
        Some((i, local.clamp(-1.0, 1.0)))
    }

    /// The element containing `point` and its reference coordinates.
    fn locate(&self, point: [f64; 2]) -> Option<(usize, [f64; 2])> {
        let (ex, xi) = StructuredGrid::interval(&self.xs, point[0])?;
        if self.ys.is_empty() {
            let length = self.xs[self.xs.len() - 1] - self.xs[0];
            return (point[1].abs() <= 1e-10 * length).then_some((ex, [xi, 0.0]));
        }
        let (ey, eta) = StructuredGrid::interval(&self.ys, point[1])?;
        Some((ey * (self.xs.len() - 1) + ex, [xi, eta]))
    }
}

/// Errors building a mesh.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MeshError {
    /// A size or count that must be positive is not.
    #[error("mesh: {what} must be positive, got {value}")]
    NotPositive {
        /// Which quantity.
        what: &'static str,
        /// The value given.
        value: f64,
    },
    /// Grading below 1.
    #[error("mesh: grading must be >= 1 (largest/smallest element size), got {0}")]
    Grading(f64),
    /// No element at all.
    #[error("mesh: no elements")]
    NoElements,
    /// The connectivity is not a whole number of elements.
    #[error(
        "mesh: {length} connectivity entries are not a whole number of {kind} elements of {nodes} nodes"
    )]
    Connectivity {
        /// The element kind.
        kind: ElementKind,
        /// Its node count.
        nodes: usize,
        /// The connectivity's length.
        length: usize,
    },
    /// An element refers to a node that does not exist.
    #[error("mesh: element {element} refers to node {node}, but the mesh has {node_count} nodes")]
    NodeOutOfRange {
        /// Element index.
        element: usize,
        /// The node index given.
        node: usize,
        /// Number of nodes.
        node_count: usize,
    },
    /// A node coordinate is NaN or infinite.
    #[error("mesh: node {node} has a non-finite coordinate {coordinates:?}")]
    NonFiniteNode {
        /// Node index.
        node: usize,
        /// Its coordinates.
        coordinates: [f64; 2],
    },
    /// A node of a line mesh is off the X axis.
    #[error("mesh: node {node} of a {kind} mesh has Y = {y}; line elements lie on the X axis")]
    OffAxis {
        /// The element kind.
        kind: ElementKind,
        /// Node index.
        node: usize,
        /// Its Y.
        y: f64,
    },
    /// [`Mesh::line`] asked for a plane element.
    #[error("mesh: a line mesh needs a line element, not {0}")]
    NotALineElement(ElementKind),
    /// An edge set on a mesh without edges.
    #[error("mesh: edge set `{set}` on a {kind} mesh, which has no edges (name points instead)")]
    EdgesOnLine {
        /// The set's name.
        set: String,
        /// The element kind.
        kind: ElementKind,
    },
    /// A boundary set refers to a node that does not exist.
    #[error(
        "mesh: boundary set `{set}` refers to node {node}, but the mesh has {node_count} nodes"
    )]
    SetNodeOutOfRange {
        /// The set's name.
        set: String,
        /// The node index given.
        node: usize,
        /// Number of nodes.
        node_count: usize,
    },
}

/// Positions of `n + 1` element boundaries on $`[0, L]`$, symmetric geometric grading with the
/// smallest elements at both ends; `grading` is the ratio largest/smallest size (1 = uniform).
pub fn graded_breakpoints(length: f64, n: usize, grading: f64) -> Vec<f64> {
    let half = (n.saturating_sub(1)) / 2;
    let ratio = if half == 0 || grading <= 1.0 {
        1.0
    } else {
        grading.powf(1.0 / half as f64)
    };
    let sizes: Vec<f64> = (0..n)
        .map(|k| ratio.powi(k.min(n - 1 - k) as i32))
        .collect();
    let total: f64 = sizes.iter().sum();
    let mut x = Vec::with_capacity(n + 1);
    let mut acc = 0.0;
    x.push(0.0);
    for s in &sizes {
        acc += s / total * length;
        x.push(acc);
    }
    x[n] = length;
    x
}

/// Which ends of one axis of a structured mesh carry its smallest elements.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RefinedEnds {
    /// Neither: the elements are uniform whatever the ratio.
    Neither,
    /// The start of the axis ($`X = 0`$ or $`Y = 0`$).
    Start,
    /// The end of the axis ($`X = L_X`$ or $`Y = L_Y`$).
    End,
    /// Both ends, symmetrically ([`graded_breakpoints`]).
    Both,
}

/// The element sizes along one axis of a structured mesh: geometric, with `ratio` the largest
/// size over the smallest and the smallest at `ends`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisGrading {
    /// Largest over smallest element size ($`\ge 1`$; 1 = uniform).
    pub ratio: f64,
    /// Where the smallest elements sit.
    pub ends: RefinedEnds,
}

impl AxisGrading {
    /// Graded toward both ends by `ratio` (the grading of [`Mesh::rectangle`]).
    pub fn symmetric(ratio: f64) -> Self {
        AxisGrading {
            ratio,
            ends: RefinedEnds::Both,
        }
    }

    /// Positions of the `n + 1` element boundaries on $`[0, L]`$, first 0 and last $`L`$
    /// exactly. Toward both ends: [`graded_breakpoints`]. Toward one end: sizes
    /// $`s_k \propto r^k`$ growing away from it, $`r = \text{ratio}^{1/(n-1)}`$. Toward neither:
    /// uniform (the same numbers as [`graded_breakpoints`] with grading 1).
    pub fn breakpoints(&self, length: f64, n: usize) -> Vec<f64> {
        match self.ends {
            RefinedEnds::Both => graded_breakpoints(length, n, self.ratio),
            RefinedEnds::Neither => graded_breakpoints(length, n, 1.0),
            RefinedEnds::Start => one_sided_breakpoints(length, n, self.ratio),
            RefinedEnds::End => {
                let start = one_sided_breakpoints(length, n, self.ratio);
                let mut x: Vec<f64> = start.iter().rev().map(|s| length - s).collect();
                x[0] = 0.0;
                x[n] = length;
                x
            }
        }
    }
}

/// Breakpoints on $`[0, L]`$ with the sizes $`r^k`$ ($`k = 0 \dots n-1`$) growing from
/// $`X = 0`$, $`r^{n-1}`$ = `grading` (uniform for `grading` $`\le 1`$ or one element).
fn one_sided_breakpoints(length: f64, n: usize, grading: f64) -> Vec<f64> {
    let ratio = if n <= 1 || grading <= 1.0 {
        1.0
    } else {
        grading.powf(1.0 / (n - 1) as f64)
    };
    let sizes: Vec<f64> = (0..n).map(|k| ratio.powi(k as i32)).collect();
    let total: f64 = sizes.iter().sum();
    let mut x = Vec::with_capacity(n + 1);
    let mut acc = 0.0;
    x.push(0.0);
    for s in &sizes {
        acc += s / total * length;
        x.push(acc);
    }
    x[n] = length;
    x
}

/// Checks the sizes and grading of a structured generator.
fn check_sizes(sizes: &[(&'static str, f64)], grading: f64) -> Result<(), MeshError> {
    for &(what, value) in sizes {
        if value.is_nan() || value <= 0.0 || !value.is_finite() {
            return Err(MeshError::NotPositive { what, value });
        }
    }
    if grading.is_nan() || grading < 1.0 || !grading.is_finite() {
        return Err(MeshError::Grading(grading));
    }
    Ok(())
}

impl Mesh {
    /// A mesh of `kind` elements with the given nodes and connectivity
    /// ([`ElementKind::nodes`] entries per element), no boundary sets and no grid. Checks that
    /// the connectivity is whole elements of existing nodes, that coordinates are finite and
    /// that a line mesh lies on the X axis. (Element shapes — inverted or degenerate — are
    /// checked where they are evaluated: [`super::ElementValues::new`].)
    pub fn new(
        kind: ElementKind,
        nodes: Vec<[f64; 2]>,
        connectivity: Vec<usize>,
    ) -> Result<Mesh, MeshError> {
        let per_element = kind.nodes();
        if connectivity.is_empty() {
            return Err(MeshError::NoElements);
        }
        if !connectivity.len().is_multiple_of(per_element) {
            return Err(MeshError::Connectivity {
                kind,
                nodes: per_element,
                length: connectivity.len(),
            });
        }
        if let Some(position) = connectivity.iter().position(|&n| n >= nodes.len()) {
            return Err(MeshError::NodeOutOfRange {
                element: position / per_element,
                node: connectivity[position],
                node_count: nodes.len(),
            });
        }
        for (node, &coordinates) in nodes.iter().enumerate() {
            if !coordinates.iter().all(|c| c.is_finite()) {
                return Err(MeshError::NonFiniteNode { node, coordinates });
            }
            if kind.dimension() == 1 && coordinates[1] != 0.0 {
                let y = coordinates[1];
                return Err(MeshError::OffAxis { kind, node, y });
            }
        }
        Ok(Mesh {
            kind,
            nodes,
            connectivity,
            edges: BTreeMap::new(),
            points: BTreeMap::new(),
            grid: None,
            bins: std::sync::OnceLock::new(),
        })
    }

    /// Names an edge set (segments `[end, end, middle]`); replaces a set of the same name.
    pub fn insert_edge_set(
        &mut self,
        name: &str,
        segments: Vec<[usize; 3]>,
    ) -> Result<(), MeshError> {
        if self.kind.dimension() != 2 {
            return Err(MeshError::EdgesOnLine {
                set: name.to_string(),
                kind: self.kind,
            });
        }
        self.check_set_nodes(name, segments.iter().flatten())?;
        self.edges.insert(name.to_string(), segments);
        Ok(())
    }

    /// Names a point set; replaces a set of the same name.
    pub fn insert_point_set(&mut self, name: &str, nodes: Vec<usize>) -> Result<(), MeshError> {
        self.check_set_nodes(name, nodes.iter())?;
        self.points.insert(name.to_string(), nodes);
        Ok(())
    }

    fn check_set_nodes<'a>(
        &self,
        name: &str,
        mut nodes: impl Iterator<Item = &'a usize>,
    ) -> Result<(), MeshError> {
        match nodes.find(|&&n| n >= self.nodes.len()) {
            Some(&node) => Err(MeshError::SetNodeOutOfRange {
                set: name.to_string(),
                node,
                node_count: self.nodes.len(),
            }),
            None => Ok(()),
        }
    }

    /// Structured mesh of `[0, lx] × [0, ly]` with `nx × ny` Q8 elements, graded toward all edges by
    /// `grading` (1 = uniform). Edges are named `left` (X = 0), `right` (X = lx), `bottom` (Y = 0),
    /// `top` (Y = ly); segments run in increasing coordinate. Mid-side nodes sit at edge midpoints,
    /// so every element is an affine rectangle. Point sets `centre`, `left_middle`,
    /// `right_middle`, `bottom_middle`, `top_middle` hold the node nearest to each, and
    /// `bottom_left`, `bottom_right`, `top_left`, `top_right` the corners.
    pub fn rectangle(
        lx: f64,
        ly: f64,
        nx: usize,
        ny: usize,
        grading: f64,
    ) -> Result<Mesh, MeshError> {
        let both = AxisGrading::symmetric(grading);
        Mesh::graded_rectangle([lx, ly], [nx, ny], [both, both])
    }

    /// [`Mesh::rectangle`] of `[0, lengths[0]] × [0, lengths[1]]` with `counts` elements along
    /// X and Y and each axis graded on its own ([`AxisGrading::breakpoints`]): the smallest
    /// elements toward the edges (or, with both axes, the corners) where the solution varies.
    pub fn graded_rectangle(
        lengths: [f64; 2],
        counts: [usize; 2],
        gradings: [AxisGrading; 2],
    ) -> Result<Mesh, MeshError> {
        let ([lx, ly], [nx, ny]) = (lengths, counts);
        for grading in gradings {
            check_sizes(
                &[("lx", lx), ("ly", ly), ("nx", nx as f64), ("ny", ny as f64)],
                grading.ratio,
            )?;
        }
        let xs = gradings[0].breakpoints(lx, nx);
        let ys = gradings[1].breakpoints(ly, ny);
        let (nodes, numbering) = NodeGrid::number(&xs, &ys);
        let mut mesh = Mesh::new(ElementKind::Quad8, nodes, numbering.connectivity())?;
        for (name, segments) in numbering.edges() {
            mesh.insert_edge_set(&name, segments)?;
        }
        mesh.grid = Some(StructuredGrid { xs, ys });
        // Points for minimal in-plane supports: the centre, the middle of each edge, the corners.
        for (name, point) in [
            ("centre", [0.5 * lx, 0.5 * ly]),
            ("left_middle", [0.0, 0.5 * ly]),
            ("right_middle", [lx, 0.5 * ly]),
            ("bottom_middle", [0.5 * lx, 0.0]),
            ("top_middle", [0.5 * lx, ly]),
            ("bottom_left", [0.0, 0.0]),
            ("bottom_right", [lx, 0.0]),
            ("top_left", [0.0, ly]),
            ("top_right", [lx, ly]),
        ] {
            let node = mesh.nearest_node(point);
            mesh.insert_point_set(name, vec![node])?;
        }
        Ok(mesh)
    }

    /// Structured mesh of the segment $`[0, L]`$ of the X axis with `n` line elements of `kind`
    /// ([`ElementKind::Line3`] or [`ElementKind::Hermite2`]), graded toward both ends by
    /// `grading` (the same [`graded_breakpoints`] as the rectangle). Nodes are numbered left to
    /// right (a Line3's middle node between its ends). Point sets `left` (X = 0) and `right`
    /// (X = L).
    pub fn line(length: f64, n: usize, grading: f64, kind: ElementKind) -> Result<Mesh, MeshError> {
        check_sizes(&[("length", length), ("n", n as f64)], grading)?;
        let xs = graded_breakpoints(length, n, grading);
        let (nodes, connectivity): (Vec<f64>, Vec<usize>) = match kind {
            ElementKind::Hermite2 => (xs.clone(), (0..n).flat_map(|e| [e, e + 1]).collect()),
            ElementKind::Line3 => {
                let positions = (0..=2 * n)
                    .map(|k| {
                        if k.is_multiple_of(2) {
                            xs[k / 2]
                        } else {
                            0.5 * (xs[k / 2] + xs[k / 2 + 1])
                        }
                    })
                    .collect();
                let elements = (0..n).flat_map(|e| [2 * e, 2 * e + 2, 2 * e + 1]).collect();
                (positions, elements)
            }
            ElementKind::Quad8 => return Err(MeshError::NotALineElement(kind)),
        };
        let last = nodes.len() - 1;
        let nodes = nodes.into_iter().map(|x| [x, 0.0]).collect();
        let mut mesh = Mesh::new(kind, nodes, connectivity)?;
        mesh.insert_point_set("left", vec![0])?;
        mesh.insert_point_set("right", vec![last])?;
        mesh.grid = Some(StructuredGrid { xs, ys: Vec::new() });
        Ok(mesh)
    }

    /// Number of elements.
    pub fn element_count(&self) -> usize {
        self.connectivity.len() / self.kind.nodes()
    }

    /// The nodes of element `e`, in the element's order.
    pub fn element_nodes(&self, e: usize) -> &[usize] {
        let per_element = self.kind.nodes();
        &self.connectivity[e * per_element..][..per_element]
    }

    /// The nodes of every element, in element order.
    pub fn elements(&self) -> std::slice::ChunksExact<'_, usize> {
        self.connectivity.chunks_exact(self.kind.nodes())
    }

    /// [`Self::element_nodes`] for code monomorphised over the element `E` (the length is the
    /// constant `E::NODES`).
    #[inline(always)]
    pub(crate) fn nodes_of<E: Element>(&self, e: usize) -> &[usize] {
        &self.connectivity[e * E::NODES..][..E::NODES]
    }

    /// Node coordinates of element `e` in element order.
    pub fn element_coordinates(&self, e: usize) -> Vec<[f64; 2]> {
        self.element_nodes(e)
            .iter()
            .map(|&n| self.nodes[n])
            .collect()
    }

    /// Sorted, de-duplicated nodes of a named point or edge set (`None` if there is no such
    /// set; a point set wins over an edge set of the same name).
    pub fn boundary_nodes(&self, name: &str) -> Option<Vec<usize>> {
        if let Some(points) = self.points.get(name) {
            return Some(points.clone());
        }
        let segments = self.edges.get(name)?;
        let mut nodes: Vec<usize> = segments.iter().flat_map(|s| s.iter().copied()).collect();
        nodes.sort_unstable();
        nodes.dedup();
        Some(nodes)
    }

    /// Names of the edge and point sets.
    pub fn boundary_names(&self) -> Vec<&str> {
        self.edges
            .keys()
            .chain(self.points.keys())
            .map(String::as_str)
            .collect()
    }

    /// The node nearest to a point.
    pub fn nearest_node(&self, point: [f64; 2]) -> usize {
        let mut best = (f64::INFINITY, 0);
        for (i, p) in self.nodes.iter().enumerate() {
            let d = (p[0] - point[0]).powi(2) + (p[1] - point[1]).powi(2);
            if d < best.0 {
                best = (d, i);
            }
        }
        best.1
    }
}

/// The node numbering of [`Mesh::rectangle`]: a grid of $`(2n_x+1)\times(2n_y+1)`$ positions
/// (element corners and mid-sides; element centres carry no node), numbered row by row.
struct NodeGrid {
    /// Elements along X and Y.
    nx: usize,
    ny: usize,
    /// Positions along X and Y.
    gx: usize,
    gy: usize,
    /// Node number of each position (`usize::MAX` at element centres).
    id: Vec<usize>,
}

impl NodeGrid {
    /// Numbers the nodes of the grid on the element boundaries `xs`, `ys`; returns their
    /// coordinates and the numbering.
    fn number(xs: &[f64], ys: &[f64]) -> (Vec<[f64; 2]>, NodeGrid) {
        let (nx, ny) = (xs.len() - 1, ys.len() - 1);
        let gx = 2 * nx + 1;
        let gy = 2 * ny + 1;
        let coordinate = |breaks: &[f64], k: usize| {
            if k.is_multiple_of(2) {
                breaks[k / 2]
            } else {
                0.5 * (breaks[k / 2] + breaks[k / 2 + 1])
            }
        };
        let mut id = vec![usize::MAX; gx * gy];
        let mut nodes = Vec::new();
        for j in 0..gy {
            for i in 0..gx {
                if !i.is_multiple_of(2) && !j.is_multiple_of(2) {
                    continue;
                }
                id[j * gx + i] = nodes.len();
                nodes.push([coordinate(xs, i), coordinate(ys, j)]);
            }
        }
        let grid = NodeGrid { nx, ny, gx, gy, id };
        (nodes, grid)
    }

    /// The node at position $`(i, j)`$.
    fn at(&self, i: usize, j: usize) -> usize {
        self.id[j * self.gx + i]
    }

    /// Element connectivity in VTK Q8 order, row by row.
    fn connectivity(&self) -> Vec<usize> {
        let mut elements = Vec::with_capacity(8 * self.nx * self.ny);
        for ey in 0..self.ny {
            for ex in 0..self.nx {
                let (i, j) = (2 * ex, 2 * ey);
                elements.extend([
                    self.at(i, j),
                    self.at(i + 2, j),
                    self.at(i + 2, j + 2),
                    self.at(i, j + 2),
                    self.at(i + 1, j),
                    self.at(i + 2, j + 1),
                    self.at(i + 1, j + 2),
                    self.at(i, j + 1),
                ]);
            }
        }
        elements
    }

    /// The four named edges, segments `[end, end, middle]` in increasing coordinate.
    fn edges(&self) -> BTreeMap<String, Vec<[usize; 3]>> {
        let (gx, gy) = (self.gx, self.gy);
        // Segment `e` of the line of positions `position(k)`.
        let segments = |count: usize, position: &dyn Fn(usize) -> (usize, usize)| {
            (0..count)
                .map(|e| {
                    let node = |k| {
                        let (i, j) = position(k);
                        self.at(i, j)
                    };
                    [node(2 * e), node(2 * e + 2), node(2 * e + 1)]
                })
                .collect()
        };
        let mut edges = BTreeMap::new();
        edges.insert("bottom".to_string(), segments(self.nx, &|k| (k, 0)));
        edges.insert("top".to_string(), segments(self.nx, &|k| (k, gy - 1)));
        edges.insert("left".to_string(), segments(self.ny, &|k| (0, k)));
        edges.insert("right".to_string(), segments(self.ny, &|k| (gx - 1, k)));
        edges
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rectangle_counts_and_edges() {
        let m = Mesh::rectangle(4.0, 2.0, 4, 2, 1.0).unwrap();
        // (2nx+1)(2ny+1) − nx ny
        assert_eq!(m.nodes.len(), 9 * 5 - 8);
        assert_eq!(m.element_count(), 8);
        assert_eq!(m.boundary_nodes("left").unwrap().len(), 5);
        assert_eq!(m.boundary_nodes("top").unwrap().len(), 9);
        for &n in &m.boundary_nodes("right").unwrap() {
            assert_eq!(m.nodes[n][0], 4.0);
        }
        for &n in &m.boundary_nodes("top").unwrap() {
            assert_eq!(m.nodes[n][1], 2.0);
        }
    }

    #[test]
    fn graded_breakpoints_respect_ratio_and_length() {
        let x = graded_breakpoints(10.0, 9, 4.0);
        assert_eq!(x.len(), 10);
        assert!((x[9] - 10.0).abs() < 1e-14);
        let sizes: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
        let max = sizes.iter().cloned().fold(0.0, f64::max);
        let min = sizes.iter().cloned().fold(f64::INFINITY, f64::min);
        assert!((max / min - 4.0).abs() < 1e-12);
        assert!((sizes[0] - sizes[8]).abs() < 1e-14);
    }

    #[test]
    fn one_sided_grading_puts_the_smallest_elements_at_the_named_end() {
        let sizes = |grading: AxisGrading| {
            let x = grading.breakpoints(10.0, 6);
            assert_eq!((x[0], x[6]), (0.0, 10.0));
            x.windows(2).map(|w| w[1] - w[0]).collect::<Vec<f64>>()
        };
        let start = sizes(AxisGrading {
            ratio: 5.0,
            ends: RefinedEnds::Start,
        });
        assert!((start[5] / start[0] - 5.0).abs() < 1e-12, "{start:?}");
        assert!(start.windows(2).all(|w| w[1] > w[0]));
        let end = sizes(AxisGrading {
            ratio: 5.0,
            ends: RefinedEnds::End,
        });
        assert!((end[0] / end[5] - 5.0).abs() < 1e-12, "{end:?}");
        let neither = AxisGrading {
            ratio: 5.0,
            ends: RefinedEnds::Neither,
        };
        assert_eq!(
            neither.breakpoints(10.0, 6),
            graded_breakpoints(10.0, 6, 1.0)
        );
        assert_eq!(
            AxisGrading::symmetric(3.0).breakpoints(10.0, 7),
            graded_breakpoints(10.0, 7, 3.0)
        );
    }

    #[test]
    fn a_rectangle_graded_per_axis_keeps_its_edges_and_the_plain_one_is_unchanged() {
        let x = AxisGrading {
            ratio: 4.0,
            ends: RefinedEnds::End,
        };
        let mesh =
            Mesh::graded_rectangle([4.0, 2.0], [4, 3], [x, AxisGrading::symmetric(2.0)]).unwrap();
        let grid = mesh.grid.as_ref().unwrap();
        assert!(grid.xs[4] - grid.xs[3] < grid.xs[1] - grid.xs[0]);
        for &n in &mesh.boundary_nodes("right").unwrap() {
            assert_eq!(mesh.nodes[n][0], 4.0);
        }
        let plain = Mesh::rectangle(4.0, 2.0, 4, 3, 2.0).unwrap();
        let same = AxisGrading::symmetric(2.0);
        let general = Mesh::graded_rectangle([4.0, 2.0], [4, 3], [same, same]).unwrap();
        assert_eq!(plain.nodes, general.nodes);
        assert_eq!(plain.connectivity, general.connectivity);
    }

    #[test]
    fn the_outline_of_a_rectangle_is_its_four_edges() {
        let mesh = Mesh::rectangle(4.0, 2.0, 4, 3, 1.0).unwrap();
        let outline = mesh.outline();
        assert_eq!(outline.len(), 2 * (4 + 3));
        let mut edges: Vec<[usize; 3]> = mesh.edges.values().flatten().copied().collect();
        let sorted = |segments: &mut Vec<[usize; 3]>| {
            for s in segments.iter_mut() {
                s[..2].sort_unstable();
            }
            segments.sort_unstable();
        };
        let mut outline = outline;
        sorted(&mut outline);
        sorted(&mut edges);
        assert_eq!(outline, edges);
    }

    #[test]
    fn invalid_sizes_are_errors() {
        assert!(Mesh::rectangle(-1.0, 1.0, 2, 2, 1.0).is_err());
        assert!(Mesh::rectangle(1.0, 1.0, 0, 2, 1.0).is_err());
        assert!(Mesh::rectangle(1.0, 1.0, 2, 2, 0.5).is_err());
        let nan = AxisGrading::symmetric(f64::NAN);
        let fine = AxisGrading::symmetric(1.0);
        assert!(Mesh::graded_rectangle([1.0, 1.0], [2, 2], [fine, nan]).is_err());
    }
}

impl Mesh {
    /// The element containing `point` and its reference coordinates. On a structured mesh, a
    /// binary search per axis ($`O(\log n)`$); otherwise the first element, in element order,
    /// among those whose box holds the point ([`ElementBins`], built once), whose map's inverse
    /// ([`Element::reference_of`]) puts it in its reference domain — the element
    /// [`Self::locate_by_scan`] finds. `None` outside the mesh (a line mesh: off the segment or
    /// off the axis; a plane mesh: outside its outline or in a hole).
    pub fn locate(&self, point: [f64; 2]) -> Option<(usize, [f64; 2])> {
        match &self.grid {
            Some(grid) => grid.locate(point),
            None => {
                let bins = self.bins.get_or_init(|| ElementBins::new(self));
                let candidates = bins.candidates(point);
                with_element!(self.kind, E => self.locate_among::<E>(candidates, point))
            }
        }
    }

    /// Whether `point` lies in the domain (in an element or on its boundary).
    pub fn contains(&self, point: [f64; 2]) -> bool {
        self.locate(point).is_some()
    }

    fn locate_among<E: Element>(
        &self,
        candidates: &[usize],
        point: [f64; 2],
    ) -> Option<(usize, [f64; 2])> {
        candidates.iter().find_map(|&e| {
            E::reference_of(&self.element_coordinates(e), point).map(|reference| (e, reference))
        })
    }

    /// [`Self::locate`] for a general mesh: the first element, in element order, whose map's
    /// inverse puts `point` in its reference domain.
    pub fn locate_by_scan(&self, point: [f64; 2]) -> Option<(usize, [f64; 2])> {
        with_element!(self.kind, E => self.locate_by_scan_on::<E>(point))
    }

    fn locate_by_scan_on<E: Element>(&self, point: [f64; 2]) -> Option<(usize, [f64; 2])> {
        (0..self.element_count()).find_map(|e| {
            E::reference_of(&self.element_coordinates(e), point).map(|reference| (e, reference))
        })
    }

    /// Value at `point` of field `field` of nodal dofs stored node-major with `field_count`
    /// fields per node and the element's components per field
    /// (`values[(node * field_count + field) * components + component]`; for Lagrange
    /// elements `values[node * field_count + field]`). `None` outside the mesh.
    pub fn interpolate(
        &self,
        values: &[f64],
        field_count: usize,
        field: usize,
        point: [f64; 2],
    ) -> Option<f64> {
        let (e, reference) = self.locate(point)?;
        Some(with_element!(self.kind, E => {
            self.interpolate_on::<E, { E::FUNCTIONS }>(e, reference, values, field_count, field)
        }))
    }

    /// [`Self::interpolate`] in element `e` at `reference`: $`\sum_b \varphi_b U_b`$ in local
    /// function order.
    fn interpolate_on<E: Element, const B: usize>(
        &self,
        e: usize,
        reference: [f64; 2],
        values: &[f64],
        field_count: usize,
        field: usize,
    ) -> f64 {
        let mut weights = [0.0; B];
        E::value_weights(&self.element_coordinates(e), reference, &mut weights);
        let nodes = self.nodes_of::<E>(e);
        weights
            .iter()
            .enumerate()
            .map(|(b, weight)| {
                let (node, component) = (nodes[b / E::COMPONENTS], b % E::COMPONENTS);
                weight * values[(node * field_count + field) * E::COMPONENTS + component]
            })
            .sum()
    }

    /// Extent of element `e` along the unit vector `direction`:
    /// $`\max_a \mathbf x_a\cdot\mathbf e - \min_a \mathbf x_a\cdot\mathbf e`$ over its nodes
    /// (an affine rectangle's width along an axis is exactly its side).
    pub fn element_extent_along(&self, e: usize, direction: [f64; 2]) -> f64 {
        let (low, high) = self.element_nodes(e).iter().fold(
            (f64::INFINITY, f64::NEG_INFINITY),
            |(low, high), &n| {
                let [x, y] = self.nodes[n];
                let along = x * direction[0] + y * direction[1];
                (low.min(along), high.max(along))
            },
        );
        high - low
    }

    /// The outline of a Q8 mesh: the sides that belong to one element only (outer outline
    /// and the rims of holes), as segments `[end, end, middle]` in element order; empty for
    /// other elements.
    pub fn outline(&self) -> Vec<[usize; 3]> {
        if self.kind != ElementKind::Quad8 {
            return Vec::new();
        }
        let sides = |e: usize| {
            let n = self.element_nodes(e);
            [(0, 1, 4), (1, 2, 5), (2, 3, 6), (3, 0, 7)].map(|(a, b, m)| [n[a], n[b], n[m]])
        };
        let key = |[a, b, _]: [usize; 3]| (a.min(b), a.max(b));
        let mut uses: BTreeMap<(usize, usize), usize> = BTreeMap::new();
        for e in 0..self.element_count() {
            for side in sides(e) {
                *uses.entry(key(side)).or_default() += 1;
            }
        }
        (0..self.element_count())
            .flat_map(sides)
            .filter(|&side| uses[&key(side)] == 1)
            .collect()
    }

    /// Bounding box `[x0, x1, y0, y1]`.
    pub fn bounds(&self) -> [f64; 4] {
        let mut b = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for [x, y] in &self.nodes {
            b[0] = b[0].min(*x);
            b[1] = b[1].max(*x);
            b[2] = b[2].min(*y);
            b[3] = b[3].max(*y);
        }
        b
    }
}

#[cfg(test)]
mod locate_tests {
    use super::*;

    #[test]
    fn interpolation_reproduces_quadratics_on_graded_mesh() {
        let mesh = Mesh::rectangle(4.0, 3.0, 5, 4, 3.0).unwrap();
        let f = |x: f64, y: f64| 1.0 + x - 2.0 * y + 0.3 * x * x - 0.2 * x * y + 0.1 * y * y;
        let values: Vec<f64> = mesh.nodes.iter().map(|p| f(p[0], p[1])).collect();
        for p in [
            [0.0, 0.0],
            [4.0, 3.0],
            [1.234, 2.5],
            [2.0, 1.5],
            [3.99, 0.01],
        ] {
            let v = mesh.interpolate(&values, 1, 0, p).unwrap();
            assert!((v - f(p[0], p[1])).abs() < 1e-12, "{p:?}");
        }
        assert!(mesh.interpolate(&values, 1, 0, [4.5, 1.0]).is_none());
    }

    #[test]
    fn structured_location_agrees_with_the_element_scan() {
        let mesh = Mesh::rectangle(4.0, 3.0, 5, 4, 3.0).unwrap();
        for p in [
            [0.0, 0.0],
            [4.0, 3.0],
            [1.234, 2.5],
            [2.0, 1.5],
            [3.99, 0.01],
            [0.7, 3.0],
        ] {
            let (e, [xi, eta]) = mesh.locate(p).unwrap();
            let (e2, [xi2, eta2]) = mesh.locate_by_scan(p).unwrap();
            // On a shared element boundary both elements are right; compare the mapped point.
            let map = |e: usize, xi: f64, eta: f64| {
                let n = crate::fem::element::Quad8::shape_values(xi, eta);
                let c = mesh.element_coordinates(e);
                let mut x = [0.0; 2];
                for k in 0..8 {
                    x[0] += n[k] * c[k][0];
                    x[1] += n[k] * c[k][1];
                }
                x
            };
            let (a, b) = (map(e, xi, eta), map(e2, xi2, eta2));
            assert!(
                (a[0] - p[0]).abs() < 1e-12 && (a[1] - p[1]).abs() < 1e-12,
                "{p:?}"
            );
            assert!(
                (b[0] - p[0]).abs() < 1e-12 && (b[1] - p[1]).abs() < 1e-12,
                "{p:?}"
            );
        }
        assert!(mesh.locate([-0.1, 1.0]).is_none());
    }
}
