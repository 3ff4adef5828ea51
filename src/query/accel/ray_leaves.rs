//! The ray queries' leaf test: each leaf's triangles through the `f32`
//! packet filter, the undecided ones handed to the query's exact test.

use crate::geom::Ray;
use crate::spatial::bvh::RayLeaves;

use super::Accel;
use super::tri_packet::{PacketRay, TriPacket};
use crate::query::ray_answers::Tally;

/// The leaves of a ray walk as the ray queries see them: `visit(i, t)` is
/// called for every triangle `i` of a leaf reached that the leaf's packet
/// cannot prove missed, with the current limit `t`, and returns the new one.
struct PacketLeaves<'a, T, V> {
    packets: &'a [TriPacket],
    ray: PacketRay,
    tally: &'a mut T,
    visit: V,
}

impl<T: Tally, V: FnMut(u32, f64) -> f64> RayLeaves for PacketLeaves<'_, T, V> {
    #[inline(always)]
    fn node(&mut self) {
        self.tally.node();
    }

    #[inline(always)]
    fn leaf(&mut self, leaf: u32, mut t_limit: f64) -> f64 {
        let packet = &self.packets[leaf as usize];
        for _ in 0..packet.count {
            self.tally.triangle();
        }
        let mut undecided = packet.undecided(&self.ray);
        while undecided != 0 {
            let i = packet.first + undecided.trailing_zeros();
            undecided &= undecided - 1;
            self.tally.exact_test();
            t_limit = (self.visit)(i, t_limit);
        }
        t_limit
    }
}

impl Accel {
    /// Visits the triangles of every leaf whose box the ray may touch before
    /// the current limit, nearest box first, except those its
    /// [`TriPacket`] proves missed. `visit(i, t_max)` returns the new limit
    /// (a `t`). The leaves' filter drops triangles only when
    /// `filter_misses` (its proof is for a ray
    /// [`unit_scaled`](crate::query::ray_scaling::unit_scaled) without rounding,
    /// [`scales_exactly`](crate::query::ray_scaling::scales_exactly)); the box
    /// tests are conservative for the caller's ray either way (a component
    /// that rounds is below `2⁻¹⁰²²`, so its slab's entry beyond a box plane
    /// is past `2⁸⁷³` — beyond every finite `f32` limit — exactly or rounded
    /// to 0). The walk itself is the shared BVH's ([`Bvh::walk_ray`]).
    ///
    /// [`Bvh::walk_ray`]: crate::spatial::Bvh
    #[inline(always)]
    pub(in crate::query) fn traverse(
        &self,
        ray: &Ray,
        filter_misses: bool,
        t_max: f64,
        tally: &mut impl Tally,
        visit: impl FnMut(u32, f64) -> f64,
    ) {
        let mut pr = PacketRay::new(ray, self.bvh.frame().scale);
        if !filter_misses {
            pr = pr.blind();
        }
        let mut leaves = PacketLeaves {
            packets: &self.packets,
            ray: pr,
            tally,
            visit,
        };
        self.bvh.walk_ray(ray, t_max, &mut leaves);
    }
}
