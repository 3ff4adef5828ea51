//! A capped cylinder primitive.

use glam::DVec3;
use thiserror::Error;

use super::cell_relation::{CELL_ROUNDING, CELL_UNDERFLOW, centre, corners};
use super::primitive::push_convex_interval;
use super::sphere::quadratic_roots;
use super::{CellRelation, Containment, Crossing, Primitive, Stats, SurfaceId};
use crate::geom::{Aabb, Ray, Readable, ReadableVec};

/// Why a cylinder could not be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CylinderError {
    /// The axis must be a non-zero finite vector, the radius positive and
    /// finite, the base finite.
    #[error("cylinder with base {}, axis {} and radius {} is not a solid", crate::geom::ReadableVec(*.base), crate::geom::ReadableVec(*.axis), crate::geom::Readable(*.radius))]
    Invalid {
        /// The base centre given.
        base: DVec3,
        /// The axis given (base to top).
        axis: DVec3,
        /// The radius given.
        radius: f64,
    },
    /// The cylinder is below `f64`'s resolution where it sits: its rounded
    /// box is flat along an axis (a unit cylinder at 1e17, where
    /// neighbouring `f64` are 16 apart).
    #[error(
        "cylinder with base {}, axis {} and radius {} collapses below f64's resolution there (its box is flat along {})",
        ReadableVec(*.base),
        ReadableVec(*.axis),
        Readable(*.radius),
        ["x", "y", "z"][*.flat_axis]
    )]
    Collapsed {
        /// The base centre given.
        base: DVec3,
        /// The axis given (base to top).
        axis: DVec3,
        /// The radius given.
        radius: f64,
        /// The axis along which the box is flat (0, 1, 2 for x, y, z).
        flat_axis: usize,
    },
}

/// Surface of the curved side.
const SIDE: SurfaceId = 0;
/// Surface of the base cap.
const BASE: SurfaceId = 1;
/// Surface of the top cap.
const TOP: SurfaceId = 2;

/// The closed capped cylinder of `radius` around the segment from `base` to
/// `base + axis`.
///
/// # Exactness
///
/// None: a convenience for scenes. The crossings are the intersection of
/// the quadratic's interval (side) with the slab between the caps, all in
/// rounded arithmetic; points are classified by rounded distances. Surfaces:
/// 0 side, 1 base cap, 2 top cap.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cylinder {
    base: DVec3,
    axis: DVec3,
    radius: f64,
    /// `axis / |axis|`.
    unit_axis: DVec3,
    /// `|axis|`.
    height: f64,
}

impl Cylinder {
    /// The cylinder from `base` along `axis` (base to top) with `radius`.
    ///
    /// # Errors
    ///
    /// [`CylinderError::Invalid`] for a zero or non-finite axis, a radius
    /// that is not positive and finite, or a non-finite base.
    pub fn try_new(base: DVec3, axis: DVec3, radius: f64) -> Result<Cylinder, CylinderError> {
        let invalid = CylinderError::Invalid { base, axis, radius };
        if !base.is_finite() || !radius.is_finite() || radius <= 0.0 {
            return Err(invalid);
        }
        let height = axis.length();
        let unit_axis = axis.try_normalize().ok_or(invalid.clone())?;
        if !height.is_finite() || height == 0.0 {
            return Err(invalid);
        }
        let cylinder = Cylinder {
            base,
            axis,
            radius,
            unit_axis,
            height,
        };
        let (min, max) = cylinder.rounded_box();
        if let Some(flat_axis) = (0..3).find(|&k| min[k] >= max[k]) {
            return Err(CylinderError::Collapsed {
                base,
                axis,
                radius,
                flat_axis,
            });
        }
        Ok(cylinder)
    }

    /// The corners of the box of the two cap disks, rounded to nearest
    /// (not padded: [`Primitive::bounds`] pads it).
    fn rounded_box(&self) -> (DVec3, DVec3) {
        let u = self.unit_axis;
        let extent = DVec3::new(
            (1.0 - u.x * u.x).max(0.0).sqrt(),
            (1.0 - u.y * u.y).max(0.0).sqrt(),
            (1.0 - u.z * u.z).max(0.0).sqrt(),
        ) * self.radius;
        let top = self.base + self.axis;
        (
            (self.base - extent).min(top - extent),
            (self.base + extent).max(top + extent),
        )
    }

    /// `(along the axis, squared distance from the axis)` of `p`.
    fn local(&self, p: DVec3) -> (f64, f64) {
        let v = p - self.base;
        let s = v.dot(self.unit_axis);
        (s, (v - self.unit_axis * s).length_squared())
    }
}

impl Primitive for Cylinder {
    fn intersect_ray(&self, ray: &Ray, crossings: &mut Vec<Crossing>, _stats: &mut Stats) -> bool {
        let u = self.unit_axis;
        let e = ray.origin - self.base;
        let (e_s, d_s) = (e.dot(u), ray.direction.dot(u));
        let e_r = e - u * e_s;
        let d_r = ray.direction - u * d_s;
        // The slab between the caps.
        let (mut near, mut near_surface, mut far, mut far_surface);
        if d_s == 0.0 {
            if !(e_s > 0.0 && e_s < self.height) {
                return false;
            }
            (near, near_surface) = (f64::NEG_INFINITY, BASE);
            (far, far_surface) = (f64::INFINITY, TOP);
        } else {
            let t_base = -e_s / d_s;
            let t_top = (self.height - e_s) / d_s;
            if d_s > 0.0 {
                (near, near_surface, far, far_surface) = (t_base, BASE, t_top, TOP);
            } else {
                (near, near_surface, far, far_surface) = (t_top, TOP, t_base, BASE);
            }
        }
        // The infinite cylinder.
        let a = d_r.length_squared();
        let c = e_r.length_squared() - self.radius * self.radius;
        if a == 0.0 {
            if c >= 0.0 {
                return false;
            }
        } else {
            let Some((t1, t2)) = quadratic_roots(a, e_r.dot(d_r), c) else {
                return false;
            };
            if t1 > near {
                (near, near_surface) = (t1, SIDE);
            }
            if t2 < far {
                (far, far_surface) = (t2, SIDE);
            }
        }
        if near >= far {
            return false;
        }
        push_convex_interval(crossings, (near, near_surface), (far, far_surface))
    }

    fn classify_point(&self, p: DVec3) -> Containment {
        let (s, r2) = self.local(p);
        let rr = self.radius * self.radius;
        if s < 0.0 || s > self.height || r2 > rr {
            Containment::Outside
        } else if s > 0.0 && s < self.height && r2 < rr {
            Containment::Inside
        } else {
            Containment::OnBoundary
        }
    }

    fn boundary_normal(&self, p: DVec3) -> Option<DVec3> {
        if self.classify_point(p) != Containment::OnBoundary {
            return None;
        }
        let (s, r2) = self.local(p);
        let on_side = r2 == self.radius * self.radius;
        let on_cap = s == 0.0 || s == self.height;
        match (on_side, on_cap) {
            (true, false) => Some(self.normal(p, SIDE)),
            (false, true) if s == 0.0 => Some(-self.unit_axis),
            (false, true) => Some(self.unit_axis),
            _ => None,
        }
    }

    fn normal(&self, p: DVec3, surface: SurfaceId) -> DVec3 {
        match surface {
            BASE => -self.unit_axis,
            TOP => self.unit_axis,
            _ => {
                let v = p - self.base;
                v - self.unit_axis * v.dot(self.unit_axis)
            }
        }
    }

    fn bounds(&self) -> Aabb {
        let (min, max) = self.rounded_box();
        // Rounded outward by a bound on the rounding of the extents, so
        // that the box holds the solid.
        let pad = (min.abs().max(max.abs()) + DVec3::splat(self.radius)) * CELL_ROUNDING
            + DVec3::splat(CELL_UNDERFLOW);
        Aabb {
            min: min - pad,
            max: max + pad,
        }
    }

    /// Conservative: `Inside` when every corner is inside beyond the
    /// rounding bound (32 ε of the magnitudes; the solid is convex); `Outside`
    /// when every corner is beyond one cap plane, or when the cell lies
    /// beyond the side along the direction from the axis to the cell's
    /// centre (a separating axis); else `Meets`. Cells near an edge of
    /// the cylinder may be `Meets` without touching it.
    fn cell_relation(&self, cell: &Aabb) -> CellRelation {
        let (u, h, r) = (self.unit_axis, self.height, self.radius);
        let rr = r * r;
        let (mut all_in, mut below, mut above) = (true, true, true);
        for p in corners(cell) {
            let v = p - self.base;
            let s = v.dot(u);
            let r2 = (v - u * s).length_squared();
            let margin_s = CELL_ROUNDING * (v.abs().dot(u.abs()) + h) + CELL_UNDERFLOW;
            let margin_r = CELL_ROUNDING * (v.length_squared() + rr) + CELL_UNDERFLOW;
            all_in &= s > margin_s && s < h - margin_s && r2 < rr - margin_r;
            below &= s < -margin_s;
            above &= s > h + margin_s;
        }
        if all_in {
            return CellRelation::Inside;
        }
        if below || above {
            return CellRelation::Outside;
        }
        let v = centre(cell) - self.base;
        let w = v - u * v.dot(u);
        let length = w.length();
        if length > 0.0 {
            let d = w / length;
            let half = (cell.max - cell.min) * 0.5;
            let reach = half.dot(d.abs());
            let cell_low = v.dot(d) - reach;
            let cylinder_high = (h * u.dot(d)).max(0.0) + r * d.length();
            let margin = CELL_ROUNDING * (v.abs().dot(d.abs()) + reach + h + r) + CELL_UNDERFLOW;
            if cell_low > cylinder_high + margin {
                return CellRelation::Outside;
            }
        }
        CellRelation::Meets
    }

    fn exact_volume(&self) -> Option<f64> {
        Some(std::f64::consts::PI * self.radius * self.radius * self.height)
    }

    fn kind(&self) -> &'static str {
        "cylinder"
    }

    fn tessellate(
        &self,
        tolerance: f64,
        _clip: &Aabb,
    ) -> Result<crate::mesh::Solid, super::TessellateError> {
        super::tessellate::cylinder(self.base, self.axis, self.radius, tolerance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cast(c: &Cylinder, e: DVec3, d: DVec3) -> (bool, Vec<(f64, SurfaceId)>) {
        let mut out = Vec::new();
        let inside = c.intersect_ray(&Ray::new(e, d), &mut out, &mut Stats::default());
        (inside, out.iter().map(|c| (c.t, c.surface)).collect())
    }

    #[test]
    fn side_and_cap_crossings() {
        // Radius 1 around the z axis from z = 0 to z = 4.
        let c = Cylinder::try_new(DVec3::ZERO, DVec3::new(0., 0., 4.), 1.0).unwrap();
        assert_eq!(
            cast(&c, DVec3::new(-3., 0., 2.), DVec3::X),
            (false, vec![(2.0, SIDE), (4.0, SIDE)])
        );
        assert_eq!(
            cast(&c, DVec3::new(0., 0., -1.), DVec3::Z),
            (false, vec![(1.0, BASE), (5.0, TOP)])
        );
        assert_eq!(
            cast(&c, DVec3::new(0., 0., 1.), DVec3::Z),
            (true, vec![(3.0, TOP)])
        );
        // Parallel to the axis outside the radius.
        assert_eq!(cast(&c, DVec3::new(2., 0., -1.), DVec3::Z), (false, vec![]));
        // Passing above the top cap.
        assert_eq!(cast(&c, DVec3::new(-3., 0., 5.), DVec3::X), (false, vec![]));
        assert_eq!(
            c.classify_point(DVec3::new(0., 0., 4.)),
            Containment::OnBoundary
        );
        assert_eq!(c.boundary_normal(DVec3::new(0., 0., 4.)), Some(DVec3::Z));
        assert_eq!(
            c.classify_point(DVec3::new(0.5, 0., 2.)),
            Containment::Inside
        );
        // Rounded outward, by a bound on the rounding.
        let b = c.bounds();
        let (lo, hi) = (DVec3::new(-1., -1., 0.), DVec3::new(1., 1., 4.));
        assert!(b.min.cmple(lo).all() && b.max.cmpge(hi).all(), "{b:?}");
        assert!((b.min - lo).abs().max_element() < 1e-12, "{b:?}");
        assert!((b.max - hi).abs().max_element() < 1e-12, "{b:?}");
        assert!(Cylinder::try_new(DVec3::ZERO, DVec3::ZERO, 1.0).is_err());
    }
}
