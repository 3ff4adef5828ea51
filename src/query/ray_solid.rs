//! Ray–solid crossings: what a CSG primitive answers for a ray, one ray
//! or a batch at a time.

use std::sync::atomic::{AtomicUsize, Ordering};

use rayon::prelude::*;

use crate::geom::{Ray, Sign};

use super::accel::Accel;
use super::accel::ray_stream::WalkScratch;
use super::ray_answers::{Crossing, RayCrossings, TraversalStats};
use super::ray_scaling::{checked_t, scales_exactly, unit_scaled, unscaled_t};
use super::ray_triangle::TriHit;
use super::{Containment, QueryError};

impl Accel {
    /// The crossings of `ray` with the solid's boundary, and whether its
    /// origin is inside.
    ///
    /// Each triangle is tested with three exact [`line_side_sos`](crate::geom::line_side_sos) signs on
    /// the ray's origin and direction (the ray crosses the triangle iff the
    /// three agree; their common sign says `Enter`/`Exit`) and one exact
    /// `orient3d` for "in front of the origin". Ties (the ray through an
    /// edge or vertex, or lying in a face's plane) are broken by the symbolic
    /// perturbation of [`line_side_sos`](crate::geom::line_side_sos): the ray is rotated by an
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
    /// [`QueryError::NotClosed`] for an open surface,
    /// [`QueryError::RayOutOfRange`] when a crossing's `t` overflows (a
    /// direction too short) or underflows to zero (too long).
    pub fn ray_crossings(&self, ray: &Ray) -> Result<RayCrossings, QueryError> {
        self.check_ray(ray, 0)?;
        self.require_closed()?;
        self.crossings_at(ray, 0)
    }

    /// [`Accel::ray_crossings`] of a checked ray of a closed solid, the
    /// ray named by `index` in a refusal.
    fn crossings_at(&self, ray: &Ray, index: usize) -> Result<RayCrossings, QueryError> {
        let caller = ray;
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
                // In the caller's units; along the caller's ray when the
                // scaling rounded (the scaled line is another line, whose
                // `t` at a face nearly along it is meaningless).
                TriHit::Cross(s) => hits.push((
                    if exact {
                        unscaled_t(self.t_of(ray, i), t_scale)
                    } else {
                        self.t_of(decide, i)
                    },
                    i,
                    s,
                )),
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
            .map(|(t, i, s)| checked_t(t, index, caller).map(|()| self.crossing(t, i, s)))
            .collect::<Result<_, _>>()?;
        Ok(RayCrossings { origin, hits })
    }

    /// The first crossing of `ray` with the boundary (`t > 0`), or `None`.
    /// Decided as in [`Accel::ray_crossings`]; the nearest is chosen by the
    /// rounded `t` (ties by triangle order). Works on open surfaces too.
    ///
    /// # Errors
    ///
    /// [`QueryError::InvalidRay`] for a non-finite or zero-direction ray,
    /// [`QueryError::RayOutOfRange`] when the first crossing's `t`
    /// overflows or underflows to zero (as [`Accel::ray_crossings`]).
    pub fn first_hit(&self, ray: &Ray) -> Result<Option<Crossing>, QueryError> {
        self.check_ray(ray, 0)?;
        checked_hit(self.first_hit_unchecked(ray), 0, ray)
    }

    /// [`Accel::first_hit`] for every ray, in order, on all cores.
    ///
    /// # Errors
    ///
    /// The first invalid ray, by index; else the first whose first
    /// crossing's `t` overflows or underflows ([`QueryError::RayOutOfRange`]).
    pub fn first_hit_batch(&self, rays: &[Ray]) -> Result<Vec<Option<Crossing>>, QueryError> {
        // Cast in input order: grouping rays that pass close to one another
        // (a Morton order of origins and directions) costs more in sorting,
        // copying and unpermuting than it saves in cache misses.
        //
        // Each worker checks a chunk of rays, then casts them a few at a
        // time, interleaved (see `ray_stream`), so that one ray's cache
        // misses overlap the others' work; the answers are written straight
        // into the result. One pass over the rays and one over the answers:
        // no separate checking pass.
        let first_invalid = AtomicUsize::new(usize::MAX);
        let mut out: Vec<Option<Crossing>> = vec![None; rays.len()];
        out.par_chunks_mut(STREAM_CHUNK)
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
        for (index, (hit, ray)) in out.iter().zip(rays).enumerate() {
            checked_hit(*hit, index, ray)?;
        }
        Ok(out)
    }

    /// [`Accel::ray_crossings`] for every ray, in order, on all cores.
    ///
    /// # Errors
    ///
    /// The first invalid ray by index, or [`QueryError::NotClosed`]; else
    /// the first ray (by index) with a crossing whose `t` overflows or
    /// underflows ([`QueryError::RayOutOfRange`]).
    pub fn ray_crossings_batch(&self, rays: &[Ray]) -> Result<Vec<RayCrossings>, QueryError> {
        check_rays(rays)?;
        self.require_closed()?;
        let answers: Vec<Result<RayCrossings, QueryError>> = rays
            .par_iter()
            .enumerate()
            .with_min_len(256)
            .map(|(index, r)| self.crossings_at(r, index))
            .collect();
        // In input order: the refusal named is the first ray's, whatever
        // the threads did first.
        answers.into_iter().collect()
    }

    /// [`Accel::first_hit`], with the work its traversal did.
    ///
    /// # Errors
    ///
    /// As [`Accel::first_hit`].
    pub fn first_hit_traced(
        &self,
        ray: &Ray,
    ) -> Result<(Option<Crossing>, TraversalStats), QueryError> {
        self.check_ray(ray, 0)?;
        let mut stats = TraversalStats::default();
        let hit = checked_hit(self.first_hit_tallied(ray, &mut stats), 0, ray)?;
        Ok((hit, stats))
    }

    fn check_ray(&self, ray: &Ray, index: usize) -> Result<(), QueryError> {
        if ray.is_valid() {
            Ok(())
        } else {
            Err(invalid_ray(ray, index))
        }
    }
}

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

/// A first hit whose `t` [`checked_t`] accepts (or none).
fn checked_hit(
    hit: Option<Crossing>,
    index: usize,
    ray: &Ray,
) -> Result<Option<Crossing>, QueryError> {
    match hit {
        Some(h) => checked_t(h.t, index, ray).map(|()| hit),
        None => Ok(None),
    }
}

fn invalid_ray(ray: &Ray, index: usize) -> QueryError {
    QueryError::InvalidRay {
        index,
        origin: ray.origin,
        direction: ray.direction,
    }
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
#[path = "ray_solid_tests.rs"]
pub(super) mod tests;
