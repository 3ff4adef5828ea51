//! The small edits every operator is made of: rewiring one wing, moving a
//! loop to another face, keeping a face's rings sorted.

use glam::DVec3;

use crate::geom::Plane;
use crate::mesh::{EdgeId, EdgeUse, FaceId, LoopId, LoopStart, Side, Solid, VertexId};

use super::EulerError;

impl Solid {
    /// Makes `edge` the wing after `u` in `u`'s loop.
    pub(super) fn set_next(&mut self, u: EdgeUse, edge: EdgeId) {
        let e = &mut self.edges[u.edge];
        match u.side {
            Side::Left => e.ccw_left = edge,
            Side::Right => e.ccw_right = edge,
        }
    }

    /// Makes `edge` the wing before `u` in `u`'s loop.
    pub(super) fn set_prev(&mut self, u: EdgeUse, edge: EdgeId) {
        let e = &mut self.edges[u.edge];
        match u.side {
            Side::Left => e.cw_left = edge,
            Side::Right => e.cw_right = edge,
        }
    }

    /// Puts `face` on `u`'s side of its edge.
    pub(super) fn set_use_face(&mut self, u: EdgeUse, face: FaceId) {
        let e = &mut self.edges[u.edge];
        match u.side {
            Side::Left => e.left_face = face,
            Side::Right => e.right_face = Some(face),
        }
    }

    /// Puts `face` on every use of the loop through `start`; O(loop length).
    pub(super) fn claim_loop(&mut self, start: EdgeUse, face: FaceId) {
        let uses: Vec<EdgeUse> = self.loop_from(start).collect();
        for u in uses {
            self.set_use_face(u, face);
        }
    }

    /// The loop of `face` that the face use `u` belongs to: walks the loop
    /// until it meets a loop's stored start. O(loop length × loops of the
    /// face).
    pub(super) fn loop_of_use(&self, u: EdgeUse, face: FaceId) -> LoopId {
        let starts: smallvec::SmallVec<[(EdgeUse, LoopId); 4]> = self
            .face_loops(face)
            .filter_map(|l| match self.loops[l].start {
                LoopStart::Edge(s) => Some((s, l)),
                LoopStart::Vertex(_) => None,
            })
            .collect();
        self.loop_from(u)
            .find_map(|w| starts.iter().find(|(s, _)| *s == w).map(|&(_, l)| l))
            .expect("every face use lies on a loop of its face")
    }

    /// Whether the walk of a loop from `from` meets `target`.
    pub(super) fn loop_reaches(&self, from: EdgeUse, target: EdgeUse) -> bool {
        self.loop_from(from).any(|u| u == target)
    }

    /// The edge joining `a` and `b`, if any; O(degree of `a`).
    pub(super) fn edge_between(&self, a: VertexId, b: VertexId) -> Option<EdgeId> {
        self.vertex_star(a)
            .find(|&u| self.use_end(u) == b)
            .map(|u| u.edge)
    }

    /// Refuses to join `v1` and `v2` by a new edge when that would start and
    /// end at one vertex or double an edge.
    pub(super) fn check_joinable(&self, v1: VertexId, v2: VertexId) -> Result<(), EulerError> {
        if v1 == v2 {
            return Err(EulerError::SameVertex(v1));
        }
        match self.edge_between(v1, v2) {
            Some(edge) => Err(EulerError::AlreadyJoined { v1, v2, edge }),
            None => Ok(()),
        }
    }

    /// Adds `ring` to `face`'s rings, keeping them sorted.
    pub(super) fn insert_ring(&mut self, face: FaceId, ring: LoopId) {
        let rings = &mut self.faces[face].rings;
        if let Err(at) = rings.binary_search(&ring) {
            rings.insert(at, ring);
        }
    }

    /// Removes `ring` from `face`'s rings.
    pub(super) fn remove_ring(&mut self, face: FaceId, ring: LoopId) {
        let rings = &mut self.faces[face].rings;
        if let Ok(at) = rings.binary_search(&ring) {
            rings.remove(at);
        }
    }

    /// The Newell plane of a loop's vertices, `None` when they enclose no
    /// area (a rounded construction, as every stored plane).
    pub(super) fn loop_plane(&self, l: LoopId) -> Option<Plane> {
        let points: Vec<DVec3> = self.loop_vertices(l).map(|v| self.position(v)).collect();
        Plane::try_fit_newell(&points).ok().map(|fit| fit.plane)
    }

    /// Refits `face`'s plane to its outer loop.
    pub(crate) fn refit_plane(&mut self, face: FaceId) {
        self.faces[face].plane = self.loop_plane(self.faces[face].outer);
    }
}

/// Refuses a non-finite position for a new vertex.
pub(super) fn check_position(position: DVec3) -> Result<(), EulerError> {
    if position.is_finite() {
        Ok(())
    } else {
        Err(EulerError::NonFinitePosition { position })
    }
}
