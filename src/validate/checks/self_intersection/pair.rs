//! The exact test of one pair of triangles of different faces: do they meet
//! anywhere but at the vertices (or the edge) they share?
//!
//! # Sharing one vertex
//!
//! Triangles `A = (v, a1, a2)` and `B = (v, b1, b2)`. Both are convex and
//! hold `v`, so their intersection is convex and holds `v`: it holds a point
//! other than `v` iff it holds a short segment from `v`, that is iff the two
//! closed corners at `v` (the cones `v + λ(a1 − v) + μ(a2 − v)`, `λ, μ ≥ 0`)
//! share a direction. With `t_k = orient3d(v, b1, b2, a_k)`, the side of
//! `B`'s plane each far vertex of `A` is on:
//!
//! - `t1 = t2 = 0` (coplanar): two closed wedges of one plane, each less
//!   than a half-turn, share a direction iff a side of one lies in the other
//!   (of two arcs of a circle that meet, one holds an end of the other). A
//!   side ray `v → p` lies in the closed corner `(v, b1, b2)` iff `p ≠ v`,
//!   `orient2d(v, b1, p)` and `orient2d(v, p, b2)` are zero or of the sign
//!   of `orient2d(v, b1, b2)` (in an axis projection that keeps `B`'s
//!   area). Corners that only share a side ray count: the faces touch along
//!   a segment from `v`.
//! - `t1 = t2 ≠ 0`: `A` lies on one side of `B`'s plane but for `v`; they
//!   meet only at `v`.
//! - otherwise the planes differ and meet in a line through `v`; `A` meets
//!   `B`'s plane in the segment from `v` to the point `x` where the far edge
//!   `a1 a2` crosses it (`x = a1` when `t1 = 0`, `x = a2` when `t2 = 0`),
//!   and `B`'s corner meets that line in one ray or only at `v`. So they
//!   share a direction iff `x` lies in `B`'s closed corner. As the segment
//!   runs from `a1` to `a2` it crosses `B`'s plane in the direction
//!   `σ = sign(t2 − t1)` (`t2` when non-zero, else `−t1`), and for `p, q` in
//!   that plane the turn `(p, q, x)` seen from `B`'s side `n` (the one its
//!   corners turn positively around) has the sign of
//!   `σ · orient3d(a1, a2, p, q)` (expand `orient3d` along the segment: it
//!   is affine in each argument). So `x` is in the closed corner iff
//!   `σ · orient3d(a1, a2, v, b1) ≥ 0` and `σ · orient3d(a1, a2, b2, v) ≥ 0`
//!   (both zero is impossible: `x ≠ v`). This covers far edges that cross
//!   exactly (the faces meet along a segment from `v` to the crossing), a
//!   far vertex on the other face or on its edges, and an edge through the
//!   other's interior.
//!
//! A degenerate triangle (its corners on one line: only a fan of a face
//! whose projection is not simple produces one) has a corner made of at
//! most two rays, each tested against the other corner as above.
//!
//! # Sharing an edge
//!
//! `(u, w, a)` and `(u, w, b)`: when not coplanar they meet only along
//! `uw`; when coplanar they overlap (a fold) iff `a` and `b` lie on the same
//! side of `uw`.
//!
//! # Corners at one position
//!
//! Two shells, or two sheets of one shell, may touch at a point or along
//! an edge where each has vertices of its own (spheres resting on a plate,
//! two cubes sharing an edge, after a boolean). Corners at exactly one
//! position count as shared: one such corner gets the rule for one shared
//! vertex, two (coincident edges) the rule for a shared edge, so only a
//! common point beyond the contact is a defect; three are two triangles in
//! one place, a defect. Two sheets that touch at a point without crossing
//! enclose disjoint solids there or one inside the other; the second is
//! caught by the shells' nesting and orientation. Whether sheets cross
//! along coincident edges depends on all the faces around the edge, not on
//! a pair: [`coincident_edges`](super::coincident_edges) decides it.
//!
//! # Sharing nothing
//!
//! Any common point is a defect (crossing or touching):
//! [`triangles_intersect`].

use glam::{DVec2, DVec3};

use super::super::super::context::Context;
use super::triangles::Triangle;
use crate::geom::polygon::Projection;
use crate::geom::{Sign, collinear3d, orient2d, orient3d, triangles_intersect};

/// Whether two triangles of different faces meet anywhere but at the
/// vertices (or the edge) they share; see the module documentation.
pub(super) fn triangles_meet_beyond_shared(ctx: &Context, a: &Triangle, b: &Triangle) -> bool {
    let pa = a.vertices.map(|v| ctx.position(v));
    let pb = b.vertices.map(|v| ctx.position(v));
    let shared = shared_corners(a, b, pa, pb);
    match shared[..] {
        [] => triangles_intersect(pa, pb),
        // One vertex, or (two shells or two sheets of one touching at a
        // point where each has a vertex) one position: a contact, not a
        // crossing, unless the triangles meet beyond it.
        [(i, j)] => corners_meet(
            pa[i],
            [pa[(i + 1) % 3], pa[(i + 2) % 3]],
            [pb[(j + 1) % 3], pb[(j + 2) % 3]],
        ),
        [(i0, j0), (i1, j1)] => {
            let (u, w) = (pa[i0], pa[i1]);
            let a_far = pa[3 - i0 - i1];
            let b_far = pb[3 - j0 - j1];
            if orient3d(u, w, a_far, b_far) != Sign::Zero {
                return false;
            }
            let projection = projection_of(pa);
            let (u2, w2) = (projection.apply(u), projection.apply(w));
            let sa = orient2d(u2, w2, projection.apply(a_far));
            sa != Sign::Zero && sa == orient2d(u2, w2, projection.apply(b_far))
        }
        // The same three vertices: a duplicate, reported as such. Three
        // positions with other vertices: two triangles in one place.
        _ => a.shared_vertices(b) < 3,
    }
}

/// The corners `(i, j)` the two triangles share: the same vertex, or
/// (sheets touching at a point or along an edge, each with its own
/// vertices there) the same position, exactly. Corners of a triangle with
/// two corners at one position match by vertex only.
fn shared_corners(
    a: &Triangle,
    b: &Triangle,
    pa: [DVec3; 3],
    pb: [DVec3; 3],
) -> smallvec::SmallVec<[(usize, usize); 3]> {
    let distinct = |p: [DVec3; 3]| p[0] != p[1] && p[1] != p[2] && p[2] != p[0];
    let by_position = distinct(pa) && distinct(pb);
    (0..3)
        .filter_map(|i| {
            (0..3)
                .find(|&j| b.vertices[j] == a.vertices[i] || (by_position && pb[j] == pa[i]))
                .map(|j| (i, j))
        })
        .collect()
}

/// Whether the triangles `(v, a1, a2)` and `(v, b1, b2)` have a common
/// point other than `v`: whether their closed corners at `v` share a
/// direction. Exact; see the module documentation for the rule.
pub(super) fn corners_meet(v: DVec3, [a1, a2]: [DVec3; 2], [b1, b2]: [DVec3; 2]) -> bool {
    let flat_a = Projection::of_triangle([v, a1, a2]).is_none();
    let flat_b = Projection::of_triangle([v, b1, b2]).is_none();
    match (flat_a, flat_b) {
        (false, false) => {}
        (true, false) => return [a1, a2].into_iter().any(|p| in_corner(v, [b1, b2], p)),
        (false, true) => return [b1, b2].into_iter().any(|p| in_corner(v, [a1, a2], p)),
        (true, true) => {
            return [a1, a2]
                .into_iter()
                .any(|p| [b1, b2].into_iter().any(|q| same_ray(v, p, q)));
        }
    }
    let t1 = orient3d(v, b1, b2, a1);
    let t2 = orient3d(v, b1, b2, a2);
    if t1 == Sign::Zero && t2 == Sign::Zero {
        return [a1, a2].into_iter().any(|p| in_corner(v, [b1, b2], p))
            || [b1, b2].into_iter().any(|p| in_corner(v, [a1, a2], p));
    }
    if t1 == t2 {
        return false;
    }
    let sigma = if t2 != Sign::Zero { t2 } else { -t1 };
    let holds = |p: DVec3, q: DVec3| sigma * orient3d(a1, a2, p, q) != Sign::Negative;
    holds(v, b1) && holds(b2, v)
}

/// Whether `p` lies in the closed corner at `v` of the non-degenerate
/// triangle `(v, b1, b2)` (the cone of its two sides, less than a
/// half-turn) and differs from `v`: in the triangle's plane, on the corner's
/// side of both side lines (or on them). Exact.
fn in_corner(v: DVec3, [b1, b2]: [DVec3; 2], p: DVec3) -> bool {
    if p == v || orient3d(v, b1, b2, p) != Sign::Zero {
        return false;
    }
    let Some(projection) = Projection::of_triangle([v, b1, b2]) else {
        return false;
    };
    let [v2, b12, b22, p2]: [DVec2; 4] = [v, b1, b2, p].map(|x| projection.apply(x));
    let turn = orient2d(v2, b12, b22);
    turn * orient2d(v2, b12, p2) != Sign::Negative && turn * orient2d(v2, p2, b22) != Sign::Negative
}

/// Whether `p` and `q` (both other than `v`) lie on the same ray from `v`:
/// on one line with it and, along every axis, on the same side of it.
/// Exact (orientations and coordinate comparisons).
fn same_ray(v: DVec3, p: DVec3, q: DVec3) -> bool {
    let side = |x: f64, o: f64| Sign::of(x - o);
    p != v
        && q != v
        && collinear3d(v, p, q)
        && side(p.x, v.x) == side(q.x, v.x)
        && side(p.y, v.y) == side(q.y, v.y)
        && side(p.z, v.z) == side(q.z, v.z)
}

/// An axis projection under which `t` keeps a non-zero area (checked
/// exactly), or the one along its rounded normal for a degenerate `t`.
fn projection_of(t: [DVec3; 3]) -> Projection {
    Projection::of_triangle(t)
        .unwrap_or_else(|| Projection::along((t[1] - t[0]).cross(t[2] - t[0])))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    #[test]
    fn far_edges_that_cross_exactly_meet_along_a_segment() {
        // Two upright triangles on the apex (0, 0, 1) whose far edges cross
        // at the origin: they meet along the segment from the apex down to
        // it, though neither edge passes strictly through the other face.
        let apex = v(0., 0., 1.);
        let a = [v(-1., 0., 0.), v(1., 0., 0.)];
        let b = [v(0., -1., 0.), v(0., 1., 0.)];
        assert!(corners_meet(apex, a, b));
        assert!(corners_meet(apex, b, a));
        // Far edges that cross elsewhere, and that do not cross.
        let b = [v(0.5, -1., 0.), v(1., 1., 0.)];
        assert!(corners_meet(apex, a, b));
        let b = [v(0.5, -1., 0.), v(2., 1., 0.)];
        assert!(!corners_meet(apex, a, b));
        let b = [v(0.5, 0.5, 0.), v(2., 1., 0.)];
        assert!(!corners_meet(apex, a, b));
    }

    #[test]
    fn a_far_vertex_on_the_other_face_or_its_edge_touches() {
        let o = v(0., 0., 0.);
        let base = [v(4., 0., 0.), v(0., 4., 0.)];
        // A side of the upright triangle lies in the base triangle.
        assert!(corners_meet(o, [v(1., 1., 0.), v(1., 1., 3.)], base));
        // A far vertex on the base's far edge.
        assert!(corners_meet(o, [v(2., 2., 0.), v(1., 1., 3.)], base));
        // A far vertex on a side of the base, beyond its end: the side rays
        // still overlap.
        assert!(corners_meet(o, [v(6., 0., 0.), v(1., 1., 3.)], base));
        // The same upright triangle outside the base's corner.
        assert!(!corners_meet(o, [v(-1., 1., 0.), v(-1., 1., 3.)], base));
        // Straight up from the corner: only the vertex in common.
        assert!(!corners_meet(o, [v(0., 0., 3.), v(1., 1., 3.)], base));
    }

    #[test]
    fn coplanar_corners_that_share_only_a_side_ray_touch() {
        let o = v(0., 0., 0.);
        let a = [v(2., 0., 0.), v(0., 2., 0.)];
        // The second corner's side runs along the first's side to (0, 1, 0).
        assert!(corners_meet(o, a, [v(0., 1., 0.), v(-2., 0., 0.)]));
        // Overlapping corners, and corners that meet only at the vertex.
        assert!(corners_meet(o, a, [v(1., 0.5, 0.), v(0.5, 1., 0.)]));
        assert!(!corners_meet(o, a, [v(-1., 1., 0.), v(-2., 0., 0.)]));
        assert!(!corners_meet(o, a, [v(0., -1., 0.), v(-2., -1., 0.)]));
    }

    #[test]
    fn degenerate_corners_are_their_rays() {
        let o = v(0., 0., 0.);
        let corner = [v(2., 0., 0.), v(0., 2., 0.)];
        // A segment through the vertex whose one half lies in the corner.
        assert!(corners_meet(o, [v(1., 1., 0.), v(-1., -1., 0.)], corner));
        assert!(!corners_meet(o, [v(1., -1., 0.), v(-1., 1., 0.)], corner));
        // Two segments from the vertex along one ray, and opposite rays.
        let ray = [v(1., 1., 1.), v(2., 2., 2.)];
        assert!(corners_meet(o, ray, [v(3., 3., 3.), v(3., 3., 3.)]));
        assert!(!corners_meet(o, ray, [v(-3., -3., -3.), v(-1., -1., -1.)]));
    }

    /// An independent reference on small integer coordinates, `v` at the
    /// origin: whether the segment `a1 a2` meets the closed cone of `b1`,
    /// `b2`, in exact integer arithmetic (the point where the segment
    /// meets the cone's plane, or in that plane the segment's ends and its
    /// crossings with the cone's sides).
    fn segment_meets_cone(a1: [i128; 3], a2: [i128; 3], b1: [i128; 3], b2: [i128; 3]) -> bool {
        let cross = |p: [i128; 3], q: [i128; 3]| {
            [
                p[1] * q[2] - p[2] * q[1],
                p[2] * q[0] - p[0] * q[2],
                p[0] * q[1] - p[1] * q[0],
            ]
        };
        let dot = |p: [i128; 3], q: [i128; 3]| p[0] * q[0] + p[1] * q[1] + p[2] * q[2];
        let n = cross(b1, b2);
        // `x` in the plane, `x ≠ 0`: in the closed cone?
        let in_cone =
            |x: [i128; 3]| x != [0; 3] && dot(n, cross(b1, x)) >= 0 && dot(n, cross(x, b2)) >= 0;
        let (d1, d2) = (dot(n, a1), dot(n, a2));
        if d1.signum() * d2.signum() == 1 {
            return false;
        }
        if d1 != 0 || d2 != 0 {
            // x = (d2 a1 − d1 a2) / (d2 − d1): scale by the denominator's
            // sign, which keeps the direction.
            let s = (d2 - d1).signum();
            let x = [0, 1, 2].map(|k| s * (d2 * a1[k] - d1 * a2[k]));
            return in_cone(x);
        }
        let e = [0, 1, 2].map(|k| a2[k] - a1[k]);
        let hits_ray = |b: [i128; 3]| {
            // a1 + τ e = s b with 0 ≤ τ ≤ 1, s ≥ 0, all in one plane.
            let eb = cross(e, b);
            if eb == [0; 3] {
                return false; // parallel: the ends decide
            }
            let k = (0..3).find(|&k| eb[k] != 0).unwrap_or(0);
            let (num, den) = (-cross(a1, b)[k], eb[k]);
            let tau_ok = num * den.signum() >= 0 && num.abs() <= den.abs();
            let ae = cross(a1, e);
            let be = cross(b, e);
            let s_ok = ae[k] * be[k] >= 0;
            tau_ok && s_ok
        };
        in_cone(a1) || in_cone(a2) || hits_ray(b1) || hits_ray(b2)
    }

    #[test]
    fn the_rule_agrees_with_an_integer_reference() {
        let mut unit = crate::test_rng::uniform(2121);
        let mut small = || (unit() * 7.0).floor() as i128 - 3;
        let (mut meet, mut apart) = (0, 0);
        for _ in 0..40_000 {
            let p: [[i128; 3]; 4] = std::array::from_fn(|_| [small(), small(), small()]);
            let f = |q: [i128; 3]| DVec3::new(q[0] as f64, q[1] as f64, q[2] as f64);
            let o = DVec3::ZERO;
            let (a, b) = ([f(p[0]), f(p[1])], [f(p[2]), f(p[3])]);
            if Projection::of_triangle([o, a[0], a[1]]).is_none()
                || Projection::of_triangle([o, b[0], b[1]]).is_none()
            {
                continue;
            }
            let want = segment_meets_cone(p[0], p[1], p[2], p[3])
                || segment_meets_cone(p[2], p[3], p[0], p[1]);
            assert_eq!(corners_meet(o, a, b), want, "{p:?}");
            assert_eq!(corners_meet(o, b, a), want, "{p:?}");
            if want { meet += 1 } else { apart += 1 }
        }
        assert!(meet > 1000 && apart > 1000, "{meet} {apart}");
    }
}
