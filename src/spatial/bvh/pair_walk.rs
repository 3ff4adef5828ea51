//! The pair walk: the leaves of two trees (or of one tree with itself)
//! whose boxes overlap — the broad phase of every test between two sets of
//! items (face against face, triangle against triangle).

use glam::DVec3;

use crate::geom::Aabb;
use crate::spatial::rounding::{f64_above, f64_below};

use super::node::{LEAF, Node8, WIDTH};
use super::tree::Bvh;

/// A subtree waiting in a pair walk: a slot entry ([`LEAF`] plus a leaf
/// number, or a node index) and its box in input coordinates.
#[derive(Clone, Copy, Debug)]
struct Side {
    child: u32,
    bounds: Aabb,
}

impl Bvh {
    /// Calls `visit(a, b)` for every leaf `a` of `self` and leaf `b` of
    /// `other` whose boxes overlap (closed boxes: touching counts), each
    /// pair once. Conservative: every pair of items, one from each tree,
    /// whose exact boxes overlap lies in a reported pair of leaves (some
    /// reported pairs may hold none). The order of the pairs is fixed by
    /// the two trees.
    pub fn leaf_pairs(&self, other: &Bvh, mut visit: impl FnMut(u32, u32)) {
        let mut stack = vec![(self.root(), other.root())];
        while let Some((a, b)) = stack.pop() {
            if !overlap(&a.bounds, &b.bounds) {
                continue;
            }
            self.expand_pair(other, a, b, &mut stack, &mut visit);
        }
    }

    /// Calls `visit(a, b)` for every unordered pair of leaves of the tree
    /// whose boxes overlap, each pair once (in either order), and
    /// `visit(a, a)` for every leaf (a leaf's items may meet each other).
    /// Conservative as [`Bvh::leaf_pairs`].
    pub fn self_leaf_pairs(&self, mut visit: impl FnMut(u32, u32)) {
        // `(x, x)` stands for the pairs within one subtree; `(x, y)` with
        // `x ≠ y` for the pairs across two disjoint subtrees.
        let root = self.root();
        let mut stack = vec![(root, root)];
        while let Some((a, b)) = stack.pop() {
            if a.child != b.child {
                if overlap(&a.bounds, &b.bounds) {
                    self.expand_pair(self, a, b, &mut stack, &mut visit);
                }
                continue;
            }
            if a.child & LEAF != 0 {
                visit(a.child & !LEAF, a.child & !LEAF);
                continue;
            }
            let slots = self.slots(a.child);
            for (i, &x) in slots.iter().enumerate() {
                stack.push((x, x));
                for &y in &slots[i + 1..] {
                    stack.push((x, y));
                }
            }
        }
    }

    /// One step of a pair walk on the overlapping subtrees `a` (of `self`)
    /// and `b` (of `other`): both leaves are visited; otherwise the inner
    /// ones are opened and their children paired.
    fn expand_pair(
        &self,
        other: &Bvh,
        a: Side,
        b: Side,
        stack: &mut Vec<(Side, Side)>,
        visit: &mut impl FnMut(u32, u32),
    ) {
        match (a.child & LEAF != 0, b.child & LEAF != 0) {
            (true, true) => visit(a.child & !LEAF, b.child & !LEAF),
            (false, true) => {
                for x in self.slots(a.child) {
                    stack.push((x, b));
                }
            }
            (true, false) => {
                for y in other.slots(b.child) {
                    stack.push((a, y));
                }
            }
            (false, false) => {
                let ys = other.slots(b.child);
                for x in self.slots(a.child) {
                    for &y in &ys {
                        stack.push((x, y));
                    }
                }
            }
        }
    }

    /// The root as a pair walk's subtree.
    fn root(&self) -> Side {
        Side {
            child: 0,
            bounds: self.bounds(),
        }
    }

    /// The filled slots of inner node `node`, with their boxes in input
    /// coordinates.
    fn slots(&self, node: u32) -> smallvec::SmallVec<[Side; WIDTH]> {
        let n = &self.nodes()[node as usize];
        (0..WIDTH)
            .filter(|&k| n.child[k] != u32::MAX)
            .map(|k| Side {
                child: n.child[k],
                bounds: self.slot_bounds(n, k),
            })
            .collect()
    }

    /// The box of slot `k` of `n` in input coordinates, rounded outward:
    /// it contains the exact box the slot's `f32` box stands for. (The
    /// division by the power-of-two scale is exact; adding the centre is
    /// rounded to nearest, and the next `f64` outward covers that.)
    pub(super) fn slot_bounds(&self, n: &Node8, k: usize) -> Aabb {
        let frame = self.frame();
        let back =
            |row: usize, a: usize| f64::from(n.bounds[row][k]) / frame.scale + frame.centre[a];
        Aabb {
            min: DVec3::new(
                f64_below(back(0, 0)),
                f64_below(back(1, 1)),
                f64_below(back(2, 2)),
            ),
            max: DVec3::new(
                f64_above(back(3, 0)),
                f64_above(back(4, 1)),
                f64_above(back(5, 2)),
            ),
        }
    }
}

/// Whether two closed boxes share a point.
fn overlap(a: &Aabb, b: &Aabb) -> bool {
    !a.intersection(*b).is_empty()
}
