//! Axis-aligned bounding boxes.

use glam::DVec3;

/// An axis-aligned box `[min, max]`.
///
/// # Invariants
///
/// A box built by [`Aabb::from_points`] or [`Aabb::grow`] from finite points
/// has `min <= max` componentwise. [`Aabb::EMPTY`] has `min = +∞`,
/// `max = −∞` and contains nothing.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Aabb {
    /// The smallest corner.
    pub min: DVec3,
    /// The largest corner.
    pub max: DVec3,
}

impl Aabb {
    /// The empty box: the identity of [`Aabb::union`].
    pub const EMPTY: Aabb = Aabb {
        min: DVec3::splat(f64::INFINITY),
        max: DVec3::splat(f64::NEG_INFINITY),
    };

    /// The smallest box holding every point (empty for no points).
    #[must_use]
    pub fn from_points(points: impl IntoIterator<Item = DVec3>) -> Aabb {
        points.into_iter().fold(Aabb::EMPTY, Aabb::grow)
    }

    /// This box grown to hold `p`.
    #[must_use]
    pub fn grow(self, p: DVec3) -> Aabb {
        Aabb {
            min: self.min.min(p),
            max: self.max.max(p),
        }
    }

    /// The smallest box holding both boxes.
    #[must_use]
    pub fn union(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The common part of both boxes (possibly empty).
    #[must_use]
    pub fn intersection(self, other: Aabb) -> Aabb {
        Aabb {
            min: self.min.max(other.min),
            max: self.max.min(other.max),
        }
    }

    /// Whether the box holds no point.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        !(self.min.x <= self.max.x && self.min.y <= self.max.y && self.min.z <= self.max.z)
    }

    /// Whether `p` is in the closed box.
    #[must_use]
    pub fn contains(&self, p: DVec3) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// `max − min` (negative components for the empty box).
    #[must_use]
    pub fn size(&self) -> DVec3 {
        self.max - self.min
    }

    /// The midpoint of the box.
    #[must_use]
    pub fn center(&self) -> DVec3 {
        (self.min + self.max) * 0.5
    }

    /// The length of the box's diagonal; 0 for the empty box. This is the
    /// "model size" that user tolerances are scaled by.
    #[must_use]
    pub fn diagonal(&self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            self.size().length()
        }
    }

    /// The box's volume; 0 for the empty box.
    #[must_use]
    pub fn volume(&self) -> f64 {
        if self.is_empty() {
            0.0
        } else {
            let s = self.size();
            s.x * s.y * s.z
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_box_is_the_identity_of_union() {
        let b = Aabb::from_points([DVec3::new(1., 2., 3.), DVec3::new(-1., 5., 0.)]);
        assert_eq!(b.union(Aabb::EMPTY), b);
        assert!(Aabb::EMPTY.is_empty());
        assert_eq!(Aabb::EMPTY.diagonal(), 0.0);
        assert_eq!(b.min, DVec3::new(-1., 2., 0.));
        assert_eq!(b.max, DVec3::new(1., 5., 3.));
        assert!(b.contains(DVec3::new(0., 3., 3.)));
        assert!(!b.contains(DVec3::new(0., 3., 3.5)));
        assert_eq!(b.volume(), 2.0 * 3.0 * 3.0);
        assert!(
            b.intersection(Aabb::from_points([DVec3::splat(10.)]))
                .is_empty()
        );
    }
}
