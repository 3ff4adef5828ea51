//! Rays and segments: `P(t) = origin + t · direction`.

use glam::DVec3;

/// A ray `P(t) = origin + t · direction` for `t ≥ 0` (`E + t D`: eye and
/// direction).
///
/// The direction need not be unit length; parameters `t` are measured in
/// multiples of it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ray {
    /// The eye point `E`.
    pub origin: DVec3,
    /// The direction `D`.
    pub direction: DVec3,
}

impl Ray {
    /// A ray from `origin` along `direction`.
    #[must_use]
    pub fn new(origin: DVec3, direction: DVec3) -> Ray {
        Ray { origin, direction }
    }

    /// The point at parameter `t`: `origin + t · direction` (rounded).
    #[must_use]
    pub fn at(&self, t: f64) -> DVec3 {
        self.origin + self.direction * t
    }

    /// Whether both origin and direction are finite and the direction is not
    /// zero: the rays every query accepts.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.origin.is_finite() && self.direction.is_finite() && self.direction != DVec3::ZERO
    }
}

/// The segment `P(u) = start + u · (end − start)` for `u ∈ [0, 1]` (the finite
/// line from `P1` to `P2`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Segment {
    /// `P1`, at `u = 0`.
    pub start: DVec3,
    /// `P2`, at `u = 1`.
    pub end: DVec3,
}

impl Segment {
    /// The segment from `start` to `end`.
    #[must_use]
    pub fn new(start: DVec3, end: DVec3) -> Segment {
        Segment { start, end }
    }

    /// The point at parameter `u` (rounded).
    #[must_use]
    pub fn at(&self, u: f64) -> DVec3 {
        self.start + (self.end - self.start) * u
    }

    /// The segment's length.
    #[must_use]
    pub fn length(&self) -> f64 {
        (self.end - self.start).length()
    }
}
