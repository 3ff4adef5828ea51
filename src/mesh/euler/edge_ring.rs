//! `kemr` / `mekr`: removing an edge that a loop runs both ways, which
//! splits the loop and makes a ring, and joining two loops of a face by a
//! new edge, which kills a ring.

use crate::mesh::{Edge, EdgeId, EdgeUse, Loop, LoopId, LoopStart, Side, Solid};

use super::corner::Place;
use super::{Corner, EulerError};

impl Solid {
    /// Kill edge, make ring: removes `edge`, whose two sides are on one loop
    /// of one face (a bridge between two parts of the loop), splitting the
    /// loop in two. The part at the edge's `dest` becomes a new ring of the
    /// face; the loop keeps the part at its `origin`. A part without edges
    /// becomes a lone vertex.
    ///
    /// Euler–Poincaré: `E − 1, R + 1`. O(length of the loop).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownEdge`], and [`EulerError::SidesOnDifferentLoops`]
    /// unless both sides of the edge are on one loop.
    pub fn kemr(&mut self, edge: EdgeId) -> Result<LoopId, EulerError> {
        let e = self.edges.get(edge).ok_or(EulerError::UnknownEdge(edge))?;
        let face = e.left_face;
        let a = EdgeUse {
            edge,
            side: Side::Left,
        };
        let b = a.opposite();
        if e.right_face != Some(face) || !self.loop_reaches(a, b) {
            return Err(EulerError::SidesOnDifferentLoops { edge });
        }
        let l = self.loop_of_use(a, face);
        let (x, y) = (e.origin, e.dest);
        let (na, pa) = (self.use_next(a), self.use_prev(a));
        let (nb, pb) = (self.use_next(b), self.use_prev(b));
        // The part at `y` runs from `na` to `pb`; the part at `x` from `nb`
        // to `pa`. Either is empty when its vertex ends a strut.
        let ring_start = if na == b {
            LoopStart::Vertex(y)
        } else {
            self.set_next(pb, na.edge);
            self.set_prev(na, pb.edge);
            LoopStart::Edge(na)
        };
        let kept_start = if nb == a {
            LoopStart::Vertex(x)
        } else {
            self.set_next(pa, nb.edge);
            self.set_prev(nb, pa.edge);
            LoopStart::Edge(nb)
        };
        let stays = match (self.loops[l].start, kept_start) {
            (LoopStart::Edge(s), LoopStart::Edge(k)) => s.edge != edge && self.loop_reaches(k, s),
            _ => false,
        };
        if !stays {
            self.loops[l].start = kept_start;
        }
        for (v, start) in [(x, kept_start), (y, ring_start)] {
            if self.vertices[v].edge == Some(edge) {
                self.vertices[v].edge = match start {
                    LoopStart::Edge(u) => Some(u.edge),
                    LoopStart::Vertex(_) => None,
                };
            }
        }
        let ring = self.loops.insert(Loop {
            face,
            start: ring_start,
        });
        self.insert_ring(face, ring);
        self.edges.remove(edge);
        Ok(ring)
    }

    /// Make edge, kill ring: a new edge from the vertex of `from` to the
    /// vertex of `to`, two corners on different loops of one face, joining
    /// the two loops into one. The loop of `to` must be a ring; it is
    /// killed, and the loop of `from` (outer or ring) holds both. The
    /// inverse of [`Solid::kemr`].
    ///
    /// Euler–Poincaré: `E + 1, R − 1`. O(length of the two loops).
    ///
    /// # Errors
    ///
    /// Those of a bad corner; [`EulerError::SameVertex`],
    /// [`EulerError::AlreadyJoined`], [`EulerError::DifferentFaces`],
    /// [`EulerError::SameLoop`] when both corners are on one loop, and
    /// [`EulerError::NotARing`] when the loop of `to` is its face's outer
    /// loop.
    pub fn mekr(&mut self, from: Corner, to: Corner) -> Result<EdgeId, EulerError> {
        let a = self.resolve(from)?;
        let b = self.resolve(to)?;
        self.check_joinable(a.vertex, b.vertex)?;
        let face = a.face;
        if face != b.face {
            return Err(EulerError::DifferentFaces {
                f1: a.face,
                f2: b.face,
            });
        }
        let loop_of = |s: &Solid, place: Place| match place {
            Place::Between(u, _) => s.loop_of_use(u, face),
            Place::Lone(l) => l,
        };
        let (kept, killed) = (loop_of(self, a.place), loop_of(self, b.place));
        if kept == killed {
            return Err(EulerError::SameLoop {
                v1: a.vertex,
                v2: b.vertex,
                loop_id: kept,
            });
        }
        if self.faces[face].outer == killed {
            return Err(EulerError::NotARing {
                loop_id: killed,
                face,
            });
        }
        let edge = self.edges.insert_with_key(|edge| {
            let (u1, n1) = a.between().map_or((edge, edge), |(u, n)| (u.edge, n.edge));
            let (u2, n2) = b.between().map_or((edge, edge), |(u, n)| (u.edge, n.edge));
            Edge {
                origin: a.vertex,
                dest: b.vertex,
                left_face: face,
                right_face: Some(face),
                cw_left: u1,
                ccw_left: n2,
                cw_right: u2,
                ccw_right: n1,
            }
        });
        for at in [a, b] {
            match at.place {
                Place::Between(u, n) => {
                    self.set_next(u, edge);
                    self.set_prev(n, edge);
                }
                Place::Lone(_) => self.vertices[at.vertex].edge = Some(edge),
            }
        }
        if let LoopStart::Vertex(_) = self.loops[kept].start {
            self.loops[kept].start = LoopStart::Edge(EdgeUse {
                edge,
                side: Side::Left,
            });
        }
        self.remove_ring(face, killed);
        self.loops.remove(killed);
        Ok(edge)
    }
}
