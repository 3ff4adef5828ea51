//! Exact orientation predicates.
//!
//! Every sign decision in wingedge goes through this module. Each predicate
//! first evaluates its determinant in plain `f64` together with a forward
//! error bound (Shewchuk's semi-static filter, "Adaptive Precision
//! Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997).
//! When the magnitude of the rounded determinant exceeds the bound its sign is
//! certain; otherwise the predicate falls back to the adaptive exact
//! evaluation of the `robust` crate, which returns the sign of the exact
//! determinant of the input coordinates. No epsilon ever decides a sign.
//!
//! Both stages hold for every finite input, not only for coordinates of
//! moderate size: the filters allow for roundings in the subnormal range
//! ([`UNDERFLOW`]) and certify nothing on overflow, and inputs outside the
//! range where expansion arithmetic is exact (about `1e-75 ..= 1e75`; see
//! `dyadic`) are decided by exact big-integer arithmetic instead.
//!
//! The number of fallbacks taken by the current thread is counted
//! ([`exact_fallbacks`]) so that callers can report how often the slow path
//! was needed.

use std::cell::Cell;

use glam::{DVec2, DVec3};

use super::dyadic::{Dyadic, det2_sign, det3_sign, in_incircle_range, in_safe_range};

/// The sign of an exactly evaluated quantity.
///
/// `Zero` means the exact value is zero (for example, four points that are
/// exactly coplanar), never "small".
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Sign {
    /// Strictly negative.
    Negative,
    /// Exactly zero.
    Zero,
    /// Strictly positive.
    Positive,
}

impl Sign {
    /// The order this sign says (of a difference `a − b`: how `a` compares
    /// with `b`).
    #[must_use]
    pub fn ordering(self) -> std::cmp::Ordering {
        match self {
            Sign::Negative => std::cmp::Ordering::Less,
            Sign::Zero => std::cmp::Ordering::Equal,
            Sign::Positive => std::cmp::Ordering::Greater,
        }
    }

    /// The sign of `value`; `NaN` is treated as [`Sign::Zero`].
    #[must_use]
    pub fn of(value: f64) -> Sign {
        if value > 0.0 {
            Sign::Positive
        } else if value < 0.0 {
            Sign::Negative
        } else {
            Sign::Zero
        }
    }

    /// The opposite sign (`Zero` stays `Zero`).
    #[must_use]
    pub fn reversed(self) -> Sign {
        match self {
            Sign::Negative => Sign::Positive,
            Sign::Zero => Sign::Zero,
            Sign::Positive => Sign::Negative,
        }
    }

    /// The sign as `-1`, `0` or `1`.
    #[must_use]
    pub fn as_i32(self) -> i32 {
        match self {
            Sign::Negative => -1,
            Sign::Zero => 0,
            Sign::Positive => 1,
        }
    }
}

impl std::ops::Neg for Sign {
    type Output = Sign;
    fn neg(self) -> Sign {
        self.reversed()
    }
}

impl std::ops::Mul for Sign {
    type Output = Sign;
    fn mul(self, rhs: Sign) -> Sign {
        match (self, rhs) {
            (Sign::Zero, _) | (_, Sign::Zero) => Sign::Zero,
            (a, b) if a == b => Sign::Positive,
            _ => Sign::Negative,
        }
    }
}

thread_local! {
    static FALLBACKS: Cell<u64> = const { Cell::new(0) };
    static TIE_BREAKS: Cell<u64> = const { Cell::new(0) };
}

/// How many times the current thread has broken an exact tie by symbolic
/// perturbation (a ray through an edge or a vertex, a query point whose
/// projection lies on a projected edge) since the thread started. The
/// generic case never pays for perturbation, so this counts exactly the
/// degenerate configurations met.
#[must_use]
pub fn tie_breaks() -> u64 {
    TIE_BREAKS.with(Cell::get)
}

/// Counts one symbolic-perturbation tie-break on the current thread.
pub(crate) fn count_tie_break() {
    TIE_BREAKS.with(|c| c.set(c.get() + 1));
}

/// How many times predicates on the current thread have fallen back to exact
/// arithmetic since the thread started (or since [`reset_exact_fallbacks`]).
#[must_use]
pub fn exact_fallbacks() -> u64 {
    FALLBACKS.with(Cell::get)
}

/// Resets the current thread's fallback counter to zero.
pub fn reset_exact_fallbacks() {
    FALLBACKS.with(|c| c.set(0));
}

pub(crate) fn count_fallback() {
    FALLBACKS.with(|c| c.set(c.get() + 1));
}

/// Relative error bound of the rounded 2-D orientation determinant
/// (Shewchuk's `ccwerrboundA`): `(3 + 16 ε) ε` with `ε = 2^-53`.
const ORIENT2D_BOUND: f64 = (3.0 + 16.0 * HALF_EPSILON) * HALF_EPSILON;
/// Relative error bound of the rounded 3-D orientation determinant
/// (Shewchuk's `o3derrboundA`): `(7 + 56 ε) ε` with `ε = 2^-53`.
const ORIENT3D_BOUND: f64 = (7.0 + 56.0 * HALF_EPSILON) * HALF_EPSILON;
/// Half a unit in the last place of 1.0: the unit round-off of `f64`.
const HALF_EPSILON: f64 = f64::EPSILON / 2.0;

/// `2⁻¹⁰⁰⁰`: the absolute allowance a filter adds to its bound for roundings
/// in the subnormal range.
///
/// Shewchuk's relative bounds assume that nothing underflows. With gradual
/// underflow a rounded product is `xy(1 + δ) + η` with `|δ| ≤ ε` and
/// `|η| ≤ 2⁻¹⁰⁷⁵`, and a sum or difference whose result is subnormal is
/// exact. So the error of a filter's determinant exceeds the relative bound
/// by at most the `η` of its products carried to the result: two for a
/// 2×2 determinant (`2η(1 + ε)`), and for a 3×3 one expanded along its
/// first row `r` the two of each minor times `|rᵢ|` plus one per outer
/// product — at most `(1 + ε)³ · 2η · Σ|rᵢ| + 3η(1 + ε)²`. Each filter adds
/// `UNDERFLOW` (2×2, dot products) or `UNDERFLOW · (Σ|rᵢ| + 1)` (3×3), far
/// more than that. The allowance is a normal number on purpose: a
/// subnormal one would make every filter evaluation multiply or add a
/// subnormal, which x86 processors do slowly, while the only cost of the
/// larger allowance is that determinants below about `1e-301` go to the
/// exact path. Overflow needs no allowance: it makes the determinant or the bound
/// infinite or NaN, which certifies nothing, and the exact path decides.
pub(crate) const UNDERFLOW: f64 = 1.0
    / (1u128 << 125) as f64
    / (1u128 << 125) as f64
    / (1u128 << 125) as f64
    / (1u128 << 125) as f64
    / (1u128 << 125) as f64
    / (1u128 << 125) as f64
    / (1u128 << 125) as f64
    / (1u128 << 125) as f64;

/// Orientation of three points in the plane.
///
/// Returns [`Sign::Positive`] when `a`, `b`, `c` turn counter-clockwise (the
/// usual mathematical orientation, `y` up), [`Sign::Negative`] when they turn
/// clockwise, and [`Sign::Zero`] when they are exactly collinear (this
/// includes coincident points). The sign is that of the exact determinant
///
/// ```text
/// | ax - cx   ay - cy |
/// | bx - cx   by - cy |
/// ```
///
/// Non-finite input gives an unspecified sign (never a panic).
#[must_use]
#[inline]
pub fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> Sign {
    let left = (a.x - c.x) * (b.y - c.y);
    let right = (a.y - c.y) * (b.x - c.x);
    let det = left - right;
    let bound = ORIENT2D_BOUND * (left.abs() + right.abs()) + UNDERFLOW;
    if det > bound || -det > bound {
        return Sign::of(det);
    }
    exact_orient2d(a, b, c)
}

#[cold]
#[inline(never)]
fn exact_orient2d(a: DVec2, b: DVec2, c: DVec2) -> Sign {
    count_fallback();
    // Three points on one axis-parallel line (a polygon edge along an axis,
    // a ray in an axis-aligned face): a column of zero differences, so the
    // determinant is exactly zero.
    if (a.x == c.x && b.x == c.x) || (a.y == c.y && b.y == c.y) {
        return Sign::Zero;
    }
    if !in_safe_range(&[a.x, a.y, b.x, b.y, c.x, c.y]) {
        let d = Dyadic::difference;
        return det2_sign(&d(a.x, c.x), &d(a.y, c.y), &d(b.x, c.x), &d(b.y, c.y));
    }
    let p = |v: DVec2| robust::Coord { x: v.x, y: v.y };
    Sign::of(robust::orient2d(p(a), p(b), p(c)))
}

/// Orientation of a point `d` against the oriented plane through `a`, `b`, `c`.
///
/// Returns [`Sign::Positive`] when `d` lies on the side of the plane from
/// which `a`, `b`, `c` are seen counter-clockwise, that is the side the normal
/// `(b − a) × (c − a)` points to. With wingedge's convention (faces wound
/// counter-clockwise seen from outside) `Positive` therefore means "outside
/// the face", `Negative` "inside" and [`Sign::Zero`] "exactly coplanar"
/// (which includes degenerate triangles `a`, `b`, `c`). This is the negation
/// of Shewchuk's `orient3d` sign convention. The sign is that of the exact
/// determinant
///
/// ```text
/// | bx - ax   by - ay   bz - az |
/// | cx - ax   cy - ay   cz - az |
/// | dx - ax   dy - ay   dz - az |
/// ```
///
/// Non-finite input gives an unspecified sign (never a panic).
#[must_use]
#[inline(always)]
pub fn orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    // Shewchuk's layout: differences against d, determinant sign negated.
    let ad = a - d;
    let bd = b - d;
    let cd = c - d;
    let bdxcdy = bd.x * cd.y;
    let cdxbdy = cd.x * bd.y;
    let cdxady = cd.x * ad.y;
    let adxcdy = ad.x * cd.y;
    let adxbdy = ad.x * bd.y;
    let bdxady = bd.x * ad.y;
    let det = ad.z * (bdxcdy - cdxbdy) + bd.z * (cdxady - adxcdy) + cd.z * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * ad.z.abs()
        + (cdxady.abs() + adxcdy.abs()) * bd.z.abs()
        + (adxbdy.abs() + bdxady.abs()) * cd.z.abs();
    let bound =
        ORIENT3D_BOUND * permanent + UNDERFLOW * (ad.z.abs() + bd.z.abs() + cd.z.abs() + 1.0);
    if det > bound || -det > bound {
        // Shewchuk's det is positive when d is below; ours is the opposite.
        return Sign::of(-det);
    }
    exact_orient3d(a, b, c, d)
}

#[cold]
#[inline(never)]
fn exact_orient3d(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> Sign {
    count_fallback();
    // Four points in one axis-aligned plane: exactly coplanar (a column of
    // zero differences).
    if (0..3).any(|k| a[k] == d[k] && b[k] == d[k] && c[k] == d[k]) {
        return Sign::Zero;
    }
    let coordinates = [a, b, c, d].map(|p| p.to_array());
    if !in_safe_range(coordinates.as_flattened()) {
        // det[b − a, c − a, d − a]: our sign convention directly.
        let row = |p: DVec3| [0, 1, 2].map(|k| Dyadic::difference(p[k], a[k]));
        return det3_sign(&[row(b), row(c), row(d)]);
    }
    let p = |v: DVec3| robust::Coord3D {
        x: v.x,
        y: v.y,
        z: v.z,
    };
    Sign::of(-robust::orient3d(p(a), p(b), p(c), p(d)))
}

/// Relative error bound of the rounded in-circle determinant (Shewchuk's
/// `iccerrboundA`): `(10 + 96 ε) ε` with `ε = 2^-53`.
const INCIRCLE_BOUND: f64 = (10.0 + 96.0 * HALF_EPSILON) * HALF_EPSILON;

/// Whether `d` lies inside the circle through `a`, `b`, `c`.
///
/// For `a`, `b`, `c` counter-clockwise ([`orient2d`] positive) returns
/// [`Sign::Positive`] when `d` lies strictly inside their circumcircle,
/// [`Sign::Negative`] when strictly outside and [`Sign::Zero`] when the four
/// points are exactly cocircular; a clockwise `a`, `b`, `c` reverses the sign.
/// This is Shewchuk's `incircle` convention (1997). The sign is that of the
/// exact determinant
///
/// ```text
/// | ax - dx   ay - dy   (ax - dx)² + (ay - dy)² |
/// | bx - dx   by - dy   (bx - dx)² + (by - dy)² |
/// | cx - dx   cy - dy   (cx - dx)² + (cy - dy)² |
/// ```
///
/// evaluated with a semi-static filter, then the adaptive expansions of the
/// `robust` crate, then (for coordinates far from 1, where a degree-4
/// expansion could lose bits) exact big-integer arithmetic.
///
/// Non-finite input gives an unspecified sign (never a panic).
#[must_use]
pub fn incircle(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> Sign {
    let (ad, bd, cd) = (a - d, b - d, c - d);
    let bdxcdy = bd.x * cd.y;
    let cdxbdy = cd.x * bd.y;
    let alift = ad.x * ad.x + ad.y * ad.y;
    let cdxady = cd.x * ad.y;
    let adxcdy = ad.x * cd.y;
    let blift = bd.x * bd.x + bd.y * bd.y;
    let adxbdy = ad.x * bd.y;
    let bdxady = bd.x * ad.y;
    let clift = cd.x * cd.x + cd.y * cd.y;
    let det = alift * (bdxcdy - cdxbdy) + blift * (cdxady - adxcdy) + clift * (adxbdy - bdxady);
    let permanent = (bdxcdy.abs() + cdxbdy.abs()) * alift
        + (cdxady.abs() + adxcdy.abs()) * blift
        + (adxbdy.abs() + bdxady.abs()) * clift;
    let bound = INCIRCLE_BOUND * permanent + UNDERFLOW * (alift + blift + clift + 1.0);
    if det > bound || -det > bound {
        return Sign::of(det);
    }
    exact_incircle(a, b, c, d)
}

#[cold]
#[inline(never)]
fn exact_incircle(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> Sign {
    count_fallback();
    if !in_incircle_range(&[a.x, a.y, b.x, b.y, c.x, c.y, d.x, d.y]) {
        let row = |p: DVec2| {
            let x = Dyadic::difference(p.x, d.x);
            let y = Dyadic::difference(p.y, d.y);
            let lift = &(&x * &x) + &(&y * &y);
            [x, y, lift]
        };
        return det3_sign(&[row(a), row(b), row(c)]);
    }
    let p = |v: DVec2| robust::Coord { x: v.x, y: v.y };
    Sign::of(robust::incircle(p(a), p(b), p(c), p(d)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn v2(x: f64, y: f64) -> DVec2 {
        DVec2::new(x, y)
    }

    #[test]
    fn orient2d_counter_clockwise_is_positive() {
        assert_eq!(orient2d(v2(0., 0.), v2(1., 0.), v2(0., 1.)), Sign::Positive);
        assert_eq!(orient2d(v2(0., 0.), v2(0., 1.), v2(1., 0.)), Sign::Negative);
        assert_eq!(orient2d(v2(0., 0.), v2(1., 1.), v2(2., 2.)), Sign::Zero);
        assert_eq!(orient2d(v2(3., 3.), v2(3., 3.), v2(3., 3.)), Sign::Zero);
    }

    #[test]
    fn orient2d_decides_nearly_collinear_points_exactly() {
        // The classic example: points on the line y = x near 0.5 with one
        // coordinate nudged by an ulp. Naive evaluation gets many wrong.
        let base = 0.5;
        let ulp = f64::EPSILON / 2.0; // one ulp of 0.5
        let a = v2(12.0, 12.0);
        let b = v2(24.0, 24.0);
        assert_eq!(orient2d(v2(base, base), a, b), Sign::Zero);
        assert_eq!(orient2d(v2(base, base + ulp), a, b), Sign::Positive);
        assert_eq!(orient2d(v2(base + ulp, base), a, b), Sign::Negative);
    }

    #[test]
    fn orient3d_positive_on_the_normal_side() {
        let a = DVec3::new(0., 0., 0.);
        let b = DVec3::new(1., 0., 0.);
        let c = DVec3::new(0., 1., 0.);
        assert_eq!(orient3d(a, b, c, DVec3::new(0.2, 0.2, 1.)), Sign::Positive);
        assert_eq!(orient3d(a, b, c, DVec3::new(0.2, 0.2, -1.)), Sign::Negative);
        assert_eq!(orient3d(a, b, c, DVec3::new(5., -7., 0.)), Sign::Zero);
    }

    #[test]
    fn orient3d_decides_one_ulp_off_the_plane_and_counts_the_fallback() {
        let a = DVec3::new(1e9, 0.0, 1.0);
        let b = DVec3::new(1e9 + 3.0, 1.0, 1.0);
        let c = DVec3::new(1e9 + 1.0, 5.0, 1.0);
        reset_exact_fallbacks();
        assert_eq!(
            orient3d(a, b, c, DVec3::new(1e9 + 0.5, 0.5, 1.0)),
            Sign::Zero
        );
        let above = 1.0 + f64::EPSILON;
        let below = 1.0 - f64::EPSILON / 2.0;
        assert_eq!(
            orient3d(a, b, c, DVec3::new(1e9 + 0.5, 0.5, above)),
            Sign::Positive
        );
        assert_eq!(
            orient3d(a, b, c, DVec3::new(1e9 + 0.5, 0.5, below)),
            Sign::Negative
        );
        assert!(exact_fallbacks() >= 1);
    }

    #[test]
    fn orient3d_agrees_with_robust_on_random_input() {
        // Compares the filter with the exact predicate on well-separated and
        // on nearly coplanar configurations.
        let mut next = crate::test_rng::uniform(0x9E37_79B9_7F4A_7C15);
        for i in 0..20_000 {
            let a = DVec3::new(next(), next(), next());
            let b = DVec3::new(next(), next(), next());
            let c = DVec3::new(next(), next(), next());
            let mut d = DVec3::new(next(), next(), next());
            if i % 2 == 0 {
                // Snap d onto the plane (rounded, so only nearly coplanar).
                let n = (b - a).cross(c - a).normalize();
                d -= n * n.dot(d - a);
            }
            let exact = Sign::of(-robust::orient3d(
                robust::Coord3D {
                    x: a.x,
                    y: a.y,
                    z: a.z,
                },
                robust::Coord3D {
                    x: b.x,
                    y: b.y,
                    z: b.z,
                },
                robust::Coord3D {
                    x: c.x,
                    y: c.y,
                    z: c.z,
                },
                robust::Coord3D {
                    x: d.x,
                    y: d.y,
                    z: d.z,
                },
            ));
            assert_eq!(orient3d(a, b, c, d), exact);
        }
    }

    #[test]
    fn incircle_inside_outside_and_cocircular() {
        let (a, b, c) = (v2(0., 0.), v2(2., 0.), v2(0., 2.));
        assert_eq!(incircle(a, b, c, v2(1., 1.)), Sign::Positive);
        assert_eq!(incircle(a, b, c, v2(3., 3.)), Sign::Negative);
        assert_eq!(incircle(a, b, c, v2(2., 2.)), Sign::Zero);
        // Clockwise reverses the sign.
        assert_eq!(incircle(a, c, b, v2(1., 1.)), Sign::Negative);
        // One ulp off the circle through the corners of the unit square.
        let (p, q, r) = (v2(0., 0.), v2(1., 0.), v2(1., 1.));
        assert_eq!(incircle(p, q, r, v2(0., 1.)), Sign::Zero);
        assert_eq!(incircle(p, q, r, v2(0., 1f64.next_down())), Sign::Positive);
        assert_eq!(incircle(p, q, r, v2(0., 1f64.next_up())), Sign::Negative);
    }

    #[test]
    fn incircle_is_exact_far_from_one() {
        // The unit-square case scaled by powers of two is still cocircular
        // and one ulp off still decides, at both ends of the range.
        for scale in [
            2f64.powi(-1000),
            2f64.powi(-200),
            2f64.powi(200),
            2f64.powi(250),
        ] {
            let s = |x: f64, y: f64| v2(x * scale, y * scale);
            let (p, q, r) = (s(0., 0.), s(1., 0.), s(1., 1.));
            assert_eq!(incircle(p, q, r, s(0., 1.)), Sign::Zero, "{scale:e}");
            let inside = v2(0., scale.next_down());
            let outside = v2(0., scale.next_up());
            assert_eq!(incircle(p, q, r, inside), Sign::Positive, "{scale:e}");
            assert_eq!(incircle(p, q, r, outside), Sign::Negative, "{scale:e}");
        }
    }
}
