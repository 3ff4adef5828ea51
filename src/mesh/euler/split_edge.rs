//! `split_edge` / `join_edges`: a new vertex on an edge, and its removal.

use glam::DVec3;

use crate::mesh::{Edge, EdgeId, EdgeUse, LoopStart, Side, Solid, Vertex, VertexId};

use super::EulerError;
use super::links::check_position;

impl Solid {
    /// Splits `edge` at a new vertex at `position` (Mäntylä's `semv`): the
    /// edge now ends at the new vertex and a new edge runs from there to the
    /// old end, with the same faces. Returns the new vertex and the new
    /// edge. The position is taken as given: it should lie on the edge.
    ///
    /// Euler–Poincaré: `V + 1, E + 1`. O(1).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownEdge`], [`EulerError::NonFinitePosition`].
    pub fn split_edge(
        &mut self,
        edge: EdgeId,
        position: DVec3,
    ) -> Result<(VertexId, EdgeId), EulerError> {
        let e = self.edges.get(edge).ok_or(EulerError::UnknownEdge(edge))?;
        check_position(position)?;
        let (left_face, right_face, y) = (e.left_face, e.right_face, e.dest);
        let left = EdgeUse {
            edge,
            side: Side::Left,
        };
        let right = left.opposite();
        // The uses after the left side and before the right side, at `y`.
        let (next_left, prev_right) = (self.use_next(left), self.use_prev(right));
        let dangling = next_left == right;
        let vertex = self.vertices.insert(Vertex {
            position,
            edge: Some(edge),
            source_index: None,
        });
        let new = self.edges.insert_with_key(|new| Edge {
            origin: vertex,
            dest: y,
            left_face,
            right_face,
            cw_left: edge,
            ccw_left: if dangling { new } else { next_left.edge },
            cw_right: if dangling { new } else { prev_right.edge },
            ccw_right: edge,
        });
        let e = &mut self.edges[edge];
        e.dest = vertex;
        e.ccw_left = new;
        e.cw_right = new;
        if !dangling {
            self.set_prev(next_left, new);
            self.set_next(prev_right, new);
        }
        if self.vertices[y].edge == Some(edge) {
            self.vertices[y].edge = Some(new);
        }
        Ok((vertex, new))
    }

    /// Joins the two edges at `vertex` into one and removes the vertex (the
    /// inverse of [`Solid::split_edge`]). The edge that ends at `vertex`
    /// survives (of two that both end or both start there, the first in id
    /// order) and reaches over to the far end of the other, which is
    /// removed. Returns the surviving edge.
    ///
    /// Euler–Poincaré: `V − 1, E − 1`. O(degree of the far ends).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownVertex`], [`EulerError::WrongDegree`] unless the
    /// vertex has exactly two edges, and [`EulerError::AlreadyJoined`] when
    /// the two far ends are already joined by an edge.
    pub fn join_edges(&mut self, vertex: VertexId) -> Result<EdgeId, EulerError> {
        if !self.vertices.contains_key(vertex) {
            return Err(EulerError::UnknownVertex(vertex));
        }
        let star: smallvec::SmallVec<[EdgeUse; 3]> = self.vertex_star(vertex).take(3).collect();
        let [o1, o2] = star.as_slice() else {
            return Err(EulerError::WrongDegree {
                vertex,
                degree: self.vertex_degree(vertex),
                expected: 2,
            });
        };
        let ends_here = |u: &EdgeUse| self.edges[u.edge].dest == vertex;
        let (keep, kill) = match (ends_here(o1), ends_here(o2)) {
            (true, false) => (*o1, *o2),
            (false, true) => (*o2, *o1),
            _ if o1.edge < o2.edge => (*o1, *o2),
            _ => (*o2, *o1),
        };
        // `a` runs into the vertex along the survivor, `b` out along the
        // killed edge, in one loop.
        let a = keep.opposite();
        let b = self.use_next(a);
        debug_assert_eq!(b, kill, "a vertex of degree two continues its loop");
        let (x, y) = (self.use_start(a), self.use_end(b));
        self.check_joinable(x, y)?;
        let (oa, ob) = (keep, b.opposite());
        let (c, d) = (self.use_next(b), self.use_prev(ob));
        if c == ob {
            self.set_next(a, a.edge);
            self.set_prev(oa, a.edge);
        } else {
            self.set_next(a, c.edge);
            self.set_prev(c, a.edge);
            self.set_next(d, a.edge);
            self.set_prev(oa, d.edge);
        }
        for (dead, alive) in [(b, a), (ob, oa)] {
            if let Some(face) = self.use_face(dead) {
                let loops: smallvec::SmallVec<[_; 4]> = self.face_loops(face).collect();
                for l in loops {
                    if self.loops[l].start == LoopStart::Edge(dead) {
                        self.loops[l].start = LoopStart::Edge(alive);
                    }
                }
            }
        }
        let e = &mut self.edges[a.edge];
        if e.dest == vertex {
            e.dest = y;
        } else {
            e.origin = y;
        }
        if self.vertices[y].edge == Some(b.edge) {
            self.vertices[y].edge = Some(a.edge);
        }
        self.edges.remove(b.edge);
        self.vertices.remove(vertex);
        Ok(a.edge)
    }
}
