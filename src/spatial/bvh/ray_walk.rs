//! The walk of one ray through the tree, nearest box first, generic over
//! what is done at a leaf ([`RayLeaves`]): first hit, all crossings, a CSG
//! leaf's spans — each a leaf test on the same tree.

use crate::geom::Ray;

use super::node::LEAF;
use super::open::NodeLanes;
use super::open_widest::{LanesJob, with_widest_lanes};
use super::ray_box::{Deferred, RayBox, limit_key};
use super::tree::Bvh;

/// What a ray walk does at the leaves it reaches: the query's half of the
/// walk.
pub(crate) trait RayLeaves {
    /// A node is being opened (for counting; nothing by default).
    #[inline(always)]
    fn node(&mut self) {}

    /// Visits leaf `leaf`, whose box the ray may touch no later than
    /// `t_limit`; returns the new limit (`t_limit` when it did not change).
    /// A limit never grows: children whose boxes the ray enters beyond it
    /// are dropped unvisited.
    fn leaf(&mut self, leaf: u32, t_limit: f64) -> f64;
}

/// Traversal stacks at most this long live on the call stack; longer ones
/// (trees deeper than 20 levels) on the heap.
const LOCAL_STACK: usize = 64;

impl Bvh {
    /// Walks `ray` through the tree: visits every leaf whose box the ray
    /// may touch before the current limit (`t_max` at first, then what the
    /// leaves return), nearest box first. The box tests are conservative
    /// (see [`RayBox`]): a leaf whose box the exact ray meets before the
    /// limit is always visited. `ray`'s direction must be scaled so that
    /// its largest component is in `[1, 2)`. Nodes are opened with AVX-512
    /// or AVX2 where the processor has them (see `open_widest`);
    /// the leaves visited, and their order, are the same either way.
    #[inline(always)]
    pub(crate) fn walk_ray(&self, ray: &Ray, t_max: f64, leaves: &mut impl RayLeaves) {
        with_widest_lanes(WalkRay {
            bvh: self,
            ray,
            t_max,
            leaves,
        });
    }

    /// [`Bvh::walk_ray`] with nodes opened by `lanes`.
    #[inline(always)]
    pub(crate) fn walk_ray_with(
        &self,
        lanes: impl NodeLanes,
        ray: &Ray,
        t_max: f64,
        leaves: &mut impl RayLeaves,
    ) {
        let rb = RayBox::new(ray, self.frame());
        let mut t_limit = t_max;
        let mut limit = rb.limit(t_limit);
        let mut key = limit_key(limit);
        let mut local = [Deferred::EMPTY; LOCAL_STACK];
        let mut heap = Vec::new();
        let stack: &mut [Deferred] = if self.stack_len() <= LOCAL_STACK {
            &mut local
        } else {
            heap.resize(self.stack_len(), Deferred::EMPTY);
            &mut heap
        };
        leaves.node();
        let mut sp = self.open_node(lanes, &rb, 0, limit, stack, 0);
        while sp > 0 {
            sp -= 1;
            let Some(child) = stack[sp].reached(key) else {
                continue;
            };
            if child & LEAF == 0 {
                leaves.node();
                sp = self.open_node(lanes, &rb, child, limit, stack, sp);
                continue;
            }
            let t_new = leaves.leaf(child & !LEAF, t_limit);
            if t_new != t_limit {
                t_limit = t_new;
                limit = rb.limit(t_limit);
                key = limit_key(limit);
            }
        }
    }

    /// Opens inner node `node` with `lanes` (see [`NodeLanes::open`]):
    /// pushes the children the ray may touch no later than `limit` onto
    /// `stack` above `sp`, nearest on top; returns the new top. `stack` has
    /// room for [`WIDTH`](super::WIDTH) entries above `sp` (see
    /// [`Bvh::stack_len`]).
    #[inline(always)]
    pub(crate) fn open_node(
        &self,
        lanes: impl NodeLanes,
        rb: &RayBox,
        node: u32,
        limit: f32,
        stack: &mut [Deferred],
        sp: usize,
    ) -> usize {
        lanes.open(rb, &self.nodes()[node as usize], limit, stack, sp)
    }
}

/// One ray's walk, as work for [`with_widest_lanes`].
struct WalkRay<'a, L> {
    bvh: &'a Bvh,
    ray: &'a Ray,
    t_max: f64,
    leaves: &'a mut L,
}

impl<L: RayLeaves> LanesJob for WalkRay<'_, L> {
    type Output = ();

    #[inline(always)]
    fn run(self, lanes: impl NodeLanes) {
        self.bvh
            .walk_ray_with(lanes, self.ray, self.t_max, self.leaves);
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeSet;

    use glam::DVec3;

    use super::*;
    use crate::geom::Aabb;
    use crate::spatial::bvh::for_each_lanes;
    use crate::spatial::bvh::pair_walk::tests::random_boxes;

    /// A leaf test that lists the leaves it is given and never lowers the
    /// limit.
    struct AllLeaves(Vec<u32>);

    impl RayLeaves for AllLeaves {
        fn leaf(&mut self, leaf: u32, t_limit: f64) -> f64 {
            self.0.push(leaf);
            t_limit
        }
    }

    /// A leaf test that takes each leaf's nearest item box entry as the new
    /// limit: a first-hit walk on boxes.
    struct NearestBox<'a> {
        bvh: &'a Bvh,
        items: &'a [Aabb],
        ray: Ray,
    }

    impl RayLeaves for NearestBox<'_> {
        fn leaf(&mut self, leaf: u32, t_limit: f64) -> f64 {
            let items = self.bvh.leaf(leaf).unwrap().range();
            items
                .filter_map(|p| entry(&self.items[p], &self.ray))
                .fold(t_limit, f64::min)
        }
    }

    /// Where the ray enters the box shrunk by a millionth of its size
    /// (`t ≥ 0`), in `f64`: far inside the walk's margins.
    fn entry(b: &Aabb, ray: &Ray) -> Option<f64> {
        let shrink = b.size() * 1e-6;
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        for a in 0..3 {
            let (lo, hi) = (b.min[a] + shrink[a], b.max[a] - shrink[a]);
            let (o, d) = (ray.origin[a], ray.direction[a]);
            if d == 0.0 {
                if o < lo || o > hi {
                    return None;
                }
                continue;
            }
            let (p, q) = ((lo - o) / d, (hi - o) / d);
            t0 = t0.max(p.min(q));
            t1 = t1.min(p.max(q));
        }
        (t0 <= t1).then_some(t0)
    }

    /// Every opener's walk visits every leaf holding a box the ray enters,
    /// each once; with a leaf test that lowers the limit, the nearest box
    /// entry found is the true nearest.
    #[test]
    fn walks_visit_every_leaf_the_ray_meets() {
        let mut boxes = random_boxes(3_000, 0x243F_6A88_85A3_08D3, -1.0, 2.0, 0.2);
        for b in &mut boxes {
            // No flat boxes: a shrunk flat box would be inside out.
            b.max += DVec3::splat(1e-3);
        }
        let (bvh, order) = Bvh::build(&boxes);
        let items: Vec<Aabb> = order.iter().map(|&i| boxes[i as usize]).collect();
        let mut u = crate::test_rng::uniform(0x1319_8A2E_0370_7344);
        let mut met = 0;
        for case in 0..300 {
            let origin = DVec3::new(u(), u(), u()) * 6.0 - DVec3::splat(3.0);
            let mut direction = DVec3::new(u(), u(), u()) - DVec3::splat(0.5) - origin;
            if case % 7 == 0 {
                direction[case % 3] = 0.0;
            }
            let largest = direction.abs().max_element();
            let ray = Ray::new(
                origin,
                direction * 2f64.powi(-(largest.log2().floor() as i32)),
            );
            let want: BTreeSet<u32> = (0..bvh.leaf_count() as u32)
                .filter(|&k| {
                    let range = bvh.leaf(k).unwrap().range();
                    range.into_iter().any(|p| entry(&items[p], &ray).is_some())
                })
                .collect();
            met += usize::from(want.len() > 2);
            let nearest = (0..items.len())
                .filter_map(|p| entry(&items[p], &ray))
                .fold(f64::INFINITY, f64::min);
            for_each_lanes!(|lanes| {
                let mut all = AllLeaves(Vec::new());
                bvh.walk_ray_with(lanes, &ray, f64::INFINITY, &mut all);
                let visited: BTreeSet<u32> = all.0.iter().copied().collect();
                assert_eq!(visited.len(), all.0.len(), "case {case}: a leaf twice");
                assert!(visited.is_superset(&want), "case {case}");
                let mut first = NearestBox {
                    bvh: &bvh,
                    items: &items,
                    ray,
                };
                let mut t = f64::INFINITY;
                bvh.walk_ray_with(
                    lanes,
                    &ray,
                    f64::INFINITY,
                    &mut TrackLimit(&mut first, &mut t),
                );
                assert_eq!(t, nearest, "case {case}");
            });
        }
        assert!(met > 100, "{met} rays met more than two leaves");
    }

    /// Forwards to a leaf test and keeps the lowest limit it returned.
    struct TrackLimit<'a, L>(&'a mut L, &'a mut f64);

    impl<L: RayLeaves> RayLeaves for TrackLimit<'_, L> {
        fn leaf(&mut self, leaf: u32, t_limit: f64) -> f64 {
            let t = self.0.leaf(leaf, t_limit);
            *self.1 = self.1.min(t);
            t
        }
    }
}
