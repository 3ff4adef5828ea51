//! Rays with their directions scaled by a power of two to unit size, which
//! every walk and crossing parameter sees, and the way back to the
//! caller's parameters.

use crate::geom::{Ray, larger};

/// The same ray with its direction multiplied by a power of two so that its
/// largest component lies in `[1, 2)`, and the factor that turns its
/// parameters back into the caller's: the half-line `t > 0` does not
/// change, only the unit of `t`, and the slab tests and crossing parameters
/// see directions of one size (a direction of `1e308` or `5e-324` overflowed
/// or underflowed them; found by the queries fuzz check).
///
/// Scaling down can round a component far smaller than the largest (a
/// direction `(64, 0, 2⁻¹⁰⁶⁹)` loses its `z`): then the scaled ray is a
/// different line, good for the conservative box tests and for `t` but not
/// for decisions. [`scales_exactly`] says which; where it does not, the
/// exact tests take the caller's ray (their signs do not depend on the
/// direction's length, symbolic perturbation included).
#[inline(always)]
pub(super) fn unit_scaled(ray: &Ray) -> (Ray, f64) {
    // A checked ray's direction is finite, never NaN.
    let d = ray.direction.abs();
    let largest = larger(larger(d.x, d.y), d.z);
    // `largest` is finite and non-zero (a checked ray): its binary exponent
    // `e` lies in −1074 ..= 1023; read from the bits for normal numbers.
    let biased = ((largest.to_bits() >> 52) & 0x7ff) as i32;
    let e = if biased == 0 {
        largest.log2().floor() as i32
    } else {
        biased - 1023
    };
    if e == 0 {
        // Already in `[1, 2)`: the common case of unit-scale directions.
        return (*ray, 1.0);
    }
    // 2^−e is applied in two exact halves, each a normal power of two.
    let (half, rest) = (-e / 2, -e - (-e / 2));
    let direction = ray.direction * pow2(half) * pow2(rest);
    // `origin + t · direction·f = origin + (t·f) · direction`: a parameter
    // along the scaled ray times `f` is the caller's parameter.
    let factor = pow2(half) * pow2(rest);
    (Ray::new(ray.origin, direction), factor)
}

/// Whether [`unit_scaled`] turned `ray` into `scaled` without rounding.
/// Scaling up (`factor ≥ 1`) never rounds: nothing ends above 2. Scaling
/// down rounded when scaling back by the inverse power of two (exact: the
/// scaled components are below 2) does not give the caller's direction.
#[inline(always)]
pub(super) fn scales_exactly(ray: &Ray, scaled: &Ray, factor: f64) -> bool {
    factor >= 1.0 || scaled.direction * (1.0 / factor) == ray.direction
}

/// `2^k` for `k` in −1022 ..= 1023 (a normal `f64`), built from its bits.
pub(super) const fn pow2(k: i32) -> f64 {
    debug_assert!(-1022 <= k && k <= 1023);
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// A parameter along the scaled direction of [`unit_scaled`] in units of the
/// caller's direction: monotone, and still `> 0` when it underflows.
pub(super) fn unscaled_t(t: f64, factor: f64) -> f64 {
    let t = t * factor;
    if t > 0.0 { t } else { f64::from_bits(1) }
}
