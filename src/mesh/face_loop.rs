//! The loop table: the boundaries of a face, one outer loop and any number
//! of rings (inner loops, the rims of holes through the face).

use super::{EdgeUse, FaceId, VertexId};

/// One closed boundary of a face.
///
/// A face has one outer loop and zero or more rings. Seen from outside the
/// solid, the outer loop runs counter-clockwise around the face and every
/// ring clockwise, so the face lies on the left of every loop (Mäntylä 1988,
/// ch. 10). That is geometry, checked by validation; the store only knows
/// the cycles.
///
/// # Invariants
///
/// - `face` names a face that lists this loop (as its outer loop or as one
///   of its rings).
/// - A [`LoopStart::Edge`] start is an edge use on `face`; following
///   [`Solid::use_next`](super::Solid::use_next) from it returns to it, and
///   no use belongs to two loops.
/// - A [`LoopStart::Vertex`] start names a vertex without edges (what
///   [`Solid::mvfs`](super::Solid::mvfs) makes, or what is left when the
///   last edge of a loop is killed); that vertex is in no other loop.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Loop {
    /// The face the loop bounds.
    pub face: FaceId,
    /// Where a walk of the loop starts.
    pub start: LoopStart,
}

/// Where a loop starts: an edge use, or a lone vertex for a loop without
/// edges.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LoopStart {
    /// A loop of one or more edge uses, starting with this one.
    Edge(EdgeUse),
    /// A loop made of one vertex and no edge.
    Vertex(VertexId),
}
