//! Rays with their directions scaled by a power of two to unit size, which
//! every walk and crossing parameter sees, and the way back to the
//! caller's parameters.

use super::QueryError;
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
pub(super) fn unit_scaled(ray: &Ray) -> (Ray, TScale) {
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
        return (*ray, TScale::ONE);
    }
    // 2^−e is applied in two exact halves, each a normal power of two
    // (2^−e itself overflows for a subnormal direction, e < −1023).
    let (half, rest) = (pow2(-e / 2), pow2(-e - (-e / 2)));
    let direction = ray.direction * half * rest;
    // `origin + t · direction·f = origin + (t·f) · direction`: a parameter
    // along the scaled ray times `f = half · rest` is the caller's.
    (Ray::new(ray.origin, direction), TScale { half, rest })
}

/// The factor `f = half · rest` (a power of two, kept as two normal
/// halves: `f` itself overflows for subnormal directions) from a
/// parameter along the scaled ray of [`unit_scaled`] to the caller's.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct TScale {
    half: f64,
    rest: f64,
}

impl TScale {
    /// No scaling.
    pub(super) const ONE: TScale = TScale {
        half: 1.0,
        rest: 1.0,
    };

    /// Whether the direction was scaled up (which never rounds).
    pub(super) fn scales_up(self) -> bool {
        self.half >= 1.0
    }

    /// A parameter along the scaled ray as one along the caller's:
    /// `t · f`, in two steps that move monotonically towards the result
    /// (so an overflow or underflow is the result's own).
    pub(super) fn caller_t(self, t: f64) -> f64 {
        t * self.half * self.rest
    }

    /// A parameter along the caller's ray as one along the scaled ray.
    #[cfg(test)]
    pub(super) fn scaled_t(self, t: f64) -> f64 {
        t / self.half / self.rest
    }
}

/// Whether [`unit_scaled`] turned `ray` into `scaled` without rounding.
/// Scaling up never rounds: nothing ends above 2. Scaling down rounded
/// when scaling back by the inverse power of two (exact: the scaled
/// components are below 2) does not give the caller's direction.
#[inline(always)]
pub(super) fn scales_exactly(ray: &Ray, scaled: &Ray, factor: TScale) -> bool {
    factor.scales_up() || scaled.direction / factor.half / factor.rest == ray.direction
}

/// `2^k` for `k` in −1022 ..= 1023 (a normal `f64`), built from its bits.
pub(super) const fn pow2(k: i32) -> f64 {
    debug_assert!(-1022 <= k && k <= 1023);
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// A parameter along the scaled direction of [`unit_scaled`] in units of the
/// caller's direction: monotone; `∞` when it overflows and `0` when it
/// underflows, which the public queries refuse ([`checked_t`]).
pub(super) fn unscaled_t(t: f64, factor: TScale) -> f64 {
    factor.caller_t(t)
}

/// What a crossing's `t` in the caller's units ([`unscaled_t`]) cannot be:
/// `∞` (the direction is so short that `t` overflows) or `0` (so long that
/// it underflows). The same rule as the CSG trace's
/// (`Csg::try_spans`): such a ray is refused by name, never answered with
/// a crossing at infinity.
pub(super) fn checked_t(t: f64, index: usize, ray: &Ray) -> Result<(), QueryError> {
    if t.is_finite() && t > 0.0 {
        return Ok(());
    }
    Err(QueryError::RayOutOfRange {
        index,
        origin: ray.origin,
        direction: ray.direction,
        reason: if t.is_finite() {
            "the direction is so long that a crossing's t underflows"
        } else {
            "the direction is so short that a crossing's t overflows"
        },
    })
}
