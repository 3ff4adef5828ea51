//! The pairs of triangles that share no vertex and whose boxes overlap,
//! found by walks of the shared BVH without handing over the pairs around a
//! vertex of high valence, and decided as they are found: no list of
//! candidate pairs is gathered, so memory stays proportional to the
//! triangles and to what the test returns, however many pairs the walks
//! meet.
//!
//! The triangles around the vertices of highest valence (the hubs: a
//! cone's apex, a pole, the centre of a fan) each form a group of their
//! own. Two triangles of one group share the hub, so no walk pairs a group
//! with itself; the other triangles are walked against each other and
//! every group against every other. A hub's triangles are slivers whose
//! boxes are as large as the hub's neighbourhood, so in the trees each is
//! cut across into pieces that shrink geometrically towards the hub and
//! towards the far edge, until a piece is about as long as the triangle is
//! wide: boxes that follow the sliver, so two fans that meet along a rim
//! (a cone's side and its base) overlap only near the rim. A group is
//! walked against an earlier group's tree one triangle at a time, the
//! triangle itself tested against the boxes of the nodes it opens (by
//! separating axes, `geom::TriangleFilter`, which never rejects a box the
//! triangle meets), so a long thin triangle crossing the model obliquely
//! opens only the nodes along it.

use std::sync::atomic::{AtomicUsize, Ordering};

use glam::DVec3;
use rayon::prelude::*;

use super::super::super::context::Context;
use super::triangles::Triangle;
use crate::geom::{Aabb, TriangleFilter};
use crate::spatial::Bvh;

/// The most hubs that get a group of their own (those of highest valence).
const MAX_HUBS: usize = 8;

/// The most halvings of a triangle towards its far edge.
const MAX_HALVINGS: u8 = 10;

/// What [`pairs_apart`] found and how many pairs it tested.
pub(super) struct Apart<T> {
    /// What the test returned.
    pub found: Vec<T>,
    /// Pairs handed to the test.
    pub tested: usize,
    /// The most candidate triangles held at once, waiting for the test
    /// (those one triangle found in another group's tree): candidates are
    /// decided as they are found, not gathered.
    pub held: usize,
}

/// Calls `test(a, b)` (triangle indices, `a < b`) once on every pair of
/// triangles of different faces that share no vertex and whose exact boxes
/// overlap (closed boxes; `box_of_triangle(i)` is triangle `i`'s exact box),
/// and collects what it returns. `min_hub_valence`:
/// a vertex of more triangles than that can be a hub.
pub(super) fn pairs_apart<T: Send>(
    ctx: &Context,
    triangles: &[Triangle],
    box_of_triangle: impl Fn(usize) -> Aabb + Sync,
    min_hub_valence: usize,
    test: impl Fn(usize, usize) -> Option<T> + Sync,
) -> Apart<T> {
    let tested = AtomicUsize::new(0);
    let held = AtomicUsize::new(0);
    // Whether a pair is one to test: cheap index and box comparisons.
    let candidate = |a: usize, b: usize| -> bool {
        let (ta, tb) = (&triangles[a], &triangles[b]);
        ta.face != tb.face
            && ta.shared_vertices(tb) == 0
            && overlap(&box_of_triangle(a), &box_of_triangle(b))
    };
    let decide = |a: usize, b: usize| -> Option<T> {
        tested.fetch_add(1, Ordering::Relaxed);
        test(a.min(b), a.max(b))
    };
    let try_pair =
        |a: usize, b: usize| -> Option<T> { if candidate(a, b) { decide(a, b) } else { None } };
    let (hub_of, hubs) = hubs(ctx.soup.positions.len(), triangles, min_hub_valence);
    // Group 0: triangles of no hub, one piece each (its own box). A piece
    // is its triangle and its index along it; its box is made when asked.
    let mut members: Vec<Vec<u32>> = vec![Vec::new(); hubs.len() + 1];
    let mut halvings_of = vec![0u8; triangles.len()];
    for (i, t) in triangles.iter().enumerate() {
        let group = t
            .vertices
            .iter()
            .filter_map(|&v| hub_of[v])
            .min()
            .map_or(0, |h| h + 1);
        members[group].push(i as u32);
        if group > 0 {
            halvings_of[i] = halvings(ctx, t, hubs[group - 1]);
        }
    }
    drop(hub_of);
    let box_of = |group: usize, (i, piece): (u32, u8)| {
        let i = i as usize;
        if group == 0 {
            box_of_triangle(i)
        } else {
            let hub = hubs[group - 1];
            piece_box(
                ctx,
                &triangles[i],
                hub,
                box_of_triangle(i),
                halvings_of[i],
                piece,
            )
        }
    };
    let bounds: Vec<Aabb> = members
        .iter()
        .map(|m| {
            m.iter()
                .fold(Aabb::EMPTY, |b, &i| b.union(box_of_triangle(i as usize)))
        })
        .collect();
    // The pieces of one group. A hub's group is walked only against the
    // other groups, so its pieces whose boxes miss every other group's
    // bounds pair with nothing (a cone's side above its base's plane):
    // they are left out of its tree.
    let pieces_of = |group: usize| -> Vec<(u32, u8)> {
        if group == 0 {
            return members[0].iter().map(|&i| (i, 0)).collect();
        }
        let others = (0..bounds.len())
            .filter(|&h| h != group)
            .fold(Aabb::EMPTY, |b, h| b.union(bounds[h]));
        members[group]
            .iter()
            .flat_map(|&i| (0..piece_count(halvings_of[i as usize])).map(move |k| (i, k)))
            .filter(|&piece| overlap(&box_of(group, piece), &others))
            .collect()
    };
    // One group's tree at a time: built, walked by the triangles of no hub
    // (group 0 only) and by every later group, then dropped, so the trees
    // of the pieces (many per sliver) are never all held at once; the last
    // group, which no later group walks against, gets none.
    let mut found = Vec::new();
    for g in 0..members.len() {
        let walked_by = &members[g + 1..];
        if g > 0 && walked_by.iter().all(Vec::is_empty) {
            continue;
        }
        let pieces = pieces_of(g);
        let (bvh, order) = Bvh::build_by(pieces.len(), |k| box_of(g, pieces[k]));
        let tree = PieceTree {
            bvh,
            order,
            pieces: &pieces,
        };
        // The triangles of no hub: one piece each, so each pair once.
        if g == 0 && tree.pieces.len() >= 2 {
            found = tree.bvh.par_self_leaf_pairs(|la, lb, found| {
                for (k, a) in tree.triangles(la).enumerate() {
                    let from = if la == lb { k + 1 } else { 0 };
                    found.extend(tree.triangles(lb).skip(from).filter_map(|b| try_pair(a, b)));
                }
            });
        }
        // Group against group, streamed: each triangle of the later group
        // asks the earlier group's tree for the pieces whose boxes overlap
        // its own, opening only the nodes whose boxes its triangle may meet
        // (a pair that meets has a common point, in a piece of the one and
        // in the other, so no pair the test would report is left out, and a
        // sliver opens the nodes along it, not all its box overlaps). The
        // triangles of the pieces one triangle finds are tested once each,
        // as they are found: nothing is kept but what the test returns and,
        // while one triangle asks, the triangles it found.
        for later in walked_by {
            if tree.pieces.is_empty() || later.is_empty() {
                continue;
            }
            found.par_extend(later.par_iter().flat_map_iter(|&b| {
                let b = b as usize;
                let filter = TriangleFilter::new(&triangles[b].vertices.map(|v| ctx.position(v)));
                // A leaf's box holds its pieces': the triangle meeting it
                // is the filter (the pair test checks the whole boxes).
                let mut near = Vec::new();
                tree.bvh.leaves_overlapping_where(
                    &box_of_triangle(b),
                    |node| filter.may_meet(node),
                    |leaf| near.extend(tree.triangles(leaf).map(|a| a as u32)),
                );
                if g > 0 {
                    // A hub's triangle is cut into pieces, several of
                    // which may be found.
                    near.sort_unstable();
                    near.dedup();
                }
                held.fetch_max(near.len(), Ordering::Relaxed);
                // The cheap comparisons first; the triangle against the
                // other's box only for a pair that passes them.
                near.into_iter()
                    .map(|a| a as usize)
                    .filter(|&a| candidate(a, b) && (g > 0 || filter.may_meet(&box_of_triangle(a))))
                    .filter_map(|a| decide(a, b))
                    .collect::<Vec<_>>()
            }));
        }
    }
    Apart {
        found,
        tested: tested.into_inner(),
        held: held.into_inner(),
    }
}

/// The BVH of one group's pieces: a triangle and the piece's index along
/// it each.
struct PieceTree<'a> {
    bvh: Bvh,
    order: Vec<u32>,
    pieces: &'a [(u32, u8)],
}

impl PieceTree<'_> {
    /// The triangles of the pieces of one leaf.
    fn triangles(&self, leaf: u32) -> impl Iterator<Item = usize> + '_ {
        let range = self.bvh.leaf(leaf).unwrap_or_default().range();
        range.map(|slot| self.pieces[self.order[slot] as usize].0 as usize)
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

/// How many times the triangle `t` with corner `hub` is cut towards its far
/// edge (see [`piece_box`]): `h` with `2^h` at least its length over its
/// width, at most [`MAX_HALVINGS`]; 0 for a triangle kept whole.
fn halvings(ctx: &Context, t: &Triangle, hub: usize) -> u8 {
    let [v, a, b] = around(ctx, t, hub);
    let length = (a - v).abs().max_element().max((b - v).abs().max_element());
    let width = (a - b).abs().max_element();
    let ratio = length / width;
    if !(width > 0.0 && ratio.is_finite()) || ratio <= 2.0 {
        return 0;
    }
    ratio.log2().ceil().clamp(2.0, f64::from(MAX_HALVINGS)) as u8
}

/// The cuts towards the hub of a triangle of `halvings` (see
/// [`piece_box`]).
fn quarterings(halvings: u8) -> u8 {
    halvings.div_ceil(2).max(1)
}

/// The pieces of a triangle of `halvings` (see [`piece_box`]).
fn piece_count(halvings: u8) -> u8 {
    if halvings == 0 {
        1
    } else {
        quarterings(halvings) + halvings + 1
    }
}

/// The corners of `t` from `hub` on, in the triangle's order.
fn around(ctx: &Context, t: &Triangle, hub: usize) -> [DVec3; 3] {
    let i = t.vertices.iter().position(|&x| x == hub).unwrap_or(0);
    [0, 1, 2].map(|k| ctx.position(t.vertices[(i + k) % 3]))
}

/// The box of piece `piece` of the triangle `t` with corner `hub`, cut
/// across by lines parallel to its edge opposite the hub: towards the hub
/// at the fractions `4⁻ʲ` of the way from it (`j` from 1 to
/// [`quarterings`]), towards the far edge at `1 − 2⁻ʲ` (`j` from 1 to
/// `halvings`): pieces that shrink geometrically towards both ends, the
/// last about as long as the triangle is wide. Near the far edge, where
/// the groups of two hubs meet (a cone's side and its base), the pieces
/// halve; near the hub, where only the hub's own group is (never walked
/// against itself), they quarter, so fewer pieces are built. `whole` is the
/// triangle's exact box.
///
/// A piece's corners are rounded constructions; each box is widened by a
/// bound on their rounding (below: coordinates of magnitude at most `m`
/// give a corner `hub + (a − hub)·s`, with `s` exact, within a few units of
/// `2⁻⁵²·m` of the exact point; the boxes are widened by `2⁻⁴⁸·m`) and cut
/// to the triangle's exact box, so it holds the exact piece. A piece whose
/// box would not be finite takes the whole box.
fn piece_box(
    ctx: &Context,
    t: &Triangle,
    hub: usize,
    whole: Aabb,
    halvings: u8,
    piece: u8,
) -> Aabb {
    if halvings == 0 {
        return whole;
    }
    let [v, a, b] = around(ctx, t, hub);
    let (q, h) = (i32::from(quarterings(halvings)), i32::from(halvings));
    // Cut k of q + h + 2 (0 and 1 included), by exact powers of two.
    let cut = |k: i32| -> f64 {
        if k == 0 {
            0.0
        } else if k <= q {
            0.25f64.powi(q + 1 - k)
        } else if k <= q + h {
            1.0 - 0.5f64.powi(k - q)
        } else {
            1.0
        }
    };
    let at = |s: f64| -> [DVec3; 2] {
        if s == 0.0 {
            [v, v]
        } else if s == 1.0 {
            [a, b]
        } else {
            [v + (a - v) * s, v + (b - v) * s]
        }
    };
    let k = i32::from(piece);
    let [p, r] = at(cut(k));
    let [s, u] = at(cut(k + 1));
    let magnitude = v.abs().max(a.abs()).max(b.abs()).max_element();
    let margin = DVec3::splat(magnitude * (1.0 / (1u64 << 48) as f64));
    let b = Aabb::from_points([p, r, s, u]);
    let piece = Aabb {
        min: (b.min - margin).max(whole.min),
        max: (b.max + margin).min(whole.max),
    };
    if piece.min.is_finite() && piece.max.is_finite() {
        piece
    } else {
        whole
    }
}

/// Whether two closed boxes share a point.
pub(super) fn overlap(a: &Aabb, b: &Aabb) -> bool {
    !a.min.max(b.min).cmpgt(a.max.min(b.max)).any()
}
