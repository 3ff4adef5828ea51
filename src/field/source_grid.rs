//! A uniform grid over the sources' balls: for a sample point, the few
//! sources whose radius can reach it.

use glam::DVec3;
use smallvec::SmallVec;

use crate::geom::Aabb;

use super::source::Source;

/// At most this many cells along one axis.
const MAX_CELLS_PER_AXIS: usize = 128;

/// A uniform grid of cells over the union of the sources' reach boxes
/// ([`Source::reach_box`]); each cell lists (compressed, row by row, in
/// increasing source order) the sources whose reach box meets it.
///
/// # Invariants
///
/// A point `p` inside a source's reach box maps (by [`SourceGrid::cell_of`])
/// to a cell that lists the source: registration and lookup use the same
/// monotone map `x ↦ ⌊(x − min) / cell⌋`, so `box.min ≤ p ≤ box.max` implies
/// the source's cell range holds `p`'s cell. Points outside the grid's box are
/// outside every reach box and get no sources. So every source that adds
/// to the field at `p` (rounded squared distance below the rounded squared
/// radius) is listed in `p`'s cell.
#[derive(Clone, Debug)]
pub(crate) struct SourceGrid {
    bounds: Aabb,
    cell: f64,
    dims: [usize; 3],
    /// `starts[c]..starts[c + 1]` is cell `c`'s range of `entries`.
    starts: Vec<u32>,
    entries: Vec<u32>,
}

impl SourceGrid {
    /// The grid over `sources` (checked sources; may be empty).
    pub(crate) fn new(sources: &[Source]) -> SourceGrid {
        let bounds = Aabb::from_points(sources.iter().flat_map(|s| {
            let b = s.reach_box();
            [b.min, b.max]
        }));
        if sources.is_empty() {
            return SourceGrid {
                bounds,
                cell: 1.0,
                dims: [0; 3],
                starts: vec![0],
                entries: Vec::new(),
            };
        }
        let size = bounds.size();
        let n = sources.len() as f64;
        let mean_radius = sources.iter().map(|s| s.radius).sum::<f64>() / n;
        // About a ball's radius per cell, but never more than ~32 cells per
        // source nor MAX_CELLS_PER_AXIS along an axis.
        let by_count = (size.x * size.y * size.z / (32.0 * n)).cbrt();
        let by_axis = size.max_element() / MAX_CELLS_PER_AXIS as f64;
        let cell = mean_radius.max(by_count).max(by_axis);
        let dims = [size.x, size.y, size.z]
            .map(|s| ((s / cell).floor() as usize + 1).min(MAX_CELLS_PER_AXIS + 1));
        let mut grid = SourceGrid {
            bounds,
            cell,
            dims,
            starts: Vec::new(),
            entries: Vec::new(),
        };
        let cells = dims[0] * dims[1] * dims[2];
        let mut counts = vec![0u32; cells + 1];
        grid.for_each_cell_of(sources, |c, _| counts[c + 1] += 1);
        for c in 0..cells {
            counts[c + 1] += counts[c];
        }
        let mut fill = counts.clone();
        let mut entries = vec![0u32; counts[cells] as usize];
        grid.for_each_cell_of(sources, |c, s| {
            entries[fill[c] as usize] = s as u32;
            fill[c] += 1;
        });
        grid.starts = counts;
        grid.entries = entries;
        grid
    }

    /// Calls `visit(cell, source)` for every cell each source's box meets.
    fn for_each_cell_of(&self, sources: &[Source], mut visit: impl FnMut(usize, usize)) {
        for (s, source) in sources.iter().enumerate() {
            let b = source.reach_box();
            let lo = self.axis_cells(b.min);
            let hi = self.axis_cells(b.max);
            for k in lo[2]..=hi[2] {
                for j in lo[1]..=hi[1] {
                    for i in lo[0]..=hi[0] {
                        visit(self.index([i, j, k]), s);
                    }
                }
            }
        }
    }

    /// The monotone map from a point to its (clamped) cell coordinates.
    fn axis_cells(&self, p: DVec3) -> [usize; 3] {
        let q = ((p - self.bounds.min) / self.cell).to_array();
        // NaN (an infinite cell) and negatives go to cell 0.
        std::array::from_fn(|a| (q[a].floor().max(0.0) as usize).min(self.dims[a] - 1))
    }

    fn index(&self, [i, j, k]: [usize; 3]) -> usize {
        (k * self.dims[1] + j) * self.dims[0] + i
    }

    /// The cell holding `p`, or `None` outside the grid's box.
    pub(crate) fn cell_of(&self, p: DVec3) -> Option<usize> {
        if !self.bounds.contains(p) {
            return None;
        }
        Some(self.index(self.axis_cells(p)))
    }

    /// The sources listed for a cell.
    pub(crate) fn sources_in(&self, cell: usize) -> &[u32] {
        &self.entries[self.starts[cell] as usize..self.starts[cell + 1] as usize]
    }

    /// The sources listed in the cells a closed box meets, in increasing
    /// order: every source that adds to the field at a point of `region`.
    pub(crate) fn sources_meeting(&self, region: &Aabb) -> SmallVec<[u32; 16]> {
        let clipped = region.intersection(self.bounds);
        if self.entries.is_empty() || clipped.is_empty() {
            return SmallVec::new();
        }
        let lo = self.axis_cells(clipped.min);
        let hi = self.axis_cells(clipped.max);
        let mut found = SmallVec::new();
        for k in lo[2]..=hi[2] {
            for j in lo[1]..=hi[1] {
                for i in lo[0]..=hi[0] {
                    found.extend_from_slice(self.sources_in(self.index([i, j, k])));
                }
            }
        }
        found.sort_unstable();
        found.dedup();
        found
    }

    /// The grid's box: the union of the sources' reach boxes.
    pub(crate) fn bounds(&self) -> Aabb {
        self.bounds
    }
}
