//! Why an Euler operator refused: its pre-condition, with the ids involved.

use glam::DVec3;
use thiserror::Error;

use crate::geom::triangulate::TriangulateError;
use crate::mesh::{EdgeId, FaceId, LoopId, Side, VertexId};

/// A pre-condition of an Euler operator or an editing operation that does
/// not hold. The solid is unchanged when an operator returns one.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum EulerError {
    /// A vertex id that names no vertex of this solid (stale, or issued by
    /// another solid).
    #[error("vertex {0:?} is not a vertex of this solid (stale, or from another solid)")]
    UnknownVertex(VertexId),
    /// An edge id that names no edge of this solid.
    #[error("edge {0:?} is not an edge of this solid (stale, or from another solid)")]
    UnknownEdge(EdgeId),
    /// A face id that names no face of this solid.
    #[error("face {0:?} is not a face of this solid (stale, or from another solid)")]
    UnknownFace(FaceId),
    /// A loop id that names no loop of this solid.
    #[error("loop {0:?} is not a loop of this solid (stale, or from another solid)")]
    UnknownLoop(LoopId),
    /// A new vertex position with a NaN or infinite coordinate.
    #[error("position {} is not finite", crate::geom::ReadableVec(*.position))]
    NonFinitePosition {
        /// The position given.
        position: DVec3,
    },
    /// A vector (of an extrusion) with a NaN or infinite coordinate.
    #[error("vector {} is not finite", crate::geom::ReadableVec(*.vector))]
    NonFiniteVector {
        /// The vector given.
        vector: DVec3,
    },
    /// A corner on the hole side of a boundary edge: no face is there.
    #[error(
        "edge {edge:?} has no face on its {side:?} side (it borders a hole of an open surface)"
    )]
    NoFaceOnSide {
        /// The edge.
        edge: EdgeId,
        /// The side without a face.
        side: Side,
    },
    /// A lone-vertex corner whose loop has edges.
    #[error("loop {0:?} is not a lone vertex")]
    NotLoneLoop(LoopId),
    /// A vertex that is not on the face.
    #[error("vertex {vertex:?} is not on face {face:?}")]
    VertexNotOnFace {
        /// The vertex.
        vertex: VertexId,
        /// The face.
        face: FaceId,
    },
    /// A vertex that the face's loops visit more than once, so the corner
    /// meant is ambiguous.
    #[error(
        "vertex {vertex:?} is visited {count} times by face {face:?}: name the corner by an edge use"
    )]
    AmbiguousCorner {
        /// The vertex.
        vertex: VertexId,
        /// The face.
        face: FaceId,
        /// How many corners of the face are at the vertex.
        count: usize,
    },
    /// Two corners at the same vertex, where an edge between them would
    /// start and end there.
    #[error("both corners are at vertex {0:?}: an edge needs two distinct ends")]
    SameVertex(VertexId),
    /// Two vertices already joined by an edge (a second one would make
    /// parallel edges).
    #[error("vertices {v1:?} and {v2:?} are already joined by edge {edge:?}")]
    AlreadyJoined {
        /// One vertex.
        v1: VertexId,
        /// The other.
        v2: VertexId,
        /// The edge joining them.
        edge: EdgeId,
    },
    /// Two corners on different faces.
    #[error("the corners are on different faces {f1:?} and {f2:?}")]
    DifferentFaces {
        /// The first corner's face.
        f1: FaceId,
        /// The second corner's face.
        f2: FaceId,
    },
    /// Two corners that should be on one loop are on two.
    #[error("the corners at {v1:?} and {v2:?} are on different loops of face {face:?}")]
    DifferentLoops {
        /// The first corner's vertex.
        v1: VertexId,
        /// The second corner's vertex.
        v2: VertexId,
        /// The face.
        face: FaceId,
    },
    /// Two corners that should be on two loops are on one.
    #[error("the corners at {v1:?} and {v2:?} are on the same loop {loop_id:?}")]
    SameLoop {
        /// The first corner's vertex.
        v1: VertexId,
        /// The second corner's vertex.
        v2: VertexId,
        /// The loop.
        loop_id: LoopId,
    },
    /// A vertex with the wrong number of edges for the operator.
    #[error("vertex {vertex:?} has {degree} edges; the operator needs {expected}")]
    WrongDegree {
        /// The vertex.
        vertex: VertexId,
        /// Its number of edges.
        degree: usize,
        /// The number the operator needs.
        expected: usize,
    },
    /// A vertex that is not an end of the edge.
    #[error("vertex {vertex:?} is not an end of edge {edge:?}")]
    NotAnEnd {
        /// The vertex.
        vertex: VertexId,
        /// The edge.
        edge: EdgeId,
    },
    /// An edge whose two sides lie on one face, where two faces are needed.
    #[error("edge {edge:?} has face {face:?} on both sides")]
    SameFaceBothSides {
        /// The edge.
        edge: EdgeId,
        /// Its face.
        face: FaceId,
    },
    /// An edge whose two sides are on different loops, where one loop is
    /// needed (or a boundary edge).
    #[error("the two sides of edge {edge:?} are not on one loop")]
    SidesOnDifferentLoops {
        /// The edge.
        edge: EdgeId,
    },
    /// A face that is not on the edge.
    #[error("face {face:?} is not on edge {edge:?}")]
    FaceNotOnEdge {
        /// The face.
        face: FaceId,
        /// The edge.
        edge: EdgeId,
    },
    /// A face with rings, where the operator needs a face without.
    #[error("face {face:?} has {rings} rings")]
    FaceHasRings {
        /// The face.
        face: FaceId,
        /// How many rings it has.
        rings: usize,
    },
    /// A loop that is the outer loop of its face, where a ring is needed.
    #[error("loop {loop_id:?} is the outer loop of face {face:?}, not a ring")]
    NotARing {
        /// The loop.
        loop_id: LoopId,
        /// Its face.
        face: FaceId,
    },
    /// The same face given twice where two faces are needed.
    #[error("face {0:?} is given twice; the operator needs two faces")]
    SameFace(FaceId),
    /// A face that is not the whole of a shell of one vertex (what
    /// [`Solid::kvfs`](crate::mesh::Solid::kvfs) removes).
    #[error("face {0:?} is not a lone face with a lone vertex")]
    NotLoneShell(FaceId),
    /// A loop that is not a simple cycle of at least three edges (a lone
    /// vertex, a strut, a vertex visited twice), where an operation needs
    /// simple loops.
    #[error(
        "loop {loop_id:?} of face {face:?} is not a simple cycle of three or more edges (at vertex {vertex:?})"
    )]
    LoopNotSimple {
        /// The loop.
        loop_id: LoopId,
        /// Its face.
        face: FaceId,
        /// Where it fails: a repeated vertex, or a vertex of a too short loop.
        vertex: VertexId,
    },
    /// An extrusion vector that does not point to the outside of the face
    /// at one of its vertices (decided exactly).
    #[error("extruding face {face:?} by {} does not move vertex {vertex:?} to its outside", crate::geom::ReadableVec(*.vector))]
    NotOutward {
        /// The face.
        face: FaceId,
        /// The vector.
        vector: DVec3,
        /// A vertex whose moved copy is not strictly outside.
        vertex: VertexId,
    },
    /// A polygon (of a lamina, a ring or a face split) that is not a valid
    /// face boundary: too few vertices, collinear, not simple, or a ring not
    /// strictly inside its face or touching another ring.
    #[error("invalid face boundary: {0}")]
    InvalidPolygon(#[from] TriangulateError),
    /// A split of a face along a segment that leaves the face or touches its
    /// boundary elsewhere than at its two ends.
    #[error("the segment {v1:?}–{v2:?} does not run inside face {face:?}")]
    SplitOutsideFace {
        /// The face.
        face: FaceId,
        /// One end.
        v1: VertexId,
        /// The other.
        v2: VertexId,
    },
}
