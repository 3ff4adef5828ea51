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

use crate::mesh::PolygonSoup;

use super::super::error::FieldError;
use super::super::scalar_field::{Field, NodeBox, THRESHOLD, node_position};
use super::super::stats::FieldStats;
use super::cube::{EDGES, corner_coords, edge_axis};
use super::extract::{EdgeKey, EdgeKeys, MarchStats, place_vertex, welded_soup};
use super::grid::GridFrame;
use super::options::MarchingOptions;
use super::table::case_table;

/// Cells along each side of a block.
pub(crate) const BLOCK: usize = 8;

/// More than the most triangles a cell's case has (at most 12 crossed
/// edges, in loops of at least 3: at most 10 triangles).
const TRIANGLES_PER_CELL: u64 = 16;

/// Blocks along each side of a group, bounded before its blocks are.
const GROUP: usize = 4;

/// What one marched block found.
#[derive(Default)]
struct BlockOutput {
    /// Triangles as edge keys, each with its rank in the whole grid's
    /// order: its cell's rank × [`TRIANGLES_PER_CELL`] + its place in the
    /// cell's list.
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
    // Groups of GROUP³ blocks: a group the bound decides is skipped whole.
    let groups = blocks.map(|b| b.div_ceil(GROUP));
    let outputs: Vec<BlockOutput> = (0..groups[0] * groups[1] * groups[2])
        .into_par_iter()
        .flat_map_iter(|g| {
            let group = [
                g % groups[0],
                g / groups[0] % groups[1],
                g / (groups[0] * groups[1]),
            ];
            let first = group.map(|v| v * GROUP);
            let lo = first.map(|v| v * BLOCK);
            let hi: [usize; 3] = std::array::from_fn(|a| (lo[a] + GROUP * BLOCK).min(cells[a]));
            let (samples, padded) = span(frame, lo, hi);
            let mut marched = Vec::new();
            if decided(field, &samples, padded) {
                return marched.into_iter();
            }
            let last: [usize; 3] = std::array::from_fn(|a| (first[a] + GROUP).min(blocks[a]));
            for z in first[2]..last[2] {
                for y in first[1]..last[1] {
                    for x in first[0]..last[0] {
                        if let Some(out) = march_block(field, frame, options, [x, y, z]).transpose()
                        {
                            marched.push(out);
                        }
                    }
                }
            }
            marched.into_iter()
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
    // The rank holds the cell and the triangle's place in the cell's list.
    triangles.par_sort_unstable_by_key(|&(rank, _)| rank);
    let mut vertices: Vec<(EdgeKey, DVec3)> =
        outputs.into_iter().flat_map(|o| o.vertices).collect();
    // An edge shared by two blocks got the same vertex in both.
    vertices.par_sort_unstable_by_key(|&(key, _)| key);
    vertices.dedup_by_key(|&mut (key, _)| key);
    let (keys, positions): (Vec<EdgeKey>, Vec<DVec3>) = vertices.into_iter().unzip();
    let triangles: Vec<[EdgeKey; 3]> = triangles.into_iter().map(|(_, t)| t).collect();
    let soup = welded_soup(&triangles, &keys, positions);
    stats.triangles = soup.polygons.len() as u64;
    stats.vertices = keys.len() as u64;
    Ok((soup, field_stats, stats))
}

/// The samples among the nodes `lo..=hi` of the padded grid (shifted by
/// +1: 0 is the padding layer at −1, `n + 1` the one beyond the last
/// sample), and whether the padding layer is among those nodes. The
/// samples are a non-empty box when `lo ≤ n` and `hi ≥ 1`.
fn span(frame: &GridFrame, lo: [usize; 3], hi: [usize; 3]) -> (NodeBox, bool) {
    let n = frame.dims;
    let padded = (0..3).any(|a| lo[a] == 0 || hi[a] == n[a] + 1);
    let first: [isize; 3] = std::array::from_fn(|a| lo[a].max(1) as isize - 1);
    let last: [isize; 3] = std::array::from_fn(|a| hi[a].min(n[a]) as isize - 1);
    let samples = NodeBox {
        origin: frame.origin,
        cell: frame.cell,
        first,
        counts: std::array::from_fn(|a| (last[a] - first[a]) as usize + 1),
    };
    (samples, padded)
}

/// Whether the field's bound over `samples` shows that no cell of the
/// span crosses the surface: all samples below ½ (the padding reads 0,
/// below too), or all at or above ½ with no padding node.
fn decided(field: &dyn Field, samples: &NodeBox, padded: bool) -> bool {
    let range = field.bound(&samples.region());
    range.all_outside() || (range.all_inside() && !padded)
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
    let lo: [usize; 3] = std::array::from_fn(|a| at[a] * BLOCK);
    let hi: [usize; 3] = std::array::from_fn(|a| (lo[a] + BLOCK).min(n[a] + 1));
    let (samples, padded) = span(frame, lo, hi);
    if decided(field, &samples, padded) {
        return Ok(None);
    }
    let first = samples.first;
    let mut out = BlockOutput::default();
    let mut sampled = vec![0.0; samples.len()];
    field.sample_nodes(&samples, &mut sampled, &mut out.field);
    if let Some(at) = sampled.iter().position(|v| !v.is_finite()) {
        let [cx, cy, _] = samples.counts;
        let local = [at % cx, at / cx % cy, at / (cx * cy)];
        let [i, j, k] = std::array::from_fn(|a| first[a] as usize + local[a]);
        return Err(FieldError::NonFiniteSample {
            i,
            j,
            k,
            value: sampled[at],
        });
    }
    // The block's nodes: the samples, and 0 in the padding layer.
    let m = [hi[0] - lo[0] + 1, hi[1] - lo[1] + 1, hi[2] - lo[2] + 1];
    let mut values = vec![0.0; m[0] * m[1] * m[2]];
    // The first sample's place among the block's nodes.
    let offset: [usize; 3] = std::array::from_fn(|a| (first[a] + 1) as usize - lo[a]);
    let [cx, cy, cz] = samples.counts;
    for z in 0..cz {
        for y in 0..cy {
            let from = (z * cy + y) * cx;
            let to = ((z + offset[2]) * m[1] + y + offset[1]) * m[0] + offset[0];
            values[to..to + cx].copy_from_slice(&sampled[from..from + cx]);
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
                for (place, t) in (0u64..).zip(&table.case(config).triangles) {
                    out.triangles.push((
                        rank * TRIANGLES_PER_CELL + place,
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
    // Checked when the frame was made.
    let margin =
        super::grid::resolution_margin(frame.origin, frame.cell, frame.dims).unwrap_or(0.5);
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
                margin,
            );
            (key, position)
        })
        .collect();
    Ok(Some(out))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_case_fits_the_triangle_places_of_a_cell() {
        let table = case_table();
        for config in 0..=255u8 {
            let count = table.case(config).triangles.len() as u64;
            assert!(count < TRIANGLES_PER_CELL, "case {config}: {count}");
        }
    }
}
