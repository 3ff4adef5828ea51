//! The march: every cell of the padded grid looked up in the case table,
//! its triangles emitted with one shared vertex per crossed grid edge.

use glam::DVec3;
use rayon::prelude::*;

use crate::mesh::PolygonSoup;

use super::super::scalar_field::THRESHOLD;
use super::cube::{EDGES, corner_coords, edge_axis};
use super::grid::SampleGrid;
use super::options::{MarchingOptions, Placement};
use super::table::case_table;

/// A grid edge: its lower node in padded coordinates (each shifted by +1,
/// so the padding layer at −1 is 0) and its axis, packed as
/// `((k · ny + j) · nx + i) · 3 + axis` over the padded sizes.
pub(super) type EdgeKey = u64;

/// The packing of grid edges into [`EdgeKey`]s for a grid of `dims`
/// samples: keys increase with `k`, then `j`, then `i`, then the axis.
#[derive(Clone, Copy, Debug)]
pub(super) struct EdgeKeys {
    /// Padded node counts along x and y.
    px: u64,
    py: u64,
}

impl EdgeKeys {
    pub(super) fn new(dims: [usize; 3]) -> EdgeKeys {
        EdgeKeys {
            px: dims[0] as u64 + 2,
            py: dims[1] as u64 + 2,
        }
    }

    /// The key of the edge from node `(i, j, k)` (padded grid, from −1)
    /// along `axis`.
    pub(super) fn key(self, i: isize, j: isize, k: isize, axis: usize) -> EdgeKey {
        let (i, j, k) = ((i + 1) as u64, (j + 1) as u64, (k + 1) as u64);
        ((k * self.py + j) * self.px + i) * 3 + axis as u64
    }

    /// The edge's lower node `(i, j, k)` and its axis.
    pub(super) fn edge(self, key: EdgeKey) -> ([isize; 3], usize) {
        let axis = (key % 3) as usize;
        let node = key / 3;
        (
            [
                (node % self.px) as isize - 1,
                (node / self.px % self.py) as isize - 1,
                (node / (self.px * self.py)) as isize - 1,
            ],
            axis,
        )
    }
}

/// The welded soup of triangles given as edge keys, in order, and the
/// crossed edges' vertices sorted by key (each once).
pub(super) fn welded_soup(
    triangles: &[[EdgeKey; 3]],
    keys: &[EdgeKey],
    positions: Vec<DVec3>,
) -> PolygonSoup {
    // Every key of a triangle is in `keys`, which was made from them.
    let index = |k: EdgeKey| {
        let found = keys.binary_search(&k);
        debug_assert!(found.is_ok());
        found.unwrap_or(0)
    };
    PolygonSoup {
        positions,
        polygons: triangles
            .par_iter()
            .map(|t| crate::mesh::Polygon::new(t.map(index)))
            .collect(),
    }
}

/// What the march found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MarchStats {
    /// Cells of the padded grid visited: all of them on a whole grid
    /// ([`march_grid`](super::march_grid)), those of the marched blocks in
    /// [`try_mesh`](super::try_mesh).
    pub cells: u64,
    /// Blocks of cells the padded grid was cut into ([`try_mesh`](super::try_mesh);
    /// 0 for a whole grid).
    pub blocks: u64,
    /// Blocks that may hold the surface, sampled and marched; the others
    /// were decided all inside or all outside from a bound of the field.
    pub blocks_marched: u64,
    /// Cells the surface passes through (neither all inside nor all
    /// outside).
    pub surface_cells: u64,
    /// Triangles emitted.
    pub triangles: u64,
    /// Vertices (crossed grid edges, each once).
    pub vertices: u64,
}

/// Marches the padded grid and returns the welded triangles, counter-
/// clockwise seen from outside (`F < ½`).
pub(crate) fn march(grid: &SampleGrid, options: &MarchingOptions) -> (PolygonSoup, MarchStats) {
    let [nx, ny, nz] = grid.dims();
    // Padded node counts: one extra layer on each side.
    let (px, py) = (nx as u64 + 2, ny as u64 + 2);
    let edge_keys = EdgeKeys::new(grid.dims());
    let table = case_table();
    // Each node of the padded grid classified once: 1 inside (F ≥ ½).
    let pz = nz as u64 + 2;
    let layer = (px * py) as usize;
    let mut inside = vec![0u8; layer * pz as usize];
    inside
        .par_chunks_mut(layer)
        .enumerate()
        .for_each(|(k, nodes)| {
            for j in 0..py as usize {
                for i in 0..px as usize {
                    let v = grid.value(i as isize - 1, j as isize - 1, k as isize - 1);
                    nodes[j * px as usize + i] = u8::from(v >= THRESHOLD);
                }
            }
        });
    // Corner c of a cell is this far from the cell's lower node.
    let offsets: [usize; 8] = std::array::from_fn(|c| {
        let [x, y, z] = corner_coords(c as u8);
        x as usize + y as usize * px as usize + z as usize * layer
    });
    // Cells run from −1 to n − 1 along each axis (their lower node).
    let slabs: Vec<(Vec<[EdgeKey; 3]>, u64)> = (-1..nz as isize)
        .into_par_iter()
        .map(|k| {
            let mut triangles = Vec::new();
            let mut surface_cells = 0;
            for j in -1..ny as isize {
                let row = ((k + 1) as usize * py as usize + (j + 1) as usize) * px as usize;
                for i in -1..nx as isize {
                    let node = row + (i + 1) as usize;
                    let config = offsets
                        .iter()
                        .enumerate()
                        .fold(0u8, |acc, (c, &o)| acc | inside[node + o] << c);
                    if config == 0 || config == 0xff {
                        continue;
                    }
                    let case = table.case(config);
                    surface_cells += 1;
                    for t in &case.triangles {
                        triangles.push(t.map(|e| {
                            let [x, y, z] = corner_coords(EDGES[usize::from(e)][0]);
                            edge_keys.key(
                                i + x as isize,
                                j + y as isize,
                                k + z as isize,
                                edge_axis(e),
                            )
                        }));
                    }
                }
            }
            (triangles, surface_cells)
        })
        .collect();
    let mut keys: Vec<EdgeKey> = slabs
        .iter()
        .flat_map(|(t, _)| t.iter().flatten().copied())
        .collect();
    keys.par_sort_unstable();
    keys.dedup();
    let margin = grid.vertex_margin();
    let positions: Vec<DVec3> = keys
        .par_iter()
        .map(|&key| {
            let ([i, j, k], axis) = edge_keys.edge(key);
            let mut step = [0isize; 3];
            step[axis] = 1;
            let a = grid.value(i, j, k);
            let b = grid.value(i + step[0], j + step[1], k + step[2]);
            place_vertex(
                a,
                b,
                grid.position(i, j, k),
                grid.cell(),
                axis,
                options,
                margin,
            )
        })
        .collect();
    let triangles: Vec<[EdgeKey; 3]> = slabs.iter().flat_map(|(t, _)| t.iter().copied()).collect();
    let soup = welded_soup(&triangles, &keys, positions);
    let stats = MarchStats {
        cells: (nx as u64 + 1) * (ny as u64 + 1) * (nz as u64 + 1),
        surface_cells: slabs.iter().map(|(_, s)| s).sum(),
        triangles: soup.polygons.len() as u64,
        vertices: keys.len() as u64,
        ..MarchStats::default()
    };
    (soup, stats)
}

/// The surface's vertex on the grid edge from `node` (sample `a`) along
/// `axis` to the next node (sample `b`): interpolated linearly between the
/// two samples (kept `edge_margin`, and at least the grid's `margin` for
/// rounding, away from the nodes) or at the midpoint.
pub(super) fn place_vertex(
    a: f64,
    b: f64,
    node: DVec3,
    cell: f64,
    axis: usize,
    options: &MarchingOptions,
    margin: f64,
) -> DVec3 {
    let t = match options.placement {
        Placement::Midpoint => 0.5,
        Placement::Interpolated => {
            // One sample is ≥ ½ and the other < ½, so b − a ≠ 0 and t ∈ [0, 1].
            let t = (THRESHOLD - a) / (b - a);
            let margin = options.edge_margin.max(margin).min(0.5);
            t.clamp(margin, 1.0 - margin)
        }
    };
    let mut offset = DVec3::ZERO;
    offset[axis] = t;
    node + cell * offset
}
