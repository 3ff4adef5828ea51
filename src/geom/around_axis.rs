//! Exact angular order of points around a line: what pairs the faces
//! around an edge (the builder's touching sheets, the validator's folds and
//! coincident edges) and orders the corners around a vertex.
//!
//! Every comparison is an exact `orient3d` sign on input coordinates and on
//! one chosen `f64` point that fixes the line; that point is a construction
//! (rounded), but whatever point it is, the order is exact for the line it
//! defines, and every statement below holds for any line.

use std::cmp::Ordering;

use glam::DVec3;

use crate::geom::{Sign, collinear3d, orient3d};

/// The angular order of points around the directed line from `origin`
/// through `toward`, seen as the angle of each point's projection onto a
/// plane across the line, measured from `reference`'s projection.
///
/// # Invariants
///
/// `origin ≠ toward`; `reference` and `second` are off the line and
/// `orient3d(origin, toward, reference, second) ≠ 0`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct AxisOrder {
    origin: DVec3,
    toward: DVec3,
    reference: DVec3,
    second: DVec3,
    /// `orient3d(origin, toward, second, reference)`.
    second_of_reference: Sign,
}

/// Where a point's projection is, from `reference`'s, turning the way
/// [`AxisOrder::turn`] calls positive.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum HalfTurn {
    /// The same direction as the reference (angle 0).
    Along,
    /// Strictly between 0 and a half-turn.
    First,
    /// Opposite the reference (a half-turn).
    Opposite,
    /// Strictly between a half-turn and a full turn.
    Second,
}

impl AxisOrder {
    /// The order around the line from `origin` through `toward`, measured
    /// from `reference`; `None` when `origin = toward`, when `reference` is on
    /// the line, or when no point among `others` (nor `reference` moved by
    /// one unit along an axis) is off the plane of the line and
    /// `reference`.
    pub fn new(
        origin: DVec3,
        toward: DVec3,
        reference: DVec3,
        others: impl IntoIterator<Item = DVec3>,
    ) -> Option<Self> {
        if origin == toward || !toward.is_finite() || collinear3d(origin, toward, reference) {
            return None;
        }
        let off_plane =
            |p: DVec3| p.is_finite() && orient3d(origin, toward, reference, p) != Sign::Zero;
        let second = others
            .into_iter()
            .chain([DVec3::X, DVec3::Y, DVec3::Z].map(|e| reference + e))
            .find(|&p| off_plane(p))?;
        Some(Self {
            origin,
            toward,
            reference,
            second,
            second_of_reference: orient3d(origin, toward, second, reference),
        })
    }

    /// The sign of the turn from `a`'s projection to `b`'s: positive when
    /// `b` is less than a half-turn ahead of `a`, negative when less than a
    /// half-turn behind, zero when the projections are parallel (same or
    /// opposite directions) or one is on the line.
    #[inline]
    pub fn turn(&self, a: DVec3, b: DVec3) -> Sign {
        orient3d(self.origin, self.toward, a, b)
    }

    /// Which half-turn `p` is in; `None` for a point on the line.
    pub fn half_turn(&self, p: DVec3) -> Option<HalfTurn> {
        match self.turn(self.reference, p) {
            Sign::Positive => Some(HalfTurn::First),
            Sign::Negative => Some(HalfTurn::Second),
            Sign::Zero => {
                // In the plane of the line and the reference: on the
                // reference's side of the line when `second`'s plane (which
                // also holds the line, and is another plane) puts it there.
                match orient3d(self.origin, self.toward, self.second, p) {
                    Sign::Zero => None,
                    s if s == self.second_of_reference => Some(HalfTurn::Along),
                    _ => Some(HalfTurn::Opposite),
                }
            }
        }
    }

    /// Compares the angles of two points off the line, given their
    /// half-turns: a total order (equal for equal angles).
    pub fn compare(&self, (ha, a): (HalfTurn, DVec3), (hb, b): (HalfTurn, DVec3)) -> Ordering {
        ha.cmp(&hb).then_with(|| match ha {
            HalfTurn::Along | HalfTurn::Opposite => Ordering::Equal,
            // Within an open half-turn the turn's sign is the order.
            HalfTurn::First | HalfTurn::Second => match self.turn(a, b) {
                Sign::Positive => Ordering::Less,
                Sign::Negative => Ordering::Greater,
                Sign::Zero => Ordering::Equal,
            },
        })
    }
}

/// The indices of `points` sorted by angle around the directed line from
/// `origin` through `toward`, counterclockwise (right-handed about the
/// line), starting from the first point's angle; `None` when the order is
/// not strict: a point on the line, two points at one angle, or all of
/// them in one plane with the line.
pub(crate) fn sorted_around(origin: DVec3, toward: DVec3, points: &[DVec3]) -> Option<Vec<usize>> {
    let (&first, rest) = points.split_first()?;
    let order = AxisOrder::new(origin, toward, first, rest.iter().copied())?;
    let mut sorted: Vec<(HalfTurn, usize)> = points
        .iter()
        .enumerate()
        .map(|(i, &p)| order.half_turn(p).map(|h| (h, i)))
        .collect::<Option<_>>()?;
    let compare = |&(ha, a): &(HalfTurn, usize), &(hb, b): &(HalfTurn, usize)| {
        order.compare((ha, points[a]), (hb, points[b]))
    };
    sorted.sort_by(compare);
    // Two points at one angle are neighbours once sorted.
    let tie = sorted.windows(2).any(|w| compare(&w[0], &w[1]).is_eq());
    (!tie).then(|| sorted.into_iter().map(|(_, i)| i).collect())
}
