//! The AVX2 node opener: the eight slab tests in one 256-bit register per
//! operation, permuted into the node's order for the ray's octant
//! ([`Node8::order`]), and the children entered packed by a permutation
//! looked up in a 256-entry table by the mask of the children entered.
//! Also the octant-order slab tests the AVX-512 opener starts from.

use std::arch::x86_64 as arch;

use super::node::{Node8, WIDTH};
use super::open::NodeLanes;
#[cfg(test)]
use super::open::PushOrder;
use super::ray_box::{Deferred, KEY_SLOT_BITS, RayBox};

/// Node opening with AVX2; a value exists only when the processor has
/// AVX2 ([`Avx2::detect`]). Pushes in the octant order (see the module
/// docs).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx2 {
    /// Whether the processor also runs the AVX-512 instructions the
    /// walks are compiled for where offered (`avx512f`, `avx512vl`,
    /// `avx512bw`, `avx512dq`, with `bmi2` and `fma`): the same lane
    /// operations in their EVEX forms, with 32 vector registers and
    /// broadcasts folded into the arithmetic.
    pub(super) avx512: bool,
}

impl Avx2 {
    /// `Some` when this processor runs AVX2 instructions.
    #[inline]
    pub(crate) fn detect() -> Option<Avx2> {
        is_x86_feature_detected!("avx2").then(|| Avx2 {
            avx512: is_x86_feature_detected!("avx512f")
                && is_x86_feature_detected!("avx512vl")
                && is_x86_feature_detected!("avx512bw")
                && is_x86_feature_detected!("avx512dq")
                && is_x86_feature_detected!("bmi2")
                && is_x86_feature_detected!("fma"),
        })
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
    fn open(self, rb: &RayBox, n: &Node8, limit: f32, stack: &mut [Deferred], sp: usize) -> usize {
        // SAFETY: an `Avx2` value proves the processor has AVX2.
        unsafe { open_avx2(rb, n, limit, stack, sp) }
    }
}

// The functions below are not `#[target_feature]` functions: those are
// not always inlined, and a call per node costs more than the node.
// They are inlined into the `#[target_feature(enable = "avx2")]` walks
// (`Bvh::walk_ray` and `query`'s interleaved first-hit walk), where the AVX2
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
pub(super) unsafe fn enter_avx2(rb: &RayBox, n: &Node8, limit: f32) -> ([f32; WIDTH], u32) {
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
pub(super) struct OctantLanes {
    /// The order's nibbles: the slot in the low three bits, bit 3 set
    /// for an empty slot.
    pub(super) nibbles: arch::__m256i,
    /// Entry and exit parameters (see [`slab_bounds`]).
    pub(super) entry: arch::__m256,
    pub(super) exit: arch::__m256,
    /// The children's keys (entry bits with `8 | slot` below them).
    pub(super) keys: arch::__m256i,
    /// The children's [`Node8::child`] entries.
    pub(super) children: arch::__m256i,
}

/// The slab tests of node `n` and its children, permuted into the ray's
/// octant order: what both octant openers start from.
#[inline(always)]
pub(super) unsafe fn in_octant_order(rb: &RayBox, n: &Node8, limit: f32) -> OctantLanes {
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
        let bits =
            arch::_mm256_castps_si256(arch::_mm256_min_ps(entry, arch::_mm256_set1_ps(f32::MAX)));
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
pub(crate) static PACK: [u32; 256] = {
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
