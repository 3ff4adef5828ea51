//! The first crossing of one ray: the leaf test of first-hit walks (the
//! nearest crossing by rounded `t`, ties by triangle) and the one-ray walk.

use crate::geom::Ray;
use crate::spatial::raw::prefetch::prefetch;

use super::accel::Accel;
use super::ray_answers::{BestHit, Crossing, Tally};
use super::ray_scaling::{scales_exactly, unit_scaled, unscaled_t};
use super::ray_triangle::TriHit;

impl Accel {
    /// The first hit of `ray` (checked valid), walking one ray at a time.
    pub(super) fn first_hit_unchecked(&self, ray: &Ray) -> Option<Crossing> {
        self.first_hit_tallied(ray, &mut ())
    }

    /// [`Accel::first_hit_unchecked`], reporting the work into `tally`.
    #[inline(always)]
    pub(super) fn first_hit_tallied(&self, ray: &Ray, tally: &mut impl Tally) -> Option<Crossing> {
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
}
