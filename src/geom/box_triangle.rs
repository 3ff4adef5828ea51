//! Whether a closed triangle meets a closed axis-aligned box, exactly.
//!
//! Two disjoint convex polytopes have a separating plane that contains a
//! face of one of them or an edge of one and is parallel to an edge of the
//! other. For a box and a triangle that leaves: the box's faces (compare
//! coordinates), the triangle's plane (the sign of `orient3d` at the box's
//! corners), and the planes through a triangle edge parallel to a box axis.
//! The last are lines in the projection along that axis, where the
//! triangle edge's line must have the whole projected box strictly on the
//! side away from the projected triangle: signs of `orient2d`. (The planes
//! through a box edge parallel to a triangle edge need no test of their
//! own: along that box edge's axis they separate the projections, and two
//! disjoint convex polygons are always separated by the line of an edge of
//! one of them — a box face or a triangle edge, both tested.) Every
//! decision is a comparison of input coordinates or an exact predicate, so
//! touching counts as meeting and one ulp of daylight as not.

use glam::{DVec2, DVec3};

use super::{Aabb, Sign, orient2d, orient3d};

/// Whether the closed triangle `t` and the closed box `b` share a point.
/// A degenerate triangle (collinear or repeated corners) is the segment or
/// point it spans.
#[must_use]
pub fn box_meets_triangle(b: &Aabb, t: &[DVec3; 3]) -> bool {
    meets(b, t, true)
}

/// [`box_meets_triangle`], with its shortcuts or without (tests compare).
fn meets(b: &Aabb, t: &[DVec3; 3], shortcuts: bool) -> bool {
    // The box's faces.
    let lo = t[0].min(t[1]).min(t[2]);
    let hi = t[0].max(t[1]).max(t[2]);
    if hi.cmplt(b.min).any() || lo.cmpgt(b.max).any() {
        return false;
    }
    // A corner in the closed box: they meet (the common case at a vertex
    // where many triangles meet, such as a cone's apex).
    if shortcuts
        && t.iter()
            .any(|&p| b.min.cmple(p).all() && p.cmple(b.max).all())
    {
        return true;
    }
    // A triangle in a plane `x_a = c` normal to an axis (the flat faces of
    // models, which often lie on the cells' own planes): that plane meets
    // the box (the coordinate test above), and an edge line's plane
    // parallel to another axis is normal to axis `a` too, so only the
    // projection along `a` is left. (Skipping the other tests changes no
    // answer; it saves the exact fallbacks their zero signs would take.)
    let flat = (0..3).find(|&a| shortcuts && t[0][a] == t[1][a] && t[1][a] == t[2][a]);
    if flat.is_none() {
        // The triangle's plane (a degenerate triangle has none: every sign
        // is zero and nothing is separated here).
        let corners = box_corners(b);
        let mut above = false;
        let mut below = false;
        for &c in &corners {
            match orient3d(t[0], t[1], t[2], c) {
                Sign::Positive => above = true,
                Sign::Negative => below = true,
                Sign::Zero => {
                    above = true;
                    below = true;
                }
            }
        }
        if above != below {
            return false;
        }
    }
    // Planes through a triangle edge parallel to a box axis.
    for axis in 0..3 {
        if flat.is_some_and(|a| a != axis) {
            continue;
        }
        let project = |p: DVec3| match axis {
            0 => DVec2::new(p.y, p.z),
            1 => DVec2::new(p.z, p.x),
            _ => DVec2::new(p.x, p.y),
        };
        let tri = t.map(project);
        let (lo, hi) = (project(b.min), project(b.max));
        let rect = [
            DVec2::new(lo.x, lo.y),
            DVec2::new(hi.x, lo.y),
            DVec2::new(hi.x, hi.y),
            DVec2::new(lo.x, hi.y),
        ];
        for k in 0..3 {
            let (p, q, r) = (tri[k], tri[(k + 1) % 3], tri[(k + 2) % 3]);
            if p == q {
                continue; // the edge projects to a point: no line
            }
            if edge_line_separates(p, q, r, &rect) {
                return false;
            }
        }
    }
    true
}

/// Whether the line through `p`, `q` has every corner of `rect` strictly on
/// the side away from `r` (either strict side when `r` is on the line).
fn edge_line_separates(p: DVec2, q: DVec2, r: DVec2, rect: &[DVec2; 4]) -> bool {
    let side_of_r = orient2d(p, q, r);
    let first = orient2d(p, q, rect[0]);
    if first == Sign::Zero || first == side_of_r {
        return false;
    }
    rect[1..].iter().all(|&c| orient2d(p, q, c) == first)
}

/// The eight corners of a box.
fn box_corners(b: &Aabb) -> [DVec3; 8] {
    std::array::from_fn(|i| {
        DVec3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit() -> Aabb {
        Aabb {
            min: DVec3::ZERO,
            max: DVec3::ONE,
        }
    }

    #[test]
    fn touching_meets_and_one_ulp_of_daylight_does_not() {
        let b = unit();
        // A triangle in the plane x = 1 (the box's face), and one ulp past.
        let on = [
            DVec3::new(1.0, -1.0, -1.0),
            DVec3::new(1.0, 3.0, -1.0),
            DVec3::new(1.0, -1.0, 3.0),
        ];
        assert!(box_meets_triangle(&b, &on));
        let off = on.map(|p| DVec3::new(1f64.next_up(), p.y, p.z));
        assert!(!box_meets_triangle(&b, &off));
        // Touching only a corner, by a vertex.
        let corner = [
            DVec3::ONE,
            DVec3::new(2.0, 1.0, 1.0),
            DVec3::new(1.0, 2.0, 3.0),
        ];
        assert!(box_meets_triangle(&b, &corner));
    }

    #[test]
    fn a_tilted_plane_near_a_corner_is_decided_by_the_plane_test() {
        let b = unit();
        // The plane x + y + z = s through the corner region: it meets the box
        // iff 0 <= s <= 3; the triangle is large enough to cover the box's
        // shadow, so only the plane decides.
        let tri = |s: f64| {
            [
                DVec3::new(s + 10.0, -5.0, -5.0),
                DVec3::new(-5.0, s + 10.0, -5.0),
                DVec3::new(-5.0, -5.0, s + 10.0),
            ]
        };
        assert!(box_meets_triangle(&b, &tri(3.0)));
        assert!(box_meets_triangle(&b, &tri(0.0)));
        // (Offsets the corners' coordinates can carry: 2^-40 next to 13.)
        assert!(!box_meets_triangle(&b, &tri(3.0 + 2f64.powi(-40))));
        assert!(!box_meets_triangle(&b, &tri(-(2f64.powi(-40)))));
    }

    #[test]
    fn an_edge_passing_a_box_edge_is_decided_by_the_edge_planes() {
        let b = unit();
        // A thin triangle whose edge runs diagonally past the box's edge
        // (x = 1, y = 1, z free): its bounding box overlaps the box and its
        // plane cuts the box, yet it misses, by the line x + y = 2 + d.
        let tri = |d: f64| {
            [
                DVec3::new(2.0 + d, 0.0, 0.5),
                DVec3::new(0.0, 2.0 + d, 0.5),
                DVec3::new(3.0, 3.0, 0.5),
            ]
        };
        assert!(box_meets_triangle(&b, &tri(0.0)));
        assert!(!box_meets_triangle(&b, &tri(2f64.next_up() - 2.0)));
        assert!(box_meets_triangle(&b, &tri(-0.5)));
    }

    #[test]
    fn degenerate_triangles_are_their_segments_and_points() {
        let b = unit();
        let segment = [DVec3::splat(-1.0), DVec3::splat(2.0), DVec3::splat(0.5)];
        assert!(box_meets_triangle(&b, &segment));
        let point_inside = [DVec3::splat(0.5); 3];
        assert!(box_meets_triangle(&b, &point_inside));
        let beside = [
            DVec3::new(-1.0, 2.0, 0.5),
            DVec3::new(2.0, 5.0, 0.5),
            DVec3::new(0.5, 3.5, 0.5),
        ];
        assert!(!box_meets_triangle(&b, &beside));
    }

    /// Against sampling: a triangle that contains a sample point inside the
    /// box meets it; random small boxes and triangles agree with an
    /// independent test (the triangle clipped by the box's six half-spaces,
    /// in exact arithmetic on dyadic inputs: the clip keeps a point).
    #[test]
    fn random_cases_agree_with_clipping() {
        let mut grid = quarter_grid(0x0C71_5EED);
        for _ in 0..3000 {
            let (b, t) = box_and_triangle(&mut grid);
            assert_eq!(
                box_meets_triangle(&b, &t),
                clip_keeps_a_point(&b, &t),
                "{b:?} {t:?}"
            );
        }
    }

    /// The shortcuts (a corner in the box; a triangle in a plane normal to
    /// an axis tested in that plane only) answer as the full test does, on
    /// random triangles flattened onto such planes, often the box's own.
    #[test]
    fn the_shortcuts_answer_as_the_full_test() {
        let mut grid = quarter_grid(0x5A0F_F1A7);
        for case in 0..3000 {
            let (b, mut t) = box_and_triangle(&mut grid);
            if case % 4 != 0 {
                let axis = case % 3;
                let level = if case % 2 == 0 { b.min[axis] } else { grid() };
                for p in &mut t {
                    p[axis] = level;
                }
            }
            assert_eq!(meets(&b, &t, true), meets(&b, &t, false), "{b:?} {t:?}");
        }
    }

    /// Seeded values on the grid of quarter units in `[-1, 1)`.
    fn quarter_grid(seed: u64) -> impl FnMut() -> f64 {
        let mut uniform = crate::test_rng::uniform(seed);
        move || (uniform() * 8.0).floor() / 4.0 - 1.0
    }

    /// A box and a triangle with every coordinate from `grid`.
    fn box_and_triangle(grid: &mut impl FnMut() -> f64) -> (Aabb, [DVec3; 3]) {
        let mut point = || DVec3::new(grid(), grid(), grid());
        let (a, c) = (point(), point());
        let b = Aabb {
            min: a.min(c),
            max: a.max(c),
        };
        (b, [point(), point(), point()])
    }

    /// Sutherland–Hodgman clipping of the triangle by the box's faces in
    /// `f64`; exact here because the inputs are on a coarse dyadic grid
    /// and every clip is by an axis plane (one division by a difference of
    /// grid values: exact in binary only when it is a power of two, so the
    /// test compares with a tolerance of zero only where it can — see the
    /// grid above, quarter units in [-1, 1], where the few rounded cuts stay
    /// far from deciding).
    fn clip_keeps_a_point(b: &Aabb, t: &[DVec3; 3]) -> bool {
        let mut poly: Vec<DVec3> = t.to_vec();
        for axis in 0..3 {
            for (bound, keep_below) in [(b.max[axis], true), (b.min[axis], false)] {
                let inside = |p: DVec3| {
                    if keep_below {
                        p[axis] <= bound
                    } else {
                        p[axis] >= bound
                    }
                };
                let mut out = Vec::new();
                for i in 0..poly.len() {
                    let (p, q) = (poly[i], poly[(i + 1) % poly.len()]);
                    if inside(p) {
                        out.push(p);
                    }
                    if inside(p) != inside(q) {
                        let s = (bound - p[axis]) / (q[axis] - p[axis]);
                        let mut x = p + (q - p) * s;
                        x[axis] = bound;
                        out.push(x);
                    }
                }
                poly = out;
                if poly.is_empty() {
                    return false;
                }
            }
        }
        true
    }
}
