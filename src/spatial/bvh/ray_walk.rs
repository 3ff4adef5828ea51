//! The walk of one ray through the tree, nearest box first, generic over
//! what is done at a leaf ([`RayLeaves`]): first hit, all crossings, a CSG
//! leaf's spans — each a leaf test on the same tree.

use crate::geom::Ray;

use super::node::LEAF;
use super::open::NodeLanes;
#[cfg(target_arch = "x86_64")]
use super::open_avx2::Avx2;
#[cfg(target_arch = "x86_64")]
use super::open_avx512::Avx512;
use super::open_portable::Portable;
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
    /// or AVX2 where the processor has them (see `open`);
    /// the leaves visited, and their order, are the same either way.
    #[inline(always)]
    pub(crate) fn walk_ray(&self, ray: &Ray, t_max: f64, leaves: &mut impl RayLeaves) {
        #[cfg(target_arch = "x86_64")]
        if let Some(lanes) = Avx2::detect() {
            if let Some(lanes) = lanes.avx512() {
                // SAFETY: the AVX-512 features were detected.
                unsafe { self.walk_ray_avx512(lanes, ray, t_max, leaves) };
            } else {
                // SAFETY: AVX2 was detected.
                unsafe { self.walk_ray_avx2(lanes, ray, t_max, leaves) };
            }
            return;
        }
        self.walk_ray_with(Portable, ray, t_max, leaves);
    }

    /// [`Bvh::walk_ray`] compiled for AVX-512, with its node opener.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,popcnt,fma,bmi1,bmi2,lzcnt,avx512f,avx512vl,avx512bw,avx512dq")]
    fn walk_ray_avx512(&self, lanes: Avx512, ray: &Ray, t_max: f64, leaves: &mut impl RayLeaves) {
        self.walk_ray_with(lanes, ray, t_max, leaves);
    }

    /// [`Bvh::walk_ray`] compiled for AVX2, so that the node opening is
    /// inlined into it.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,popcnt")]
    fn walk_ray_avx2(&self, lanes: Avx2, ray: &Ray, t_max: f64, leaves: &mut impl RayLeaves) {
        self.walk_ray_with(lanes, ray, t_max, leaves);
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
