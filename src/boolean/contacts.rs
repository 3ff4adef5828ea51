//! Stage 1: every pair of triangles of two operands that meet, found
//! through the operands' BVHs and decided exactly (`intersect::contact`).

use super::intersect::{self, Contact, Tri};
use super::operand::Prepared;

/// Every pair of triangles of two operands that meet, with its contact, in
/// an order fixed by the two BVHs; point indices are global (each
/// operand's vertices from its offset on).
pub(super) fn contacts(
    first: &Prepared,
    second: &Prepared,
    first_offset: u32,
    second_offset: u32,
) -> Vec<(u32, u32, Contact)> {
    let tri = |operand: &Prepared, t: u32, base: u32| Tri {
        corners: operand.corners(t),
        ids: operand.triangles[t as usize].map(|i| i + base),
    };
    first.bvh.par_leaf_pairs(&second.bvh, |la, lb, found| {
        let (Some(items_a), Some(items_b)) = (first.bvh.leaf(la), second.bvh.leaf(lb)) else {
            return;
        };
        for pa in items_a.range() {
            let ta = first.order[pa];
            let box_a = first.bounds[ta as usize];
            for pb in items_b.range() {
                let tb = second.order[pb];
                if box_a.intersection(second.bounds[tb as usize]).is_empty() {
                    continue;
                }
                if let Some(contact) = intersect::contact(
                    &tri(first, ta, first_offset),
                    &tri(second, tb, second_offset),
                ) {
                    found.push((ta, tb, contact));
                }
            }
        }
    })
}
