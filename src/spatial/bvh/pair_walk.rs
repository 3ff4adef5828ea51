//! The pair walk: the leaves of two trees (or of one tree with itself)
//! whose boxes overlap — the broad phase of every test between two sets of
//! items (face against face, triangle against triangle).
//!
//! Boxes are compared in the first tree's frame, in `f32`: its own boxes
//! as stored, the second tree's carried over rounded outward (back to input
//! coordinates, then into the frame). Every comparison can only err towards
//! "overlap", so no pair of overlapping items is lost.

use rayon::prelude::*;

use crate::spatial::rounding::{f64_above, f64_below};

use super::node::{LEAF, Node8, WIDTH};
use super::tree::Bvh;

/// Pairs of subtrees a parallel walk has in hand before it hands them out
/// to the threads (each then walks its pairs to the leaves alone).
const PARALLEL_TASKS: usize = 256;

/// A subtree in a pair walk: a slot entry ([`LEAF`] plus a leaf number, or
/// a node index) and its box in the first tree's frame.
#[derive(Clone, Copy, Debug)]
struct Side {
    child: u32,
    lo: [f32; 3],
    hi: [f32; 3],
}

impl Side {
    /// A whole tree: the root, with a box that holds everything (the root's
    /// slots carry the real boxes).
    const ROOT: Side = Side {
        child: 0,
        lo: [f32::NEG_INFINITY; 3],
        hi: [f32::INFINITY; 3],
    };

    fn is_leaf(&self) -> bool {
        self.child & LEAF != 0
    }

    fn leaf(&self) -> u32 {
        self.child & !LEAF
    }

    /// Whether the two closed boxes share a point.
    #[inline]
    fn meets(&self, other: &Side) -> bool {
        (0..3).all(|a| self.lo[a] <= other.hi[a] && other.lo[a] <= self.hi[a])
    }
}

/// One pair walk: tree `a` against tree `b`, or against itself when `same`.
struct PairWalk<'t> {
    a: &'t Bvh,
    b: &'t Bvh,
    same: bool,
}

impl PairWalk<'_> {
    /// The filled slots of inner node `node` of tree `a`, boxes as stored.
    fn slots_a(&self, node: u32) -> smallvec::SmallVec<[Side; WIDTH]> {
        let n = &self.a.nodes()[node as usize];
        (0..WIDTH)
            .filter(|&k| n.child[k] != u32::MAX)
            .map(|k| Side {
                child: n.child[k],
                lo: [0, 1, 2].map(|a| n.bounds[a][k]),
                hi: [0, 1, 2].map(|a| n.bounds[3 + a][k]),
            })
            .collect()
    }

    /// The filled slots of inner node `node` of tree `b`, boxes carried
    /// into `a`'s frame (rounded outward).
    fn slots_b(&self, node: u32) -> smallvec::SmallVec<[Side; WIDTH]> {
        if self.same {
            return self.slots_a(node);
        }
        let n = &self.b.nodes()[node as usize];
        (0..WIDTH)
            .filter(|&k| n.child[k] != u32::MAX)
            .map(|k| {
                let (lo, hi) = carried_over(self.b, self.a, n, k);
                Side {
                    child: n.child[k],
                    lo,
                    hi,
                }
            })
            .collect()
    }

    /// One step on the pair `(x, y)` (of `a` and `b`; boxes already known
    /// to meet, or the roots): both leaves are visited; otherwise the inner
    /// ones are opened and the pairs of children whose boxes meet pushed.
    /// In a walk of one tree with itself, `(x, x)` stands for the pairs
    /// within one subtree, each unordered pair once.
    fn step(
        &self,
        (x, y): (Side, Side),
        stack: &mut Vec<(Side, Side)>,
        visit: &mut impl FnMut(u32, u32),
    ) {
        if self.same && x.child == y.child {
            if x.is_leaf() {
                visit(x.leaf(), x.leaf());
                return;
            }
            let slots = self.slots_a(x.child);
            for (i, s) in slots.iter().enumerate() {
                stack.push((*s, *s));
                for t in &slots[i + 1..] {
                    if s.meets(t) {
                        stack.push((*s, *t));
                    }
                }
            }
            return;
        }
        match (x.is_leaf(), y.is_leaf()) {
            (true, true) => visit(x.leaf(), y.leaf()),
            (false, true) => {
                for s in self.slots_a(x.child) {
                    if s.meets(&y) {
                        stack.push((s, y));
                    }
                }
            }
            (true, false) => {
                for t in self.slots_b(y.child) {
                    if x.meets(&t) {
                        stack.push((x, t));
                    }
                }
            }
            (false, false) => {
                let ts = self.slots_b(y.child);
                for s in self.slots_a(x.child) {
                    if !s.meets(&y) {
                        continue;
                    }
                    for t in &ts {
                        if s.meets(t) {
                            stack.push((s, *t));
                        }
                    }
                }
            }
        }
    }

    /// The whole walk on one thread.
    fn run(&self, mut visit: impl FnMut(u32, u32)) {
        let mut stack = vec![(Side::ROOT, Side::ROOT)];
        while let Some(pair) = stack.pop() {
            self.step(pair, &mut stack, &mut visit);
        }
    }

    /// The whole walk on all cores: the pairs near the roots are expanded
    /// level by level until there are enough to share out, then each is
    /// walked to the leaves on its own. What `visit` pushes is returned in
    /// an order fixed by the trees (independent of the threads).
    fn run_parallel<T: Send>(&self, visit: impl Fn(u32, u32, &mut Vec<T>) + Sync) -> Vec<T> {
        let mut out = Vec::new();
        let mut frontier = vec![(Side::ROOT, Side::ROOT)];
        while !frontier.is_empty() && frontier.len() < PARALLEL_TASKS {
            let mut next = Vec::new();
            for pair in frontier {
                self.step(pair, &mut next, &mut |p, q| visit(p, q, &mut out));
            }
            frontier = next;
        }
        let parts: Vec<Vec<T>> = frontier
            .par_iter()
            .with_max_len(1)
            .map(|&pair| {
                let mut found = Vec::new();
                let mut stack = vec![pair];
                while let Some(pair) = stack.pop() {
                    self.step(pair, &mut stack, &mut |p, q| visit(p, q, &mut found));
                }
                found
            })
            .collect();
        out.extend(parts.into_iter().flatten());
        out
    }
}

impl Bvh {
    /// Calls `visit(a, b)` for every leaf `a` of `self` and leaf `b` of
    /// `other` whose boxes overlap (closed boxes: touching counts), each
    /// pair once. Conservative: every pair of items, one from each tree,
    /// whose exact boxes overlap lies in a reported pair of leaves (some
    /// reported pairs may hold none). The order of the pairs is fixed by
    /// the two trees.
    pub fn leaf_pairs(&self, other: &Bvh, visit: impl FnMut(u32, u32)) {
        PairWalk {
            a: self,
            b: other,
            same: false,
        }
        .run(visit);
    }

    /// Calls `visit(a, b)` for every unordered pair of leaves of the tree
    /// whose boxes overlap, each pair once (in either order), and
    /// `visit(a, a)` for every leaf (a leaf's items may meet each other).
    /// Conservative as [`Bvh::leaf_pairs`].
    pub fn self_leaf_pairs(&self, visit: impl FnMut(u32, u32)) {
        PairWalk {
            a: self,
            b: self,
            same: true,
        }
        .run(visit);
    }

    /// [`Bvh::leaf_pairs`] on all cores: `visit(a, b, found)` is called
    /// once for each pair of leaves, from any thread, and pushes what it
    /// finds onto `found`; everything found is returned, in an order fixed
    /// by the two trees whatever the number of threads.
    pub fn par_leaf_pairs<T: Send>(
        &self,
        other: &Bvh,
        visit: impl Fn(u32, u32, &mut Vec<T>) + Sync,
    ) -> Vec<T> {
        PairWalk {
            a: self,
            b: other,
            same: false,
        }
        .run_parallel(visit)
    }

    /// [`Bvh::self_leaf_pairs`] on all cores, as [`Bvh::par_leaf_pairs`].
    pub fn par_self_leaf_pairs<T: Send>(
        &self,
        visit: impl Fn(u32, u32, &mut Vec<T>) + Sync,
    ) -> Vec<T> {
        PairWalk {
            a: self,
            b: self,
            same: true,
        }
        .run_parallel(visit)
    }
}

/// The box of slot `k` of node `n` of tree `from`, carried into the frame
/// of tree `to` and rounded outward: it contains the exact box the slot's
/// `f32` box stands for. (Back in input coordinates, the division by the
/// power-of-two scale is exact and adding the centre is rounded to nearest,
/// which the next `f64` outward covers; the frame's own rounding of
/// `to` is outward.)
fn carried_over(from: &Bvh, to: &Bvh, n: &Node8, k: usize) -> ([f32; 3], [f32; 3]) {
    let (f, t) = (from.frame(), to.frame());
    let back = |row: usize, a: usize| f64::from(n.bounds[row][k]) / f.scale + f.centre[a];
    let lo = [0, 1, 2].map(|a| t.lower(f64_below(back(a, a)), a));
    let hi = [0, 1, 2].map(|a| t.upper(f64_above(back(3 + a, a)), a));
    (lo, hi)
}

#[cfg(test)]
pub(super) mod tests {
    use std::collections::BTreeSet;

    use glam::DVec3;

    use super::*;
    use crate::geom::Aabb;

    fn overlap(a: &Aabb, b: &Aabb) -> bool {
        !a.intersection(*b).is_empty()
    }

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

    fn sorted(mut pairs: Vec<(u32, u32)>) -> Vec<(u32, u32)> {
        pairs.sort_unstable();
        pairs
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
            // The parallel walks visit the same pairs, in the same order
            // every time.
            let push = |x: u32, y: u32, found: &mut Vec<(u32, u32)>| found.push((x, y));
            let mut serial = Vec::new();
            ta.leaf_pairs(&tb, |x, y| serial.push((x, y)));
            let parallel = ta.par_leaf_pairs(&tb, push);
            assert_eq!(sorted(parallel.clone()), sorted(serial), "{n} × {m}");
            assert_eq!(parallel, ta.par_leaf_pairs(&tb, push), "{n} × {m}");
            let parallel = ta.par_self_leaf_pairs(push);
            assert_eq!(sorted(parallel.clone()), sorted(own), "{n} with itself");
            assert_eq!(parallel, ta.par_self_leaf_pairs(push), "{n} with itself");
        }
        // Trees large enough for the parallel walks to share out subtrees:
        // the same pairs as the one-thread walks.
        let a = random_boxes(20_000, 0x6A09_E667_F3BC_C909, 0.0, 1.0, 0.02);
        let b = random_boxes(5_000, 0xBB67_AE85_84CA_A73B, 0.2, 1.0, 0.03);
        let ((ta, _), (tb, _)) = (Bvh::build(&a), Bvh::build(&b));
        let push = |x: u32, y: u32, found: &mut Vec<(u32, u32)>| found.push((x, y));
        let mut serial = Vec::new();
        ta.self_leaf_pairs(|x, y| serial.push((x, y)));
        assert!(serial.len() > ta.leaf_count(), "{}", serial.len());
        assert_eq!(sorted(ta.par_self_leaf_pairs(push)), sorted(serial));
        let mut serial = Vec::new();
        ta.leaf_pairs(&tb, |x, y| serial.push((x, y)));
        assert!(serial.len() > tb.leaf_count(), "{}", serial.len());
        assert_eq!(sorted(ta.par_leaf_pairs(&tb, push)), sorted(serial));
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
