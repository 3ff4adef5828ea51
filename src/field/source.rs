//! One blobby source: a center, a radius of influence and a strength.

use glam::DVec3;

use crate::geom::Aabb;

use super::error::FieldError;

/// The largest magnitude of a center coordinate or a radius, and the
/// smallest radius: 2^±500 keeps every squared distance the field computes
/// between 2^-1000 and 2^1004, a normal `f64`.
pub const SOURCE_RANGE: f64 = f64::from_bits((1023 + 500) << 52);

/// A point source of a blobby field: it adds `strength · g(|P − center|, radius)`
/// to the field, and nothing beyond `radius`.
///
/// # Invariants
///
/// Once accepted by [`Source::try_new`]: `center` finite, `radius` finite
/// and > 0, both within [`SOURCE_RANGE`] (the radius at least its
/// reciprocal), `strength` finite (negative strengths carve).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Source {
    /// The center `P_i`.
    pub center: DVec3,
    /// The radius of influence `R_i`: the source adds nothing at or beyond it.
    pub radius: f64,
    /// The weight of the falloff (1 for the classic blob).
    pub strength: f64,
}

impl Source {
    /// A unit-strength source.
    ///
    /// # Errors
    ///
    /// As [`Source::try_new`], naming source 0.
    pub fn try_unit(center: DVec3, radius: f64) -> Result<Source, FieldError> {
        Source::try_new(center, radius, 1.0)
    }

    /// A source, checked.
    ///
    /// # Errors
    ///
    /// [`FieldError::NonFiniteCenter`], [`FieldError::BadRadius`] (zero,
    /// negative or not finite), [`FieldError::OutOfRange`] or
    /// [`FieldError::BadStrength`], naming source 0 (lists renumber them).
    pub fn try_new(center: DVec3, radius: f64, strength: f64) -> Result<Source, FieldError> {
        let source = Source {
            center,
            radius,
            strength,
        };
        source.check(0)?;
        Ok(source)
    }

    /// Checks the invariants, naming the source by `index`.
    pub(crate) fn check(&self, index: usize) -> Result<(), FieldError> {
        if !self.center.is_finite() {
            return Err(FieldError::NonFiniteCenter {
                source_index: index,
                center: self.center,
            });
        }
        if !(self.radius.is_finite() && self.radius > 0.0) {
            return Err(FieldError::BadRadius {
                source_index: index,
                radius: self.radius,
            });
        }
        if let Some(&value) = self
            .center
            .to_array()
            .iter()
            .find(|c| c.abs() > SOURCE_RANGE)
        {
            return Err(FieldError::OutOfRange {
                source_index: index,
                what: "center coordinate",
                value,
            });
        }
        if !(1.0 / SOURCE_RANGE..=SOURCE_RANGE).contains(&self.radius) {
            return Err(FieldError::OutOfRange {
                source_index: index,
                what: "radius",
                value: self.radius,
            });
        }
        if !self.strength.is_finite() {
            return Err(FieldError::BadStrength {
                source_index: index,
                strength: self.strength,
            });
        }
        Ok(())
    }

    /// A box holding every point `p` at which the field's rounded squared
    /// distance `|p − center|²` is below the rounded `radius²`, that is,
    /// every point this source adds to.
    ///
    /// The influence box widened by a rounding allowance: with
    /// `u = 2⁻⁵³`, a rounded squared distance below the rounded `radius²`
    /// implies `|p_a − center_a| < radius · (1 + 4u)` along each axis; the
    /// box's half-side `radius · (1 + 2⁻⁴⁰)` exceeds that, and its sides
    /// are rounded outward by one ulp.
    #[must_use]
    pub fn reach_box(&self) -> Aabb {
        let reach = self.radius * (1.0 + f64::from_bits((1023 - 40) << 52));
        let (lo, hi) = (
            self.center - DVec3::splat(reach),
            self.center + DVec3::splat(reach),
        );
        Aabb {
            min: DVec3::new(lo.x.next_down(), lo.y.next_down(), lo.z.next_down()),
            max: DVec3::new(hi.x.next_up(), hi.y.next_up(), hi.z.next_up()),
        }
    }

    /// The box of the ball of influence.
    #[must_use]
    pub fn influence_box(&self) -> Aabb {
        Aabb {
            min: self.center - DVec3::splat(self.radius),
            max: self.center + DVec3::splat(self.radius),
        }
    }
}
