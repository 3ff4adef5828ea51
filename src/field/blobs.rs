//! Blobby objects: a field summed from point sources.

use glam::DVec3;

use crate::geom::Aabb;

use super::error::FieldError;
use super::falloff::Falloff;
use super::scalar_field::{Field, NodeBox, ValueRange};
use super::source::Source;
use super::source_grid::SourceGrid;
use super::stats::FieldStats;

/// A blobby object (Blinn 1982; soft objects, Wyvill et al. 1986):
/// `F(P) = Σᵢ wᵢ · g(|P − Pᵢ|, Rᵢ)`, the solid where `F ≥ ½`.
///
/// Evaluation looks up the sample's cell in a uniform grid over the sources'
/// balls and evaluates only the sources listed there whose ball holds the
/// sample ([`FieldStats`] counts both).
#[derive(Clone, Debug)]
pub struct Blobs {
    sources: Vec<Source>,
    falloff: Falloff,
    grid: SourceGrid,
}

impl Blobs {
    /// A blobby field of `sources` with the given falloff.
    ///
    /// # Errors
    ///
    /// The first bad source ([`FieldError::NonFiniteCenter`],
    /// [`FieldError::BadRadius`], [`FieldError::BadStrength`]), named by its
    /// index in `sources`.
    pub fn try_new(sources: Vec<Source>, falloff: Falloff) -> Result<Blobs, FieldError> {
        for (i, s) in sources.iter().enumerate() {
            s.check(i)?;
        }
        let grid = SourceGrid::new(&sources);
        Ok(Blobs {
            sources,
            falloff,
            grid,
        })
    }

    /// The sources.
    #[must_use]
    pub fn sources(&self) -> &[Source] {
        &self.sources
    }

    /// How many sources there are.
    #[must_use]
    pub fn len(&self) -> usize {
        self.sources.len()
    }

    /// Whether there is no source (the field is 0 everywhere).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.sources.is_empty()
    }

    /// The falloff.
    #[must_use]
    pub fn falloff(&self) -> Falloff {
        self.falloff
    }

    /// `F(p)` summed over every source, without the grid: the reference the
    /// grid's answer is tested against.
    #[must_use]
    pub fn value_brute_force(&self, p: DVec3) -> f64 {
        self.sources
            .iter()
            .map(|s| {
                s.strength
                    * self
                        .falloff
                        .value(p.distance_squared(s.center), s.radius * s.radius)
            })
            .sum()
    }
}

impl Field for Blobs {
    fn value_counted(&self, p: DVec3, stats: &mut FieldStats) -> f64 {
        stats.samples += 1;
        let Some(cell) = self.grid.cell_of(p) else {
            return 0.0;
        };
        let mut sum = 0.0;
        for &s in self.grid.sources_in(cell) {
            stats.candidates += 1;
            let source = &self.sources[s as usize];
            let r2 = p.distance_squared(source.center);
            let radius2 = source.radius * source.radius;
            if r2 < radius2 {
                stats.source_evaluations += 1;
                sum += source.strength * self.falloff.value(r2, radius2);
            }
        }
        sum
    }

    /// The sources near the box are found once, from the source grid;
    /// each node sums those whose ball holds it, in source order — the
    /// sources its own grid cell lists that reach it, since every source
    /// that adds at a point is listed in the point's cell and in the
    /// cells the box meets. So each value is `value_counted`'s, bit for bit.
    fn sample_nodes(&self, nodes: &NodeBox, values: &mut [f64], stats: &mut FieldStats) {
        let near: Vec<(DVec3, f64, f64)> = self
            .grid
            .sources_meeting(&nodes.region())
            .into_iter()
            .map(|s| {
                let s = &self.sources[s as usize];
                (s.center, s.radius * s.radius, s.strength)
            })
            .collect();
        let [nx, ny, nz] = nodes.counts;
        let mut evaluations = 0;
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let p = nodes.position(i, j, k);
                    let mut sum = 0.0;
                    for &(center, radius2, strength) in &near {
                        let r2 = p.distance_squared(center);
                        if r2 < radius2 {
                            evaluations += 1;
                            sum += strength * self.falloff.value(r2, radius2);
                        }
                    }
                    values[(k * ny + j) * nx + i] = sum;
                }
            }
        }
        let samples = nodes.len() as u64;
        stats.samples += samples;
        stats.candidates += samples * near.len() as u64;
        stats.source_evaluations += evaluations;
    }

    /// Sums, over the sources that may reach the box (from the source
    /// grid), each falloff at the box's nearest and farthest points,
    /// widened by a bound on the rounding of both the samples and this sum.
    ///
    /// Why the widening suffices (`ε = 2⁻⁵²`): a sample's rounded squared
    /// distance and `s² = r²/R²` are within `4ε` of the exact ones, the
    /// falloffs have slopes at most 3 in `s²` on `[0, 1]` and are evaluated
    /// within `5ε`, so each rounded term is within `17ε |w|` of the exact
    /// term, and the same holds for the ends computed here; a sum of `k`
    /// terms of magnitude at most `|w|` is rounded by at most `k ε Σ|w|`.
    /// So the computed values lie within `(34 + 2k) ε Σ|w|` of the exact
    /// range; the allowance used is `(64 + 2k) ε Σ|w|`.
    fn bound(&self, region: &Aabb) -> ValueRange {
        let candidates = self.grid.sources_meeting(region);
        let (mut low, mut high, mut weight) = (0.0, 0.0, 0.0);
        for &s in &candidates {
            let source = &self.sources[s as usize];
            let near = (region.min - source.center)
                .max(source.center - region.max)
                .max(DVec3::ZERO);
            let far = (region.min - source.center)
                .abs()
                .max((region.max - source.center).abs());
            let radius2 = source.radius * source.radius;
            // The falloff decreases with distance.
            let most = source.strength * self.falloff.value(near.length_squared(), radius2);
            let least = source.strength * self.falloff.value(far.length_squared(), radius2);
            low += most.min(least);
            high += most.max(least);
            weight += source.strength.abs();
        }
        let allowance = (64.0 + 2.0 * candidates.len() as f64) * f64::EPSILON * weight;
        ValueRange {
            low: low - allowance,
            high: high + allowance,
        }
    }

    /// The union of the influence boxes of the sources with positive
    /// strength: elsewhere only carving sources reach, and `F ≤ 0`.
    fn bounds(&self) -> Aabb {
        self.sources
            .iter()
            .filter(|s| s.strength > 0.0)
            .fold(Aabb::EMPTY, |b, s| b.union(s.influence_box()))
            .intersection(self.grid.bounds())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_grid_gives_the_brute_force_sum_and_skips_far_sources() {
        let mut u = crate::test_rng::uniform(7);
        let mut range = |lo: f64, hi: f64| lo + (hi - lo) * u();
        let sources: Vec<Source> = (0..200)
            .map(|_| {
                Source::try_new(
                    DVec3::new(range(0.0, 20.0), range(0.0, 20.0), range(0.0, 20.0)),
                    range(0.5, 2.0),
                    range(-0.5, 1.5),
                )
                .unwrap()
            })
            .collect();
        let blobs = Blobs::try_new(sources, Falloff::SoftObject).unwrap();
        let mut stats = FieldStats::default();
        for _ in 0..2000 {
            let p = DVec3::new(range(-3.0, 23.0), range(-3.0, 23.0), range(-3.0, 23.0));
            let fast = blobs.value_counted(p, &mut stats);
            let slow = blobs.value_brute_force(p);
            // The grid lists every source that adds at `p`, in order: the
            // same sum, exactly (zeros aside, bit for bit).
            assert!(fast == slow, "{p}: {fast} vs {slow}");
        }
        assert_eq!(stats.samples, 2000);
        // Each sample looks at a few dozen candidates, not all 200 sources.
        assert!(stats.candidates < 2000 * 40, "{stats}");
        assert!(stats.source_evaluations <= stats.candidates);
    }

    #[test]
    fn the_bound_holds_every_sample_of_a_box_and_decides_far_boxes() {
        let mut u = crate::test_rng::uniform(11);
        let mut range = |lo: f64, hi: f64| lo + (hi - lo) * u();
        for falloff in [Falloff::SoftObject, Falloff::CubicParabola] {
            let sources: Vec<Source> = (0..40)
                .map(|_| {
                    Source::try_new(
                        DVec3::new(range(0.0, 8.0), range(0.0, 8.0), range(0.0, 8.0)),
                        range(0.5, 2.0),
                        range(-0.8, 1.5),
                    )
                    .unwrap()
                })
                .collect();
            let blobs = Blobs::try_new(sources, falloff).unwrap();
            let (mut decided, mut boxes) = (0, 0);
            for _ in 0..300 {
                let lo = DVec3::new(range(-3.0, 11.0), range(-3.0, 11.0), range(-3.0, 11.0));
                let side = range(0.0, 1.0);
                let region = Aabb {
                    min: lo,
                    max: lo + DVec3::splat(side),
                };
                let bound = blobs.bound(&region);
                boxes += 1;
                decided += usize::from(bound.all_outside() || bound.all_inside());
                for _ in 0..40 {
                    let t = DVec3::new(range(0.0, 1.0), range(0.0, 1.0), range(0.0, 1.0));
                    let p = (lo + t * side).clamp(region.min, region.max);
                    let v = blobs.value(p);
                    assert!(
                        bound.low <= v && v <= bound.high,
                        "{v} outside {bound:?} at {p}"
                    );
                }
                // The corners too.
                for c in 0..8 {
                    let p = DVec3::new(
                        if c & 1 == 0 {
                            region.min.x
                        } else {
                            region.max.x
                        },
                        if c & 2 == 0 {
                            region.min.y
                        } else {
                            region.max.y
                        },
                        if c & 4 == 0 {
                            region.min.z
                        } else {
                            region.max.z
                        },
                    );
                    let v = blobs.value(p);
                    assert!(bound.low <= v && v <= bound.high, "{v} outside {bound:?}");
                }
            }
            // Small boxes away from the surface are decided.
            assert!(decided * 3 > boxes, "{decided} of {boxes} ({falloff:?})");
        }
    }

    #[test]
    fn bad_sources_are_named_by_index() {
        let good = Source::try_unit(DVec3::ZERO, 1.0).unwrap();
        let mut bad = good;
        bad.radius = 0.0;
        assert_eq!(
            Blobs::try_new(vec![good, bad], Falloff::default()).unwrap_err(),
            FieldError::BadRadius {
                source_index: 1,
                radius: 0.0
            }
        );
        bad.radius = 1.0;
        bad.center.y = f64::NAN;
        assert!(matches!(
            Blobs::try_new(vec![good, good, bad], Falloff::default()),
            Err(FieldError::NonFiniteCenter {
                source_index: 2,
                ..
            })
        ));
    }

    #[test]
    fn an_empty_field_has_empty_bounds() {
        let blobs = Blobs::try_new(Vec::new(), Falloff::default()).unwrap();
        assert!(blobs.bounds().is_empty());
        assert_eq!(blobs.value(DVec3::ZERO), 0.0);
        let carving = Source::try_new(DVec3::ZERO, 1.0, -1.0).unwrap();
        let blobs = Blobs::try_new(vec![carving], Falloff::default()).unwrap();
        assert!(blobs.bounds().is_empty());
    }
}
