//! Volume by integrating span lengths over a grid of parallel rays.

use glam::DVec3;
use rayon::prelude::*;
use thiserror::Error;

use super::{Csg, Stats};
use crate::geom::{Aabb, Ray, Readable};

/// Why a volume cannot be estimated.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum VolumeError {
    /// The solid's bounds are infinite (a half-space not cut down).
    #[error("the solid is unbounded (bounds {bounds:?}); cut it with a bounded solid first")]
    Unbounded {
        /// The bounds found.
        bounds: Aabb,
    },
    /// The spacing must be positive and finite.
    #[error("ray spacing {} must be positive and finite", Readable(*spacing))]
    BadSpacing {
        /// The spacing given.
        spacing: f64,
    },
    /// A spacing larger than the solid: one ray would stand for all of it.
    #[error(
        "ray spacing {} is larger than the solid (its longest side is {}); use a spacing below that",
        Readable(*spacing),
        Readable(*size)
    )]
    SpacingTooLarge {
        /// The spacing given.
        spacing: f64,
        /// The longest side of the solid's bounds.
        size: f64,
    },
    /// The grid would need more rays than the limit.
    #[error(
        "spacing {} needs {rays} rays, more than the limit {limit}; use a larger spacing",
        Readable(*spacing)
    )]
    TooManyRays {
        /// The spacing given.
        spacing: f64,
        /// Rays needed.
        rays: u64,
        /// The limit.
        limit: u64,
    },
}

/// The largest grid [`Csg::try_volume`] casts (about a minute of work on
/// two cores for a simple scene).
pub const MAX_VOLUME_RAYS: u64 = 400_000_000;

/// A volume found by ray integration.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct VolumeEstimate {
    /// `Σ (span length) · h²` over the grid.
    pub volume: f64,
    /// The grid spacing used: the requested `h` shrunk so that a whole
    /// number of cells spans the bounds (the larger of the x and y cell
    /// sides).
    pub spacing: f64,
    /// The number of rays cast.
    pub rays: u64,
    /// The closed-form volume when the tree is a single leaf that has one
    /// (for a polyhedral solid, the divergence-theorem volume).
    pub exact: Option<f64>,
    /// The work done.
    pub stats: Stats,
}

impl Csg {
    /// The volume, by casting rays along +z through the centres of a grid of
    /// cells covering the bounds in x and y (the midpoint rule) and summing
    /// span lengths times the cell area. The cells are at most `h × h`: the
    /// grid is fitted to the bounds (`⌈size / h⌉` cells per side), so that
    /// faces on the bounds never cut a cell. Rows run in parallel (rayon).
    ///
    /// The error shrinks as `h` does: it comes from cells cut by the
    /// silhouette (about `h × (silhouette length)` in the worst case, much
    /// less when the errors of neighbouring cells cancel) and from where the
    /// span length varies steeply (tangent cylinders and spheres).
    ///
    /// # Errors
    ///
    /// [`VolumeError`] for an unbounded solid, a bad spacing, or more than
    /// [`MAX_VOLUME_RAYS`] rays.
    pub fn try_volume(&self, spacing: f64) -> Result<VolumeEstimate, VolumeError> {
        self.try_volume_with_progress(spacing, |_| {})
    }

    /// [`Csg::try_volume`], calling `progress(rows_done_fraction)` as rows
    /// finish (from worker threads).
    ///
    /// # Errors
    ///
    /// As [`Csg::try_volume`].
    pub fn try_volume_with_progress(
        &self,
        spacing: f64,
        progress: impl Fn(f64) + Sync,
    ) -> Result<VolumeEstimate, VolumeError> {
        if !(spacing.is_finite() && spacing > 0.0) {
            return Err(VolumeError::BadSpacing { spacing });
        }
        let bounds = self.bounds();
        let exact = self.single_leaf().and_then(|l| l.primitive.exact_volume());
        if bounds.is_empty() {
            return Ok(VolumeEstimate {
                volume: 0.0,
                spacing,
                rays: 0,
                exact,
                stats: Stats::default(),
            });
        }
        if !(bounds.min.is_finite() && bounds.max.is_finite()) {
            return Err(VolumeError::Unbounded { bounds });
        }
        let size = bounds.size();
        if spacing > size.max_element() {
            return Err(VolumeError::SpacingTooLarge {
                spacing,
                size: size.max_element(),
            });
        }
        let nx = ((size.x / spacing).ceil() as u64).max(1);
        let ny = ((size.y / spacing).ceil() as u64).max(1);
        let rays = nx.saturating_mul(ny);
        let (hx, hy) = (size.x / nx as f64, size.y / ny as f64);
        if rays > MAX_VOLUME_RAYS {
            return Err(VolumeError::TooManyRays {
                spacing,
                rays,
                limit: MAX_VOLUME_RAYS,
            });
        }
        let done = std::sync::atomic::AtomicU64::new(0);
        // Rows in parallel, their lengths summed in row order afterwards: a
        // rayon reduce would add them in an order that depends on the
        // threads, and the volume's last bits with it.
        let rows: Vec<(f64, Stats)> = (0..ny)
            .into_par_iter()
            .map(|j| {
                let mut stats = Stats::default();
                let y = bounds.min.y + (j as f64 + 0.5) * hy;
                let mut row = 0.0;
                for i in 0..nx {
                    let x = bounds.min.x + (i as f64 + 0.5) * hx;
                    let ray = Ray::new(DVec3::new(x, y, bounds.min.z), DVec3::Z);
                    let spans = self.spans(&ray, &mut stats);
                    row += spans
                        .intervals()
                        .iter()
                        .map(|&(a, b)| b.min(size.z) - a)
                        .sum::<f64>();
                }
                let finished = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
                progress(finished as f64 / ny as f64);
                (row, stats)
            })
            .collect();
        let mut length = 0.0;
        let mut stats = Stats::default();
        for (row, row_stats) in rows {
            length += row;
            stats += row_stats;
        }
        Ok(VolumeEstimate {
            volume: length * hx * hy,
            spacing: hx.max(hy),
            rays,
            exact,
            stats,
        })
    }
}
