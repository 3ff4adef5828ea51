//! Holes bridged to the outer loop, then ears clipped: a valid
//! triangulation of checked loops, decided by exact [`orient2d`].
//!
//! The polygon is a cyclic doubly linked list of nodes. A bridge from a hole
//! to the outer polygon enters the hole and comes back along the same
//! segment, so its two end vertices appear twice: the list is a weakly
//! simple polygon whose only self-contacts are such repeated vertices.

use glam::DVec2;

use super::super::polygon::segments_touch;
use super::super::{Sign, orient2d};
use super::{Ring, TriangulateError};

/// A node of the polygon: a vertex (index into the points) and its
/// neighbours in the list.
#[derive(Clone, Copy, Debug)]
struct Node {
    vertex: usize,
    prev: usize,
    next: usize,
}

/// The polygon being cut: nodes of the merged polygon and of the holes not
/// yet merged.
struct Polygon<'a> {
    points: &'a [DVec2],
    nodes: Vec<Node>,
}

impl Polygon<'_> {
    fn at(&self, node: usize) -> DVec2 {
        self.points[self.nodes[node].vertex]
    }

    /// Adds a cycle of nodes for `ring`; returns its first node.
    fn push_cycle(&mut self, ring: &[usize]) -> usize {
        let start = self.nodes.len();
        let n = ring.len();
        for (k, &vertex) in ring.iter().enumerate() {
            self.nodes.push(Node {
                vertex,
                prev: start + (k + n - 1) % n,
                next: start + (k + 1) % n,
            });
        }
        start
    }

    /// The nodes of the cycle through `start`, in order.
    fn cycle(&self, start: usize) -> Vec<usize> {
        let mut out = vec![start];
        let mut node = self.nodes[start].next;
        while node != start {
            out.push(node);
            node = self.nodes[node].next;
        }
        out
    }

    /// Whether the segment from node `v` towards `x` leaves `v` into the
    /// open interior angle of the polygon at `v` (the inside is on the left
    /// of every edge).
    fn in_cone(&self, v: usize, x: DVec2) -> bool {
        let (a, p, b) = (
            self.at(self.nodes[v].prev),
            self.at(v),
            self.at(self.nodes[v].next),
        );
        let left_of_in = orient2d(a, p, x) == Sign::Positive;
        let left_of_out = orient2d(p, b, x) == Sign::Positive;
        match orient2d(a, p, b) {
            Sign::Positive => left_of_in && left_of_out,
            Sign::Negative => left_of_in || left_of_out,
            Sign::Zero => left_of_in,
        }
    }

    /// Links hole node `m` to node `p` of the merged polygon by a bridge
    /// there and back, duplicating both.
    fn splice(&mut self, m: usize, p: usize) {
        let m2 = self.nodes.len();
        let p2 = m2 + 1;
        let p_next = self.nodes[p].next;
        let m_prev = self.nodes[m].prev;
        self.nodes.push(Node {
            vertex: self.nodes[m].vertex,
            prev: m_prev,
            next: p2,
        });
        self.nodes.push(Node {
            vertex: self.nodes[p].vertex,
            prev: m2,
            next: p_next,
        });
        self.nodes[p].next = m;
        self.nodes[m].prev = p;
        self.nodes[m_prev].next = m2;
        self.nodes[p_next].prev = p2;
    }
}

/// Whether the edge `uw` blocks the bridge or diagonal `mp`: it meets the
/// closed segment anywhere but at a shared end. Exact.
fn blocks(m: DVec2, p: DVec2, u: DVec2, w: DVec2) -> bool {
    if !segments_touch(m, p, u, w) {
        return false;
    }
    let shared = [(u, w), (w, u)]
        .into_iter()
        .find(|&(s, _)| s == m || s == p);
    let Some((end, other)) = shared else {
        return true;
    };
    if orient2d(m, p, other) != Sign::Zero {
        return false;
    }
    // Collinear and sharing an end: it overlaps the segment iff its other
    // end lies on the segment's side of that end. On one line the
    // lexicographic order of coordinates is the order along it.
    let far = if end == m { p } else { m };
    let key = |q: DVec2| (q.x, q.y);
    (key(other) > key(end)) == (key(far) > key(end))
}

/// A valid triangulation of checked loops (the first counter-clockwise, the
/// others clockwise): holes bridged, ears clipped. Triangles are
/// counter-clockwise.
pub(super) fn triangulate_loops(
    points: &[DVec2],
    loops: &[Vec<usize>],
) -> Result<Vec<[usize; 3]>, TriangulateError> {
    let mut polygon = Polygon {
        points,
        nodes: Vec::with_capacity(points.len() + 2 * loops.len()),
    };
    let outer = polygon.push_cycle(&loops[0]);
    let key = |q: DVec2| (q.x, q.y);
    // Each hole from its rightmost (lexicographically greatest) vertex.
    let mut holes: Vec<(usize, usize, usize)> = loops[1..]
        .iter()
        .enumerate()
        .map(|(h, ring)| {
            let start = polygon.push_cycle(ring);
            let rightmost = (start..start + ring.len())
                .max_by(|&a, &b| {
                    key(polygon.at(a))
                        .partial_cmp(&key(polygon.at(b)))
                        .unwrap_or(std::cmp::Ordering::Equal)
                })
                .unwrap_or(start);
            (h, start, rightmost)
        })
        .collect();
    holes.sort_by(|a, b| {
        key(polygon.at(b.2))
            .partial_cmp(&key(polygon.at(a.2)))
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    for (k, &(hole, _, m)) in holes.iter().enumerate() {
        let merged = polygon.cycle(outer);
        let mut edges: Vec<(DVec2, DVec2)> = merged
            .iter()
            .map(|&n| (polygon.at(n), polygon.at(polygon.nodes[n].next)))
            .collect();
        for &(_, start, _) in &holes[k..] {
            for n in polygon.cycle(start) {
                edges.push((polygon.at(n), polygon.at(polygon.nodes[n].next)));
            }
        }
        let pm = polygon.at(m);
        let mut candidates = merged;
        candidates.sort_by(|&a, &b| {
            polygon
                .at(a)
                .distance_squared(pm)
                .total_cmp(&polygon.at(b).distance_squared(pm))
        });
        let bridge = candidates.into_iter().find(|&p| {
            let pp = polygon.at(p);
            polygon.in_cone(p, pm)
                && polygon.in_cone(m, pp)
                && !edges.iter().any(|&(u, w)| blocks(pm, pp, u, w))
        });
        let Some(p) = bridge else {
            debug_assert!(false, "no bridge for hole {hole}");
            return Err(TriangulateError::Internal {
                ring: Ring::Hole(hole),
            });
        };
        polygon.splice(m, p);
    }
    clip_ears(&mut polygon, outer)
}

/// Clips ears from the (weakly simple, counter-clockwise) polygon through
/// node `start` until one triangle is left.
fn clip_ears(polygon: &mut Polygon<'_>, start: usize) -> Result<Vec<[usize; 3]>, TriangulateError> {
    let mut count = polygon.cycle(start).len();
    let mut triangles = Vec::with_capacity(count.saturating_sub(2));
    let mut v = start;
    let mut misses = 0;
    while count > 3 {
        let Node { prev, next, .. } = polygon.nodes[v];
        if is_ear(polygon, v) {
            let vertex = |n: usize| polygon.nodes[n].vertex;
            triangles.push([vertex(prev), vertex(v), vertex(next)]);
            polygon.nodes[prev].next = next;
            polygon.nodes[next].prev = prev;
            count -= 1;
            misses = 0;
            v = prev;
        } else {
            misses += 1;
            if misses > count {
                debug_assert!(false, "no ear among {count} vertices");
                return Err(TriangulateError::Internal { ring: Ring::Outer });
            }
            v = next;
        }
    }
    let Node { prev, next, .. } = polygon.nodes[v];
    let vertex = |n: usize| polygon.nodes[n].vertex;
    triangles.push([vertex(prev), vertex(v), vertex(next)]);
    Ok(triangles)
}

/// Whether node `v` with its neighbours `a`, `b` is an ear: a strictly
/// convex corner whose closed triangle holds no other vertex, and at whose
/// corners no edge of a repeated vertex enters the triangle.
fn is_ear(polygon: &Polygon<'_>, v: usize) -> bool {
    let Node { prev, next, .. } = polygon.nodes[v];
    let (a, p, b) = (polygon.at(prev), polygon.at(v), polygon.at(next));
    if orient2d(a, p, b) != Sign::Positive {
        return false;
    }
    let inside = |x: DVec2| {
        orient2d(a, p, x) != Sign::Negative
            && orient2d(p, b, x) != Sign::Negative
            && orient2d(b, a, x) != Sign::Negative
    };
    // Strictly inside the triangle's angle at a corner, given the corner
    // and the next corner counter-clockwise and the previous one.
    let enters = |corner: DVec2, x: DVec2| {
        let (following, preceding) = if corner == a {
            (p, b)
        } else if corner == p {
            (b, a)
        } else {
            (a, p)
        };
        orient2d(corner, following, x) == Sign::Positive
            && orient2d(preceding, corner, x) == Sign::Positive
    };
    let mut w = next;
    loop {
        let Node {
            next: after,
            prev: before,
            ..
        } = polygon.nodes[w];
        let q = polygon.at(w);
        if q == a || q == p || q == b {
            if enters(q, polygon.at(before)) || enters(q, polygon.at(after)) {
                return false;
            }
        } else if inside(q) {
            return false;
        }
        w = after;
        if w == v {
            return true;
        }
    }
}
