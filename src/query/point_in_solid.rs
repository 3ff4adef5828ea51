//! Point-in-polyhedron by parity of a `+x` ray, exact, with the three
//! methods behind one entry point.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use crate::geom::polygon::coplanar_point_in_closed_triangle;
use crate::geom::{Sign, orient2d, orient3d};

use super::accel::YzTri;
use super::{Accel, Containment, QueryError};

/// Batches at least this large are classified in grid-cell order.
const SORTED_BATCH: usize = 8192;

/// How to decide inside/outside.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Method {
    /// Parity of the crossings of a `+x` ray (the seed's method 1), exact,
    /// ties broken by symbolic perturbation. Needs a closed surface.
    #[default]
    Parity,
    /// Inside iff strictly on the inner side of every face (the seed's method
    /// 2). Needs a convex solid; anything else is an error.
    Normals,
    /// The generalized winding number (sum of solid angles over `4π`),
    /// thresholded at ½; defined for open and overlapping input too. On a
    /// closed surface the winding number is the integer signed count of the
    /// `+x` ray's crossings, which is used instead: exact, and right also
    /// within rounding distance of the surface, where the solid-angle sum is
    /// not.
    Winding,
}

/// What the `+x` ray from a point found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum XRay {
    /// The point lies exactly on a triangle.
    OnBoundary,
    /// The signed number of crossings in front of the point: `+1` for each
    /// triangle whose normal has positive `x` (the ray leaves through it),
    /// `−1` for each it enters through. For a closed outward-oriented
    /// surface this is the winding number of the surface around the point.
    Winding(i32),
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
    /// **Parity** casts the ray `p + t·(1, 0, 0)`, `t > 0`. A triangle is
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
    /// predicates; only triangles whose `yz` grid cell holds `p` are tested.
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
                Ok(match self.x_ray(p) {
                    XRay::OnBoundary => Containment::OnBoundary,
                    XRay::Winding(w) if w % 2 != 0 => Containment::Inside,
                    XRay::Winding(_) => Containment::Outside,
                })
            }
            Method::Normals => self.classify_convex(p),
            Method::Winding => Ok(match self.x_ray(p) {
                XRay::OnBoundary => Containment::OnBoundary,
                // Found by the queries fuzz check (fixtures/fuzz/queries/): 2e-69 outside a
                // face and 5e-324 above another, the solid-angle sum was
                // near 1.
                XRay::Winding(w) if self.is_closed() => {
                    if w > 0 {
                        Containment::Inside
                    } else {
                        Containment::Outside
                    }
                }
                XRay::Winding(_) => {
                    if self.winding_number_unchecked(p) > 0.5 {
                        Containment::Inside
                    } else {
                        Containment::Outside
                    }
                }
            }),
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
        if let Some(index) = points.iter().position(|p| !p.is_finite()) {
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
        // Large batches: visit the points grouped by grid cell (a counting
        // sort, O(n + cells)) so that each cell's triangles are fetched from
        // memory once per group rather than once per point; answers are
        // written back in input order.
        let g = self.grid();
        let cells: Vec<u32> = points
            .par_iter()
            .with_min_len(4096)
            .map(|p| g.cell_index(p.y, p.z) as u32)
            .collect();
        let mut start = vec![0u32; g.ny * g.nz + 1];
        for &c in &cells {
            start[c as usize + 1] += 1;
        }
        for i in 0..g.ny * g.nz {
            start[i + 1] += start[i];
        }
        let mut sorted: Vec<(DVec3, u32)> = vec![(DVec3::ZERO, 0); points.len()];
        for (i, (&c, &p)) in cells.iter().zip(points).enumerate() {
            let slot = &mut start[c as usize];
            sorted[*slot as usize] = (p, i as u32);
            *slot += 1;
        }
        let answers: Vec<Containment> = sorted
            .par_iter()
            .with_min_len(4096)
            .map(|&(p, _)| self.classify_with(p, method))
            .collect::<Result<_, _>>()?;
        let mut out = vec![Containment::Outside; points.len()];
        for (&(_, i), a) in sorted.iter().zip(answers) {
            out[i as usize] = a;
        }
        Ok(out)
    }

    /// The `+x` ray from `p`: on the boundary, or the signed crossing count.
    pub(super) fn x_ray(&self, p: DVec3) -> XRay {
        let g = self.grid();
        // Outside the projected box nothing can be crossed or touched.
        if !(p.y >= g.y0 && p.y <= g.y1 && p.z >= g.z0 && p.z <= g.z1) || p.x > self.bounds.max.x {
            return XRay::Winding(0);
        }
        // Left of the box every triangle the line meets is in front of `p`,
        // wherever `p` is: move it next to the box, so that the exact
        // predicates see coordinates of the model's magnitude (a point at
        // `x = −1e308` overflows their arithmetic) and decide the same.
        let beside = self.bounds.min.x - (1.0 + self.bounds.min.x.abs());
        let p = DVec3::new(p.x.max(beside), p.y, p.z);
        let q = DVec2::new(p.y, p.z);
        let mut winding = 0i32;
        for e in g.cell(p.y, p.z) {
            if f64::from(e.max_x) < p.x {
                continue;
            }
            let t = &self.tris[e.record as usize];
            match cross_x(t, q) {
                Cross::No => {}
                Cross::Degenerate => {
                    let [a, b, c] = t.corners();
                    if orient3d(a, b, c, p) == Sign::Zero
                        && coplanar_point_in_closed_triangle(a, b, c, p)
                    {
                        return XRay::OnBoundary;
                    }
                }
                Cross::Closed(perturbed_inside) => {
                    let [a, b, c] = t.corners();
                    let side = orient3d(a, b, c, p);
                    if side == Sign::Zero {
                        return XRay::OnBoundary;
                    }
                    let sigma = Sign::of(f64::from(t.sigma));
                    if perturbed_inside && side == -sigma {
                        winding += i32::from(t.sigma);
                    }
                }
            }
        }
        XRay::Winding(winding)
    }
}

/// How the `+x` line through a point meets a triangle's `yz` projection.
enum Cross {
    /// The projected point is outside the closed projected triangle.
    No,
    /// The projection has zero area: only an on-boundary check applies.
    Degenerate,
    /// The projected point is in the closed projected triangle; the flag says
    /// whether the symbolically moved point is inside.
    Closed(bool),
}

#[inline]
fn cross_x(t: &YzTri, q: DVec2) -> Cross {
    if t.sigma == 0 {
        let (ymin, ymax) = (
            t.y[0].min(t.y[1]).min(t.y[2]),
            t.y[0].max(t.y[1]).max(t.y[2]),
        );
        let (zmin, zmax) = (
            t.z[0].min(t.z[1]).min(t.z[2]),
            t.z[0].max(t.z[1]).max(t.z[2]),
        );
        return if q.x >= ymin && q.x <= ymax && q.y >= zmin && q.y <= zmax {
            Cross::Degenerate
        } else {
            Cross::No
        };
    }
    let sigma = Sign::of(f64::from(t.sigma));
    let a = DVec2::new(t.y[0], t.z[0]);
    let b = DVec2::new(t.y[1], t.z[1]);
    let c = DVec2::new(t.y[2], t.z[2]);
    let s0 = orient2d(a, b, q);
    if s0 == -sigma {
        return Cross::No;
    }
    let s1 = orient2d(b, c, q);
    if s1 == -sigma {
        return Cross::No;
    }
    let s2 = orient2d(c, a, q);
    if s2 == -sigma {
        return Cross::No;
    }
    if s0 != Sign::Zero && s1 != Sign::Zero && s2 != Sign::Zero {
        return Cross::Closed(true);
    }
    let inside = [(s0, a, b), (s1, b, c), (s2, c, a)]
        .iter()
        .all(|&(s, u, v)| s != Sign::Zero || perturbed_orient(u, v) == sigma);
    Cross::Closed(inside)
}

/// `orient2d(u, v, q')` for `q' = q + (ε, ε²)` when `orient2d(u, v, q) = 0`:
/// the sign of `u.y − v.y`, or of `v.x − u.x` when that is zero (2-D names:
/// `x` is the 3-D `y`, `y` the 3-D `z`).
#[inline]
fn perturbed_orient(u: DVec2, v: DVec2) -> Sign {
    crate::geom::count_tie_break();
    match Sign::of(u.y - v.y) {
        Sign::Zero => Sign::of(v.x - u.x),
        s => s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

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
