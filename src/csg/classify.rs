//! Points against a tree, right at coincident faces.

use crate::SetOp;
use glam::DVec3;

use super::stats::counting_fallbacks;
use super::tree::{NodeIndex, NodeKind};
use super::{Containment, Csg, Stats, normal_alignment};
use crate::geom::Sign;
use crate::query::QueryError;

/// What a solid looks like in an infinitesimal neighbourhood of a point:
/// the information the tree needs to combine boundary points correctly.
///
/// A point inside a face (or on a smooth part of a curved surface) sees a
/// half-space bounded by the face, described by its outward normal. Two
/// touching boxes combine `Face(+x)` and `Face(−x)` into `Inside` for their
/// union; a point where B cuts A's interior is `Inside` for A and `Face` for
/// B, hence `Face` (on the boundary) for `A − B`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Neighbourhood {
    /// Everything near the point is inside.
    Inside,
    /// Everything near the point is outside.
    Outside,
    /// The point is inside a face; the solid lies opposite this outward
    /// normal.
    Face(DVec3),
    /// The point is on the boundary, at an edge, a corner or where several
    /// surfaces meet at an angle.
    Complex,
}

impl Neighbourhood {
    /// The three-way answer.
    #[must_use]
    pub fn containment(self) -> Containment {
        match self {
            Neighbourhood::Inside => Containment::Inside,
            Neighbourhood::Outside => Containment::Outside,
            Neighbourhood::Face(_) | Neighbourhood::Complex => Containment::OnBoundary,
        }
    }

    /// The complement's neighbourhood (regularised: a face flips).
    #[must_use]
    pub fn complement(self) -> Neighbourhood {
        match self {
            Neighbourhood::Inside => Neighbourhood::Outside,
            Neighbourhood::Outside => Neighbourhood::Inside,
            Neighbourhood::Face(n) => Neighbourhood::Face(-n),
            Neighbourhood::Complex => Neighbourhood::Complex,
        }
    }

    /// The neighbourhood of `A ∪ B` (regularised).
    #[must_use]
    pub fn union(self, other: Neighbourhood) -> Neighbourhood {
        use Neighbourhood::*;
        match (self, other) {
            (Inside, _) | (_, Inside) => Inside,
            (Outside, x) | (x, Outside) => x,
            (Face(a), Face(b)) => match normal_alignment(a, b) {
                // Two faces back to back: the shared face is interior.
                Sign::Negative => Inside,
                Sign::Positive => Face(a),
                Sign::Zero => Complex,
            },
            _ => Complex,
        }
    }

    /// The neighbourhood of `A ∩ B` (regularised: two faces back to back
    /// meet in a face with no volume, which is outside).
    #[must_use]
    pub fn intersection(self, other: Neighbourhood) -> Neighbourhood {
        self.complement().union(other.complement()).complement()
    }

    /// The neighbourhood of the combination `op` of `self` (A) and `other`
    /// (B).
    #[must_use]
    pub fn combine(self, op: SetOp, other: Neighbourhood) -> Neighbourhood {
        match op {
            SetOp::Union => self.union(other),
            SetOp::Intersection => self.intersection(other),
            SetOp::Difference => self.intersection(other.complement()),
            SetOp::ReverseDifference => self.complement().intersection(other),
        }
    }
}

impl Csg {
    /// Where `p` lies relative to the combined solid: `OnBoundary` on its
    /// (regularised) boundary. A point on the shared face of two touching
    /// solids is inside their union; a point on a face of B inside A is on
    /// the boundary of `A − B`.
    ///
    /// Exact when every leaf involved is exact at `p` (half-spaces, boxes,
    /// polyhedra). Two faces are recognised as coincident when their normals
    /// are exactly parallel. Where surfaces meet at an angle (edges,
    /// corners, faces of two meshes whose rounded normals differ), the
    /// point is decided by one direction per cell of the planes through it
    /// (counted in `stats.direction_analyses`): two boxes that share only a
    /// face have an empty intersection, so even their shared corners are
    /// `Outside`. Points where a curved leaf's boundary meets
    /// another surface at an angle stay `OnBoundary` (see
    /// [`Primitive::planes_through`](super::Primitive::planes_through)).
    ///
    /// A point with a NaN or infinite coordinate is answered `Outside`;
    /// [`Csg::try_classify_point`] refuses it instead.
    pub fn classify_point(&self, p: DVec3, stats: &mut Stats) -> Containment {
        match self.neighbourhood(p, stats) {
            Neighbourhood::Complex => counting_fallbacks(stats, |stats| {
                self.classify_by_directions(p, stats)
                    .unwrap_or(Containment::OnBoundary)
            }),
            n => n.containment(),
        }
    }

    /// [`Csg::classify_point`] for points from users: a non-finite point is
    /// an error, not an answer.
    ///
    /// # Errors
    ///
    /// [`QueryError::NonFinitePoint`] (index 0) for a NaN or infinite
    /// coordinate.
    pub fn try_classify_point(
        &self,
        p: DVec3,
        stats: &mut Stats,
    ) -> Result<Containment, QueryError> {
        if !p.is_finite() {
            return Err(QueryError::NonFinitePoint { index: 0, point: p });
        }
        Ok(self.classify_point(p, stats))
    }

    /// The neighbourhood of `p` in the combined solid (`Outside` for a
    /// non-finite point).
    pub fn neighbourhood(&self, p: DVec3, stats: &mut Stats) -> Neighbourhood {
        if !p.is_finite() {
            return Neighbourhood::Outside;
        }
        counting_fallbacks(stats, |stats| self.node_neighbourhood(self.root, p, stats))
    }

    fn node_neighbourhood(&self, node: NodeIndex, p: DVec3, stats: &mut Stats) -> Neighbourhood {
        let n = &self.nodes[node];
        stats.bounds_tests += 1;
        if !n.bounds.contains(p) {
            stats.culled_subtrees += 1;
            return Neighbourhood::Outside;
        }
        match n.kind {
            NodeKind::Leaf(id) => {
                stats.primitive_point_tests += 1;
                let primitive = &self.leaves[id.0 as usize].primitive;
                match primitive.classify_point(p) {
                    Containment::Inside => Neighbourhood::Inside,
                    Containment::Outside => Neighbourhood::Outside,
                    Containment::OnBoundary => primitive
                        .boundary_normal(p)
                        .map_or(Neighbourhood::Complex, Neighbourhood::Face),
                }
            }
            NodeKind::Op { op, left, right } => {
                let a = self.node_neighbourhood(left, p, stats);
                let decided = match (op, a) {
                    (SetOp::Union, Neighbourhood::Inside) => Some(Neighbourhood::Inside),
                    (SetOp::Intersection | SetOp::Difference, Neighbourhood::Outside) => {
                        Some(Neighbourhood::Outside)
                    }
                    (SetOp::ReverseDifference, Neighbourhood::Inside) => {
                        Some(Neighbourhood::Outside)
                    }
                    _ => None,
                };
                if let Some(answer) = decided {
                    stats.skipped_right_sides += 1;
                    return answer;
                }
                let b = self.node_neighbourhood(right, p, stats);
                a.combine(op, b)
            }
        }
    }
}
