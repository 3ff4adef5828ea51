//! Field CSG: union, intersection and difference of two fields by `max`,
//! `min` and `min(a, 1 − b)`.

use crate::SetOp;
use glam::DVec3;

use crate::geom::Aabb;

use super::scalar_field::{Field, NodeBox, ValueRange};
use super::stats::FieldStats;

/// Two fields combined by a [`SetOp`]: itself a [`Field`], so trees nest.
///
/// - union: `max(a, b)`, inside where either is ≥ ½;
/// - intersection: `min(a, b)`, inside where both are ≥ ½;
/// - difference: `min(a, 1 − b)`, inside where `a ≥ ½` and `b ≤ ½` (the
///   points on B's surface stay in, so the result is closed); the reverse
///   difference is `min(b, 1 − a)`.
///
/// Unlike ray-cast CSG there is no boundary to merge: the combination is a
/// new scalar field whose ½ level set is the combined solid's surface, and
/// marching cubes meshes it like any other field.
pub struct FieldCsg {
    op: SetOp,
    a: Box<dyn Field>,
    b: Box<dyn Field>,
}

impl FieldCsg {
    /// `a op b`.
    #[must_use]
    pub fn new(op: SetOp, a: Box<dyn Field>, b: Box<dyn Field>) -> FieldCsg {
        FieldCsg { op, a, b }
    }

    /// The operator.
    #[must_use]
    pub fn op(&self) -> SetOp {
        self.op
    }
}

impl std::fmt::Debug for FieldCsg {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FieldCsg")
            .field("op", &self.op)
            .field("bounds", &self.bounds())
            .finish_non_exhaustive()
    }
}

impl Field for FieldCsg {
    fn value_counted(&self, p: DVec3, stats: &mut FieldStats) -> f64 {
        let a = self.a.value_counted(p, stats);
        let b = self.b.value_counted(p, stats);
        match self.op {
            SetOp::Union => a.max(b),
            SetOp::Intersection => a.min(b),
            SetOp::Difference => a.min(1.0 - b),
            SetOp::ReverseDifference => b.min(1.0 - a),
        }
    }

    /// Both operands sampled over the box, then combined node by node
    /// (the same values as node by node).
    fn sample_nodes(&self, nodes: &NodeBox, values: &mut [f64], stats: &mut FieldStats) {
        self.a.sample_nodes(nodes, values, stats);
        let mut other = vec![0.0; values.len()];
        self.b.sample_nodes(nodes, &mut other, stats);
        for (a, b) in values.iter_mut().zip(other) {
            *a = match self.op {
                SetOp::Union => a.max(b),
                SetOp::Intersection => a.min(b),
                SetOp::Difference => a.min(1.0 - b),
                SetOp::ReverseDifference => b.min(1.0 - *a),
            };
        }
    }

    /// The operator applied to the ends of the operands' ranges: `max` and
    /// `min` are exact and monotone, and so is the rounded `1 − b`, so the
    /// ends bound the computed values.
    fn bound(&self, region: &Aabb) -> ValueRange {
        let (a, b) = (self.a.bound(region), self.b.bound(region));
        match self.op {
            SetOp::Union => ValueRange {
                low: a.low.max(b.low),
                high: a.high.max(b.high),
            },
            SetOp::Intersection => ValueRange {
                low: a.low.min(b.low),
                high: a.high.min(b.high),
            },
            SetOp::Difference => ValueRange {
                low: a.low.min(1.0 - b.high),
                high: a.high.min(1.0 - b.low),
            },
            SetOp::ReverseDifference => ValueRange {
                low: b.low.min(1.0 - a.high),
                high: b.high.min(1.0 - a.low),
            },
        }
    }

    fn bounds(&self) -> Aabb {
        let (a, b) = (self.a.bounds(), self.b.bounds());
        match self.op {
            SetOp::Union => match (a.is_empty(), b.is_empty()) {
                (true, _) => b,
                (_, true) => a,
                _ => a.union(b),
            },
            SetOp::Intersection => {
                let both = a.intersection(b);
                if both.is_empty() { Aabb::EMPTY } else { both }
            }
            SetOp::Difference => a,
            SetOp::ReverseDifference => b,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::field::{Blobs, Falloff, Source};

    fn ball(x: f64) -> Box<dyn Field> {
        let s = Source::try_unit(DVec3::new(x, 0.0, 0.0), 2.0).unwrap();
        Box::new(Blobs::try_new(vec![s], Falloff::SoftObject).unwrap())
    }

    #[test]
    fn the_operators_follow_max_min_and_one_minus() {
        // Two balls of radius 1 at x = 0 and x = 1.5.
        let probe =
            |op, x: f64| FieldCsg::new(op, ball(0.0), ball(1.5)).contains(DVec3::new(x, 0.0, 0.0));
        for (x, union, inter, diff) in [
            (-0.9, true, false, true),
            (0.75, true, true, false),
            (2.4, true, false, false),
            (3.0, false, false, false),
        ] {
            assert_eq!(probe(SetOp::Union, x), union, "union at {x}");
            assert_eq!(probe(SetOp::Intersection, x), inter, "intersection at {x}");
            assert_eq!(probe(SetOp::Difference, x), diff, "difference at {x}");
        }
        let far = FieldCsg::new(SetOp::Intersection, ball(0.0), ball(10.0));
        assert!(far.bounds().is_empty());
        let d = FieldCsg::new(SetOp::Difference, ball(0.0), ball(10.0));
        assert_eq!(d.bounds(), ball(0.0).bounds());
    }
}
