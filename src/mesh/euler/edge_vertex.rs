//! `mev` / `kev`: a new edge to a new vertex inside a face, and its removal.

use glam::DVec3;

use crate::mesh::{Edge, EdgeId, EdgeUse, LoopStart, Side, Solid, Vertex, VertexId};

use super::corner::Place;
use super::links::check_position;
use super::{Corner, EulerError};

impl Solid {
    /// Make edge, vertex: a new vertex at `position` joined by a new edge to
    /// the vertex of `corner`, inside the corner's face (a "strut": the
    /// face's loop runs out along the edge and back). The edge runs from the
    /// corner's vertex to the new vertex and has the corner's face on both
    /// sides.
    ///
    /// Euler–Poincaré: `V + 1, E + 1`. O(1).
    ///
    /// # Errors
    ///
    /// [`EulerError::NonFinitePosition`], and those of a bad corner:
    /// [`EulerError::UnknownEdge`], [`EulerError::UnknownLoop`],
    /// [`EulerError::NoFaceOnSide`], [`EulerError::NotLoneLoop`].
    pub fn mev(
        &mut self,
        corner: Corner,
        position: DVec3,
    ) -> Result<(EdgeId, VertexId), EulerError> {
        let at = self.resolve(corner)?;
        check_position(position)?;
        let vertex = self.vertices.insert(Vertex {
            position,
            edge: None,
            source_index: None,
        });
        let edge = self.edges.insert_with_key(|edge| {
            let (cw_left, ccw_right) = match at.between() {
                Some((u, n)) => (u.edge, n.edge),
                None => (edge, edge),
            };
            Edge {
                origin: at.vertex,
                dest: vertex,
                left_face: at.face,
                right_face: Some(at.face),
                cw_left,
                ccw_left: edge,
                cw_right: edge,
                ccw_right,
            }
        });
        self.vertices[vertex].edge = Some(edge);
        match at.place {
            Place::Between(u, n) => {
                self.set_next(u, edge);
                self.set_prev(n, edge);
            }
            Place::Lone(l) => {
                self.loops[l].start = LoopStart::Edge(EdgeUse {
                    edge,
                    side: Side::Left,
                });
                self.vertices[at.vertex].edge = Some(edge);
            }
        }
        Ok((edge, vertex))
    }

    /// Kill edge, vertex: removes `vertex`, which must have `edge` as its
    /// only edge, together with `edge`. The inverse of [`Solid::mev`]. When
    /// the edge was the only edge of its loop, the loop becomes the lone
    /// vertex at the edge's other end.
    ///
    /// Euler–Poincaré: `V − 1, E − 1`. O(1) plus the loops of the face.
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownEdge`], [`EulerError::UnknownVertex`],
    /// [`EulerError::NotAnEnd`], and [`EulerError::WrongDegree`] when
    /// `vertex` has other edges.
    pub fn kev(&mut self, edge: EdgeId, vertex: VertexId) -> Result<(), EulerError> {
        let e = self.edges.get(edge).ok_or(EulerError::UnknownEdge(edge))?;
        if !self.vertices.contains_key(vertex) {
            return Err(EulerError::UnknownVertex(vertex));
        }
        let out = if e.dest == vertex {
            EdgeUse {
                edge,
                side: Side::Left,
            }
        } else if e.origin == vertex {
            EdgeUse {
                edge,
                side: Side::Right,
            }
        } else {
            return Err(EulerError::NotAnEnd { vertex, edge });
        };
        let back = out.opposite();
        if self.use_next(out) != back {
            return Err(EulerError::WrongDegree {
                vertex,
                degree: self.vertex_degree(vertex),
                expected: 1,
            });
        }
        let keep = self.use_start(out);
        let face = self.use_face(out).ok_or(EulerError::NoFaceOnSide {
            edge,
            side: out.side,
        })?;
        let (p, n) = (self.use_prev(out), self.use_next(back));
        let lone = p == back;
        if !lone {
            self.set_next(p, n.edge);
            self.set_prev(n, p.edge);
        }
        let fixed_start = if lone {
            LoopStart::Vertex(keep)
        } else {
            LoopStart::Edge(n)
        };
        let loops: smallvec::SmallVec<[_; 4]> = self.face_loops(face).collect();
        for l in loops {
            if matches!(self.loops[l].start, LoopStart::Edge(s) if s.edge == edge) {
                self.loops[l].start = fixed_start;
            }
        }
        if self.vertices[keep].edge == Some(edge) {
            self.vertices[keep].edge = (!lone).then_some(n.edge);
        }
        self.edges.remove(edge);
        self.vertices.remove(vertex);
        Ok(())
    }
}
