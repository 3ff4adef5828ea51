//! Double-double numbers with a certified error bound: the second stage of
//! the predicates on implicit points, between the interval filter and
//! exact dyadic arithmetic.
//!
//! A value is `hi + lo` (non-overlapping, by error-free transformations)
//! and a bound `err` with `|exact − (hi + lo)| ≤ err`. Sums and products
//! keep about 106 bits, so where the interval filter (53 bits, widened at
//! every step) cannot tell — most often: which `f64` a constructed point's
//! coordinate rounds to — this stage usually can, at a few dozen flops per
//! operation instead of big-integer arithmetic.
//!
//! # The bounds
//!
//! With `u = 2⁻⁵³`, `two_sum` and `two_product` exact, and `γₖ ≤ 1.01 k u`:
//!
//! - `a + b`: `(s, e) = two_sum(a.hi, b.hi)`, `t = (a.lo + b.lo) + e` (two
//!   roundings, error `≤ γ₂ (|a.lo| + |b.lo| + |e|)`), `(hi, lo) =
//!   two_sum(s, t)`. So `err = a.err + b.err + 2.02 u (|a.lo| + |b.lo| +
//!   |e|)`.
//! - `a · b`: `(p, e) = two_product(a.hi, b.hi)`, `t = (a.hi b.lo + a.lo
//!   b.hi) + e` (three roundings over `S = |a.hi b.lo| + |a.lo b.hi| +
//!   |e|`), `(hi, lo) = two_sum(p, t)`; the dropped `a.lo b.lo` and the
//!   operands' own errors propagate: `err = |A| b.err + |B| a.err + a.err
//!   b.err + |a.lo b.lo| + 3.03 u S`, with `|A| ≤ |a.hi| + |a.lo|`.
//!
//! Each `err` is itself computed in floating point (at most a dozen
//! roundings of non-negative terms) and then multiplied by `1 + 16 u`,
//! which more than covers them.
//!
//! These hold while nothing overflows. Callers use this stage
//! only on points whose defining coordinates are all zero or of magnitude
//! in `[2⁻⁶⁰, 2⁶⁰]` ([`SAFE_EXPONENT`]): every non-zero difference of two
//! of them is then at least `2⁻¹¹²`, so every exact value of the
//! polynomials here (degree at most 8) is zero or at least `2⁻⁸⁹⁶` (a
//! multiple of that grain) and below `2⁵⁰⁰`. Terms lost to underflow on the
//! way (below `2⁻¹⁰²²` each) are covered by a `2⁻¹⁰⁰⁰` added to every
//! bound, so no sign decided here is wrong: a value certified non-zero is
//! more than the bound from zero, and no computed value is certified zero.
//! Results that are not finite certify nothing.

use crate::geom::Sign;
use crate::geom::expansion::{two_product, two_sum};

use super::arithmetic::Arithmetic;

const U: f64 = f64::EPSILON / 2.0;

/// Inputs of magnitude within `2^±SAFE_EXPONENT` (or zero) keep this
/// stage's arithmetic away from underflow and overflow (see the module).
pub(crate) const SAFE_EXPONENT: i32 = 60;

/// Whether `x` is zero or of magnitude within `2^±SAFE_EXPONENT`.
#[must_use]
pub(crate) fn in_safe_range(x: f64) -> bool {
    let m = x.abs();
    m == 0.0 || (m >= f64::powi(2.0, -SAFE_EXPONENT) && m <= f64::powi(2.0, SAFE_EXPONENT))
}

/// `hi + lo` within `err` of the exact value.
///
/// # Invariants
///
/// `hi = fl(hi + lo)` (the pair does not overlap); `err ≥ 0`, or NaN /
/// infinite once something overflowed (then no sign is certified).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct DoubleDouble {
    pub hi: f64,
    pub lo: f64,
    pub err: f64,
}

impl DoubleDouble {
    /// The exact pair `hi + lo` (for `lo` small beside `hi`).
    #[must_use]
    pub fn pair(hi: f64, lo: f64) -> DoubleDouble {
        let (hi, lo) = two_sum(hi, lo);
        DoubleDouble { hi, lo, err: 0.0 }
    }

    /// The value rounded to `f64`.
    #[must_use]
    pub fn value(&self) -> f64 {
        self.hi + self.lo
    }
}

/// The bound's own rounding: `1 + 16 u`.
const ROUND_UP: f64 = 1.0 + 16.0 * U;

/// Added to every computed bound: more than what terms of the bound lost
/// to underflow (each below `2⁻¹⁰²²`), so the bound stays a bound even
/// for values near zero; no computed value is ever certified zero, and
/// none below `2⁻¹⁰⁰⁰` is certified at all (every non-zero exact value
/// here is far larger: see the module).
const TINY: f64 = f64::from_bits(23 << 52);

impl Arithmetic for DoubleDouble {
    #[inline]
    fn of(x: f64) -> DoubleDouble {
        DoubleDouble {
            hi: x,
            lo: 0.0,
            err: 0.0,
        }
    }

    #[inline]
    fn plus(&self, other: &DoubleDouble) -> DoubleDouble {
        let (s, e) = two_sum(self.hi, other.hi);
        let t = (self.lo + other.lo) + e;
        let (hi, lo) = two_sum(s, t);
        let err = (self.err + other.err + 2.02 * U * (self.lo.abs() + other.lo.abs() + e.abs()))
            * ROUND_UP
            + TINY;
        DoubleDouble { hi, lo, err }
    }

    #[inline]
    fn minus(&self, other: &DoubleDouble) -> DoubleDouble {
        self.plus(&DoubleDouble {
            hi: -other.hi,
            lo: -other.lo,
            err: other.err,
        })
    }

    #[inline]
    fn times(&self, other: &DoubleDouble) -> DoubleDouble {
        let (p, e) = two_product(self.hi, other.hi);
        let (cross_a, cross_b) = (self.hi * other.lo, self.lo * other.hi);
        let t = (cross_a + cross_b) + e;
        let (hi, lo) = two_sum(p, t);
        let size_a = self.hi.abs() + self.lo.abs();
        let size_b = other.hi.abs() + other.lo.abs();
        let err = (size_a * other.err
            + size_b * self.err
            + self.err * other.err
            + (self.lo * other.lo).abs()
            + 3.03 * U * (cross_a.abs() + cross_b.abs() + e.abs()))
            * ROUND_UP
            + TINY;
        DoubleDouble { hi, lo, err }
    }

    #[inline]
    fn sign(&self) -> Option<Sign> {
        if !(self.hi.is_finite() && self.lo.is_finite() && self.err.is_finite()) {
            return None;
        }
        if self.err == 0.0 {
            // hi + lo is exact; hi carries its sign (hi = 0 only with lo = 0).
            return Some(Sign::of(self.hi));
        }
        // |hi + lo| ≥ |hi| − |lo| ≥ |hi| (1 − u) − |lo| (1 + u) beats err.
        if self.hi.abs() * (1.0 - 4.0 * U) > (self.lo.abs() + self.err) * (1.0 + 4.0 * U) {
            Some(Sign::of(self.hi))
        } else {
            None
        }
    }
}

/// The coordinate `x / w` rounded to the nearest `f64` (ties to even),
/// when this stage can certify it: the exact quotient lies strictly
/// between the midpoints that bound the candidate's rounding interval.
/// `None` when it cannot (the caller rounds exactly).
#[must_use]
pub(crate) fn rounded_quotient(x: &DoubleDouble, w: &DoubleDouble) -> Option<f64> {
    let w_sign = w.sign()?;
    if w_sign == Sign::Zero {
        return None;
    }
    if x.sign()? == Sign::Zero {
        return Some(0.0);
    }
    // A first quotient and one correction by its residual.
    let first = x.hi / w.hi;
    let residual = x.minus(&DoubleDouble::of(first).times(w));
    let candidate = first + residual.value() / w.value();
    if !candidate.is_finite() || candidate == 0.0 {
        return None;
    }
    // The rounding interval of `candidate`: its midpoints with the
    // neighbours (exact as pairs; wider below a power of two's neighbour).
    let above = DoubleDouble::pair(candidate, (candidate.next_up() - candidate) / 2.0);
    let below = DoubleDouble::pair(candidate, -(candidate - candidate.next_down()) / 2.0);
    // x / w against m: the sign of (x − m w) times the sign of w.
    let against = |m: &DoubleDouble| -> Option<Sign> {
        let s = x.minus(&m.times(w)).sign()?;
        Some(if w_sign == Sign::Negative {
            s.reversed()
        } else {
            s
        })
    };
    (against(&below)? == Sign::Positive && against(&above)? == Sign::Negative).then_some(candidate)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::dyadic::Dyadic;
    use crate::test_rng;

    /// The exact value of an expression and its double-double evaluation:
    /// the exact value lies within the bound, on random inputs spread over
    /// the safe range, with heavy cancellation.
    #[test]
    fn the_bound_holds_under_cancellation() {
        let mut bits = test_rng::bits(5);
        let mut number = || {
            let mantissa = (bits() >> 11) as f64 / (1u64 << 53) as f64 + 0.5;
            let exponent = (bits() % 41) as i32 - 20;
            let sign = if bits() & 1 == 0 { 1.0 } else { -1.0 };
            sign * mantissa * f64::powi(2.0, exponent)
        };
        for _ in 0..2000 {
            let [a, b, c, d] = [0; 4].map(|_| number());
            // (a + b)(c − d) − (a c − b d) + a (b⁺ − b): cancels to
            // −a d + b c + a ulp(b).
            let near = b.next_up();
            let dd = |x: f64| DoubleDouble::of(x);
            let ex = |x: f64| Dyadic::of(x);
            let value = dd(a)
                .plus(&dd(b))
                .times(&dd(c).minus(&dd(d)))
                .minus(&dd(a).times(&dd(c)).minus(&dd(b).times(&dd(d))))
                .plus(&dd(a).times(&dd(near).minus(&dd(b))));
            let exact = ex(a)
                .plus(&ex(b))
                .times(&ex(c).minus(&ex(d)))
                .minus(&ex(a).times(&ex(c)).minus(&ex(b).times(&ex(d))))
                .plus(&ex(a).times(&ex(near).minus(&ex(b))));
            let represented = Dyadic::of(value.hi).plus(&Dyadic::of(value.lo));
            let gap = represented.minus(&exact);
            let err = Dyadic::of(value.err);
            assert!(
                err.minus(&gap).sign() != Sign::Negative && err.plus(&gap).sign() != Sign::Negative,
                "{a} {b} {c} {d}: {value:?}"
            );
            if let Some(s) = value.sign() {
                assert_eq!(s, exact.sign());
            }
        }
    }

    #[test]
    fn quotients_round_to_nearest_or_say_they_cannot() {
        let mut bits = test_rng::bits(9);
        let mut unit = || (bits() >> 11) as f64 / (1u64 << 53) as f64 + 0.25;
        let mut decided = 0;
        for _ in 0..2000 {
            let [a, b, c, d] = [0; 4].map(|_| unit());
            // x = a b − c d, w = a + d, exactly known and rounded apart.
            let dd = |x: f64| DoubleDouble::of(x);
            let x = dd(a).times(&dd(b)).minus(&dd(c).times(&dd(d)));
            let w = dd(a).plus(&dd(d));
            let ex = |x: f64| Dyadic::of(x);
            let xe = ex(a).times(&ex(b)).minus(&ex(c).times(&ex(d)));
            let we = ex(a).plus(&ex(d));
            let nearest = xe.quotient_to_f64(&we);
            if let Some(q) = rounded_quotient(&x, &w) {
                decided += 1;
                assert_eq!(q, nearest, "{a} {b} {c} {d}");
            }
        }
        assert!(decided > 1990, "{decided}");
        // A zero numerator is zero; a zero weight is never a quotient.
        let zero = DoubleDouble::of(0.0);
        assert_eq!(rounded_quotient(&zero, &DoubleDouble::of(3.0)), Some(0.0));
        assert_eq!(rounded_quotient(&DoubleDouble::of(1.0), &zero), None);
    }

    #[test]
    fn the_safe_range() {
        assert!(in_safe_range(0.0) && in_safe_range(-1.5) && in_safe_range(1e18));
        assert!(!in_safe_range(1e19) && !in_safe_range(1e-19) && !in_safe_range(f64::NAN));
    }
}
