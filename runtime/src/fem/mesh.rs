//! Meshes of Q8 elements and the structured rectangle generator.

use super::element::QUAD8_NODES;
use std::collections::BTreeMap;

/// A mesh of Q8 elements with named edge sets.
#[derive(Clone, Debug)]
pub struct Mesh {
    /// Node coordinates $`(X, Y)`$.
    pub nodes: Vec<[f64; 2]>,
    /// Element connectivity in VTK Q8 order (corners counter-clockwise, then mid-sides).
    pub elements: Vec<[usize; QUAD8_NODES]>,
    /// Named boundary edges, each a list of 3-node segments `[end, end, middle]`.
    pub edges: BTreeMap<String, Vec<[usize; 3]>>,
    /// Named node sets that are not edges (single points used to remove rigid-body motions).
    pub points: BTreeMap<String, Vec<usize>>,
    /// Element boundaries of a structured rectangle (`None` for a general mesh): point location
    /// is then a binary search per axis instead of a scan of the elements.
    pub grid: Option<StructuredGrid>,
}

/// The tensor-product layout of a mesh made by [`Mesh::rectangle`]: element `ey * nx + ex`
/// covers $`[x_{e_x}, x_{e_x+1}] \times [y_{e_y}, y_{e_y+1}]`$ and is an affine rectangle.
#[derive(Clone, Debug, PartialEq)]
pub struct StructuredGrid {
    /// Element boundaries along X (`nx + 1`, increasing).
    pub xs: Vec<f64>,
    /// Element boundaries along Y (`ny + 1`, increasing).
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

impl Mesh {
    /// Structured mesh of `[0, lx] × [0, ly]` with `nx × ny` Q8 elements, graded toward all edges by
    /// `grading` (1 = uniform). Edges are named `left` (X = 0), `right` (X = lx), `bottom` (Y = 0),
    /// `top` (Y = ly); segments run in increasing coordinate. Mid-side nodes sit at edge midpoints,
    /// so every element is an affine rectangle.
    pub fn rectangle(
        lx: f64,
        ly: f64,
        nx: usize,
        ny: usize,
        grading: f64,
    ) -> Result<Mesh, MeshError> {
        for (what, value) in [("lx", lx), ("ly", ly), ("nx", nx as f64), ("ny", ny as f64)] {
            if value.is_nan() || value <= 0.0 || !value.is_finite() {
                return Err(MeshError::NotPositive { what, value });
            }
        }
        if grading.is_nan() || grading < 1.0 || !grading.is_finite() {
            return Err(MeshError::Grading(grading));
        }
        let xs = graded_breakpoints(lx, nx, grading);
        let ys = graded_breakpoints(ly, ny, grading);
        let (nodes, numbering) = NodeGrid::number(&xs, &ys);
        let mut mesh = Mesh {
            nodes,
            elements: numbering.elements(),
            edges: numbering.edges(),
            points: BTreeMap::new(),
            grid: Some(StructuredGrid { xs, ys }),
        };
        // Points for minimal in-plane supports: the centre, and the middle of each edge.
        for (name, point) in [
            ("centre", [0.5 * lx, 0.5 * ly]),
            ("left_middle", [0.0, 0.5 * ly]),
            ("right_middle", [lx, 0.5 * ly]),
            ("bottom_middle", [0.5 * lx, 0.0]),
            ("top_middle", [0.5 * lx, ly]),
        ] {
            let node = mesh.nearest_node(point);
            mesh.points.insert(name.to_string(), vec![node]);
        }
        Ok(mesh)
    }

    /// Node coordinates of element `e` in element order.
    pub fn element_coordinates(&self, e: usize) -> [[f64; 2]; QUAD8_NODES] {
        let mut c = [[0.0; 2]; QUAD8_NODES];
        for (k, &n) in self.elements[e].iter().enumerate() {
            c[k] = self.nodes[n];
        }
        c
    }

    /// Sorted, de-duplicated nodes of a named edge or point set (`None` if there is no such set).
    pub fn edge_nodes(&self, name: &str) -> Option<Vec<usize>> {
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
    pub fn edge_names(&self) -> Vec<&str> {
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
    fn elements(&self) -> Vec<[usize; QUAD8_NODES]> {
        let mut elements = Vec::with_capacity(self.nx * self.ny);
        for ey in 0..self.ny {
            for ex in 0..self.nx {
                let (i, j) = (2 * ex, 2 * ey);
                elements.push([
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
        assert_eq!(m.elements.len(), 8);
        assert_eq!(m.edge_nodes("left").unwrap().len(), 5);
        assert_eq!(m.edge_nodes("top").unwrap().len(), 9);
        for &n in &m.edge_nodes("right").unwrap() {
            assert_eq!(m.nodes[n][0], 4.0);
        }
        for &n in &m.edge_nodes("top").unwrap() {
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
    fn invalid_sizes_are_errors() {
        assert!(Mesh::rectangle(-1.0, 1.0, 2, 2, 1.0).is_err());
        assert!(Mesh::rectangle(1.0, 1.0, 0, 2, 1.0).is_err());
        assert!(Mesh::rectangle(1.0, 1.0, 2, 2, 0.5).is_err());
    }
}

impl Mesh {
    /// The element containing `point` and its reference coordinates $`(\xi,\eta)`$. On a
    /// structured rectangle, a binary search per axis ($`O(\log n)`$); otherwise a bounding-box
    /// scan of the elements with Newton inversion of the isoparametric map. `None` outside the
    /// mesh.
    pub fn locate(&self, point: [f64; 2]) -> Option<(usize, [f64; 2])> {
        if let Some(grid) = &self.grid {
            let (ex, xi) = StructuredGrid::interval(&grid.xs, point[0])?;
            let (ey, eta) = StructuredGrid::interval(&grid.ys, point[1])?;
            return Some((ey * (grid.xs.len() - 1) + ex, [xi, eta]));
        }
        self.locate_by_scan(point)
    }

    /// [`Self::locate`] for a general mesh: scan of the elements' bounding boxes.
    pub fn locate_by_scan(&self, point: [f64; 2]) -> Option<(usize, [f64; 2])> {
        use super::element::Quad8;
        let tolerance = 1e-10;
        for (e, nodes) in self.elements.iter().enumerate() {
            let (mut x0, mut x1, mut y0, mut y1) = (
                f64::INFINITY,
                f64::NEG_INFINITY,
                f64::INFINITY,
                f64::NEG_INFINITY,
            );
            for &n in nodes {
                let [x, y] = self.nodes[n];
                x0 = x0.min(x);
                x1 = x1.max(x);
                y0 = y0.min(y);
                y1 = y1.max(y);
            }
            let slack = tolerance * ((x1 - x0) + (y1 - y0));
            if point[0] < x0 - slack
                || point[0] > x1 + slack
                || point[1] < y0 - slack
                || point[1] > y1 + slack
            {
                continue;
            }
            let coordinates = self.element_coordinates(e);
            let mut reference = [0.0, 0.0];
            for _ in 0..20 {
                let n = Quad8::shape_values(reference[0], reference[1]);
                let dn = Quad8::shape_reference_gradients(reference[0], reference[1]);
                let mut x = [0.0; 2];
                let mut jac = [[0.0; 2]; 2];
                for k in 0..QUAD8_NODES {
                    for a in 0..2 {
                        x[a] += n[k] * coordinates[k][a];
                        for b in 0..2 {
                            jac[a][b] += coordinates[k][a] * dn[k][b];
                        }
                    }
                }
                let r = [point[0] - x[0], point[1] - x[1]];
                let det = jac[0][0] * jac[1][1] - jac[0][1] * jac[1][0];
                if det.abs() < f64::MIN_POSITIVE {
                    break;
                }
                let d = [
                    (jac[1][1] * r[0] - jac[0][1] * r[1]) / det,
                    (-jac[1][0] * r[0] + jac[0][0] * r[1]) / det,
                ];
                reference[0] += d[0];
                reference[1] += d[1];
                if d[0].abs() + d[1].abs() < 1e-14 {
                    break;
                }
            }
            if reference[0].abs() <= 1.0 + 1e-9 && reference[1].abs() <= 1.0 + 1e-9 {
                return Some((e, reference));
            }
        }
        None
    }

    /// Value at `point` of a nodal field stored node-major with `field_count` fields per node
    /// (`values[node * field_count + field]`). `None` outside the mesh.
    pub fn interpolate(
        &self,
        values: &[f64],
        field_count: usize,
        field: usize,
        point: [f64; 2],
    ) -> Option<f64> {
        let (e, [xi, eta]) = self.locate(point)?;
        let n = super::element::Quad8::shape_values(xi, eta);
        Some(
            self.elements[e]
                .iter()
                .enumerate()
                .map(|(k, &node)| n[k] * values[node * field_count + field])
                .sum(),
        )
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
                for k in 0..QUAD8_NODES {
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
