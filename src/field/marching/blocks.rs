//! Marching cubes by blocks: only the parts of the grid the surface may
//! pass through are sampled and marched.
//!
//! The cells of the padded grid are cut into blocks of [`BLOCK`]³ cells.
//! Before a block is sampled, the field bounds its values over the block's
//! nodes ([`Field::bound`], for blobs from the sources the source grid
//! lists near the block). A block whose nodes are all certainly below ½,
//! or all certainly at or above ½ (and not in the padding layer, which
//! reads 0), holds no crossed edge: every one of its cells is all outside
//! or all inside, and it is skipped. The other blocks are sampled node by
//! node and marched.
//!
//! # Invariant: the same output as the whole grid
//!
//! A sampled node gets the value the whole-grid sampler gives it (the same
//! position formula, the same field call), a cell's configuration reads
//! only its own eight nodes, and the bound decides a skipped block's nodes
//! the way their computed values would. So every cell gets the same
//! configuration as on the whole grid, and every crossed edge the same
//! vertex. Triangles are put back in the whole grid's order (by cell, `z`
//! slowest; a stable sort keeps each cell's own order) and vertices sorted
//! by edge key, so the soup is the one [`march_grid`](super::march_grid)
//! makes from [`SampleGrid::try_sample`](super::SampleGrid::try_sample),
//! bit for bit (tested on random blob fields).

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::Aabb;
use crate::mesh::PolygonSoup;

use super::super::error::FieldError;
use super::super::scalar_field::{Field, THRESHOLD};
use super::super::stats::FieldStats;
use super::cube::{EDGES, corner_coords, edge_axis};
use super::extract::{EdgeKey, EdgeKeys, MarchStats, place_vertex, welded_soup};
use super::grid::{GridFrame, node_position};
use super::options::MarchingOptions;
use super::table::case_table;

/// Cells along each side of a block.
pub(crate) const BLOCK: usize = 8;

/// What one marched block found.
#[derive(Default)]
struct BlockOutput {
    /// Triangles as edge keys, each with its cell's rank in the whole
    /// grid's order.
    triangles: Vec<(u64, [EdgeKey; 3])>,
    /// The block's crossed edges and their vertices, sorted by key.
    vertices: Vec<(EdgeKey, DVec3)>,
    cells: u64,
    surface_cells: u64,
    field: FieldStats,
}

/// Samples and marches the blocks of `frame`'s padded grid that may hold
/// the surface.
///
/// # Errors
///
/// [`FieldError::NonFiniteSample`] when the field returns NaN or an
/// infinity at a sample (one such sample is named).
pub(crate) fn march_blocks(
    field: &dyn Field,
    frame: &GridFrame,
    options: &MarchingOptions,
) -> Result<(PolygonSoup, FieldStats, MarchStats), FieldError> {
    // Cells of the padded grid along each axis: lower nodes −1 to n − 1.
    let cells = frame.dims.map(|n| n + 1);
    let blocks = cells.map(|c| c.div_ceil(BLOCK));
    let block_count = blocks[0] * blocks[1] * blocks[2];
    let outputs: Vec<BlockOutput> = (0..block_count)
        .into_par_iter()
        .filter_map(|b| {
            let at = [
                b % blocks[0],
                b / blocks[0] % blocks[1],
                b / (blocks[0] * blocks[1]),
            ];
            march_block(field, frame, options, at).transpose()
        })
        .collect::<Result<_, _>>()?;
    let mut field_stats = FieldStats::default();
    let mut stats = MarchStats {
        blocks: block_count as u64,
        blocks_marched: outputs.len() as u64,
        ..MarchStats::default()
    };
    for o in &outputs {
        field_stats += o.field;
        stats.cells += o.cells;
        stats.surface_cells += o.surface_cells;
    }
    let mut triangles: Vec<(u64, [EdgeKey; 3])> = outputs
        .iter()
        .flat_map(|o| o.triangles.iter().copied())
        .collect();
    // Stable: a cell's triangles keep their table order.
    triangles.par_sort_by_key(|&(rank, _)| rank);
    let mut vertices: Vec<(EdgeKey, DVec3)> =
        outputs.into_iter().flat_map(|o| o.vertices).collect();
    // An edge shared by two blocks got the same vertex in both.
    vertices.par_sort_unstable_by_key(|&(key, _)| key);
    vertices.dedup_by_key(|&mut (key, _)| key);
    let (keys, positions): (Vec<EdgeKey>, Vec<DVec3>) = vertices.into_iter().unzip();
    let soup = welded_soup(triangles.iter().map(|&(_, t)| t), &keys, positions);
    stats.triangles = soup.polygons.len() as u64;
    stats.vertices = keys.len() as u64;
    Ok((soup, field_stats, stats))
}

/// Samples and marches block `at` (block coordinates), or `None` when the
/// field's bound shows that the surface does not pass through it.
fn march_block(
    field: &dyn Field,
    frame: &GridFrame,
    options: &MarchingOptions,
    at: [usize; 3],
) -> Result<Option<BlockOutput>, FieldError> {
    let n = frame.dims;
    // Nodes of the block in padded coordinates shifted by +1 (0 is the
    // padding layer at −1, n + 1 the one beyond the last sample):
    // lo..=hi, its cells lo..hi.
    let lo: [usize; 3] = std::array::from_fn(|a| at[a] * BLOCK);
    let hi: [usize; 3] = std::array::from_fn(|a| (lo[a] + BLOCK).min(n[a] + 1));
    let padded = (0..3).any(|a| lo[a] == 0 || hi[a] == n[a] + 1);
    // The block's real samples, shifted back: a non-empty range, as
    // lo ≤ n and hi ≥ 1 (the node counts are at least 1).
    let first: [isize; 3] = std::array::from_fn(|a| lo[a].max(1) as isize - 1);
    let last: [isize; 3] = std::array::from_fn(|a| hi[a].min(n[a]) as isize - 1);
    // The position formula is monotone in each index, so this box holds
    // every sample point of the block.
    let region = Aabb {
        min: node_position(frame.origin, frame.cell, first[0], first[1], first[2]),
        max: node_position(frame.origin, frame.cell, last[0], last[1], last[2]),
    };
    let range = field.bound(&region);
    if range.all_outside() || (range.all_inside() && !padded) {
        return Ok(None);
    }
    let m = [hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1];
    let mut out = BlockOutput::default();
    let mut values = vec![0.0; m[0] * m[1] * m[2]];
    for z in 0..m[2] {
        for y in 0..m[1] {
            for x in 0..m[0] {
                let s = [lo[0] + x, lo[1] + y, lo[2] + z];
                if (0..3).all(|a| (1..=n[a]).contains(&s[a])) {
                    let p = node_position(
                        frame.origin,
                        frame.cell,
                        s[0] as isize - 1,
                        s[1] as isize - 1,
                        s[2] as isize - 1,
                    );
                    let value = field.value_counted(p, &mut out.field);
                    if !value.is_finite() {
                        let [i, j, k] = s.map(|v| v - 1);
                        return Err(FieldError::NonFiniteSample { i, j, k, value });
                    }
                    values[(z * m[1] + y) * m[0] + x] = value;
                }
            }
        }
    }
    let inside: Vec<u8> = values.iter().map(|&v| u8::from(v >= THRESHOLD)).collect();
    let offsets: [usize; 8] = std::array::from_fn(|c| {
        let [x, y, z] = corner_coords(c as u8);
        x as usize + (y as usize + z as usize * m[1]) * m[0]
    });
    let table = case_table();
    let keys = EdgeKeys::new(n);
    let rank_row = (n[0] + 1) as u64;
    let rank_layer = rank_row * (n[1] + 1) as u64;
    for z in 0..m[2] - 1 {
        for y in 0..m[1] - 1 {
            for x in 0..m[0] - 1 {
                out.cells += 1;
                let node = (z * m[1] + y) * m[0] + x;
                let config = offsets
                    .iter()
                    .enumerate()
                    .fold(0u8, |acc, (c, &o)| acc | inside[node + o] << c);
                if config == 0 || config == 0xff {
                    continue;
                }
                out.surface_cells += 1;
                // The cell's lower node, unshifted, and its rank.
                let [i, j, k] = [lo[0] + x, lo[1] + y, lo[2] + z].map(|s| s as isize - 1);
                let rank = (lo[2] + z) as u64 * rank_layer
                    + (lo[1] + y) as u64 * rank_row
                    + (lo[0] + x) as u64;
                for t in &table.case(config).triangles {
                    out.triangles.push((
                        rank,
                        t.map(|e| {
                            let [cx, cy, cz] = corner_coords(EDGES[usize::from(e)][0]);
                            keys.key(
                                i + cx as isize,
                                j + cy as isize,
                                k + cz as isize,
                                edge_axis(e),
                            )
                        }),
                    ));
                }
            }
        }
    }
    let mut crossed: Vec<EdgeKey> = out.triangles.iter().flat_map(|(_, t)| *t).collect();
    crossed.sort_unstable();
    crossed.dedup();
    // Both nodes of a crossed edge are nodes of this block (the edge is an
    // edge of one of its cells).
    let value_at = |[i, j, k]: [isize; 3]| {
        let local = [i, j, k].map(|v| (v + 1) as usize);
        values[((local[2] - lo[2]) * m[1] + (local[1] - lo[1])) * m[0] + (local[0] - lo[0])]
    };
    out.vertices = crossed
        .into_iter()
        .map(|key| {
            let (node, axis) = keys.edge(key);
            let mut next = node;
            next[axis] += 1;
            let position = place_vertex(
                value_at(node),
                value_at(next),
                node_position(frame.origin, frame.cell, node[0], node[1], node[2]),
                frame.cell,
                axis,
                options,
            );
            (key, position)
        })
        .collect();
    Ok(Some(out))
}
