//! Interval arithmetic rounded outward: the filter stage of the predicates
//! on implicit points.
//!
//! Each operation rounds to nearest and then widens the result by one unit
//! in the last place on each side, so the exact result of the operation on
//! any reals within the operands lies within the result. A sign is
//! certified when the interval excludes zero; an interval that contains zero,
//! overflows to an infinity or turns NaN certifies nothing, and the caller
//! evaluates exactly instead.

use crate::geom::Sign;

use super::arithmetic::Arithmetic;

/// A closed interval `[lo, hi]` known to contain an exact value.
///
/// # Invariants
///
/// `lo ≤ hi` unless one of them is NaN (after an invalid operation such as
/// `∞ − ∞`); a NaN bound makes [`Arithmetic::sign`] return `None`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Interval {
    pub lo: f64,
    pub hi: f64,
}

impl Interval {
    /// The midpoint, an estimate of the value.
    #[must_use]
    pub fn mid(self) -> f64 {
        0.5 * self.lo + 0.5 * self.hi
    }

    fn widened(lo: f64, hi: f64) -> Interval {
        Interval {
            lo: lo.next_down(),
            hi: hi.next_up(),
        }
    }
}

impl Arithmetic for Interval {
    #[inline]
    fn of(x: f64) -> Interval {
        Interval { lo: x, hi: x }
    }

    #[inline]
    fn plus(&self, other: &Interval) -> Interval {
        Interval::widened(self.lo + other.lo, self.hi + other.hi)
    }

    #[inline]
    fn minus(&self, other: &Interval) -> Interval {
        Interval::widened(self.lo - other.hi, self.hi - other.lo)
    }

    #[inline]
    fn times(&self, other: &Interval) -> Interval {
        if self.lo == self.hi && other.lo == other.hi {
            let p = self.lo * other.lo;
            return Interval::widened(p, p);
        }
        let products = [
            self.lo * other.lo,
            self.lo * other.hi,
            self.hi * other.lo,
            self.hi * other.hi,
        ];
        let mut lo = products[0];
        let mut hi = products[0];
        for &p in &products[1..] {
            // A NaN product (0 · ∞) poisons the interval on purpose.
            if p.is_nan() {
                return Interval {
                    lo: f64::NAN,
                    hi: f64::NAN,
                };
            }
            lo = lo.min(p);
            hi = hi.max(p);
        }
        Interval::widened(lo, hi)
    }

    #[inline]
    fn sign(&self) -> Option<Sign> {
        if self.lo > 0.0 {
            Some(Sign::Positive)
        } else if self.hi < 0.0 {
            Some(Sign::Negative)
        } else if self.lo == 0.0 && self.hi == 0.0 {
            Some(Sign::Zero)
        } else {
            None
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The exact product and sum lie inside the computed intervals, also
    /// where rounding happens; overflow and NaN certify nothing.
    #[test]
    fn results_enclose_the_exact_values() {
        let third = Interval::of(1.0 / 3.0);
        let three = Interval::of(3.0);
        let product = third.times(&three);
        // 1/3 rounded times 3 is exactly 1 − 2⁻⁵⁴ ... within the interval.
        assert!(product.lo < 1.0 && product.hi >= 1.0 - f64::EPSILON);
        let tiny = Interval::of(f64::MIN_POSITIVE * f64::EPSILON);
        let underflow = tiny.times(&tiny);
        assert!(underflow.lo < 0.0 && underflow.hi > 0.0);
        assert_eq!(underflow.sign(), None);
        let huge = Interval::of(f64::MAX);
        assert_eq!(huge.times(&huge).minus(&huge.times(&huge)).sign(), None);
        assert_eq!(
            Interval::of(2.0).minus(&Interval::of(1.0)).sign(),
            Some(Sign::Positive)
        );
        assert_eq!(Interval::of(0.0).times(&Interval::of(5.0)).sign(), None);
    }
}
