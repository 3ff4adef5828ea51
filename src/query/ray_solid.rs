//! Ray–solid crossings: what a CSG primitive answers for a ray.

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::{BVec4A, DVec3, Vec4};
use rayon::prelude::*;

use crate::geom::exact::{line_side_filter_scalar, triangle_edge_sides};
use crate::geom::polygon::coplanar_point_in_closed_triangle;
use crate::geom::{Ray, Sign, larger, line_side_sos, orient3d};
use crate::mesh::FaceId;

use super::accel::{BoxFrame, LEAF};
#[cfg(target_arch = "x86_64")]
use super::node_open::{Avx2, Avx512};
use super::node_open::{KEY_SLOT_BITS, NodeLanes, Portable};
use super::ray_stream::WalkScratch;
use super::tri_packet::PacketRay;
use super::{Accel, Containment, QueryError};

/// Whether the ray enters or leaves the solid at a crossing.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Transition {
    /// The ray goes from outside to inside (against the face's outward
    /// normal).
    Enter,
    /// The ray goes from inside to outside (along the outward normal).
    Exit,
}

/// One crossing of a ray with a solid's boundary.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Crossing {
    /// The ray parameter, `origin + t · direction`; a rounded construction,
    /// always `> 0`.
    pub t: f64,
    /// The face crossed (for a ray through an edge or a vertex: the one face
    /// the perturbed ray crosses).
    pub face: FaceId,
    /// Entering or leaving, decided exactly (from the face's orientation).
    pub transition: Transition,
}

/// A ray's answer from one solid: whether its origin is inside, and where it
/// crosses the boundary.
///
/// # Invariants
///
/// `hits` is sorted by ascending `t`, every `t > 0`; crossings with equal
/// rounded `t` (a ray grazing a vertex or an edge) are listed in the order the
/// perturbed ray meets them. On a valid closed solid
/// the transitions alternate, starting with `Exit` when `origin` is
/// `Inside` and `Enter` when it is `Outside`; the list ends with an `Exit`
/// (the ray ends outside). When `origin` is `OnBoundary`, crossings at the
/// origin itself are not listed, and the first transition tells whether the
/// ray runs inside (`Exit` first) or outside (`Enter` first) just after
/// leaving the origin.
#[derive(Clone, Debug, PartialEq)]
pub struct RayCrossings {
    /// Where the ray's origin is.
    pub origin: Containment,
    /// The crossings with `t > 0`, ascending.
    pub hits: Vec<Crossing>,
}

/// What one ray's traversal touched: the work counts behind its time, so
/// that culling can be checked by counting rather than by timing.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraversalStats {
    /// BVH nodes whose child boxes were tested.
    pub nodes: u64,
    /// Triangles the ray was tested against (by the leaves' `f32` miss
    /// filter).
    pub triangles: u64,
    /// Of those, the triangles the filter could not prove missed, which
    /// went on to the exact test.
    pub exact_tests: u64,
}

/// Where a traversal reports its work: nowhere (the queries) or into a
/// [`TraversalStats`] (the traced forms).
pub(super) trait Tally {
    fn node(&mut self);
    fn triangle(&mut self);
    fn exact_test(&mut self);
}

impl Tally for () {
    #[inline(always)]
    fn node(&mut self) {}
    #[inline(always)]
    fn triangle(&mut self) {}
    #[inline(always)]
    fn exact_test(&mut self) {}
}

impl Tally for TraversalStats {
    #[inline(always)]
    fn node(&mut self) {
        self.nodes += 1;
    }
    #[inline(always)]
    fn triangle(&mut self) {
        self.triangles += 1;
    }
    #[inline(always)]
    fn exact_test(&mut self) {
        self.exact_tests += 1;
    }
}

/// A ray as the `f32` slab tests of the BVH see it: in the accel's
/// [`BoxFrame`], with its parameter rescaled and every constant rounded so
/// that the tests can only err towards entering a box.
///
/// The ray's direction `d'` is already scaled by [`unit_scaled`] (largest
/// `|d'ₐ|` in `[1, 2)`). In the frame, the ray is `o' + s · d'` with
/// `o' = (o − centre) · scale` and `s = t · scale`: the same points, with
/// `s` a power-of-two multiple of `t`, so comparisons of `s` are
/// comparisons of `t`.
///
/// # Why the test is conservative
///
/// Per axis, the entry `(near − o')/d'ₐ` is computed from `f32` constants
/// chosen to make it smaller (the origin rounded away from the near plane,
/// `1/d'ₐ` rounded towards zero) and the exit `(far − o')/d'ₐ` from
/// constants making it larger (the origin rounded the other way, `1/d'ₐ`
/// rounded away from zero and grown by `1 + 2⁻²⁰`; the origin is widened by
/// `|f|·2⁻²² + 2⁻¹²⁶` around its `f32` value `f`, the reciprocals shrunk by
/// `1 − 2⁻²²` and grown by `1 + 2⁻¹⁹`, which cover their own roundings).
/// The two `f32` roundings
/// of the subtraction and the product change each by a factor within
/// `(1 ± u)²`, `u = 2⁻²⁴`; as `(1 + u)² < (1 + 2⁻²⁰)(1 − u)²`, a box the
/// exact ray enters at `s₀ ≤ s₁` has computed entry ≤ computed exit, and a
/// computed entry at most `(1 + u)² s₀`. Signs survive rounding, so boxes
/// behind the origin stay behind. A zero direction component gives `1/0 =
/// ±∞` exactly (the slab then holds the origin or not, as the exact test
/// says; `0 · ∞ = NaN` when the origin is on the slab plane leaves the bound
/// unchanged). The limit a box is compared with is the current best `t`
/// grown by the same `2⁻²⁰`, which covers both the entry's rounding and the
/// `f64` rounding of the best `t` itself.
pub(super) struct RayBox {
    /// The origin in the frame, rounded (per axis) away from the near
    /// planes: used for entries. (Lane 3 of this and the next three
    /// arrays is unused.)
    pub o_near: [f32; 4],
    /// The origin in the frame, rounded towards the near planes: used for
    /// exits.
    pub o_far: [f32; 4],
    /// `1/d'ₐ` rounded towards zero (exactly `±∞` when `d'ₐ = 0`).
    pub inv_near: [f32; 4],
    /// `1/d'ₐ · (1 + 2⁻²⁰)` rounded away from zero.
    pub inv_far: [f32; 4],
    /// Per axis, the row of [`Node8::bounds`](super::accel::Node8::bounds) holding the near planes
    /// (lower bounds when the ray runs up the axis).
    pub near_row: [Row; 3],
    /// Per axis, the row holding the far planes.
    pub far_row: [Row; 3],
    /// `scale`: the factor from `t` to `s`.
    t_to_s: f64,
    /// The octant of the direction: bit `a` set when it runs down axis `a`
    /// (see [`Node8::order`](super::accel::Node8::order)).
    pub octant: usize,
}

/// `2⁻²²`: the relative widening of the origin (see [`RayBox`]).
const ORIGIN_WIDEN: f32 = 1.0 / (1u32 << 22) as f32;
/// `1 − 2⁻²²`: `1/d'ₐ` rounded to `f32` (relative error at most 2⁻²⁴, plus
/// 2⁻⁵³ from `f64`) times this, rounded, is below the exact reciprocal.
const INV_SHRINK: f32 = 1.0 - ORIGIN_WIDEN;
/// `1 + 2⁻¹⁹`: `1/d'ₐ` rounded to `f32` times this, rounded, is at least
/// the exact reciprocal grown by the slab margin `1 + 2⁻²⁰`:
/// `(1 − 2⁻²⁴)² (1 + 2⁻¹⁹) > 1 + 2⁻²⁰`.
const INV_GROW: f32 = 1.0 + 2.0 / (1u32 << 20) as f32;

impl RayBox {
    /// The slab-test form of `ray`, whose direction is already scaled by
    /// [`unit_scaled`] (largest component in `[1, 2)`, so `d' = d`, `k = 0`).
    #[inline(always)]
    pub(super) fn new(ray: &Ray, frame: &BoxFrame) -> RayBox {
        let d = ray.direction;
        debug_assert!((1.0..2.0).contains(&d.abs().max_element()), "{d}");
        // The three axes side by side (lane 3 is unused). `d32` carries the
        // sign of each `dₐ`, −0 included (rounding to `f32` keeps it).
        let d32 = d.as_vec3().extend(1.0);
        // The origin in the frame, rounded to `f32`, widened by
        // `|f|·2⁻²² + 2⁻¹²⁶` either way (see `RayBox`): covers the rounding
        // to `f32` (at most `|f|·2⁻²⁴`, or 2⁻¹⁵⁰ below the normal range),
        // the `f64` rounding of `o` and the rounding of the widening itself.
        // Beyond the `f32` range: no constraint at all. Going down the axis
        // (`d'ₐ` negative, or −0), the ray enters through the upper plane:
        // `(upper − o) · (−|inv|)` is smallest for the smallest origin, so
        // the near origin is `f − m` and the far one `f + m` (the widening
        // takes the sign of `dₐ`: no branch on the signs of random
        // directions, which are not predictable).
        let f = ((ray.origin - frame.centre) * frame.scale)
            .as_vec3()
            .extend(0.0);
        let widen = (f.abs() * ORIGIN_WIDEN + Vec4::splat(f32::MIN_POSITIVE)).copysign(d32);
        let unbounded = Vec4::INFINITY.copysign(d32);
        let finite = f.is_finite_mask();
        let o_near = Vec4::select(finite, f + widen, unbounded);
        let o_far = Vec4::select(finite, f - widen, -unbounded);
        // `1/|dₐ|` rounded to `f32`, shrunk and grown (see the constants);
        // exactly `+∞` for a zero component. Then the sign of `dₐ`.
        let recip = (DVec3::ONE / d.abs()).as_vec3().extend(1.0);
        let zero = d.cmpeq(DVec3::ZERO);
        let zero = BVec4A::new(zero.x, zero.y, zero.z, false);
        let inv_lo = Vec4::select(
            zero,
            Vec4::INFINITY,
            (recip * INV_SHRINK).min(Vec4::splat(f32::MAX)),
        );
        let inv_hi = Vec4::select(zero, Vec4::INFINITY, recip * INV_GROW);
        let down = d32.is_negative_bitmask();
        RayBox {
            o_near: o_near.to_array(),
            o_far: o_far.to_array(),
            inv_near: inv_lo.copysign(d32).to_array(),
            inv_far: inv_hi.copysign(d32).to_array(),
            near_row: [0, 1, 2].map(|a| Row::of(a, down >> a & 1 == 1)),
            far_row: [0, 1, 2].map(|a| Row::of(a, down >> a & 1 == 0)),
            t_to_s: frame.scale,
            octant: (down & 7) as usize,
        }
    }

    /// The limit in `s` for a best crossing at `t` (grown by the margin,
    /// rounded up; `+∞` for none).
    #[inline]
    pub(super) fn limit(&self, t: f64) -> f32 {
        // `(x as f32) ≥ x (1 − 2⁻²⁴)` for normal `f32`; grown by 2⁻¹⁹ and
        // rounded it is at least `x (1 + 2⁻²⁰)`; `+ 2⁻¹²⁶` covers `x` below
        // the normal range. `+∞` stays `+∞`.
        ((t * self.t_to_s) as f32) * INV_GROW + f32::MIN_POSITIVE
    }
}

/// A row of [`Node8::bounds`](super::accel::Node8::bounds): the lower
/// (`Lower*`) or upper (`Upper*`) bounds of the children along one axis.
/// An enum rather than an index, so that a row is always in range (the
/// slab tests index the rows without a bounds check).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u8)]
pub(super) enum Row {
    /// Lower bounds along `x`.
    LowerX = 0,
    /// Lower bounds along `y`.
    LowerY = 1,
    /// Lower bounds along `z`.
    LowerZ = 2,
    /// Upper bounds along `x`.
    UpperX = 3,
    /// Upper bounds along `y`.
    UpperY = 4,
    /// Upper bounds along `z`.
    UpperZ = 5,
}

impl Row {
    /// The row of the bounds along axis `a` (0, 1 or 2): the upper ones
    /// when `upper`.
    #[inline(always)]
    fn of(a: usize, upper: bool) -> Row {
        match (a, upper) {
            (0, false) => Row::LowerX,
            (1, false) => Row::LowerY,
            (2, false) => Row::LowerZ,
            (0, true) => Row::UpperX,
            (1, true) => Row::UpperY,
            _ => Row::UpperZ,
        }
    }

    /// The row's index into [`Node8::bounds`](super::accel::Node8::bounds).
    #[inline(always)]
    pub(super) fn index(self) -> usize {
        self as usize
    }
}

/// The best crossing of a first-hit query so far: rounded `t`, triangle,
/// and the sign of its crossing (`+` for an exit).
pub(super) type BestHit = Option<(f64, u32, Sign)>;

/// The same ray with its direction multiplied by a power of two so that its
/// largest component lies in `[1, 2)`, and the factor that turns its
/// parameters back into the caller's: the half-line `t > 0` does not
/// change, only the unit of `t`, and the slab tests and crossing parameters
/// see directions of one size (a direction of `1e308` or `5e-324` overflowed
/// or underflowed them; found by the queries fuzz check).
///
/// Scaling down can round a component far smaller than the largest (a
/// direction `(64, 0, 2⁻¹⁰⁶⁹)` loses its `z`): then the scaled ray is a
/// different line, good for the conservative box tests and for `t` but not
/// for decisions. [`scales_exactly`] says which; where it does not, the
/// exact tests take the caller's ray (their signs do not depend on the
/// direction's length, symbolic perturbation included).
#[inline(always)]
pub(super) fn unit_scaled(ray: &Ray) -> (Ray, f64) {
    // A checked ray's direction is finite, never NaN.
    let d = ray.direction.abs();
    let largest = larger(larger(d.x, d.y), d.z);
    // `largest` is finite and non-zero (a checked ray): its binary exponent
    // `e` lies in −1074 ..= 1023; read from the bits for normal numbers.
    let biased = ((largest.to_bits() >> 52) & 0x7ff) as i32;
    let e = if biased == 0 {
        largest.log2().floor() as i32
    } else {
        biased - 1023
    };
    if e == 0 {
        // Already in `[1, 2)`: the common case of unit-scale directions.
        return (*ray, 1.0);
    }
    // 2^−e is applied in two exact halves, each a normal power of two.
    let (half, rest) = (-e / 2, -e - (-e / 2));
    let direction = ray.direction * pow2(half) * pow2(rest);
    // `origin + t · direction·f = origin + (t·f) · direction`: a parameter
    // along the scaled ray times `f` is the caller's parameter.
    let factor = pow2(half) * pow2(rest);
    (Ray::new(ray.origin, direction), factor)
}

/// Whether [`unit_scaled`] turned `ray` into `scaled` without rounding.
/// Scaling up (`factor ≥ 1`) never rounds: nothing ends above 2. Scaling
/// down rounded when scaling back by the inverse power of two (exact: the
/// scaled components are below 2) does not give the caller's direction.
#[inline(always)]
pub(super) fn scales_exactly(ray: &Ray, scaled: &Ray, factor: f64) -> bool {
    factor >= 1.0 || scaled.direction * (1.0 / factor) == ray.direction
}

/// `2⁻⁶⁰⁰`: below this denominator [`Accel::plane_t`]'s plain formula may
/// have lost `n` to underflow.
const PLANE_T_DENOMINATOR: f64 = pow2(-600);

/// [`Accel::plane_t`] for triangles or distances of extreme size: the
/// corners and origin are first scaled down by `2⁻⁶⁴` if any coordinate is
/// beyond `2¹⁰⁰⁰` (so that differences cannot overflow), then the edges and
/// `a − o` are each scaled by a power of two to a largest component in
/// `[1, 2)`, so that the cross product neither underflows nor overflows;
/// the powers of two are divided out of the quotient at the end (exactly,
/// unless the true `t` itself is beyond the `f64` range).
#[cold]
#[inline(never)]
fn plane_t_rescaled([a, b, c]: [DVec3; 3], ray: &Ray) -> f64 {
    let far = [a, b, c, ray.origin]
        .iter()
        .any(|p| p.abs().max_element() > pow2(1000));
    let pre = if far { pow2(-64) } else { 1.0 };
    let (a, b, c, o) = (a * pre, b * pre, c * pre, ray.origin * pre);
    // `v · 2^k` with its largest component in [1, 2), and `2^k`.
    let unit = |v: DVec3| {
        let m = v.abs().max_element();
        if m == 0.0 || !m.is_finite() {
            return (v, 1.0);
        }
        let k = (-m.log2().floor() as i32).clamp(-1022, 1022);
        (v * pow2(k), pow2(k))
    };
    let ((e1, _), (e2, _)) = (unit(b - a), unit(c - a));
    let (w, w_scale) = unit(a - o);
    let n = e1.cross(e2);
    // t = n·(a − o) / n·d, and (a − o) = w / w_scale / pre.
    n.dot(w) / n.dot(ray.direction) / w_scale / pre
}

/// `2^k` for `k` in −1022 ..= 1023 (a normal `f64`), built from its bits.
const fn pow2(k: i32) -> f64 {
    debug_assert!(-1022 <= k && k <= 1023);
    f64::from_bits(((k + 1023) as u64) << 52)
}

/// A parameter along the scaled direction of [`unit_scaled`] in units of the
/// caller's direction: monotone, and still `> 0` when it underflows.
pub(super) fn unscaled_t(t: f64, factor: f64) -> f64 {
    let t = t * factor;
    if t > 0.0 { t } else { f64::from_bits(1) }
}

/// How a ray meets one triangle.
enum TriHit {
    Miss,
    /// The origin lies on the triangle.
    Origin,
    /// A crossing in front of the origin; the sign is `+` for an exit.
    Cross(Sign),
}

impl Accel {
    /// The crossings of `ray` with the solid's boundary, and whether its
    /// origin is inside.
    ///
    /// Each triangle is tested with three exact [`line_side_sos`] signs on
    /// the ray's origin and direction (the ray crosses the triangle iff the
    /// three agree; their common sign says `Enter`/`Exit`) and one exact
    /// `orient3d` for "in front of the origin". Ties (the ray through an
    /// edge or vertex, or lying in a face's plane) are broken by the symbolic
    /// perturbation of [`line_side_sos`]: the ray is rotated by an
    /// infinitesimal angle and moved by an infinitely smaller distance, the
    /// same for every triangle, so each crossing counts exactly once and
    /// grazing gives 0 or 2 crossings. The exactness is with respect to the
    /// line `origin + t · direction` for real `t` with the given `f64`
    /// origin and direction. Triangles whose plane contains the origin are
    /// crossed at `t = 0` (or not at all) and are never listed.
    ///
    /// The origin's containment is parity of the listed crossings, or
    /// [`Containment::OnBoundary`] when it lies exactly on a triangle.
    ///
    /// # Errors
    ///
    /// [`QueryError::InvalidRay`] for a non-finite or zero-direction ray,
    /// [`QueryError::NotClosed`] for an open surface.
    pub fn ray_crossings(&self, ray: &Ray) -> Result<RayCrossings, QueryError> {
        self.check_ray(ray, 0)?;
        self.require_closed()?;
        let (scaled, t_scale) = unit_scaled(ray);
        // Decided with the caller's ray when the scaling rounded.
        let exact = scales_exactly(ray, &scaled, t_scale);
        let decide = if exact { &scaled } else { ray };
        let ray = &scaled;
        let mut on_boundary = false;
        let mut hits: Vec<(f64, u32, Sign)> = Vec::new();
        self.traverse(ray, exact, f64::INFINITY, &mut (), |i, _| {
            match self.hit_triangle::<true>(decide, i) {
                TriHit::Miss => {}
                TriHit::Origin => on_boundary = true,
                TriHit::Cross(s) => hits.push((self.t_of(ray, i), i, s)),
            }
            f64::INFINITY
        });
        hits.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        let winding: i32 = hits.iter().map(|h| h.2.as_i32()).sum();
        let origin = if on_boundary {
            Containment::OnBoundary
        } else if winding % 2 != 0 {
            Containment::Inside
        } else {
            Containment::Outside
        };
        let inside = match origin {
            Containment::Inside => true,
            Containment::Outside => false,
            Containment::OnBoundary => winding > 0,
        };
        alternate(&mut hits, inside);
        let hits = hits
            .into_iter()
            .map(|(t, i, s)| self.crossing(unscaled_t(t, t_scale), i, s))
            .collect();
        Ok(RayCrossings { origin, hits })
    }

    /// The first crossing of `ray` with the boundary (`t > 0`), or `None`.
    /// Decided as in [`Accel::ray_crossings`]; the nearest is chosen by the
    /// rounded `t` (ties by triangle order). Works on open surfaces too.
    ///
    /// # Errors
    ///
    /// [`QueryError::InvalidRay`] for a non-finite or zero-direction ray.
    pub fn first_hit(&self, ray: &Ray) -> Result<Option<Crossing>, QueryError> {
        self.check_ray(ray, 0)?;
        Ok(self.first_hit_unchecked(ray))
    }

    /// [`Accel::first_hit`] for every ray, in order, on all cores.
    ///
    /// # Errors
    ///
    /// The first invalid ray, by index.
    pub fn first_hit_batch(&self, rays: &[Ray]) -> Result<Vec<Option<Crossing>>, QueryError> {
        // Cast in input order: grouping rays that pass close to one another
        // (a 6-D Morton order of origin and direction, or a 3-D one of the
        // point nearest the solid's centre) cost more in sorting, copying
        // and unpermuting than it saved in cache misses — on 1M random rays
        // over the 1M-triangle sphere the 6-D order took 1.2–1.5× the time
        // of the input order on 2 threads (2026-11-21).
        //
        // Each worker checks a chunk of rays, then casts them a few at a
        // time, interleaved (see `ray_stream`), so that one ray's cache
        // misses overlap the others' work; the answers are written straight
        // into the result. One pass over the rays and one over the answers:
        // no separate checking pass, no initialisation of the result.
        let first_invalid = AtomicUsize::new(usize::MAX);
        let mut out: Vec<Option<Crossing>> = Vec::with_capacity(rays.len());
        out.spare_capacity_mut()[..rays.len()]
            .par_chunks_mut(STREAM_CHUNK)
            .zip(rays.par_chunks(STREAM_CHUNK))
            .enumerate()
            .for_each_init(
                || WalkScratch::new(STREAM_CHUNK),
                |scratch, (chunk, (o, r))| match r.iter().position(|r| !r.is_valid()) {
                    Some(k) => {
                        first_invalid.fetch_min(chunk * STREAM_CHUNK + k, Ordering::Relaxed);
                    }
                    None => self.first_hits_interleaved(r, o, scratch),
                },
            );
        let first_invalid = first_invalid.into_inner();
        if first_invalid != usize::MAX {
            return Err(invalid_ray(&rays[first_invalid], first_invalid));
        }
        // SAFETY: every chunk of slots was written: no chunk held an invalid
        // ray, and `first_hits_interleaved` writes each slot it is given.
        unsafe { out.set_len(rays.len()) };
        Ok(out)
    }

    /// [`Accel::ray_crossings`] for every ray, in order, on all cores.
    ///
    /// # Errors
    ///
    /// The first invalid ray by index, or [`QueryError::NotClosed`].
    pub fn ray_crossings_batch(&self, rays: &[Ray]) -> Result<Vec<RayCrossings>, QueryError> {
        check_rays(rays)?;
        self.require_closed()?;
        rays.par_iter()
            .with_min_len(256)
            .map(|r| self.ray_crossings(r))
            .collect()
    }

    /// [`Accel::first_hit`], with the work its traversal did.
    ///
    /// # Errors
    ///
    /// [`QueryError::InvalidRay`] for a non-finite or zero-direction ray.
    pub fn first_hit_traced(
        &self,
        ray: &Ray,
    ) -> Result<(Option<Crossing>, TraversalStats), QueryError> {
        self.check_ray(ray, 0)?;
        let mut stats = TraversalStats::default();
        let hit = self.first_hit_tallied(ray, &mut stats);
        Ok((hit, stats))
    }

    pub(super) fn first_hit_unchecked(&self, ray: &Ray) -> Option<Crossing> {
        self.first_hit_tallied(ray, &mut ())
    }

    #[inline(always)]
    fn first_hit_tallied(&self, ray: &Ray, tally: &mut impl Tally) -> Option<Crossing> {
        self.first_best(ray, tally)
            .map(|(t, i, s)| self.crossing(t, i, s))
    }

    /// The first crossing of `ray` (checked valid) as its rounded `t` in the
    /// caller's units, triangle and sign, walking one ray at a time.
    #[inline(always)]
    pub(super) fn first_best(&self, ray: &Ray, tally: &mut impl Tally) -> BestHit {
        let (scaled, t_scale) = unit_scaled(ray);
        // Decided with the caller's ray when the scaling rounded.
        let exact = scales_exactly(ray, &scaled, t_scale);
        let decide = if exact { &scaled } else { ray };
        let ray = &scaled;
        let mut best: BestHit = None;
        self.traverse(ray, exact, f64::INFINITY, tally, |i, t_max| {
            self.consider_for_first_hit(ray, decide, i, &mut best, t_max)
        });
        best.map(|(t, i, s)| (unscaled_t(t, t_scale), i, s))
    }

    /// Tests triangle `i` for the first hit of `ray`, updating `best`;
    /// returns the new limit `t` (the best crossing's, or `t_max` when it
    /// did not change). `t` is measured along `ray` (scaled by
    /// [`unit_scaled`]); the crossing is decided with `decide`, the same
    /// half-line exactly (the caller's ray when [`scales_exactly`] says
    /// the scaling rounded).
    #[inline(always)]
    pub(super) fn consider_for_first_hit(
        &self,
        ray: &Ray,
        decide: &Ray,
        i: u32,
        best: &mut BestHit,
        t_max: f64,
    ) -> f64 {
        // Once a crossing is known, a triangle whose rounded `t` is larger
        // cannot be the answer (the nearest is chosen by the rounded `t`),
        // whether or not the ray crosses it: skip the exact decision. `t_of`
        // clamps only values `≤ 0` (and NaN) up to the smallest positive
        // `f64`, which never exceeds `bt`, so the skip is exactly "would not
        // be better".
        // Before the first crossing, most triangles tested are misses:
        // decide first, and construct `t` only for a crossing.
        let raw = match *best {
            Some((bt, _, _)) => {
                let raw = self.plane_t(ray, i);
                if raw > bt {
                    return t_max;
                }
                Some(raw)
            }
            None => None,
        };
        if let TriHit::Cross(s) = self.hit_triangle::<false>(decide, i) {
            let raw = raw.unwrap_or_else(|| self.plane_t(ray, i));
            let t = if raw > 0.0 { raw } else { f64::MIN_POSITIVE };
            let better = match *best {
                None => true,
                Some((bt, bi, _)) => t < bt || (t == bt && i < bi),
            };
            if better {
                *best = Some((t, i, s));
                // The answer will name its face: ask for it now.
                prefetch(std::slice::from_ref(&self.tri_face[i as usize]));
                return t;
            }
        }
        t_max
    }

    fn check_ray(&self, ray: &Ray, index: usize) -> Result<(), QueryError> {
        if ray.is_valid() {
            Ok(())
        } else {
            Err(invalid_ray(ray, index))
        }
    }

    pub(super) fn crossing(&self, t: f64, i: u32, s: Sign) -> Crossing {
        Crossing {
            t,
            face: self.tri_face[i as usize],
            transition: if s == Sign::Positive {
                Transition::Exit
            } else {
                Transition::Enter
            },
        }
    }

    /// The rounded parameter of the crossing with triangle `i`'s plane,
    /// clamped to the smallest positive `f64` (the crossing is known exactly
    /// to be in front of the origin).
    fn t_of(&self, ray: &Ray, i: u32) -> f64 {
        let t = self.plane_t(ray, i);
        if t > 0.0 { t } else { f64::MIN_POSITIVE }
    }

    /// The rounded parameter of the ray's crossing with triangle `i`'s
    /// plane, unclamped (any sign, `±∞` or NaN for a parallel ray). `ray`
    /// is scaled by [`unit_scaled`] (largest direction component in
    /// `[1, 2)`).
    ///
    /// `t = n·(a − o) / n·d` with `n = (b − a) × (c − a)`. When the
    /// denominator is at least `2⁻⁶⁰⁰` and `t` is finite (nothing
    /// overflowed), every
    /// component of `n` that matters is far above the subnormal range and
    /// the quotient is accurate; otherwise (triangles of size `1e-160` or
    /// `1e200`, origins near `f64::MAX`) it is recomputed with the edges
    /// and `a − o` brought to unit size by powers of two
    /// ([`plane_t_rescaled`]).
    #[inline(always)]
    fn plane_t(&self, ray: &Ray, i: u32) -> f64 {
        let [a, b, c] = self.tris[i as usize].corners();
        let n = (b - a).cross(c - a);
        let den = n.dot(ray.direction);
        let t = n.dot(a - ray.origin) / den;
        // An overflow anywhere leaves `t` infinite or NaN (an infinite `n`
        // meets a non-zero or a zero coordinate of `a − o`).
        if den.abs() >= PLANE_T_DENOMINATOR && t.is_finite() {
            t
        } else {
            plane_t_rescaled(self.tris[i as usize].corners(), ray)
        }
    }

    /// How `ray` meets triangle `i`; with `ORIGIN = false` the (costlier)
    /// test of the origin lying on the triangle is skipped and reported as
    /// a miss — what first-hit queries need, which list no crossing at the
    /// origin.
    #[inline(always)]
    fn hit_triangle<const ORIGIN: bool>(&self, ray: &Ray, i: u32) -> TriHit {
        let [a, b, c] = &self.tris[i as usize].corners();
        let (o, d) = (&ray.origin, &ray.direction);
        let dd = [d.x, d.y, d.z];
        let u = [a.x - o.x, a.y - o.y, a.z - o.z];
        let v = [b.x - o.x, b.y - o.y, b.z - o.z];
        let w = [c.x - o.x, c.y - o.y, c.z - o.z];
        let origin_check = || {
            if ORIGIN {
                self.origin_check(*a, *b, *c, *o)
            } else {
                TriHit::Miss
            }
        };
        // The three edge signs at once with a shared error bound: it
        // certifies most misses and most crossings outright. The exact
        // decision below is the same as the edge-by-edge one it replaces
        // (a crossing needs three equal non-zero signs; certified signs are
        // the exact ones).
        let sides = triangle_edge_sides(dd, u, v, w);
        if sides.certainly_mixed() {
            return origin_check();
        }
        let s0 = match sides.certainly_uniform() {
            Some(s) => s,
            None => {
                let s0 = line_side_filter_scalar(dd, u, v)
                    .unwrap_or_else(|| line_side_sos(*o, *d, *a, *b));
                let s1 = line_side_filter_scalar(dd, v, w)
                    .unwrap_or_else(|| line_side_sos(*o, *d, *b, *c));
                if s0 != s1 || s0 == Sign::Zero {
                    return origin_check();
                }
                let s2 = line_side_filter_scalar(dd, w, u)
                    .unwrap_or_else(|| line_side_sos(*o, *d, *c, *a));
                if s2 != s0 {
                    return origin_check();
                }
                s0
            }
        };
        match orient3d(*a, *b, *c, *o) {
            Sign::Zero => origin_check(),
            side if side == -s0 => TriHit::Cross(s0),
            _ => TriHit::Miss,
        }
    }

    /// Whether the origin lies on the triangle (cheap rejections first).
    #[inline]
    fn origin_check(&self, a: DVec3, b: DVec3, c: DVec3, o: DVec3) -> TriHit {
        let lo = a.min(b).min(c);
        let hi = a.max(b).max(c);
        if o.cmplt(lo).any() || o.cmpgt(hi).any() {
            return TriHit::Miss;
        }
        if orient3d(a, b, c, o) == Sign::Zero && coplanar_point_in_closed_triangle(a, b, c, o) {
            TriHit::Origin
        } else {
            TriHit::Miss
        }
    }

    /// Visits the triangles of every leaf whose box the ray may touch before
    /// the current limit, nearest box first, except those its
    /// [`TriPacket`](super::tri_packet::TriPacket) proves missed.
    /// `visit(i, t_max)` returns the new limit (a `t`). Deferred children
    /// are kept with their entry parameter, so that one beyond the limit is
    /// dropped without touching its node or packet. The leaves' filter
    /// drops triangles only when `filter_misses` (its proof is for a ray
    /// [`unit_scaled`] without rounding, [`scales_exactly`]); the box tests
    /// are conservative for the caller's ray either way (a component that
    /// rounds is below `2⁻¹⁰²²`, so its slab's entry beyond a box plane is
    /// past `2⁸⁷³` — beyond every finite `f32` limit — exactly or rounded to
    /// 0). Nodes are opened with
    /// AVX2 where the processor has it (see `node_open`); the walk is the
    /// same either way.
    #[inline(always)]
    fn traverse(
        &self,
        ray: &Ray,
        filter_misses: bool,
        t_max: f64,
        tally: &mut impl Tally,
        visit: impl FnMut(u32, f64) -> f64,
    ) {
        #[cfg(target_arch = "x86_64")]
        if let Some(lanes) = Avx2::detect() {
            if let Some(lanes) = lanes.avx512() {
                // SAFETY: the AVX-512 features were detected.
                unsafe { self.traverse_avx512(lanes, ray, filter_misses, t_max, tally, visit) };
            } else {
                // SAFETY: AVX2 was detected.
                unsafe { self.traverse_avx2(lanes, ray, filter_misses, t_max, tally, visit) };
            }
            return;
        }
        self.traverse_with(Portable, ray, filter_misses, t_max, tally, visit);
    }

    /// [`Accel::traverse`] compiled for AVX-512, with its node opener.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,popcnt,fma,bmi1,bmi2,lzcnt,avx512f,avx512vl,avx512bw,avx512dq")]
    fn traverse_avx512(
        &self,
        lanes: Avx512,
        ray: &Ray,
        filter_misses: bool,
        t_max: f64,
        tally: &mut impl Tally,
        visit: impl FnMut(u32, f64) -> f64,
    ) {
        self.traverse_with(lanes, ray, filter_misses, t_max, tally, visit);
    }

    /// [`Accel::traverse`] compiled for AVX2, so that the node opening is
    /// inlined into it.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2,popcnt")]
    fn traverse_avx2(
        &self,
        lanes: Avx2,
        ray: &Ray,
        filter_misses: bool,
        t_max: f64,
        tally: &mut impl Tally,
        visit: impl FnMut(u32, f64) -> f64,
    ) {
        self.traverse_with(lanes, ray, filter_misses, t_max, tally, visit);
    }

    /// [`Accel::traverse`] with nodes opened by `lanes`.
    #[inline(always)]
    fn traverse_with(
        &self,
        lanes: impl NodeLanes,
        ray: &Ray,
        filter_misses: bool,
        t_max: f64,
        tally: &mut impl Tally,
        mut visit: impl FnMut(u32, f64) -> f64,
    ) {
        let rb = RayBox::new(ray, &self.frame);
        let mut pr = PacketRay::new(ray, self.frame.scale);
        if !filter_misses {
            pr = pr.blind();
        }
        let mut t_limit = t_max;
        let mut limit = rb.limit(t_limit);
        let mut key = limit_key(limit);
        let mut local = [Deferred::EMPTY; LOCAL_STACK];
        let mut heap = Vec::new();
        let stack: &mut [Deferred] = if self.stack_len <= LOCAL_STACK {
            &mut local
        } else {
            heap.resize(self.stack_len, Deferred::EMPTY);
            &mut heap
        };
        tally.node();
        let mut sp = self.open_node(lanes, &rb, 0, limit, stack, 0);
        while sp > 0 {
            sp -= 1;
            let Some(child) = stack[sp].reached(key) else {
                continue;
            };
            if child & LEAF == 0 {
                tally.node();
                sp = self.open_node(lanes, &rb, child, limit, stack, sp);
                continue;
            }
            let packet = &self.packets[(child & !LEAF) as usize];
            for _ in 0..packet.count {
                tally.triangle();
            }
            let mut undecided = packet.undecided(&pr);
            while undecided != 0 {
                let i = packet.first + undecided.trailing_zeros();
                undecided &= undecided - 1;
                tally.exact_test();
                let t_new = visit(i, t_limit);
                if t_new != t_limit {
                    t_limit = t_new;
                    limit = rb.limit(t_limit);
                    key = limit_key(limit);
                }
            }
        }
    }

    /// Opens inner node `node` with `lanes` (see [`NodeLanes::open`]):
    /// pushes the children the ray may touch no later than `limit` onto
    /// `stack` above `sp`, nearest on top; returns the new top. `stack` has
    /// room for [`WIDTH`](super::accel::WIDTH) entries above `sp` (see `Accel::stack_len`).
    #[inline(always)]
    pub(super) fn open_node(
        &self,
        lanes: impl NodeLanes,
        rb: &RayBox,
        node: u32,
        limit: f32,
        stack: &mut [Deferred],
        sp: usize,
    ) -> usize {
        lanes.open(rb, &self.nodes[node as usize], limit, stack, sp)
    }
}

/// A child waiting on a traversal's stack: its [`Node8::child`](super::accel::Node8::child) entry and
/// its key (see `node_open`). `repr(C)`: the AVX2 opener writes entries as
/// pairs of `u32` lanes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(C)]
pub(super) struct Deferred {
    /// [`LEAF`] plus a packet index, or an inner node's index.
    pub child: u32,
    /// The child's entry bits with `8 | slot` in the low four bits.
    pub key: u32,
}

impl Deferred {
    /// An unused stack slot.
    pub(super) const EMPTY: Deferred = Deferred { child: 0, key: 0 };

    /// The child, unless its box is entered beyond the limit whose
    /// [`limit_key`] is `limit_key`: the key without its slot bits, read as
    /// an `f32`, is at most the child's entry (so culling with it stays
    /// conservative).
    #[inline(always)]
    pub(super) fn reached(self, limit_key: u32) -> Option<u32> {
        (self.key <= limit_key).then_some(self.child)
    }
}

/// The culling limit `limit` (a non-negative `f32` or `+∞`, never NaN) as a
/// key: a [`Deferred`] child is within the limit exactly when its key is at
/// most this, compared as integers.
///
/// A key's bits without the slot bits, `k = key & !15`, are those of a
/// non-negative `f32`, and so is `L = limit.to_bits()`: for such values the
/// bits order as the numbers do, so `f32::from_bits(k) ≤ limit` is `k ≤ L`.
/// As `k` is a multiple of 16, `k ≤ L` holds exactly when `k ≤ L & !15`,
/// that is when `key = k | slot ≤ L | 15`.
#[inline(always)]
pub(super) fn limit_key(limit: f32) -> u32 {
    debug_assert!(limit >= 0.0, "{limit}");
    limit.to_bits() | KEY_SLOT_BITS
}

/// Traversal stacks at most this long live on the call stack; longer ones
/// (trees deeper than 20 levels) on the heap.
const LOCAL_STACK: usize = 64;

/// The first invalid ray of a batch, by index, as an error (checked on all
/// cores).
fn check_rays(rays: &[Ray]) -> Result<(), QueryError> {
    match rays
        .par_iter()
        .enumerate()
        .find_first(|(_, r)| !r.is_valid())
    {
        Some((index, ray)) => Err(invalid_ray(ray, index)),
        None => Ok(()),
    }
}

fn invalid_ray(ray: &Ray, index: usize) -> QueryError {
    QueryError::InvalidRay {
        index,
        origin: ray.origin,
        direction: ray.direction,
    }
}

/// Asks the processor to start loading the cache lines of `items` (a hint:
/// no effect on any answer; nothing on targets without the instruction).
#[inline(always)]
pub(super) fn prefetch<T>(items: &[T]) {
    let bytes = std::mem::size_of_val(items);
    if bytes > 0 {
        let start = items.as_ptr().cast::<u8>();
        prefetch_bytes(start, bytes - 1);
    }
}

/// Asks the processor to start loading the cache lines of the bytes
/// `start ..= start + last` (a hint: the address is never dereferenced, and
/// may be anything).
#[inline(always)]
pub(super) fn prefetch_bytes(start: *const u8, last: usize) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let start = start.cast::<i8>();
        let mut offset = 0;
        while offset < last {
            // SAFETY: SSE is part of the x86_64 baseline, and a prefetch
            // is a hint that never faults, whatever the address.
            unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset)) };
            offset += 64;
        }
        // The last line, when the bytes straddle one more boundary.
        // SAFETY: as above.
        unsafe { _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(last)) };
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (start, last);
}

/// Rays per unit of parallel work in [`Accel::first_hit_batch`].
const STREAM_CHUNK: usize = 512;

/// Orders crossings whose rounded `t` coincide (or are inverted by
/// rounding) so that transitions alternate, starting from `inside`: the
/// perturbed ray crosses them in such an order, infinitesimally apart. The
/// `t` values stay ascending; a transition is only moved forward past
/// crossings of the wrong kind, which on a valid closed solid can only be
/// crossings at (nearly) the same `t`.
fn alternate(hits: &mut [(f64, u32, Sign)], mut inside: bool) {
    let ts: Vec<f64> = hits.iter().map(|h| h.0).collect();
    for i in 0..hits.len() {
        let want = if inside {
            Sign::Positive
        } else {
            Sign::Negative
        };
        if hits[i].2 != want
            && let Some(j) = (i + 1..hits.len()).find(|&j| hits[j].2 == want)
        {
            hits[i..=j].rotate_right(1);
        }
        inside = hits[i].2 == Sign::Negative;
    }
    for (h, t) in hits.iter_mut().zip(ts) {
        h.0 = t;
    }
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::mesh::builders;
    use crate::query::accel::{Node8, WIDTH};
    use crate::query::node_open::for_each_lanes;
    use crate::query::ray_stream;
    use std::mem::MaybeUninit;

    /// `count` rays (those valid) from anywhere in `[-2, 2]³` towards points
    /// within `spread` of the origin: around and through a unit solid
    /// centred there, seeded.
    pub(in crate::query) fn rays_towards_the_centre(
        seed: u64,
        count: usize,
        spread: f64,
    ) -> Vec<Ray> {
        let mut uniform = crate::test_rng::uniform(seed);
        let mut rand = || DVec3::new(uniform(), uniform(), uniform()) * 4.0 - DVec3::splat(2.0);
        (0..count)
            .map(|_| {
                let origin = rand();
                Ray::new(origin, rand() * spread - origin)
            })
            .filter(Ray::is_valid)
            .collect()
    }

    /// The `f32` slab test never rejects a box the exact ray enters: boxes
    /// and rays at many scales and offsets, including rays grazing a box's
    /// face and rays parallel to an axis, checked against the slab test
    /// evaluated in `f64` (whose error, ~1e-16 relative, is far below the
    /// `f32` margins).
    #[test]
    fn f32_slab_test_is_conservative() {
        let mut uniform = crate::test_rng::uniform(0x9E37_79B9_7F4A_7C15u64);
        let mut entered = 0;
        for case in 0..20_000 {
            let centre = DVec3::new(uniform(), uniform(), uniform()) * 2e8 - DVec3::splat(1e8);
            let scale = 2f64.powi((uniform() * 40.0) as i32 - 20);
            let frame = BoxFrame { centre, scale };
            let size = 1.0 / scale;
            let mut rand = || DVec3::new(uniform(), uniform(), uniform()) * 2.0 - DVec3::ONE;
            let lo = centre + rand() * size;
            let hi = lo + (rand() + DVec3::ONE) * size * 0.1;
            let origin = centre + rand() * size * 3.0;
            let mut direction = (lo + (hi - lo) * (rand() + DVec3::ONE) * 0.5) - origin;
            if case % 5 == 0 {
                direction[case % 3] = 0.0;
            }
            if direction == DVec3::ZERO {
                continue;
            }
            direction *= 2f64.powi((uniform() * 200.0) as i32 - 100);
            let ray = Ray::new(origin, direction);
            let mut node = Node8 {
                child: [0; WIDTH],
                ..Node8::EMPTY
            };
            for a in 0..3 {
                node.bounds[a] = [f32::INFINITY; WIDTH];
                node.bounds[3 + a] = [f32::NEG_INFINITY; WIDTH];
                node.bounds[a][0] = frame.lower(lo[a], a);
                node.bounds[3 + a][0] = frame.upper(hi[a], a);
            }
            // The slab test in f64 on the exact box, shrunk by 1e-9 of its
            // size so that rounding cannot make it enter spuriously.
            let shrink = (hi - lo) * 1e-9;
            let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
            let mut misses = false;
            for a in 0..3 {
                let (l, h) = (lo[a] + shrink[a], hi[a] - shrink[a]);
                if direction[a] == 0.0 {
                    misses |= origin[a] < l || origin[a] > h;
                    continue;
                }
                let (ta, tb) = (
                    (l - origin[a]) / direction[a],
                    (h - origin[a]) / direction[a],
                );
                t0 = t0.max(ta.min(tb));
                t1 = t1.min(ta.max(tb));
            }
            if misses || t0 > t1 {
                continue;
            }
            entered += 1;
            // The slab test sees rays scaled as every query passes them;
            // `t` along the scaled ray is `t / factor`, exactly.
            let (scaled, factor) = unit_scaled(&ray);
            let rb = RayBox::new(&scaled, &frame);
            for_each_lanes!(|lanes| {
                let (entry, mask) = lanes.enter(&rb, &node, rb.limit(f64::INFINITY));
                assert_eq!(mask, 1, "case {case}: {ray:?} misses [{lo}, {hi}]");
                // And with the limit at the exact entry, the box still counts.
                let (_, mask) = lanes.enter(&rb, &node, rb.limit(t0 / factor));
                let entry = entry[0];
                assert_eq!(mask, 1, "case {case}: entry {entry} vs limit {t0}");
            });
        }
        assert!(entered > 5_000, "{entered}");
    }

    #[test]
    fn a_batch_answers_as_single_queries() {
        let accel = Accel::new(&builders::sphere(24));
        // From anywhere around the unit sphere towards points near its
        // centre; several stream chunks and a partial one.
        let rays = rays_towards_the_centre(0xD1B5_4A32_D192_ED03, 5 * STREAM_CHUNK + 123, 0.25);
        let batch = accel.first_hit_batch(&rays).unwrap();
        assert_eq!(batch.len(), rays.len());
        for (ray, hit) in rays.iter().zip(&batch) {
            assert_eq!(accel.first_hit(ray).unwrap(), *hit);
        }
        let hits = batch.iter().filter(|h| h.is_some()).count();
        assert!(hits > rays.len() / 2, "{hits} of {}", rays.len());
    }

    /// The walk gives the same answers whichever way its nodes are opened
    /// (the AVX2 one only runs where the processor has it).
    #[test]
    fn both_node_openers_give_the_same_hits() {
        let accel = Accel::new(&builders::sphere(24));
        let rays = rays_towards_the_centre(0x3C6E_F372_FE94_F82B, 4000, 0.5);
        // Slots made initialised, so reading them back is sound whatever
        // the walk wrote.
        type Slots = [MaybeUninit<Option<Crossing>>];
        let cast = |lanes: &dyn Fn(&[Ray], &mut Slots)| {
            let mut out = vec![MaybeUninit::new(None); rays.len()];
            lanes(&rays, &mut out);
            // SAFETY: every slot was initialised above.
            out.into_iter()
                .map(|o| unsafe { o.assume_init() })
                .collect::<Vec<_>>()
        };
        let scratch = std::cell::RefCell::new(WalkScratch::new(rays.len()));
        let portable =
            cast(&|r, o| accel.first_hits_with(Portable, r, o, &mut scratch.borrow_mut()));
        let hits = portable.iter().filter(|h| h.is_some()).count();
        assert!(hits > rays.len() / 2, "{hits} of {}", rays.len());
        for_each_lanes!(|lanes| {
            assert_eq!(
                cast(&|r, o| accel.first_hits_with(lanes, r, o, &mut scratch.borrow_mut())),
                portable
            );
        });
        for (ray, hit) in rays.iter().zip(&portable).step_by(5) {
            assert_eq!(accel.first_hit(ray).unwrap(), *hit);
        }
    }

    /// `RayBox::new` works on the three axes side by side; its values are
    /// bit for bit those of the per-axis definition written out here:
    /// origins near and far (beyond the `f32` range too), directions with
    /// zero, negative-zero, tiny and unit-size components.
    #[test]
    fn ray_box_lanes_equal_the_per_axis_definition() {
        fn per_axis(ray: &Ray, frame: &BoxFrame) -> ([[u32; 3]; 4], [Row; 3], [Row; 3]) {
            let mut values = [[0u32; 3]; 4];
            let (mut near_row, mut far_row) = ([Row::LowerX; 3], [Row::LowerX; 3]);
            for a in 0..3 {
                let f = frame.in_frame(ray.origin[a], a) as f32;
                let (lo, hi) = if f.is_finite() {
                    let m = f.abs() * ORIGIN_WIDEN + f32::MIN_POSITIVE;
                    (f - m, f + m)
                } else {
                    (f32::NEG_INFINITY, f32::INFINITY)
                };
                let da = ray.direction[a];
                let recip = (1.0 / da.abs()) as f32;
                let (inv_lo, inv_hi) = if da == 0.0 {
                    (f32::INFINITY, f32::INFINITY)
                } else {
                    ((recip * INV_SHRINK).min(f32::MAX), recip * INV_GROW)
                };
                let down = da.is_sign_negative();
                let sign = u32::from(down) << 31;
                let (o_near, o_far) = if down { (lo, hi) } else { (hi, lo) };
                values[0][a] = o_near.to_bits();
                values[1][a] = o_far.to_bits();
                values[2][a] = inv_lo.to_bits() | sign;
                values[3][a] = inv_hi.to_bits() | sign;
                near_row[a] = Row::of(a, down);
                far_row[a] = Row::of(a, !down);
            }
            (values, near_row, far_row)
        }
        let frames = [
            BoxFrame {
                centre: DVec3::ZERO,
                scale: 1.0,
            },
            BoxFrame {
                centre: DVec3::new(3.5, -2.25, 1e10),
                scale: 2f64.powi(-33),
            },
            BoxFrame {
                centre: DVec3::new(-1e-300, 0.0, 7.0),
                scale: 2f64.powi(900),
            },
        ];
        let mut uniform = crate::test_rng::uniform(0x510E_527F_ADE6_82D1);
        let special = [
            0.0, -0.0, 1e-300, -1e-300, 5e-324, 1.0, -1.5, 1e38, 1e300, -1e300,
        ];
        let mut checked = 0;
        for case in 0..4000usize {
            let mut pick = |k: usize| {
                if (case + k).is_multiple_of(3) {
                    special[(case / 3 + k) % special.len()]
                } else {
                    (uniform() - 0.5) * 8.0
                }
            };
            let origin = DVec3::new(pick(0), pick(1), pick(2));
            let direction = DVec3::new(pick(3), pick(4), pick(5));
            let ray = Ray::new(origin, direction);
            if !ray.is_valid() {
                continue;
            }
            let (ray, _) = unit_scaled(&ray);
            for frame in &frames {
                let rb = RayBox::new(&ray, frame);
                let lanes = [rb.o_near, rb.o_far, rb.inv_near, rb.inv_far]
                    .map(|v| [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()]);
                assert_eq!(
                    (lanes, rb.near_row, rb.far_row),
                    per_axis(&ray, frame),
                    "case {case}: {ray:?}"
                );
                assert_eq!(rb.t_to_s, frame.scale);
                checked += 1;
            }
        }
        assert!(checked > 9000, "{checked}");
    }

    /// A tree whose traversal stack would not fit the interleaved walk's
    /// is cast one ray at a time, with the same answers.
    #[test]
    fn batches_over_trees_too_deep_to_interleave_give_the_same_hits() {
        let mut accel = Accel::new(&builders::sphere(24));
        let rays = rays_towards_the_centre(0x9B05_688C_2B3E_6C1F, 2 * STREAM_CHUNK + 57, 0.25);
        let interleaved = accel.first_hit_batch(&rays).unwrap();
        let hits = interleaved.iter().filter(|h| h.is_some()).count();
        assert!(hits > rays.len() / 2, "{hits} of {}", rays.len());
        // The longest stack the interleaved walk holds, and one more (a
        // longer stack length still bounds the tree's stacks).
        for stack_len in [ray_stream::STACK, ray_stream::STACK + 1] {
            accel.stack_len = stack_len;
            assert_eq!(accel.first_hit_batch(&rays).unwrap(), interleaved);
        }
        for (ray, hit) in rays.iter().zip(&interleaved).step_by(7) {
            assert_eq!(accel.first_hit(ray).unwrap(), *hit);
        }
    }

    #[test]
    fn a_tree_deeper_than_the_local_stack_is_walked_in_full() {
        // Tetrahedra at x = 1.2^k: binned splits peel off only the farthest
        // few at each level (as far as the `f32` boxes of the build tell
        // them apart), so the tree is far deeper than a balanced one and
        // traversal stacks spill to the heap.
        let count = 150;
        let corner = |k: i32| (1.2f64.powi(k), 1.2f64.powi(k) / 4.0);
        let mut positions = Vec::new();
        let mut polygons = Vec::new();
        for k in 0..count {
            let (x, s) = corner(k);
            let base = positions.len();
            positions.extend([
                DVec3::new(x, 0.0, 0.0),
                DVec3::new(x + s, 0.0, 0.0),
                DVec3::new(x, s, 0.0),
                DVec3::new(x, 0.0, s),
            ]);
            for f in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
                polygons.push(f.map(|i| base + i));
            }
        }
        let soup = crate::mesh::PolygonSoup::new(positions, polygons);
        let accel = Accel::new(&crate::mesh::Solid::try_from_soup(&soup).unwrap());
        assert!(accel.stack_len > LOCAL_STACK, "{}", accel.stack_len);
        // Straight down onto each slanted face `x' + y' + z' = s`.
        let rays: Vec<Ray> = (0..count)
            .map(|k| {
                let (x, s) = corner(k);
                Ray::new(DVec3::new(x + s / 4.0, s / 4.0, 10.0 * s), DVec3::NEG_Z)
            })
            .collect();
        let batch = accel.first_hit_batch(&rays).unwrap();
        for (k, (ray, hit)) in rays.iter().zip(batch).enumerate() {
            let (_, s) = corner(k as i32);
            let hit = hit.unwrap_or_else(|| panic!("tetrahedron {k} missed"));
            assert_eq!(hit.transition, Transition::Enter, "{k}");
            assert!((hit.t - 9.5 * s).abs() <= 1e-12 * s, "{k}: {}", hit.t);
            assert_eq!(accel.first_hit(ray).unwrap(), Some(hit), "{k}");
            assert_eq!(accel.ray_crossings(ray).unwrap().hits.len(), 2, "{k}");
        }
    }

    #[test]
    fn huge_and_tiny_directions_give_the_same_crossings() {
        // Found by the queries fuzz check: a direction component of
        // −f64::MAX overflowed the exact line tests.
        let accel = Accel::new(&builders::l_prism());
        let origin = DVec3::new(0.5, 0.5, 0.5);
        let unit = DVec3::new(0.25, 1.0, -0.125);
        let reference = accel.ray_crossings(&Ray::new(origin, unit)).unwrap();
        assert_eq!(reference.origin, Containment::Inside);
        for scale in [f64::MAX, 1e300, 1e-300, f64::MIN_POSITIVE] {
            let ray = Ray::new(origin, unit * scale);
            let answer = accel.ray_crossings(&ray).unwrap();
            assert_eq!(answer.origin, reference.origin, "{scale}");
            let faces = |r: &RayCrossings| -> Vec<_> {
                r.hits.iter().map(|h| (h.face, h.transition)).collect()
            };
            assert_eq!(faces(&answer), faces(&reference), "{scale}");
            let first = accel.first_hit(&ray).unwrap().unwrap();
            assert_eq!(first.t, answer.hits[0].t);
            assert!(answer.hits.iter().all(|h| h.t > 0.0));
        }
        // Along one axis the parameter is exact: 1 / f64::MAX.
        let down = Ray::new(DVec3::ZERO, DVec3::new(0.0, 0.0, -f64::MAX));
        let cube = Accel::new(&builders::cube());
        let hit = cube.first_hit(&down).unwrap().unwrap();
        assert_eq!(hit.t, 1.0 / f64::MAX);
    }

    #[test]
    fn ray_through_a_cube() {
        let accel = Accel::new(&builders::cube());
        let r = accel
            .ray_crossings(&Ray::new(DVec3::new(-3.0, 0.1, 0.2), DVec3::X))
            .unwrap();
        assert_eq!(r.origin, Containment::Outside);
        assert_eq!(r.hits.len(), 2);
        assert_eq!(r.hits[0].t, 2.0);
        assert_eq!(r.hits[0].transition, Transition::Enter);
        assert_eq!(r.hits[1].t, 4.0);
        let r = accel
            .ray_crossings(&Ray::new(DVec3::ZERO, DVec3::new(1.0, 1.0, 1.0)))
            .unwrap();
        assert_eq!(r.origin, Containment::Inside);
        assert_eq!(r.hits.len(), 1);
        assert_eq!(r.hits[0].t, 1.0);
    }

    /// The leaves' `f32` filter leaves most of the triangles a ray meets in
    /// leaf boxes to no exact test at all (counted, not timed), and the
    /// first hits it finds are those of the exact crossings.
    #[test]
    fn the_leaf_filter_spares_most_exact_tests() {
        let accel = Accel::new(&builders::sphere(40));
        let (mut triangles, mut exact) = (0, 0);
        for k in 0..200 {
            let a = f64::from(k) * 0.37;
            let origin = DVec3::new(3.0 * a.cos(), 3.0 * a.sin(), 0.5 * (a * 0.7).sin());
            let target = DVec3::new(0.3 * (a * 1.3).sin(), 0.2 * a.cos(), 0.4 * (a * 0.9).cos());
            let ray = Ray::new(origin, target - origin);
            let (hit, stats) = accel.first_hit_traced(&ray).unwrap();
            let all = accel.ray_crossings(&ray).unwrap();
            assert_eq!(hit, all.hits.first().copied(), "ray {k}");
            assert!(hit.is_some(), "ray {k} aims inside the sphere");
            assert!(stats.exact_tests <= stats.triangles);
            triangles += stats.triangles;
            exact += stats.exact_tests;
        }
        assert!(4 * exact < triangles, "{exact} exact of {triangles}");
    }
}
