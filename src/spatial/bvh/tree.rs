//! The tree itself: what a build leaves behind, and what every walk reads.

use crate::geom::Aabb;
use crate::spatial::raw::huge_pages::HugeVec;

use super::build::build_bvh;
use super::collapse::collapse;
use super::node::{BoxFrame, LeafItems, Node8, WIDTH};

/// A bounding-volume hierarchy over items given by their exact boxes
/// (triangles, faces, primitives): eight-wide nodes of `f32` boxes in a
/// frame (`BoxFrame`), and leaves of at most [`LEAF_SIZE`](super::LEAF_SIZE)
/// items.
///
/// The tree does not hold the items: [`Bvh::build`] returns the order in
/// which its leaves list them, and the owner keeps its items in that
/// order, so that leaf `k` holds the positions [`Bvh::leaf`]`(k)` of it.
/// Walks report leaves (and item positions); what a leaf's items mean is
/// the owner's business.
///
/// # Invariants
///
/// - Node 0 is the root; a node's slots hold `LEAF` plus a
///   leaf number, the index of an inner node, or `u32::MAX` (empty).
/// - Every slot's `f32` box, in `frame`, contains the exact boxes of all the
///   items below it (bounds rounded outward), so a walk that culls by
///   boxes never loses an item whose box it meets.
/// - `leaves` tile `0 .. n` (for `n` items) in order, each of
///   `1 ..= LEAF_SIZE` items.
/// - `stack_len` is at least `(WIDTH − 1) · depth + WIDTH` for the depth of
///   `nodes`: a depth-first walk holds at most `WIDTH − 1` deferred children
///   per level above the node it opens, which then pushes at most `WIDTH`.
#[derive(Clone, Debug)]
pub struct Bvh {
    nodes: HugeVec<Node8>,
    leaves: Vec<LeafItems>,
    frame: BoxFrame,
    stack_len: usize,
    bounds: Aabb,
}

impl Bvh {
    /// The tree over items with exact boxes `items`, and the order of the
    /// items in its leaves (`order[p]` is the index in `items` of the item
    /// at position `p`). Never fails: no items give a tree with no leaves.
    #[must_use]
    pub fn build(items: &[Aabb]) -> (Bvh, Vec<u32>) {
        Bvh::build_by(items.len(), |i| items[i])
    }

    /// [`Bvh::build`] over `count` items whose exact boxes `bounds_of`
    /// makes (each is asked for twice), for owners who would rather not
    /// keep an array of boxes.
    #[must_use]
    pub fn build_by(count: usize, bounds_of: impl Fn(usize) -> Aabb + Sync) -> (Bvh, Vec<u32>) {
        let (binary, order, frame, bounds) = build_bvh(count, bounds_of);
        let (nodes, leaves, depth) = collapse(&binary);
        let bvh = Bvh {
            nodes,
            leaves,
            frame,
            stack_len: (WIDTH - 1) * depth + WIDTH,
            bounds,
        };
        (bvh, order)
    }

    /// The number of leaves.
    #[must_use]
    #[inline]
    pub fn leaf_count(&self) -> usize {
        self.leaves.len()
    }

    /// The item positions of leaf `leaf` (`None` past the last leaf).
    #[must_use]
    #[inline]
    pub fn leaf(&self, leaf: u32) -> Option<LeafItems> {
        self.leaves.get(leaf as usize).copied()
    }

    /// The number of eight-wide nodes.
    #[must_use]
    #[inline]
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// The exact bounding box of all items.
    #[must_use]
    #[inline]
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Heap bytes held by the tree.
    #[must_use]
    pub fn memory_bytes(&self) -> usize {
        self.nodes.memory_bytes() + self.leaves.capacity() * std::mem::size_of::<LeafItems>()
    }

    /// Moves the nodes onto huge pages where the system offers them (see
    /// `spatial::raw::huge_pages`); changes nothing else.
    pub(crate) fn collapse_into_huge_pages(&self) {
        self.nodes.collapse();
    }

    /// The nodes, root first.
    #[inline]
    pub(crate) fn nodes(&self) -> &[Node8] {
        &self.nodes
    }

    /// The frame of the nodes' boxes.
    #[inline]
    pub(crate) fn frame(&self) -> &BoxFrame {
        &self.frame
    }

    /// A stack length no depth-first walk overflows (see the invariants).
    #[inline]
    pub(crate) fn stack_len(&self) -> usize {
        self.stack_len
    }

    /// Overrides the stack length (tests of walks over deep trees).
    #[cfg(test)]
    pub(crate) fn set_stack_len(&mut self, stack_len: usize) {
        self.stack_len = stack_len;
    }
}
