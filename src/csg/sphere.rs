//! A sphere primitive.

use glam::DVec3;
use thiserror::Error;

use super::cell_relation::{CELL_ROUNDING, CELL_UNDERFLOW};
use super::{CellRelation, Containment, Crossing, Primitive, Stats, SurfaceId};
use crate::geom::{Aabb, Ray, Readable, ReadableVec};

/// Why a sphere could not be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum SphereError {
    /// The radius must be positive and finite, the centre finite.
    #[error("sphere with centre {} and radius {} is not a solid", ReadableVec(*.center), Readable(*.radius))]
    Invalid {
        /// The centre given.
        center: DVec3,
        /// The radius given.
        radius: f64,
    },
    /// The ball is below `f64`'s resolution where it sits: its centre
    /// plus or minus its radius rounds back to the centre along some axis
    /// (a unit sphere at 1e17, where neighbouring `f64` are 16 apart), so
    /// no ray or point there could tell its inside from its outside.
    #[error(
        "sphere of radius {} at {} collapses below f64's resolution there (centre ± radius rounds to the centre)",
        Readable(*.radius),
        ReadableVec(*.center)
    )]
    Collapsed {
        /// The centre given.
        center: DVec3,
        /// The radius given.
        radius: f64,
    },
}

/// The closed ball `|P − C| ≤ r`.
///
/// # Exactness
///
/// None: a convenience for scenes. Crossings are roots of a quadratic
/// (`t = (−b ± √(b² − a c)) / a`, in the cancellation-free form) and points
/// are classified by the rounded `|P − C|² − r²`; both are floating-point
/// constructions. A tangent ray (`b² − a c ≤ 0` as computed) crosses nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sphere {
    center: DVec3,
    radius: f64,
}

impl Sphere {
    /// The ball of `radius` around `center`.
    ///
    /// # Errors
    ///
    /// [`SphereError::Invalid`] for a radius that is not positive and finite
    /// or a non-finite centre; [`SphereError::Collapsed`] for a ball below
    /// `f64`'s resolution at its centre.
    pub fn try_new(center: DVec3, radius: f64) -> Result<Sphere, SphereError> {
        if !(center.is_finite() && radius.is_finite() && radius > 0.0) {
            return Err(SphereError::Invalid { center, radius });
        }
        let r = DVec3::splat(radius);
        if !((center - r).cmplt(center).all() && center.cmplt(center + r).all()) {
            return Err(SphereError::Collapsed { center, radius });
        }
        Ok(Sphere { center, radius })
    }
}

/// The roots `t₁ ≤ t₂` of `a t² + 2 b t + c = 0` (`a > 0`), or `None` when
/// the discriminant is not positive.
pub(crate) fn quadratic_roots(a: f64, b: f64, c: f64) -> Option<(f64, f64)> {
    let discriminant = b * b - a * c;
    if discriminant.is_nan() || discriminant <= 0.0 {
        return None;
    }
    let root = discriminant.sqrt();
    let q = -(b + b.signum() * root);
    let (t1, t2) = (q / a, c / q);
    Some((t1.min(t2), t1.max(t2)))
}

impl Primitive for Sphere {
    fn intersect_ray(&self, ray: &Ray, crossings: &mut Vec<Crossing>, _stats: &mut Stats) -> bool {
        let oc = ray.origin - self.center;
        let a = ray.direction.length_squared();
        let b = oc.dot(ray.direction);
        let c = oc.length_squared() - self.radius * self.radius;
        let roots = quadratic_roots(a, b, c);
        let inside = c < 0.0 || (c == 0.0 && b < 0.0);
        match roots {
            Some((_, t2)) if inside => {
                crossings.push(Crossing {
                    t: t2.max(f64::MIN_POSITIVE),
                    surface: 0,
                });
            }
            Some((t1, t2)) if t1 > 0.0 => {
                crossings.push(Crossing { t: t1, surface: 0 });
                crossings.push(Crossing { t: t2, surface: 0 });
            }
            _ => {}
        }
        inside
    }

    fn classify_point(&self, p: DVec3) -> Containment {
        let f = (p - self.center).length_squared() - self.radius * self.radius;
        if f < 0.0 {
            Containment::Inside
        } else if f > 0.0 {
            Containment::Outside
        } else {
            Containment::OnBoundary
        }
    }

    fn boundary_normal(&self, p: DVec3) -> Option<DVec3> {
        (self.classify_point(p) == Containment::OnBoundary).then_some(p - self.center)
    }

    fn normal(&self, p: DVec3, _surface: SurfaceId) -> DVec3 {
        p - self.center
    }

    fn bounds(&self) -> Aabb {
        let r = DVec3::splat(self.radius);
        // Rounded outward, so that the box holds the ball.
        let (min, max) = (self.center - r, self.center + r);
        Aabb {
            min: DVec3::new(min.x.next_down(), min.y.next_down(), min.z.next_down()),
            max: DVec3::new(max.x.next_up(), max.y.next_up(), max.z.next_up()),
        }
    }

    /// Conservative: the squared distances from the centre to the nearest
    /// point of the cell and to its farthest corner, compared with `r²`
    /// beyond their rounding bound (32 ε of the magnitudes); a cell within that
    /// bound of the sphere is `Meets`.
    fn cell_relation(&self, cell: &Aabb) -> CellRelation {
        let c = self.center;
        let near = c.clamp(cell.min, cell.max) - c;
        let far = (cell.min - c).abs().max((cell.max - c).abs());
        let (near2, far2) = (near.length_squared(), far.length_squared());
        let rr = self.radius * self.radius;
        let margin = CELL_ROUNDING * (far2 + rr) + CELL_UNDERFLOW;
        if near2 > rr + margin {
            CellRelation::Outside
        } else if far2 < rr - margin {
            CellRelation::Inside
        } else {
            CellRelation::Meets
        }
    }

    fn exact_volume(&self) -> Option<f64> {
        Some(4.0 / 3.0 * std::f64::consts::PI * self.radius.powi(3))
    }

    fn kind(&self) -> &'static str {
        "sphere"
    }

    fn tessellate(
        &self,
        tolerance: f64,
        _clip: &Aabb,
    ) -> Result<crate::mesh::Solid, super::TessellateError> {
        super::tessellate::sphere(self.center, self.radius, tolerance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossings_from_outside_inside_and_tangent() {
        let s = Sphere::try_new(DVec3::ZERO, 2.0).unwrap();
        let mut stats = Stats::default();
        let mut out = Vec::new();
        let ray = Ray::new(DVec3::new(-5., 0., 0.), DVec3::X);
        assert!(!s.intersect_ray(&ray, &mut out, &mut stats));
        assert_eq!(out.iter().map(|c| c.t).collect::<Vec<_>>(), [3.0, 7.0]);
        out.clear();
        assert!(s.intersect_ray(&Ray::new(DVec3::ZERO, DVec3::Y), &mut out, &mut stats));
        assert_eq!(out.iter().map(|c| c.t).collect::<Vec<_>>(), [2.0]);
        out.clear();
        let tangent = Ray::new(DVec3::new(-5., 2., 0.), DVec3::X);
        assert!(!s.intersect_ray(&tangent, &mut out, &mut stats));
        assert!(out.is_empty());
        assert_eq!(
            s.classify_point(DVec3::new(0., 2., 0.)),
            Containment::OnBoundary
        );
        assert!(Sphere::try_new(DVec3::ZERO, 0.0).is_err());
        assert!(Sphere::try_new(DVec3::ZERO, f64::NAN).is_err());
    }
}
