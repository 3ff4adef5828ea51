//! What an octree is laid over: a closed solid or a CSG tree, each saying
//! how a cell lies. The octree's refinement, labelling and outputs are
//! written once, over [`CellTarget`].

use std::cell::{Cell, RefCell};
use std::rc::Rc;
use std::sync::Arc;

use glam::DVec3;

use super::label::Label;
use crate::csg::{CellVerdict, Csg, LeafId, LeafSides, Stats};
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
    /// (and its siblings) and is extended for its children.
    fn judge(&self, cell: &Aabb, known: &mut Self::Known) -> Judgement;

    /// What each of the eight children of a cell starts from, child `k`
    /// at offset `(k & 1, k >> 1 & 1, k >> 2)` with the closed box
    /// `children[k]`; `finest` when the children are at the octree's finest
    /// depth, where they are judged but never split.
    fn split(&self, known: &Self::Known, children: &[Aabb; 8], finest: bool) -> [Self::Known; 8];

    /// The label of a point of a [`Judgement::Free`] region.
    fn classify(&self, p: DVec3) -> Label;
}

/// A closed solid: `Meets` exactly when a face meets the cell, every other
/// cell `Free`. A refined cell sorts the triangles that meet it among its
/// eight sub-cells in one pass (see [`BoundaryTiles::meeting_children`]),
/// and a sub-cell is judged by its list alone: a cell costs what meets its
/// parent, whatever the triangles' boxes.
pub(crate) struct SolidTarget {
    pub(crate) accel: Accel,
    pub(crate) tiles: BoundaryTiles,
}

/// What a cell of a solid knows: the triangles that may meet it, made by
/// its parent's split (`None` at the root until it is judged), and whether
/// they certainly do. The list holds every triangle that meets the cell;
/// at the finest depth it holds one that meets it exactly, or none.
#[derive(Clone, Debug)]
pub(crate) struct SolidKnown {
    meeting: Option<Arc<[u32]>>,
    certain: bool,
}

impl CellTarget for SolidTarget {
    type Known = SolidKnown;

    fn root_known(&self) -> SolidKnown {
        SolidKnown {
            meeting: None,
            certain: false,
        }
    }

    fn split(&self, known: &SolidKnown, children: &[Aabb; 8], finest: bool) -> [SolidKnown; 8] {
        let parent = known.meeting.as_deref().unwrap_or_default();
        self.tiles
            .meeting_children(parent, children, finest)
            .map(|list| SolidKnown {
                meeting: Some(list.into()),
                certain: finest,
            })
    }

    fn judge(&self, cell: &Aabb, known: &mut SolidKnown) -> Judgement {
        let meets = match &known.meeting {
            None => {
                let list: Arc<[u32]> = self.tiles.meeting(cell).into();
                let meets = !list.is_empty();
                known.meeting = Some(list);
                meets
            }
            Some(list) if known.certain => !list.is_empty(),
            Some(list) => self.tiles.meets_among(cell, list),
        };
        if meets {
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

/// What a cell of a CSG tree knows: the leaves' sides learnt on it and
/// above, and what its siblings learnt.
#[derive(Clone, Debug)]
pub(crate) struct CsgKnown {
    sides: LeafSides,
    /// The sides learnt by the siblings judged so far, by position.
    family: Rc<RefCell<[Option<LeafSides>; 8]>>,
    /// This cell's position among its siblings.
    position: usize,
}

/// A CSG tree: each cell decided by [`Csg::cell_verdict_beside`], what is
/// learnt of the leaves handed down to the sub-cells. A leaf whose
/// boundary misses a cell takes its side from a sibling sharing a face
/// with the cell that learnt it (their closed union is connected and
/// misses the boundary too); only otherwise is a point classified.
pub(crate) struct CsgTarget<'a> {
    pub(crate) csg: &'a Csg,
    /// The work of the tree's queries.
    pub(crate) stats: RefCell<Stats>,
}

impl CellTarget for CsgTarget<'_> {
    type Known = CsgKnown;

    fn root_known(&self) -> CsgKnown {
        CsgKnown {
            sides: LeafSides::unknown(self.csg),
            family: Rc::default(),
            position: 0,
        }
    }

    fn split(&self, known: &CsgKnown, _children: &[Aabb; 8], _finest: bool) -> [CsgKnown; 8] {
        let family = Rc::default();
        std::array::from_fn(|position| CsgKnown {
            sides: known.sides.clone(),
            family: Rc::clone(&family),
            position,
        })
    }

    fn judge(&self, cell: &Aabb, known: &mut CsgKnown) -> Judgement {
        let mut stats = self.stats.borrow_mut();
        let classified = stats.primitive_point_tests;
        let borrowed = Cell::new(false);
        let verdict = {
            let family = known.family.borrow();
            let k = known.position;
            let neighbour = |leaf: LeafId| {
                let side = [1, 2, 4]
                    .iter()
                    .find_map(|&bit| family[k ^ bit].as_ref()?.side(leaf));
                borrowed.set(borrowed.get() || side.is_some());
                side
            };
            self.csg
                .cell_verdict_beside(cell, &mut known.sides, &mut stats, &neighbour)
        };
        if stats.primitive_point_tests != classified || borrowed.get() {
            // A side of a leaf whose boundary misses the cell was learnt
            // here: the later siblings may use it.
            known.family.borrow_mut()[known.position] = Some(known.sides.clone());
        }
        match verdict {
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
