//! The AVX-512 node opener: the AVX2 opener's octant-order slab tests,
//! then the children entered packed with one compress instruction.

use std::arch::x86_64 as arch;

use super::node::{Node8, WIDTH};
use super::open::NodeLanes;
#[cfg(test)]
use super::open::PushOrder;
use super::open_avx2::{Avx2, enter_avx2, in_octant_order};
use super::ray_box::{Deferred, RayBox};

/// Node opening with AVX-512 (the `f`, `vl`, `bw` and `dq` subsets):
/// pushes in the node's octant order (see the module docs). A value
/// exists only when the processor has them ([`Avx2::avx512`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Avx512(());

impl Avx2 {
    /// The AVX-512 opener, when this processor runs it.
    #[inline]
    pub(crate) fn avx512(self) -> Option<Avx512> {
        self.avx512.then_some(Avx512(()))
    }
}

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
    fn open(self, rb: &RayBox, n: &Node8, limit: f32, stack: &mut [Deferred], sp: usize) -> usize {
        // SAFETY: an `Avx512` value proves the processor has AVX-512.
        unsafe { open_avx512(rb, n, limit, stack, sp) }
    }
}

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
