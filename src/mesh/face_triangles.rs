//! Triangles of a face, rings included: the exact constrained triangulation
//! of its loops.

use glam::DVec3;

use crate::geom::triangulate::{TriangulateError, triangulate_3d};

use super::{FaceId, Solid, VertexId};

impl Solid {
    /// The triangles of `face`: the constrained Delaunay triangulation of
    /// its outer loop with its rings as holes ([`triangulate_3d`], exact
    /// predicates: no triangle is flipped or of zero area), each triangle
    /// wound like the face (counter-clockwise seen from outside).
    ///
    /// # Errors
    ///
    /// The [`TriangulateError`] of loops that do not bound a valid face: a
    /// loop that is not simple or has fewer than three vertices, collinear
    /// corners, a ring not strictly inside the outer loop, rings touching.
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    pub fn try_triangulate_face(
        &self,
        face: FaceId,
    ) -> Result<Vec<[VertexId; 3]>, TriangulateError> {
        if let Some(triangle) = self.face_as_triangle(face) {
            return Ok(vec![triangle]);
        }
        let loops: Vec<Vec<VertexId>> = self
            .face_loops(face)
            .map(|l| self.loop_vertices(l).collect())
            .collect();
        let points: Vec<Vec<DVec3>> = loops
            .iter()
            .map(|l| l.iter().map(|&v| self.position(v)).collect())
            .collect();
        let holes: Vec<&[DVec3]> = points[1..].iter().map(Vec::as_slice).collect();
        let triangles = triangulate_3d(&points[0], &holes)?;
        let all: Vec<VertexId> = loops.into_iter().flatten().collect();
        Ok(triangles.into_iter().map(|t| t.map(|i| all[i])).collect())
    }

    /// The corners of `face` when it is a triangle without rings whose
    /// corners are distinct and not on one line: then it is its own
    /// triangulation ([`Solid::try_triangulate_face`] answers it without
    /// the general path, which checks the other cases).
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    #[must_use]
    pub(crate) fn face_as_triangle(&self, face: FaceId) -> Option<[VertexId; 3]> {
        let face = self.face(face);
        if !face.rings.is_empty() {
            return None;
        }
        let mut corners = self.loop_vertices(face.outer);
        if let (Some(a), Some(b), Some(c), None) = (
            corners.next(),
            corners.next(),
            corners.next(),
            corners.next(),
        ) && a != b
            && b != c
            && c != a
            && !crate::geom::collinear3d(self.position(a), self.position(b), self.position(c))
        {
            return Some([a, b, c]);
        }
        None
    }
}
