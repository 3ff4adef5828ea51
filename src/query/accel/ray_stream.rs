//! First hits of many rays on one thread, interleaved: a few rays are walked
//! through the BVH in turn, one node or leaf each, and each step asks for
//! the memory its next step needs before handing over to the next ray. A
//! ray's cache misses (the BVH and its triangles are far larger than the
//! caches on big meshes) then overlap the other rays' work instead of
//! stalling the core; so does the latency of each step's chain of dependent
//! loads and lane operations, which bounds a single ray's walk even when
//! everything is in cache.
//!
//! Every ray visits the same nodes and triangles in the same order as
//! [`Accel::first_hit`] and decides each triangle with the same exact
//! predicates, so the answers are the same.

use crate::geom::Ray;

use crate::spatial::bvh::{
    BoxFrame, Deferred, LEAF, LanesJob, Node8, NodeLanes, RayBox, WIDTH, limit_key,
    with_widest_lanes,
};
use crate::spatial::raw::prefetch::prefetch_bytes;

use super::Accel;
use super::tri_packet::{PacketRay, TriPacket};
use super::triangle_records::YzTri;
use crate::query::ray_answers::{BestHit, Crossing, Nearest};
use crate::query::ray_scaling::{TScale, scales_exactly, unit_scaled, unscaled_t};

/// Rays walked in turn on accels that stay in the caches...
const LANES: usize = 8;

/// ...and on accels of at least `MANY_LANES_BYTES`, whose memory requests
/// take longer to come back: more walks in turn keep more of them under
/// way. On accels that stay in the caches the extra walks only cost their
/// bookkeeping.
const MANY_LANES: usize = 16;

/// See [`MANY_LANES`]: well past what a core's caches hold.
const MANY_LANES_BYTES: usize = 8 << 20;

/// The deepest traversal stack a walk holds (a power of two): enough for
/// trees of up to 35 levels (see `Bvh::stack_len`). Deeper trees are
/// walked one ray at a time.
pub(in crate::query) const STACK: usize = 256;

/// Accels at least this large (about the size of a core's L2 cache) are
/// walked asking ahead for memory; smaller ones stay in cache, where the
/// requests only cost instructions.
const ASK_AHEAD_BYTES: usize = 1 << 20;

/// The bytes of a node: four cache lines...
const NODE_BYTES: usize = size_of::<Node8>();
/// ...and of a leaf packet: three.
const PACKET_BYTES: usize = size_of::<TriPacket>();
const _: () = assert!(NODE_BYTES == 256 && PACKET_BYTES == 192 && LANES <= MANY_LANES);

/// One ray's walk in progress.
struct Walk {
    /// Index of the ray in the batch.
    ray: usize,
    /// The ray with its direction scaled by a power of two
    /// ([`unit_scaled`]), and the factor back to the caller's `t`.
    scaled: Ray,
    t_scale: TScale,
    rays_box: RayBox,
    /// The ray as the leaves' miss filter sees it.
    packet_ray: PacketRay,
    best: Option<Nearest>,
    /// The best crossing's `t` (`+∞` before any).
    t_limit: f64,
    /// `t_limit` as the slab tests see it ([`RayBox::limit`]).
    limit: f32,
    /// `limit` as the stack's culling sees it ([`limit_key`]).
    limit_key: u32,
    /// The leaf filtered by the last step: its first triangle and the mask
    /// of its triangles still to decide (requested from memory).
    pending: (u32, u32),
    /// Children still to visit, nearest on top; `stack[..top]` is live,
    /// `top ≤ accel.bvh.stack_len() ≤ STACK`, and a node opening writes at most
    /// `WIDTH` entries from `top` on. Indices are taken modulo `STACK`
    /// (which changes none of them) so that no access needs a bounds check.
    stack: [Deferred; STACK + WIDTH],
    top: usize,
}

/// The memory of one worker's interleaved walks, kept from one chunk of
/// rays to the next (a walk's stack is 2 KiB; making and clearing eight of
/// them for every chunk of 512 rays cost 65 instructions per ray).
pub(in crate::query) struct WalkScratch {
    walks: Vec<Walk>,
    /// Each ray's best crossing, `t` already in the caller's units.
    best: Vec<BestHit>,
}

impl WalkScratch {
    /// Scratch memory for walks of up to `rays` rays a chunk.
    pub(in crate::query) fn new(rays: usize) -> WalkScratch {
        WalkScratch {
            walks: (0..MANY_LANES).map(|_| Walk::idle()).collect(),
            best: Vec::with_capacity(rays),
        }
    }
}

impl Walk {
    /// A walk with nothing to do (the next [`Walk::start`] gives it a ray).
    fn idle() -> Walk {
        let ray = Ray::new(glam::DVec3::ZERO, glam::DVec3::X);
        let frame = BoxFrame {
            centre: glam::DVec3::ZERO,
            scale: 1.0,
        };
        Walk {
            ray: 0,
            scaled: ray,
            t_scale: TScale::ONE,
            rays_box: RayBox::new(&ray, &frame),
            packet_ray: PacketRay::new(&ray, frame.scale),
            best: None,
            t_limit: f64::INFINITY,
            limit: f32::INFINITY,
            limit_key: limit_key(f32::INFINITY),
            pending: (0, 0),
            stack: [Deferred::EMPTY; STACK + WIDTH],
            top: 0,
        }
    }

    /// Starts the walk of ray `index`, `r`, in place (the stack's memory is
    /// reused): the root is opened at once (it stays in cache). A ray whose
    /// direction [`unit_scaled`] would round (rare: a component below
    /// `2⁻¹⁰²²` of the largest) is answered here by the one-ray walk, which
    /// decides with the caller's direction ([`Accel::first_best`]); its walk
    /// is then over at its first step.
    #[inline(always)]
    fn start(&mut self, lanes: impl NodeLanes, index: usize, r: &Ray, accel: &Accel) {
        let (scaled, t_scale) = unit_scaled(r);
        self.ray = index;
        if !scales_exactly(r, &scaled, t_scale) {
            self.answer_alone(r, accel);
            return;
        }
        self.scaled = scaled;
        self.t_scale = t_scale;
        self.rays_box = RayBox::new(&scaled, accel.bvh.frame());
        self.packet_ray = PacketRay::new(&scaled, accel.bvh.frame().scale);
        self.best = None;
        self.t_limit = f64::INFINITY;
        self.limit = self.rays_box.limit(f64::INFINITY);
        self.limit_key = limit_key(self.limit);
        self.pending = (0, 0);
        self.top = accel
            .bvh
            .open_node(lanes, &self.rays_box, 0, self.limit, &mut self.stack, 0);
    }

    /// The answer for `r` by [`Accel::first_best`], left as this walk's
    /// best (in the caller's units: `t_scale` 1) with nothing to visit.
    #[cold]
    #[inline(never)]
    fn answer_alone(&mut self, r: &Ray, accel: &Accel) {
        // Final: nothing is compared with it any more.
        self.best = accel
            .first_best(r, &mut ())
            .map(|(t, triangle, sign)| Nearest {
                t,
                error: 0.0,
                triangle,
                sign,
            });
        self.t_scale = TScale::ONE;
        self.pending = (0, 0);
        self.top = 0;
    }
}

impl Accel {
    /// The first hits of `rays` (checked valid by the caller) into `out`,
    /// in order; every slot of `out` is written.
    /// Nodes are opened with AVX-512 or AVX2 where the processor has them
    /// (see `spatial::bvh::open`).
    pub(in crate::query) fn first_hits_interleaved(
        &self,
        rays: &[Ray],
        out: &mut [Option<Crossing>],
        scratch: &mut WalkScratch,
    ) {
        with_widest_lanes(FirstHits {
            accel: self,
            rays,
            out,
            scratch,
        });
    }

    /// [`Accel::first_hits_interleaved`] with nodes opened by `lanes`.
    #[inline(always)]
    pub(in crate::query) fn first_hits_with(
        &self,
        lanes: impl NodeLanes,
        rays: &[Ray],
        out: &mut [Option<Crossing>],
        scratch: &mut WalkScratch,
    ) {
        if self.bvh.stack_len() > STACK {
            for (o, r) in out.iter_mut().zip(rays) {
                *o = self.first_hit_unchecked(r);
            }
        } else if self.stats.memory_bytes >= MANY_LANES_BYTES {
            self.walk_interleaved::<true, MANY_LANES>(lanes, rays, out, scratch);
        } else if self.stats.memory_bytes >= ASK_AHEAD_BYTES {
            self.walk_interleaved::<true, LANES>(lanes, rays, out, scratch);
        } else {
            self.walk_interleaved::<false, LANES>(lanes, rays, out, scratch);
        }
    }

    /// [`Accel::first_hits_interleaved`], `N` walks in turn (at most
    /// [`MANY_LANES`]), each step asking for the next step's memory when
    /// `ASK_AHEAD`.
    #[inline(always)]
    fn walk_interleaved<const ASK_AHEAD: bool, const N: usize>(
        &self,
        lanes: impl NodeLanes,
        rays: &[Ray],
        out: &mut [Option<Crossing>],
        scratch: &mut WalkScratch,
    ) {
        debug_assert_eq!(rays.len(), out.len());
        // Each ray's best crossing; its face is looked up after all walks,
        // where the lookups (a cache miss each on large meshes) overlap
        // instead of stalling the walks.
        let WalkScratch { walks, best } = scratch;
        best.clear();
        best.resize(rays.len(), None);
        let started = rays.len().min(N);
        for (k, w) in walks.iter_mut().enumerate().take(started) {
            w.start(lanes, k, &rays[k], self);
        }
        // The walks under way are `walks[order[..live]]`, taken in turn.
        let mut order: [usize; N] = std::array::from_fn(|k| k);
        let (mut fed, mut live, mut k) = (started, started, 0);
        while live > 0 {
            if k >= live {
                k = 0;
            }
            let w = &mut walks[order[k]];
            if self.step::<ASK_AHEAD>(lanes, w) {
                best[w.ray] = w.best.map(|n| {
                    let t = self.accurate_t(&w.scaled, n.triangle, n.t, n.error);
                    (unscaled_t(t, w.t_scale), n.triangle, n.sign)
                });
                if fed < rays.len() {
                    w.start(lanes, fed, &rays[fed], self);
                    fed += 1;
                } else {
                    live -= 1;
                    order.swap(k, live);
                    continue;
                }
            }
            k += 1;
        }
        for (o, b) in out.iter_mut().zip(best.iter()) {
            *o = b.map(|(t, i, s)| self.crossing(t, i, s));
        }
    }

    /// One step of a walk: decide exactly the triangles the previous step's
    /// filter left undecided, then take the nearest child still in reach
    /// off the stack: filter a leaf (requesting its undecided triangles
    /// from memory for the next step), or open a node. Either way, the
    /// child then on top is requested from memory for the next step. (The
    /// requests only when `ASK_AHEAD`.) Returns whether the walk is over.
    #[inline(always)]
    fn step<const ASK_AHEAD: bool>(&self, lanes: impl NodeLanes, w: &mut Walk) -> bool {
        let (first, mut undecided) = w.pending;
        w.pending.1 = 0;
        while undecided != 0 {
            let i = first + undecided.trailing_zeros();
            undecided &= undecided - 1;
            let t_new =
                self.consider_for_first_hit(&w.scaled, &w.scaled, i, &mut w.best, w.t_limit);
            if t_new != w.t_limit {
                w.t_limit = t_new;
                w.limit = w.rays_box.limit(t_new);
                w.limit_key = limit_key(w.limit);
            }
        }
        let child = loop {
            if w.top == 0 {
                return true;
            }
            w.top -= 1;
            if let Some(child) = w.stack[w.top % STACK].reached(w.limit_key) {
                break child;
            }
        };
        if child & LEAF != 0 {
            let packet = &self.packets[(child & !LEAF) as usize];
            let undecided = packet.undecided(&w.packet_ray);
            // The first undecided triangle (rarely more than one) is asked
            // for without a branch; with none, the packet itself (already in
            // cache), so that no memory is fetched for nothing.
            if ASK_AHEAD {
                let first = packet.first as usize + undecided.trailing_zeros() as usize;
                let tri = self.tris.as_ptr().wrapping_add(first).cast::<u8>();
                let start = std::hint::select_unpredictable(
                    undecided != 0,
                    tri,
                    std::ptr::from_ref(packet).cast::<u8>(),
                );
                prefetch_bytes(start, size_of::<YzTri>() - 1);
            }
            w.pending = (packet.first, undecided);
        } else {
            let sp = w.top % STACK;
            w.top = self
                .bvh
                .open_node(lanes, &w.rays_box, child, w.limit, &mut w.stack, sp);
        }
        if ASK_AHEAD && w.top > 0 {
            let next = w.stack[(w.top - 1) % STACK].child;
            // A node or a packet: the address is selected without a branch
            // (which kind comes next is not predictable). A node's four
            // lines are asked for; a packet's three, then its first again
            // (a line already on its way, not the next packet's).
            let index = (next & !LEAF) as usize;
            let packet = self.packets.as_ptr().wrapping_add(index).cast::<u8>();
            let node = self.bvh.nodes().as_ptr().wrapping_add(index).cast::<u8>();
            let is_packet = next & LEAF != 0;
            let start = std::hint::select_unpredictable(is_packet, packet, node);
            prefetch_bytes(start, PACKET_BYTES - 1);
            let last = std::hint::select_unpredictable(is_packet, 0, NODE_BYTES - 1);
            prefetch_bytes(start.wrapping_add(last), 0);
        }
        false
    }
}

/// The first hits of a stream of rays, as work for [`with_widest_lanes`].
struct FirstHits<'a> {
    accel: &'a Accel,
    rays: &'a [Ray],
    out: &'a mut [Option<Crossing>],
    scratch: &'a mut WalkScratch,
}

impl LanesJob for FirstHits<'_> {
    type Output = ();

    #[inline(always)]
    fn run(self, lanes: impl NodeLanes) {
        self.accel
            .first_hits_with(lanes, self.rays, self.out, self.scratch);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;
    use crate::query::ray_solid::tests::rays_towards_the_centre;
    use crate::spatial::bvh::for_each_lanes;

    /// Every form of the interleaved walk (asking ahead or not, 8 or 16
    /// walks in turn) answers each ray as the one-ray walk does, whatever
    /// the accel's size would choose: rays from all around a sphere, over
    /// more rays than walks and a partial last round.
    #[test]
    fn every_form_of_the_walk_answers_as_the_one_ray_walk() {
        let accel = Accel::new(&builders::sphere(24));
        let rays = rays_towards_the_centre(0x4A7C_15D2_6E3B_90F1, 1_000, 0.3);
        let want: Vec<Option<Crossing>> =
            rays.iter().map(|r| accel.first_hit(r).unwrap()).collect();
        let hits = want.iter().filter(|h| h.is_some()).count();
        assert!(hits > rays.len() / 2, "{hits} of {}", rays.len());
        let mut scratch = WalkScratch::new(rays.len());
        let mut forms = 0;
        macro_rules! check {
            ($lanes:expr, $ask:literal, $n:expr) => {
                for count in [rays.len(), 5, 1] {
                    let mut out = vec![None; count];
                    accel.walk_interleaved::<$ask, { $n }>(
                        $lanes,
                        &rays[..count],
                        &mut out,
                        &mut scratch,
                    );
                    assert_eq!(out, want[..count]);
                }
                forms += 1;
            };
        }
        for_each_lanes!(|lanes| {
            check!(lanes, false, LANES);
            check!(lanes, true, LANES);
            check!(lanes, true, MANY_LANES);
        });
        assert!(forms >= 3);
    }
}
