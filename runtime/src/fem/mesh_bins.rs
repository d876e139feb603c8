//! Point location on a general mesh: a uniform grid of bins over the mesh, each listing the
//! elements whose bounding box meets it ([`ElementBins`]), so that [`super::Mesh::locate`]
//! inverts the map of a few elements instead of every one.

use super::element::ElementKind;
use super::mesh::Mesh;

/// Elements listed by the bins of a uniform grid over the mesh's bounding box (about one
/// element per bin), in compressed rows: the elements of bin `b` are
/// `elements[start[b]..start[b + 1]]`, in increasing element order.
#[derive(Clone, Debug)]
pub struct ElementBins {
    /// Lower-left corner of the grid.
    origin: [f64; 2],
    /// Upper-right corner of the grid.
    upper: [f64; 2],
    /// Size of a bin along X and Y.
    size: [f64; 2],
    /// Bins along X and Y.
    counts: [usize; 2],
    /// Row starts, one per bin plus one.
    start: Vec<usize>,
    /// Element indices, bin after bin.
    elements: Vec<usize>,
}

/// The box `[x0, x1, y0, y1]` that holds element `e` whole. A quadratic edge through its ends
/// $`\mathbf a, \mathbf b`$ and middle node $`\mathbf m`$ lies in the hull of $`\mathbf a`$,
/// $`\mathbf b`$ and its Bézier control point $`2\mathbf m - (\mathbf a + \mathbf b)/2`$, so a
/// curved Q8 side that bulges past its nodes is still inside; other elements get their nodes'
/// box widened by a tenth.
fn element_box(mesh: &Mesh, e: usize) -> [f64; 4] {
    let points = mesh.element_coordinates(e);
    let mut all = points.clone();
    let widen = if mesh.kind == ElementKind::Quad8 {
        for (a, b, m) in [(0, 1, 4), (1, 2, 5), (2, 3, 6), (3, 0, 7)] {
            let control = |k: usize| 2.0 * points[m][k] - 0.5 * (points[a][k] + points[b][k]);
            all.push([control(0), control(1)]);
        }
        0.0
    } else {
        0.1
    };
    let mut bounds = [
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    ];
    for [x, y] in all {
        bounds = [
            bounds[0].min(x),
            bounds[1].max(x),
            bounds[2].min(y),
            bounds[3].max(y),
        ];
    }
    let pad = widen * (bounds[1] - bounds[0]).hypot(bounds[3] - bounds[2]);
    [
        bounds[0] - pad,
        bounds[1] + pad,
        bounds[2] - pad,
        bounds[3] + pad,
    ]
}

impl ElementBins {
    /// The bins of `mesh`: about one element per bin, square-ish bins over the elements' boxes.
    pub fn new(mesh: &Mesh) -> ElementBins {
        let boxes: Vec<[f64; 4]> = (0..mesh.element_count())
            .map(|e| element_box(mesh, e))
            .collect();
        let mut extent = [
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ];
        for b in &boxes {
            extent = [
                extent[0].min(b[0]),
                extent[1].max(b[1]),
                extent[2].min(b[2]),
                extent[3].max(b[3]),
            ];
        }
        let (width, height) = (extent[1] - extent[0], extent[3] - extent[2]);
        let count = boxes.len().max(1) as f64;
        let along_x = (count * width / height.max(f64::MIN_POSITIVE))
            .sqrt()
            .clamp(1.0, count);
        let counts = [
            along_x.ceil() as usize,
            (count / along_x).ceil().max(1.0) as usize,
        ];
        let size = [
            (width / counts[0] as f64).max(f64::MIN_POSITIVE),
            (height / counts[1] as f64).max(f64::MIN_POSITIVE),
        ];
        let mut bins = ElementBins {
            origin: [extent[0], extent[2]],
            upper: [extent[1], extent[3]],
            size,
            counts,
            start: Vec::new(),
            elements: Vec::new(),
        };
        bins.fill(&boxes);
        bins
    }

    /// The bin range `[low, high]` along `axis` that `[from, to]` meets.
    fn range(&self, axis: usize, from: f64, to: f64) -> (usize, usize) {
        let index = |value: f64| {
            let cell = ((value - self.origin[axis]) / self.size[axis]).floor();
            cell.clamp(0.0, (self.counts[axis] - 1) as f64) as usize
        };
        (index(from), index(to))
    }

    /// Lists each element in every bin its box meets (counting sort: rows in bin order,
    /// elements in increasing order within a row).
    fn fill(&mut self, boxes: &[[f64; 4]]) {
        let bins = self.counts[0] * self.counts[1];
        let mut members: Vec<(usize, usize)> = Vec::new();
        for (e, b) in boxes.iter().enumerate() {
            let (x0, x1) = self.range(0, b[0], b[1]);
            let (y0, y1) = self.range(1, b[2], b[3]);
            for j in y0..=y1 {
                for i in x0..=x1 {
                    members.push((j * self.counts[0] + i, e));
                }
            }
        }
        let mut start = vec![0usize; bins + 1];
        for &(bin, _) in &members {
            start[bin + 1] += 1;
        }
        for b in 0..bins {
            start[b + 1] += start[b];
        }
        let mut next = start.clone();
        let mut elements = vec![0usize; members.len()];
        for (bin, e) in members {
            elements[next[bin]] = e;
            next[bin] += 1;
        }
        self.start = start;
        self.elements = elements;
    }

    /// The elements whose box may hold `point`, in increasing order (empty off the grid).
    pub fn candidates(&self, point: [f64; 2]) -> &[usize] {
        let inside =
            |axis: usize| point[axis] >= self.origin[axis] && point[axis] <= self.upper[axis];
        if !(inside(0) && inside(1)) {
            return &[];
        }
        let (i, _) = self.range(0, point[0], point[0]);
        let (j, _) = self.range(1, point[1], point[1]);
        let bin = j * self.counts[0] + i;
        &self.elements[self.start[bin]..self.start[bin + 1]]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rectangle mesh bent by a smooth map (curved Q8 sides), without its grid: the bins find
    /// the element the scan finds, inside and outside, and are built once.
    #[test]
    fn the_bins_locate_what_the_scan_locates_on_a_curved_mesh() {
        let mut mesh = Mesh::rectangle(4.0, 3.0, 7, 5, 1.5).unwrap();
        mesh.grid = None;
        for node in &mut mesh.nodes {
            let [x, y] = *node;
            *node = [x + 0.3 * (0.9 * y).sin(), y + 0.25 * (1.1 * x).sin()];
        }
        let mut found = 0;
        for i in 0..=60 {
            for j in 0..=50 {
                let point = [-0.5 + 5.0 * i as f64 / 60.0, -0.5 + 4.0 * j as f64 / 50.0];
                let scan = mesh.locate_by_scan(point);
                assert_eq!(mesh.locate(point), scan, "{point:?}");
                found += usize::from(scan.is_some());
            }
        }
        assert!(found > 1000, "{found}");
        let bins = mesh.bins.get().unwrap();
        assert_eq!(bins.start.len(), bins.counts[0] * bins.counts[1] + 1);
    }
}
