//! Checks of faces with rings (inner loops), which only solids made through
//! the API have (OBJ faces have no holes): one check per file, each named
//! after what is wrong, every instance reported and located by the ids of
//! the solid's face, loops and vertices.
//!
//! Every decision is exact: [`orient2d`](crate::geom::orient2d) on the
//! face's loops projected onto the axis plane closest to the outer loop's
//! Newell normal (exact for loops that are exactly planar; of loops that are
//! not, the projection is judged, as the triangulation of the face does).
//!
//! A defect is reported once, by its most specific rule: a ring that
//! crosses or touches another loop is not also reported as outside the
//! outer loop, and the winding of a loop that touches another is not judged.

mod loop_wound_wrong_way;
mod loops_cross_or_touch;
mod ring_not_inside_outer_loop;

use glam::{DVec2, DVec3};
use serde::Serialize;

use crate::geom::newell_vector_area;
use crate::geom::polygon::Projection;
use crate::mesh::{FaceId, LoopId, Solid, VertexId};

/// A rule a face with rings must satisfy, named after what is wrong when it
/// is broken.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RingRule {
    /// Two loops of a face share a point (their edges cross or touch, or a
    /// vertex of one lies on the other), or a loop touches itself.
    LoopsCrossOrTouch,
    /// A ring that is not strictly inside the face's outer loop, or that
    /// lies inside another ring (nested holes).
    RingNotInsideOuterLoop,
    /// A ring wound the same way as its face's outer loop (a ring must run
    /// the other way, so that the face is on the left of every loop).
    LoopWoundWrongWay,
}

impl RingRule {
    /// The rule's snake-case name.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            RingRule::LoopsCrossOrTouch => "loops_cross_or_touch",
            RingRule::RingNotInsideOuterLoop => "ring_not_inside_outer_loop",
            RingRule::LoopWoundWrongWay => "loop_wound_wrong_way",
        }
    }
}

/// One broken ring rule, located by the solid's ids.
#[derive(Clone, Debug, PartialEq)]
pub struct RingViolation {
    /// The rule broken.
    pub rule: RingRule,
    /// A sentence saying what is wrong and where.
    pub message: String,
    /// The face.
    pub face: FaceId,
    /// The loops involved.
    pub loops: Vec<LoopId>,
    /// The vertices where it shows (a touching vertex, the ends of crossing
    /// edges, a ring vertex outside).
    pub vertices: Vec<VertexId>,
}

/// Every violation of a [`RingRule`] by the faces of `solid` that have
/// rings, in face order and then rule order. Faces without rings are not
/// looked at (their loops are checked by the soup checks of
/// [`validate_soup`](super::validate_soup)).
#[must_use]
pub fn check_rings(solid: &Solid) -> Vec<RingViolation> {
    let mut found = Vec::new();
    for (face, f) in solid.faces() {
        if f.rings.is_empty() {
            continue;
        }
        let loops = FaceLoops::new(solid, face);
        let touching = loops_cross_or_touch::check(&loops, &mut found);
        ring_not_inside_outer_loop::check(&loops, &touching, &mut found);
        loop_wound_wrong_way::check(&loops, &touching, &mut found);
    }
    found
}

/// A face's loops projected: the outer loop first, then the rings.
pub(super) struct FaceLoops {
    pub(super) face: FaceId,
    pub(super) ids: Vec<LoopId>,
    pub(super) vertices: Vec<Vec<VertexId>>,
    pub(super) points: Vec<Vec<DVec2>>,
}

impl FaceLoops {
    fn new(solid: &Solid, face: FaceId) -> FaceLoops {
        let ids: Vec<LoopId> = solid.face_loops(face).collect();
        let vertices: Vec<Vec<VertexId>> = ids
            .iter()
            .map(|&l| solid.loop_vertices(l).collect())
            .collect();
        let outer: Vec<DVec3> = vertices[0].iter().map(|&v| solid.position(v)).collect();
        let projection = Projection::along(newell_vector_area(&outer, outer[0]));
        let points = vertices
            .iter()
            .map(|l| {
                l.iter()
                    .map(|&v| projection.apply(solid.position(v)))
                    .collect()
            })
            .collect();
        FaceLoops {
            face,
            ids,
            vertices,
            points,
        }
    }
}
