//! Stage 2b (several operands only): where the segments of different
//! operands cross inside one triangle.
//!
//! Two operands never cut one triangle of a third along crossing segments
//! when there are only two operands (the other operand's surface does not
//! cross itself). With three or more, the segment where triangle `t` meets
//! operand `j` and the one where it meets operand `k` can cross inside `t`:
//! at the point where the three faces' planes meet. That point is made
//! here, as an implicit point of three planes (or an edge–plane or
//! edge–edge point when a segment runs along a coplanar triangle's edge),
//! and added to the triangle's points, so that the split inserts it and
//! breaks both segments there. The same point is found again in the other
//! two triangles and merged with this one by exact comparison.
//!
//! Segments that only touch (an end on the other segment, or overlapping
//! along one line) need nothing here: the split breaks a segment at every
//! point of the triangle lying on it.

use glam::DVec3;

use crate::geom::implicit::{ImplicitPoint, enclosing_box, kept_axes, orient2d_points};
use crate::geom::{Aabb, Sign};

/// The line a segment lies on, besides the plane of the triangle it cuts.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Line {
    /// Where the triangle's plane meets this plane (through three points).
    Meets([DVec3; 3]),
    /// The line through two points in the triangle's plane (the edge of a
    /// coplanar triangle).
    Through(DVec3, DVec3),
}

/// A segment cutting a triangle: its ends (raw point indices), the operand
/// whose surface made it, and its line.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Segment {
    pub ends: (u32, u32),
    pub operand: usize,
    pub line: Line,
}

/// The points where segments of different operands cross properly inside
/// the triangle `plane` (projected along `axis`, which keeps it
/// non-degenerate); `point(i)` gives the definition of raw point `i`.
pub(crate) fn crossings(
    plane: [DVec3; 3],
    axis: u8,
    segments: &[Segment],
    point: impl Fn(u32) -> ImplicitPoint,
) -> Vec<ImplicitPoint> {
    // A sweep along the first kept axis: only segments whose boxes overlap
    // are tested exactly.
    let (u, v) = kept_axes(axis);
    let ends: Vec<[ImplicitPoint; 2]> = segments
        .iter()
        .map(|s| [point(s.ends.0), point(s.ends.1)])
        .collect();
    let boxes: Vec<Aabb> = ends
        .iter()
        .map(|[a, b]| enclosing_box(a).union(enclosing_box(b)))
        .collect();
    let mut order: Vec<usize> = (0..segments.len()).collect();
    order.sort_by(|&i, &j| boxes[i].min[u].total_cmp(&boxes[j].min[u]));
    let mut found = Vec::new();
    for (k, &i) in order.iter().enumerate() {
        for &j in &order[k + 1..] {
            if boxes[j].min[u] > boxes[i].max[u] {
                break;
            }
            let (s, r) = (&segments[i], &segments[j]);
            if r.operand == s.operand
                || boxes[j].min[v] > boxes[i].max[v]
                || boxes[i].min[v] > boxes[j].max[v]
            {
                continue;
            }
            let ([a, b], [c, d]) = (&ends[i], &ends[j]);
            let proper = |x: Sign, y: Sign| x != Sign::Zero && y != Sign::Zero && x != y;
            if proper(
                orient2d_points(a, b, c, axis),
                orient2d_points(a, b, d, axis),
            ) && proper(
                orient2d_points(c, d, a, axis),
                orient2d_points(c, d, b, axis),
            ) {
                found.push(crossing(plane, axis, s.line, r.line).simplified());
            }
        }
    }
    found
}

/// The point where two lines in the plane `plane` cross (they are known
/// not to be parallel).
fn crossing(plane: [DVec3; 3], axis: u8, first: Line, second: Line) -> ImplicitPoint {
    match (first, second) {
        (Line::Meets(u), Line::Meets(w)) => ImplicitPoint::ThreePlanes {
            planes: Box::new([plane, u, w]),
        },
        (Line::Meets(u), Line::Through(p, q)) | (Line::Through(p, q), Line::Meets(u)) => {
            ImplicitPoint::EdgePlane { p, q, plane: u }
        }
        (Line::Through(p, q), Line::Through(r, s)) => ImplicitPoint::EdgeEdge {
            p,
            q,
            r,
            s,
            drop_axis: axis,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::implicit::{compare_points, point_side_of_plane};
    use std::cmp::Ordering;

    /// In the triangle z = 0, the tilted plane of operand 1 and the plane
    /// of operand 2 cut two crossing segments; their crossing lies on all
    /// three planes. Segments of one operand are never crossed.
    #[test]
    fn segments_of_two_operands_cross_at_the_three_planes_point() {
        let plane = [
            DVec3::new(-4.0, -4.0, 0.0),
            DVec3::new(4.0, -4.0, 0.0),
            DVec3::new(0.0, 4.0, 0.0),
        ];
        // x + 0.1 z = 0.3 and y − 0.2 z = -0.7 cut z = 0 along x = 0.3 and
        // y = -0.7.
        let u = [
            DVec3::new(0.3, 0.0, 0.0),
            DVec3::new(0.3, 1.0, 0.0),
            DVec3::new(0.2, 0.0, 1.0),
        ];
        let w = [
            DVec3::new(0.0, -0.7, 0.0),
            DVec3::new(1.0, -0.7, 0.0),
            DVec3::new(0.0, -0.5, 1.0),
        ];
        let points = [
            DVec3::new(0.3, -2.0, 0.0),
            DVec3::new(0.3, 2.0, 0.0),
            DVec3::new(-2.0, -0.7, 0.0),
            DVec3::new(2.0, -0.7, 0.0),
        ];
        let point = |i: u32| ImplicitPoint::Explicit(points[i as usize]);
        let segments = [
            Segment {
                ends: (0, 1),
                operand: 1,
                line: Line::Meets(u),
            },
            Segment {
                ends: (2, 3),
                operand: 2,
                line: Line::Meets(w),
            },
        ];
        let found = crossings(plane, 2, &segments, point);
        assert_eq!(found.len(), 1);
        for p in [plane, u, w] {
            assert_eq!(point_side_of_plane(p, &found[0]), Sign::Zero);
        }
        assert_eq!(
            compare_points(
                &found[0],
                &ImplicitPoint::Explicit(DVec3::new(0.3, -0.7, 0.0))
            ),
            Ordering::Equal
        );
        let same_operand = [
            segments[0],
            Segment {
                operand: 1,
                ..segments[1]
            },
        ];
        assert!(crossings(plane, 2, &same_operand, point).is_empty());
        // Segments that only touch at an end do not cross.
        let touching = [
            segments[0],
            Segment {
                ends: (2, 0),
                ..segments[1]
            },
        ];
        assert!(crossings(plane, 2, &touching, point).is_empty());
    }
}
