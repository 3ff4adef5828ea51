//! The [`Field`] trait: a scalar field whose solid is where it reaches ½.

use glam::DVec3;

use crate::geom::Aabb;

use super::stats::FieldStats;

/// The iso-value of every field: a point is inside the solid where
/// `F(P) ≥ THRESHOLD` and outside where `F(P) < THRESHOLD`.
///
/// With the default falloff a single unit-strength source reaches this value
/// at half its radius, so its solid is a ball of radius `R / 2`.
pub const THRESHOLD: f64 = 0.5;

/// A scalar field `F: ℝ³ → ℝ` whose solid is `{P : F(P) ≥ ½}`.
///
/// Implemented by [`Blobs`](super::Blobs) (sums of point sources) and by
/// [`FieldCsg`](super::FieldCsg) (union, intersection and difference of two
/// fields). Marching cubes reads nothing else.
pub trait Field: Send + Sync {
    /// `F(p)`, adding the work done to `stats`.
    ///
    /// Must be finite for every finite `p`.
    fn value_counted(&self, p: DVec3, stats: &mut FieldStats) -> f64;

    /// A box outside of which `F < ½` everywhere, strictly (also on the
    /// box's own faces); [`Aabb::EMPTY`] when `F < ½` everywhere.
    fn bounds(&self) -> Aabb;

    /// A range holding every value [`value_counted`](Field::value_counted)
    /// returns at a point of the closed box `region` — the values as
    /// computed, rounding included, so that a range entirely below or
    /// entirely at or above ½ decides every sample in the box without
    /// evaluating one. The default, [`ValueRange::ANY`], decides nothing.
    fn bound(&self, region: &Aabb) -> ValueRange {
        let _ = region;
        ValueRange::ANY
    }

    /// `F(p)`.
    fn value(&self, p: DVec3) -> f64 {
        self.value_counted(p, &mut FieldStats::default())
    }

    /// Whether `p` is inside the solid: `F(p) ≥ ½`.
    fn contains(&self, p: DVec3) -> bool {
        self.value(p) >= THRESHOLD
    }
}

/// A closed range `[low, high]` of field values.
///
/// # Invariants
///
/// `low ≤ high`; either may be infinite, neither is NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValueRange {
    /// No value is below it.
    pub low: f64,
    /// No value is above it.
    pub high: f64,
}

impl ValueRange {
    /// The range that holds every value.
    pub const ANY: ValueRange = ValueRange {
        low: f64::NEG_INFINITY,
        high: f64::INFINITY,
    };

    /// Whether every value in the range is outside the solid (`< ½`).
    #[must_use]
    pub fn all_outside(&self) -> bool {
        self.high < THRESHOLD
    }

    /// Whether every value in the range is inside the solid (`≥ ½`).
    #[must_use]
    pub fn all_inside(&self) -> bool {
        self.low >= THRESHOLD
    }
}
