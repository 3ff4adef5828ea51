//! Opening a BVH node for one ray, the trait every opener implements: the
//! slab tests of its eight children side by side, and the children entered
//! pushed onto the traversal stack, the nearest on top (by entry parameter,
//! or along the ray's octant).
//!
//! Each child entered is keyed by the bits of its entry parameter (a
//! non-negative `f32`, clamped to finite, whose bits order as the values
//! do) with the low four bits replaced by `8 | slot`. Keys are distinct and
//! never 0. The order of the pushes decides only how soon a walk finds its
//! answer, never the answer (a first-hit walk keeps the nearest crossing
//! found, ties by triangle; culling by key is conservative). Three
//! implementations:
//!
//! - [`Avx512`](super::Avx512), on `x86_64` processors with AVX-512
//!   (detected at run time): the eight slab tests in one 256-bit register per operation,
//!   the results permuted into the node's precomputed order for the ray's
//!   octant ([`Node8::order`]: farthest first along the octant's
//!   diagonal), and the children entered packed with a compress
//!   instruction — no sorting;
//! - [`Avx2`](super::Avx2), on `x86_64` processors with AVX2 but not
//!   AVX-512: the same octant order, the children entered packed by a permutation looked up
//!   in a 256-entry table by the mask of the children entered;
//! - [`Portable`](super::Portable), everywhere: the children in two halves
//!   of four `F32x4` lanes, then each child entered inserted into place by key,
//!   the nearest on top (a ray enters two or three of eight on average).
//!
//! Why an order fixed per node and octant rather than sorting the keys: a
//! sorting network over eight keys is a chain of shuffles on every node,
//! which costs more than the packing; pushing in slot order with no order
//! at all makes walks visit markedly more nodes.

use super::node::{Node8, WIDTH};
use super::ray_box::{Deferred, RayBox};

/// The order in which an opener pushes the children it enters (what the
/// tests expect of each).
#[cfg(test)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PushOrder {
    /// Farthest first by key: the nearest on top.
    ByKey,
    /// In the node's order for the ray's octant ([`Node8::order`]).
    Octant,
}

/// One way of opening a node: see the module docs.
pub(crate) trait NodeLanes: Copy {
    /// The order of the pushes.
    #[cfg(test)]
    const ORDER: PushOrder;

    /// The entry parameters `s` of node `n`'s children's boxes and a bit
    /// mask of the children the ray (`s ≥ 0`) may touch no later than
    /// `limit`; conservative (see [`RayBox`]).
    fn enter(self, rb: &RayBox, n: &Node8, limit: f32) -> ([f32; WIDTH], u32);

    /// Tests the children of node `n` against the ray and pushes those it
    /// may touch no later than `limit` onto `stack` above `sp`, nearest on
    /// top; returns the new top. `stack` has room for [`WIDTH`] entries
    /// above `sp`; those above the new top may be overwritten.
    fn open(self, rb: &RayBox, n: &Node8, limit: f32, stack: &mut [Deferred], sp: usize) -> usize;
}

/// Runs `$body` with `$lanes` bound to each implementation this processor
/// runs ([`Portable`], and [`Avx2`] and [`Avx512`] when detected).
#[cfg(test)]
macro_rules! for_each_lanes {
    (|$lanes:ident| $body:block) => {{
        {
            let $lanes = $crate::spatial::bvh::open_portable::Portable;
            $body
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = $crate::spatial::bvh::open_avx2::Avx2::detect() {
            {
                let $lanes = avx2;
                $body
            }
            if let Some($lanes) = avx2.avx512() {
                $body
            }
        }
    }};
}
#[cfg(test)]
pub(crate) use for_each_lanes;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Ray;
    use crate::spatial::bvh::Portable;
    use crate::spatial::bvh::node::{BoxFrame, LEAF, Node8, WIDTH};
    #[cfg(target_arch = "x86_64")]
    use crate::spatial::bvh::open_avx2;
    use crate::spatial::bvh::ray_box::{Deferred, KEY_SLOT_BITS};
    use glam::DVec3;

    /// Every opener pushes the children entered, and only those, with
    /// their keys: by key, the nearest on top (ties by slot), or in the
    /// node's octant order, as it says. Random nodes with empty, flat and
    /// huge slots, rays from inside and outside, some parallel to an axis.
    #[test]
    fn openers_push_the_entered_children_in_their_order() {
        let mut uniform = crate::test_rng::uniform(0xBB67_AE85_84CA_A73B);
        let frame = BoxFrame {
            centre: DVec3::ZERO,
            scale: 1.0,
        };
        let (mut pushed, mut several) = (0, 0);
        for case in 0..5_000 {
            let mut rand = || DVec3::new(uniform(), uniform(), uniform()) * 2.0 - DVec3::ONE;
            let mut node = Node8::EMPTY;
            for k in 0..WIDTH {
                let (lo, size) = (rand() * 0.8, (rand() + DVec3::ONE) * 0.8);
                for a in 0..3 {
                    let flat = (case + k + a) % 11 == 0;
                    node.bounds[a][k] = lo[a] as f32;
                    node.bounds[3 + a][k] = if flat { lo[a] } else { lo[a] + size[a] } as f32;
                }
                node.child[k] = match (case + 3 * k) % 7 {
                    0 => u32::MAX,
                    1 => LEAF | k as u32,
                    _ => 100 + k as u32,
                };
            }
            node.order_children();
            let origin = rand() * if case % 2 == 0 { 0.5 } else { 3.0 };
            // Aimed near one slot's box, so that most rays enter a few.
            let k = case % WIDTH;
            let aim = DVec3::from_array(
                [0, 1, 2].map(|a| f64::from(node.bounds[a][k] + node.bounds[3 + a][k]) * 0.5),
            );
            let mut direction = aim + rand() * 0.02 - origin;
            if case % 5 == 0 {
                direction[case % 3] = 0.0;
            }
            if direction == DVec3::ZERO {
                continue;
            }
            // Scaled by a power of two to a largest component in `[1, 2)`,
            // as the walks take rays.
            let largest = direction.abs().max_element();
            let ray = Ray::new(
                origin,
                direction * 2f64.powi(-(largest.log2().floor() as i32)),
            );
            let rb = RayBox::new(&ray, &frame);
            let limit = if case % 3 == 0 {
                rb.limit(uniform() * 2.0)
            } else {
                f32::INFINITY
            };
            let (entry, entered) = Portable.enter(&rb, &node, limit);
            // Keyed by the entry with its low four bits replaced: the
            // farthest first, the nearest on top.
            let mut want: Vec<(u32, usize)> = (0..WIDTH)
                .filter(|&k| entered & (1 << k) != 0)
                .map(|k| {
                    (
                        (entry[k].min(f32::MAX).to_bits() & !KEY_SLOT_BITS) | 8 | k as u32,
                        k,
                    )
                })
                .collect();
            want.sort_by(|p, q| q.cmp(p));
            // The same in the octant's order.
            let rank = |k: usize| {
                (0..WIDTH)
                    .position(|i| (node.order[rb.octant] >> (4 * i)) & 7 == k as u32)
                    .expect("every slot is in the order")
            };
            let mut by_octant = want.clone();
            by_octant.sort_by_key(|&(_, k)| rank(k));
            let mut orders = 0;
            for_each_lanes!(|lanes| {
                assert_eq!(lanes.enter(&rb, &node, limit), (entry, entered));
                let mut stack = [Deferred::EMPTY; WIDTH + 3];
                let top = lanes.open(&rb, &node, limit, &mut stack, 3);
                assert_eq!(top, 3 + want.len(), "case {case}");
                let want = match lanes_order(lanes) {
                    PushOrder::ByKey => &want,
                    PushOrder::Octant => &by_octant,
                };
                for (d, &(key, k)) in stack[3..top].iter().zip(want) {
                    assert_eq!((d.child, d.key), (node.child[k], key), "case {case}");
                    assert!(f32::from_bits(d.key & !KEY_SLOT_BITS) <= entry[k]);
                }
                orders += 1;
            });
            assert!(orders >= 1);
            pushed += want.len();
            several += usize::from(want.len() >= 3);
        }
        assert!(
            pushed > 3_000 && several > 500,
            "{pushed} pushed, {several} several"
        );
    }

    /// The AVX2 network orders every 0–1 input (which proves a network
    /// sorts everything) and random keys as `sort` does.
    fn lanes_order<L: NodeLanes>(_: L) -> PushOrder {
        L::ORDER
    }

    /// The octant order lists every slot once, farthest first along the
    /// octant's diagonal, with the empty slots flagged; boxes with infinite
    /// bounds (their centres NaN or infinite) are listed too.
    #[test]
    fn octant_orders_list_every_slot_farthest_first() {
        let mut uniform = crate::test_rng::uniform(0x1F83_D9AB_FB41_BD6B);
        for case in 0..500 {
            let mut node = Node8::EMPTY;
            for k in 0..WIDTH {
                if (case + k) % 5 == 0 {
                    continue;
                }
                for a in 0..3 {
                    let lo = uniform() as f32;
                    node.bounds[a][k] = lo;
                    node.bounds[3 + a][k] = lo + uniform() as f32;
                }
                match (case + 2 * k) % 13 {
                    0 => node.bounds[case % 3][k] = f32::NEG_INFINITY,
                    1 => node.bounds[3 + case % 3][k] = f32::INFINITY,
                    2 => {
                        node.bounds[case % 3][k] = f32::NEG_INFINITY;
                        node.bounds[3 + case % 3][k] = f32::INFINITY;
                    }
                    _ => {}
                }
                node.child[k] = k as u32;
            }
            node.order_children();
            for octant in 0..WIDTH {
                let nibbles: Vec<u32> = (0..WIDTH)
                    .map(|i| (node.order[octant] >> (4 * i)) & 15)
                    .collect();
                let mut slots: Vec<u32> = nibbles.iter().map(|n| n & 7).collect();
                slots.sort_unstable();
                assert_eq!(slots, (0..WIDTH as u32).collect::<Vec<_>>());
                let along = |k: usize| -> f64 {
                    (0..3)
                        .map(|a| {
                            let c = f64::from(node.bounds[a][k] + node.bounds[3 + a][k]);
                            if octant >> a & 1 == 1 { -c } else { c }
                        })
                        .sum()
                };
                let filled: Vec<usize> = nibbles
                    .iter()
                    .filter(|&&n| n & 8 == 0)
                    .map(|&n| (n & 7) as usize)
                    .collect();
                for pair in filled.windows(2) {
                    let (p, q) = (along(pair[0]), along(pair[1]));
                    assert!(p >= q || p.is_nan() || q.is_nan(), "case {case}");
                }
                for &n in &nibbles {
                    let empty = node.child[(n & 7) as usize] == u32::MAX;
                    assert_eq!(n & 8 != 0, empty, "case {case}");
                }
            }
        }
    }

    /// The AVX2 opener's packing table lists, for every mask of eight
    /// lanes, exactly the lanes set, in ascending order.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn the_packing_table_lists_the_lanes_set_in_order() {
        for mask in 0..256usize {
            let want: Vec<u32> = (0..8).filter(|&lane| mask >> lane & 1 == 1).collect();
            let bits = open_avx2::PACK[mask];
            let got: Vec<u32> = (0..want.len()).map(|k| (bits >> (4 * k)) & 15).collect();
            assert_eq!(got, want, "mask {mask:#010b}");
            if want.len() < 8 {
                assert_eq!(bits >> (4 * want.len()), 0, "mask {mask:#010b}");
            }
        }
    }
}
