//! Where the tags of a panel's points go (`16×8`, `N=12`, `1e-5`): each beside its point, on
//! none of the other points and none of the tags placed before it, inside the panel, crossing
//! as few of the lines as it can; a tag with no free place is left out rather than drawn over
//! another. Everything here is in pixels of the plotting area, $`y`$ downwards.

/// A position in pixels: $`(x, y)`$.
pub(super) type Pixel = (f64, f64);

/// A line segment between two positions.
pub(super) type Segment = (Pixel, Pixel);

/// A tag to place: its point, and the width and height of its text.
pub(super) type Tag = (Pixel, (f64, f64));

/// A rectangle in pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rectangle {
    pub left: f64,
    pub top: f64,
    pub right: f64,
    pub bottom: f64,
}

impl Rectangle {
    fn overlaps(&self, other: &Rectangle) -> bool {
        self.left < other.right
            && other.left < self.right
            && self.top < other.bottom
            && other.top < self.bottom
    }

    fn contains(&self, other: &Rectangle) -> bool {
        other.left >= self.left
            && other.right <= self.right
            && other.top >= self.top
            && other.bottom <= self.bottom
    }

    /// Whether the disc of `radius` around `centre` reaches into the rectangle.
    fn touches_disc(&self, centre: (f64, f64), radius: f64) -> bool {
        let dx = centre.0 - centre.0.clamp(self.left, self.right);
        let dy = centre.1 - centre.1.clamp(self.top, self.bottom);
        dx * dx + dy * dy < radius * radius
    }

    /// Whether the segment from `a` to `b` passes through the rectangle (Liang–Barsky
    /// clipping of the segment's parameter $`t \in [0, 1]`$).
    fn crosses(&self, a: (f64, f64), b: (f64, f64)) -> bool {
        let (dx, dy) = (b.0 - a.0, b.1 - a.1);
        let (mut enter, mut leave) = (0.0_f64, 1.0_f64);
        for (p, q) in [
            (-dx, a.0 - self.left),
            (dx, self.right - a.0),
            (-dy, a.1 - self.top),
            (dy, self.bottom - a.1),
        ] {
            if p == 0.0 {
                if q < 0.0 {
                    return false;
                }
            } else if p < 0.0 {
                enter = enter.max(q / p);
            } else {
                leave = leave.min(q / p);
            }
        }
        enter < leave
    }
}

/// The picture a panel's tags are placed into.
pub(super) struct Scene<'a> {
    /// The plotting area (tags stay inside).
    pub bounds: Rectangle,
    /// Every point drawn, as a disc of [`Scene::marker_radius`].
    pub markers: &'a [Pixel],
    /// Radius of a point's disc, with a little room around it.
    pub marker_radius: f64,
    /// Every line segment drawn.
    pub segments: &'a [Segment],
}

/// Top-left corners of the tags of `size` (width, height) beside their `points`, in order, or
/// `None` for a tag that has no free place. Candidates, in order of preference: up-right (the
/// usual place), right, down-right, up-left, left, down-left, above, below — then the same
/// twice as far; the first free one crossing the fewest segments wins.
pub(super) fn place_tags(scene: &Scene, tags: &[Tag]) -> Vec<Option<(f64, f64)>> {
    let mut placed: Vec<Rectangle> = Vec::new();
    tags.iter()
        .map(|&(point, size)| {
            let best = candidates(point, size, scene.marker_radius)
                .enumerate()
                .filter(|(_, r)| is_free(scene, &placed, r))
                .min_by_key(|(order, r)| (crossings(scene, r), *order))
                .map(|(_, r)| r);
            best.map(|r| {
                placed.push(r);
                (r.left, r.top)
            })
        })
        .collect()
}

fn candidates(
    point: (f64, f64),
    (width, height): (f64, f64),
    radius: f64,
) -> impl Iterator<Item = Rectangle> {
    let (x, y) = point;
    [1.0, 2.5].into_iter().flat_map(move |ring| {
        let d = ring * radius;
        let diagonal = 0.7 * d;
        [
            (x + diagonal, y - diagonal - height),
            (x + d, y - height / 2.0),
            (x + diagonal, y + diagonal),
            (x - diagonal - width, y - diagonal - height),
            (x - d - width, y - height / 2.0),
            (x - diagonal - width, y + diagonal),
            (x - width / 2.0, y - d - height),
            (x - width / 2.0, y + d),
        ]
        .map(|(left, top)| Rectangle {
            left,
            top,
            right: left + width,
            bottom: top + height,
        })
    })
}

fn is_free(scene: &Scene, placed: &[Rectangle], candidate: &Rectangle) -> bool {
    scene.bounds.contains(candidate)
        && !scene
            .markers
            .iter()
            .any(|&m| candidate.touches_disc(m, scene.marker_radius))
        && !placed.iter().any(|p| p.overlaps(candidate))
}

fn crossings(scene: &Scene, candidate: &Rectangle) -> usize {
    scene
        .segments
        .iter()
        .filter(|(a, b)| candidate.crosses(*a, *b))
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bounds() -> Rectangle {
        Rectangle {
            left: 0.0,
            top: 0.0,
            right: 400.0,
            bottom: 300.0,
        }
    }

    fn rectangle(corner: (f64, f64), size: (f64, f64)) -> Rectangle {
        Rectangle {
            left: corner.0,
            top: corner.1,
            right: corner.0 + size.0,
            bottom: corner.1 + size.1,
        }
    }

    /// Three tags of points 3 px apart (the mesh sweeps of three methods at one mesh): none
    /// overlaps another or a point, all inside the panel.
    #[test]
    fn tags_of_close_points_do_not_overlap() {
        let markers = [(200.0, 150.0), (203.0, 150.0), (206.0, 151.0)];
        let scene = Scene {
            bounds: bounds(),
            markers: &markers,
            marker_radius: 8.0,
            segments: &[],
        };
        let size = (30.0, 12.0);
        let tags: Vec<_> = markers.iter().map(|&m| (m, size)).collect();
        let corners = place_tags(&scene, &tags);
        let boxes: Vec<Rectangle> = corners
            .iter()
            .map(|c| rectangle(c.expect("a free place"), size))
            .collect();
        for (i, a) in boxes.iter().enumerate() {
            assert!(bounds().contains(a));
            for m in markers {
                assert!(!a.touches_disc(m, 8.0), "{a:?} on {m:?}");
            }
            for b in &boxes[i + 1..] {
                assert!(!a.overlaps(b), "{a:?} and {b:?}");
            }
        }
    }

    /// A point in the panel's top-right corner gets its tag below-left; a line through the
    /// usual place pushes the tag to a free one.
    #[test]
    fn tags_avoid_the_border_and_the_lines() {
        let corner = [(395.0, 5.0)];
        let scene = Scene {
            bounds: bounds(),
            markers: &corner,
            marker_radius: 4.0,
            segments: &[],
        };
        let placed = place_tags(&scene, &[(corner[0], (30.0, 12.0))]);
        let (left, top) = placed[0].unwrap();
        assert!(left + 30.0 <= 400.0 && top >= 5.0, "{left}, {top}");
        let point = [(200.0, 150.0)];
        let line = [((200.0, 150.0), (300.0, 50.0))];
        let scene = Scene {
            bounds: bounds(),
            markers: &point,
            marker_radius: 4.0,
            segments: &line,
        };
        let placed = place_tags(&scene, &[(point[0], (30.0, 12.0))]);
        let tag = rectangle(placed[0].unwrap(), (30.0, 12.0));
        assert!(!tag.crosses(line[0].0, line[0].1), "{tag:?}");
    }

    /// With no free place (a panel smaller than the tag), the tag is left out.
    #[test]
    fn a_tag_without_room_is_left_out() {
        let point = [(5.0, 5.0)];
        let scene = Scene {
            bounds: rectangle((0.0, 0.0), (10.0, 10.0)),
            markers: &point,
            marker_radius: 2.0,
            segments: &[],
        };
        assert_eq!(place_tags(&scene, &[(point[0], (30.0, 12.0))]), vec![None]);
    }
}
