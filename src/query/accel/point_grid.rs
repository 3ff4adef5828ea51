//! The uniform grid over the `yz` projection that point classification
//! walks along `±x` (see ARCHITECTURE.md, "The point grid").

use std::ops::RangeInclusive;

use rayon::prelude::*;

use crate::geom::Aabb;
use crate::spatial::raw::huge_pages::{HugeVec, collapse_into_huge_pages};
use crate::spatial::rounding::{f32_down, f32_up, f64_above};

use super::triangle_records::YzTri;

/// A uniform grid over the `yz` projection of the solid's bounding box; each
/// cell lists the triangles whose projection can hold a point of the cell
/// (see [`TriangleCut::row_columns`]: the cells the projected triangle meets, not every
/// cell of its projected box), by ascending lower bound of `x`, and a bound on their `x` extents: so the
/// triangles a `−x` ray from a point can meet are a prefix of the cell's list
/// and those a `+x` ray can meet are within a suffix.
///
/// # Invariants
///
/// - Cell `c` owns `entries[cell_start[c] .. cell_start[c + 1]]`, sorted by
///   ascending [`GridEntry::x`], ties by record.
/// - Every triangle whose closed projection holds a point `(y, z)` of the
///   solid's projected box is listed in the cell
///   [`YzGrid::cell_index`]`(y, z)`.
/// - `extent[c] ≥ max x − entry.x` for every triangle listed in cell `c`
///   (exactly, not only as rounded), so a triangle whose largest `x` is at
///   least `x` has `entry.x ≥ x − extent[c]`.
#[derive(Clone, Debug)]
pub(in crate::query) struct YzGrid {
    pub y0: f64,
    pub z0: f64,
    pub y1: f64,
    pub z1: f64,
    pub inv_hy: f64,
    pub inv_hz: f64,
    pub ny: usize,
    pub nz: usize,
    pub cell_start: Vec<u32>,
    pub entries: HugeVec<GridEntry>,
    pub extent: Vec<f32>,
}

/// One triangle listed in a grid cell: its `yz` record and its smallest `x`
/// rounded down to `f32` (8 bytes).
#[derive(Clone, Copy, Debug, Default)]
pub(in crate::query) struct GridEntry {
    /// A lower bound on the triangle's smallest `x`.
    pub x: f32,
    /// Index into the accel's triangles.
    pub record: u32,
}

impl YzGrid {
    /// The cell column of `y` (monotone in `y`, clamped).
    #[inline]
    pub fn col(&self, y: f64) -> usize {
        (((y - self.y0) * self.inv_hy) as usize).min(self.ny - 1)
    }

    /// The cell row of `z` (monotone in `z`, clamped).
    #[inline]
    pub fn row(&self, z: f64) -> usize {
        (((z - self.z0) * self.inv_hz) as usize).min(self.nz - 1)
    }

    /// The index of the cell holding `(y, z)`.
    #[inline]
    pub fn cell_index(&self, y: f64, z: f64) -> usize {
        self.row(z) * self.ny + self.col(y)
    }

    /// The triangles of cell `c` (an index from [`YzGrid::cell_index`]) and
    /// the bound on their `x` extents (see [`YzGrid`]).
    #[inline]
    pub fn cell_at(&self, c: usize) -> (&[GridEntry], f32) {
        let range = self.cell_start[c] as usize..self.cell_start[c + 1] as usize;
        (&self.entries[range], self.extent[c])
    }

    /// The number of cells, `ny · nz`.
    #[inline]
    pub fn cell_count(&self) -> usize {
        self.ny * self.nz
    }

    /// Triangle references held by the cells.
    pub fn entries(&self) -> usize {
        self.entries.len()
    }

    /// Heap bytes.
    pub fn memory_bytes(&self) -> usize {
        (self.cell_start.capacity() + self.extent.capacity()) * std::mem::size_of::<u32>()
            + self.entries.memory_bytes()
    }
}

/// Grid cells per triangle on a small mesh: with the gaps along `x` of
/// each cell's column (`cell_gaps`), smaller cells leave a point's ray
/// fewer triangles between the gaps around it. A layout choice, not a
/// tolerance: it decides no answer.
const CELLS_PER_TRIANGLE_SMALL: f64 = 4.0;
/// The most cells [`CELLS_PER_TRIANGLE_SMALL`] may ask for; a mesh with
/// more triangles than this gets one cell per triangle (the grid's
/// memory and build time then matter more than its last few tests per
/// point).
const FINE_GRID_CELLS: f64 = (1u64 << 18) as f64;
/// The largest ratio of the grid's cell counts along `y` and `z`: a mesh
/// that is flat in one of them still gets a grid of sensible shape. A layout
/// choice, not a tolerance: it decides no answer.
const MAX_GRID_ASPECT: f64 = 1e6;

/// The most grid entries per triangle, on average, that a grid of the
/// first-chosen size may hold before its sides are halved (see
/// [`coarsening`]). A layout choice, not a tolerance: it decides no answer.
const MAX_ENTRIES_PER_TRIANGLE: f64 = 32.0;

/// How many times to halve both sides of a grid of `inv_h` cells per unit
/// (`y`, `z`), whose origin is `origin`, so that the triangles `yz` are
/// expected to take at most [`MAX_ENTRIES_PER_TRIANGLE`] entries each on
/// average.
///
/// A triangle whose projection spans `r` rows, `c` columns and `a` cells of
/// area meets about `r + c + a + 1` cells: a long sliver (a cone's side from
/// apex to rim, a pole's, a cap's fan seen edge-on) takes one grid side's
/// worth, and thousands of them around one vertex fill a grid of one cell
/// per triangle with a hundred entries per triangle and more. Halving the
/// sides halves `r + c` and quarters `a`, so the estimate is summed once and
/// the smallest number of halvings that brings it within the budget is
/// taken: the cells then hold more triangles each (a point's ray tests more
/// candidates) but the grid's size, and its build time, stay a bounded
/// multiple of the triangle count. A mesh of evenly sized triangles (a
/// sphere, a scanned model) takes a few entries per triangle and keeps the
/// first size.
fn coarsening(yz: &[YzTri], origin: (f64, f64), inv_h: (f64, f64)) -> u32 {
    let (lines, area) = yz
        .par_iter()
        .with_min_len(4096)
        .map(|t| {
            let u = t.y.map(|y| (y - origin.0) * inv_h.0);
            let w = t.z.map(|z| (z - origin.1) * inv_h.1);
            let span = |x: [f64; 3]| x[0].max(x[1]).max(x[2]) - x[0].min(x[1]).min(x[2]);
            let area = ((u[1] - u[0]) * (w[2] - w[0]) - (u[2] - u[0]) * (w[1] - w[0])).abs() / 2.0;
            (span(u) + span(w), area)
        })
        .filter(|(l, a)| l.is_finite() && a.is_finite())
        .reduce(|| (0.0, 0.0), |x, y| (x.0 + y.0, x.1 + y.1));
    let budget = MAX_ENTRIES_PER_TRIANGLE * yz.len() as f64;
    let mut halvings = 0;
    let mut scale = 1.0;
    while halvings < 14 && lines * scale + area * scale * scale + yz.len() as f64 > budget {
        halvings += 1;
        scale /= 2.0;
    }
    halvings
}

/// The grid of the triangles `yz` (in accel order) over the box `bounds`.
pub(in crate::query) fn build_grid(yz: &[YzTri], bounds: Aabb) -> YzGrid {
    let (y0, z0, y1, z1) = if bounds.is_empty() {
        (0.0, 0.0, 1.0, 1.0)
    } else {
        (bounds.min.y, bounds.min.z, bounds.max.y, bounds.max.z)
    };
    let (wy, wz) = (
        (y1 - y0).max(f64::MIN_POSITIVE),
        (z1 - z0).max(f64::MIN_POSITIVE),
    );
    let triangles = yz.len() as f64;
    let cells = (triangles * CELLS_PER_TRIANGLE_SMALL)
        .min(triangles.max(FINE_GRID_CELLS))
        .clamp(1.0, 64.0e6);
    let aspect = (wy / wz).clamp(1.0 / MAX_GRID_ASPECT, MAX_GRID_ASPECT);
    // At most 2¹⁴ cells either way (so a cell index fits `u16`).
    let ny = ((cells * aspect).sqrt().round() as usize).clamp(1, 1 << 14);
    let nz = ((cells / ny as f64).round() as usize).clamp(1, 1 << 14);
    let halvings = coarsening(yz, (y0, z0), (ny as f64 / wy, nz as f64 / wz));
    let (ny, nz) = ((ny >> halvings).max(1), (nz >> halvings).max(1));
    let mut grid = YzGrid {
        y0,
        z0,
        y1,
        z1,
        inv_hy: ny as f64 / wy,
        inv_hz: nz as f64 / wz,
        ny,
        nz,
        cell_start: vec![0; ny * nz + 1],
        entries: HugeVec::with_capacity(0),
        extent: vec![0.0; ny * nz],
    };
    let map = CellMap::of(&grid);
    // Each triangle's cells: columns `c0..=c1`, rows `r0..=r1` (its
    // projected box mapped by the monotone `col` and `row`).
    let spans: Vec<[u16; 4]> = yz
        .par_iter()
        .with_min_len(4096)
        .map(|t| {
            let ymin = t.y[0].min(t.y[1]).min(t.y[2]);
            let ymax = t.y[0].max(t.y[1]).max(t.y[2]);
            let zmin = t.z[0].min(t.z[1]).min(t.z[2]);
            let zmax = t.z[0].max(t.z[1]).max(t.z[2]);
            [
                grid.col(ymin),
                grid.col(ymax),
                grid.row(zmin),
                grid.row(zmax),
            ]
            .map(|k| k as u16)
        })
        .collect();
    // Rows are split into bands; a band's cells are a contiguous range (row
    // major), so each band counts, fills and sorts its own part in parallel.
    let bands = (4 * rayon::current_num_threads()).clamp(1, nz);
    let band_rows = |b: usize| (b * nz / bands, (b + 1) * nz / bands);
    let rows_of = |span: &[u16; 4], (lo, hi): (usize, usize)| {
        usize::from(span[2]).max(lo)..(usize::from(span[3]) + 1).min(hi)
    };
    {
        let mut counts: Vec<&mut [u32]> = Vec::with_capacity(bands);
        let mut rest: &mut [u32] = &mut grid.cell_start[1..];
        for b in 0..bands {
            let (lo, hi) = band_rows(b);
            let (head, tail) = std::mem::take(&mut rest).split_at_mut((hi - lo) * ny);
            counts.push(head);
            rest = tail;
        }
        counts.into_par_iter().enumerate().for_each(|(b, count)| {
            let (lo, hi) = band_rows(b);
            for (t, span) in yz.iter().zip(&spans) {
                let rows = rows_of(span, (lo, hi));
                if rows.is_empty() {
                    continue;
                }
                let cut = map.cut(t, span);
                for r in rows {
                    for c in cut.row_columns(r) {
                        count[(r - lo) * ny + c] += 1;
                    }
                }
            }
        });
    }
    for i in 0..ny * nz {
        grid.cell_start[i + 1] += grid.cell_start[i];
    }
    let total = grid.cell_start[ny * nz] as usize;
    // Initialised in parallel: for a large mesh this is mostly page faults
    // (fewer of them on huge pages, which the point queries' random reads
    // want too).
    let mut entries = HugeVec::from_par_iter(
        (0..total)
            .into_par_iter()
            .with_min_len(1 << 16)
            .map(|_| GridEntry::default()),
    );
    let mut parts = Vec::with_capacity(bands);
    let mut rest: &mut [GridEntry] = &mut entries;
    let mut extent_rest: &mut [f32] = &mut grid.extent;
    for b in 0..bands {
        let (lo, hi) = band_rows(b);
        let len = (grid.cell_start[hi * ny] - grid.cell_start[lo * ny]) as usize;
        let (head, tail) = std::mem::take(&mut rest).split_at_mut(len);
        let (extent_head, extent_tail) =
            std::mem::take(&mut extent_rest).split_at_mut((hi - lo) * ny);
        parts.push((head, extent_head));
        rest = tail;
        extent_rest = extent_tail;
    }
    let cell_start = &grid.cell_start;
    parts
        .into_par_iter()
        .enumerate()
        .for_each(|(b, (part, extent))| {
            let (lo, hi) = band_rows(b);
            let base = cell_start[lo * ny];
            let mut fill: Vec<u32> = cell_start[lo * ny..hi * ny]
                .iter()
                .map(|&s| s - base)
                .collect();
            for (i, (t, span)) in yz.iter().zip(&spans).enumerate() {
                let rows = rows_of(span, (lo, hi));
                if rows.is_empty() {
                    continue;
                }
                let min_x = f32_down(t.min_x());
                // At least `max x − min_x` exactly: the rounded difference
                // is within half an ulp of it, the next `f64` above it is not
                // below it, and rounding up to `f32` keeps that.
                let reach = f32_up(f64_above(t.max_x() - f64::from(min_x)));
                let cut = map.cut(t, span);
                for r in rows {
                    for c in cut.row_columns(r) {
                        let cell = (r - lo) * ny + c;
                        part[fill[cell] as usize] = GridEntry {
                            x: min_x,
                            record: i as u32,
                        };
                        fill[cell] += 1;
                        extent[cell] = extent[cell].max(reach);
                    }
                }
            }
            // Each cell's list by ascending `x`: filled in record order, so a
            // stable sort breaks ties by record.
            for cell in lo * ny..hi * ny {
                let s = (cell_start[cell] - base) as usize;
                let e = (cell_start[cell + 1] - base) as usize;
                sort_by_x(&mut part[s..e]);
            }
        });
    entries.collapse();
    collapse_into_huge_pages(&grid.cell_start);
    collapse_into_huge_pages(&grid.extent);
    grid.entries = entries;
    grid
}

/// The map from `yz` to cell coordinates that [`YzGrid::col`] and
/// [`YzGrid::row`] round down: `u = (y − y0)·inv_hy`, `w = (z − z0)·inv_hz`,
/// each computed with the same two roundings.
#[derive(Clone, Copy, Debug)]
struct CellMap {
    y0: f64,
    z0: f64,
    inv_hy: f64,
    inv_hz: f64,
    nz: usize,
}

/// How far (in cells) [`TriangleCut::row_columns`] widens a row and a
/// triangle's reach in it, to cover the roundings of the cell coordinates.
/// Every cell coordinate of a point of the solid's box is at most `2¹⁵`
/// (`ny, nz ≤ 2¹⁴`), and is computed with two roundings of relative size
/// `2⁻⁵³`, so it is within `2⁻³⁷` of the exact affine image; the crossing of
/// an edge with a row's border adds roundings of at most a few `2⁻³⁸` times
/// coordinates below `2¹⁶`. Their sum is below `2⁻³²`: this margin covers it
/// many times over. It makes a triangle listed in a few more cells, never in
/// fewer, and decides no answer.
const ROUNDING_MARGIN: f64 = 1.0 / (1u64 << 20) as f64;

/// The largest cell coordinate [`TriangleCut::row_columns`] computes with (see
/// [`ROUNDING_MARGIN`]); beyond it a triangle keeps its box's columns.
const CELL_COORDINATE_LIMIT: f64 = (1u64 << 15) as f64;

impl CellMap {
    fn of(grid: &YzGrid) -> Self {
        Self {
            y0: grid.y0,
            z0: grid.z0,
            inv_hy: grid.inv_hy,
            inv_hz: grid.inv_hz,
            nz: grid.nz,
        }
    }

    /// The triangle `t`, whose projected box in cells is `span` (columns
    /// `span[0]..=span[1]`, rows `span[2]..=span[3]`), ready to be cut into
    /// rows by [`TriangleCut::row_columns`].
    fn cut(&self, t: &YzTri, span: &[u16; 4]) -> TriangleCut {
        let (c0, c1) = (usize::from(span[0]), usize::from(span[1]));
        let u = t.y.map(|y| (y - self.y0) * self.inv_hy);
        let w = t.z.map(|z| (z - self.z0) * self.inv_hz);
        let tame = |x: f64| x.abs() <= CELL_COORDINATE_LIMIT;
        let whole = c0 == c1
            || span[2] == span[3]
            || !(u.iter().all(|&x| tame(x)) && w.iter().all(|&x| tame(x)));
        TriangleCut {
            u,
            w,
            columns: (c0, c1),
            whole,
            last_row: self.nz - 1,
        }
    }
}

/// A triangle in cell coordinates, cut into the grid's rows.
#[derive(Clone, Copy, Debug)]
struct TriangleCut {
    /// The corners' cell coordinates, as [`CellMap`] computes them.
    u: [f64; 3],
    w: [f64; 3],
    /// The columns of the triangle's projected box.
    columns: (usize, usize),
    /// Whether every row keeps the box's columns (one row or column, or
    /// coordinates beyond [`CELL_COORDINATE_LIMIT`]).
    whole: bool,
    /// The grid's last row.
    last_row: usize,
}

impl TriangleCut {
    /// The columns of row `r` (one of the rows of the triangle's box) that
    /// list the triangle: every column `c` such that a point of its closed
    /// projection lies in cell `(c, r)`, and perhaps a few more.
    ///
    /// Why that holds: let `A` be the exact affine map whose rounding gives
    /// the cell coordinates `(u, w)`. A point `q` of the projected triangle
    /// has `A(q)` in the triangle of the exact images of the corners, each
    /// within `δ = 2⁻³⁷` (per coordinate) of its computed image, so `A(q)` is
    /// within `δ` of a point `t′` of the triangle of computed corners, and
    /// the computed `(u, w)` of `q` within `2δ` of `t′`. If `q` is in row `r`
    /// (computed `w ∈ [r, r + 1)`), `t′` lies in the slab
    /// `r − m ≤ w ≤ r + 1 + m` (`m` = [`ROUNDING_MARGIN`]), so `t′.u` is
    /// within the `u` range of the computed triangle cut by that slab, and
    /// `q`'s column is that range widened by `m`, rounded down. The first
    /// row reaches down to `−∞` and the last up to `+∞`, as the clamping of
    /// [`YzGrid::row`] does.
    fn row_columns(&self, r: usize) -> RangeInclusive<usize> {
        let (c0, c1) = self.columns;
        if self.whole {
            return c0..=c1;
        }
        let (u, w) = (self.u, self.w);
        let bottom = if r == 0 {
            f64::NEG_INFINITY
        } else {
            r as f64 - ROUNDING_MARGIN
        };
        let top = if r >= self.last_row {
            f64::INFINITY
        } else {
            (r + 1) as f64 + ROUNDING_MARGIN
        };
        let (mut low, mut high) = (f64::INFINITY, f64::NEG_INFINITY);
        for i in 0..3 {
            if w[i] >= bottom && w[i] <= top {
                low = low.min(u[i]);
                high = high.max(u[i]);
            }
            let j = (i + 1) % 3;
            for level in [bottom, top] {
                if (w[i] < level && w[j] > level) || (w[i] > level && w[j] < level) {
                    let s = (level - w[i]) / (w[j] - w[i]);
                    let cross = u[i] + s * (u[j] - u[i]);
                    low = low.min(cross);
                    high = high.max(cross);
                }
            }
        }
        if low > high {
            // Not reached by the rows of the triangle's box; kept whole
            // rather than relying on that.
            return c0..=c1;
        }
        // `as` rounds a non-negative value down and takes a negative one to 0.
        let column = |x: f64| (x as usize).clamp(c0, c1);
        column(low - ROUNDING_MARGIN)..=column(high + ROUNDING_MARGIN)
    }
}

/// Stable sort of a cell's entries by ascending [`GridEntry::x`]: most
/// cells hold a handful of entries, for which insertion sort is the
/// fastest; a cell that many triangles cross (around a vertex where many
/// faces meet) takes the library's stable sort. The bounds are never NaN
/// (rounded from finite coordinates).
fn sort_by_x(entries: &mut [GridEntry]) {
    if entries.len() > INSERTION_SORT_LIMIT {
        entries.sort_by(|a, b| a.x.partial_cmp(&b.x).unwrap_or(std::cmp::Ordering::Equal));
        return;
    }
    for i in 1..entries.len() {
        let e = entries[i];
        let mut j = i;
        while j > 0 && e.x < entries[j - 1].x {
            entries[j] = entries[j - 1];
            j -= 1;
        }
        entries[j] = e;
    }
}

/// The longest cell list [`sort_by_x`] sorts by insertion.
const INSERTION_SORT_LIMIT: usize = 32;
