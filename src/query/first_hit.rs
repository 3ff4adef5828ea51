//! The first crossing of one ray: the leaf test of first-hit walks and the
//! one-ray walk.
//!
//! The nearest crossing is chosen exactly: each crossing's rounded `t`
//! carries a bound on its error ([`Accel::plane_t_bounded`]); crossings
//! whose intervals are apart are ordered by them, and those whose
//! intervals overlap (a ray nearly in a face's plane, where `t` is
//! ill-conditioned, or two faces crossed at nearly one point) by the exact
//! quotients `n·(a − o) / n·d`; exact ties go to the smaller triangle.

use std::cmp::Ordering;

use crate::geom::Ray;
use crate::spatial::raw::prefetch::prefetch;

use super::accel::Accel;
use super::ray_answers::{BestHit, Crossing, Nearest, Tally};
use super::ray_scaling::{scales_exactly, unit_scaled, unscaled_t};
use super::ray_triangle::{TriHit, plane_parts};

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
        let mut best: Option<Nearest> = None;
        self.traverse(ray, exact, f64::INFINITY, tally, |i, t_max| {
            self.consider_for_first_hit(ray, decide, i, &mut best, t_max)
        });
        best.map(|n| {
            // Along the caller's ray when the scaling rounded (the scaled
            // line is another line).
            let t = if exact {
                unscaled_t(self.accurate_t(ray, n.triangle, n.t, n.error), t_scale)
            } else {
                self.t_of(decide, n.triangle)
            };
            (t, n.triangle, n.sign)
        })
    }

    /// Tests triangle `i` for the first hit of `ray`, updating `best`;
    /// returns the new limit `t` (beyond which no crossing can be nearer:
    /// the best crossing's `t` plus its error bound, or `t_max` when it
    /// did not change). `t` is measured along `ray` (scaled by
    /// [`unit_scaled`]); the crossing is decided with `decide`, the same
    /// half-line exactly (the caller's ray when [`scales_exactly`] says
    /// the scaling rounded), and so are exact comparisons of `t`.
    #[inline(always)]
    pub(super) fn consider_for_first_hit(
        &self,
        ray: &Ray,
        decide: &Ray,
        i: u32,
        best: &mut Option<Nearest>,
        t_max: f64,
    ) -> f64 {
        // Once a crossing is known, a triangle whose `t` is certainly larger
        // cannot be the answer, whether or not the ray crosses it: skip the
        // exact decision. Before the first crossing, most triangles tested
        // are misses: decide first, and construct `t` only for a crossing.
        let bounded = match *best {
            Some(b) => {
                let (raw, error) = self.plane_t_bounded(ray, i);
                if raw - error > b.t + b.error {
                    return t_max;
                }
                Some((raw, error))
            }
            None => None,
        };
        if let TriHit::Cross(sign) = self.hit_triangle::<false>(decide, i) {
            let (raw, error) = bounded.unwrap_or_else(|| self.plane_t_bounded(ray, i));
            // A decided crossing lies in front of the origin: a rounded `t`
            // at or behind it is raised to the smallest positive `t`, which
            // moves it towards the exact value.
            let t = if raw > 0.0 { raw } else { f64::MIN_POSITIVE };
            let better = match *best {
                None => true,
                Some(b) => {
                    if t + error < b.t - b.error {
                        true
                    } else if t - error > b.t + b.error {
                        false
                    } else {
                        match self.exact_t_order(decide, i, b.triangle) {
                            Ordering::Less => true,
                            Ordering::Greater => false,
                            Ordering::Equal => i < b.triangle,
                        }
                    }
                }
            };
            if better {
                *best = Some(Nearest {
                    t,
                    error,
                    triangle: i,
                    sign,
                });
                // The answer will name its face: ask for it now.
                prefetch(std::slice::from_ref(&self.tri_face[i as usize]));
                return t + error;
            }
        }
        t_max
    }

    /// The exact order of the parameters at which `ray` crosses the planes
    /// of triangles `i` and `j` (both crossed, so neither plane is parallel
    /// to it): `t = n·(a − o) / n·d`, compared as `N_i·D_j − N_j·D_i` times
    /// the sign of `D_i·D_j`, in exact dyadic arithmetic.
    #[cold]
    #[inline(never)]
    fn exact_t_order(&self, ray: &Ray, i: u32, j: u32) -> Ordering {
        let parts = |k: u32| plane_parts(self.tris[k as usize].corners(), ray);
        let ((ni, di), (nj, dj)) = (parts(i), parts(j));
        let difference = &(&ni * &dj) - &(&nj * &di);
        (difference.sign() * (&di * &dj).sign()).ordering()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;
    use crate::query::ray_triangle::T_ACCURACY;

    /// Rays nearly in the plane of a triangle of a sphere (tilted by about
    /// 10⁻¹² out of it), from outside and from inside: the first hit, by the
    /// one-ray walk and by the batch walk, is the exactly nearest crossing
    /// among all triangles crossed (every triangle decided exactly, the
    /// nearest by exact comparison). Rounded `t` picks another triangle on
    /// some of these rays, which the test counts to show it reaches them.
    #[test]
    fn grazing_rays_hit_the_exactly_nearest_crossing() {
        let accel = Accel::new(&builders::sphere(24));
        let count = accel.tris.len() as u32;
        let mut u = crate::test_rng::uniform(0x06A2_1146);
        let (mut rays, mut expected) = (Vec::new(), Vec::new());
        let mut rounded_differs = 0;
        while rays.len() < 3000 {
            let i = ((u() * f64::from(count)) as u32).min(count - 1);
            let [a, b, c] = accel.tris[i as usize].corners();
            let n = (b - a).cross(c - a).normalize();
            let (w1, w2) = (u() * 0.5, u() * 0.5);
            let p = a + (b - a) * w1 + (c - a) * w2;
            let along = ((b - a) * (u() - 0.5) + (c - a) * (u() - 0.5)).normalize();
            let d = along + n * ((u() - 0.5) * 2e-12);
            let origin = p - d * (0.05 + 3.0 * u());
            let ray = Ray::new(origin, d);
            let crossed: Vec<u32> = (0..count)
                .filter(|&j| matches!(accel.hit_triangle::<false>(&ray, j), TriHit::Cross(_)))
                .collect();
            let exact = crossed
                .iter()
                .copied()
                .min_by(|&x, &y| accel.exact_t_order(&ray, x, y).then(x.cmp(&y)));
            let rounded = crossed.iter().copied().min_by(|&x, &y| {
                accel
                    .plane_t_bounded(&ray, x)
                    .0
                    .total_cmp(&accel.plane_t_bounded(&ray, y).0)
                    .then(x.cmp(&y))
            });
            rounded_differs += usize::from(exact != rounded);
            rays.push(ray);
            expected.push(exact);
        }
        let batch = accel.first_hit_batch(&rays).unwrap();
        let mut inaccurate = 0;
        for (k, ray) in rays.iter().enumerate() {
            let one = accel.first_hit(ray).unwrap();
            assert_eq!(one.map(|c| c.triangle), expected[k], "ray {k}: {ray:?}");
            assert_eq!(batch[k], one, "ray {k} in a batch");
            // `t` within `T_ACCURACY` of the exact one.
            if let (Some(c), Some(i)) = (one, expected[k]) {
                let (num, den) = plane_parts(accel.tris[i as usize].corners(), ray);
                let exact_t = num.quotient_to_f64(&den);
                assert!(
                    (c.t - exact_t).abs() <= T_ACCURACY * exact_t,
                    "ray {k}: t {} vs {exact_t}",
                    c.t
                );
                let rounded_t = accel.plane_t_bounded(ray, i).0;
                inaccurate += usize::from((rounded_t - exact_t).abs() > T_ACCURACY * exact_t);
            }
        }
        assert!(rounded_differs > 0, "no ray where rounded t misorders");
        assert!(inaccurate > 0, "no ray whose rounded t is inaccurate");
        println!(
            "{rounded_differs} of {} rays where rounded t picks another triangle",
            rays.len()
        );
    }
}
