//! Exact signs of dot products: which side of a plane given by a point and a
//! normal a point lies on, and which way a direction points across it.
//!
//! These are the half-space predicates of the ray–plane method: the
//! side of `P` is the sign of `(P − Q) · N`, and whether a ray runs towards or
//! away from the plane is the sign of `D · N`. As in
//! [`orient3d`](super::orient3d), a floating-point filter decides the common
//! case and an exact evaluation (error-free transformations summed into a
//! non-overlapping expansion, after Shewchuk 1997) decides the rest; each
//! exact evaluation is counted by [`exact_fallbacks`](super::exact_fallbacks).
//! The answers are exact for every finite input: the filter allows for
//! roundings in the subnormal range ([`UNDERFLOW`]) and input outside the
//! range where expansions are exact goes to big-integer arithmetic
//! (`dyadic`).

use glam::DVec3;

use super::Sign;
use super::dyadic::{Dyadic, in_safe_range};
use super::expansion::Expansion;
use super::predicates::{UNDERFLOW, count_fallback};

/// Unit round-off of `f64` (half an ulp of 1.0).
const HALF_EPSILON: f64 = f64::EPSILON / 2.0;
/// Relative error bound of a rounded three-term dot product whose first
/// factors are themselves rounded differences: one rounding in each
/// difference, one in each product and two in the sum give at most
/// `(4 ε + 6 ε²) Σ |termᵢ|`; `8 ε` leaves a margin for the second-order terms.
const DOT_BOUND: f64 = 8.0 * HALF_EPSILON;

/// The exact sign of `a · b`.
///
/// `Positive` when the angle between `a` and `b` is acute, `Zero` when they
/// are exactly perpendicular (or one is zero), `Negative` when obtuse.
/// Non-finite input gives an unspecified sign (never a panic).
#[must_use]
pub fn dot_sign(a: DVec3, b: DVec3) -> Sign {
    side_of_plane(a, DVec3::ZERO, b)
}

/// The exact sign of `(p − q) · n`: which side of the plane through `q` with
/// normal `n` the point `p` lies on.
///
/// `Positive` on the side `n` points to (for a half-space whose normal points
/// OUTSIDE, the outside), `Zero` exactly in the plane, `Negative` on the other
/// side. The differences `p − q` are not rounded: the sign is that of the
/// exact real number. Non-finite input gives an unspecified sign.
#[must_use]
pub fn side_of_plane(p: DVec3, q: DVec3, n: DVec3) -> Sign {
    let d = p - q;
    let terms = [d.x * n.x, d.y * n.y, d.z * n.z];
    let sum = terms[0] + terms[1] + terms[2];
    let bound = DOT_BOUND * (terms[0].abs() + terms[1].abs() + terms[2].abs()) + UNDERFLOW;
    if sum > bound || -sum > bound {
        return Sign::of(sum);
    }
    // Every term a product with an exactly zero factor (a float difference
    // is zero only for equal operands): the exact sum is zero. This keeps
    // points on axis-aligned planes off the slow path.
    if (0..3).all(|i| d[i] == 0.0 || n[i] == 0.0) {
        return Sign::Zero;
    }
    exact_side_of_plane(p, q, n)
}

fn exact_side_of_plane(p: DVec3, q: DVec3, n: DVec3) -> Sign {
    count_fallback();
    let inputs = [p, q, n].map(|v| v.to_array());
    if !in_safe_range(inputs.as_flattened()) {
        let mut total = Dyadic::of(0.0);
        for i in 0..3 {
            total = &total + &(&Dyadic::difference(p[i], q[i]) * &Dyadic::of(n[i]));
        }
        return total.sign();
    }
    let mut total = Expansion::default();
    for i in 0..3 {
        total.grow_expansion(&Expansion::difference(p[i], q[i]).scale(n[i]), false);
    }
    total.sign()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::expansion::two_sum;
    use crate::geom::{exact_fallbacks, reset_exact_fallbacks};

    #[test]
    fn signs_of_plain_cases() {
        let q = DVec3::new(1., 2., 3.);
        let n = DVec3::new(0., 0., 2.);
        assert_eq!(side_of_plane(DVec3::new(9., -4., 4.), q, n), Sign::Positive);
        assert_eq!(side_of_plane(DVec3::new(9., -4., 2.), q, n), Sign::Negative);
        assert_eq!(side_of_plane(DVec3::new(9., -4., 3.), q, n), Sign::Zero);
        assert_eq!(dot_sign(DVec3::X, DVec3::Y), Sign::Zero);
        assert_eq!(dot_sign(DVec3::X, -DVec3::ONE), Sign::Negative);
    }

    #[test]
    fn decides_points_one_ulp_off_a_tilted_plane() {
        // The plane x + y + z = 0.3 through q = (0.1, 0.1, 0.1) rounded: the
        // exact answer for p = (0.3, 0, 0) differs from the rounded one.
        let q = DVec3::new(0.1, 0.1, 0.1);
        let n = DVec3::ONE;
        reset_exact_fallbacks();
        // 0.1 + 0.1 + 0.1 (exact reals of the doubles) vs 0.3 (a double).
        let exact = {
            // 3 · 0.1_f64 as an exact rational compared with 0.3_f64.
            let tenth = 0.1_f64;
            let (s, e) = two_sum(tenth, tenth);
            let (s2, e2) = two_sum(s, tenth);
            let total_err = e + e2;
            Sign::of((0.3 - s2) - total_err)
        };
        assert_eq!(side_of_plane(DVec3::new(0.3, 0., 0.), q, n), exact);
        assert!(exact_fallbacks() >= 1);
        let ulp = 0.3_f64.next_up() - 0.3;
        assert_eq!(
            side_of_plane(DVec3::new(0.3 + 4.0 * ulp, 0., 0.), q, n),
            Sign::Positive
        );
    }

    #[test]
    fn differences_are_not_rounded() {
        // p − q rounds to 1e16 in every coordinate, but the exact differences
        // are 1e16 + 1 and 1e16 − 1 (with the -1 shifts): their sum decides.
        let p = DVec3::new(1e16, 1e16, 0.0);
        let q = DVec3::new(-1.0, 1.0, 0.0);
        // (1e16 + 1) − (1e16 − 1) = 2 > 0 though both products round alike.
        assert_eq!(side_of_plane(p, q, DVec3::new(1., -1., 0.)), Sign::Positive);
        assert_eq!(side_of_plane(q, p, DVec3::new(1., -1., 0.)), Sign::Negative);
    }
}
