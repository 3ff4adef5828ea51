//! The half-space: a plane through `Q` with a normal `N` pointing OUTSIDE.

use glam::DVec3;
use thiserror::Error;

use super::primitive::perturbed_side;
use super::{
    CellRelation, Containment, Crossing, CrossingPlane, LocalPlane, Primitive, Stats, SurfaceId,
};
use crate::geom::{Aabb, Ray, Sign, dot_sign, side_of_plane};

/// Why a half-space could not be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum HalfSpaceError {
    /// The normal is zero: no side is outside.
    #[error("half-space normal is zero")]
    ZeroNormal,
    /// A coordinate is NaN or infinite.
    #[error("half-space point {} or normal {} is not finite", crate::geom::ReadableVec(*.point), crate::geom::ReadableVec(*.normal))]
    NonFinite {
        /// The point given.
        point: DVec3,
        /// The normal given.
        normal: DVec3,
    },
}

/// The half-space `{ P : (P − Q) · N ≤ 0 }`: the side the normal does not
/// point to (`(P − Q) · N > 0` is OUTSIDE, `< 0` INSIDE, with the points of the plane itself reported as `OnBoundary`).
///
/// # Exactness
///
/// Every decision is exact on the given `Q` and `N`: the side of a point is
/// the exact sign of `(P − Q) · N` ([`side_of_plane`]), and the ray's
/// cases — `D · N = 0` (parallel: no crossing), `t < 0` (behind the eye: no
/// crossing), the eye in the plane — are decided from the exact signs of
/// `D · N` and `(Q − E) · N` (the sign of `t` is their product). Only the
/// value `t = (Q − E) · N / (D · N)` is a rounded construction; should
/// rounding make it non-positive although its exact sign is positive, it is
/// replaced by the smallest positive double, so the crossing is kept.
///
/// # Invariants
///
/// `point` and `normal` are finite and `normal` is not zero.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HalfSpace {
    point: DVec3,
    normal: DVec3,
}

impl HalfSpace {
    /// The half-space through `point` whose outside is where `normal`
    /// points. The normal need not be unit length and is kept as given (so
    /// decisions stay exact on the user's numbers).
    ///
    /// # Errors
    ///
    /// [`HalfSpaceError`] for a zero normal or non-finite input.
    pub fn try_new(point: DVec3, normal: DVec3) -> Result<HalfSpace, HalfSpaceError> {
        if !point.is_finite() || !normal.is_finite() {
            return Err(HalfSpaceError::NonFinite { point, normal });
        }
        if normal == DVec3::ZERO {
            return Err(HalfSpaceError::ZeroNormal);
        }
        Ok(HalfSpace { point, normal })
    }

    /// `Q`: a point of the plane.
    #[must_use]
    pub fn point(&self) -> DVec3 {
        self.point
    }

    /// `N`: the outward normal, as given.
    #[must_use]
    pub fn normal(&self) -> DVec3 {
        self.normal
    }

    /// The ray–plane parameter `t = (Q − E) · N / (D · N)`: the parameter where the ray meets the plane,
    /// or `None` when the ray is parallel to it (`D · N = 0`), the meeting
    /// is behind the eye (`t < 0`), or the eye is in the plane (`t = 0`: the
    /// ray starts on the boundary and does not cross it at any `t > 0`).
    #[must_use]
    pub fn ray_plane(&self, ray: &Ray) -> Option<f64> {
        let denominator = dot_sign(ray.direction, self.normal);
        let numerator = side_of_plane(self.point, ray.origin, self.normal);
        if denominator == Sign::Zero || numerator * denominator != Sign::Positive {
            return None;
        }
        let t = (self.point - ray.origin).dot(self.normal) / ray.direction.dot(self.normal);
        Some(if t > 0.0 { t } else { f64::MIN_POSITIVE })
    }
}

impl Primitive for HalfSpace {
    fn intersect_ray(&self, ray: &Ray, crossings: &mut Vec<Crossing>, stats: &mut Stats) -> bool {
        let side = side_of_plane(ray.origin, self.point, self.normal);
        let heading = dot_sign(ray.direction, self.normal);
        let inside = match (side, heading) {
            (Sign::Negative, _) => true,
            (Sign::Positive, _) => false,
            // The eye in the plane: inside iff the ray heads inward.
            (Sign::Zero, Sign::Negative) => true,
            (Sign::Zero, Sign::Positive) => false,
            // The whole ray lies in the plane: perturb.
            (Sign::Zero, Sign::Zero) => {
                stats.tie_breaks += 1;
                perturbed_side(self.normal) == Sign::Negative
            }
        };
        if let Some(t) = self.ray_plane(ray) {
            crossings.push(Crossing { t, surface: 0 });
        }
        inside
    }

    fn classify_point(&self, p: DVec3) -> Containment {
        match side_of_plane(p, self.point, self.normal) {
            Sign::Positive => Containment::Outside,
            Sign::Negative => Containment::Inside,
            Sign::Zero => Containment::OnBoundary,
        }
    }

    fn boundary_normal(&self, p: DVec3) -> Option<DVec3> {
        (self.classify_point(p) == Containment::OnBoundary).then_some(self.normal)
    }

    fn crossing_plane(&self, _surface: SurfaceId) -> Option<CrossingPlane> {
        Some(CrossingPlane::PointNormal {
            point: self.point,
            normal: self.normal,
        })
    }

    fn planes_through(&self, _p: DVec3, planes: &mut Vec<LocalPlane>) -> bool {
        planes.extend(LocalPlane::from_normal(self.normal));
        true
    }

    fn inside_along(&self, _p: DVec3, d: DVec3) -> Option<bool> {
        Some(dot_sign(self.normal, d) == Sign::Negative)
    }

    fn normal(&self, _p: DVec3, _surface: SurfaceId) -> DVec3 {
        self.normal
    }

    /// Exact: the signs of the plane at the two corners extreme along
    /// the normal.
    fn cell_relation(&self, cell: &Aabb) -> CellRelation {
        let n = self.normal;
        let positive = n.cmpge(DVec3::ZERO);
        let low = DVec3::select(positive, cell.min, cell.max);
        let high = DVec3::select(positive, cell.max, cell.min);
        match (
            side_of_plane(low, self.point, n),
            side_of_plane(high, self.point, n),
        ) {
            (_, Sign::Negative) => CellRelation::Inside,
            (Sign::Positive, _) => CellRelation::Outside,
            _ => CellRelation::Meets,
        }
    }

    fn bounds(&self) -> Aabb {
        // Unbounded, except along an axis-aligned normal.
        let mut bounds = Aabb {
            min: DVec3::NEG_INFINITY,
            max: DVec3::INFINITY,
        };
        let n = self.normal;
        for axis in 0..3 {
            let others_zero = (0..3).all(|k| k == axis || n[k] == 0.0);
            if others_zero && n[axis] > 0.0 {
                bounds.max[axis] = self.point[axis];
            } else if others_zero && n[axis] < 0.0 {
                bounds.min[axis] = self.point[axis];
            }
        }
        bounds
    }

    fn kind(&self) -> &'static str {
        "halfspace"
    }

    fn tessellate(
        &self,
        _tolerance: f64,
        clip: &Aabb,
    ) -> Result<crate::mesh::Solid, super::TessellateError> {
        super::tessellate::half_space(self.point(), self.normal(), clip)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cast(h: &HalfSpace, e: DVec3, d: DVec3) -> (bool, Vec<f64>) {
        let mut out = Vec::new();
        let mut stats = Stats::default();
        let inside = h.intersect_ray(&Ray::new(e, d), &mut out, &mut stats);
        (inside, out.iter().map(|c| c.t).collect())
    }

    #[test]
    fn the_ray_plane_cases() {
        // z ≤ 1 is inside.
        let h = HalfSpace::try_new(DVec3::new(5., 5., 1.), DVec3::Z).unwrap();
        // From outside towards the plane: one crossing at t = 2.
        assert_eq!(
            cast(&h, DVec3::new(0., 0., 3.), -DVec3::Z),
            (false, vec![2.0])
        );
        // From inside outward.
        assert_eq!(
            cast(&h, DVec3::new(0., 0., -1.), DVec3::Z * 0.5),
            (true, vec![4.0])
        );
        // Parallel: D · N = 0, no crossing.
        assert_eq!(cast(&h, DVec3::new(0., 0., 3.), DVec3::X), (false, vec![]));
        assert_eq!(cast(&h, DVec3::new(0., 0., 0.), DVec3::Y), (true, vec![]));
        // t < 0: the plane is behind the eye.
        assert_eq!(cast(&h, DVec3::new(0., 0., 3.), DVec3::Z), (false, vec![]));
        // The eye in the plane: no crossing; the heading decides.
        assert_eq!(cast(&h, DVec3::new(1., 2., 1.), DVec3::Z), (false, vec![]));
        assert_eq!(cast(&h, DVec3::new(1., 2., 1.), -DVec3::Z), (true, vec![]));
        assert_eq!(
            h.ray_plane(&Ray::new(DVec3::new(1., 2., 1.), DVec3::Z)),
            None
        );
    }

    #[test]
    fn a_ray_in_the_plane_is_perturbed_and_counted() {
        let h = HalfSpace::try_new(DVec3::ZERO, DVec3::Z).unwrap();
        let mut stats = Stats::default();
        let mut out = Vec::new();
        let inside = h.intersect_ray(&Ray::new(DVec3::ZERO, DVec3::X), &mut out, &mut stats);
        assert!(!inside && out.is_empty());
        assert_eq!(stats.tie_breaks, 1);
        let flipped = HalfSpace::try_new(DVec3::ZERO, -DVec3::Z).unwrap();
        assert!(flipped.intersect_ray(&Ray::new(DVec3::ZERO, DVec3::X), &mut out, &mut stats));
    }

    #[test]
    fn points_are_classified_exactly() {
        let h = HalfSpace::try_new(DVec3::new(0.1, 0.1, 0.1), DVec3::ONE).unwrap();
        assert_eq!(
            h.classify_point(DVec3::new(0.1, 0.1, 0.1)),
            Containment::OnBoundary
        );
        assert_eq!(h.classify_point(DVec3::ZERO), Containment::Inside);
        assert_eq!(h.classify_point(DVec3::ONE), Containment::Outside);
        assert!(HalfSpace::try_new(DVec3::ZERO, DVec3::ZERO).is_err());
        assert!(HalfSpace::try_new(DVec3::NAN, DVec3::X).is_err());
    }

    #[test]
    fn axis_aligned_half_spaces_have_one_finite_bound() {
        let h = HalfSpace::try_new(DVec3::new(0., 0., 2.), DVec3::Z).unwrap();
        assert_eq!(h.bounds().max.z, 2.0);
        assert_eq!(h.bounds().min.z, f64::NEG_INFINITY);
        let tilted = HalfSpace::try_new(DVec3::ZERO, DVec3::ONE).unwrap();
        assert_eq!(tilted.bounds().max.z, f64::INFINITY);
    }
}
