//! Point-in-convex-polyhedron by the face planes (the normals test).

use glam::DVec3;

use crate::geom::{Sign, collinear3d, orient3d};

use super::{Accel, Containment, QueryError};

impl Accel {
    /// Classifies `p` against a convex solid by its face planes: outside if
    /// strictly on the outer side of any fan triangle's plane, on the
    /// boundary if on none's outer side but exactly on one's plane, inside
    /// otherwise. Each side is an exact `orient3d` on the triangle's corners
    /// (the sign of the normal's dot product with a vector to a vertex of
    /// the face, without rounding). Cost `O(faces)`.
    ///
    /// Convexity is decided exactly on first use and cached
    /// ([`Accel::convexity`], [`NotConvex`](super::NotConvex)): closed, one
    /// shell, and convex (or flat without folding) across every edge of the
    /// fan triangulation. A closed connected surface that is convex at every
    /// edge is the boundary of a convex body, so the answer then agrees with
    /// parity. Faces whose corners are not exactly coplanar are handled
    /// through their fan triangles (one bent outward is a reflex edge and is
    /// refused).
    ///
    /// # Errors
    ///
    /// [`QueryError::NotConvex`] when the solid is not convex,
    /// [`QueryError::NonFinitePoint`] for a NaN or infinite coordinate.
    pub fn classify_convex(&self, p: DVec3) -> Result<Containment, QueryError> {
        if !p.is_finite() {
            return Err(QueryError::NonFinitePoint { index: 0, point: p });
        }
        self.convexity().map_err(QueryError::NotConvex)?;
        // A convex solid lies in its box; deciding this first also keeps far
        // points (whose differences overflow) away from the predicates.
        if !self.bounds.contains(p) {
            return Ok(Containment::Outside);
        }
        let mut on_plane = false;
        for [a, b, c] in self.tris.iter().map(|t| t.corners()) {
            match orient3d(a, b, c, p) {
                Sign::Positive => return Ok(Containment::Outside),
                Sign::Zero => on_plane |= !collinear3d(a, b, c),
                Sign::Negative => {}
            }
        }
        Ok(if on_plane {
            Containment::OnBoundary
        } else {
            Containment::Inside
        })
    }
}
