//! An exact point-in-polyhedron reference that shares no code with the
//! crate: ray parity in big-integer arithmetic.
//!
//! Every `f64` is a dyadic rational, so after scaling all coordinates of one
//! question by a common power of two they are integers, and every sign below
//! is the sign of an exact integer polynomial. A ray that meets an edge or a
//! vertex of a triangle, or lies in a triangle's plane, is a degenerate case;
//! it is not perturbed but thrown away and another direction (the six axis
//! directions, then small integer components from a fixed sequence) is
//! tried. A point on a triangle is on the boundary. Triangles are culled by
//! a floating-point slab test on boxes widened by a few ulps (it may keep a
//! triangle the ray misses, never drop one it meets); only the survivors
//! get the big-integer test. The module that holds this one holds
//! `src/test_rng.rs` as `test_rng` too (`super::test_rng`).

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

/// Why a ray has no exact crossing count of its own.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Degenerate {
    /// The origin lies on a triangle.
    OnBoundary,
    /// The ray meets an edge or a vertex, or runs in a triangle's plane:
    /// its count depends on a tie rule.
    Tie,
}

/// Whether the ray may meet the box `[lo, hi]`: a floating-point slab test
/// on the box widened by a few ulps of its size, so that it never drops a
/// box the ray meets (it may keep one it misses; the exact test decides).
fn may_meet(lo: DVec3, hi: DVec3, origin: DVec3, direction: DVec3) -> bool {
    let pad = (hi - lo).max(lo.abs()).max(hi.abs()) * (16.0 * f64::EPSILON) + f64::MIN_POSITIVE;
    let (lo, hi) = (lo - pad, hi + pad);
    let (mut near, mut far) = (0.0f64, f64::INFINITY);
    for axis in 0..3 {
        let (o, d) = (origin[axis], direction[axis]);
        if d == 0.0 {
            if o < lo[axis] || o > hi[axis] {
                return false;
            }
            continue;
        }
        let (a, b) = ((lo[axis] - o) / d, (hi[axis] - o) / d);
        near = near.max(a.min(b));
        far = far.min(a.max(b));
    }
    near <= far * (1.0 + 16.0 * f64::EPSILON)
}

/// The exact number of triangles the open ray `origin + t · direction`,
/// `t > 0`, crosses through their interiors.
///
/// # Errors
///
/// [`Degenerate::OnBoundary`] when the origin lies on a triangle,
/// [`Degenerate::Tie`] when the ray meets an edge or a vertex or runs in a
/// triangle's plane.
pub fn crossings(
    triangles: &[[DVec3; 3]],
    origin: DVec3,
    direction: DVec3,
) -> Result<usize, Degenerate> {
    let candidates: Vec<&[DVec3; 3]> = triangles
        .iter()
        .filter(|t| {
            let lo = t[0].min(t[1]).min(t[2]);
            let hi = t[0].max(t[1]).max(t[2]);
            may_meet(lo, hi, origin, direction)
        })
        .collect();
    let base = candidates
        .iter()
        .flat_map(|t| t.iter())
        .chain(std::iter::once(&origin))
        .flat_map(|v| v.to_array())
        .filter(|&x| x != 0.0)
        .map(|x| split(x).1)
        .min()
        .unwrap_or(0);
    let big =
        |v: DVec3, base: i32| -> Vec3 { [scaled(v.x, base), scaled(v.y, base), scaled(v.z, base)] };
    // The direction's own scale does not matter: it enters every test
    // linearly.
    let d_base = direction
        .to_array()
        .into_iter()
        .filter(|&x| x != 0.0)
        .map(|x| split(x).1)
        .min()
        .unwrap_or(0);
    let p = big(origin, base);
    let d = big(direction, d_base);
    let mut count = 0;
    for t in candidates {
        match meets(&p, &d, &[big(t[0], base), big(t[1], base), big(t[2], base)]) {
            Meets::Misses => {}
            Meets::Crosses => count += 1,
            Meets::HoldsThePoint => return Err(Degenerate::OnBoundary),
            Meets::Degenerate => return Err(Degenerate::Tie),
        }
    }
    Ok(count)
}

/// The class of `point` against a closed, consistently oriented triangle
/// mesh, exactly: the parity of [`crossings`] along the first of the six
/// axis directions, then of small integer directions, that meets no edge
/// or vertex.
pub fn classify(triangles: &[[DVec3; 3]], point: DVec3) -> Class {
    let axes = [
        DVec3::X,
        DVec3::NEG_X,
        DVec3::Y,
        DVec3::NEG_Y,
        DVec3::Z,
        DVec3::NEG_Z,
    ];
    let mut bits = super::test_rng::bits(0x9E37_79B9_7F4A_7C15);
    let mut component = move || (bits() % 2001) as f64 - 1000.0;
    let others = std::iter::repeat_with(|| DVec3::new(component(), component(), component()))
        .filter(|d| *d != DVec3::ZERO)
        .take(64);
    for direction in axes.into_iter().chain(others) {
        match crossings(triangles, point, direction) {
            Ok(n) if n % 2 == 1 => return Class::Inside,
            Ok(_) => return Class::Outside,
            Err(Degenerate::OnBoundary) => return Class::Boundary,
            Err(Degenerate::Tie) => {}
        }
    }
    panic!("70 ray directions from {point} all met an edge or a vertex")
}
