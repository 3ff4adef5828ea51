//! The [`Field`] trait: a scalar field whose solid is where it reaches ½.

use glam::DVec3;

use crate::geom::Aabb;

use super::stats::FieldStats;

/// The iso-value of every field: a point is inside the solid where
/// `F(P) ≥ THRESHOLD` and outside where `F(P) < THRESHOLD`.
///
/// With the default falloff a single unit-strength source reaches this value
/// at half its radius, so its solid is a ball of radius `R / 2`.
pub const THRESHOLD: f64 = 0.5;

/// A scalar field `F: ℝ³ → ℝ` whose solid is `{P : F(P) ≥ ½}`.
///
/// Implemented by [`Blobs`](super::Blobs) (sums of point sources) and by
/// [`FieldCsg`](super::FieldCsg) (union, intersection and difference of two
/// fields). Marching cubes reads nothing else.
pub trait Field: Send + Sync {
    /// `F(p)`, adding the work done to `stats`.
    ///
    /// Must be finite for every finite `p`.
    fn value_counted(&self, p: DVec3, stats: &mut FieldStats) -> f64;

    /// A box outside of which `F < ½` everywhere, strictly (also on the
    /// box's own faces); [`Aabb::EMPTY`] when `F < ½` everywhere.
    fn bounds(&self) -> Aabb;

    /// A range holding every value [`value_counted`](Field::value_counted)
    /// returns at a point of the closed box `region` — the values as
    /// computed, rounding included, so that a range entirely below or
    /// entirely at or above ½ decides every sample in the box without
    /// evaluating one. The default, [`ValueRange::ANY`], decides nothing.
    fn bound(&self, region: &Aabb) -> ValueRange {
        let _ = region;
        ValueRange::ANY
    }

    /// Samples the field at every node of `nodes` into `values` (x
    /// fastest, then y, then z; `values.len()` = [`NodeBox::len`]), adding
    /// the work to `stats`.
    ///
    /// Each value must be the one [`value_counted`](Field::value_counted)
    /// gives at [`NodeBox::position`], bit for bit: an implementation may
    /// only share work between the nodes (such as finding the sources near
    /// the box once). The default calls `value_counted` at each node.
    fn sample_nodes(&self, nodes: &NodeBox, values: &mut [f64], stats: &mut FieldStats) {
        let [nx, ny, nz] = nodes.counts;
        debug_assert_eq!(values.len(), nodes.len());
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    values[(k * ny + j) * nx + i] =
                        self.value_counted(nodes.position(i, j, k), stats);
                }
            }
        }
    }

    /// `F(p)`.
    fn value(&self, p: DVec3) -> f64 {
        self.value_counted(p, &mut FieldStats::default())
    }

    /// Whether `p` is inside the solid: `F(p) ≥ ½`.
    fn contains(&self, p: DVec3) -> bool {
        self.value(p) >= THRESHOLD
    }
}

/// A closed range `[low, high]` of field values.
///
/// # Invariants
///
/// `low ≤ high`; either may be infinite, neither is NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ValueRange {
    /// No value is below it.
    pub low: f64,
    /// No value is above it.
    pub high: f64,
}

impl ValueRange {
    /// The range that holds every value.
    pub const ANY: ValueRange = ValueRange {
        low: f64::NEG_INFINITY,
        high: f64::INFINITY,
    };

    /// Whether every value in the range is outside the solid (`< ½`).
    #[must_use]
    pub fn all_outside(&self) -> bool {
        self.high < THRESHOLD
    }

    /// Whether every value in the range is inside the solid (`≥ ½`).
    #[must_use]
    pub fn all_inside(&self) -> bool {
        self.low >= THRESHOLD
    }
}

/// A box of grid nodes: node `(i, j, k)` of the box sits at
/// `origin + cell · (first + (i, j, k))`, for `0 ≤ i < counts[0]` and so on.
///
/// # Invariants
///
/// Every count ≥ 1; `origin` and `cell` finite.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct NodeBox {
    /// The grid's node `(0, 0, 0)`.
    pub origin: DVec3,
    /// The grid's cell edge.
    pub cell: f64,
    /// The grid indices of the box's first node.
    pub first: [isize; 3],
    /// Nodes along x, y and z.
    pub counts: [usize; 3],
}

impl NodeBox {
    /// The position of the box's node `(i, j, k)`: the grid's formula
    /// `origin + cell · (grid i, grid j, grid k)`, monotone in each index.
    #[must_use]
    pub fn position(&self, i: usize, j: usize, k: usize) -> DVec3 {
        node_position(
            self.origin,
            self.cell,
            self.first[0] + i as isize,
            self.first[1] + j as isize,
            self.first[2] + k as isize,
        )
    }

    /// How many nodes.
    #[must_use]
    pub fn len(&self) -> usize {
        self.counts[0] * self.counts[1] * self.counts[2]
    }

    /// Whether the box holds no node (never, by the invariants).
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The closed box spanned by the nodes' positions: it holds every one
    /// of them, the formula being monotone.
    #[must_use]
    pub fn region(&self) -> Aabb {
        let [nx, ny, nz] = self.counts.map(|c| c.saturating_sub(1));
        Aabb {
            min: self.position(0, 0, 0),
            max: self.position(nx, ny, nz),
        }
    }
}

/// The position of grid node `(i, j, k)`: `origin + cell · (i, j, k)`, the
/// one formula every sampler and the vertex placement use, so that the
/// same node always gets the same point. Monotone in each index.
pub(crate) fn node_position(origin: DVec3, cell: f64, i: isize, j: isize, k: isize) -> DVec3 {
    origin + cell * DVec3::new(i as f64, j as f64, k as f64)
}
