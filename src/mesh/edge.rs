//! The edge table: Baumgart's winged edge.

use super::{EdgeId, FaceId, VertexId};

/// An edge with its two faces and four wings.
///
/// The edge runs from `origin` to `dest`. Seen from outside the solid, with
/// faces wound counter-clockwise, `left_face` traverses the edge from
/// `origin` to `dest` and `right_face` from `dest` to `origin`.
///
/// The four wings are the neighbouring edges in the loops of the two faces.
///
/// - `ccw_left`: the edge after this one going counter-clockwise around
///   `left_face` (it starts at `dest`);
/// - `cw_left`: the edge before this one in that loop (it ends at `origin`);
/// - `ccw_right`: the edge after this one going counter-clockwise around
///   `right_face` (it starts at `origin`, since the right face runs the edge
///   from `dest` to `origin`);
/// - `cw_right`: the edge before this one in that loop (it ends at `dest`).
///
/// # Invariants
///
/// - `origin != dest`, and no other edge joins the same two vertices.
/// - `left_face` always exists: the edge is oriented so that the face that
///   first used it runs it from `origin` to `dest`. Both sides may be on one
///   face (an edge inside a face's loop, run out and back, while a solid is
///   made by Euler operators).
/// - `right_face` is `None` for a boundary edge (an edge of one face, on the
///   rim of a hole). The right-hand wings then run around the hole: the
///   boundary edges of one hole form a loop exactly as a face's edges do, so
///   every wing always names an edge and vertex stars can be walked across
///   holes.
/// - Following `ccw_left`/`ccw_right` from any edge use returns to it after
///   visiting exactly the edges of one loop of that face (its outer loop or a
///   ring; for a boundary edge's right side, the hole); `cw_*` walks the
///   same loop backwards.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Edge {
    /// The start vertex.
    pub origin: VertexId,
    /// The end vertex.
    pub dest: VertexId,
    /// The face that runs the edge from `origin` to `dest`.
    pub left_face: FaceId,
    /// The face that runs the edge from `dest` to `origin`, if any.
    pub right_face: Option<FaceId>,
    /// Previous edge around the left face (ends at `origin`).
    pub cw_left: EdgeId,
    /// Next edge around the left face (starts at `dest`).
    pub ccw_left: EdgeId,
    /// Previous edge around the right face or hole (ends at `dest`).
    pub cw_right: EdgeId,
    /// Next edge around the right face or hole (starts at `origin`).
    pub ccw_right: EdgeId,
}

/// Which of an edge's two sides a loop uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Side {
    /// The left side: traversed from `origin` to `dest`, by `left_face`.
    Left,
    /// The right side: traversed from `dest` to `origin`, by `right_face` or
    /// by a hole.
    Right,
}

impl Side {
    /// The other side.
    #[must_use]
    pub fn other(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
        }
    }
}

/// An edge as used by one of its two loops: a directed edge (what half-edge
/// structures store explicitly, derived here from the winged edge).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EdgeUse {
    /// The edge.
    pub edge: EdgeId,
    /// Which side of it.
    pub side: Side,
}

impl EdgeUse {
    /// The same edge used from its other side.
    #[must_use]
    pub fn opposite(self) -> EdgeUse {
        EdgeUse {
            edge: self.edge,
            side: self.side.other(),
        }
    }
}
