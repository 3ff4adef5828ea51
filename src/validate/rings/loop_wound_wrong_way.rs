//! A ring wound the same way as its face's outer loop.

use glam::DVec2;

use crate::geom::{Sign, orient2d};

use super::{FaceLoops, RingRule, RingViolation};

/// Reports every ring (that touches no other loop and is simple) whose
/// winding in the face's projection is the outer loop's.
pub(super) fn check(loops: &FaceLoops, touching: &[bool], found: &mut Vec<RingViolation>) {
    if touching[0] {
        return;
    }
    let Some(outer) = winding(&loops.points[0]) else {
        return;
    };
    for (r, points) in loops.points.iter().enumerate().skip(1) {
        if !touching[r] && winding(points) == Some(outer) {
            found.push(RingViolation {
                rule: RingRule::LoopWoundWrongWay,
                message: format!(
                    "ring {:?} of face {:?} runs the same way as the outer loop {:?}; a ring runs the other way",
                    loops.ids[r], loops.face, loops.ids[0]
                ),
                face: loops.face,
                loops: vec![loops.ids[r], loops.ids[0]],
                vertices: loops.vertices[r].clone(),
            });
        }
    }
}

/// The winding of a simple polygon, decided exactly at its lowest-leftmost
/// vertex (a convex corner): positive for counter-clockwise, `None` when
/// that corner is flat (the polygon is degenerate there).
fn winding(points: &[DVec2]) -> Option<Sign> {
    let n = points.len();
    let lowest = (0..n).min_by(|&i, &j| {
        points[i]
            .x
            .total_cmp(&points[j].x)
            .then(points[i].y.total_cmp(&points[j].y))
    })?;
    let sign = orient2d(
        points[(lowest + n - 1) % n],
        points[lowest],
        points[(lowest + 1) % n],
    );
    (sign != Sign::Zero).then_some(sign)
}
