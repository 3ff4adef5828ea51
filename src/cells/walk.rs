//! The cells of an octree still to be judged: where each is, what its
//! parent learnt, its children, and the leaf it becomes.

use super::label::{Cell, Label};
use super::target::{CellTarget, Judgement};
use crate::geom::Aabb;

/// A cell still to be judged, with what its parent learnt.
pub(super) struct Pending<K> {
    pub(super) depth: u32,
    pub(super) at: [u32; 3],
    pub(super) known: K,
}

impl<K> Pending<K> {
    /// Its eight children, child `k` at offset `(k & 1, k >> 1 & 1, k >> 2)`
    /// with the closed box `boxes[k]`, in the order they are pushed on a
    /// stack; `finest` when they are at the octree's finest depth.
    pub(super) fn children<T: CellTarget<Known = K>>(
        &self,
        target: &T,
        boxes: &[Aabb; 8],
        finest: bool,
    ) -> impl Iterator<Item = Pending<K>> {
        let [x, y, z] = self.at;
        let depth = self.depth + 1;
        (0u32..)
            .zip(target.split(&self.known, boxes, finest))
            .map(move |(k, known)| Pending {
                depth,
                at: [2 * x + (k & 1), 2 * y + (k >> 1 & 1), 2 * z + (k >> 2)],
                known,
            })
    }

    /// The leaf a judged cell becomes: `Meets` at the finest depth is
    /// `On`; `Free` is `Out` until its region is labelled.
    pub(super) fn leaf(&self, judgement: Judgement) -> Cell {
        let [x, y, z] = self.at;
        Cell {
            depth: self.depth,
            x,
            y,
            z,
            label: match judgement {
                Judgement::In => Label::In,
                Judgement::Out | Judgement::Free => Label::Out,
                Judgement::Meets => Label::On,
            },
        }
    }
}

/// A piece of the parallel build: a cell decided above the depth where the
/// parallel part starts, or a subtree to refine.
pub(super) enum Task<K> {
    /// A leaf; `free` when its label is its region's, found later.
    Leaf {
        /// The leaf.
        cell: Cell,
        /// Whether it was judged `Free`.
        free: bool,
    },
    /// A cell whose subtree is refined on one thread.
    Subtree(Pending<K>),
}
