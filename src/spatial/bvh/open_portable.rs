//! The portable node opener: the slab tests in two halves of four `f32`
//! lanes, then each child entered inserted into place by key, the nearest
//! on top. Runs on every processor.

use crate::spatial::raw::lanes::F32x4;

use super::node::{Node8, WIDTH};
use super::open::NodeLanes;
#[cfg(test)]
use super::open::PushOrder;
use super::ray_box::{Deferred, KEY_SLOT_BITS, RayBox};

/// Node opening in [`F32x4`] lanes and scalar code: runs everywhere.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Portable;

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
