//! Exact floating-point expansion arithmetic (Shewchuk, "Adaptive Precision
//! Floating-Point Arithmetic and Fast Robust Geometric Predicates", 1997).
//!
//! An expansion is an exact sum of non-overlapping `f64` components, kept in
//! increasing order of magnitude with zeros eliminated; its sign is the sign
//! of its largest component. The predicates of the crate fall back to these
//! sums only when their floating-point filter cannot decide a sign. Exactness
//! assumes no intermediate product overflows or underflows into the
//! subnormal range.

use smallvec::SmallVec;

use super::Sign;

/// `a + b = sum + err` exactly (Knuth's TwoSum).
#[must_use]
pub(crate) fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let sum = a + b;
    let bv = sum - a;
    let av = sum - bv;
    (sum, (a - av) + (b - bv))
}

/// `a · b = product + err` exactly (the fused multiply-add gives the error).
#[must_use]
pub(crate) fn two_product(a: f64, b: f64) -> (f64, f64) {
    let product = a * b;
    (product, a.mul_add(b, -product))
}

/// An exact sum of non-overlapping doubles, smallest magnitude first.
#[derive(Clone, Debug, Default)]
pub(crate) struct Expansion {
    parts: SmallVec<[f64; 16]>,
}

impl Expansion {
    /// The exact difference `plus − minus` of two doubles.
    #[must_use]
    pub(crate) fn difference(plus: f64, minus: f64) -> Expansion {
        let (sum, err) = two_sum(plus, -minus);
        let mut e = Expansion::default();
        for c in [err, sum] {
            if c != 0.0 {
                e.parts.push(c);
            }
        }
        e
    }

    /// Adds `b` exactly (Grow-Expansion with zero elimination).
    pub(crate) fn grow(&mut self, b: f64) {
        if b == 0.0 {
            return;
        }
        let mut carry = b;
        let mut kept = 0;
        for j in 0..self.parts.len() {
            let (sum, err) = two_sum(carry, self.parts[j]);
            carry = sum;
            if err != 0.0 {
                self.parts[kept] = err;
                kept += 1;
            }
        }
        self.parts.truncate(kept);
        if carry != 0.0 {
            self.parts.push(carry);
        }
    }

    /// Adds the product `a · b` exactly.
    pub(crate) fn grow_product(&mut self, a: f64, b: f64) {
        let (hi, lo) = two_product(a, b);
        self.grow(lo);
        self.grow(hi);
    }

    /// Adds every component of `other`, negated when `negate` is set.
    pub(crate) fn grow_expansion(&mut self, other: &Expansion, negate: bool) {
        for &c in &other.parts {
            self.grow(if negate { -c } else { c });
        }
    }

    /// The exact product of two expansions.
    #[must_use]
    pub(crate) fn mul(&self, other: &Expansion) -> Expansion {
        let mut out = Expansion::default();
        for &x in &self.parts {
            for &y in &other.parts {
                out.grow_product(x, y);
            }
        }
        out
    }

    /// The exact product with one double.
    #[must_use]
    pub(crate) fn scale(&self, factor: f64) -> Expansion {
        let mut out = Expansion::default();
        for &x in &self.parts {
            out.grow_product(x, factor);
        }
        out
    }

    /// The sign of the exact sum.
    #[must_use]
    pub(crate) fn sign(&self) -> Sign {
        self.parts.last().map_or(Sign::Zero, |&c| Sign::of(c))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sums_and_products_are_exact() {
        // 0.1 + 0.2 − 0.3 is not zero in binary; the expansion knows its sign.
        let mut e = Expansion::default();
        for x in [0.1, 0.2, -0.3] {
            e.grow(x);
        }
        assert_eq!(e.sign(), Sign::Positive);
        // (1 + 2⁻⁵²)² − 1 − 2⁻⁵¹ = 2⁻¹⁰⁴ > 0, invisible to rounded arithmetic.
        let x = 1.0 + f64::EPSILON;
        let square = Expansion::difference(x, 0.0).mul(&Expansion::difference(x, 0.0));
        let mut rest = square.clone();
        rest.grow(-1.0);
        rest.grow(-2.0 * f64::EPSILON);
        assert_eq!(rest.sign(), Sign::Positive);
        assert_eq!(rest.parts.as_slice(), &[f64::EPSILON * f64::EPSILON]);
        let mut zero = Expansion::difference(1e300, 1e300);
        assert_eq!(zero.sign(), Sign::Zero);
        zero.grow_expansion(&square.scale(-1.0), true);
        assert_eq!(zero.sign(), Sign::Positive);
    }
}
