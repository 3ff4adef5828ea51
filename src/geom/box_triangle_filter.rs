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

/// A triangle prepared for many [`TriangleFilter::may_meet`] calls.
#[derive(Clone, Copy, Debug)]
pub struct TriangleFilter {
    corners: [DVec3; 3],
    edges: [DVec3; 3],
    normal: DVec3,
    magnitude: f64,
}

impl TriangleFilter {
    /// The filter of the closed triangle `t`.
    #[must_use]
    pub fn new(t: &[DVec3; 3]) -> TriangleFilter {
        let edges = [t[1] - t[0], t[2] - t[1], t[0] - t[2]];
        TriangleFilter {
            corners: *t,
            edges,
            normal: edges[0].cross(edges[1]),
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
        let t = &self.corners;
        // The box's faces.
        let tmin = t[0].min(t[1]).min(t[2]);
        let tmax = t[0].max(t[1]).max(t[2]);
        if tmin.cmpgt(hi).any() || tmax.cmplt(lo).any() {
            return false;
        }
        let centre = (lo + hi) * 0.5;
        let half = (hi - lo) * 0.5;
        let v = [t[0] - centre, t[1] - centre, t[2] - centre];
        let gap = |a: DVec3| -> bool {
            let p = [a.dot(v[0]), a.dot(v[1]), a.dot(v[2])];
            let r = half.dot(a.abs());
            p[0].min(p[1]).min(p[2]) > r || p[0].max(p[1]).max(p[2]) < -r
        };
        // The triangle's plane.
        if gap(self.normal) {
            return false;
        }
        // Each box axis crossed with each triangle edge.
        for f in &self.edges {
            let axes = [
                DVec3::new(0.0, -f.z, f.y),
                DVec3::new(f.z, 0.0, -f.x),
                DVec3::new(-f.y, f.x, 0.0),
            ];
            if axes.into_iter().any(gap) {
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
