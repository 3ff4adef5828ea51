//! The self-intersection check restricted to the pairs that involve a
//! changed face: for a surface made by editing surfaces already known not
//! to intersect themselves or each other (a boolean's result), only the
//! faces the edit touched can meet anything.
//!
//! Every triangle of a changed face is indexed in a BVH of its own; every
//! triangle of the surface asks that BVH for the changed triangles whose
//! boxes overlap its own and that its triangle may meet (opening only the
//! nodes whose boxes it may meet), and each such pair gets the same exact test as
//! in the full check ([`triangles_meet_beyond_shared`], which also holds the
//! rules for triangles sharing a vertex or an edge). Pairs of two unchanged
//! triangles are not tested: the caller vouches for them.

use rayon::prelude::*;

use super::super::super::context::Context;
use super::bounds;
use super::pair::triangles_meet_beyond_shared;
use super::triangles::Triangle;
use crate::geom::{Aabb, TriangleFilter};
use crate::spatial::Bvh;

/// The pairs of faces (smaller index first, sorted, each once) of which two
/// triangles meet beyond what they share, at least one of the two from a
/// face with `changed[face]`.
pub(super) fn pairs_near_changed(
    ctx: &Context,
    triangles: &[Triangle],
    changed: &[bool],
) -> Vec<(usize, usize)> {
    let is_changed = |t: &Triangle| changed.get(t.face).copied().unwrap_or(true);
    let fresh: Vec<u32> = (0..triangles.len() as u32)
        .filter(|&t| is_changed(&triangles[t as usize]))
        .collect();
    if fresh.is_empty() {
        return Vec::new();
    }
    let boxes: Vec<Aabb> = triangles.par_iter().map(|t| bounds(ctx, t)).collect();
    let fresh_boxes: Vec<Aabb> = fresh.iter().map(|&t| boxes[t as usize]).collect();
    let (bvh, order) = Bvh::build(&fresh_boxes);
    let reach = bvh.bounds();
    let mut pairs: Vec<(usize, usize)> = (0..triangles.len())
        .into_par_iter()
        .flat_map_iter(|a| {
            let mut found = Vec::new();
            let query = boxes[a];
            if query.intersection(reach).is_empty() {
                return found;
            }
            let ta = &triangles[a];
            let a_fresh = is_changed(ta);
            // Only the nodes and items whose boxes the triangle may meet
            // (`TriangleFilter` never rejects one it meets): a pair
            // with a common point has one in the other's box, so no pair
            // the test would report is left out, and a sliver opens only
            // the nodes along it.
            let filter = TriangleFilter::new(&ta.vertices.map(|v| ctx.position(v)));
            bvh.leaves_overlapping_where(
                &query,
                |b| filter.may_meet(b),
                |leaf| {
                    for p in bvh.leaf(leaf).unwrap_or_default().range() {
                        let b = fresh[order[p] as usize] as usize;
                        // A pair of two changed triangles is met twice: once.
                        if a_fresh && b <= a {
                            continue;
                        }
                        let tb = &triangles[b];
                        let item = fresh_boxes[order[p] as usize];
                        if ta.face != tb.face
                            && !item.intersection(query).is_empty()
                            && filter.may_meet(&item)
                            && triangles_meet_beyond_shared(ctx, ta, tb)
                        {
                            found.push((ta.face.min(tb.face), ta.face.max(tb.face)));
                        }
                    }
                },
            );
            found
        })
        .collect();
    pairs.par_sort_unstable();
    pairs.dedup();
    pairs
}
