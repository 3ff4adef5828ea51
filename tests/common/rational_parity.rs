//! An exact point-in-polyhedron reference that shares no code with the
//! crate: ray parity in big-integer arithmetic.
//!
//! Every `f64` is a dyadic rational, so after scaling all coordinates of one
//! question by a common power of two they are integers, and every sign below
//! is the sign of an exact integer polynomial. A ray that meets an edge or a
//! vertex of a triangle, or lies in a triangle's plane, is a degenerate case;
//! it is not perturbed but thrown away and another direction (small integer
//! components from a fixed sequence) is tried. A point on a triangle is on
//! the boundary.

use num_bigint::BigInt;
use wingedge::glam::DVec3;

/// Where a point is, by the reference.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Class {
    /// Inside the solid.
    Inside,
    /// On a triangle (closed).
    Boundary,
    /// Outside the solid.
    Outside,
}

type Vec3 = [BigInt; 3];

/// Mantissa and exponent of a finite `f64`: `x = m · 2^e`.
fn split(x: f64) -> (i64, i32) {
    assert!(x.is_finite(), "the reference takes finite coordinates");
    if x == 0.0 {
        return (0, 0);
    }
    let bits = x.to_bits();
    let exponent = ((bits >> 52) & 0x7ff) as i32;
    let fraction = (bits & ((1 << 52) - 1)) as i64;
    let (m, e) = if exponent == 0 {
        (fraction, -1074)
    } else {
        (fraction | (1 << 52), exponent - 1075)
    };
    (if x < 0.0 { -m } else { m }, e)
}

fn scaled(x: f64, base: i32) -> BigInt {
    let (m, e) = split(x);
    BigInt::from(m) << ((e - base) as usize)
}

fn sub(a: &Vec3, b: &Vec3) -> Vec3 {
    [&a[0] - &b[0], &a[1] - &b[1], &a[2] - &b[2]]
}

fn cross(a: &Vec3, b: &Vec3) -> Vec3 {
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

fn dot(a: &Vec3, b: &Vec3) -> BigInt {
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

fn sign(x: &BigInt) -> i8 {
    match x.sign() {
        num_bigint::Sign::Minus => -1,
        num_bigint::Sign::NoSign => 0,
        num_bigint::Sign::Plus => 1,
    }
}

/// What one triangle does to the ray from the point.
enum Meets {
    Misses,
    Crosses,
    HoldsThePoint,
    Degenerate,
}

fn meets(p: &Vec3, d: &Vec3, tri: &[Vec3; 3]) -> Meets {
    let [a, b, c] = tri;
    let n = cross(&sub(b, a), &sub(c, a));
    let along = sign(&dot(&n, d));
    let height = sign(&dot(&n, &sub(a, p)));
    // Which side of each edge's plane through the ray's line.
    let (pa, pb, pc) = (sub(a, p), sub(b, p), sub(c, p));
    let sides = [
        sign(&dot(&cross(&pa, &pb), d)),
        sign(&dot(&cross(&pb, &pc), d)),
        sign(&dot(&cross(&pc, &pa), d)),
    ];
    let mixed = sides.contains(&1) && sides.contains(&-1);
    if along == 0 {
        if height != 0 {
            return Meets::Misses; // parallel, off the plane
        }
        // The point is in the plane, the ray too: inside the closed
        // triangle it is on the boundary; otherwise the ray runs in the plane.
        return if in_closed_triangle(p, tri, &n) {
            Meets::HoldsThePoint
        } else {
            Meets::Degenerate
        };
    }
    if height == 0 {
        return if mixed {
            Meets::Misses
        } else {
            Meets::HoldsThePoint
        };
    }
    if mixed || height != along {
        return Meets::Misses; // beside the triangle, or behind the point
    }
    if sides.contains(&0) {
        Meets::Degenerate // through an edge or a vertex
    } else {
        Meets::Crosses
    }
}

/// Whether a point of the triangle's plane lies in the closed triangle.
fn in_closed_triangle(p: &Vec3, [a, b, c]: &[Vec3; 3], n: &Vec3) -> bool {
    let s = [
        sign(&dot(&cross(&sub(b, a), &sub(p, a)), n)),
        sign(&dot(&cross(&sub(c, b), &sub(p, b)), n)),
        sign(&dot(&cross(&sub(a, c), &sub(p, c)), n)),
    ];
    !(s.contains(&1) && s.contains(&-1))
}

/// The class of `point` against a closed, consistently oriented triangle
/// mesh, exactly.
pub fn classify(triangles: &[[DVec3; 3]], point: DVec3) -> Class {
    let base = triangles
        .iter()
        .flatten()
        .chain(std::iter::once(&point))
        .flat_map(|v| v.to_array())
        .filter(|&x| x != 0.0)
        .map(|x| split(x).1)
        .min()
        .unwrap_or(0);
    let big = |v: DVec3| -> Vec3 { [scaled(v.x, base), scaled(v.y, base), scaled(v.z, base)] };
    let p = big(point);
    let tris: Vec<[Vec3; 3]> = triangles
        .iter()
        .map(|t| [big(t[0]), big(t[1]), big(t[2])])
        .collect();
    // Directions with small coprime-ish integer components, in a fixed order.
    let mut state: u64 = 0x9E37_79B9_7F4A_7C15;
    'direction: for _ in 0..64 {
        let mut component = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            BigInt::from((state % 2001) as i64 - 1000)
        };
        let d = [component(), component(), component()];
        if d.iter().all(|x| sign(x) == 0) {
            continue;
        }
        let mut crossings = 0usize;
        for tri in &tris {
            match meets(&p, &d, tri) {
                Meets::Misses => {}
                Meets::Crosses => crossings += 1,
                Meets::HoldsThePoint => return Class::Boundary,
                Meets::Degenerate => continue 'direction,
            }
        }
        return if crossings % 2 == 1 {
            Class::Inside
        } else {
            Class::Outside
        };
    }
    panic!("64 ray directions from {point} were all degenerate")
}
