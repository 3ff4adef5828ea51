//! Gaps along `x` in the columns of the point grid: values of `x` that no
//! triangle of a cell reaches, each with the parity its column has there, so
//! that a point's ray need only test the triangles between the two gaps
//! around it.

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::point_grid::YzGrid;
use super::triangle_records::YzTri;
use crate::query::x_direction::XDirection;
use crate::query::x_ray_triangle::{Step, triangle_step};

/// A plane `x = const` across one grid cell's column that no triangle of the
/// cell meets.
///
/// # Invariants
///
/// - Every triangle listed before [`Gap::split`] in the cell's (sorted)
///   list has its largest `x` below [`Gap::x`], and every triangle from
///   `split` on has its smallest `x` above it (exactly).
/// - [`Gap::winding`] is the signed number of crossings of the `+x` ray
///   from one point `(x, y, z)` of the cell's column, found exactly (with
///   the perturbation of ties) over the triangles in front of it.
///
/// Why one point speaks for the whole column: the points `(y, z)` that
/// [`YzGrid::cell_index`] maps to the cell form a rectangle (the index is
/// monotone in `y` and in `z`), and every triangle whose projection holds
/// a point of it is listed in the cell. So the rectangle at height `x`
/// meets no triangle of the surface at all: on a closed surface every
/// point of it is on the same side, and the parity of its crossings in
/// front is the same (see [`XDirection`] for why the parity of the
/// perturbed ray's crossings is the side). On an oriented closed surface
/// the signed count is the winding number, the same too; only parity
/// reads it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(in crate::query) struct Gap {
    /// The plane's `x`.
    pub x: f64,
    /// How many of the cell's listed triangles lie wholly below `x`.
    pub split: u32,
    /// Signed crossings of the `+x` ray from the plane (see above).
    pub winding: i32,
}

/// The gaps of every cell of a grid, ascending in `x` within a cell.
///
/// # Invariants
///
/// Cell `c` owns `gaps[start[c] .. start[c + 1]]`, in ascending `x` (and
/// so in ascending [`Gap::split`]), each strictly between its neighbours'
/// triangles as [`Gap`] states.
#[derive(Clone, Debug, Default)]
pub(in crate::query) struct CellGaps {
    start: Vec<u32>,
    gaps: Vec<Gap>,
}

/// The triangles of one cell between two gaps, and what the column's
/// crossings beyond them add.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(in crate::query) struct Between {
    /// The listed triangles `first .. end` lie between the gaps.
    pub first: usize,
    /// See [`Between::first`].
    pub end: usize,
    /// Signed crossings of the `+x` ray from the lower gap (0 for none:
    /// the ray from below every triangle crosses the closed surface an
    /// even number of times, see [`XDirection`]).
    pub winding_below: i32,
    /// Signed crossings of the `+x` ray from the upper gap (0 for none).
    pub winding_above: i32,
}

/// Cells per parallel task while finding gaps.
const CELLS_PER_TASK: usize = 1024;

impl CellGaps {
    /// The gaps of every cell of `grid`, whose entries index `tris`.
    pub fn find(grid: &YzGrid, tris: &[YzTri]) -> Self {
        let cells = grid.cell_count();
        let parts: Vec<(Vec<u32>, Vec<Gap>)> = (0..cells.div_ceil(CELLS_PER_TASK))
            .into_par_iter()
            .map(|task| {
                let range = task * CELLS_PER_TASK..((task + 1) * CELLS_PER_TASK).min(cells);
                let mut counts = Vec::with_capacity(range.len());
                let mut gaps = Vec::new();
                let mut scratch = Vec::new();
                for c in range {
                    let before = gaps.len();
                    cell_gaps(grid, tris, c, &mut scratch, &mut gaps);
                    counts.push((gaps.len() - before) as u32);
                }
                (counts, gaps)
            })
            .collect();
        let mut start = Vec::with_capacity(cells + 1);
        start.push(0u32);
        let mut gaps = Vec::with_capacity(parts.iter().map(|p| p.1.len()).sum());
        for (counts, part) in parts {
            for n in counts {
                start.push(start.last().copied().unwrap_or(0) + n);
            }
            gaps.extend(part);
        }
        Self { start, gaps }
    }

    /// The triangles of cell `c` (of `count` listed) that lie between the
    /// nearest gaps below and at or above `x`.
    #[inline]
    pub fn around(&self, c: usize, count: usize, x: f64) -> Between {
        let gaps = &self.gaps[self.start[c] as usize..self.start[c + 1] as usize];
        let above = gaps.iter().take_while(|g| g.x < x).count();
        let (first, winding_below) = match above.checked_sub(1) {
            Some(k) => (gaps[k].split as usize, gaps[k].winding),
            None => (0, 0),
        };
        let (end, winding_above) = match gaps.get(above) {
            Some(g) => (g.split as usize, g.winding),
            None => (count, 0),
        };
        Between {
            first,
            end,
            winding_below,
            winding_above,
        }
    }

    /// Heap bytes.
    pub fn memory_bytes(&self) -> usize {
        self.start.capacity() * std::mem::size_of::<u32>()
            + self.gaps.capacity() * std::mem::size_of::<Gap>()
    }
}

/// Appends to `out` the gaps of cell `c`, using `suffix_min` as scratch.
/// A cell whose centre does not map back to it, or whose planes meet a
/// triangle after all (neither happens; both are refused rather than
/// relied on), gets none, which only costs its points time.
fn cell_gaps(
    grid: &YzGrid,
    tris: &[YzTri],
    c: usize,
    suffix_min: &mut Vec<f64>,
    out: &mut Vec<Gap>,
) {
    let (entries, _) = grid.cell_at(c);
    if entries.len() < 2 {
        return;
    }
    // The smallest `x` of the triangles from each position on.
    suffix_min.clear();
    suffix_min.resize(entries.len(), f64::INFINITY);
    let mut low = f64::INFINITY;
    for (k, e) in entries.iter().enumerate().rev() {
        low = low.min(tris[e.record as usize].min_x());
        suffix_min[k] = low;
    }
    let first = out.len();
    let mut high = f64::NEG_INFINITY;
    for k in 1..entries.len() {
        high = high.max(tris[entries[k - 1].record as usize].max_x());
        let next = suffix_min[k];
        let x = high / 2.0 + next / 2.0;
        if high < x && x < next {
            out.push(Gap {
                x,
                split: k as u32,
                winding: 0,
            });
        }
    }
    if out.len() == first {
        return;
    }
    let Some(centre) = cell_centre(grid, c) else {
        out.truncate(first);
        return;
    };
    // From the top gap down: a gap's count is its own triangles' crossings
    // (those up to the next gap) plus the next gap's count.
    let mut winding = 0;
    let mut end = entries.len();
    for g in (first..out.len()).rev() {
        let Gap { x, split, .. } = out[g];
        let from = DVec3::new(x, centre.x, centre.y);
        for e in &entries[split as usize..end] {
            match triangle_step(&tris[e.record as usize], from, centre, XDirection::Plus) {
                Step::Miss => {}
                Step::Crossing(w) => winding += w,
                Step::OnBoundary => {
                    out.truncate(first);
                    return;
                }
            }
        }
        out[g].winding = winding;
        end = split as usize;
    }
}

/// A point `(y, z)` of the solid's projected box that the grid maps to
/// cell `c`, or `None` if the rounded centre of the cell is not one.
fn cell_centre(grid: &YzGrid, c: usize) -> Option<DVec2> {
    let (column, row) = (c % grid.ny, c / grid.ny);
    let y = (grid.y0 + (column as f64 + 0.5) / grid.inv_hy).clamp(grid.y0, grid.y1);
    let z = (grid.z0 + (row as f64 + 0.5) / grid.inv_hz).clamp(grid.z0, grid.z1);
    (grid.cell_index(y, z) == c).then_some(DVec2::new(y, z))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;
    use crate::query::Accel;
    use crate::query::x_ray::XRay;

    /// Every gap separates its cell's triangles as stated, and its count is
    /// the `+x` winding of points spread over its whole column (not only of
    /// the centre it was found from); a point between two gaps is answered
    /// from either as from no gap at all.
    #[test]
    fn gaps_separate_their_cells_and_speak_for_their_columns() {
        for solid in [builders::sphere(24), builders::cube()] {
            let accel = Accel::new(&solid);
            let (grid, gaps) = accel.grid_and_gaps();
            assert!(!gaps.gaps.is_empty(), "no gaps found");
            let mut u = crate::test_rng::uniform(41);
            for c in 0..grid.cell_count() {
                let (entries, _) = grid.cell_at(c);
                let own = &gaps.gaps[gaps.start[c] as usize..gaps.start[c + 1] as usize];
                for g in own {
                    let split = g.split as usize;
                    for e in &entries[..split] {
                        assert!(accel.tris[e.record as usize].max_x() < g.x);
                    }
                    for e in &entries[split..] {
                        assert!(accel.tris[e.record as usize].min_x() > g.x);
                    }
                    let (column, row) = (c % grid.ny, c / grid.ny);
                    for _ in 0..20 {
                        let y = grid.y0 + (column as f64 + u()) / grid.inv_hy;
                        let z = grid.z0 + (row as f64 + u()) / grid.inv_hz;
                        if grid.cell_index(y, z) != c || y > grid.y1 || z > grid.z1 {
                            continue;
                        }
                        let p = DVec3::new(g.x, y, z);
                        assert_eq!(accel.x_ray(p), XRay::Winding(g.winding), "cell {c} at {p}");
                    }
                }
            }
        }
    }
}
