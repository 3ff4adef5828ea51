//! Exact arithmetic on dyadic rationals `m · 2ᵉ` with a big-integer `m`: the
//! predicates' last resort when their inputs lie outside the safe range
//! ([`in_safe_range`]),
//! where floating-point expansions could overflow or lose bits to
//! underflow.
//!
//! Every finite `f64` is such a number, and sums, differences and products
//! of them are too, so a polynomial in the inputs evaluated here has exactly
//! the value of the real polynomial: its sign needs no error analysis at
//! all. The price is speed (heap-allocated integers of up to a few thousand
//! bits), paid only by inputs a hundred orders of magnitude from 1.
//!
//! [`in_safe_range`] decides which path a fallback takes. Within the range
//! the expansion arithmetic of [`expansion`](super::expansion) and the
//! `robust` crate is exact: an input `x` with `2⁻²⁵⁰ ≤ |x| ≤ 2²⁵⁰` is a
//! multiple of `2⁻³⁰²` (its unit in the last place), so every difference,
//! product and error term of a polynomial of degree at most 3 in such inputs
//! is a multiple of `2⁻⁹⁰⁶` — never below the smallest normal `f64`, `2⁻¹⁰²²`,
//! when non-zero — and every magnitude stays below `2⁷⁶⁴`, far from overflow.

use std::ops::{Add, Mul, Neg, Sub};

use num_bigint::BigInt;

use super::Sign;

/// `2⁻²⁵⁰`: with [`SAFE_MAX`], the magnitudes within which (with 0) the
/// expansion arithmetic is exact for polynomials of degree at most 3
/// (module docs).
const SAFE_MIN: f64 = 1.0 / (1u128 << 125) as f64 / (1u128 << 125) as f64;
/// `2²⁵⁰`.
const SAFE_MAX: f64 = (1u128 << 125) as f64 * (1u128 << 125) as f64;

/// Whether every value is 0 or of magnitude within [`SAFE_MIN`] ..= [`SAFE_MAX`]: then the
/// expansion fallbacks are exact; otherwise (subnormal, tiny, huge or
/// non-finite values) the dyadic one is needed.
#[must_use]
#[inline]
pub(crate) fn in_safe_range(values: &[f64]) -> bool {
    values
        .iter()
        .all(|&x| x == 0.0 || (SAFE_MIN..=SAFE_MAX).contains(&x.abs()))
}

/// `2⁻¹⁹⁰` and `2¹⁹⁰`: the magnitudes within which (with 0) the expansion
/// arithmetic is exact for polynomials of degree 4 (the in-circle test): a
/// multiple of `2⁻²⁴²` raised to the fourth power is a multiple of `2⁻⁹⁶⁸`,
/// above the smallest normal `f64`, and magnitudes stay below `2⁷⁷⁰`.
const DEGREE4_MIN: f64 = 1.0 / (1u128 << 95) as f64 / (1u128 << 95) as f64;
/// `2¹⁹⁰`.
const DEGREE4_MAX: f64 = (1u128 << 95) as f64 * (1u128 << 95) as f64;

/// Whether every value is 0 or of magnitude within [`DEGREE4_MIN`] ..=
/// [`DEGREE4_MAX`]: then the expansion fallback of a degree-4 predicate
/// (`incircle`) is exact; otherwise the dyadic one is needed.
#[must_use]
#[inline]
pub(crate) fn in_incircle_range(values: &[f64]) -> bool {
    values
        .iter()
        .all(|&x| x == 0.0 || (DEGREE4_MIN..=DEGREE4_MAX).contains(&x.abs()))
}

/// The exact value `mantissa · 2^exponent`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Dyadic {
    mantissa: BigInt,
    exponent: i64,
}

impl Dyadic {
    /// The exact value of a finite `x`. A non-finite `x` reads as 0: the
    /// predicates promise no particular sign for non-finite input, only no
    /// panic.
    #[must_use]
    pub(crate) fn of(x: f64) -> Dyadic {
        if !x.is_finite() {
            return Dyadic::zero();
        }
        let bits = x.to_bits();
        let biased = ((bits >> 52) & 0x7ff) as i64;
        let fraction = bits & ((1u64 << 52) - 1);
        // Subnormals (biased exponent 0) have no hidden bit and the exponent
        // of the smallest normal.
        let (digits, exponent) = if biased == 0 {
            (fraction, -1074)
        } else {
            (fraction | (1u64 << 52), biased - 1075)
        };
        let mantissa = BigInt::from(digits);
        Dyadic {
            mantissa: if x < 0.0 { -mantissa } else { mantissa },
            exponent,
        }
    }

    /// The exact difference `plus − minus` of two finite doubles.
    #[must_use]
    pub(crate) fn difference(plus: f64, minus: f64) -> Dyadic {
        &Dyadic::of(plus) - &Dyadic::of(minus)
    }

    /// `self / denominator` rounded to the nearest `f64` (ties to even;
    /// within one unit in the last place where the result is subnormal; an
    /// infinity or 0 when the quotient is beyond the range of `f64`), or
    /// NaN when `denominator` is 0.
    #[must_use]
    pub(crate) fn quotient_to_f64(&self, denominator: &Dyadic) -> f64 {
        if denominator.mantissa.sign() == num_bigint::Sign::NoSign {
            return f64::NAN;
        }
        if self.mantissa.sign() == num_bigint::Sign::NoSign {
            return 0.0;
        }
        let (num, den) = (self.mantissa.magnitude(), denominator.mantissa.magnitude());
        // Enough bits that the integer quotient carries 64 significant ones.
        let widen = (den.bits() + 64).saturating_sub(num.bits());
        let shifted = num << widen;
        let quotient = &shifted / den;
        let drop = quotient.bits().saturating_sub(64);
        let mut top = (&quotient >> drop).iter_u64_digits().next().unwrap_or(0);
        // A sticky bit for whatever the 64 bits leave out (the division's
        // remainder, the dropped bits), so that converting them rounds to
        // nearest as the whole quotient would: 64 > 53 + 2 bits.
        let inexact = quotient.trailing_zeros().is_some_and(|zeros| zeros < drop)
            || &quotient * den != shifted;
        if inexact {
            top |= 1;
        }
        let exponent = self.exponent - denominator.exponent - widen as i64 + drop as i64;
        let magnitude = scale_by_power_of_two(top as f64, exponent);
        if (self.mantissa.sign() == num_bigint::Sign::Minus)
            != (denominator.mantissa.sign() == num_bigint::Sign::Minus)
        {
            -magnitude
        } else {
            magnitude
        }
    }

    fn zero() -> Dyadic {
        Dyadic {
            mantissa: BigInt::ZERO,
            exponent: 0,
        }
    }

    /// The sign of the value.
    #[must_use]
    pub(crate) fn sign(&self) -> Sign {
        match self.mantissa.sign() {
            num_bigint::Sign::Plus => Sign::Positive,
            num_bigint::Sign::Minus => Sign::Negative,
            num_bigint::Sign::NoSign => Sign::Zero,
        }
    }

    /// The mantissas of `self` and `other` scaled to their common (the
    /// smaller) exponent.
    fn aligned(&self, other: &Dyadic) -> (BigInt, BigInt, i64) {
        let e = self.exponent.min(other.exponent);
        let widen = |d: &Dyadic| &d.mantissa << (d.exponent - e) as usize;
        (widen(self), widen(other), e)
    }
}

impl Add for &Dyadic {
    type Output = Dyadic;

    fn add(self, other: &Dyadic) -> Dyadic {
        let (a, b, exponent) = self.aligned(other);
        Dyadic {
            mantissa: a + b,
            exponent,
        }
    }
}

impl Sub for &Dyadic {
    type Output = Dyadic;

    fn sub(self, other: &Dyadic) -> Dyadic {
        let (a, b, exponent) = self.aligned(other);
        Dyadic {
            mantissa: a - b,
            exponent,
        }
    }
}

impl Mul for &Dyadic {
    type Output = Dyadic;

    fn mul(self, other: &Dyadic) -> Dyadic {
        Dyadic {
            mantissa: &self.mantissa * &other.mantissa,
            exponent: self.exponent + other.exponent,
        }
    }
}

impl Neg for Dyadic {
    type Output = Dyadic;

    fn neg(self) -> Dyadic {
        Dyadic {
            mantissa: -self.mantissa,
            exponent: self.exponent,
        }
    }
}

/// `x · 2^exponent`, in steps that stay within the range of `f64` until
/// the result itself leaves it.
fn scale_by_power_of_two(mut x: f64, mut exponent: i64) -> f64 {
    const STEP: i64 = 1000;
    let up = 2f64.powi(STEP as i32);
    let down = 2f64.powi(-STEP as i32);
    while exponent > STEP && x.is_finite() {
        x *= up;
        exponent -= STEP;
    }
    while exponent < -STEP && x != 0.0 {
        x *= down;
        exponent += STEP;
    }
    x * 2f64.powi(exponent as i32)
}

/// The exact sign of the 3×3 determinant with entries `rows[i][j]` (each
/// already exact), expanded along the first row.
#[must_use]
pub(crate) fn det3_sign(rows: &[[Dyadic; 3]; 3]) -> Sign {
    let [r0, r1, r2] = rows;
    let minor = |j: usize, k: usize| &(&r1[j] * &r2[k]) - &(&r1[k] * &r2[j]);
    let det = &(&(&r0[0] * &minor(1, 2)) + &(&r0[1] * &minor(2, 0))) + &(&r0[2] * &minor(0, 1));
    det.sign()
}

/// The exact sign of `a·d − b·c`.
#[must_use]
pub(crate) fn det2_sign(a: &Dyadic, b: &Dyadic, c: &Dyadic, d: &Dyadic) -> Sign {
    (&(a * d) - &(b * c)).sign()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// IEEE division rounds the exact quotient of two doubles to nearest:
    /// an independent answer for the exact quotient's rounding, on
    /// quotients whose 64 leading bits end in every pattern (ties of the
    /// truncated bits included).
    #[test]
    fn quotients_round_to_nearest_like_ieee_division() {
        let mut bits = crate::test_rng::bits(3);
        for _ in 0..20_000 {
            let a = f64::from_bits((bits() >> 2) | 0x3ff0_0000_0000_0000);
            let b = f64::from_bits((bits() >> 2) | 0x3fe0_0000_0000_0000);
            let (a, b) = (
                if bits() & 1 == 0 { a } else { -a },
                b * f64::powi(2.0, (bits() % 64) as i32 - 32),
            );
            assert_eq!(
                Dyadic::of(a).quotient_to_f64(&Dyadic::of(b)),
                a / b,
                "{a:e} / {b:e}"
            );
            // A product over a double: a·b / b is a, exactly.
            let product = &Dyadic::of(a) * &Dyadic::of(b);
            assert_eq!(product.quotient_to_f64(&Dyadic::of(b)), a);
        }
    }

    #[test]
    fn every_kind_of_double_is_read_exactly() {
        // Reading back m · 2^e through exact powers of two.
        let back = |d: &Dyadic| {
            let m: f64 = d.mantissa.to_string().parse().expect("an integer");
            let mut v = m;
            let mut e = d.exponent;
            while e > 0 {
                v *= 2.0;
                e -= 1;
            }
            while e < 0 {
                v /= 2.0;
                e += 1;
            }
            v
        };
        for x in [
            0.0,
            -0.0,
            1.0,
            -1.5,
            0.1,
            f64::MAX,
            -f64::MAX,
            f64::MIN_POSITIVE,
            5e-324,
            -3e-320,
            1e300,
        ] {
            // The mantissa has at most 53 bits, so it converts exactly; the
            // scaling loop is exact until the final value is reached, for
            // the normal values; subnormals scale from an integer < 2^52.
            assert_eq!(back(&Dyadic::of(x)), x, "{x:e}");
        }
    }

    #[test]
    fn arithmetic_is_exact_across_the_whole_range() {
        let tiny = Dyadic::of(5e-324); // 2^-1074
        let huge = Dyadic::of(f64::MAX);
        // (huge + tiny) − huge = tiny exactly; in f64 it would be 0.
        let same = |a: &Dyadic, b: &Dyadic| (a - b).sign() == Sign::Zero;
        assert!(same(&(&(&huge + &tiny) - &huge), &tiny));
        assert!(!same(&tiny, &Dyadic::of(0.0)));
        // huge · huge · tiny · tiny is positive (f64: ∞ · 0 = NaN).
        let p = &(&(&huge * &huge) * &tiny) * &tiny;
        assert_eq!(p.sign(), Sign::Positive);
        // 0.1 + 0.2 − 0.3 in exact reals of the doubles: positive.
        let s = &(&Dyadic::of(0.1) + &Dyadic::of(0.2)) - &Dyadic::of(0.3);
        assert_eq!(s.sign(), Sign::Positive);
        assert_eq!(Dyadic::difference(0.5, 0.5).sign(), Sign::Zero);
        assert_eq!((-Dyadic::of(2.0)).sign(), Sign::Negative);
    }

    #[test]
    fn determinants() {
        let d = |x: f64| Dyadic::of(x);
        // diag(2^1000, 2^-1074, -1): negative, where f64 products overflow
        // and underflow.
        let z = || d(0.0);
        let rows = [
            [d(f64::MAX), z(), z()],
            [d(7.0), d(5e-324), z()],
            [d(1e300), d(-1e-300), d(-1.0)],
        ];
        assert_eq!(det3_sign(&rows), Sign::Negative);
        assert_eq!(det2_sign(&d(3.0), &d(2.0), &d(6.0), &d(4.0)), Sign::Zero);
        assert_eq!(
            det2_sign(&d(1e-320), &d(1e300), &d(-1e300), &d(1e-320)),
            Sign::Positive
        );
    }

    #[test]
    fn the_safe_range() {
        assert!(in_safe_range(&[0.0, -0.0, 1.0, 1e75, -1e-75]));
        assert!(!in_safe_range(&[1.0, 1e76]));
        assert!(!in_safe_range(&[1e-76]));
        assert!(!in_safe_range(&[f64::NAN]));
        assert!(!in_safe_range(&[f64::INFINITY]));
        assert_eq!(SAFE_MIN * SAFE_MAX, 1.0);
        assert_eq!(SAFE_MAX, 2f64.powi(250));
    }
}
