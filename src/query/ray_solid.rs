//! Ray–solid crossings: what a CSG primitive answers for a ray.

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::exact::line_side_filter_scalar;
use crate::geom::polygon::coplanar_point_in_closed_triangle;
use crate::geom::{Ray, Sign, line_side_sos, orient3d};
use crate::mesh::FaceId;

use super::accel::{Node4, WIDTH};
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

/// Per-ray constants for box tests.
struct RayBox {
    origin: [f64; 3],
    inv: [f64; 3],
    neg: [bool; 3],
}

/// `1 + 2γ₃` with `γₙ = n u / (1 − n u)`: Ize's factor making the slab test
/// conservative under rounding ("Robust BVH Ray Traversal", JCGT 2013).
const SLAB_GROW: f64 = 1.0 + 2.0 * (3.0 * HALF_EPS / (1.0 - 3.0 * HALF_EPS));
const HALF_EPS: f64 = f64::EPSILON / 2.0;

impl RayBox {
    fn new(ray: &Ray) -> RayBox {
        let inv = DVec3::ONE / ray.direction;
        RayBox {
            origin: ray.origin.to_array(),
            inv: inv.to_array(),
            neg: [inv.x < 0.0, inv.y < 0.0, inv.z < 0.0],
        }
    }

    /// The entry parameters of a node's children's boxes, each `Some` if
    /// the ray (`t ≥ 0`) may touch that box before `t_max`; conservative.
    /// The children are computed side by side (the same operations per
    /// child, so the compiler can pair them in vector registers).
    #[inline(always)]
    fn enter4(&self, n: &Node4, t_max: f64) -> [Option<f64>; WIDTH] {
        let mut t0 = [0.0f64; WIDTH];
        let mut t1 = [t_max; WIDTH];
        for a in 0..3 {
            let (near, far) = if self.neg[a] {
                (&n.max[a], &n.min[a])
            } else {
                (&n.min[a], &n.max[a])
            };
            for k in 0..WIDTH {
                let tn = (f64::from(near[k]) - self.origin[a]) * self.inv[a];
                let tf = (f64::from(far[k]) - self.origin[a]) * self.inv[a] * SLAB_GROW;
                // NaN (0 · ∞: origin on the slab plane of a parallel ray)
                // leaves the bound unchanged.
                t0[k] = if tn > t0[k] { tn } else { t0[k] };
                t1[k] = if tf < t1[k] { tf } else { t1[k] };
            }
        }
        std::array::from_fn(|k| (t0[k] <= t1[k]).then_some(t0[k]))
    }
}

/// The same ray with its direction multiplied by a power of two so that its
/// largest component lies in `[1, 2)`, and that factor. Exact: the line and
/// the half-line `t > 0` do not change, only the unit of `t`; the exact
/// predicates then never see a direction whose products overflow or
/// underflow (a direction of `1e308` or `5e-324`; found by the queries
/// fuzz check).
fn unit_scaled(ray: &Ray) -> (Ray, f64) {
    let largest = ray.direction.abs().max_element();
    // `largest` is finite and non-zero (a checked ray): its binary exponent
    // lies in −1074 ..= 1023, and 2^−e is applied in two exact halves.
    let e = largest.log2().floor() as i32;
    let (half, rest) = (-e / 2, -e - (-e / 2));
    let direction = ray.direction * 2f64.powi(half) * 2f64.powi(rest);
    // `origin + t · direction·f = origin + (t·f) · direction`: a parameter
    // along the scaled ray times `f` is the caller's parameter.
    let factor = 2f64.powi(half) * 2f64.powi(rest);
    (Ray::new(ray.origin, direction), factor)
}

/// A parameter along the scaled direction of [`unit_scaled`] in units of the
/// caller's direction: monotone, and still `> 0` when it underflows.
fn unscaled_t(t: f64, factor: f64) -> f64 {
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
        let (ray, t_scale) = unit_scaled(ray);
        let ray = &ray;
        let mut on_boundary = false;
        let mut hits: Vec<(f64, u32, Sign)> = Vec::new();
        self.traverse(ray, f64::INFINITY, |i, _| {
            match self.hit_triangle(ray, i) {
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
        for (index, ray) in rays.iter().enumerate() {
            self.check_ray(ray, index)?;
        }
        // Small meshes fit in cache: sorting would cost more than it saves.
        if rays.len() < SORTED_BATCH || self.tris.len() < COHERENT_MIN_TRIANGLES {
            return Ok(rays
                .par_iter()
                .with_min_len(512)
                .map(|r| self.first_hit_unchecked(r))
                .collect());
        }
        // Large batches: cast the rays in the order of a 6-D Morton code of
        // (origin, direction), so that rays cast one after the other walk
        // mostly the same BVH nodes and triangles, which are then still in
        // cache; answers are written back in input order.
        let order = coherent_order(rays);
        let sorted: Vec<Ray> = order.par_iter().map(|&i| rays[i as usize]).collect();
        let answers: Vec<Option<Crossing>> = sorted
            .par_iter()
            .with_min_len(1024)
            .map(|r| self.first_hit_unchecked(r))
            .collect();
        let mut out = vec![None; rays.len()];
        for (&i, a) in order.iter().zip(answers) {
            out[i as usize] = a;
        }
        Ok(out)
    }

    /// [`Accel::ray_crossings`] for every ray, in order, on all cores.
    ///
    /// # Errors
    ///
    /// The first invalid ray by index, or [`QueryError::NotClosed`].
    pub fn ray_crossings_batch(&self, rays: &[Ray]) -> Result<Vec<RayCrossings>, QueryError> {
        for (index, ray) in rays.iter().enumerate() {
            self.check_ray(ray, index)?;
        }
        self.require_closed()?;
        rays.par_iter()
            .with_min_len(256)
            .map(|r| self.ray_crossings(r))
            .collect()
    }

    fn first_hit_unchecked(&self, ray: &Ray) -> Option<Crossing> {
        let (ray, t_scale) = unit_scaled(ray);
        let ray = &ray;
        let mut best: Option<(f64, u32, Sign)> = None;
        self.traverse(ray, f64::INFINITY, |i, t_max| {
            // Once a crossing is known, a triangle whose rounded `t` is
            // larger cannot be the answer (the nearest is chosen by the
            // rounded `t`), whether or not the ray crosses it: skip the exact
            // decision. `t_of` clamps only values `≤ 0` (and NaN) up to the
            // smallest positive `f64`, which never exceeds `bt`, so the skip
            // is exactly "would not be better".
            let raw = self.plane_t(ray, i);
            if let Some((bt, _, _)) = best {
                if raw > bt {
                    return t_max;
                }
            }
            if let TriHit::Cross(s) = self.hit_triangle(ray, i) {
                let t = if raw > 0.0 { raw } else { f64::MIN_POSITIVE };
                let better = match best {
                    None => true,
                    Some((bt, bi, _)) => t < bt || (t == bt && i < bi),
                };
                if better {
                    best = Some((t, i, s));
                    return t;
                }
            }
            t_max
        });
        best.map(|(t, i, s)| self.crossing(unscaled_t(t, t_scale), i, s))
    }

    fn check_ray(&self, ray: &Ray, index: usize) -> Result<(), QueryError> {
        if ray.is_valid() {
            Ok(())
        } else {
            Err(QueryError::InvalidRay {
                index,
                origin: ray.origin,
                direction: ray.direction,
            })
        }
    }

    fn crossing(&self, t: f64, i: u32, s: Sign) -> Crossing {
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
    /// plane, unclamped (any sign, `±∞` or NaN for a parallel ray).
    #[inline(always)]
    fn plane_t(&self, ray: &Ray, i: u32) -> f64 {
        let [a, b, c] = self.tris[i as usize].corners();
        let n = (b - a).cross(c - a);
        n.dot(a - ray.origin) / n.dot(ray.direction)
    }

    #[inline]
    fn hit_triangle(&self, ray: &Ray, i: u32) -> TriHit {
        let [a, b, c] = &self.tris[i as usize].corners();
        let (o, d) = (&ray.origin, &ray.direction);
        let dd = [d.x, d.y, d.z];
        let u = [a.x - o.x, a.y - o.y, a.z - o.z];
        let v = [b.x - o.x, b.y - o.y, b.z - o.z];
        let s0 = line_side_filter_scalar(dd, u, v).unwrap_or_else(|| line_side_sos(*o, *d, *a, *b));
        let w = [c.x - o.x, c.y - o.y, c.z - o.z];
        let s1 = line_side_filter_scalar(dd, v, w).unwrap_or_else(|| line_side_sos(*o, *d, *b, *c));
        if s0 != s1 || s0 == Sign::Zero {
            return self.origin_check(*a, *b, *c, *o);
        }
        let s2 = line_side_filter_scalar(dd, w, u).unwrap_or_else(|| line_side_sos(*o, *d, *c, *a));
        if s2 != s0 {
            return self.origin_check(*a, *b, *c, *o);
        }
        match orient3d(*a, *b, *c, *o) {
            Sign::Zero => self.origin_check(*a, *b, *c, *o),
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
    /// the current limit, near child first. `visit(i, t_max)` returns the new
    /// limit. Deferred subtrees are kept with their entry parameter, so that
    /// a subtree beyond the limit is dropped without touching its node.
    fn traverse(&self, ray: &Ray, t_max: f64, mut visit: impl FnMut(u32, f64) -> f64) {
        let rb = RayBox::new(ray);
        let mut limit = t_max;
        let mut stack: smallvec::SmallVec<[(u32, f64); 64]> = smallvec::SmallVec::new();
        let nodes = &self.nodes;
        let mut current = 0u32;
        loop {
            let node = &nodes[current as usize];
            let entry = rb.enter4(node, limit);
            // The children the ray may touch, nearer first (ties by slot).
            let mut order: [(f64, usize); WIDTH] = [(0.0, 0); WIDTH];
            let mut len = 0;
            for (k, e) in entry.into_iter().enumerate() {
                if let Some(t) = e {
                    let mut j = len;
                    while j > 0 && order[j - 1].0 > t {
                        order[j] = order[j - 1];
                        j -= 1;
                    }
                    order[j] = (t, k);
                    len += 1;
                }
            }
            // Leaves are tested at once, nearer first; the nearest inner
            // child is descended into, the others deferred (nearer popped
            // first).
            let mut next: Option<u32> = None;
            let mut deferred: [(u32, f64); WIDTH] = [(0, 0.0); WIDTH];
            let mut n_deferred = 0;
            for &(t, k) in &order[..len] {
                if t > limit {
                    continue;
                }
                let (child, count) = (node.child[k], node.count[k]);
                if count > 0 {
                    for i in child..child + count {
                        limit = visit(i, limit);
                    }
                } else if next.is_none() {
                    next = Some(child);
                } else {
                    deferred[n_deferred] = (child, t);
                    n_deferred += 1;
                }
            }
            for &d in deferred[..n_deferred].iter().rev() {
                stack.push(d);
            }
            if let Some(n) = next {
                current = n;
                continue;
            }
            loop {
                let Some((n, t)) = stack.pop() else {
                    return;
                };
                if t <= limit {
                    current = n;
                    break;
                }
            }
        }
    }
}

/// Batches at least this large are cast in a coherent order...
const SORTED_BATCH: usize = 8192;
/// ...on meshes with at least this many triangles.
const COHERENT_MIN_TRIANGLES: usize = 16 * 1024;

/// Ray indices sorted by a 6-D Morton code of the ray's origin (within the
/// origins' bounding box) and its normalized direction, 10 bits per
/// coordinate.
fn coherent_order(rays: &[Ray]) -> Vec<u32> {
    let bounds = rays
        .iter()
        .fold(crate::geom::Aabb::EMPTY, |b, r| b.grow(r.origin));
    let size = bounds.size().max(DVec3::splat(f64::MIN_POSITIVE));
    let quantize = |x: f64| (x.clamp(0.0, 1.0) * 1023.0) as u64;
    let mut keyed: Vec<(u64, u32)> = rays
        .par_iter()
        .with_min_len(4096)
        .enumerate()
        .map(|(i, r)| {
            let o = (r.origin - bounds.min) / size;
            let d = r.direction.normalize_or_zero() * 0.5 + DVec3::splat(0.5);
            let q = [o.x, o.y, o.z, d.x, d.y, d.z].map(quantize);
            let mut key = 0u64;
            for bit in (0..10).rev() {
                for &c in &q {
                    key = (key << 1) | ((c >> bit) & 1);
                }
            }
            (key, i as u32)
        })
        .collect();
    keyed.par_sort_unstable();
    keyed.into_iter().map(|(_, i)| i).collect()
}

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
        if hits[i].2 != want {
            if let Some(j) = (i + 1..hits.len()).find(|&j| hits[j].2 == want) {
                hits[i..=j].rotate_right(1);
            }
        }
        inside = hits[i].2 == Sign::Negative;
    }
    for (h, t) in hits.iter_mut().zip(ts) {
        h.0 = t;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

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
}
