//! A ring that is not strictly inside its face's outer loop, or that lies
//! inside another ring.

use crate::geom::polygon::{PolygonLocation, locate_point_in_polygon};

use super::{FaceLoops, RingRule, RingViolation};

/// Reports every ring (that touches no other loop: those are reported by
/// `loops_cross_or_touch`) whose first vertex is outside the outer loop or
/// inside another ring. A ring that touches nothing is wholly on one side
/// of every other loop, so its first vertex decides.
pub(super) fn check(loops: &FaceLoops, touching: &[bool], found: &mut Vec<RingViolation>) {
    for r in 1..loops.ids.len() {
        if touching[r] {
            continue;
        }
        let first = loops.points[r][0];
        let vertex = loops.vertices[r][0];
        let outer = locate_point_in_polygon(&loops.points[0], first);
        if outer != PolygonLocation::Inside {
            found.push(RingViolation {
                rule: RingRule::RingNotInsideOuterLoop,
                message: format!(
                    "ring {:?} of face {:?} lies outside the face's outer loop {:?} (vertex {vertex:?})",
                    loops.ids[r], loops.face, loops.ids[0]
                ),
                face: loops.face,
                loops: vec![loops.ids[r], loops.ids[0]],
                vertices: vec![vertex],
            });
            continue;
        }
        let container = (1..loops.ids.len()).find(|&o| {
            o != r
                && !touching[o]
                && locate_point_in_polygon(&loops.points[o], first) == PolygonLocation::Inside
        });
        if let Some(o) = container {
            found.push(RingViolation {
                rule: RingRule::RingNotInsideOuterLoop,
                message: format!(
                    "ring {:?} of face {:?} lies inside ring {:?} (vertex {vertex:?}): holes cannot nest",
                    loops.ids[r], loops.face, loops.ids[o]
                ),
                face: loops.face,
                loops: vec![loops.ids[r], loops.ids[o]],
                vertices: vec![vertex],
            });
        }
    }
}
