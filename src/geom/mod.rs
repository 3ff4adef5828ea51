//! Numbers: exact predicates, planes, boxes, rays and segments.
//!
//! This is the bottom layer. Signs are decided exactly by [`orient2d`] and
//! [`orient3d`]; everything else here (plane coefficients, distances, box
//! extents) is a floating-point construction that never decides a sign.

mod aabb;
pub(crate) mod around_axis;
mod box_triangle;
mod box_triangle_filter;
mod compensated;
mod dot;
pub(crate) mod dyadic;
pub mod exact;
pub(crate) mod expansion;
pub mod implicit;
mod plane;
pub mod polygon;
mod predicates;
mod ray;
mod readable;
mod tolerance;
pub mod tri_tri;
pub mod triangulate;

pub use aabb::Aabb;
pub use box_triangle::box_meets_triangle;
pub use box_triangle_filter::TriangleFilter;
pub use dot::{dot_sign, side_of_plane};
pub use exact::{line_side, line_side_sos};
pub use plane::{Plane, PlaneError, PlaneFit, newell_vector_area, unit_direction};
pub use predicates::{
    Sign, exact_fallbacks, incircle, orient2d, orient3d, reset_exact_fallbacks, tie_breaks,
};
pub(crate) use predicates::{UNDERFLOW, count_tie_break};
pub use ray::{Ray, Segment};
pub use readable::{Readable, ReadableVec};
pub use tolerance::Tolerance;
pub use tri_tri::{TriTriContact, triangle_contact, triangles_intersect};
pub use triangulate::{Ring, TriangulateError, triangulate, triangulate_3d};

use glam::{DVec2, DVec3};

/// The larger of `a` and `b`, for values that are never NaN (differences
/// and magnitudes of finite numbers): a plain comparison, where `f64::max`
/// and `f32::max` spend several instructions on NaN handling. With a NaN it
/// returns `b`.
#[must_use]
#[inline(always)]
pub(crate) fn larger<T: PartialOrd>(a: T, b: T) -> T {
    if a > b { a } else { b }
}

/// Whether three points are exactly collinear (coincident points included).
///
/// Decided exactly: three points are collinear iff their projections onto all
/// three axis planes are collinear.
#[must_use]
pub fn collinear3d(a: DVec3, b: DVec3, c: DVec3) -> bool {
    let xy = |p: DVec3| DVec2::new(p.x, p.y);
    let yz = |p: DVec3| DVec2::new(p.y, p.z);
    let zx = |p: DVec3| DVec2::new(p.z, p.x);
    orient2d(xy(a), xy(b), xy(c)) == Sign::Zero
        && orient2d(yz(a), yz(b), yz(c)) == Sign::Zero
        && orient2d(zx(a), zx(b), zx(c)) == Sign::Zero
}

/// The orientation of triangle `t` seen along `axis` (its projection on
/// the other two coordinates, in cyclic order: `y, z` along `x`, `z, x`
/// along `y`, `x, y` along `z`), exact.
#[must_use]
pub(crate) fn projected_orientation(t: [DVec3; 3], axis: u8) -> Sign {
    let (u, v) = (((axis + 1) % 3) as usize, ((axis + 2) % 3) as usize);
    let flat = t.map(|p| DVec2::new(p[u], p[v]));
    orient2d(flat[0], flat[1], flat[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn collinearity_is_exact() {
        let a = DVec3::new(0.1, 0.2, 0.3);
        let b = DVec3::new(0.2, 0.4, 0.6);
        assert!(collinear3d(a, a, b));
        assert!(collinear3d(DVec3::ZERO, DVec3::ONE, DVec3::splat(3.0)));
        // 0.3 = 3 * 0.1 is false in binary: these are not exactly collinear.
        assert!(!collinear3d(DVec3::ZERO, a, DVec3::new(0.3, 0.6, 0.9)));
    }
}
