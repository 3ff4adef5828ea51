//! First hits of many rays on one thread, interleaved: a few rays are walked
//! through the BVH in turn, one node each, and each step asks for the memory
//! its next step needs before handing over to the next ray. A ray's cache
//! misses (the BVH and its triangles are far larger than the caches on big
//! meshes) then overlap the other rays' work instead of stalling the core.
//!
//! Every ray visits the same nodes and triangles in the same order as
//! [`Accel::first_hit`] and decides each triangle with the same exact
//! predicates, so the answers are the same.

use crate::geom::Ray;

use super::Accel;
use super::accel::WIDTH;
use super::ray_solid::{
    BestHit, Crossing, RayBox, prefetch, split_children, unit_scaled, unscaled_t,
};
use super::tri_packet::PacketRay;

/// Rays walked in turn.
const LANES: usize = 8;

/// One ray's walk in progress.
struct Walk {
    /// Index of the ray in the batch.
    ray: usize,
    /// The ray with its direction scaled by a power of two
    /// ([`unit_scaled`]), and the factor back to the caller's `t`.
    scaled: Ray,
    t_scale: f64,
    rays_box: RayBox,
    /// The ray as the leaves' miss filter sees it.
    packet_ray: PacketRay,
    best: BestHit,
    /// The best crossing's `t` (`+∞` before any).
    t_limit: f64,
    /// `t_limit` as the slab tests see it ([`RayBox::limit`]).
    limit: f32,
    /// The node to open next and its entry (requested from memory).
    next: Option<(u32, f32)>,
    /// Leaves of the node opened last, in slot order: entry and packet
    /// (requested from memory).
    leaves: [(f32, u32); WIDTH],
    n_leaves: usize,
    /// Leaves filtered by the last step: entry, first triangle and the
    /// mask of triangles still to decide (requested from memory).
    pending: [(f32, u32, u32); WIDTH],
    n_pending: usize,
    /// Deferred subtrees with their entries; nearer on top.
    stack: smallvec::SmallVec<[(u32, f32); 64]>,
}

impl Walk {
    fn new(ray: usize, r: &Ray, accel: &Accel) -> Walk {
        let (scaled, t_scale) = unit_scaled(r);
        let rays_box = RayBox::new(&scaled, &accel.frame);
        let packet_ray = PacketRay::new(&scaled, accel.frame.scale);
        let limit = rays_box.limit(f64::INFINITY);
        Walk {
            ray,
            scaled,
            t_scale,
            rays_box,
            packet_ray,
            best: None,
            t_limit: f64::INFINITY,
            limit,
            next: Some((0, 0.0)),
            leaves: [(0.0, 0); WIDTH],
            n_leaves: 0,
            pending: [(0.0, 0, 0); WIDTH],
            n_pending: 0,
            stack: smallvec::SmallVec::new(),
        }
    }
}

impl Accel {
    /// The first hits of `rays` (checked valid by the caller) into `out`,
    /// in order.
    pub(super) fn first_hits_interleaved(&self, rays: &[Ray], out: &mut [Option<Crossing>]) {
        debug_assert_eq!(rays.len(), out.len());
        let mut lanes: smallvec::SmallVec<[Walk; LANES]> = (0..rays.len().min(LANES))
            .map(|k| Walk::new(k, &rays[k], self))
            .collect();
        let mut fed = lanes.len();
        while !lanes.is_empty() {
            let mut k = 0;
            while k < lanes.len() {
                let w = &mut lanes[k];
                let ray = w.scaled;
                if self.step(w, &ray) {
                    out[w.ray] = w
                        .best
                        .map(|(t, i, s)| self.crossing(unscaled_t(t, w.t_scale), i, s));
                    if fed < rays.len() {
                        lanes[k] = Walk::new(fed, &rays[fed], self);
                        fed += 1;
                    } else {
                        lanes.swap_remove(k);
                        continue;
                    }
                }
                k += 1;
            }
        }
    }

    /// One step of a walk: decide exactly the triangles the previous step's
    /// filter left undecided, filter the leaves found by the previous step
    /// (requesting their undecided triangles from memory for the next
    /// step), then open the next node (or fetch the next deferred one).
    /// Returns whether the walk is over.
    #[inline(always)]
    fn step(&self, w: &mut Walk, ray: &Ray) -> bool {
        for j in 0..w.n_pending {
            let (t, first, mut undecided) = w.pending[j];
            if t > w.limit {
                continue;
            }
            while undecided != 0 {
                let i = first + undecided.trailing_zeros();
                undecided &= undecided - 1;
                let t_new = self.consider_for_first_hit(ray, i, &mut w.best, w.t_limit);
                if t_new != w.t_limit {
                    w.t_limit = t_new;
                    w.limit = w.rays_box.limit(t_new);
                }
            }
        }
        w.n_pending = 0;
        for j in 0..w.n_leaves {
            let (t, packet) = w.leaves[j];
            if t > w.limit {
                continue;
            }
            let packet = &self.packets[packet as usize];
            let undecided = packet.undecided(&w.packet_ray);
            if undecided != 0 {
                let mut lanes = undecided;
                while lanes != 0 {
                    let i = (packet.first + lanes.trailing_zeros()) as usize;
                    lanes &= lanes - 1;
                    prefetch(std::slice::from_ref(&self.tris[i]));
                }
                w.pending[w.n_pending] = (t, packet.first, undecided);
                w.n_pending += 1;
            }
        }
        w.n_leaves = 0;
        let current = match w.next.take() {
            Some((n, t)) if t <= w.limit => n,
            _ => {
                // The next deferred subtree still in reach: ask for its node
                // now and open it on the next turn.
                while let Some((n, t)) = w.stack.pop() {
                    if t <= w.limit {
                        prefetch(std::slice::from_ref(&self.nodes[n as usize]));
                        w.next = Some((n, t));
                        return false;
                    }
                }
                return w.n_pending == 0;
            }
        };
        let node = &self.nodes[current as usize];
        let (entry, mask) = w.rays_box.enter4(node, w.limit);
        let (mut leaves, order) = split_children(node, &entry, mask);
        // Leaves wait for the next turn's filter; the nearest inner child
        // is opened then too; the other inner children are deferred (nearer
        // popped first). All of them are requested from memory now.
        while leaves != 0 {
            let k = leaves.trailing_zeros() as usize;
            leaves &= leaves - 1;
            let packet = node.child[k];
            prefetch(std::slice::from_ref(&self.packets[packet as usize]));
            w.leaves[w.n_leaves] = (entry[k], packet);
            w.n_leaves += 1;
        }
        let mut deferred: [(u32, f32); WIDTH] = [(0, 0.0); WIDTH];
        let mut n_deferred = 0;
        for j in 0..order.len {
            let k = order.get(j);
            let (child, t) = (node.child[k], entry[k]);
            prefetch(std::slice::from_ref(&self.nodes[child as usize]));
            if w.next.is_none() {
                w.next = Some((child, t));
            } else {
                deferred[n_deferred] = (child, t);
                n_deferred += 1;
            }
        }
        for &d in deferred[..n_deferred].iter().rev() {
            w.stack.push(d);
        }
        false
    }
}
