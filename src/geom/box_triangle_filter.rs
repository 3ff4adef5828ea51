//! A fast, conservative floating-point filter for "may this closed triangle
//! meet this closed box?": the separating-axis test of
//! [`box_meets_triangle`](super::box_meets_triangle) in plain `f64`, with
//! the box widened so that rounding can only err towards "may meet".
//!
//! Any vector that separates the projections of the two sets proves them
//! disjoint, exact or not, so the axes may be computed with rounding; what
//! must hold is that a computed gap is a real one. The projections of the
//! triangle's corners (relative to the box's centre) and the box's radius
//! along an axis `a` are sums of a few products of numbers of magnitude at
//! most `2m` (`m` the largest coordinate magnitude of the triangle and the
//! box), each rounded: their error is below `16 ε |a|₁ m` (`ε = 2⁻⁵³`).
//! Widening the box by `2⁻⁴⁰ m` along each axis adds `2⁻⁴⁰ m |a|₁` to the
//! radius, far more than that. Non-finite values compare false and so
//! never separate.

use glam::DVec3;

use super::Aabb;

/// A triangle prepared for many [`TriangleFilter::may_meet`] calls: its
/// box, and its separating axes (its plane's normal, each box axis crossed
/// with each edge) with the triangle's extent along each, computed once.
///
/// Along an axis `a` the test compares the triangle's extent
/// `[min a·tᵢ, max a·tᵢ]`, computed here, with the box's `a·c ± r` (centre
/// `c`, radius `r = h·|a|`), computed per box. The rounding errors of those
/// dot products of three terms and of the two subtractions stay below
/// `16 ε |a|₁ m` as in the form relative to the box's centre, far below
/// the `2⁻⁴⁰ m |a|₁` the widening adds.
#[derive(Clone, Copy, Debug)]
pub struct TriangleFilter {
    min: DVec3,
    max: DVec3,
    /// The axes: the normal, then the edges crossed with `x`, `y`, `z`.
    axes: [DVec3; AXES],
    /// Their components' magnitudes.
    abs_axes: [DVec3; AXES],
    /// The triangle's smallest and largest projection on each axis.
    low: [f64; AXES],
    high: [f64; AXES],
    magnitude: f64,
}

/// The triangle's separating axes: its normal and nine edge × box-axis
/// crossings.
const AXES: usize = 10;

impl TriangleFilter {
    /// The filter of the closed triangle `t`.
    #[must_use]
    pub fn new(t: &[DVec3; 3]) -> TriangleFilter {
        let edges = [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
        let mut axes = [edges[0].cross(edges[1]); AXES];
        for (k, f) in edges.iter().enumerate() {
            axes[1 + 3 * k] = DVec3::new(0.0, -f.z, f.y);
            axes[2 + 3 * k] = DVec3::new(f.z, 0.0, -f.x);
            axes[3 + 3 * k] = DVec3::new(-f.y, f.x, 0.0);
        }
        let project = |a: DVec3| [a.dot(t[0]), a.dot(t[1]), a.dot(t[2])];
        TriangleFilter {
            min: t[0].min(t[1]).min(t[2]),
            max: t[0].max(t[1]).max(t[2]),
            abs_axes: axes.map(DVec3::abs),
            low: axes.map(|a| {
                let p = project(a);
                p[0].min(p[1]).min(p[2])
            }),
            high: axes.map(|a| {
                let p = project(a);
                p[0].max(p[1]).max(p[2])
            }),
            axes,
            magnitude: t[0].abs().max(t[1].abs()).max(t[2].abs()).max_element(),
        }
    }

    /// `false` only when the triangle and the closed box `b` certainly
    /// share no point; `true` when they may (always when they do).
    #[must_use]
    pub fn may_meet(&self, b: &Aabb) -> bool {
        let m = self
            .magnitude
            .max(b.min.abs().max(b.max.abs()).max_element());
        let widen = DVec3::splat(m * (1.0 / (1u64 << 40) as f64));
        let (lo, hi) = (b.min - widen, b.max + widen);
        // The box's faces.
        if self.min.cmpgt(hi).any() || self.max.cmplt(lo).any() {
            return false;
        }
        let centre = (lo + hi) * 0.5;
        let half = (hi - lo) * 0.5;
        // The triangle's plane, then each box axis crossed with each edge.
        for k in 0..AXES {
            let c = self.axes[k].dot(centre);
            let r = half.dot(self.abs_axes[k]);
            if self.low[k] - c > r || self.high[k] - c < -r {
                return false;
            }
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::box_meets_triangle;

    /// The filter never says "apart" where the exact test says "meets",
    /// touching included, and agrees with it on clear cases.
    #[test]
    fn the_filter_never_rejects_a_box_the_triangle_meets() {
        let mut u = crate::test_rng::uniform(0x5EED_F17E);
        let mut point = |s: f64| DVec3::new(u(), u(), u()) * s;
        let mut agree = 0;
        for case in 0..20_000 {
            let scale = [1.0, 1e-9, 1e9][case % 3];
            let t = [point(scale), point(scale), point(scale)];
            let lo = point(scale);
            let b = Aabb::from_points([lo, lo + point(0.3 * scale)]);
            let exact = box_meets_triangle(&b, &t);
            let may = TriangleFilter::new(&t).may_meet(&b);
            assert!(may || !exact, "case {case}: {t:?} {b:?}");
            agree += usize::from(may == exact);
        }
        assert!(agree > 19_000, "{agree}");
        // Touching exactly: a corner on the box's face, a box on the plane.
        let t = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.0),
            DVec3::new(2.0, 0.0, 1.0),
        ];
        let touching = Aabb::from_points([DVec3::new(0.0, -1.0, -1.0), DVec3::new(1.0, 0.0, 0.0)]);
        assert!(box_meets_triangle(&touching, &t));
        assert!(TriangleFilter::new(&t).may_meet(&touching));
    }
}
