//! Opening a BVH node for one ray: the slab tests of its eight children
//! side by side, and the children entered pushed onto the traversal stack,
//! the nearest on top (by entry parameter, or along the ray's octant).
//!
//! Each child entered is keyed by the bits of its entry parameter (a
//! non-negative `f32`, clamped to finite, whose bits order as the values
//! do) with the low four bits replaced by `8 | slot`. Keys are distinct and
//! never 0. The order of the pushes decides only how soon a walk finds its
//! answer, never the answer (a first-hit walk keeps the nearest crossing
//! found, ties by triangle; culling by key is conservative). Three
//! implementations:
//!
//! - [`Avx512`], on `x86_64` processors with AVX-512 (detected at run
//!   time): the eight slab tests in one 256-bit register per operation,
//!   the results permuted into the node's precomputed order for the ray's
//!   octant ([`Node8::order`]: farthest first along the octant's
//!   diagonal), and the children entered packed with a compress
//!   instruction — no sorting;
//! - [`Avx2`], on `x86_64` processors with AVX2 but not AVX-512: the same
//!   octant order, the children entered packed by a permutation looked up
//!   in a 256-entry table by the mask of the children entered;
//! - [`Portable`], everywhere: the children in two halves of four
//!   [`F32x4`] lanes, then each child entered inserted into place by key,
//!   the nearest on top (a ray enters two or three of eight on average).
//!
//! Measured (1 thread, 1M peer rays, alternated pairs, 2026-11-24): the
//! AVX-512 opener took 7% less time per ray than a bitonic network sorting
//! all eight keys (six shuffle rounds) on fandisk and on sphere_80k; on the
//! AVX2 path the table packing took 2–5% less than the same network (on
//! fandisk, spot, sphere_80k). Pushing in slot order with no ordering at
//! all took 35% more time (walks visit more nodes), so the octant order
//! keeps what sorting bought. Earlier (sphere_80k, one thread): 0.36–0.40 s
//! for 1M rays with the insertion, 0.70–0.74 s with a scalar sorting
//! network, 0.29–0.32 s with the AVX2 network.

use super::accel::{Node8, WIDTH};
use super::lanes::F32x4;
use super::ray_solid::{Deferred, RayBox};

/// The low bits of a key that carry `8 | slot` (see the module docs).
pub(super) const KEY_SLOT_BITS: u32 = 15;

/// The order in which an opener pushes the children it enters (what the
/// tests expect of each).
#[cfg(test)]
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum PushOrder {
    /// Farthest first by key: the nearest on top.
    ByKey,
    /// In the node's order for the ray's octant ([`Node8::order`]).
    Octant,
}

/// One way of opening a node: see the module docs.
pub(super) trait NodeLanes: Copy {
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

/// Node opening in [`F32x4`] lanes and scalar code: runs everywhere.
#[derive(Clone, Copy, Debug)]
pub(super) struct Portable;

impl NodeLanes for Portable {
    #[cfg(test)]
    const ORDER: PushOrder = PushOrder::ByKey;
    #[inline(always)]
    fn enter(self, rb: &RayBox, n: &Node8, limit: f32) -> ([f32; WIDTH], u32) {
        let mut entry = [0.0f32; WIDTH];
        let mut entered = 0;
        for half in 0..2 {
            let lanes = |row: &[f32; WIDTH]| {
                F32x4::load(row[4 * half..4 * half + 4].try_into().expect("4 lanes"))
            };
            let mut t0 = F32x4::splat(0.0);
            let mut t1 = F32x4::splat(limit);
            for a in 0..3 {
                let near = lanes(&n.bounds[rb.near_row[a].index()]);
                let far = lanes(&n.bounds[rb.far_row[a].index()]);
                let tn = near
                    .sub(F32x4::splat(rb.o_near[a]))
                    .mul(F32x4::splat(rb.inv_near[a]));
                let tf = far
                    .sub(F32x4::splat(rb.o_far[a]))
                    .mul(F32x4::splat(rb.inv_far[a]));
                // NaN (0 · ∞: origin on the slab plane of a parallel ray)
                // leaves the bound unchanged.
                t0 = tn.max_or(t0);
                t1 = tf.min_or(t1);
            }
            entry[4 * half..4 * half + 4].copy_from_slice(&t0.to_array());
            entered |= t0.le(t1).bits() << (4 * half);
        }
        // An empty slot (`child == u32::MAX`) is never entered: its inverted
        // box is refused by the comparisons above except when the origin is
        // beyond the `f32` range (no constraint, NaN bounds left unchanged);
        // found by the queries fuzz target.
        for (k, &child) in n.child.iter().enumerate() {
            entered &= !(u32::from(child == u32::MAX) << k);
        }
        (entry, entered)
    }

    #[inline(always)]
    fn open(self, rb: &RayBox, n: &Node8, limit: f32, stack: &mut [Deferred], sp: usize) -> usize {
        let (entry, entered) = self.enter(rb, n, limit);
        // Insertion of each child entered (a ray enters two or three of
        // eight on average) into the run above `sp`, kept farthest first.
        let (mut top, mut rest) = (sp, entered);
        while rest != 0 {
            let k = rest.trailing_zeros() as usize;
            rest &= rest - 1;
            let key = (entry[k].min(f32::MAX).to_bits() & !KEY_SLOT_BITS) | 8 | k as u32;
            let mut j = top;
            while j > sp && stack[j - 1].key < key {
                stack[j] = stack[j - 1];
                j -= 1;
            }
            stack[j] = Deferred {
                child: n.child[k],
                key,
            };
            top += 1;
        }
        top
    }
}

#[cfg(target_arch = "x86_64")]
pub(super) use avx2::{Avx2, Avx512};

#[cfg(target_arch = "x86_64")]
mod avx2 {
    use std::arch::x86_64 as arch;

    #[cfg(test)]
    use super::PushOrder;
    use super::{Deferred, KEY_SLOT_BITS, Node8, NodeLanes, RayBox, WIDTH};

    /// Node opening with AVX2; a value exists only when the processor has
    /// AVX2 ([`Avx2::detect`]). Pushes in the octant order (see the module
    /// docs).
    #[derive(Clone, Copy, Debug)]
    pub(in super::super) struct Avx2 {
        /// Whether the processor also runs the AVX-512 instructions the
        /// walks are compiled for where offered (`avx512f`, `avx512vl`,
        /// `avx512bw`, `avx512dq`, with `bmi2` and `fma`): the same lane
        /// operations in their EVEX forms, with 32 vector registers and
        /// broadcasts folded into the arithmetic.
        avx512: bool,
    }

    impl Avx2 {
        /// `Some` when this processor runs AVX2 instructions.
        #[inline]
        pub(in super::super) fn detect() -> Option<Avx2> {
            is_x86_feature_detected!("avx2").then(|| Avx2 {
                avx512: is_x86_feature_detected!("avx512f")
                    && is_x86_feature_detected!("avx512vl")
                    && is_x86_feature_detected!("avx512bw")
                    && is_x86_feature_detected!("avx512dq")
                    && is_x86_feature_detected!("bmi2")
                    && is_x86_feature_detected!("fma"),
            })
        }

        /// The AVX-512 opener, when this processor runs it.
        #[inline]
        pub(in super::super) fn avx512(self) -> Option<Avx512> {
            self.avx512.then_some(Avx512(()))
        }
    }

    /// Node opening with AVX-512 (the `f`, `vl`, `bw` and `dq` subsets):
    /// pushes in the node's octant order (see the module docs). A value
    /// exists only when the processor has them ([`Avx2::avx512`]).
    #[derive(Clone, Copy, Debug)]
    pub(in super::super) struct Avx512(());

    impl NodeLanes for Avx512 {
        #[cfg(test)]
        const ORDER: PushOrder = PushOrder::Octant;
        #[inline(always)]
        fn enter(self, rb: &RayBox, n: &Node8, limit: f32) -> ([f32; WIDTH], u32) {
            // SAFETY: an `Avx512` value proves the processor has AVX-512,
            // and so AVX2.
            unsafe { enter_avx2(rb, n, limit) }
        }

        #[inline(always)]
        fn open(
            self,
            rb: &RayBox,
            n: &Node8,
            limit: f32,
            stack: &mut [Deferred],
            sp: usize,
        ) -> usize {
            // SAFETY: an `Avx512` value proves the processor has AVX-512.
            unsafe { open_avx512(rb, n, limit, stack, sp) }
        }
    }

    impl NodeLanes for Avx2 {
        #[cfg(test)]
        const ORDER: PushOrder = PushOrder::Octant;
        #[inline(always)]
        fn enter(self, rb: &RayBox, n: &Node8, limit: f32) -> ([f32; WIDTH], u32) {
            // SAFETY: an `Avx2` value proves the processor has AVX2.
            unsafe { enter_avx2(rb, n, limit) }
        }

        #[inline(always)]
        fn open(
            self,
            rb: &RayBox,
            n: &Node8,
            limit: f32,
            stack: &mut [Deferred],
            sp: usize,
        ) -> usize {
            // SAFETY: an `Avx2` value proves the processor has AVX2.
            unsafe { open_avx2(rb, n, limit, stack, sp) }
        }
    }

    // The functions below are not `#[target_feature]` functions: those are
    // not always inlined, and a call per node costs more than the node.
    // They are inlined into the `#[target_feature(enable = "avx2")]` walks
    // (`Accel::traverse`, `Accel::first_hits_interleaved`), where the AVX2
    // intrinsics inline in turn.
    //
    // # Safety (each function)
    //
    // The processor must have AVX2.

    /// The children's entry and exit parameters, `max(0, entries)` and
    /// `min(limit, exits)`, as lanes.
    #[inline(always)]
    unsafe fn slab_bounds(rb: &RayBox, n: &Node8, limit: f32) -> (arch::__m256, arch::__m256) {
        // SAFETY: AVX2 (the caller's contract); the loads read whole rows
        // of `n`, 32-byte aligned (`Node8` is 64-byte aligned and its rows
        // are 32 bytes).
        unsafe {
            let mut t0 = arch::_mm256_setzero_ps();
            let mut t1 = arch::_mm256_set1_ps(limit);
            for a in 0..3 {
                let near = arch::_mm256_load_ps(n.bounds[rb.near_row[a].index()].as_ptr());
                let far = arch::_mm256_load_ps(n.bounds[rb.far_row[a].index()].as_ptr());
                let tn = arch::_mm256_mul_ps(
                    arch::_mm256_sub_ps(near, arch::_mm256_set1_ps(rb.o_near[a])),
                    arch::_mm256_set1_ps(rb.inv_near[a]),
                );
                let tf = arch::_mm256_mul_ps(
                    arch::_mm256_sub_ps(far, arch::_mm256_set1_ps(rb.o_far[a])),
                    arch::_mm256_set1_ps(rb.inv_far[a]),
                );
                // `maxps`/`minps` return their second operand when either is
                // NaN (0 · ∞: origin on the slab plane of a parallel ray), which
                // leaves the bound unchanged.
                t0 = arch::_mm256_max_ps(tn, t0);
                t1 = arch::_mm256_min_ps(tf, t1);
            }
            (t0, t1)
        }
    }

    /// Entry parameters and the entered children as lanes (all bits set
    /// where entered).
    #[inline(always)]
    unsafe fn slab_test(rb: &RayBox, n: &Node8, limit: f32) -> (arch::__m256, arch::__m256) {
        // SAFETY: AVX2 (the caller's contract); the load reads `n`'s
        // children, eight `u32`s 32-byte aligned.
        unsafe {
            let (t0, t1) = slab_bounds(rb, n, limit);
            // An empty slot (`child == u32::MAX`) is never entered (see
            // `Portable::enter`).
            let children = arch::_mm256_load_si256(n.child.as_ptr().cast());
            let empty = arch::_mm256_cmpeq_epi32(children, arch::_mm256_set1_epi32(-1));
            let entered = arch::_mm256_andnot_ps(
                arch::_mm256_castsi256_ps(empty),
                arch::_mm256_cmp_ps::<{ arch::_CMP_LE_OQ }>(t0, t1),
            );
            (t0, entered)
        }
    }

    #[inline(always)]
    unsafe fn enter_avx2(rb: &RayBox, n: &Node8, limit: f32) -> ([f32; WIDTH], u32) {
        let mut entry = [0.0f32; WIDTH];
        // SAFETY: AVX2 (the caller's contract); `entry` is eight `f32`s,
        // stored unaligned.
        unsafe {
            let (t0, entered) = slab_test(rb, n, limit);
            arch::_mm256_storeu_ps(entry.as_mut_ptr(), t0);
            (entry, arch::_mm256_movemask_ps(entered) as u32)
        }
    }

    #[inline(always)]
    unsafe fn open_avx2(
        rb: &RayBox,
        n: &Node8,
        limit: f32,
        stack: &mut [Deferred],
        sp: usize,
    ) -> usize {
        let out = &mut stack[sp..sp + WIDTH];
        // SAFETY: AVX2 (the caller's contract); the loads read `n`'s
        // children, eight `u32`s 32-byte aligned; `out` is eight `Deferred`s,
        // each two `u32`s in order (`repr(C)`), 64 bytes written unaligned.
        unsafe {
            let o = in_octant_order(rb, n, limit);
            let empty = arch::_mm256_castsi256_ps(arch::_mm256_cmpgt_epi32(
                o.nibbles,
                arch::_mm256_set1_epi32(7),
            ));
            let entered = arch::_mm256_andnot_ps(
                empty,
                arch::_mm256_cmp_ps::<{ arch::_CMP_LE_OQ }>(o.entry, o.exit),
            );
            let mask = arch::_mm256_movemask_ps(entered) as usize;
            // The lanes entered, packed low in order.
            let packed = arch::_mm256_srlv_epi32(
                arch::_mm256_set1_epi32(PACK[mask & 0xFF] as i32),
                nibble_shifts(),
            );
            let (keys, children) = (o.keys, o.children);
            let keys = arch::_mm256_permutevar8x32_epi32(keys, packed);
            let children = arch::_mm256_permutevar8x32_epi32(children, packed);
            let low = arch::_mm256_unpacklo_epi32(children, keys);
            let high = arch::_mm256_unpackhi_epi32(children, keys);
            let out = out.as_mut_ptr().cast::<arch::__m256i>();
            arch::_mm256_storeu_si256(out, arch::_mm256_permute2x128_si256::<0x20>(low, high));
            arch::_mm256_storeu_si256(
                out.add(1),
                arch::_mm256_permute2x128_si256::<0x31>(low, high),
            );
            sp + (mask as u32).count_ones() as usize
        }
    }

    /// The shifts that bring nibble `k` of a word to the bottom of lane `k`.
    #[inline(always)]
    unsafe fn nibble_shifts() -> arch::__m256i {
        // SAFETY: AVX (the caller's contract: AVX2).
        unsafe { arch::_mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28) }
    }

    /// A node's children in the ray's octant order ([`Node8::order`]):
    /// lane `k` holds the `k`-th slot of the order.
    struct OctantLanes {
        /// The order's nibbles: the slot in the low three bits, bit 3 set
        /// for an empty slot.
        nibbles: arch::__m256i,
        /// Entry and exit parameters (see [`slab_bounds`]).
        entry: arch::__m256,
        exit: arch::__m256,
        /// The children's keys (entry bits with `8 | slot` below them).
        keys: arch::__m256i,
        /// The children's [`Node8::child`] entries.
        children: arch::__m256i,
    }

    /// The slab tests of node `n` and its children, permuted into the ray's
    /// octant order: what both octant openers start from.
    #[inline(always)]
    unsafe fn in_octant_order(rb: &RayBox, n: &Node8, limit: f32) -> OctantLanes {
        // SAFETY: AVX2 (the caller's contract); the load reads `n`'s
        // children, eight `u32`s 32-byte aligned.
        unsafe {
            let (t0, t1) = slab_bounds(rb, n, limit);
            let nibbles = arch::_mm256_and_si256(
                arch::_mm256_srlv_epi32(
                    arch::_mm256_set1_epi32(n.order[rb.octant & 7] as i32),
                    nibble_shifts(),
                ),
                arch::_mm256_set1_epi32(15),
            );
            let entry = arch::_mm256_permutevar8x32_ps(t0, nibbles);
            let exit = arch::_mm256_permutevar8x32_ps(t1, nibbles);
            let bits = arch::_mm256_castps_si256(arch::_mm256_min_ps(
                entry,
                arch::_mm256_set1_ps(f32::MAX),
            ));
            let keys = arch::_mm256_or_si256(
                arch::_mm256_and_si256(bits, arch::_mm256_set1_epi32(!KEY_SLOT_BITS as i32)),
                arch::_mm256_or_si256(nibbles, arch::_mm256_set1_epi32(8)),
            );
            let children = arch::_mm256_permutevar8x32_epi32(
                arch::_mm256_load_si256(n.child.as_ptr().cast()),
                nibbles,
            );
            OctantLanes {
                nibbles,
                entry,
                exit,
                keys,
                children,
            }
        }
    }

    /// For each mask of eight lanes, the lanes set, in order, as nibbles
    /// (lane of the `k`-th set bit in bits `4k ..`; the rest 0).
    pub(in super::super) static PACK: [u32; 256] = {
        let mut table = [0u32; 256];
        let mut mask = 0;
        while mask < 256 {
            let (mut bits, mut k, mut lane) = (0u32, 0, 0);
            while lane < 8 {
                if mask >> lane & 1 == 1 {
                    bits |= (lane as u32) << (4 * k);
                    k += 1;
                }
                lane += 1;
            }
            table[mask] = bits;
            mask += 1;
        }
        table
    };

    /// [`NodeLanes::open`] in the octant order, with AVX-512.
    ///
    /// # Safety
    ///
    /// The processor must have AVX-512 (`f`, `vl`).
    #[inline(always)]
    unsafe fn open_avx512(
        rb: &RayBox,
        n: &Node8,
        limit: f32,
        stack: &mut [Deferred],
        sp: usize,
    ) -> usize {
        let out = &mut stack[sp..sp + WIDTH];
        // SAFETY: AVX-512 (the caller's contract), and so AVX2; the loads
        // read `n`'s children, eight `u32`s 32-byte aligned; `out` is eight
        // `Deferred`s, each two `u32`s in order (`repr(C)`), 64 bytes
        // written unaligned.
        unsafe {
            let o = in_octant_order(rb, n, limit);
            // A slot flagged empty (nibble bit 3) is never entered.
            let filled = arch::_mm256_testn_epi32_mask(o.nibbles, arch::_mm256_set1_epi32(8));
            let entered =
                arch::_mm256_mask_cmp_ps_mask::<{ arch::_CMP_LE_OQ }>(filled, o.entry, o.exit);
            // The children entered, in order, packed into the low lanes,
            // each beside its key.
            let keys = arch::_mm256_maskz_compress_epi32(entered, o.keys);
            let children = arch::_mm256_maskz_compress_epi32(entered, o.children);
            let pairs = arch::_mm512_permutex2var_epi32(
                arch::_mm512_castsi256_si512(children),
                arch::_mm512_setr_epi32(0, 16, 1, 17, 2, 18, 3, 19, 4, 20, 5, 21, 6, 22, 7, 23),
                arch::_mm512_castsi256_si512(keys),
            );
            arch::_mm512_storeu_si512(out.as_mut_ptr().cast(), pairs);
            sp + entered.count_ones() as usize
        }
    }
}

/// Runs `$body` with `$lanes` bound to each implementation this processor
/// runs ([`Portable`], and [`Avx2`] and [`Avx512`] when detected).
#[cfg(test)]
macro_rules! for_each_lanes {
    (|$lanes:ident| $body:block) => {{
        {
            let $lanes = $crate::query::node_open::Portable;
            $body
        }
        #[cfg(target_arch = "x86_64")]
        if let Some(avx2) = $crate::query::node_open::Avx2::detect() {
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
pub(super) use for_each_lanes;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::Ray;
    use crate::query::accel::BoxFrame;
    use crate::query::ray_solid::unit_scaled;
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
                    1 => crate::query::accel::LEAF | k as u32,
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
            let (ray, _) = unit_scaled(&Ray::new(origin, direction));
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
            let bits = avx2::PACK[mask];
            let got: Vec<u32> = (0..want.len()).map(|k| (bits >> (4 * k)) & 15).collect();
            assert_eq!(got, want, "mask {mask:#010b}");
            if want.len() < 8 {
                assert_eq!(bits >> (4 * want.len()), 0, "mask {mask:#010b}");
            }
        }
    }
}
