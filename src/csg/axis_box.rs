//! An axis-aligned box primitive.

use glam::DVec3;
use thiserror::Error;

use super::primitive::push_convex_interval;
use super::{
    CellRelation, Containment, Crossing, CrossingPlane, LocalPlane, Primitive, Stats, SurfaceId,
};
use crate::geom::{Aabb, Ray};

/// Why a box could not be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum AxisBoxError {
    /// `min < max` must hold in every coordinate (a flat box has no volume).
    #[error("box min {} is not below max {} in every coordinate", crate::geom::ReadableVec(*.min), crate::geom::ReadableVec(*.max))]
    Inverted {
        /// The corner given as `min`.
        min: DVec3,
        /// The corner given as `max`.
        max: DVec3,
    },
}

/// The closed axis-aligned box `[min, max]`.
///
/// # Exactness
///
/// Points are classified by exact coordinate comparisons. Along a ray, each
/// slab parameter `(c − E) / D` has the exact sign (a rounded difference or
/// quotient of doubles never changes sign), so "origin inside" and "behind
/// the eye" are exact, and the same face coordinate always yields the
/// bit-identical `t` — which is what lets touching boxes merge without a
/// phantom boundary. Which slab is entered last is decided on rounded
/// parameters. A ray lying exactly in a face plane is decided by
/// [`perturbed_side`](super::perturbed_side): in the box for a `min` face,
/// out of it for a `max` face.
///
/// # Invariants
///
/// `min < max` componentwise, all finite. Surfaces are numbered
/// `2·axis + (0 for the min face, 1 for the max face)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AxisBox {
    min: DVec3,
    max: DVec3,
}

impl AxisBox {
    /// The box `[min, max]`.
    ///
    /// # Errors
    ///
    /// [`AxisBoxError::Inverted`] unless `min < max` in every coordinate (NaN
    /// fails too); infinite corners are refused the same way.
    pub fn try_new(min: DVec3, max: DVec3) -> Result<AxisBox, AxisBoxError> {
        if min.is_finite() && max.is_finite() && min.cmplt(max).all() {
            Ok(AxisBox { min, max })
        } else {
            Err(AxisBoxError::Inverted { min, max })
        }
    }

    /// The smallest corner.
    #[must_use]
    pub fn min(&self) -> DVec3 {
        self.min
    }

    /// The largest corner.
    #[must_use]
    pub fn max(&self) -> DVec3 {
        self.max
    }
}

/// The interval of `t` where a ray is inside a closed box, with the surfaces
/// at its ends, or `None` when the ray misses it or only touches it.
/// `stats` counts perturbation tie-breaks.
pub(crate) fn slab_interval(
    min: DVec3,
    max: DVec3,
    ray: &Ray,
    mut stats: Option<&mut Stats>,
) -> Option<((f64, SurfaceId), (f64, SurfaceId))> {
    let (mut near, mut near_surface) = (f64::NEG_INFINITY, 0);
    let (mut far, mut far_surface) = (f64::INFINITY, 0);
    for axis in 0..3 {
        let (e, d) = (ray.origin[axis], ray.direction[axis]);
        let (lo, hi) = (min[axis], max[axis]);
        if d == 0.0 {
            if e < lo || e > hi {
                return None;
            }
            if e == lo || e == hi {
                // The ray lies in a face plane: perturb the origin by
                // ε (1, ε, ε²), which moves it to +axis: into the box at the
                // min face, out of it at the max face (an infinite slab has
                // no face, so nothing to break).
                if let Some(s) = stats.as_deref_mut() {
                    s.tie_breaks += 1;
                }
                if e == hi {
                    return None;
                }
            }
            continue;
        }
        let t_lo = (lo - e) / d;
        let t_hi = (hi - e) / d;
        let axis_id = 2 * axis as SurfaceId;
        let ((t0, s0), (t1, s1)) = if d > 0.0 {
            ((t_lo, axis_id), (t_hi, axis_id + 1))
        } else {
            ((t_hi, axis_id + 1), (t_lo, axis_id))
        };
        if t0 > near {
            (near, near_surface) = (t0, s0);
        }
        if t1 < far {
            (far, far_surface) = (t1, s1);
        }
    }
    (near < far).then_some(((near, near_surface), (far, far_surface)))
}

impl Primitive for AxisBox {
    fn intersect_ray(&self, ray: &Ray, crossings: &mut Vec<Crossing>, stats: &mut Stats) -> bool {
        let Some(((near, near_surface), (far, far_surface))) =
            slab_interval(self.min, self.max, ray, Some(stats))
        else {
            return false;
        };
        push_convex_interval(crossings, (near, near_surface), (far, far_surface))
    }

    fn classify_point(&self, p: DVec3) -> Containment {
        if p.cmplt(self.min).any() || p.cmpgt(self.max).any() {
            Containment::Outside
        } else if p.cmpgt(self.min).all() && p.cmplt(self.max).all() {
            Containment::Inside
        } else {
            Containment::OnBoundary
        }
    }

    fn boundary_normal(&self, p: DVec3) -> Option<DVec3> {
        if self.classify_point(p) != Containment::OnBoundary {
            return None;
        }
        let mut normal = None;
        for axis in 0..3 {
            let sign = if p[axis] == self.min[axis] {
                -1.0
            } else if p[axis] == self.max[axis] {
                1.0
            } else {
                continue;
            };
            if normal.is_some() {
                return None; // an edge or a corner
            }
            let mut n = DVec3::ZERO;
            n[axis] = sign;
            normal = Some(n);
        }
        normal
    }

    /// Surface `2 axis` is the face at `min[axis]`, `2 axis + 1` the one at
    /// `max[axis]`.
    fn crossing_plane(&self, surface: SurfaceId) -> Option<CrossingPlane> {
        let axis = (surface / 2) as usize;
        (axis < 3).then(|| CrossingPlane::Axis {
            axis,
            value: if surface.is_multiple_of(2) {
                self.min[axis]
            } else {
                self.max[axis]
            },
        })
    }

    fn planes_through(&self, p: DVec3, planes: &mut Vec<LocalPlane>) -> bool {
        for axis in 0..3 {
            if p[axis] == self.min[axis] || p[axis] == self.max[axis] {
                let mut n = DVec3::ZERO;
                n[axis] = 1.0;
                planes.extend(LocalPlane::from_normal(n));
            }
        }
        true
    }

    /// Inside along `d` when `d` points into the box across every face
    /// through `p`.
    fn inside_along(&self, p: DVec3, d: DVec3) -> Option<bool> {
        Some((0..3).all(|axis| {
            (p[axis] != self.min[axis] || d[axis] > 0.0)
                && (p[axis] != self.max[axis] || d[axis] < 0.0)
        }))
    }

    fn normal(&self, _p: DVec3, surface: SurfaceId) -> DVec3 {
        let mut n = DVec3::ZERO;
        n[(surface / 2) as usize % 3] = if surface.is_multiple_of(2) { -1.0 } else { 1.0 };
        n
    }

    fn bounds(&self) -> Aabb {
        Aabb {
            min: self.min,
            max: self.max,
        }
    }

    /// Exact (comparisons of input coordinates): a closed cell that meets
    /// the closed box without lying in its open interior is connected, so
    /// it meets the boundary.
    fn cell_relation(&self, cell: &Aabb) -> CellRelation {
        if cell.max.cmplt(self.min).any() || cell.min.cmpgt(self.max).any() {
            CellRelation::Outside
        } else if cell.min.cmpgt(self.min).all() && cell.max.cmplt(self.max).all() {
            CellRelation::Inside
        } else {
            CellRelation::Meets
        }
    }

    fn exact_volume(&self) -> Option<f64> {
        let s = self.max - self.min;
        Some(s.x * s.y * s.z)
    }

    fn kind(&self) -> &'static str {
        "box"
    }

    fn is_polyhedral(&self) -> bool {
        true
    }

    fn tessellate(
        &self,
        _tolerance: f64,
        _clip: &Aabb,
    ) -> Result<crate::mesh::Solid, super::TessellateError> {
        crate::mesh::builders::cuboid(self.min(), self.max())
            .map_err(|e| super::TessellateError::Build(e.to_string()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> AxisBox {
        AxisBox::try_new(DVec3::ZERO, DVec3::ONE).unwrap()
    }

    fn cast(b: &AxisBox, e: DVec3, d: DVec3) -> (bool, Vec<f64>, u64) {
        let mut out = Vec::new();
        let mut stats = Stats::default();
        let inside = b.intersect_ray(&Ray::new(e, d), &mut out, &mut stats);
        (inside, out.iter().map(|c| c.t).collect(), stats.tie_breaks)
    }

    #[test]
    fn rays_through_and_from_inside() {
        let b = unit();
        assert_eq!(
            cast(&b, DVec3::new(-1., 0.5, 0.5), DVec3::X),
            (false, vec![1., 2.], 0)
        );
        assert_eq!(
            cast(&b, DVec3::new(0.5, 0.5, 0.5), DVec3::X),
            (true, vec![0.5], 0)
        );
        assert_eq!(
            cast(&b, DVec3::new(2., 0.5, 0.5), DVec3::X),
            (false, vec![], 0)
        );
        // Origin on the min face heading in: inside, one crossing.
        assert_eq!(
            cast(&b, DVec3::new(0., 0.5, 0.5), DVec3::X),
            (true, vec![1.], 0)
        );
        // Origin on the max face heading out: outside, nothing.
        assert_eq!(
            cast(&b, DVec3::new(1., 0.5, 0.5), DVec3::X),
            (false, vec![], 0)
        );
        // Through an edge only (touching): no zero-length span.
        assert_eq!(
            cast(&b, DVec3::new(-1., 0.5, 0.), DVec3::new(1., 0., 1.)),
            (false, vec![], 0)
        );
        // The same in the face plane y = 0: a perturbation, still a touch.
        assert_eq!(
            cast(&b, DVec3::new(-1., 0., 1.), DVec3::new(1., 0., -1.)),
            (false, vec![], 1)
        );
    }

    #[test]
    fn grazing_rays_are_perturbed() {
        let b = unit();
        // In the plane x = 0 (min face): inside by perturbation.
        assert_eq!(
            cast(&b, DVec3::new(0., -1., 0.5), DVec3::Y),
            (false, vec![1., 2.], 1)
        );
        // In the plane x = 1 (max face): outside.
        assert_eq!(
            cast(&b, DVec3::new(1., -1., 0.5), DVec3::Y),
            (false, vec![], 1)
        );
    }

    #[test]
    fn points_and_boundary_normals() {
        let b = unit();
        assert_eq!(b.classify_point(DVec3::splat(0.5)), Containment::Inside);
        assert_eq!(
            b.classify_point(DVec3::new(1., 0.5, 0.5)),
            Containment::OnBoundary
        );
        assert_eq!(
            b.classify_point(DVec3::new(1.0f64.next_up(), 0.5, 0.5)),
            Containment::Outside
        );
        assert_eq!(b.boundary_normal(DVec3::new(1., 0.5, 0.5)), Some(DVec3::X));
        assert_eq!(b.boundary_normal(DVec3::new(1., 1., 0.5)), None);
        assert_eq!(b.normal(DVec3::ZERO, 4), -DVec3::Z);
        assert!(AxisBox::try_new(DVec3::ONE, DVec3::ZERO).is_err());
        assert!(AxisBox::try_new(DVec3::ZERO, DVec3::new(1., 0., 1.)).is_err());
    }
}
