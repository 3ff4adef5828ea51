//! `mef` / `kef`: a new edge splitting a loop into two faces, and its
//! removal merging them.

use slotmap::Key;

use crate::mesh::{Edge, EdgeId, EdgeUse, Face, FaceId, Loop, LoopId, LoopStart, Side, Solid};

use super::corner::Place;
use super::{Corner, EulerError};

impl Solid {
    /// Make edge, face: a new edge from the vertex of `from` to the vertex
    /// of `to`, two corners of one loop, splitting that loop in two. The
    /// new face lies on the edge's left: its loop is the new edge followed
    /// by the old loop from `to` around to `from`. The old face keeps the
    /// other part (the new edge from `to` to `from`, then the old loop from
    /// `from` around to `to`) and all its rings. The new face copies the old
    /// face's attributes and gets the Newell plane of its loop.
    ///
    /// Euler–Poincaré: `E + 1, F + 1`. O(length of the loop).
    ///
    /// # Errors
    ///
    /// Those of a bad corner; [`EulerError::SameVertex`] and
    /// [`EulerError::AlreadyJoined`] (the new edge would start and end at
    /// one vertex, or double an edge); [`EulerError::DifferentFaces`] and
    /// [`EulerError::DifferentLoops`] unless both corners are on one loop.
    pub fn mef(&mut self, from: Corner, to: Corner) -> Result<(EdgeId, FaceId), EulerError> {
        let a = self.resolve(from)?;
        let b = self.resolve(to)?;
        self.check_joinable(a.vertex, b.vertex)?;
        if a.face != b.face {
            return Err(EulerError::DifferentFaces {
                f1: a.face,
                f2: b.face,
            });
        }
        let (Place::Between(u1, n1), Place::Between(u2, n2)) = (a.place, b.place) else {
            // A lone vertex is a loop by itself: the other corner, at
            // another vertex, is on another loop.
            return Err(EulerError::DifferentLoops {
                v1: a.vertex,
                v2: b.vertex,
                face: a.face,
            });
        };
        if !self.loop_reaches(u1, u2) {
            return Err(EulerError::DifferentLoops {
                v1: a.vertex,
                v2: b.vertex,
                face: a.face,
            });
        }
        let old = a.face;
        let l = self.loop_of_use(u1, old);
        let attributes = self.faces[old].attributes.clone();
        let new = self.faces.insert(Face {
            plane: None,
            outer: LoopId::null(),
            rings: Vec::new(),
            attributes,
        });
        let edge = self.edges.insert(Edge {
            origin: a.vertex,
            dest: b.vertex,
            left_face: new,
            right_face: Some(old),
            cw_left: u1.edge,
            ccw_left: n2.edge,
            cw_right: u2.edge,
            ccw_right: n1.edge,
        });
        self.set_next(u1, edge);
        self.set_prev(n2, edge);
        self.set_next(u2, edge);
        self.set_prev(n1, edge);
        let left = EdgeUse {
            edge,
            side: Side::Left,
        };
        let moved = matches!(self.loops[l].start, LoopStart::Edge(s) if self.loop_reaches(left, s));
        if moved {
            self.loops[l].start = LoopStart::Edge(left.opposite());
        }
        self.claim_loop(left, new);
        let new_loop = self.loops.insert(Loop {
            face: new,
            start: LoopStart::Edge(left),
        });
        self.faces[new].outer = new_loop;
        self.faces[new].plane = self.loop_plane(new_loop);
        Ok((edge, new))
    }

    /// Kill edge, face: removes `edge` and the face `face` on one of its
    /// sides, merging that face's loop into the loop of the face on the
    /// other side. The inverse of [`Solid::mef`] (with the face it made).
    ///
    /// Euler–Poincaré: `E − 1, F − 1`. O(length of the killed face's loop).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownEdge`], [`EulerError::UnknownFace`],
    /// [`EulerError::FaceNotOnEdge`], [`EulerError::SidesOnDifferentLoops`]
    /// for a boundary edge, [`EulerError::SameFaceBothSides`], and
    /// [`EulerError::FaceHasRings`] when the killed face has rings.
    pub fn kef(&mut self, edge: EdgeId, face: FaceId) -> Result<(), EulerError> {
        let e = self.edges.get(edge).ok_or(EulerError::UnknownEdge(edge))?;
        let f = self.faces.get(face).ok_or(EulerError::UnknownFace(face))?;
        let Some(right) = e.right_face else {
            return Err(EulerError::SidesOnDifferentLoops { edge });
        };
        if e.left_face == right {
            return Err(EulerError::SameFaceBothSides { edge, face: right });
        }
        let (side, survivor) = if e.left_face == face {
            (Side::Left, right)
        } else if right == face {
            (Side::Right, e.left_face)
        } else {
            return Err(EulerError::FaceNotOnEdge { face, edge });
        };
        if !f.rings.is_empty() {
            return Err(EulerError::FaceHasRings {
                face,
                rings: f.rings.len(),
            });
        }
        let killed_loop = f.outer;
        let a = EdgeUse { edge, side };
        let b = a.opposite();
        let (x, y) = (self.use_start(a), self.use_end(a));
        let (na, pa) = (self.use_next(a), self.use_prev(a));
        let (nb, pb) = (self.use_next(b), self.use_prev(b));
        self.set_next(pb, na.edge);
        self.set_prev(na, pb.edge);
        self.set_next(pa, nb.edge);
        self.set_prev(nb, pa.edge);
        // The killed face's uses, now between `pb` and `nb`, join the
        // survivor.
        let mut u = na;
        while u != nb {
            self.set_use_face(u, survivor);
            u = self.use_next(u);
        }
        let loops: smallvec::SmallVec<[_; 4]> = self.face_loops(survivor).collect();
        for l in loops {
            if self.loops[l].start == LoopStart::Edge(b) {
                self.loops[l].start = LoopStart::Edge(nb);
            }
        }
        if self.vertices[x].edge == Some(edge) {
            self.vertices[x].edge = Some(nb.edge);
        }
        if self.vertices[y].edge == Some(edge) {
            self.vertices[y].edge = Some(na.edge);
        }
        self.loops.remove(killed_loop);
        self.faces.remove(face);
        self.edges.remove(edge);
        Ok(())
    }
}
