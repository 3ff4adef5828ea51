//! The winged-edge solid: three tables and their accessors.

use glam::DVec3;
use slotmap::SlotMap;

use crate::geom::{Sign, orient3d};

use super::{Edge, EdgeId, Face, FaceId, Loop, LoopId, Vertex, VertexId};

/// A polyhedral boundary representation in winged-edge form.
///
/// # Invariants
///
/// Every invariant of [`Vertex`], [`Edge`], [`Face`] and [`Loop`] holds, and
/// every id stored in a table names an element of the same solid. Closed
/// solids (no boundary edges) are oriented outward when built by the
/// builders in this crate; imported ones are checked by validation. A
/// `Solid` is only created through checked constructors and changed only by
/// the Euler operators ([`super::euler`]), which check their pre-conditions
/// before they change anything; it offers no mutable access to its tables,
/// so the invariants cannot be broken from outside;
/// [`Solid::check_consistency`] re-verifies all of them.
#[derive(Clone, Debug, Default)]
pub struct Solid {
    pub(super) vertices: SlotMap<VertexId, Vertex>,
    pub(super) edges: SlotMap<EdgeId, Edge>,
    pub(super) faces: SlotMap<FaceId, Face>,
    pub(super) loops: SlotMap<LoopId, Loop>,
}

impl Solid {
    /// Replaces the attributes of `face` (labels only: no topology or
    /// geometry changes, so no invariant is affected). Does nothing for an
    /// unknown face.
    pub fn set_face_attributes(&mut self, face: FaceId, attributes: super::FaceAttributes) {
        if let Some(f) = self.faces.get_mut(face) {
            f.attributes = attributes;
        }
    }

    /// Makes `ring`, a ring of `face`, the face's outer loop and the outer
    /// loop a ring (which loop is outer is a designation, not topology:
    /// no wing or count changes). Returns whether it did; `false` when
    /// `ring` is not a ring of `face`.
    pub fn swap_outer_loop(&mut self, face: FaceId, ring: super::LoopId) -> bool {
        let Some(f) = self.faces.get_mut(face) else {
            return false;
        };
        let Some(k) = f.rings.iter().position(|&r| r == ring) else {
            return false;
        };
        f.rings[k] = f.outer;
        f.outer = ring;
        f.rings.sort_unstable();
        true
    }

    /// The number of vertices.
    #[must_use]
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// The number of edges.
    #[must_use]
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// The number of faces.
    #[must_use]
    pub fn face_count(&self) -> usize {
        self.faces.len()
    }

    /// The number of loops (one outer loop per face plus the rings).
    #[must_use]
    pub fn loop_count(&self) -> usize {
        self.loops.len()
    }

    /// The number of rings: inner loops of faces, `R` in the
    /// Euler–Poincaré formula `V − E + F − R = 2 (S − H)`.
    #[must_use]
    pub fn ring_count(&self) -> usize {
        self.loops.len() - self.faces.len()
    }

    /// The vertex `id`.
    ///
    /// # Panics
    ///
    /// If `id` is not a vertex of this solid (a programmer error: ids are
    /// only valid for the solid that issued them). See [`Solid::get_vertex`].
    #[must_use]
    pub fn vertex(&self, id: VertexId) -> &Vertex {
        &self.vertices[id]
    }

    /// The edge `id`.
    ///
    /// # Panics
    ///
    /// If `id` is not an edge of this solid.
    #[must_use]
    pub fn edge(&self, id: EdgeId) -> &Edge {
        &self.edges[id]
    }

    /// The face `id`.
    ///
    /// # Panics
    ///
    /// If `id` is not a face of this solid.
    #[must_use]
    pub fn face(&self, id: FaceId) -> &Face {
        &self.faces[id]
    }

    /// The loop `id`.
    ///
    /// # Panics
    ///
    /// If `id` is not a loop of this solid.
    #[must_use]
    pub fn loop_record(&self, id: LoopId) -> &Loop {
        &self.loops[id]
    }

    /// The loop `id`, or `None` if it is not a loop of this solid.
    #[must_use]
    pub fn get_loop(&self, id: LoopId) -> Option<&Loop> {
        self.loops.get(id)
    }

    /// The vertex `id`, or `None` if it is not a vertex of this solid.
    #[must_use]
    pub fn get_vertex(&self, id: VertexId) -> Option<&Vertex> {
        self.vertices.get(id)
    }

    /// The edge `id`, or `None` if it is not an edge of this solid.
    #[must_use]
    pub fn get_edge(&self, id: EdgeId) -> Option<&Edge> {
        self.edges.get(id)
    }

    /// The face `id`, or `None` if it is not a face of this solid.
    #[must_use]
    pub fn get_face(&self, id: FaceId) -> Option<&Face> {
        self.faces.get(id)
    }

    /// The position of vertex `id`.
    ///
    /// # Panics
    ///
    /// If `id` is not a vertex of this solid.
    #[must_use]
    pub fn position(&self, id: VertexId) -> DVec3 {
        self.vertices[id].position
    }

    /// All vertices with their ids, in creation order.
    pub fn vertices(&self) -> impl ExactSizeIterator<Item = (VertexId, &Vertex)> + '_ {
        self.vertices.iter()
    }

    /// All edges with their ids, in creation order.
    pub fn edges(&self) -> impl ExactSizeIterator<Item = (EdgeId, &Edge)> + '_ {
        self.edges.iter()
    }

    /// All faces with their ids, in creation order.
    pub fn faces(&self) -> impl ExactSizeIterator<Item = (FaceId, &Face)> + '_ {
        self.faces.iter()
    }

    /// All loops with their ids, in creation order.
    pub fn loops(&self) -> impl ExactSizeIterator<Item = (LoopId, &Loop)> + '_ {
        self.loops.iter()
    }

    /// Whether every edge has two faces (the surface has no holes).
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.edges.values().all(|e| e.right_face.is_some())
    }

    /// The edges with only one face: the rims of holes.
    pub fn boundary_edges(&self) -> impl Iterator<Item = EdgeId> + '_ {
        self.edges
            .iter()
            .filter(|(_, e)| e.right_face.is_none())
            .map(|(id, _)| id)
    }

    /// Which side of face `face` the point `p` lies on, decided exactly.
    ///
    /// [`Sign::Positive`] means outside (the side the outward normal points
    /// to), [`Sign::Negative`] inside and [`Sign::Zero`] exactly in the
    /// plane. The decision is [`orient3d`] on three of the face's own vertices
    /// (the first vertex and the two that span the largest triangle with it),
    /// never the rounded plane coefficients. For a triangle this is exact with
    /// respect to the face itself; for a polygon whose vertices are not
    /// exactly coplanar it is exact with respect to that triangle's plane.
    /// A face with zero area gives [`Sign::Zero`] everywhere.
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    #[must_use]
    pub fn face_side(&self, face: FaceId, p: DVec3) -> Sign {
        match self.face_pivot(face) {
            Some([a, b, c]) => orient3d(a, b, c, p),
            None => Sign::Zero,
        }
    }

    /// Three vertices of `face`'s outer loop spanning its plane, in the
    /// face's winding: the first vertex and the pair that forms the largest
    /// triangle with it.
    /// `None` for a face of zero area.
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    #[must_use]
    pub fn face_pivot(&self, face: FaceId) -> Option<[DVec3; 3]> {
        let outer = self.faces[face].outer;
        let points: smallvec::SmallVec<[DVec3; 8]> = self
            .loop_vertices(outer)
            .map(|v| self.position(v))
            .collect();
        let n = points.len();
        if n < 3 {
            return None;
        }
        if n == 3 {
            return Some([points[0], points[1], points[2]]);
        }
        let normal = self.faces[face].plane?.normal;
        let a = points[0];
        let (mut best, mut best_area) = (None, 0.0);
        for i in 1..n - 1 {
            let area = (points[i] - a).cross(points[i + 1] - a).dot(normal);
            if area > best_area {
                best_area = area;
                best = Some([a, points[i], points[i + 1]]);
            }
        }
        best
    }
}
