//! Volume by integrating span lengths over a grid of parallel rays.

use glam::DVec3;
use rayon::prelude::*;
use thiserror::Error;

use super::tree::{NodeIndex, NodeKind};
use super::{Csg, LeafId, Stats};
use crate::SetOp;
use crate::geom::{Aabb, Ray, Readable};

/// Why a volume cannot be estimated.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum VolumeError {
    /// The solid's bounds are infinite (a half-space not cut down).
    #[error(
        "the solid is unbounded (bounds {} to {}); cut it with a bounded solid first",
        crate::geom::ReadableVec(.bounds.min),
        crate::geom::ReadableVec(.bounds.max)
    )]
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
    /// The default grid ([`Csg::try_default_volume`]) would need more rays
    /// than the limit to put [`MIN_CELLS_ACROSS_LEAF`] cells across a leaf
    /// that adds volume: the leaves are too small for their distance apart.
    #[error(
        "the default grid cannot resolve leaf {leaf} ({} wide along {}) in a solid {} long: it would need {rays} rays, more than the limit {limit}; give a spacing",
        Readable(*width),
        ["x", "y"][*axis],
        Readable(*size)
    )]
    Unresolvable {
        /// The label of the narrowest leaf.
        leaf: String,
        /// Its width along `axis`.
        width: f64,
        /// The axis (0 for x, 1 for y) along which it is narrowest.
        axis: usize,
        /// The longest side of the solid's bounds.
        size: f64,
        /// Rays needed.
        rays: u64,
        /// The limit.
        limit: u64,
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

/// Cells across the longest side of the solid's bounds in the default
/// grid ([`Csg::try_default_volume`]).
pub const DEFAULT_VOLUME_CELLS: f64 = 400.0;

/// Cells across every bounded leaf that adds volume (one not subtracted),
/// along x and along y, in the default grid: two unit boxes 1,000 apart
/// are not missed by a grid laid for the distance between them.
pub const MIN_CELLS_ACROSS_LEAF: f64 = 4.0;

/// Leaves a grid may miss: bounded leaves narrower than one cell along x
/// or y, so that no ray of the grid need pass through them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Unresolved {
    /// How many leaves are that narrow.
    pub count: usize,
    /// The narrowest of them (relative to the cell side along its axis).
    pub narrowest: LeafId,
    /// Its width along that axis.
    pub width: f64,
    /// The axis: 0 for x, 1 for y.
    pub axis: usize,
}

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
    /// Leaves the grid may have missed (`None` when every bounded leaf is
    /// at least one cell wide along x and y).
    pub unresolved: Option<Unresolved>,
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
        let Some(bounds) = self.volume_bounds()? else {
            return Ok(self.empty_estimate(spacing));
        };
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
        if rays > MAX_VOLUME_RAYS {
            return Err(VolumeError::TooManyRays {
                spacing,
                rays,
                limit: MAX_VOLUME_RAYS,
            });
        }
        Ok(self.integrate(bounds, [nx, ny], progress))
    }

    /// [`Csg::try_volume`] on the default grid: at most
    /// [`DEFAULT_VOLUME_CELLS`] cells across the solid's longest side, and
    /// at least [`MIN_CELLS_ACROSS_LEAF`] cells across every bounded leaf
    /// that adds volume (one not subtracted), along x and along y
    /// separately (a needle along x does not make the grid fine along x).
    ///
    /// # Errors
    ///
    /// As [`Csg::try_volume`]; [`VolumeError::Unresolvable`] when such a
    /// grid would need more than [`MAX_VOLUME_RAYS`] rays (leaves far
    /// smaller than their distance apart): give a spacing then.
    pub fn try_default_volume(&self) -> Result<VolumeEstimate, VolumeError> {
        self.try_default_volume_with_progress(|_| {})
    }

    /// [`Csg::try_default_volume`], calling `progress` as rows finish.
    ///
    /// # Errors
    ///
    /// As [`Csg::try_default_volume`].
    pub fn try_default_volume_with_progress(
        &self,
        progress: impl Fn(f64) + Sync,
    ) -> Result<VolumeEstimate, VolumeError> {
        let Some(bounds) = self.volume_bounds()? else {
            return Ok(self.empty_estimate(0.0));
        };
        let size = bounds.size();
        let longest = size.max_element();
        let mut cell = [longest / DEFAULT_VOLUME_CELLS; 2];
        let mut narrowest: [Option<(LeafId, f64)>; 2] = [None, None];
        for id in self.adding_leaves() {
            let leaf = self.leaves[id.0 as usize].primitive.bounds();
            if !(leaf.min.is_finite() && leaf.max.is_finite()) || leaf.is_empty() {
                continue;
            }
            for axis in 0..2 {
                let width = leaf.size()[axis];
                if width > 0.0 && width / MIN_CELLS_ACROSS_LEAF < cell[axis] {
                    cell[axis] = width / MIN_CELLS_ACROSS_LEAF;
                    narrowest[axis] = Some((id, width));
                }
            }
        }
        let count = |axis: usize| {
            let side = size[axis];
            if cell[axis] > 0.0 {
                ((side / cell[axis]).ceil() as u64).max(1)
            } else {
                1
            }
        };
        let (nx, ny) = (count(0), count(1));
        let rays = nx.saturating_mul(ny);
        if rays > MAX_VOLUME_RAYS {
            let axis = usize::from(cell[1] < cell[0]);
            let (leaf, width) = narrowest[axis]
                .or(narrowest[1 - axis])
                .map_or((String::from("-"), cell[axis]), |(id, w)| {
                    (self.leaves[id.0 as usize].label.clone(), w)
                });
            return Err(VolumeError::Unresolvable {
                leaf,
                width,
                axis,
                size: longest,
                rays,
                limit: MAX_VOLUME_RAYS,
            });
        }
        Ok(self.integrate(bounds, [nx, ny], progress))
    }

    /// The leaves whose solid can add to the tree's: all but those under
    /// the subtracted side of a difference (an odd number of times).
    fn adding_leaves(&self) -> Vec<LeafId> {
        let mut out = Vec::new();
        let mut stack: Vec<(NodeIndex, bool)> = vec![(self.root, true)];
        while let Some((node, adds)) = stack.pop() {
            match self.nodes[node].kind {
                NodeKind::Leaf(id) => {
                    if adds {
                        out.push(id);
                    }
                }
                NodeKind::Op { op, left, right } => {
                    let (l, r) = match op {
                        SetOp::Union | SetOp::Intersection => (adds, adds),
                        SetOp::Difference => (adds, !adds),
                        SetOp::ReverseDifference => (!adds, adds),
                    };
                    stack.push((left, l));
                    stack.push((right, r));
                }
            }
        }
        out
    }

    /// The bounds a grid is laid over: `None` when they are empty.
    fn volume_bounds(&self) -> Result<Option<Aabb>, VolumeError> {
        let bounds = self.bounds();
        if bounds.is_empty() {
            return Ok(None);
        }
        if !(bounds.min.is_finite() && bounds.max.is_finite()) {
            return Err(VolumeError::Unbounded { bounds });
        }
        Ok(Some(bounds))
    }

    /// The estimate of a solid with empty bounds.
    fn empty_estimate(&self, spacing: f64) -> VolumeEstimate {
        VolumeEstimate {
            volume: 0.0,
            spacing,
            rays: 0,
            exact: self.single_leaf().and_then(|l| l.primitive.exact_volume()),
            stats: Stats::default(),
            unresolved: None,
        }
    }

    /// Bounded leaves narrower than a cell of `hx × hy` along x or y.
    fn unresolved(&self, hx: f64, hy: f64) -> Option<Unresolved> {
        let mut found: Option<(Unresolved, f64)> = None;
        let mut count = 0;
        for (k, leaf) in self.leaves.iter().enumerate() {
            let b = leaf.primitive.bounds();
            if !(b.min.is_finite() && b.max.is_finite()) || b.is_empty() {
                continue;
            }
            let (ratio, axis) = [(b.size().x / hx, 0), (b.size().y / hy, 1)]
                .into_iter()
                .min_by(|a, b| a.0.total_cmp(&b.0))
                .unwrap_or((f64::INFINITY, 0));
            if ratio >= 1.0 {
                continue;
            }
            count += 1;
            if found.is_none_or(|(_, worst)| ratio < worst) {
                let unresolved = Unresolved {
                    count: 0,
                    narrowest: LeafId(k as u32),
                    width: b.size()[axis],
                    axis,
                };
                found = Some((unresolved, ratio));
            }
        }
        found.map(|(u, _)| Unresolved { count, ..u })
    }

    /// Casts the grid of `nx × ny` rays over `bounds` and sums the spans.
    fn integrate(
        &self,
        bounds: Aabb,
        [nx, ny]: [u64; 2],
        progress: impl Fn(f64) + Sync,
    ) -> VolumeEstimate {
        let size = bounds.size();
        let exact = self.single_leaf().and_then(|l| l.primitive.exact_volume());
        let rays = nx * ny;
        let (hx, hy) = (size.x / nx as f64, size.y / ny as f64);
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
        VolumeEstimate {
            volume: length * hx * hy,
            spacing: hx.max(hy),
            rays,
            exact,
            stats,
            unresolved: self.unresolved(hx, hy),
        }
    }
}
