//! The binary SAH tree over the items' boxes, which is then collapsed
//! into eight-wide nodes (`collapse`).
//!
//! Boxes are the items' boxes in the tree's [`BoxFrame`], rounded
//! outward to `f32` as node boxes are stored, so every node's box contains
//! its items exactly. Where a split falls is a heuristic (binned SAH
//! on the longest axis of the items' centres); it decides no answer,
//! only how fast answers come.
//!
//! Box arithmetic is on [`Vec3A`] (one SSE register on `x86_64`): the
//! build's inner loop grows a bin's box and its centres' box by an item,
//! which is then four `minps`/`maxps`.

use glam::Vec3A;
use rayon::prelude::*;

use crate::geom::Aabb;

use super::node::{BoxFrame, Node};

/// Largest number of items in a leaf: four, so that a leaf's items fit
/// the four lanes of the rays' leaf filter (`query::tri_packet`).
pub const LEAF_SIZE: usize = 4;
/// SAH bins per split.
const BINS: usize = 16;
/// Subtrees of at most this many items are split by sorting them and
/// trying every split (cheaper than binning at this size, and exact).
const SORTED_SPLIT: usize = 16;
/// Subtrees at least this large are built on two threads.
const PARALLEL_BUILD: usize = 16 * 1024;

/// The binary BVH of `count` items with exact boxes `bounds_of(0 ..
/// count)` (leaves of at most [`LEAF_SIZE`] items), the item order of its
/// leaves, the frame its boxes are in, and the exact bounding box of all
/// items. `bounds_of` is called twice per item (a box is cheaper to make
/// again than to keep).
pub(super) fn build_bvh(
    count: usize,
    bounds_of: impl Fn(usize) -> Aabb + Sync,
) -> (Vec<Node>, Vec<u32>, BoxFrame, Aabb) {
    let bounds = (0..count)
        .into_par_iter()
        .map(&bounds_of)
        .reduce(|| Aabb::EMPTY, Aabb::union);
    let frame = BoxFrame::of(&bounds);
    let (mut boxes, mut index): (Vec<PrimBox>, Vec<u32>) = (0..count)
        .into_par_iter()
        .map(|i| {
            let b = bounds_of(i);
            let lo = [0, 1, 2].map(|a| frame.lower(b.min[a], a));
            let hi = [0, 1, 2].map(|a| frame.upper(b.max[a], a));
            let prim = PrimBox {
                lo: Vec3A::from_array(lo),
                hi: Vec3A::from_array(hi),
            };
            (prim, i as u32)
        })
        .unzip();
    if boxes.is_empty() {
        let empty = Node {
            min: [f32::INFINITY; 3],
            max: [f32::NEG_INFINITY; 3],
            first: 0,
            count: 0,
        };
        return (vec![empty], Vec::new(), frame, bounds);
    }
    let ext = boxes
        .par_chunks(4096)
        .map(Extent::of)
        .reduce(|| Extent::EMPTY, |a, b| a.union(&b));
    let mut bin_of = vec![0u8; boxes.len()];
    let prims = Prims {
        boxes: &mut boxes,
        index: &mut index,
        bin_of: &mut bin_of,
    };
    let nodes = build_node_parallel(prims, 0, &ext);
    (nodes, index, frame, bounds)
}

/// An item's box as the build sees it (32 bytes). The build partitions
/// these records in place, so each level streams through memory instead of
/// gathering boxes through an index array.
#[derive(Clone, Copy, Debug)]
struct PrimBox {
    lo: Vec3A,
    hi: Vec3A,
}

impl PrimBox {
    /// Twice the middle of the box (the SAH's position of the item:
    /// any point of the box would keep the build correct, and doubling
    /// spares a multiplication).
    #[inline(always)]
    fn centre2(&self) -> Vec3A {
        self.lo + self.hi
    }
}

/// The items of a subtree: their boxes and, in step, their indices,
/// with a byte each of scratch (their bins while the subtree is split).
struct Prims<'a> {
    boxes: &'a mut [PrimBox],
    index: &'a mut [u32],
    bin_of: &'a mut [u8],
}

impl<'a> Prims<'a> {
    fn len(&self) -> usize {
        self.boxes.len()
    }

    fn swap(&mut self, i: usize, j: usize) {
        self.boxes.swap(i, j);
        self.index.swap(i, j);
    }

    fn split_at(self, mid: usize) -> (Prims<'a>, Prims<'a>) {
        let (bl, br) = self.boxes.split_at_mut(mid);
        let (il, ir) = self.index.split_at_mut(mid);
        let (sl, sr) = self.bin_of.split_at_mut(mid);
        (
            Prims {
                boxes: bl,
                index: il,
                bin_of: sl,
            },
            Prims {
                boxes: br,
                index: ir,
                bin_of: sr,
            },
        )
    }
}

/// The boxes of a subtree: of its items (as stored in nodes) and of
/// their doubled centres ([`PrimBox::centre2`]).
#[derive(Clone, Copy, Debug)]
struct Extent {
    min: Vec3A,
    max: Vec3A,
    centre2_min: Vec3A,
    centre2_max: Vec3A,
}

impl Extent {
    const EMPTY: Extent = Extent {
        min: Vec3A::INFINITY,
        max: Vec3A::NEG_INFINITY,
        centre2_min: Vec3A::INFINITY,
        centre2_max: Vec3A::NEG_INFINITY,
    };

    #[inline(always)]
    fn grow(mut self, p: &PrimBox) -> Extent {
        let c = p.centre2();
        self.min = self.min.min(p.lo);
        self.max = self.max.max(p.hi);
        self.centre2_min = self.centre2_min.min(c);
        self.centre2_max = self.centre2_max.max(c);
        self
    }

    #[inline]
    fn union(mut self, o: &Extent) -> Extent {
        self.min = self.min.min(o.min);
        self.max = self.max.max(o.max);
        self.centre2_min = self.centre2_min.min(o.centre2_min);
        self.centre2_max = self.centre2_max.max(o.centre2_max);
        self
    }

    fn of(boxes: &[PrimBox]) -> Extent {
        boxes.iter().fold(Extent::EMPTY, Extent::grow)
    }

    /// Half the surface area of the items' box (0 when empty).
    fn half_area(&self) -> f32 {
        if self.min.x > self.max.x {
            return 0.0;
        }
        let s = self.max - self.min;
        s.x * s.y + s.y * s.z + s.z * s.x
    }

    fn node(&self, count: usize, offset: usize) -> Node {
        Node {
            min: self.min.to_array(),
            max: self.max.to_array(),
            first: offset as u32,
            count: count as u32,
        }
    }
}

/// One SAH bin: the items whose centre falls in it.
#[derive(Clone, Copy)]
struct Bin {
    ext: Extent,
    count: u32,
}

impl Bin {
    const EMPTY: Bin = Bin {
        ext: Extent::EMPTY,
        count: 0,
    };

    #[inline(always)]
    fn add(&mut self, p: &PrimBox) {
        self.ext = self.ext.grow(p);
        self.count += 1;
    }

    fn union(&self, o: &Bin) -> Bin {
        Bin {
            ext: self.ext.union(&o.ext),
            count: self.count + o.count,
        }
    }
}

/// Where items fall among the bins along axis `AXIS`: the bin of a
/// doubled centre `c` is `(c − lo) · scale`, rounded down and clamped.
/// Binning and partitioning place a item by the bin recorded for it.
#[derive(Clone, Copy)]
struct Binning<const AXIS: usize> {
    lo: f32,
    scale: f32,
}

impl<const AXIS: usize> Binning<AXIS> {
    #[inline(always)]
    fn bin(&self, p: &PrimBox) -> u8 {
        let at = (p.lo[AXIS] + p.hi[AXIS] - self.lo) * self.scale;
        (at as i32).clamp(0, BINS as i32 - 1) as u8
    }

    /// The items' counts and extents per bin; `bin_of[i]` is set to
    /// the bin of `boxes[i]`.
    fn bins(&self, boxes: &[PrimBox], bin_of: &mut [u8]) -> [Bin; BINS] {
        // Two sets of bins, for even and odd items: consecutive
        // items often share a bin, and one set would make each update
        // wait for the last.
        let mut bins = [[Bin::EMPTY; BINS]; 2];
        let (pairs, rest) = boxes.as_chunks::<2>();
        let (pair_bins, rest_bins) = bin_of.as_chunks_mut::<2>();
        for ([p, q], [bp, bq]) in pairs.iter().zip(pair_bins) {
            (*bp, *bq) = (self.bin(p), self.bin(q));
            bins[0][usize::from(*bp)].add(p);
            bins[1][usize::from(*bq)].add(q);
        }
        for (p, b) in rest.iter().zip(rest_bins) {
            *b = self.bin(p);
            bins[0][usize::from(*b)].add(p);
        }
        std::array::from_fn(|k| bins[0][k].union(&bins[1][k]))
    }
}

/// The bin after which the SAH splits `bins`, if any split leaves
/// items on both sides.
fn best_split(bins: &[Bin; BINS]) -> Option<usize> {
    // Sweep from the right for suffix areas.
    let mut right_area = [0.0f32; BINS];
    let mut right_count = [0u32; BINS];
    let mut acc = Bin::EMPTY;
    for k in (1..BINS).rev() {
        acc = acc.union(&bins[k]);
        right_area[k] = acc.ext.half_area();
        right_count[k] = acc.count;
    }
    // A leaf's items are tested a packet of four at a time (the rays' leaf
    // filter): count packets, not items, so that splits fill them.
    let packets = |c: u32| c.div_ceil(LEAF_SIZE as u32) as f32;
    let mut best: Option<(f32, usize)> = None;
    let mut acc = Bin::EMPTY;
    for k in 0..BINS - 1 {
        acc = acc.union(&bins[k]);
        if acc.count == 0 || right_count[k + 1] == 0 {
            continue;
        }
        let cost = acc.ext.half_area() * packets(acc.count)
            + right_area[k + 1] * packets(right_count[k + 1]);
        if best.is_none_or(|(c, _)| cost < c) {
            best = Some((cost, k));
        }
    }
    best.map(|(_, k)| k)
}

/// Splits `prims` (more than [`LEAF_SIZE`], extent `ext`) along the
/// longest axis of the centres' box, in place: by binned SAH, or for at
/// most [`SORTED_SPLIT`] items by [`split_sorted`]. Returns the size of
/// the first part and the extents of both parts.
fn partition(prims: &mut Prims, ext: &Extent) -> (usize, Extent, Extent) {
    let size = ext.centre2_max - ext.centre2_min;
    let axis = if size.x >= size.y && size.x >= size.z {
        0
    } else if size.y >= size.z {
        1
    } else {
        2
    };
    let split = if prims.len() <= SORTED_SPLIT {
        Some(split_sorted(prims, axis))
    } else {
        match axis {
            0 => split_along::<0>(prims, ext),
            1 => split_along::<1>(prims, ext),
            _ => split_along::<2>(prims, ext),
        }
    };
    split.unwrap_or_else(|| {
        // No useful split (all centres equal): halve by count.
        let mid = prims.len() / 2;
        let (l, r) = prims.boxes.split_at(mid);
        (mid, Extent::of(l), Extent::of(r))
    })
}

/// A key whose unsigned order is the order of the `f32`s (never NaN here).
fn ordered_bits(x: f32) -> u32 {
    let b = x.to_bits();
    if b >> 31 == 1 { !b } else { b | 1 << 31 }
}

/// [`partition`] of at most [`SORTED_SPLIT`] items: sorted by centre
/// along `axis` (ties by position, so the order is deterministic), then
/// split where the SAH cost over all `n − 1` places is least.
fn split_sorted(prims: &mut Prims, axis: usize) -> (usize, Extent, Extent) {
    let n = prims.len();
    let mut keys = [0u64; SORTED_SPLIT];
    for (k, p) in prims.boxes.iter().enumerate() {
        keys[k] = u64::from(ordered_bits(p.centre2()[axis])) << 32 | k as u64;
    }
    let keys = &mut keys[..n];
    keys.sort_unstable();
    // The low 16 bits of a key are the item's place; slots past `n`
    // repeat the last item and are never used.
    let boxes: [PrimBox; SORTED_SPLIT] =
        std::array::from_fn(|k| prims.boxes[(keys[k.min(n - 1)] & 0xffff) as usize]);
    let index: [u32; SORTED_SPLIT] =
        std::array::from_fn(|k| prims.index[(keys[k.min(n - 1)] & 0xffff) as usize]);
    prims.boxes.copy_from_slice(&boxes[..n]);
    prims.index.copy_from_slice(&index[..n]);
    // right[k]: the extent of items k.. .
    let mut right = [Extent::EMPTY; SORTED_SPLIT + 1];
    for k in (1..n).rev() {
        right[k] = right[k + 1].grow(&boxes[k]);
    }
    let packets = |c: usize| c.div_ceil(LEAF_SIZE) as f32;
    let (mut best, mut left) = ((f32::INFINITY, n / 2), Extent::EMPTY);
    for k in 1..n {
        left = left.grow(&boxes[k - 1]);
        let cost = left.half_area() * packets(k) + right[k].half_area() * packets(n - k);
        if cost < best.0 {
            best = (cost, k);
        }
    }
    let mid = best.1;
    (mid, Extent::of(&boxes[..mid]), right[mid])
}

/// [`partition`] along `AXIS`, if the SAH finds a split there.
fn split_along<const AXIS: usize>(
    prims: &mut Prims,
    ext: &Extent,
) -> Option<(usize, Extent, Extent)> {
    let n = prims.len();
    let width = ext.centre2_max[AXIS] - ext.centre2_min[AXIS];
    if width.is_nan() || width <= 0.0 {
        return None;
    }
    let binning = Binning::<AXIS> {
        lo: ext.centre2_min[AXIS],
        scale: BINS as f32 / width,
    };
    let bins = binning.bins(prims.boxes, prims.bin_of);
    let split = best_split(&bins)? as u8;
    // Hoare-style: both ends move towards each other. A swapped pair is
    // never looked at again, so only the boxes and indices move.
    let (mut i, mut j) = (0, n);
    loop {
        while i < j && prims.bin_of[i] <= split {
            i += 1;
        }
        while i < j && prims.bin_of[j - 1] > split {
            j -= 1;
        }
        if i >= j {
            break;
        }
        prims.swap(i, j - 1);
        i += 1;
        j -= 1;
    }
    if i == 0 || i == n {
        return None;
    }
    let merge = |range: std::ops::Range<usize>| {
        bins[range]
            .iter()
            .fold(Extent::EMPTY, |e, b| e.union(&b.ext))
    };
    let split = usize::from(split);
    Some((i, merge(0..split + 1), merge(split + 1..BINS)))
}

fn build_node(mut prims: Prims, offset: usize, ext: &Extent, nodes: &mut Vec<Node>) {
    let me = nodes.len();
    nodes.push(ext.node(prims.len(), offset));
    if prims.len() <= LEAF_SIZE {
        return;
    }
    let (mid, le, re) = partition(&mut prims, ext);
    let (left, right) = prims.split_at(mid);
    build_node(left, offset, &le, nodes);
    let second = nodes.len() as u32;
    build_node(right, offset + mid, &re, nodes);
    nodes[me].first = second;
    nodes[me].count = 0;
}

/// [`build_node`] with the two halves of large subtrees built in parallel;
/// returns the subtree's nodes with indices local to it.
fn build_node_parallel(mut prims: Prims, offset: usize, ext: &Extent) -> Vec<Node> {
    let mut nodes = Vec::new();
    if prims.len() < PARALLEL_BUILD {
        build_node(prims, offset, ext, &mut nodes);
        return nodes;
    }
    nodes.push(ext.node(prims.len(), offset));
    let (mid, le, re) = partition(&mut prims, ext);
    let (left, right) = prims.split_at(mid);
    let (l, r) = rayon::join(
        || build_node_parallel(left, offset, &le),
        || build_node_parallel(right, offset + mid, &re),
    );
    let shift = |n: &Node, base: u32| {
        let mut n = *n;
        if n.count == 0 {
            n.first += base;
        }
        n
    };
    nodes.reserve(l.len() + r.len());
    nodes.extend(l.iter().map(|n| shift(n, 1)));
    let second = nodes.len() as u32;
    nodes.extend(r.iter().map(|n| shift(n, second)));
    nodes[0].first = second;
    nodes[0].count = 0;
    nodes
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    /// Checks every invariant the collapse and the walks rely on: leaves
    /// of 1..=LEAF_SIZE triangles tile the leaf order in sequence, the
    /// order is a permutation, an inner node's box holds its children's,
    /// and each triangle's rounded box lies in its leaf's box.
    fn check_tree(tris: &[[DVec3; 3]]) {
        let (nodes, order, frame, bounds) = build_bvh(tris.len(), |i| Aabb::from_points(tris[i]));
        let mut seen = vec![false; tris.len()];
        for &i in &order {
            assert!(!std::mem::replace(&mut seen[i as usize], true), "{i} twice");
        }
        assert!(seen.iter().all(|&s| s), "order is not a permutation");
        if tris.is_empty() {
            assert_eq!(nodes.len(), 1);
            return;
        }
        for t in tris {
            for p in t {
                assert!(bounds.contains(*p));
            }
        }
        let inside = |inner: &Node, outer: &Node| {
            (0..3).all(|a| outer.min[a] <= inner.min[a] && inner.max[a] <= outer.max[a])
        };
        // Depth-first from the root: leaves must come in leaf order.
        let mut next_leaf_start = 0;
        let mut stack = vec![0usize];
        while let Some(i) = stack.pop() {
            let n = &nodes[i];
            if n.count > 0 {
                assert!(n.count as usize <= LEAF_SIZE);
                assert_eq!(n.first as usize, next_leaf_start);
                next_leaf_start += n.count as usize;
                for &t in &order[n.first as usize..next_leaf_start] {
                    let b = Aabb::from_points(tris[t as usize]);
                    for a in 0..3 {
                        assert!(n.min[a] <= frame.lower(b.min[a], a));
                        assert!(frame.upper(b.max[a], a) <= n.max[a]);
                    }
                }
            } else {
                let (l, r) = (i + 1, n.first as usize);
                assert!(inside(&nodes[l], n) && inside(&nodes[r], n));
                stack.push(r);
                stack.push(l);
            }
        }
        assert_eq!(next_leaf_start, tris.len());
    }

    fn random_triangles(n: usize, seed: u64, size: f64) -> Vec<[DVec3; 3]> {
        let mut u = crate::test_rng::uniform(seed);
        let mut point = || DVec3::new(u(), u(), u());
        (0..n)
            .map(|_| {
                let c = point() * 100.0;
                [c, c + point() * size, c + point() * size]
            })
            .collect()
    }

    #[test]
    fn trees_of_every_size_keep_their_invariants() {
        // Sizes around the leaf, the sorted split and the parallel build.
        for n in [0, 1, 4, 5, 8, 16, 17, 100, 2_000, 40_000] {
            check_tree(&random_triangles(n, 0x5851_F42D_4C95_7F2D + n as u64, 1.0));
        }
    }

    #[test]
    fn equal_centres_are_halved_by_count() {
        // One triangle many times: no SAH split separates them.
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y];
        for n in [5, 16, 17, 300, 20_000] {
            check_tree(&vec![t; n]);
        }
        // Equal centres along the longest axis only.
        let fan: Vec<[DVec3; 3]> = (0..500)
            .map(|k| {
                let y = f64::from(k);
                [
                    DVec3::new(-1e6, y, 0.0),
                    DVec3::new(1e6, y, 0.0),
                    DVec3::new(0.0, y, 1.0),
                ]
            })
            .collect();
        check_tree(&fan);
    }

    #[test]
    fn slivers_and_far_offsets_keep_their_invariants() {
        let mut tris = random_triangles(3_000, 0x1405_7B7E_F767_814F, 1e-9);
        for t in &mut tris {
            for p in t.iter_mut() {
                *p += DVec3::splat(1e12);
            }
        }
        check_tree(&tris);
    }

    #[test]
    fn ordered_bits_follow_the_floats() {
        let xs = [
            f32::NEG_INFINITY,
            -3.5,
            -1e-40,
            -0.0,
            0.0,
            1e-40,
            1.0,
            2.0,
            f32::INFINITY,
        ];
        for w in xs.windows(2) {
            assert!(
                ordered_bits(w[0]) <= ordered_bits(w[1]),
                "{} {}",
                w[0],
                w[1]
            );
        }
    }
}
