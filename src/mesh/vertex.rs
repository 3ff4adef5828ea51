//! The vertex table.

use glam::DVec3;

use super::EdgeId;

/// A vertex: a position and one incident edge.
///
/// # Invariants
///
/// - `position` is finite.
/// - `edge` is an edge of the same solid with `origin == self` or
///   `dest == self`; walking the wings from it visits every edge at the vertex
///   (the faces around a vertex form a single fan: a closed cycle, or an open
///   fan whose two boundary edges border the same hole).
/// - `edge` is `None` exactly for a vertex without edges, which is then the
///   whole of one loop ([`super::LoopStart::Vertex`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Vertex {
    /// Where the vertex is.
    pub position: DVec3,
    /// One edge incident to the vertex, `None` for a lone vertex.
    pub edge: Option<EdgeId>,
    /// The vertex's index in the polygon soup it was built from (0-based),
    /// if any: the link back to the OBJ file's `v` lines.
    pub source_index: Option<usize>,
}
