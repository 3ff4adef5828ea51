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
        // A triangle without rings is its own triangulation (when its
        // corners are distinct and not collinear, which the general path
        // checks).
        if self.face(face).rings.is_empty() {
            let mut corners = self.loop_vertices(self.face(face).outer);
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
                return Ok(vec![[a, b, c]]);
            }
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
}
