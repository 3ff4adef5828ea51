//! Closed boxes (octree cells) against primitives and trees: inside,
//! outside, or possibly met by the boundary.
//!
//! A primitive answers one box with a [`CellRelation`]
//! ([`Primitive::cell_relation`]). A tree combines its leaves' answers by
//! its operators in three-valued logic ([`Csg::cell_verdict`]): a box
//! inside or outside every leaf that matters gets the tree's label; a box
//! the boundary of a leaf may meet is [`CellVerdict::Undecided`] only when
//! that leaf's side could change the answer (in `A ∩ B`, a box outside `B`
//! is outside whatever `A` does). What is learnt of a leaf on a box holds
//! for every box inside it, so [`LeafSides`] is handed down to sub-boxes
//! and only the leaves still undecided are asked again.

use crate::SetOp;
use glam::DVec3;
use thiserror::Error;

use super::tree::{LeafId, NodeIndex, NodeKind};
use super::{Containment, Csg, Primitive, Stats};
use crate::geom::Aabb;
use crate::query::TileError;

/// How a closed box lies against a primitive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellRelation {
    /// The closed box lies in the solid's interior.
    Inside,
    /// The closed box lies in the solid's exterior.
    Outside,
    /// The boundary does not meet the closed box: the box is wholly inside
    /// or wholly outside, and one point of it tells which.
    Apart,
    /// The boundary may meet the closed box: exactly when it does for flat
    /// primitives (half-spaces, boxes, polyhedra, transformed or not),
    /// conservatively for curved ones.
    Meets,
}

/// A relative bound on the rounding of the few sums of products that the
/// curved primitives' box tests compute (differences, squares, dot
/// products of three terms: each below `8 ε` of the sum of magnitudes);
/// `32 ε` leaves room for the rounding of the bound itself. A rounding
/// bound, not a tolerance: it only makes the `Inside` and `Outside`
/// answers certain, moving doubtful boxes to [`CellRelation::Meets`].
pub(crate) const CELL_ROUNDING: f64 = 32.0 * f64::EPSILON;

/// An absolute term covering products that underflow.
pub(crate) const CELL_UNDERFLOW: f64 = f64::MIN_POSITIVE;

/// The eight corners of a box.
pub(crate) fn corners(b: &Aabb) -> [DVec3; 8] {
    std::array::from_fn(|k| {
        DVec3::new(
            if k & 1 == 0 { b.min.x } else { b.max.x },
            if k & 2 == 0 { b.min.y } else { b.max.y },
            if k & 4 == 0 { b.min.z } else { b.max.z },
        )
    })
}

/// The centre of a box, rounded, but inside it.
pub(crate) fn centre(b: &Aabb) -> DVec3 {
    (b.min + (b.max - b.min) * 0.5).clamp(b.min, b.max)
}

/// A tree's answer for a box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CellVerdict {
    /// The closed box lies in the interior of the tree's solid.
    Inside,
    /// The closed box lies in its exterior.
    Outside,
    /// The boundary of a leaf whose side matters may meet the box.
    Undecided,
}

/// What is known of each leaf on a box: `Some(true)` inside, `Some(false)`
/// outside, `None` not known (not asked yet, or its boundary may meet the
/// box). Valid for every box inside the one it was learnt on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct LeafSides(Vec<Option<bool>>);

impl LeafSides {
    /// Nothing known of any leaf of `csg`.
    #[must_use]
    pub fn unknown(csg: &Csg) -> LeafSides {
        LeafSides(vec![None; csg.leaves.len()])
    }

    /// How many leaves are known.
    #[must_use]
    pub fn known(&self) -> usize {
        self.0.iter().filter(|s| s.is_some()).count()
    }

    /// The side of `leaf`, if known.
    #[must_use]
    pub fn side(&self, leaf: LeafId) -> Option<bool> {
        self.0.get(leaf.0 as usize).copied().flatten()
    }
}

/// Whether the closed boxes `a` and `b` share no point, with `b` first
/// grown by its rounding allowance (the bounds of curved and transformed
/// primitives are rounded constructions).
fn apart(a: &Aabb, b: &Aabb) -> bool {
    if b.is_empty() {
        return true;
    }
    let pad = (b.min.abs().max(b.max.abs())) * CELL_ROUNDING + DVec3::splat(CELL_UNDERFLOW);
    let (lo, hi) = (b.min - pad, b.max + pad);
    a.max.cmplt(lo).any() || a.min.cmpgt(hi).any()
}

/// A leaf that cannot answer boxes exactly.
#[derive(Clone, Debug, Error, PartialEq)]
#[error("leaf {leaf}: {source}")]
pub struct LeafTileError {
    /// The leaf's label (a scene's JSON path).
    pub leaf: String,
    /// Why.
    pub source: TileError,
}

/// `primitive.classify_point(p)`, counted.
fn count_point(stats: &mut Stats, primitive: &dyn Primitive, p: DVec3) -> Containment {
    stats.primitive_point_tests += 1;
    primitive.classify_point(p)
}

impl Csg {
    /// Makes every leaf ready for [`Csg::cell_verdict`] (a polyhedron tiles
    /// its faces exactly), so that no box is answered conservatively
    /// because of a face that could not be tiled.
    ///
    /// # Errors
    ///
    /// [`LeafTileError`] naming the first leaf that cannot.
    pub fn prepare_cells(&self) -> Result<(), LeafTileError> {
        for leaf in &self.leaves {
            leaf.primitive
                .prepare_cells()
                .map_err(|source| LeafTileError {
                    leaf: leaf.label.clone(),
                    source,
                })?;
        }
        Ok(())
    }

    /// How the closed box `cell` lies against the tree's solid, using and
    /// extending what `sides` knows of the leaves (learnt on `cell` or a box
    /// holding it). Subtrees whose bounds the box misses are outside
    /// without a question to their leaves; the right operand of an
    /// intersection or difference is not asked when the left one already
    /// decides, nor the right operand of a union whose left one is inside.
    /// A leaf whose boundary is apart from the box is decided by
    /// classifying the box's centre. The work is counted in `stats`
    /// (`primitive_cell_tests`, `primitive_point_tests`, `bounds_tests`,
    /// `culled_subtrees`, `skipped_right_sides`).
    pub fn cell_verdict(
        &self,
        cell: &Aabb,
        sides: &mut LeafSides,
        stats: &mut Stats,
    ) -> CellVerdict {
        self.cell_verdict_beside(cell, sides, stats, &|_| None)
    }

    /// [`Csg::cell_verdict`], where a leaf whose boundary is apart from the
    /// box may take its side from `neighbour` instead of a point
    /// classification: `neighbour(leaf)` is the leaf's side on a box that
    /// shares a face with this one and that the leaf's boundary does not
    /// meet either (the two closed boxes together are connected and miss
    /// the boundary, so they lie on one side of it), or `None`.
    pub fn cell_verdict_beside(
        &self,
        cell: &Aabb,
        sides: &mut LeafSides,
        stats: &mut Stats,
        neighbour: &dyn Fn(LeafId) -> Option<bool>,
    ) -> CellVerdict {
        self.node_verdict(self.root, cell, sides, stats, neighbour)
    }

    fn node_verdict(
        &self,
        node: NodeIndex,
        cell: &Aabb,
        sides: &mut LeafSides,
        stats: &mut Stats,
        neighbour: &dyn Fn(LeafId) -> Option<bool>,
    ) -> CellVerdict {
        use CellVerdict::{Inside, Outside, Undecided};
        let n = &self.nodes[node];
        stats.bounds_tests += 1;
        if apart(cell, &n.bounds) {
            stats.culled_subtrees += 1;
            return Outside;
        }
        match n.kind {
            NodeKind::Leaf(id) => {
                let slot = &mut sides.0[id.0 as usize];
                if let Some(inside) = *slot {
                    return if inside { Inside } else { Outside };
                }
                let primitive: &dyn Primitive = &*self.leaves[id.0 as usize].primitive;
                stats.primitive_cell_tests += 1;
                let inside = match primitive.cell_relation(cell) {
                    CellRelation::Inside => true,
                    CellRelation::Outside => false,
                    CellRelation::Meets => return Undecided,
                    CellRelation::Apart => match neighbour(id).map_or_else(
                        || count_point(stats, primitive, centre(cell)),
                        |inside| {
                            if inside {
                                Containment::Inside
                            } else {
                                Containment::Outside
                            }
                        },
                    ) {
                        Containment::Inside => true,
                        Containment::Outside => false,
                        // Apart from the boundary yet on it: only a rounded
                        // primitive could say so; stay conservative.
                        Containment::OnBoundary => return Undecided,
                    },
                };
                *slot = Some(inside);
                if inside { Inside } else { Outside }
            }
            NodeKind::Op { op, left, right } => {
                let a = self.node_verdict(left, cell, sides, stats, neighbour);
                match op {
                    SetOp::Union => {
                        if a == Inside {
                            stats.skipped_right_sides += 1;
                            return Inside;
                        }
                        match self.node_verdict(right, cell, sides, stats, neighbour) {
                            Inside => Inside,
                            Outside => a,
                            Undecided => Undecided,
                        }
                    }
                    SetOp::Intersection => {
                        if a == Outside {
                            stats.skipped_right_sides += 1;
                            return Outside;
                        }
                        match self.node_verdict(right, cell, sides, stats, neighbour) {
                            Outside => Outside,
                            Inside => a,
                            Undecided => Undecided,
                        }
                    }
                    SetOp::Difference => {
                        if a == Outside {
                            stats.skipped_right_sides += 1;
                            return Outside;
                        }
                        match self.node_verdict(right, cell, sides, stats, neighbour) {
                            Inside => Outside,
                            Outside => a,
                            Undecided => Undecided,
                        }
                    }
                    SetOp::ReverseDifference => {
                        // right − left.
                        if a == Inside {
                            stats.skipped_right_sides += 1;
                            return Outside;
                        }
                        match self.node_verdict(right, cell, sides, stats, neighbour) {
                            Outside => Outside,
                            Inside if a == Outside => Inside,
                            _ => Undecided,
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::csg::{AxisBox, CsgExpr, Cylinder, HalfSpace, Sphere, Transformed};

    fn cube(min: f64, max: f64) -> Aabb {
        Aabb {
            min: DVec3::splat(min),
            max: DVec3::splat(max),
        }
    }

    trait Shift {
        fn translate(self, x: f64) -> Aabb;
    }

    impl Shift for Aabb {
        fn translate(self, x: f64) -> Aabb {
            let d = DVec3::new(x, 0.0, 0.0);
            Aabb {
                min: self.min + d,
                max: self.max + d,
            }
        }
    }

    #[test]
    fn a_box_on_one_operand_but_outside_the_other_is_outside_their_intersection() {
        let a = CsgExpr::leaf(AxisBox::try_new(DVec3::ZERO, DVec3::ONE).unwrap());
        let b = CsgExpr::leaf(AxisBox::try_new(DVec3::splat(2.0), DVec3::splat(3.0)).unwrap());
        let csg = Csg::try_new(a.clone().intersection(b.clone())).unwrap();
        // On a's boundary (touches x = 1), far from b.
        let cell = cube(0.75, 1.25);
        let mut sides = LeafSides::unknown(&csg);
        assert_eq!(
            csg.cell_verdict(&cell, &mut sides, &mut Stats::default()),
            CellVerdict::Outside
        );
        let union = Csg::try_new(a.clone().union(b.clone())).unwrap();
        let mut sides = LeafSides::unknown(&union);
        assert_eq!(
            union.cell_verdict(&cell, &mut sides, &mut Stats::default()),
            CellVerdict::Undecided
        );
        // Inside a, the cut b is far: a − b holds the box.
        let diff = Csg::try_new(a.difference(b)).unwrap();
        let mut sides = LeafSides::unknown(&diff);
        assert_eq!(
            diff.cell_verdict(&cube(0.25, 0.5), &mut sides, &mut Stats::default()),
            CellVerdict::Inside
        );
    }

    #[test]
    fn a_sphere_answers_conservatively() {
        let s = Sphere::try_new(DVec3::ZERO, 1.0).unwrap();
        assert_eq!(s.cell_relation(&cube(-0.5, 0.5)), CellRelation::Inside);
        assert_eq!(s.cell_relation(&cube(0.9, 1.0)), CellRelation::Outside);
        assert_eq!(s.cell_relation(&cube(0.5, 1.0)), CellRelation::Meets);
        // Touching at one point: the boundary meets the closed box.
        let touching = Aabb {
            min: DVec3::new(1.0, -0.5, -0.5),
            max: DVec3::new(2.0, 0.5, 0.5),
        };
        assert_eq!(s.cell_relation(&touching), CellRelation::Meets);
    }

    #[test]
    fn flat_primitives_answer_exactly() {
        let h = HalfSpace::try_new(DVec3::splat(0.5), DVec3::new(1.0, 1.0, 0.0)).unwrap();
        // x + y ≤ 1: the cell [0, ½]³ touches the plane at its corner.
        assert_eq!(h.cell_relation(&cube(0.0, 0.5)), CellRelation::Meets);
        assert_eq!(
            h.cell_relation(&cube(0.0, 0.5f64.next_down())),
            CellRelation::Inside
        );
        assert_eq!(
            h.cell_relation(&cube(0.5f64.next_up(), 1.0)),
            CellRelation::Outside
        );
        let b = AxisBox::try_new(DVec3::ZERO, DVec3::ONE).unwrap();
        assert_eq!(b.cell_relation(&cube(0.25, 0.75)), CellRelation::Inside);
        assert_eq!(b.cell_relation(&cube(0.5, 1.0)), CellRelation::Meets);
        assert_eq!(b.cell_relation(&cube(1.0, 2.0)), CellRelation::Meets);
        assert_eq!(
            b.cell_relation(&cube(1f64.next_up(), 2.0)),
            CellRelation::Outside
        );
    }

    #[test]
    fn a_cylinder_and_a_transformed_sphere_answer_conservatively_a_transformed_box_exactly() {
        let c = Cylinder::try_new(DVec3::ZERO, DVec3::new(0.0, 0.0, 4.0), 1.0).unwrap();
        let cell = |min: [f64; 3], max: [f64; 3]| Aabb {
            min: DVec3::from(min),
            max: DVec3::from(max),
        };
        assert_eq!(
            c.cell_relation(&cell([-0.5, -0.5, 1.0], [0.5, 0.5, 2.0])),
            CellRelation::Inside
        );
        // Beyond the side (a separating axis along x), beyond the top cap.
        assert_eq!(
            c.cell_relation(&cell([1.25, -0.25, 1.0], [1.75, 0.25, 2.0])),
            CellRelation::Outside
        );
        assert_eq!(
            c.cell_relation(&cell([-0.5, -0.5, 4.5], [0.5, 0.5, 5.0])),
            CellRelation::Outside
        );
        assert_eq!(
            c.cell_relation(&cell([0.5, -0.25, 1.0], [1.5, 0.25, 2.0])),
            CellRelation::Meets
        );
        let moved: std::sync::Arc<dyn Primitive> =
            std::sync::Arc::new(AxisBox::try_new(DVec3::ZERO, DVec3::ONE).unwrap());
        let t = Transformed::try_new(
            moved,
            glam::DAffine3::from_translation(DVec3::new(10.0, 0.0, 0.0)),
        )
        .unwrap();
        // A moved box is a polyhedron in world coordinates: exact.
        assert_eq!(
            t.cell_relation(&cube(0.25, 0.75).translate(10.0)),
            CellRelation::Apart
        );
        assert_eq!(
            t.cell_relation(&cube(0.5, 1.0).translate(10.0)),
            CellRelation::Meets
        );
        assert_eq!(t.cell_relation(&cube(0.25, 0.75)), CellRelation::Outside);
        // A moved sphere answers its own test on the cell's image.
        let ball: std::sync::Arc<dyn Primitive> =
            std::sync::Arc::new(Sphere::try_new(DVec3::ZERO, 1.0).unwrap());
        let t = Transformed::try_new(
            ball,
            glam::DAffine3::from_translation(DVec3::new(10.0, 0.0, 0.0)),
        )
        .unwrap();
        assert_eq!(
            t.cell_relation(&cube(-0.25, 0.25).translate(10.0)),
            CellRelation::Inside
        );
        assert_eq!(t.cell_relation(&cube(2.0, 3.0)), CellRelation::Outside);
    }
}
