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

#[cfg(test)]
pub(super) mod tests {
    use std::collections::BTreeSet;

    use super::*;

    /// `n` random boxes in a cube of side `spread` (offset by `at`), of
    /// sizes up to `size`, some flat and some repeated.
    pub(in crate::spatial) fn random_boxes(
        n: usize,
        seed: u64,
        at: f64,
        spread: f64,
        size: f64,
    ) -> Vec<Aabb> {
        let mut u = crate::test_rng::uniform(seed);
        let mut point = || DVec3::new(u(), u(), u());
        let mut boxes: Vec<Aabb> = (0..n)
            .map(|k| {
                let lo = DVec3::splat(at) + point() * spread;
                let mut extent = point() * size;
                if k % 7 == 0 {
                    extent.z = 0.0;
                }
                Aabb::from_points([lo, lo + extent])
            })
            .collect();
        if n > 10 {
            boxes[n - 1] = boxes[3];
        }
        boxes
    }

    fn overlapping_items(a: &[Aabb], b: &[Aabb], same: bool) -> BTreeSet<(usize, usize)> {
        let mut pairs = BTreeSet::new();
        for (i, x) in a.iter().enumerate() {
            for (j, y) in b.iter().enumerate() {
                if (!same || i < j) && overlap(x, y) {
                    pairs.insert((i, j));
                }
            }
        }
        pairs
    }

    /// The item pairs within the leaf pairs a walk reports, with the leaf
    /// pairs checked to come once each.
    fn reported_items(
        a: (&Bvh, &[u32], &[Aabb]),
        b: (&Bvh, &[u32], &[Aabb]),
        leaf_pairs: &[(u32, u32)],
        same: bool,
    ) -> BTreeSet<(usize, usize)> {
        let distinct: BTreeSet<(u32, u32)> = leaf_pairs
            .iter()
            .map(|&(x, y)| if same { (x.min(y), x.max(y)) } else { (x, y) })
            .collect();
        assert_eq!(distinct.len(), leaf_pairs.len(), "a leaf pair came twice");
        let mut items = BTreeSet::new();
        for &(la, lb) in leaf_pairs {
            for p in a.0.leaf(la).unwrap().range() {
                for q in b.0.leaf(lb).unwrap().range() {
                    let (i, j) = (a.1[p] as usize, b.1[q] as usize);
                    let (i, j) = if same { (i.min(j), i.max(j)) } else { (i, j) };
                    if (!same || i < j) && overlap(&a.2[i], &b.2[j]) {
                        items.insert((i, j));
                    }
                }
            }
        }
        items
    }

    /// Both pair walks find every pair of overlapping boxes (touching and
    /// flat ones included), over trees of many sizes, in frames far apart
    /// in scale and position.
    #[test]
    fn pair_walks_find_every_overlapping_pair() {
        for (n, m, seed) in [(0, 5, 1), (1, 1, 2), (5, 3, 3), (40, 70, 4), (700, 500, 5)] {
            let a = random_boxes(n, 0x2545_F491_4F6C_DD1D + seed, 0.0, 1.0, 0.1);
            let b = random_boxes(m, 0x9E37_79B9_7F4A_7C15 + seed, 0.5, 0.7, 0.05);
            let (ta, oa) = Bvh::build(&a);
            let (tb, ob) = Bvh::build(&b);
            let mut pairs = Vec::new();
            ta.leaf_pairs(&tb, |x, y| pairs.push((x, y)));
            let found = reported_items((&ta, &oa, &a), (&tb, &ob, &b), &pairs, false);
            assert_eq!(found, overlapping_items(&a, &b, false), "{n} × {m}");
            let mut own = Vec::new();
            ta.self_leaf_pairs(|x, y| own.push((x, y)));
            let found = reported_items((&ta, &oa, &a), (&ta, &oa, &a), &own, true);
            assert_eq!(found, overlapping_items(&a, &a, true), "{n} with itself");
            let leaves: BTreeSet<u32> = own.iter().filter(|p| p.0 == p.1).map(|p| p.0).collect();
            assert_eq!(leaves.len(), ta.leaf_count(), "every leaf with itself");
        }
        // A tiny tree far from the origin against a huge one around it.
        let small = random_boxes(300, 11, 1e8, 1e-3, 1e-4);
        let large = random_boxes(300, 12, -1e9, 3e9, 1.5e9);
        let (ts, os) = Bvh::build(&small);
        let (tl, ol) = Bvh::build(&large);
        let mut pairs = Vec::new();
        ts.leaf_pairs(&tl, |x, y| pairs.push((x, y)));
        let found = reported_items((&ts, &os, &small), (&tl, &ol, &large), &pairs, false);
        let want = overlapping_items(&small, &large, false);
        assert!(!want.is_empty());
        assert_eq!(found, want);
    }
}
