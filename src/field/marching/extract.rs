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
type EdgeKey = u64;

/// What the march found.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MarchStats {
    /// Cells of the padded grid visited.
    pub cells: u64,
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
    let key = |i: isize, j: isize, k: isize, axis: usize| -> EdgeKey {
        let (i, j, k) = ((i + 1) as u64, (j + 1) as u64, (k + 1) as u64);
        ((k * py + j) * px + i) * 3 + axis as u64
    };
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
                            key(i + x as isize, j + y as isize, k + z as isize, edge_axis(e))
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
    let positions: Vec<DVec3> = keys
        .par_iter()
        .map(|&key| vertex(grid, options, key, px, py))
        .collect();
    // Every key of a triangle is in `keys`, which was made from them.
    let index = |k: EdgeKey| {
        let found = keys.binary_search(&k);
        debug_assert!(found.is_ok());
        found.unwrap_or(0)
    };
    let mut soup = PolygonSoup {
        positions,
        polygons: Vec::new(),
    };
    let mut stats = MarchStats {
        cells: (nx as u64 + 1) * (ny as u64 + 1) * (nz as u64 + 1),
        vertices: keys.len() as u64,
        ..MarchStats::default()
    };
    for (triangles, surface_cells) in &slabs {
        stats.surface_cells += surface_cells;
        for t in triangles {
            soup.polygons.push(crate::mesh::Polygon::new(t.map(index)));
        }
    }
    stats.triangles = soup.polygons.len() as u64;
    (soup, stats)
}

/// The surface's vertex on a grid edge: interpolated linearly between the
/// two samples (kept `edge_margin` away from the nodes) or at the midpoint.
fn vertex(grid: &SampleGrid, options: &MarchingOptions, key: EdgeKey, px: u64, py: u64) -> DVec3 {
    let axis = (key % 3) as usize;
    let node = key / 3;
    let (i, j, k) = (
        (node % px) as isize - 1,
        (node / px % py) as isize - 1,
        (node / (px * py)) as isize - 1,
    );
    let mut step = [0isize; 3];
    step[axis] = 1;
    let a = grid.value(i, j, k);
    let b = grid.value(i + step[0], j + step[1], k + step[2]);
    let t = match options.placement {
        Placement::Midpoint => 0.5,
        Placement::Interpolated => {
            // One sample is ≥ ½ and the other < ½, so b − a ≠ 0 and t ∈ [0, 1].
            let t = (THRESHOLD - a) / (b - a);
            t.clamp(options.edge_margin, 1.0 - options.edge_margin)
        }
    };
    let mut offset = DVec3::ZERO;
    offset[axis] = t;
    grid.position(i, j, k) + grid.cell() * offset
}
