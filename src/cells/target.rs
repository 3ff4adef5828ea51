//! What an octree is laid over: a closed solid or a CSG tree, each saying
//! how a cell lies. The octree's refinement, labelling and outputs are
//! written once, over [`CellTarget`].

use std::cell::RefCell;

use glam::DVec3;

use super::label::Label;
use crate::csg::{CellVerdict, Csg, LeafSides, Stats};
use crate::geom::Aabb;
use crate::query::{Accel, BoundaryTiles, Containment};

/// How a cell lies against a target.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Judgement {
    /// In the interior.
    In,
    /// In the exterior.
    Out,
    /// The boundary does not meet the closed cell: the label is its
    /// region's, found by one point classification.
    Free,
    /// The boundary may meet the closed cell: refined, or `On` at the
    /// finest depth.
    Meets,
}

/// A solid the octree can be laid over.
pub(crate) trait CellTarget {
    /// What a cell learns that holds for its sub-cells too.
    type Known: Clone;

    /// What is known before the root is judged.
    fn root_known(&self) -> Self::Known;

    /// How the closed `cell` lies; `known` was learnt on the cell's parent
    /// and is extended for its children.
    fn judge(&self, cell: &Aabb, known: &mut Self::Known) -> Judgement;

    /// The label of a point of a [`Judgement::Free`] region.
    fn classify(&self, p: DVec3) -> Label;
}

/// A closed solid: `Meets` exactly when a face meets the cell, every other
/// cell `Free`.
pub(crate) struct SolidTarget {
    pub(crate) accel: Accel,
    pub(crate) tiles: BoundaryTiles,
}

impl CellTarget for SolidTarget {
    type Known = ();

    fn root_known(&self) {}

    fn judge(&self, cell: &Aabb, (): &mut ()) -> Judgement {
        if self.tiles.meets(cell) {
            Judgement::Meets
        } else {
            Judgement::Free
        }
    }

    fn classify(&self, p: DVec3) -> Label {
        match self.accel.classify(p) {
            Ok(Containment::Inside) => Label::In,
            Ok(Containment::Outside) => Label::Out,
            // The closed cell meets no boundary: neither can happen; `On`
            // would still be a safe (conservative) answer.
            Ok(Containment::OnBoundary) | Err(_) => Label::On,
        }
    }
}

/// A CSG tree: each cell decided by [`Csg::cell_verdict`], what is learnt
/// of the leaves handed down to the sub-cells.
pub(crate) struct CsgTarget<'a> {
    pub(crate) csg: &'a Csg,
    /// The work of the tree's queries.
    pub(crate) stats: RefCell<Stats>,
}

impl CellTarget for CsgTarget<'_> {
    type Known = LeafSides;

    fn root_known(&self) -> LeafSides {
        LeafSides::unknown(self.csg)
    }

    fn judge(&self, cell: &Aabb, known: &mut LeafSides) -> Judgement {
        match self
            .csg
            .cell_verdict(cell, known, &mut self.stats.borrow_mut())
        {
            CellVerdict::Inside => Judgement::In,
            CellVerdict::Outside => Judgement::Out,
            CellVerdict::Undecided => Judgement::Meets,
        }
    }

    fn classify(&self, p: DVec3) -> Label {
        match self.csg.classify_point(p, &mut self.stats.borrow_mut()) {
            Containment::Inside => Label::In,
            Containment::Outside => Label::Out,
            Containment::OnBoundary => Label::On,
        }
    }
}
