//! The pairs of triangles that share no vertex and whose boxes overlap,
//! found by walks of the shared BVH without handing over the pairs around a
//! vertex of high valence.
//!
//! The triangles around the vertices of highest valence (the hubs: a
//! cone's apex, a pole, the centre of a fan) each form a group of their
//! own. Two triangles of one group share the hub, so no walk pairs a group
//! with itself; the other triangles are walked against each other and
//! every group against every other. A hub's triangles are slivers whose
//! boxes are as large as the hub's neighbourhood, so for these walks each
//! is cut across into pieces that shrink geometrically towards the hub and
//! towards the far edge, until a piece is about as long as the triangle is
//! wide: boxes that follow the sliver, so two fans that meet along a rim
//! (a cone's side and its base) overlap only near the rim.

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use super::super::super::context::Context;
use super::triangles::Triangle;
use crate::geom::Aabb;
use crate::spatial::Bvh;

/// The most hubs that get a group of their own (those of highest valence).
const MAX_HUBS: usize = 8;

/// The most halvings of a triangle towards each end.
const MAX_HALVINGS: u32 = 10;

/// What [`pairs_apart`] found and how many pairs it tested.
pub(super) struct Apart<T> {
    /// What the test returned.
    pub found: Vec<T>,
    /// Pairs handed to the test.
    pub tested: usize,
}

/// Calls `test(a, b)` (triangle indices, `a < b`) once on every pair of
/// triangles of different faces that share no vertex and whose exact boxes
/// overlap (closed boxes), and collects what it returns. `min_hub_valence`:
/// a vertex of more triangles than that can be a hub.
pub(super) fn pairs_apart<T: Send>(
    ctx: &Context,
    triangles: &[Triangle],
    boxes: &[Aabb],
    min_hub_valence: usize,
    test: impl Fn(usize, usize) -> Option<T> + Sync,
) -> Apart<T> {
    let tested = AtomicUsize::new(0);
    let try_pair = |a: usize, b: usize| -> Option<T> {
        let (ta, tb) = (&triangles[a], &triangles[b]);
        if ta.face == tb.face || ta.shared_vertices(tb) != 0 || !overlap(&boxes[a], &boxes[b]) {
            return None;
        }
        tested.fetch_add(1, Ordering::Relaxed);
        test(a.min(b), a.max(b))
    };
    let (hub_of, hubs) = hubs(ctx.soup.positions.len(), triangles, min_hub_valence);
    // Group 0: triangles of no hub, one piece each (its own box).
    let mut pieces: Vec<Vec<(Aabb, u32)>> = vec![Vec::new(); hubs.len() + 1];
    for (i, t) in triangles.iter().enumerate() {
        let group = t
            .vertices
            .iter()
            .filter_map(|&v| hub_of[v])
            .min()
            .map_or(0, |h| h + 1);
        if group == 0 {
            pieces[0].push((boxes[i], i as u32));
        } else {
            let hub = hubs[group - 1];
            cut_into_pieces(ctx, t, hub, boxes[i], |b| pieces[group].push((b, i as u32)));
        }
    }
    let trees: Vec<PieceTree> = pieces
        .iter()
        .map(|p| {
            let (bvh, order) = Bvh::build_by(p.len(), |k| p[k].0);
            PieceTree {
                bvh,
                order,
                pieces: p,
            }
        })
        .collect();
    let leaf_items = |tree: &PieceTree, leaf: u32| tree.triangles(leaf).collect::<Vec<_>>();
    // The triangles of no hub: one piece each, so each pair once.
    let mut found = if trees[0].pieces.len() >= 2 {
        let tree = &trees[0];
        tree.bvh.par_self_leaf_pairs(|la, lb, found| {
            let others = leaf_items(tree, lb);
            for (k, a) in leaf_items(tree, la).into_iter().enumerate() {
                let from = if la == lb { k + 1 } else { 0 };
                found.extend(others[from..].iter().filter_map(|&b| try_pair(a, b)));
            }
        })
    } else {
        Vec::new()
    };
    // Group against group: pieces pair up more than once, so the triangle
    // pairs are gathered and tested once each.
    for g in 0..trees.len() {
        for h in g + 1..trees.len() {
            let (tg, th) = (&trees[g], &trees[h]);
            if tg.pieces.is_empty() || th.pieces.is_empty() {
                continue;
            }
            let mut candidates: Vec<(u32, u32)> =
                tg.bvh.par_leaf_pairs(&th.bvh, |la, lb, found| {
                    for a in leaf_items(tg, la) {
                        for b in leaf_items(th, lb) {
                            found.push((a.min(b) as u32, a.max(b) as u32));
                        }
                    }
                });
            candidates.par_sort_unstable();
            candidates.dedup();
            found.par_extend(
                candidates
                    .par_iter()
                    .filter_map(|&(a, b)| try_pair(a as usize, b as usize)),
            );
        }
    }
    Apart {
        found,
        tested: tested.into_inner(),
    }
}

/// The BVH of one group's pieces: a box and its triangle each.
struct PieceTree<'a> {
    bvh: Bvh,
    order: Vec<u32>,
    pieces: &'a [(Aabb, u32)],
}

impl PieceTree<'_> {
    /// The triangles of the pieces of one leaf.
    fn triangles(&self, leaf: u32) -> impl Iterator<Item = usize> + '_ {
        let range = self.bvh.leaf(leaf).unwrap_or_default().range();
        range.map(|slot| self.pieces[self.order[slot] as usize].1 as usize)
    }
}

/// The hubs: up to [`MAX_HUBS`] vertices of the most triangles, each of more
/// than `min_valence`, by descending valence (ties by vertex); and for each
/// vertex its rank among them.
fn hubs(
    vertex_count: usize,
    triangles: &[Triangle],
    min_valence: usize,
) -> (Vec<Option<usize>>, Vec<usize>) {
    let mut valence = vec![0usize; vertex_count];
    for t in triangles {
        for &v in &t.vertices {
            valence[v] += 1;
        }
    }
    let mut hubs: Vec<usize> = (0..vertex_count)
        .filter(|&v| valence[v] > min_valence)
        .collect();
    hubs.sort_unstable_by_key(|&v| (std::cmp::Reverse(valence[v]), v));
    hubs.truncate(MAX_HUBS);
    let mut hub_of = vec![None; vertex_count];
    for (rank, &v) in hubs.iter().enumerate() {
        hub_of[v] = Some(rank);
    }
    (hub_of, hubs)
}

/// Cuts the triangle `t` with corner `hub` across, by lines parallel to its
/// edge opposite the hub, at the fractions `2⁻ʲ` and `1 − 2⁻ʲ` of the way
/// from the hub (`j` up to the halvings that make a piece about as long as
/// the triangle is wide), and gives each piece's box to `push`.
///
/// A piece's corners are rounded constructions; each box is widened by a
/// bound on their rounding (below: coordinates of magnitude at most `m`
/// give a corner `hub + (a − hub)·s`, with `s` exact, within a few units of
/// `2⁻⁵²·m` of the exact point; the boxes are widened by `2⁻⁴⁸·m`) and cut
/// to the triangle's exact box, so it holds the exact piece. A triangle
/// whose cut would not be finite stays whole.
fn cut_into_pieces(
    ctx: &Context,
    t: &Triangle,
    hub: usize,
    whole: Aabb,
    mut push: impl FnMut(Aabb),
) {
    let i = t.vertices.iter().position(|&x| x == hub).unwrap_or(0);
    let v = ctx.position(t.vertices[i]);
    let a = ctx.position(t.vertices[(i + 1) % 3]);
    let b = ctx.position(t.vertices[(i + 2) % 3]);
    let length = (a - v).abs().max_element().max((b - v).abs().max_element());
    let width = (a - b).abs().max_element();
    let halvings = if width > 0.0 && (length / width).is_finite() {
        ((length / width).log2().ceil().max(0.0) as u32).min(MAX_HALVINGS)
    } else {
        0
    };
    if halvings <= 1 {
        return push(whole);
    }
    let magnitude = v.abs().max(a.abs()).max(b.abs()).max_element();
    let margin = DVec3::splat(magnitude * (1.0 / (1u64 << 48) as f64));
    let toward_hub = (1..=halvings).rev().map(|j| 0.5f64.powi(j as i32));
    let toward_edge = (2..=halvings).map(|j| 1.0 - 0.5f64.powi(j as i32));
    let cuts: Vec<f64> = std::iter::once(0.0)
        .chain(toward_hub)
        .chain(toward_edge)
        .chain(std::iter::once(1.0))
        .collect();
    let at = |s: f64| -> [DVec3; 2] {
        if s == 0.0 {
            [v, v]
        } else if s == 1.0 {
            [a, b]
        } else {
            [v + (a - v) * s, v + (b - v) * s]
        }
    };
    let boxes: Vec<Aabb> = cuts
        .windows(2)
        .map(|w| {
            let [p, q] = at(w[0]);
            let [r, s] = at(w[1]);
            let b = Aabb::from_points([p, q, r, s]);
            Aabb {
                min: (b.min - margin).max(whole.min),
                max: (b.max + margin).min(whole.max),
            }
        })
        .collect();
    if boxes.iter().all(|b| b.min.is_finite() && b.max.is_finite()) {
        boxes.into_iter().for_each(push);
    } else {
        push(whole);
    }
}

/// Whether two closed boxes share a point.
pub(super) fn overlap(a: &Aabb, b: &Aabb) -> bool {
    !a.min.max(b.min).cmpgt(a.max.min(b.max)).any()
}
