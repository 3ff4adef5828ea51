//! Samples of a field on a regular grid, padded by a layer of zeros.

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::Aabb;

use super::super::error::FieldError;
use super::super::scalar_field::{Field, node_position};
use super::super::stats::FieldStats;

/// The most samples a grid may hold (2²⁵, 256 MiB of values): enough for
/// 320³.
pub const MAX_SAMPLES: usize = 1 << 25;

/// The smallest cell a grid may have, in units of the spacing of `f64`
/// at the grid's farthest coordinate: below it, vertices kept
/// [`VERTEX_ULPS`] from the nodes would crowd the cell, and nodes
/// themselves would round onto each other.
pub const MIN_CELL_ULPS: f64 = 32.0;

/// How far a vertex stays from its edge's nodes, at least, in units of the
/// spacing of `f64` at the grid's farthest coordinate: so that rounding
/// its position never puts it on a node or on another vertex (a blob
/// centred at 1e12 gave thousands of degenerate faces when the margin
/// was only a fraction of a cell, below that spacing).
pub const VERTEX_ULPS: f64 = 4.0;

/// The margin, as a fraction of the cell, that keeps vertices
/// [`VERTEX_ULPS`] spacings of `f64` away from the nodes of the grid of
/// `dims` nodes from `origin` with `cell` (padding included).
///
/// # Errors
///
/// [`FieldError::CellBelowResolution`] for a cell smaller than
/// [`MIN_CELL_ULPS`] such spacings.
pub(crate) fn resolution_margin(
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
) -> Result<f64, FieldError> {
    let far = origin + DVec3::new(dims[0] as f64, dims[1] as f64, dims[2] as f64) * cell;
    let reach = (origin - DVec3::splat(cell))
        .abs()
        .max(far.abs())
        .max_element();
    // The spacing of f64 just above the farthest coordinate (the largest
    // anywhere on the grid).
    let spacing = (reach.next_up() - reach).max(f64::from_bits(1));
    if cell.is_nan() || cell < MIN_CELL_ULPS * spacing {
        return Err(FieldError::CellBelowResolution {
            cell,
            coordinate: reach,
            spacing,
            needed: MIN_CELL_ULPS,
        });
    }
    Ok(VERTEX_ULPS * spacing / cell)
}

/// Field values at the nodes `origin + cell · (i, j, k)` of a regular grid,
/// `0 ≤ i < dims[0]` and so on.
///
/// Marching cubes reads the grid through [`SampleGrid::value`], which
/// answers 0 one node beyond each side: the grid is padded by a layer of
/// outside samples, so the surface always closes at the border.
///
/// # Invariants
///
/// `values.len() = dims[0] · dims[1] · dims[2] ≤ MAX_SAMPLES`, every value
/// finite, `origin` finite, `cell` finite and > 0.
#[derive(Clone, Debug, PartialEq)]
pub struct SampleGrid {
    origin: DVec3,
    cell: f64,
    dims: [usize; 3],
    values: Vec<f64>,
}

impl SampleGrid {
    /// A grid of given values, x fastest, then y, then z.
    ///
    /// # Errors
    ///
    /// [`FieldError::BadGridFrame`], [`FieldError::GridTooLarge`],
    /// [`FieldError::CellBelowResolution`], [`FieldError::SampleCount`] or
    /// the first [`FieldError::NonFiniteSample`].
    pub fn try_new(
        origin: DVec3,
        cell: f64,
        dims: [usize; 3],
        values: Vec<f64>,
    ) -> Result<SampleGrid, FieldError> {
        if !(origin.is_finite() && cell.is_finite() && cell > 0.0) {
            return Err(FieldError::BadGridFrame { origin, cell });
        }
        let expected = check_size(dims)?;
        resolution_margin(origin, cell, dims)?;
        if values.len() != expected {
            return Err(FieldError::SampleCount {
                dims,
                expected,
                found: values.len(),
            });
        }
        if let Some(n) = values.iter().position(|v| !v.is_finite()) {
            return Err(FieldError::NonFiniteSample {
                i: n % dims[0],
                j: n / dims[0] % dims[1],
                k: n / (dims[0] * dims[1]),
                value: values[n],
            });
        }
        Ok(SampleGrid {
            origin,
            cell,
            dims,
            values,
        })
    }

    /// Samples `field` over its [`bounds`](Field::bounds) with `resolution`
    /// cells along the longest side, in parallel (z slabs), and returns the
    /// work done.
    ///
    /// # Errors
    ///
    /// [`FieldError::ZeroResolution`], [`FieldError::Empty`] when the
    /// field's bounds are empty, [`FieldError::GridTooLarge`], or
    /// [`FieldError::NonFiniteSample`] when the field returns NaN.
    pub fn try_sample(
        field: &dyn Field,
        resolution: usize,
    ) -> Result<(SampleGrid, FieldStats), FieldError> {
        let GridFrame { origin, cell, dims } = GridFrame::try_new(field, resolution)?;
        let total = check_size(dims)?;
        let slab = dims[0] * dims[1];
        let mut values = vec![0.0; total];
        let stats: Vec<FieldStats> = values
            .par_chunks_mut(slab)
            .enumerate()
            .map(|(k, slab_values)| {
                let mut stats = FieldStats::default();
                for j in 0..dims[1] {
                    for i in 0..dims[0] {
                        let p = node_position(origin, cell, i as isize, j as isize, k as isize);
                        slab_values[j * dims[0] + i] = field.value_counted(p, &mut stats);
                    }
                }
                stats
            })
            .collect();
        let mut sum = FieldStats::default();
        for s in stats {
            sum += s;
        }
        let grid = SampleGrid::try_new(origin, cell, dims, values)?;
        Ok((grid, sum))
    }

    /// Samples along x, y and z.
    #[must_use]
    pub fn dims(&self) -> [usize; 3] {
        self.dims
    }

    /// The edge length of a cell.
    #[must_use]
    pub fn cell(&self) -> f64 {
        self.cell
    }

    /// The position of node `(0, 0, 0)`.
    #[must_use]
    pub fn origin(&self) -> DVec3 {
        self.origin
    }

    /// The values, x fastest.
    #[must_use]
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The value at a node of the padded grid: the sample for
    /// `0 ≤ i < dims[0]` (and so on), 0 elsewhere.
    #[must_use]
    pub fn value(&self, i: isize, j: isize, k: isize) -> f64 {
        let inside = |v: isize, n: usize| usize::try_from(v).ok().filter(|&v| v < n);
        match (
            inside(i, self.dims[0]),
            inside(j, self.dims[1]),
            inside(k, self.dims[2]),
        ) {
            (Some(i), Some(j), Some(k)) => self.values[(k * self.dims[1] + j) * self.dims[0] + i],
            _ => 0.0,
        }
    }

    /// The margin that keeps vertices off this grid's nodes after
    /// rounding ([`VERTEX_ULPS`]), as a fraction of the cell.
    pub(crate) fn vertex_margin(&self) -> f64 {
        // Checked when the grid was made.
        resolution_margin(self.origin, self.cell, self.dims).unwrap_or(0.5)
    }

    /// The position of a node of the padded grid.
    #[must_use]
    pub fn position(&self, i: isize, j: isize, k: isize) -> DVec3 {
        node_position(self.origin, self.cell, i, j, k)
    }
}

/// Where the grid over a field lies: its first node, its cell and its
/// node counts (without the padding).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct GridFrame {
    pub(crate) origin: DVec3,
    pub(crate) cell: f64,
    pub(crate) dims: [usize; 3],
}

impl GridFrame {
    /// The frame over `field`'s bounds with `resolution` cells along the
    /// longest side, its size checked against [`MAX_SAMPLES`].
    pub(crate) fn try_new(field: &dyn Field, resolution: usize) -> Result<GridFrame, FieldError> {
        if resolution == 0 {
            return Err(FieldError::ZeroResolution);
        }
        let bounds: Aabb = field.bounds();
        let size = bounds.size();
        // `F < ½` outside the box and on its faces: a box flat along an axis
        // is all faces, so the solid is empty.
        if bounds.is_empty() {
            return Err(FieldError::Empty);
        }
        if size.min_element() <= 0.0 {
            // Flat by rounding (a blob of radius 10 at 1e100, whose box
            // rounds to a point) is below f64's resolution, not empty.
            let cell = size.max_element() / resolution as f64;
            resolution_margin(bounds.min, cell, [1; 3])?;
            return Err(FieldError::Empty);
        }
        let cell = size.max_element() / resolution as f64;
        if !(cell.is_finite() && cell > 0.0) {
            return Err(FieldError::BadGridFrame {
                origin: bounds.min,
                cell,
            });
        }
        let dims = [size.x, size.y, size.z].map(|s| {
            let n = (s / cell).ceil();
            // Saturate: check_size refuses it below.
            if n < (MAX_SAMPLES as f64) {
                n as usize + 1
            } else {
                MAX_SAMPLES + 1
            }
        });
        check_size(dims)?;
        resolution_margin(bounds.min, cell, dims)?;
        Ok(GridFrame {
            origin: bounds.min,
            cell,
            dims,
        })
    }
}

fn check_size(dims: [usize; 3]) -> Result<usize, FieldError> {
    let samples = dims
        .iter()
        .try_fold(1usize, |acc, &d| acc.checked_mul(d))
        .unwrap_or(usize::MAX);
    if samples == 0 {
        return Err(FieldError::EmptyGrid { dims });
    }
    if samples > MAX_SAMPLES {
        return Err(FieldError::GridTooLarge {
            dims,
            samples,
            limit: MAX_SAMPLES,
        });
    }
    Ok(samples)
}
