//! Exact signs on implicit points: each predicate is written once over
//! [`Arithmetic`], evaluated first on intervals and, when the interval
//! contains zero, again in exact dyadic arithmetic.

use std::cmp::Ordering;

use glam::DVec3;

use crate::geom::dyadic::Dyadic;
use crate::geom::{Sign, orient2d, orient3d};

use super::arithmetic::Arithmetic;
use super::double_double::{DoubleDouble, rounded_quotient};
use super::point::{HasHomogeneous, Homogeneous, ImplicitPoint, cross, dot, kept_axes};

/// The product of two signs.
#[must_use]
pub(crate) fn times(a: Sign, b: Sign) -> Sign {
    match (a, b) {
        (Sign::Zero, _) | (_, Sign::Zero) => Sign::Zero,
        (x, y) if x == y => Sign::Positive,
        _ => Sign::Negative,
    }
}

/// The sign of `value · w` for homogeneous `w`: the sign of a quantity
/// computed on `X, Y, Z` and scaled by `w`.
fn unscaled<T: Arithmetic>(value: &T, w: &T) -> Option<Sign> {
    Some(times(value.sign()?, w.sign()?))
}

fn decide(filter: impl FnOnce() -> Option<Sign>, exact: impl FnOnce() -> Option<Sign>) -> Sign {
    if let Some(sign) = filter() {
        return sign;
    }
    // Exact arithmetic always knows the sign.
    exact().unwrap_or(Sign::Zero)
}

fn side_in<T: Arithmetic>(plane: [DVec3; 3], p: &Homogeneous<T>) -> Option<Sign> {
    let [a, b, c] = plane.map(|v| [T::of(v.x), T::of(v.y), T::of(v.z)]);
    let sub = |u: &[T; 3], v: &[T; 3]| [u[0].minus(&v[0]), u[1].minus(&v[1]), u[2].minus(&v[2])];
    let normal = cross(&sub(&b, &a), &sub(&c, &a));
    // n · (P − a·w), then divided by the sign of w.
    let offset = [
        p.xyz[0].minus(&a[0].times(&p.w)),
        p.xyz[1].minus(&a[1].times(&p.w)),
        p.xyz[2].minus(&a[2].times(&p.w)),
    ];
    unscaled(&dot(&normal, &offset), &p.w)
}

/// The side of the plane through `plane` (counter-clockwise seen from its
/// positive side) on which `p` lies: `Positive` on the side the normal
/// `(b − a) × (c − a)` points to, as [`orient3d`]`(a, b, c, p)`.
#[must_use]
pub(crate) fn side_of_plane(plane: [DVec3; 3], p: &impl HasHomogeneous) -> Sign {
    decide(
        || side_in(plane, &p.filter()),
        || side_in::<Dyadic>(plane, &p.exact()),
    )
}

/// The side of the plane through `plane` on which `p` lies, exactly:
/// `Positive` on the side the normal `(b − a) × (c − a)` points to, as
/// [`orient3d`]`(a, b, c, p)` (which it takes when the point is explicit).
#[must_use]
pub fn point_side_of_plane(plane: [DVec3; 3], p: &ImplicitPoint) -> Sign {
    match p {
        ImplicitPoint::Explicit(v) => orient3d(plane[0], plane[1], plane[2], *v),
        _ => side_of_plane(plane, p),
    }
}

fn orient2d_in<T: Arithmetic>([a, b, c]: [Homogeneous<T>; 3], axis: u8) -> Option<Sign> {
    let (u, v) = kept_axes(axis);
    // det [[au, av, aw], [bu, bv, bw], [cu, cv, cw]]
    let minor = |p: &Homogeneous<T>, q: &Homogeneous<T>| {
        [
            p.xyz[v].times(&q.w).minus(&p.w.times(&q.xyz[v])),
            p.w.times(&q.xyz[u]).minus(&p.xyz[u].times(&q.w)),
            p.xyz[u].times(&q.xyz[v]).minus(&p.xyz[v].times(&q.xyz[u])),
        ]
    };
    let m = minor(&b, &c);
    let det = a.xyz[u]
        .times(&m[0])
        .plus(&a.xyz[v].times(&m[1]))
        .plus(&a.w.times(&m[2]));
    let weight = a.w.times(&b.w).times(&c.w);
    unscaled(&det, &weight)
}

/// The orientation of `a, b, c` in the projection that drops coordinate
/// `axis` (the kept coordinates in cyclic order, see `kept_axes`):
/// `Positive` when counter-clockwise.
#[must_use]
pub(crate) fn orient2d_projected(
    a: &impl HasHomogeneous,
    b: &impl HasHomogeneous,
    c: &impl HasHomogeneous,
    axis: u8,
) -> Sign {
    decide(
        || orient2d_in([a.filter(), b.filter(), c.filter()], axis),
        || orient2d_in::<Dyadic>([a.exact(), b.exact(), c.exact()], axis),
    )
}

/// The orientation of three points in the projection that drops
/// coordinate `axis` (the other two in cyclic order: `y, z` for `x`, `z, x`
/// for `y`, `x, y` for `z`), exactly: `Positive` when counter-clockwise; by
/// [`orient2d`] when all three are explicit.
#[must_use]
pub fn orient2d_points(a: &ImplicitPoint, b: &ImplicitPoint, c: &ImplicitPoint, axis: u8) -> Sign {
    if let (Some(a), Some(b), Some(c)) = (a.explicit(), b.explicit(), c.explicit()) {
        let (u, v) = kept_axes(axis);
        let flat = |p: DVec3| glam::DVec2::new(p[u], p[v]);
        return orient2d(flat(a), flat(b), flat(c));
    }
    orient2d_projected(a, b, c, axis)
}

fn compare_in<T: Arithmetic>(a: &Homogeneous<T>, b: &Homogeneous<T>, axis: usize) -> Option<Sign> {
    let difference = a.xyz[axis].times(&b.w).minus(&b.xyz[axis].times(&a.w));
    unscaled(&difference, &a.w.times(&b.w))
}

/// The exact order of the coordinates `axis` of `a` and `b`.
#[must_use]
pub(crate) fn compare_axis(
    a: &impl HasHomogeneous,
    b: &impl HasHomogeneous,
    axis: usize,
) -> Ordering {
    // Coordinates the definitions give (a point made on a segment whose
    // ends share it): compared as they are, where they may well be equal
    // and the filter could not tell.
    if let (Some(x), Some(y)) = (a.known_coordinate(axis), b.known_coordinate(axis)) {
        return x.partial_cmp(&y).unwrap_or(Ordering::Equal);
    }
    decide(
        || compare_in(&a.filter(), &b.filter(), axis),
        || compare_in::<Dyadic>(&a.exact(), &b.exact(), axis),
    )
    .ordering()
}

/// The exact lexicographic order (`x`, then `y`, then `z`) of two points:
/// `Equal` exactly when they are the same point.
#[must_use]
pub fn compare_points(a: &ImplicitPoint, b: &ImplicitPoint) -> Ordering {
    if let (Some(a), Some(b)) = (a.explicit(), b.explicit()) {
        // By value: −0 and +0 are the same coordinate (inputs are finite).
        let by = |x: f64, y: f64| x.partial_cmp(&y).unwrap_or(Ordering::Equal);
        return by(a.x, b.x).then(by(a.y, b.y)).then(by(a.z, b.z));
    }
    (0..3)
        .map(|axis| compare_axis(a, b, axis))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}

/// The point's coordinates, each rounded to the nearest `f64` (ties to
/// even).
#[must_use]
pub fn rounded(p: &ImplicitPoint) -> DVec3 {
    if let Some(v) = p.explicit() {
        return v;
    }
    rounded_point(p)
}

/// [`rounded`] for any point with exact coordinates: certified by the
/// double-double stage where it can (almost always), else rounded from the
/// exact coordinates; the same `f64`s either way.
#[must_use]
pub(crate) fn rounded_point(p: &impl HasHomogeneous) -> DVec3 {
    if p.double_double_safe() {
        let h = p.homogeneous::<DoubleDouble>();
        let coordinate = |i: usize| rounded_quotient(&h.xyz[i], &h.w);
        if let (Some(x), Some(y), Some(z)) = (coordinate(0), coordinate(1), coordinate(2)) {
            return DVec3::new(x, y, z);
        }
    }
    let exact = p.exact();
    DVec3::new(
        exact.xyz[0].quotient_to_f64(&exact.w),
        exact.xyz[1].quotient_to_f64(&exact.w),
        exact.xyz[2].quotient_to_f64(&exact.w),
    )
}

/// Where the ray `p + t·(1, 0, 0)`, `t > 0`, stands against a triangle.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum XRayCrossing {
    /// The ray crosses the triangle (once).
    Crosses,
    /// The ray misses it.
    Misses,
    /// `p` lies on the triangle.
    Contains,
}

/// Whether the `+x` ray from `p` crosses the triangle `tri`, exactly, with
/// ties broken by Simulation of Simplicity: `p`'s `(y, z)` moved
/// symbolically to `(y + ε, z + ε²)`, so a ray through an edge or vertex
/// crosses exactly one of the triangles around it and a closed surface is
/// crossed an odd number of times exactly when `p` is inside. Triangles
/// parallel to the ray (zero area in the `yz` projection) are never
/// crossed. A `p` on the closed triangle (whatever its orientation) is
/// reported as [`XRayCrossing::Contains`].
#[must_use]
pub(crate) fn x_ray_crossing<P: HasHomogeneous>(p: &P, tri: [DVec3; 3]) -> XRayCrossing {
    let side = side_of_plane(tri, p);
    let point = |v: DVec3| ImplicitPoint::Explicit(v);
    if side == Sign::Zero {
        // In the plane: on the closed triangle, or beside it (the ray then
        // meets the plane only at p).
        for axis in 0..3u8 {
            let facing = orient2d_projected(&point(tri[0]), &point(tri[1]), &point(tri[2]), axis);
            if facing == Sign::Zero {
                continue;
            }
            let on = (0..3).all(|k| {
                let s = orient2d_projected(&point(tri[k]), &point(tri[(k + 1) % 3]), p, axis);
                s == Sign::Zero || s == facing
            });
            return if on {
                XRayCrossing::Contains
            } else {
                XRayCrossing::Misses
            };
        }
        return XRayCrossing::Misses;
    }
    let yz = |v: DVec3| glam::DVec2::new(v.y, v.z);
    let facing = orient2d(yz(tri[0]), yz(tri[1]), yz(tri[2]));
    if facing == Sign::Zero {
        return XRayCrossing::Misses;
    }
    // The projected triangle counter-clockwise.
    let [a, b, c] = if facing == Sign::Positive {
        tri
    } else {
        [tri[0], tri[2], tri[1]]
    };
    for (s, e) in [(a, b), (b, c), (c, a)] {
        let exact = orient2d_projected(&point(s), &point(e), p, 0);
        let sign = if exact != Sign::Zero {
            exact
        } else if s.z != e.z {
            // The perturbation's ε term: −(e.z − s.z).
            Sign::of(s.z - e.z)
        } else {
            Sign::of(e.y - s.y)
        };
        if sign != Sign::Positive {
            return XRayCrossing::Misses;
        }
    }
    // Inside the projection: in front when p is behind the plane as seen
    // along +x, i.e. the plane side of p is opposite to the normal's x.
    if side != facing {
        XRayCrossing::Crosses
    } else {
        XRayCrossing::Misses
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn edge_plane(p: DVec3, q: DVec3, plane: [DVec3; 3]) -> ImplicitPoint {
        ImplicitPoint::EdgePlane { p, q, plane }
    }

    /// A constructed point lies exactly on its plane and on its segment's
    /// line, although its rounded coordinates do not.
    #[test]
    fn an_edge_plane_point_is_on_its_plane() {
        let plane = [
            DVec3::new(0.1, 0.0, 0.3),
            DVec3::new(1.0, 0.2, 0.7),
            DVec3::new(0.3, 1.0, 0.1),
        ];
        let point = edge_plane(DVec3::new(0.4, 0.4, -1.0), DVec3::new(0.5, 0.3, 2.0), plane);
        assert_eq!(side_of_plane(plane, &point), Sign::Zero);
        // Collinear with its segment in every projection.
        let (p, q) = (
            ImplicitPoint::Explicit(DVec3::new(0.4, 0.4, -1.0)),
            ImplicitPoint::Explicit(DVec3::new(0.5, 0.3, 2.0)),
        );
        for axis in 0..3 {
            assert_eq!(orient2d_points(&p, &q, &point, axis), Sign::Zero);
        }
    }

    /// The same point made two ways compares equal; −0 and +0 too.
    #[test]
    fn one_point_made_two_ways_is_equal() {
        let z0 = [
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
        ];
        let crossing = edge_plane(DVec3::new(0.25, 0.5, -1.0), DVec3::new(0.25, 0.5, 3.0), z0);
        let known = ImplicitPoint::Explicit(DVec3::new(0.25, 0.5, 0.0));
        assert_eq!(compare_points(&crossing, &known), Ordering::Equal);
        assert_eq!(crossing.simplified(), known);
        let tilted = edge_plane(
            DVec3::new(-0.75, -1.5, -2.0),
            DVec3::new(1.25, 2.5, 2.0),
            z0,
        );
        assert_eq!(compare_points(&tilted, &known), Ordering::Equal);
        let negative = ImplicitPoint::Explicit(DVec3::new(0.25, 0.5, -0.0));
        assert_eq!(compare_points(&negative, &known), Ordering::Equal);
        let beside = ImplicitPoint::Explicit(DVec3::new(0.25f64.next_up(), 0.5, 0.0));
        assert_eq!(compare_points(&tilted, &beside), Ordering::Less);
    }

    /// Three tilted planes meet in a point that lies exactly on each of
    /// them and equals the same point made as an edge–plane point; planes
    /// that share a coordinate give it explicitly.
    #[test]
    fn three_planes_meet_exactly_on_each() {
        let planes = [
            [
                DVec3::new(0.1, 0.0, 0.3),
                DVec3::new(1.0, 0.2, 0.7),
                DVec3::new(0.3, 1.0, 0.1),
            ],
            [
                DVec3::new(0.0, 0.7, 0.0),
                DVec3::new(0.9, 0.1, 0.2),
                DVec3::new(0.2, 0.3, 1.1),
            ],
            [
                DVec3::new(0.6, 0.0, 0.0),
                DVec3::new(0.1, 0.9, 0.3),
                DVec3::new(0.4, 0.2, 1.3),
            ],
        ];
        let point = ImplicitPoint::ThreePlanes {
            planes: Box::new(planes),
        };
        for plane in planes {
            assert_eq!(side_of_plane(plane, &point), Sign::Zero);
        }
        let beside = ImplicitPoint::Explicit(rounded(&point) + DVec3::splat(1e-9));
        assert_ne!(side_of_plane(planes[0], &beside), Sign::Zero);
        // Planes x = 0.25, y = 0.5 and a tilted one: x and y are known.
        let x = [
            DVec3::new(0.25, 0.0, 0.0),
            DVec3::new(0.25, 1.0, 0.0),
            DVec3::new(0.25, 0.0, 1.0),
        ];
        let y = [
            DVec3::new(0.0, 0.5, 0.0),
            DVec3::new(0.0, 0.5, 1.0),
            DVec3::new(1.0, 0.5, 0.0),
        ];
        let z = [
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        let corner = ImplicitPoint::ThreePlanes {
            planes: Box::new([x, y, z]),
        };
        assert_eq!(
            compare_points(
                &corner,
                &ImplicitPoint::Explicit(DVec3::new(0.25, 0.5, 0.5))
            ),
            Ordering::Equal
        );
        // The line of planes x and y, met by the plane z, as an edge–plane
        // point.
        let along = edge_plane(DVec3::new(0.25, 0.5, -3.0), DVec3::new(0.25, 0.5, 5.0), z);
        assert_eq!(compare_points(&corner, &along), Ordering::Equal);
        assert_eq!(
            corner.simplified(),
            ImplicitPoint::ThreePlanes {
                planes: Box::new([x, y, z])
            }
        );
    }

    /// A point on a triangle parallel to the ray is on it, not beside it;
    /// a ray through a shared edge crosses exactly one of its triangles.
    #[test]
    fn x_rays_see_points_on_parallel_faces_and_cross_edges_once() {
        let top = [
            DVec3::new(0.0, 0.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
            DVec3::new(0.0, 1.0, 1.0),
        ];
        let on = ImplicitPoint::Explicit(DVec3::new(0.25, 0.25, 1.0));
        assert_eq!(x_ray_crossing(&on, top), XRayCrossing::Contains);
        let below = ImplicitPoint::Explicit(DVec3::new(0.25, 0.25, 0.5));
        assert_eq!(x_ray_crossing(&below, top), XRayCrossing::Misses);
        // Two triangles of the plane x = 1 sharing the edge y = z.
        let first = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 1.0, 1.0),
        ];
        let second = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 1.0),
            DVec3::new(1.0, 0.0, 1.0),
        ];
        let through_edge = ImplicitPoint::Explicit(DVec3::new(0.0, 0.5, 0.5));
        let crossings = [first, second]
            .iter()
            .filter(|&&t| x_ray_crossing(&through_edge, t) == XRayCrossing::Crosses)
            .count();
        assert_eq!(crossings, 1);
    }
}
