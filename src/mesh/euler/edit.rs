//! Editing operations built on the Euler operators that also keep the
//! geometry right: splitting a face along a diagonal and extruding a face.

use glam::{DVec2, DVec3};

use crate::geom::polygon::{PolygonLocation, Projection, locate_point_in_polygon, segments_touch};
use crate::geom::{Sign, orient2d};
use crate::mesh::{EdgeId, EdgeUse, FaceId, LoopId, Side, Solid, VertexId};

use super::{Corner, EulerError};

impl Solid {
    /// Splits `face` in two along the segment from `v1` to `v2`, two
    /// vertices of the same loop, with [`Solid::mef`]. The segment must run
    /// inside the face, touching its loops only at its two ends (decided
    /// exactly in the projection onto the axis plane closest to the face).
    /// Rings go with the part that contains them. Returns the new edge and
    /// the new face (on the new edge's left, running it from `v1` to `v2`);
    /// both parts get planes refitted to their outer loops.
    ///
    /// O(size of the face, times its length for the segment test).
    ///
    /// # Errors
    ///
    /// Those of [`Solid::corner`] and [`Solid::mef`];
    /// [`EulerError::LoopNotSimple`]; [`EulerError::SplitOutsideFace`] when
    /// the segment leaves the face or touches its boundary elsewhere.
    pub fn split_face(
        &mut self,
        face: FaceId,
        v1: VertexId,
        v2: VertexId,
    ) -> Result<(EdgeId, FaceId), EulerError> {
        let c1 = self.corner(face, v1)?;
        let c2 = self.corner(face, v2)?;
        self.check_joinable(v1, v2)?;
        self.check_simple_loops(face)?;
        let projection = self.face_projection(face);
        let flat = |s: &Solid, v: VertexId| projection.apply(s.position(v));
        let outside = EulerError::SplitOutsideFace { face, v1, v2 };
        let (Corner::After(u1), Corner::After(u2)) = (c1, c2) else {
            return Err(outside);
        };
        for (u, other) in [(u1, v2), (u2, v1)] {
            let n = self.use_next(u);
            let [p, v, q] =
                [self.use_start(u), self.use_end(u), self.use_end(n)].map(|w| flat(self, w));
            // A projection that flips the winding puts the inside on the
            // right: the corner seen backwards has it on the left.
            let (p, q) = if projection.flipped { (q, p) } else { (p, q) };
            if !inside_corner(p, v, q, flat(self, other)) {
                return Err(outside);
            }
        }
        let (a, b) = (flat(self, v1), flat(self, v2));
        for u in self.face_loop(face) {
            let (s, t) = (self.use_start(u), self.use_end(u));
            if [s, t].iter().any(|&w| w == v1 || w == v2) {
                continue;
            }
            if segments_touch(a, b, flat(self, s), flat(self, t)) {
                return Err(outside);
            }
        }
        let (edge, new) = self.mef(c1, c2)?;
        let outline: Vec<DVec2> = self
            .face_outer_vertices(new)
            .map(|v| flat(self, v))
            .collect();
        let rings: Vec<LoopId> = self.faces[face].rings.clone();
        for ring in rings {
            let first = self
                .loop_vertices(ring)
                .next()
                .expect("a loop has a vertex");
            if locate_point_in_polygon(&outline, flat(self, first)) == PolygonLocation::Inside {
                self.remove_ring(face, ring);
                self.loops[ring].face = new;
                let start = self
                    .loop_uses(ring)
                    .next()
                    .expect("a simple ring has edges");
                self.claim_loop(start, new);
                self.insert_ring(new, ring);
            }
        }
        self.refit_plane(face);
        self.refit_plane(new);
        Ok((edge, new))
    }

    /// Extrudes `face` by `vector`: every vertex of every loop of the face
    /// gets a copy moved by `vector` ([`Solid::mev`]), consecutive copies
    /// are joined ([`Solid::mef`]), so that each edge of the face gets a
    /// side face and the face itself, with its rings, moves to the copies
    /// (Mäntylä's sweep). The face keeps its id and gets its plane refitted.
    ///
    /// O(Σ loop length²) for the loop checks of [`Solid::mef`].
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownFace`], [`EulerError::NonFiniteVector`],
    /// [`EulerError::NonFinitePosition`] when a moved vertex overflows,
    /// [`EulerError::LoopNotSimple`], and [`EulerError::NotOutward`] unless
    /// every moved vertex is strictly on the outer side of the face's
    /// plane (decided exactly by [`Solid::face_side`]).
    pub fn extrude_face(&mut self, face: FaceId, vector: DVec3) -> Result<(), EulerError> {
        if !self.faces.contains_key(face) {
            return Err(EulerError::UnknownFace(face));
        }
        if !vector.is_finite() {
            return Err(EulerError::NonFiniteVector { vector });
        }
        self.check_simple_loops(face)?;
        let vertices: Vec<VertexId> = self.face_vertices(face).collect();
        for &v in &vertices {
            let position = self.position(v) + vector;
            if !position.is_finite() {
                return Err(EulerError::NonFinitePosition { position });
            }
            if self.face_side(face, position) != Sign::Positive {
                return Err(EulerError::NotOutward {
                    face,
                    vector,
                    vertex: v,
                });
            }
        }
        let loops: Vec<Vec<EdgeUse>> = self
            .face_loops(face)
            .map(|l| self.loop_uses(l).collect())
            .collect();
        for uses in loops {
            self.extrude_loop(&uses, vector)?;
        }
        self.refit_plane(face);
        Ok(())
    }

    /// Sweeps one simple loop (its uses `u_i` from `v_i` to `v_{i+1}`): a
    /// strut `s_i` from each `v_i` to its copy `w_i`, then the edge from
    /// `w_{i+1}` to `w_i`, which cuts the side face
    /// `w_{i+1} w_i v_i v_{i+1}` off the loop.
    fn extrude_loop(&mut self, uses: &[EdgeUse], vector: DVec3) -> Result<(), EulerError> {
        let n = uses.len();
        let mut struts = Vec::with_capacity(n);
        for i in 0..n {
            let before = uses[(i + n - 1) % n];
            let v = self.use_end(before);
            let (edge, _) = self.mev(Corner::After(before), self.position(v) + vector)?;
            struts.push(EdgeUse {
                edge,
                side: Side::Left,
            });
        }
        let mut previous_top: Option<EdgeUse> = None;
        for i in 0..n {
            let from = Corner::After(struts[(i + 1) % n]);
            let to = Corner::After(previous_top.unwrap_or(struts[0]));
            let (edge, _) = self.mef(from, to)?;
            previous_top = Some(EdgeUse {
                edge,
                side: Side::Right,
            });
        }
        Ok(())
    }

    /// Raises a pyramid over `face`: a new vertex at `apex` joined to every
    /// corner of the face ([`Solid::mev`] once, then [`Solid::mef`] per
    /// further corner), so that the face becomes a fan of triangles around
    /// the apex. The face keeps its id as one of the triangles. Returns the
    /// apex.
    ///
    /// O(length of the face's loop²).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownFace`], [`EulerError::NonFinitePosition`],
    /// [`EulerError::FaceHasRings`], [`EulerError::LoopNotSimple`], and
    /// [`EulerError::NotOutward`] unless `apex` is strictly on the outer
    /// side of the face's plane (decided exactly by [`Solid::face_side`]).
    pub fn cone_face(&mut self, face: FaceId, apex: DVec3) -> Result<VertexId, EulerError> {
        let f = self.faces.get(face).ok_or(EulerError::UnknownFace(face))?;
        if !f.rings.is_empty() {
            return Err(EulerError::FaceHasRings {
                face,
                rings: f.rings.len(),
            });
        }
        super::links::check_position(apex)?;
        self.check_simple_loops(face)?;
        let uses: Vec<EdgeUse> = self.face_loop(face).collect();
        if self.face_side(face, apex) != Sign::Positive {
            return Err(EulerError::NotOutward {
                face,
                vector: apex - self.position(self.use_start(uses[0])),
                vertex: self.use_start(uses[0]),
            });
        }
        let n = uses.len();
        let (strut, top) = self.mev(Corner::After(uses[n - 1]), apex)?;
        let up = EdgeUse {
            edge: strut,
            side: Side::Left,
        };
        for &before in &uses[..n - 1] {
            self.mef(Corner::After(before), Corner::After(up))?;
        }
        self.refit_plane(face);
        Ok(top)
    }

    /// The projection onto the axis plane closest to `face`'s outer loop.
    fn face_projection(&self, face: FaceId) -> Projection {
        let points: Vec<DVec3> = self
            .face_outer_vertices(face)
            .map(|v| self.position(v))
            .collect();
        Projection::along(crate::geom::newell_vector_area(&points, points[0]))
    }
}

/// Whether the direction from `v` to `target` lies strictly inside the
/// corner `p v q` of a polygon whose inside is on the left of `p → v → q`
/// (counter-clockwise in the projection), decided exactly.
fn inside_corner(p: DVec2, v: DVec2, q: DVec2, target: DVec2) -> bool {
    let after_incoming = orient2d(p, v, target) == Sign::Positive;
    let before_outgoing = orient2d(v, q, target) == Sign::Positive;
    match orient2d(p, v, q) {
        Sign::Positive => after_incoming && before_outgoing,
        Sign::Negative => after_incoming || before_outgoing,
        Sign::Zero => after_incoming,
    }
}
