//! Rays through a tree: spans, first hits, normals.

use crate::SetOp;
use std::cmp::Ordering;

use glam::DVec3;

use super::crossing_order::{certain_order, compare_exactly};
use super::merge::{Hit, merge_by, oriented_normal};
use super::stats::counting_fallbacks;
use super::tree::{NodeIndex, NodeKind};
use super::{Crossing, Csg, LeafId, Stats, SurfaceId};
use crate::geom::{Aabb, Ray};
use crate::query::QueryError;

/// The answer of a tree to a ray: Roth's `(INOUT_C, t_C1, t_C2, …)` (Roth 1982).
///
/// # Invariants
///
/// `hits` is strictly ascending with every `t > 0`; the ray is inside the
/// solid on `(0, t₁)` iff `origin_inside`, and every hit toggles that.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Spans {
    /// Whether the ray is inside just after its origin.
    pub origin_inside: bool,
    /// Where the ray crosses the boundary of the combined solid.
    pub hits: Vec<Hit>,
}

impl Spans {
    /// The intervals of `t` inside the solid, as `(start, end)`; a span
    /// starting at the origin starts at 0 and one that never ends ends at
    /// `f64::INFINITY`.
    #[must_use]
    pub fn intervals(&self) -> Vec<(f64, f64)> {
        let mut ts: Vec<f64> = Vec::with_capacity(self.hits.len() + 2);
        if self.origin_inside {
            ts.push(0.0);
        }
        ts.extend(self.hits.iter().map(|h| h.t));
        if ts.len() % 2 == 1 {
            ts.push(f64::INFINITY);
        }
        ts.chunks_exact(2).map(|p| (p[0], p[1])).collect()
    }

    /// The total length of the spans in units of `t` (infinite for an
    /// unbounded span).
    #[must_use]
    pub fn total_length(&self) -> f64 {
        self.intervals().iter().map(|(a, b)| b - a).sum()
    }
}

/// The first place a ray meets the boundary of the combined solid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FirstHit {
    /// The ray parameter.
    pub t: f64,
    /// The point `origin + t · direction` (rounded).
    pub point: DVec3,
    /// The leaf whose surface it is.
    pub leaf: LeafId,
    /// Which surface of that leaf.
    pub surface: SurfaceId,
    /// Whether the ray enters the solid there (it leaves when it started
    /// inside).
    pub entering: bool,
}

/// Reusable buffers for one thread's traversals.
#[derive(Default)]
struct Scratch {
    pool: Vec<Vec<Hit>>,
    leaf: Vec<Crossing>,
}

impl Scratch {
    fn take(&mut self) -> Vec<Hit> {
        let mut v = self.pool.pop().unwrap_or_default();
        v.clear();
        v
    }
}

/// Relative allowance for rounding in the bounds test: the slab parameters
/// of a box are each rounded once (a difference and a quotient: `2 ε`), so
/// comparing two of them can be off by `4 ε` of their size. Culling accepts
/// rays within that margin so that it never drops a real crossing.
const SLAB_ROUNDING: f64 = 4.0 * f64::EPSILON;

/// Whether the ray `[0, ∞)` may touch the closed box (conservatively).
pub(crate) fn ray_meets_bounds(bounds: &Aabb, ray: &Ray) -> bool {
    if bounds.is_empty() {
        return false;
    }
    let (mut near, mut far) = (0.0_f64, f64::INFINITY);
    for axis in 0..3 {
        let (e, d) = (ray.origin[axis], ray.direction[axis]);
        let (lo, hi) = (bounds.min[axis], bounds.max[axis]);
        if d == 0.0 {
            if e < lo || e > hi {
                return false;
            }
            continue;
        }
        let (t0, t1) = ((lo - e) / d, (hi - e) / d);
        let (t0, t1) = if t0 <= t1 { (t0, t1) } else { (t1, t0) };
        near = near.max(t0);
        far = far.min(t1);
    }
    near <= far + SLAB_ROUNDING * near.abs().max(far.abs())
}

/// How far (in multiples of a finite scene's size) a user's ray may start
/// from the scene's bounds. Beyond it, `t` at the scene is so large that its
/// rounding (`2^-52` of `t`) exceeds `2^-22` of the scene's size, and spans
/// thinner than that would merge; such rays are refused, not answered wrong.
pub const MAX_ORIGIN_DISTANCE: f64 = (1u64 << 30) as f64;

/// `x · 2^k`, exactly whenever the result is a normal number or zero.
fn times_power_of_two(mut x: f64, mut k: i32) -> f64 {
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        x *= f64::powi(2.0, step);
        k -= step;
    }
    x
}

/// A user's ray made ready for a trace: the direction `d` scaled to
/// `d' = d · 2^-k`, `k` the exponent of its largest component, so that
/// component lies in `[1, 2)` (exact: the line and the order of crossings
/// do not change). The scaled ray's `t'` is the caller's `t · 2^k`, so
/// `t = t' · 2^-k`.
///
/// # Errors
///
/// [`QueryError::InvalidRay`] for a non-finite origin or direction or a
/// zero direction; [`QueryError::RayOutOfRange`] when the origin lies more
/// than [`MAX_ORIGIN_DISTANCE`] scene sizes from finite scene bounds that
/// the ray meets.
fn conditioned(bounds: &Aabb, index: usize, ray: &Ray) -> Result<(Ray, i32), QueryError> {
    let Ray { origin, direction } = *ray;
    if !ray.is_valid() {
        return Err(QueryError::InvalidRay {
            index,
            origin,
            direction,
        });
    }
    let largest = direction.abs().max_element();
    // The exponent of the largest component (subnormals included).
    let k = largest.log2().floor() as i32;
    let scaled = Ray::new(
        origin,
        DVec3::new(
            times_power_of_two(direction.x, -k),
            times_power_of_two(direction.y, -k),
            times_power_of_two(direction.z, -k),
        ),
    );
    if !bounds.is_empty() && bounds.min.is_finite() && bounds.max.is_finite() {
        let size = bounds.size().max_element();
        let gap = (bounds.min - origin)
            .max(origin - bounds.max)
            .max(DVec3::ZERO);
        let distance = gap.max_element();
        if distance > MAX_ORIGIN_DISTANCE * size && ray_meets_bounds(bounds, &scaled) {
            return Err(QueryError::RayOutOfRange {
                index,
                origin,
                direction,
                reason: "the origin is more than 2^30 scene sizes from the scene, so t could not \
                         tell its features apart; start the ray nearer",
            });
        }
    }
    Ok((scaled, k))
}

/// Turns the scaled ray's crossings back into the caller's `t = t' · 2^-k`,
/// checking that they stay finite, positive and strictly ascending.
fn unscaled(hits: &mut [Hit], k: i32, index: usize, ray: &Ray) -> Result<(), QueryError> {
    let mut previous = 0.0;
    for hit in hits.iter_mut() {
        hit.t = times_power_of_two(hit.t, -k);
        if !hit.t.is_finite() || hit.t <= previous {
            return Err(QueryError::RayOutOfRange {
                index,
                origin: ray.origin,
                direction: ray.direction,
                reason: if hit.t.is_finite() {
                    "the direction is so long that crossings' t underflow together"
                } else {
                    "the direction is so short that a crossing's t overflows"
                },
            });
        }
        previous = hit.t;
    }
    Ok(())
}

impl Csg {
    /// The in/out spans of a ray through the whole solid.
    ///
    /// A ray whose direction is zero or not finite gets an empty answer
    /// (check [`Ray::is_valid`] to tell).
    pub fn spans(&self, ray: &Ray, stats: &mut Stats) -> Spans {
        let mut out = Vec::new();
        let origin_inside = self.trace(ray, None, stats, &mut out);
        Spans {
            origin_inside,
            hits: out,
        }
    }

    /// [`Csg::spans`] for rays from users: an invalid ray is an error, not
    /// an empty answer, and so is one whose answer `f64` cannot hold.
    ///
    /// The direction is first scaled exactly by a power of two (its largest
    /// component into `[1, 2)`) and the crossings' `t` scaled back, so a
    /// direction of any finite non-zero length gives the same crossings,
    /// in units of the caller's direction, as long as those `t` are normal
    /// `f64` numbers. An origin may lie up to [`MAX_ORIGIN_DISTANCE`] scene
    /// sizes from the scene's (finite) bounds.
    ///
    /// # Errors
    ///
    /// [`QueryError::InvalidRay`] (index 0) for a non-finite origin or
    /// direction or a zero direction; [`QueryError::RayOutOfRange`] for an
    /// origin farther than that from a scene the ray meets, or a crossing's
    /// `t` that overflows (or underflows into its neighbour).
    pub fn try_spans(&self, ray: &Ray, stats: &mut Stats) -> Result<Spans, QueryError> {
        self.try_spans_at(0, ray, stats)
    }

    /// [`Csg::try_spans`] for the ray at `index` of a batch (the index the
    /// error names).
    ///
    /// # Errors
    ///
    /// As [`Csg::try_spans`].
    pub fn try_spans_at(
        &self,
        index: usize,
        ray: &Ray,
        stats: &mut Stats,
    ) -> Result<Spans, QueryError> {
        let (scaled, k) = conditioned(&self.bounds(), index, ray)?;
        let mut spans = self.spans(&scaled, stats);
        unscaled(&mut spans.hits, k, index, ray)?;
        Ok(spans)
    }

    /// The first boundary crossing along the ray, or `None` when the ray
    /// never meets the boundary (or is not valid: see [`Csg::try_first_hit`]).
    /// The root merge stops at the first crossing; no normal is computed (see
    /// [`Csg::hit_normal`]).
    pub fn first_hit(&self, ray: &Ray, stats: &mut Stats) -> Option<FirstHit> {
        let mut out = Vec::new();
        let inside = self.trace(ray, Some(1), stats, &mut out);
        out.first().map(|h| FirstHit {
            t: h.t,
            point: ray.at(h.t),
            leaf: h.leaf,
            surface: h.surface,
            entering: !inside,
        })
    }

    /// [`Csg::first_hit`] for rays from users: an invalid ray is an error,
    /// not a miss.
    ///
    /// # Errors
    ///
    /// As for [`Csg::try_spans`].
    pub fn try_first_hit(
        &self,
        ray: &Ray,
        stats: &mut Stats,
    ) -> Result<Option<FirstHit>, QueryError> {
        self.try_first_hit_at(0, ray, stats)
    }

    /// [`Csg::try_first_hit`] for the ray at `index` of a batch (the index
    /// the error names).
    ///
    /// # Errors
    ///
    /// As for [`Csg::try_spans`].
    pub fn try_first_hit_at(
        &self,
        index: usize,
        ray: &Ray,
        stats: &mut Stats,
    ) -> Result<Option<FirstHit>, QueryError> {
        let (scaled, k) = conditioned(&self.bounds(), index, ray)?;
        let Some(hit) = self.first_hit(&scaled, stats) else {
            return Ok(None);
        };
        let mut hits = [Hit {
            t: hit.t,
            spread: 0.0,
            leaf: hit.leaf,
            surface: hit.surface,
        }];
        unscaled(&mut hits, k, 0, ray)?;
        Ok(Some(FirstHit {
            t: hits[0].t,
            ..hit
        }))
    }

    /// The unit outward normal of the combined solid at a first hit: the
    /// leaf's normal, turned to face the ray where it enters (so a hit on
    /// B's surface in `A − B` points into B). Counted in `stats.normals`.
    pub fn hit_normal(&self, ray: &Ray, hit: &FirstHit, stats: &mut Stats) -> DVec3 {
        stats.normals += 1;
        let Some(leaf) = self.leaf(hit.leaf) else {
            return -ray.direction.normalize_or_zero();
        };
        let n = leaf
            .primitive
            .normal(hit.point, hit.surface)
            .normalize_or_zero();
        oriented_normal(n, ray.direction, hit.entering)
    }

    /// Whether the segment of the ray `(0, t_max)` meets the solid's
    /// boundary: the shadow test. Counted in `stats.shadow_rays`.
    pub fn occluded(&self, ray: &Ray, t_max: f64, stats: &mut Stats) -> bool {
        stats.shadow_rays += 1;
        match self.first_hit(ray, stats) {
            Some(hit) => hit.t < t_max,
            None => false,
        }
    }

    fn trace(
        &self,
        ray: &Ray,
        limit: Option<usize>,
        stats: &mut Stats,
        out: &mut Vec<Hit>,
    ) -> bool {
        stats.rays += 1;
        if !ray.is_valid() {
            return false;
        }
        SCRATCH.with(|cell| {
            let mut scratch = cell.take();
            let inside = counting_fallbacks(stats, |stats| {
                self.trace_node(self.root, ray, limit, &mut scratch, stats, out)
            });
            cell.set(scratch);
            inside
        })
    }

    fn trace_node(
        &self,
        node: NodeIndex,
        ray: &Ray,
        limit: Option<usize>,
        scratch: &mut Scratch,
        stats: &mut Stats,
        out: &mut Vec<Hit>,
    ) -> bool {
        let n = &self.nodes[node];
        stats.bounds_tests += 1;
        if !ray_meets_bounds(&n.bounds, ray) {
            stats.culled_subtrees += 1;
            return false;
        }
        match n.kind {
            NodeKind::Leaf(id) => {
                stats.primitive_ray_tests += 1;
                scratch.leaf.clear();
                let primitive = &self.leaves[id.0 as usize].primitive;
                let inside = primitive.intersect_ray(ray, &mut scratch.leaf, stats);
                let start = out.len();
                out.extend(scratch.leaf.iter().map(|c| {
                    Hit {
                        t: c.t,
                        spread: primitive
                            .crossing_plane(c.surface)
                            .map_or(0.0, |plane| plane.spread(ray, c.t)),
                        leaf: id,
                        surface: c.surface,
                    }
                }));
                let mine = &mut out[start..];
                // The leaf's list in exact order (it is sorted by rounded t).
                for k in 1..mine.len() {
                    let mut m = k;
                    while m > 0
                        && self.order(ray, &mine[m - 1], &mine[m], stats) == Ordering::Greater
                    {
                        mine.swap(m - 1, m);
                        m -= 1;
                    }
                }
                let kept = drop_instants(mine, |x, y| self.order(ray, x, y, stats));
                out.truncate(start + kept.min(limit.unwrap_or(usize::MAX)));
                inside
            }
            NodeKind::Op { op, left, right } => {
                let mut a = scratch.take();
                let in_a = self.trace_node(left, ray, None, scratch, stats, &mut a);
                let left_decides = a.is_empty()
                    && match op {
                        SetOp::Union => in_a,
                        SetOp::Intersection | SetOp::Difference => !in_a,
                        SetOp::ReverseDifference => in_a,
                    };
                if left_decides {
                    stats.skipped_right_sides += 1;
                    scratch.pool.push(a);
                    // ∪ with A everywhere is everything; ∩, − and B − A
                    // here are empty.
                    return op == SetOp::Union;
                }
                let mut b = scratch.take();
                let in_b = self.trace_node(right, ray, None, scratch, stats, &mut b);
                let (inside, stopped) = merge_by(op, (in_a, &a), (in_b, &b), out, limit, |x, y| {
                    self.order(ray, x, y, stats)
                });
                if stopped {
                    stats.early_stops += 1;
                }
                scratch.pool.push(a);
                scratch.pool.push(b);
                inside
            }
        }
    }
}

impl Csg {
    /// The order of two hits along `ray`: by their rounded `t` when the gap
    /// exceeds both spreads, else exactly by the planes of the pieces
    /// crossed (counted in `stats.exact_orders`), else (curved surfaces)
    /// by the rounded `t`.
    #[inline(always)]
    fn order(&self, ray: &Ray, x: &Hit, y: &Hit, stats: &mut Stats) -> Ordering {
        match certain_order(x.t, x.spread, y.t, y.spread) {
            Some(order) => order,
            None => self.close_order(ray, x, y, stats),
        }
    }

    /// [`Csg::order`] of two hits within each other's spreads.
    #[cold]
    #[inline(never)]
    fn close_order(&self, ray: &Ray, x: &Hit, y: &Hit, stats: &mut Stats) -> Ordering {
        if x.leaf == y.leaf && x.surface == y.surface {
            return x.t.total_cmp(&y.t);
        }
        let plane = |h: &Hit| {
            self.leaves[h.leaf.0 as usize]
                .primitive
                .crossing_plane(h.surface)
        };
        if let (Some(p), Some(q)) = (plane(x), plane(y))
            && let Some(order) = compare_exactly(&p, &q, ray)
        {
            stats.exact_orders += 1;
            return order;
        }
        x.t.total_cmp(&y.t)
    }
}

/// Removes pairs of consecutive crossings at the same `t` (`Equal` by
/// `order`): a leaf may list two (a ray through a reflex edge of a
/// polyhedron, tangent to a sphere), an instant inside or outside that a
/// span list, strictly ascending, does not hold. Parity after each
/// remaining crossing is unchanged. Found by fuzzing the scene loader
/// (fixtures/fuzz/scene_load/). Returns how many are kept, at the front.
fn drop_instants(hits: &mut [Hit], mut order: impl FnMut(&Hit, &Hit) -> Ordering) -> usize {
    let mut kept = 0;
    let mut i = 0;
    while i < hits.len() {
        if i + 1 < hits.len() && order(&hits[i], &hits[i + 1]) == Ordering::Equal {
            i += 2;
        } else {
            hits[kept] = hits[i];
            kept += 1;
            i += 1;
        }
    }
    kept
}

thread_local! {
    static SCRATCH: std::cell::Cell<Scratch> = std::cell::Cell::new(Scratch::default());
}
