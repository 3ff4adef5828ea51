//! Whether, and how, two triangles in space meet: decided exactly.
//!
//! Triangles are closed point sets: a triangle is its interior, its edges and
//! its vertices, so triangles that only touch (a vertex on the other's edge,
//! a shared edge) intersect. A degenerate triangle (collinear corners) is the
//! segment or point it covers.
//!
//! Method (non-coplanar triangles): the sides of each triangle's vertices
//! against the other's plane (exact [`orient3d`]) rule out most pairs; the
//! rest meet the line `L` common to both planes in two closed intervals,
//! and the triangles meet iff the intervals overlap. The interval ends are
//! never constructed: two ends, each the point where an edge of one triangle
//! meets the other's plane, are ordered along `L` by the sign of one more
//! `orient3d` on the four edge ends (the idea of Guigue and Devillers,
//! "Fast and robust triangle-triangle overlap test using orientation
//! predicates", 2003). Coplanar triangles are projected onto an axis plane
//! that keeps their area and tested by separating axes along their edges
//! (exact [`orient2d`]). Every decision is a sign of an exact predicate, so
//! the answers hold for every finite input.

use glam::{DVec2, DVec3};

use super::polygon::{Projection, segments_touch};
use super::{Sign, collinear3d, orient2d, orient3d};

/// How two closed triangles meet; see [`triangle_contact`].
///
/// The *interior* of a triangle is its relative interior: the points of the
/// triangle that are on none of its edges. A degenerate triangle has none.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum TriTriContact {
    /// No common point.
    Disjoint,
    /// Not coplanar, and the interiors meet: the triangles cut through each
    /// other along a segment of positive length that runs through the
    /// interiors of both.
    Crossing,
    /// Not coplanar (or one is degenerate), with common points, all on the
    /// boundary of at least one of the two: a vertex or an edge resting on
    /// the other triangle, a shared vertex or edge, a fin ending on the
    /// other's edge.
    Touching,
    /// In one plane, with interiors that overlap: the common part has
    /// positive area.
    CoplanarOverlap,
    /// In one plane, meeting only along boundaries: the common part is a
    /// point or a segment.
    CoplanarTouching,
}

impl TriTriContact {
    /// Whether the triangles have a common point (anything but
    /// [`TriTriContact::Disjoint`]).
    #[must_use]
    pub fn meets(self) -> bool {
        self != TriTriContact::Disjoint
    }
}

/// Whether the closed triangles `p` and `q` share a point (touching counts),
/// decided exactly for every finite input; degenerate triangles are the
/// segments or points they cover. Non-finite input gives an unspecified
/// answer, never a panic.
#[must_use]
pub fn triangles_intersect(p: [DVec3; 3], q: [DVec3; 3]) -> bool {
    // Most pairs a broad phase hands over lie apart, one strictly on one
    // side of the other's plane: answered before the degeneracy tests. (A
    // degenerate triangle's "plane" gives only zeros, never a strict side.)
    if same_strict_side(q.map(|x| orient3d(p[0], p[1], p[2], x)))
        || same_strict_side(p.map(|x| orient3d(q[0], q[1], q[2], x)))
    {
        return false;
    }
    triangle_contact(p, q).meets()
}

/// How the closed triangles `p` and `q` meet ([`TriTriContact`]), decided
/// exactly for every finite input. The answer does not depend on the order
/// of the two triangles, on which vertex comes first or on their winding.
/// A degenerate triangle (collinear corners) has no interior: it is
/// [`TriTriContact::Touching`] anything it meets. Non-finite input gives an
/// unspecified answer, never a panic.
#[must_use]
pub fn triangle_contact(p: [DVec3; 3], q: [DVec3; 3]) -> TriTriContact {
    let p_flat = collinear3d(p[0], p[1], p[2]);
    let q_flat = collinear3d(q[0], q[1], q[2]);
    if p_flat || q_flat {
        let meets = match (p_flat, q_flat) {
            (true, true) => {
                let (a, b) = extent(p);
                let (c, d) = extent(q);
                segments_meet(a, b, c, d)
            }
            (true, false) => {
                let (a, b) = extent(p);
                segment_meets_triangle(a, b, q)
            }
            _ => {
                let (a, b) = extent(q);
                segment_meets_triangle(a, b, p)
            }
        };
        return if meets {
            TriTriContact::Touching
        } else {
            TriTriContact::Disjoint
        };
    }
    let sq = q.map(|x| orient3d(p[0], p[1], p[2], x));
    if same_strict_side(sq) {
        return TriTriContact::Disjoint;
    }
    let sp = p.map(|x| orient3d(q[0], q[1], q[2], x));
    if same_strict_side(sp) {
        return TriTriContact::Disjoint;
    }
    if sq.iter().all(|&s| s == Sign::Zero) {
        return coplanar_contact(p, q);
    }
    // Along L, directed as n_p × n_q (n_p, n_q the triangles' normals), each
    // interval runs from its `low` end to its `high` end.
    let ip = interval(sp, false);
    let iq = interval(sq, true);
    // The position of an end of q's interval relative to an end of p's.
    let after = |y: End, x: End| {
        orient3d(p[x.from], p[x.to], q[y.from], q[y.to])
            * rising(sq[y.from], sq[y.to])
            * rising(sp[x.from], sp[x.to])
    };
    let q_low_after_p_high = after(iq.low, ip.high);
    let q_high_after_p_low = after(iq.high, ip.low);
    if q_low_after_p_high == Sign::Positive || q_high_after_p_low == Sign::Negative {
        return TriTriContact::Disjoint;
    }
    if straddles(sp)
        && straddles(sq)
        && q_low_after_p_high == Sign::Negative
        && q_high_after_p_low == Sign::Positive
    {
        TriTriContact::Crossing
    } else {
        TriTriContact::Touching
    }
}

/// One end of the interval where a triangle meets the other's plane: the
/// point where its edge `from → to` meets that plane (the vertex itself
/// when one of them lies on the plane). `from` and `to` are on different
/// sides, one of them perhaps on the plane.
#[derive(Clone, Copy, Debug)]
struct End {
    from: usize,
    to: usize,
}

/// The two ends of an interval along `L`.
#[derive(Clone, Copy, Debug)]
struct Interval {
    low: End,
    high: End,
}

/// The interval where a triangle with vertex sides `s` (against the other
/// triangle's plane; neither all on one strict side nor all zero) meets
/// that plane, ordered along `n_p × n_q`; `second` says the triangle is `q`,
/// for which the natural direction `n_q × n_p` is the reverse.
///
/// Let vertex `k` be alone on its strict side, the other two on the
/// other side or on the plane; the ends lie on edges `k → k+1` and
/// `k → k+2`. Within the triangle's plane the end on `k → k+2` lies on
/// the left of the edge `k → k+1` (the triangle winds counter-clockwise
/// around its normal), so along the triangle's own direction
/// `n_self × n_other` it comes first when `k` is on the positive side.
/// Without such a vertex the triangle touches the plane at one vertex only.
fn interval(s: [Sign; 3], second: bool) -> Interval {
    let lone = (0..3).find(|&k| s[k] != Sign::Zero && (1..3).all(|d| s[(k + d) % 3] != s[k]));
    let Some(k) = lone else {
        // One vertex on the plane, the other two on one strict side.
        let k = (0..3).find(|&k| s[k] == Sign::Zero).unwrap_or(0);
        let end = End {
            from: k,
            to: (k + 1) % 3,
        };
        return Interval {
            low: end,
            high: end,
        };
    };
    let next = End {
        from: k,
        to: (k + 1) % 3,
    };
    let prev = End {
        from: k,
        to: (k + 2) % 3,
    };
    if (s[k] == Sign::Positive) != second {
        Interval {
            low: prev,
            high: next,
        }
    } else {
        Interval {
            low: next,
            high: prev,
        }
    }
}

/// The sign of `to − from` for two different sides.
fn rising(from: Sign, to: Sign) -> Sign {
    if to > from {
        Sign::Positive
    } else {
        Sign::Negative
    }
}

fn same_strict_side(s: [Sign; 3]) -> bool {
    s[0] != Sign::Zero && s[0] == s[1] && s[1] == s[2]
}

fn straddles(s: [Sign; 3]) -> bool {
    s.contains(&Sign::Positive) && s.contains(&Sign::Negative)
}

/// The contact of two non-degenerate coplanar triangles: separating axes
/// along the six edges in a projection that keeps the plane's area.
///
/// Two convex polygons are disjoint iff the line through some edge of one
/// has the other strictly on its outer side, and their interiors are
/// disjoint iff some such line has the other on its closed outer side (the
/// edges of their Minkowski difference are parallel to theirs).
fn coplanar_contact(p: [DVec3; 3], q: [DVec3; 3]) -> TriTriContact {
    let Some(projection) = Projection::of_triangle(p) else {
        return TriTriContact::Disjoint;
    };
    let p2 = counter_clockwise(p.map(|x| projection.apply(x)));
    let q2 = counter_clockwise(q.map(|x| projection.apply(x)));
    // The least-inward side of the other's vertices over a's edges: Negative
    // if some edge has them all strictly outside, Zero if some edge has them
    // all on its closed outer side, Positive otherwise.
    let separation = |a: [DVec2; 3], b: [DVec2; 3]| {
        (0..3)
            .map(|i| {
                b.iter()
                    .map(|&x| orient2d(a[i], a[(i + 1) % 3], x))
                    .max()
                    .unwrap_or(Sign::Positive)
            })
            .min()
            .unwrap_or(Sign::Positive)
    };
    match separation(p2, q2).min(separation(q2, p2)) {
        Sign::Negative => TriTriContact::Disjoint,
        Sign::Zero => TriTriContact::CoplanarTouching,
        Sign::Positive => TriTriContact::CoplanarOverlap,
    }
}

/// `t` wound counter-clockwise (`t` has non-zero area).
fn counter_clockwise(t: [DVec2; 3]) -> [DVec2; 3] {
    if orient2d(t[0], t[1], t[2]) == Sign::Negative {
        [t[0], t[2], t[1]]
    } else {
        t
    }
}

/// The two extreme points of three collinear points (the lexicographic
/// least and greatest, which are the ends along their common line).
fn extent(t: [DVec3; 3]) -> (DVec3, DVec3) {
    let key = |p: &DVec3| (p.x, p.y, p.z);
    let less = |a: &DVec3, b: &DVec3| key(a) < key(b);
    let mut lo = t[0];
    let mut hi = t[0];
    for x in &t[1..] {
        if less(x, &lo) {
            lo = *x;
        }
        if less(&hi, x) {
            hi = *x;
        }
    }
    (lo, hi)
}

/// Whether the closed segment `ab` (perhaps a point) meets the closed,
/// non-degenerate triangle `t`. Exact.
fn segment_meets_triangle(a: DVec3, b: DVec3, t: [DVec3; 3]) -> bool {
    let sa = orient3d(t[0], t[1], t[2], a);
    let sb = orient3d(t[0], t[1], t[2], b);
    if sa == sb && sa != Sign::Zero {
        return false;
    }
    if sa == Sign::Zero && sb == Sign::Zero {
        let Some(projection) = Projection::of_triangle(t) else {
            return false;
        };
        let t2 = t.map(|x| projection.apply(x));
        let (a2, b2) = (projection.apply(a), projection.apply(b));
        return point_in_triangle_2d(a2, t2)
            || (0..3).any(|i| segments_touch(a2, b2, t2[i], t2[(i + 1) % 3]));
    }
    // The line through a and b pierces the plane at one point of the
    // segment; it lies in the closed triangle iff the line passes no edge on
    // the outside, i.e. the three signs are not mixed.
    let s = [
        orient3d(a, b, t[0], t[1]),
        orient3d(a, b, t[1], t[2]),
        orient3d(a, b, t[2], t[0]),
    ];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

/// Whether the closed segments `ab` and `cd` in space (either perhaps a
/// point) share a point. Exact.
fn segments_meet(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> bool {
    if orient3d(a, b, c, d) != Sign::Zero {
        return false;
    }
    // Coplanar: in a projection that keeps the area of a triangle of three
    // of the points, the common plane maps one to one onto the axis plane.
    let projection = [[a, b, c], [a, b, d], [c, d, a], [c, d, b]]
        .into_iter()
        .find_map(Projection::of_triangle);
    if let Some(projection) = projection {
        let [a, b, c, d] = [a, b, c, d].map(|x| projection.apply(x));
        return segments_touch(a, b, c, d);
    }
    // All on one line (or one point): the lexicographic order of the
    // coordinates is the order along it.
    let key = |p: DVec3| (p.x, p.y, p.z);
    let (lo1, hi1) = if key(a) <= key(b) { (a, b) } else { (b, a) };
    let (lo2, hi2) = if key(c) <= key(d) { (c, d) } else { (d, c) };
    key(lo2) <= key(hi1) && key(lo1) <= key(hi2)
}

/// Whether `p` lies in the closed 2-D triangle `t` (either winding).
fn point_in_triangle_2d(p: DVec2, t: [DVec2; 3]) -> bool {
    let s = [
        orient2d(t[0], t[1], p),
        orient2d(t[1], t[2], p),
        orient2d(t[2], t[0], p),
    ];
    !(s.contains(&Sign::Positive) && s.contains(&Sign::Negative))
}

#[cfg(test)]
mod tests;
