//! Corners: the places in a loop where an operator attaches a new edge.

use crate::mesh::{EdgeUse, FaceId, LoopId, LoopStart, Solid, VertexId};

use super::EulerError;

/// A place in a face's loop, at one vertex, where a new edge can be
/// inserted.
///
/// A vertex may be visited several times by one face (a strut edge is used
/// from both of its sides, and a vertex may touch a ring), so a vertex alone
/// does not always say where: a corner does.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Corner {
    /// The corner at the vertex where this edge use ends, between it and
    /// the use that follows it in its loop.
    After(EdgeUse),
    /// A loop that is a lone vertex.
    Lone(LoopId),
}

/// A corner checked against the solid: its face, vertex and, for a corner
/// on edges, the uses on either side.
#[derive(Clone, Copy, Debug)]
pub(super) struct Resolved {
    pub(super) face: FaceId,
    pub(super) vertex: VertexId,
    pub(super) place: Place,
}

/// What is at a resolved corner.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Place {
    /// The use ending at the corner and the use starting there.
    Between(EdgeUse, EdgeUse),
    /// A lone-vertex loop.
    Lone(LoopId),
}

impl Resolved {
    /// The uses on either side of the corner, `None` for a lone vertex.
    pub(super) fn between(&self) -> Option<(EdgeUse, EdgeUse)> {
        match self.place {
            Place::Between(u, n) => Some((u, n)),
            Place::Lone(_) => None,
        }
    }
}

impl Solid {
    /// The corner of `face` at `vertex`.
    ///
    /// Walks the face's loops: O(size of the face).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownFace`], [`EulerError::UnknownVertex`],
    /// [`EulerError::VertexNotOnFace`], and [`EulerError::AmbiguousCorner`]
    /// when the face visits the vertex more than once (name the corner by
    /// [`Corner::After`] an edge use then).
    pub fn corner(&self, face: FaceId, vertex: VertexId) -> Result<Corner, EulerError> {
        if !self.faces.contains_key(face) {
            return Err(EulerError::UnknownFace(face));
        }
        if !self.vertices.contains_key(vertex) {
            return Err(EulerError::UnknownVertex(vertex));
        }
        let mut found = Vec::new();
        for l in self.face_loops(face) {
            match self.loops[l].start {
                LoopStart::Vertex(v) if v == vertex => found.push(Corner::Lone(l)),
                LoopStart::Vertex(_) => {}
                LoopStart::Edge(_) => found.extend(
                    self.loop_uses(l)
                        .filter(|&u| self.use_end(u) == vertex)
                        .map(Corner::After),
                ),
            }
        }
        match found.as_slice() {
            [] => Err(EulerError::VertexNotOnFace { vertex, face }),
            [one] => Ok(*one),
            _ => Err(EulerError::AmbiguousCorner {
                vertex,
                face,
                count: found.len(),
            }),
        }
    }

    /// Checks `corner` against the solid.
    pub(super) fn resolve(&self, corner: Corner) -> Result<Resolved, EulerError> {
        match corner {
            Corner::After(u) => {
                if !self.edges.contains_key(u.edge) {
                    return Err(EulerError::UnknownEdge(u.edge));
                }
                let face = self.use_face(u).ok_or(EulerError::NoFaceOnSide {
                    edge: u.edge,
                    side: u.side,
                })?;
                Ok(Resolved {
                    face,
                    vertex: self.use_end(u),
                    place: Place::Between(u, self.use_next(u)),
                })
            }
            Corner::Lone(l) => {
                let record = self.loops.get(l).ok_or(EulerError::UnknownLoop(l))?;
                match record.start {
                    LoopStart::Vertex(vertex) => Ok(Resolved {
                        face: record.face,
                        vertex,
                        place: Place::Lone(l),
                    }),
                    LoopStart::Edge(_) => Err(EulerError::NotLoneLoop(l)),
                }
            }
        }
    }
}
