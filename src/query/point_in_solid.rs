//! Point-in-polyhedron: the three methods behind one entry point, for one
//! point and for batches. Parity and winding read the exact `±x` ray of
//! [`x_ray`](super::x_ray); normals is
//! [`point_in_convex`](super::point_in_convex).

use glam::DVec3;
use rayon::prelude::*;

use super::x_direction::{RayChoice, XDirection};
use super::x_ray::XRay;
use super::{Accel, Containment, QueryError};

/// Batches at least this large are classified in grid-cell order.
const SORTED_BATCH: usize = 8192;

/// How to decide inside/outside.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Method {
    /// Parity of the crossings of a ray along `x` (the ray-crossing test),
    /// exact, ties broken by symbolic perturbation: the `+x` ray, or the `−x`
    /// ray when that meets fewer triangles, which has the same parity.
    /// Needs a closed surface.
    #[default]
    Parity,
    /// Inside iff strictly on the inner side of every face's plane (the
    /// normals test). Needs a convex solid; anything else is an error.
    Normals,
    /// The generalized winding number (sum of solid angles over `4π`),
    /// thresholded at ½; defined for open and overlapping input too. On a
    /// closed surface the winding number is the integer signed count of the
    /// `+x` ray's crossings, which is used instead: exact, and right also
    /// within rounding distance of the surface, where the solid-angle sum is
    /// not.
    Winding,
}

impl Accel {
    /// Classifies `p` by parity of the `+x` ray from it; see
    /// [`Accel::classify_with`].
    ///
    /// # Errors
    ///
    /// As for [`Accel::classify_with`].
    pub fn classify(&self, p: DVec3) -> Result<Containment, QueryError> {
        self.classify_with(p, Method::Parity)
    }

    /// Classifies `p` as inside, outside or on the boundary of the solid.
    ///
    /// **Parity** casts the ray `p + t·(1, 0, 0)`, `t > 0` (or its opposite,
    /// see below). A triangle is
    /// crossed when the projection of `p` onto the `yz` plane is inside the
    /// triangle's projection (three exact `orient2d`) and the triangle is in
    /// front of `p` (one exact `orient3d`). When the projected point lies
    /// exactly on a projected edge or vertex, the tie is broken by Simulation
    /// of Simplicity: `p`'s `(y, z)` is moved symbolically to
    /// `(y + ε, z + ε²)`, so `orient2d(a, b, p) = 0` becomes the sign of
    /// `a.z − b.z`, or of `b.y − a.y` when that is zero. The moved ray passes
    /// through no vertex and along no edge; each crossing is counted exactly
    /// once, a silhouette is crossed 0 or 2 times, and a ray in a face's plane
    /// crosses that face 0 times. If `p` lies on a triangle (exact
    /// `orient3d = 0` and inside the closed triangle) the answer is
    /// [`Containment::OnBoundary`]. The generic case pays only the filtered
    /// predicates; only triangles whose `yz` grid cell holds `p` and whose
    /// `x` extent reaches `p.x` from the ray's side are tested.
    ///
    /// On a closed surface the moved line crosses the triangles an even
    /// number of times in all, so the crossings behind `p` have the parity of
    /// those in front; parity therefore casts `p + t·(−1, 0, 0)` instead
    /// when fewer of the cell's triangles reach `p.x` from `−x`, with the
    /// same perturbation and the same answer, `OnBoundary` included (the
    /// proof is at `XDirection` in the source). The winding method always
    /// counts towards `+x`.
    ///
    /// **Normals** and **Winding** are described at [`Method`],
    /// [`Accel::classify_convex`] and [`Accel::winding_number`].
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFinitePoint`] for a NaN or infinite coordinate,
    /// [`QueryError::NotClosed`] for parity on an open surface,
    /// [`QueryError::NotConvex`] for normals on a non-convex solid.
    pub fn classify_with(&self, p: DVec3, method: Method) -> Result<Containment, QueryError> {
        if !p.is_finite() {
            return Err(QueryError::NonFinitePoint { index: 0, point: p });
        }
        match method {
            Method::Parity => {
                self.require_closed()?;
                let ray = self.x_ray_towards(p, RayChoice::Fewer);
                Ok(self.containment_from(p, method, ray))
            }
            Method::Normals => self.classify_convex(p),
            Method::Winding => Ok(self.containment_from(p, method, self.x_ray(p))),
        }
    }

    /// What `method` (parity or winding) answers for `p` from the ray cast
    /// from it.
    fn containment_from(&self, p: DVec3, method: Method, ray: XRay) -> Containment {
        let inside = |yes: bool| {
            if yes {
                Containment::Inside
            } else {
                Containment::Outside
            }
        };
        match ray {
            XRay::OnBoundary => Containment::OnBoundary,
            XRay::Winding(w) if method == Method::Parity => inside(w % 2 != 0),
            // Found by the queries fuzz check (fixtures/fuzz/queries/): 2e-69
            // outside a face and 5e-324 above another, the solid-angle sum
            // was near 1. On a closed surface the exact count decides.
            XRay::Winding(w) if self.is_closed() => inside(w > 0),
            XRay::Winding(_) => inside(self.winding_number_unchecked(p) > 0.5),
        }
    }

    /// Classifies every point, in order, on all cores (rayon).
    ///
    /// # Errors
    ///
    /// The first error by index: [`QueryError::NonFinitePoint`] carries the
    /// offending point's index; the method errors as for
    /// [`Accel::classify_with`].
    pub fn classify_batch(
        &self,
        points: &[DVec3],
        method: Method,
    ) -> Result<Vec<Containment>, QueryError> {
        if let Some(index) = points.par_iter().position_first(|p| !p.is_finite()) {
            return Err(QueryError::NonFinitePoint {
                index,
                point: points[index],
            });
        }
        match method {
            Method::Parity => self.require_closed()?,
            Method::Normals => self.convexity().map_err(QueryError::NotConvex)?,
            Method::Winding => {}
        }
        if method == Method::Normals || points.len() < SORTED_BATCH {
            return points
                .par_iter()
                .with_min_len(1024)
                .map(|&p| self.classify_with(p, method))
                .collect();
        }
        // Large batches: grouped by grid cell (see `point_batch`). Parity
        // casts each point's ray whichever way meets fewer triangles (the
        // same answer, see `XDirection`); the winding method needs the `+x`
        // count itself.
        let choice = match method {
            Method::Parity => RayChoice::Fewer,
            _ => RayChoice::Always(XDirection::Plus),
        };
        Ok(self.x_ray_batch(points, choice, |p, ray| {
            self.containment_from(p, method, ray)
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;
    use crate::query::stress_points::stress_points;

    #[test]
    fn cube_centre_faces_edges_vertices() {
        let accel = Accel::new(&builders::cube());
        let c = |x, y, z| accel.classify(DVec3::new(x, y, z)).unwrap();
        assert_eq!(c(0.0, 0.0, 0.0), Containment::Inside);
        assert_eq!(c(2.0, 0.0, 0.0), Containment::Outside);
        assert_eq!(c(-2.0, 0.0, 0.0), Containment::Outside);
        assert_eq!(c(1.0, 0.0, 0.0), Containment::OnBoundary);
        assert_eq!(c(0.0, 1.0, 0.0), Containment::OnBoundary);
        assert_eq!(c(1.0, 1.0, 0.0), Containment::OnBoundary);
        assert_eq!(c(1.0, 1.0, 1.0), Containment::OnBoundary);
        assert_eq!(c(0.0, 0.0, 1.0), Containment::OnBoundary);
        assert_eq!(c(-0.5, 1.0, -1.0), Containment::OnBoundary);
        // Rays along faces and edges from inside and outside.
        assert_eq!(c(0.0, 1.0, 1.0), Containment::OnBoundary);
        assert_eq!(c(-3.0, 1.0, 1.0), Containment::Outside);
        assert_eq!(c(-3.0, 1.0, 0.0), Containment::Outside);
        assert_eq!(c(-3.0, 0.0, 0.0), Containment::Outside);
        assert_eq!(c(0.5, 0.0, 0.0), Containment::Inside);
    }

    #[test]
    fn large_batches_match_single_queries_for_every_method() {
        // Above the grouped-batch threshold, on a closed solid and on an open
        // one (a sphere missing one face), where the winding method must not
        // take a parity shortcut.
        let closed = builders::sphere(24);
        let mut soup = builders::sphere_soup(24);
        soup.polygons.pop();
        let open = crate::mesh::Solid::try_from_soup(&soup).unwrap();
        for (solid, methods) in [
            (&closed, &[Method::Parity, Method::Winding][..]),
            (&open, &[Method::Winding][..]),
        ] {
            let accel = Accel::new(solid);
            let mut points = stress_points(solid, 3);
            while points.len() < SORTED_BATCH + 100 {
                let more = stress_points(solid, points.len() as u64);
                points.extend(more);
            }
            for &method in methods {
                let batch = accel.classify_batch(&points, method).unwrap();
                for (p, got) in points.iter().zip(&batch) {
                    assert_eq!(
                        accel.classify_with(*p, method).unwrap(),
                        *got,
                        "{p} {method:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn far_points_are_outside_by_every_method() {
        // Points far left of the box on lines through the solid: the exact
        // predicates would overflow on their coordinates (the no-panic
        // audit, after the queries fuzz check's far points).
        for solid in [builders::cube(), builders::l_prism()] {
            let accel = Accel::new(&solid);
            for x in [-f64::MAX, -1e300, -1e154, f64::MAX] {
                let p = DVec3::new(x, 0.5, 0.5);
                for method in [Method::Parity, Method::Winding, Method::Normals] {
                    match accel.classify_with(p, method) {
                        Ok(c) => assert_eq!(c, Containment::Outside, "{p} {method:?}"),
                        Err(e) => assert!(matches!(e, QueryError::NotConvex(_)), "{e}"),
                    }
                }
            }
        }
    }
}
