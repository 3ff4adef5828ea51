//! Polygons projected onto an axis plane (dropping the coordinate of the
//! normal's largest component).
//!
//! A planar polygon is projected onto the coordinate plane most nearly
//! parallel to it: the one perpendicular to the largest component of its
//! normal. Projection only drops a coordinate, so it is exact, and 2-D
//! predicates on the projected points are exact statements about the input.

use glam::{DVec2, DVec3};

use super::{Sign, orient2d};

/// A coordinate axis: the one dropped when projecting.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Axis {
    /// Drop `x`: project onto the `yz` plane.
    X,
    /// Drop `y`: project onto the `zx` plane.
    Y,
    /// Drop `z`: project onto the `xy` plane.
    Z,
}

/// The projection of a polygon with the normal `normal`: which axis to drop,
/// and whether the projection reverses the winding.
///
/// Projected coordinates are chosen so that a polygon wound counter-clockwise
/// around `normal` stays counter-clockwise in 2-D when `flipped` is false.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Projection {
    /// The dropped axis.
    pub axis: Axis,
    /// Whether the normal points along the negative dropped axis, so that
    /// counter-clockwise in 3-D is clockwise in 2-D.
    pub flipped: bool,
}

impl Projection {
    /// The projection onto the axis plane closest to the plane with normal
    /// `normal` (largest absolute component dropped; ties go to `z`, then
    /// `y`).
    #[must_use]
    pub fn along(normal: DVec3) -> Projection {
        let a = normal.abs();
        let (axis, component) = if a.z >= a.x && a.z >= a.y {
            (Axis::Z, normal.z)
        } else if a.y >= a.x {
            (Axis::Y, normal.y)
        } else {
            (Axis::X, normal.x)
        };
        Projection {
            axis,
            flipped: component < 0.0,
        }
    }

    /// An axis projection under which the triangle `t` keeps a non-zero
    /// area, or `None` when `t` is degenerate (its corners collinear).
    /// Decided exactly; the rounded normal only proposes the axis to try
    /// first. Under it, the plane of `t` maps one to one onto the axis
    /// plane, so 2-D predicates on projected points of that plane are exact
    /// statements about the 3-D points.
    #[must_use]
    pub fn of_triangle(t: [DVec3; 3]) -> Option<Projection> {
        let normal = (t[1] - t[0]).cross(t[2] - t[0]);
        let first = Projection::along(normal);
        let keeps_area = |p: Projection| {
            let t2 = t.map(|x| p.apply(x));
            orient2d(t2[0], t2[1], t2[2]) != Sign::Zero
        };
        if keeps_area(first) {
            return Some(first);
        }
        [DVec3::Z, DVec3::Y, DVec3::X]
            .into_iter()
            .map(Projection::along)
            .find(|&p| keeps_area(p))
    }

    /// `p` with the dropped coordinate removed; `(y, z)`, `(z, x)` or `(x, y)`,
    /// which keeps right-handedness.
    #[must_use]
    pub fn apply(&self, p: DVec3) -> DVec2 {
        match self.axis {
            Axis::X => DVec2::new(p.y, p.z),
            Axis::Y => DVec2::new(p.z, p.x),
            Axis::Z => DVec2::new(p.x, p.y),
        }
    }
}

/// Whether a closed 2-D polygon is simple: no two non-adjacent edges touch,
/// and no two adjacent edges fold back over each other. Decided exactly;
/// `O(n²)`, meant for builder input, not for large meshes.
///
/// Returns the first pair of offending edge indices (edge `i` runs from vertex
/// `i` to vertex `i + 1`), or `None` for a simple polygon.
#[must_use]
pub fn find_self_intersection(points: &[DVec2]) -> Option<(usize, usize)> {
    let n = points.len();
    let edge = |i: usize| (points[i], points[(i + 1) % n]);
    for i in 0..n {
        let (a, b) = edge(i);
        // Adjacent edge i+1 folds back onto edge i.
        let c = points[(i + 2) % n];
        if n >= 3 && orient2d(a, b, c) == Sign::Zero && (b - a).dot(c - b) < 0.0 {
            return Some((i, (i + 1) % n));
        }
        for j in i + 2..n {
            if i == 0 && j == n - 1 {
                continue;
            }
            let (c, d) = edge(j);
            if segments_touch(a, b, c, d) {
                return Some((i, j));
            }
        }
    }
    None
}

/// Whether the closed segments `ab` and `cd` share a point, decided exactly.
#[must_use]
pub fn segments_touch(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> bool {
    let abc = orient2d(a, b, c);
    let abd = orient2d(a, b, d);
    let cda = orient2d(c, d, a);
    let cdb = orient2d(c, d, b);
    if abc != Sign::Zero && abc == abd || cda != Sign::Zero && cda == cdb {
        return false;
    }
    if a == b {
        // A point: on the closed segment cd (itself perhaps a point).
        return cda == Sign::Zero && on_box(c, d, a);
    }
    if abc == Sign::Zero && abd == Sign::Zero {
        // Collinear: one end of a segment within the other's box.
        return on_box(a, b, c) || on_box(a, b, d) || on_box(c, d, a) || on_box(c, d, b);
    }
    true
}

/// Whether `r` lies in the closed axis-aligned box of `p` and `q`: for `r`
/// collinear with them, whether it lies on the closed segment `pq`.
fn on_box(p: DVec2, q: DVec2, r: DVec2) -> bool {
    r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
}

/// Where a point lies relative to a polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum PolygonLocation {
    /// Strictly inside (non-zero winding number).
    Inside,
    /// Strictly outside.
    Outside,
    /// Exactly on the open edge from vertex `i` to vertex `i + 1` (mod n).
    OnEdge(usize),
    /// Exactly at vertex `i`.
    OnVertex(usize),
}

/// Locates a point relative to a polygon of `n` vertices using only an
/// orientation oracle, so that the point itself never has to be constructed.
///
/// `orient(i, j)` must return the exact sign of `orient2d(vᵢ, vⱼ, p)` up to
/// one global sign factor (the same for every call); `collinear(i, j, k)`
/// whether vertices `i`, `j`, `k` are exactly collinear. The polygon may be
/// non-convex; it must not have all its vertices collinear (then the answer is
/// [`PolygonLocation::Outside`] unless the point is a vertex).
///
/// Method: the point is at vertex `i` iff it is collinear with `vᵢ` and every
/// other vertex; on the open edge `(i, i + 1)` iff it is on the edge's line and
/// on the same side of `vᵢ₊₁ vₖ` and `vₖ vᵢ` for a vertex `vₖ` off that line;
/// otherwise its winding number is the signed count of fan triangles
/// `(v₀, vₖ, vₖ₊₁)` that contain it, a point exactly on a fan diagonal being
/// assigned consistently to one side of it (the diagonal's sign is taken as
/// positive when zero). Non-zero winding is [`PolygonLocation::Inside`].
pub fn locate_with_oracle(
    n: usize,
    orient: impl Fn(usize, usize) -> Sign,
    collinear: impl Fn(usize, usize, usize) -> bool,
) -> PolygonLocation {
    if n < 3 {
        return PolygonLocation::Outside;
    }
    let signs: smallvec::SmallVec<[Sign; 8]> = (0..n).map(|i| orient(i, (i + 1) % n)).collect();
    // At a vertex: collinear with it and all others.
    for i in 0..n {
        let prev = (i + n - 1) % n;
        if signs[i] == Sign::Zero
            && signs[prev] == Sign::Zero
            && (0..n)
                .filter(|&j| j != i)
                .all(|j| orient(i, j) == Sign::Zero)
        {
            return PolygonLocation::OnVertex(i);
        }
    }
    // On an open edge.
    for i in 0..n {
        if signs[i] != Sign::Zero {
            continue;
        }
        let j = (i + 1) % n;
        if let Some(k) = (0..n).find(|&k| k != i && k != j && !collinear(i, j, k)) {
            let s1 = orient(j, k);
            if s1 != Sign::Zero && s1 == orient(k, i) {
                return PolygonLocation::OnEdge(i);
            }
        }
    }
    // Strictly inside or outside: signed count of fan triangles.
    let diagonal = |k: usize| match orient(0, k) {
        Sign::Zero => Sign::Positive,
        s => s,
    };
    let mut winding = 0i32;
    for k in 1..n - 1 {
        let s1 = diagonal(k);
        let s2 = signs[k];
        let s3 = -diagonal(k + 1);
        if s1 == s2 && s2 == s3 {
            winding += s1.as_i32();
        }
    }
    if winding != 0 {
        PolygonLocation::Inside
    } else {
        PolygonLocation::Outside
    }
}

/// Locates the point `q` relative to the 2-D polygon `points` (any simple
/// polygon, convex or not, either winding), exactly; see
/// [`locate_with_oracle`].
#[must_use]
pub fn locate_point_in_polygon(points: &[DVec2], q: DVec2) -> PolygonLocation {
    locate_with_oracle(
        points.len(),
        |i, j| orient2d(points[i], points[j], q),
        |i, j, k| orient2d(points[i], points[j], points[k]) == Sign::Zero,
    )
}

/// Whether the point `q`, assumed exactly coplanar with the triangle
/// `a, b, c`, lies in the closed triangle; decided exactly by projecting onto
/// an axis plane in which the triangle has non-zero area. A triangle of zero
/// area contains nothing.
#[must_use]
pub fn coplanar_point_in_closed_triangle(a: DVec3, b: DVec3, c: DVec3, q: DVec3) -> bool {
    for axis in [Axis::X, Axis::Y, Axis::Z] {
        let p = Projection {
            axis,
            flipped: false,
        };
        let (pa, pb, pc, pq) = (p.apply(a), p.apply(b), p.apply(c), p.apply(q));
        let s = orient2d(pa, pb, pc);
        if s == Sign::Zero {
            continue;
        }
        let bad = -s;
        return orient2d(pa, pb, pq) != bad
            && orient2d(pb, pc, pq) != bad
            && orient2d(pc, pa, pq) != bad;
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    #[test]
    fn projection_keeps_counter_clockwise() {
        for normal in [
            DVec3::X,
            DVec3::Y,
            DVec3::Z,
            -DVec3::X,
            -DVec3::Y,
            -DVec3::Z,
        ] {
            let p = Projection::along(normal);
            // A triangle counter-clockwise around `normal`.
            let (u, w) = (
                normal.any_orthonormal_vector(),
                normal.cross(normal.any_orthonormal_vector()),
            );
            let tri = [DVec3::ZERO, u, w].map(|q| p.apply(q));
            let expected = if p.flipped {
                Sign::Negative
            } else {
                Sign::Positive
            };
            assert_eq!(orient2d(tri[0], tri[1], tri[2]), expected, "{normal}");
        }
    }

    #[test]
    fn simple_and_non_simple_polygons() {
        let square = [v(0., 0.), v(1., 0.), v(1., 1.), v(0., 1.)];
        assert_eq!(find_self_intersection(&square), None);
        let bowtie = [v(0., 0.), v(1., 1.), v(1., 0.), v(0., 1.)];
        assert_eq!(find_self_intersection(&bowtie), Some((0, 2)));
        let l_shape = [
            v(0., 0.),
            v(2., 0.),
            v(2., 1.),
            v(1., 1.),
            v(1., 2.),
            v(0., 2.),
        ];
        assert_eq!(find_self_intersection(&l_shape), None);
        let folded = [v(0., 0.), v(2., 0.), v(1., 0.), v(1., 1.)];
        assert!(find_self_intersection(&folded).is_some());
        let touching = [v(0., 0.), v(2., 0.), v(2., 2.), v(1., 0.), v(0., 2.)];
        assert!(find_self_intersection(&touching).is_some());
    }

    #[test]
    fn a_point_touches_a_segment_only_on_it() {
        let (c, d) = (v(0., 0.), v(2., 1.));
        assert!(segments_touch(v(1., 0.5), v(1., 0.5), c, d));
        // In the segment's box but off its line.
        assert!(!segments_touch(v(1., 0.2), v(1., 0.2), c, d));
        assert!(!segments_touch(c, d, v(1., 0.2), v(1., 0.2)));
        assert!(segments_touch(c, c, c, c));
        assert!(!segments_touch(c, c, d, d));
    }

    #[test]
    fn a_projection_that_keeps_a_triangle_s_area() {
        let t = [DVec3::ZERO, DVec3::X, DVec3::Z];
        let p = Projection::of_triangle(t).map(|p| p.axis);
        assert_eq!(p, Some(Axis::Y));
        let flat = [DVec3::ZERO, DVec3::ONE, DVec3::splat(2.0)];
        assert_eq!(Projection::of_triangle(flat), None);
    }

    #[test]
    fn locate_point_in_non_convex_polygon() {
        let l_shape = [
            v(0., 0.),
            v(2., 0.),
            v(2., 1.),
            v(1., 1.),
            v(1., 2.),
            v(0., 2.),
        ];
        use PolygonLocation::*;
        assert_eq!(locate_point_in_polygon(&l_shape, v(0.5, 0.5)), Inside);
        assert_eq!(locate_point_in_polygon(&l_shape, v(0.5, 1.5)), Inside);
        assert_eq!(locate_point_in_polygon(&l_shape, v(1.5, 0.5)), Inside);
        assert_eq!(locate_point_in_polygon(&l_shape, v(1.5, 1.5)), Outside);
        assert_eq!(locate_point_in_polygon(&l_shape, v(1.0, 1.0)), OnVertex(3));
        assert_eq!(locate_point_in_polygon(&l_shape, v(1.5, 1.0)), OnEdge(2));
        assert_eq!(locate_point_in_polygon(&l_shape, v(3.0, 0.0)), Outside);
        assert_eq!(locate_point_in_polygon(&l_shape, v(1.0, 0.0)), OnEdge(0));
        // On a fan diagonal (0 -> 2, 0 -> 3 ...) inside the polygon.
        assert_eq!(locate_point_in_polygon(&l_shape, v(0.5, 0.5)), Inside);
        assert_eq!(locate_point_in_polygon(&l_shape, v(0.8, 0.8)), Inside);
        // Clockwise copy gives the same answers.
        let mut cw = l_shape;
        cw.reverse();
        assert_eq!(locate_point_in_polygon(&cw, v(0.8, 0.8)), Inside);
        assert_eq!(locate_point_in_polygon(&cw, v(1.5, 1.5)), Outside);
    }
}
