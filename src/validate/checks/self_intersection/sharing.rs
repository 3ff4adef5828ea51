//! The pairs of triangles that share a vertex or an edge, found from the
//! topology rather than from boxes (the boxes of such a pair always
//! overlap, so a box walk would hand over every pair around a vertex of
//! valence `k`: `k²/2` of them).
//!
//! Around an edge `uw`, two triangles `(u, w, a)` and `(u, w, b)` fold onto
//! each other only when `a` and `b` lie in one half-plane bounded by the
//! line `uw`: the same angle around that line. The triangles of an edge are
//! sorted by that angle ([`AxisOrder`]) and only triangles of equal angle
//! are paired.
//!
//! Around a vertex `v`, two triangles that share only `v` meet beyond `v`
//! only if their corners at `v` share a direction: their intersection is
//! convex and holds `v`, so it holds the segment from `v` to any other
//! common point. Seen along an axis through `v`, a corner whose plane does
//! not hold the axis projects to a wedge of less than a half-turn, and a
//! direction the two corners share projects into both wedges (it is not
//! along the axis, which neither corner holds), so their angular intervals
//! around the axis overlap; and of two overlapping arcs of a circle one
//! starts inside the other. So the corners are sorted by angle around the
//! axis `v + n` (`n` the sum of the corners' unit normals: a cone's axis,
//! around which a cone's, a pole's or a fan's corners follow each other
//! without overlapping), every corner is paired with the corners whose
//! interval holds its start (a sweep), and a corner whose plane holds the
//! axis is paired with every other.
//!
//! Both are filters: each pair they keep is still decided by the exact
//! pair test, so the verdicts are those of testing every pair. Edges and
//! vertices with few triangles pair them all.

use std::sync::atomic::{AtomicUsize, Ordering as AtomicOrdering};

use glam::DVec3;
use rayon::prelude::*;

use super::super::super::context::Context;
use super::triangles::Triangle;
use crate::geom::around_axis::{AxisOrder, HalfTurn};
use crate::geom::{Sign, collinear3d, orient3d};

/// Up to this many triangles around a vertex or an edge, every pair of them
/// is tested; above it the angular filters choose.
pub(super) const SMALL_FAN: usize = 24;

/// Receives candidate pairs of triangles (indices).
type Visit<'a> = dyn FnMut(u32, u32) + 'a;

/// What [`pairs_sharing_corners`] found and how many pairs it tested.
pub(super) struct Sharing<T> {
    /// What the test returned for the pairs it kept.
    pub found: Vec<T>,
    /// Pairs handed to the test.
    pub tested: usize,
}

/// Calls `test(a, b)` (triangle indices, `a < b`) on every pair of triangles that
/// share exactly one or exactly two vertices and whose corners can overlap
/// (see the module documentation), and collects what it returns.
pub(super) fn pairs_sharing_corners<T: Send>(
    ctx: &Context,
    triangles: &[Triangle],
    test: impl Fn(usize, usize) -> Option<T> + Sync,
) -> Sharing<T> {
    let tested = AtomicUsize::new(0);
    // Tests the candidates that `candidates` visits and share exactly
    // `shared` vertices.
    let run = |shared: usize, candidates: &dyn Fn(&mut Visit)| -> Vec<T> {
        let mut count = 0;
        let mut found = Vec::new();
        candidates(&mut |a, b| {
            if triangles[a as usize].shared_vertices(&triangles[b as usize]) == shared {
                count += 1;
                found.extend(test(a.min(b) as usize, a.max(b) as usize));
            }
        });
        tested.fetch_add(count, AtomicOrdering::Relaxed);
        found
    };
    let (star_start, stars) = stars(ctx.soup.positions.len(), triangles);
    // Per vertex `u`: the pairs around `u`, then the pairs around each
    // edge `uw` with `w > u`, whose triangles are those of `u`'s star that
    // hold `w` (in index order, as the star lists them). Each edge is met
    // once, at its lower vertex, and nothing is listed for all edges at
    // once.
    let found: Vec<T> = (0..ctx.soup.positions.len())
        .into_par_iter()
        .with_min_len(256)
        .flat_map_iter(|u| {
            let star = &stars[star_start[u] as usize..star_start[u + 1] as usize];
            let mut found = run(1, &|visit| {
                if star.len() <= SMALL_FAN {
                    all_pairs(star, visit);
                } else {
                    corners_that_can_overlap(ctx, triangles, u, star, visit);
                }
            });
            let mut far: Vec<(usize, u32)> = star
                .iter()
                .flat_map(|&t| {
                    triangles[t as usize]
                        .vertices
                        .into_iter()
                        .filter(move |&w| w > u)
                        .map(move |w| (w, t))
                })
                .collect();
            far.sort_unstable();
            for edge in far.chunk_by(|x, y| x.0 == y.0).filter(|e| e.len() >= 2) {
                let run_of: Vec<u32> = edge.iter().map(|x| x.1).collect();
                let w = edge[0].0;
                found.extend(run(2, &|visit| {
                    if run_of.len() <= SMALL_FAN {
                        all_pairs(&run_of, visit);
                    } else {
                        triangles_in_one_half_plane(ctx, triangles, (u, w), &run_of, visit);
                    }
                }));
            }
            found
        })
        .collect();
    Sharing {
        found,
        tested: tested.into_inner(),
    }
}

/// The triangles around each vertex: those of vertex `v` are
/// `stars[start[v] .. start[v + 1]]`.
fn stars(vertex_count: usize, triangles: &[Triangle]) -> (Vec<u32>, Vec<u32>) {
    let mut start = vec![0u32; vertex_count + 1];
    for t in triangles {
        for &v in &t.vertices {
            start[v + 1] += 1;
        }
    }
    for v in 0..vertex_count {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut stars = vec![0u32; start[vertex_count] as usize];
    for (i, t) in triangles.iter().enumerate() {
        for &v in &t.vertices {
            stars[fill[v] as usize] = i as u32;
            fill[v] += 1;
        }
    }
    (start, stars)
}

/// Visits every pair of the listed triangles.
fn all_pairs(list: &[u32], visit: &mut dyn FnMut(u32, u32)) {
    for (i, &a) in list.iter().enumerate() {
        for &b in &list[i + 1..] {
            visit(a, b);
        }
    }
}

/// Visits the pairs of triangles of the edge `(u, w)` whose third vertices
/// lie at the same angle around the edge's line (one half-plane), and each
/// triangle whose third vertex is on that line with every other.
fn triangles_in_one_half_plane(
    ctx: &Context,
    triangles: &[Triangle],
    (u, w): (usize, usize),
    run: &[u32],
    visit: &mut dyn FnMut(u32, u32),
) {
    let (pu, pw) = (ctx.position(u), ctx.position(w));
    let far = |t: u32| -> DVec3 {
        let vs = triangles[t as usize].vertices;
        ctx.position(vs.into_iter().find(|&x| x != u && x != w).unwrap_or(vs[0]))
    };
    let Some(order) = run
        .iter()
        .map(|&t| far(t))
        .find(|&p| !collinear3d(pu, pw, p))
        .and_then(|p| AxisOrder::new(pu, pw, p, run.iter().map(|&s| far(s))))
    else {
        return all_pairs(run, visit);
    };
    let mut pages: Vec<(HalfTurn, DVec3, u32)> = Vec::with_capacity(run.len());
    let mut loose: Vec<u32> = Vec::new();
    for &t in run {
        let p = far(t);
        match order.half_turn(p) {
            Some(h) => pages.push((h, p, t)),
            None => loose.push(t),
        }
    }
    pages.sort_by(|a, b| order.compare((a.0, a.1), (b.0, b.1)));
    for same in pages.chunk_by(|a, b| order.compare((a.0, a.1), (b.0, b.1)).is_eq()) {
        for (i, a) in same.iter().enumerate() {
            for b in &same[i + 1..] {
                visit(a.2, b.2);
            }
        }
    }
    with_every_other(&loose, run, |_| 0, visit);
}

/// Visits the pairs of each of `loose` with every other of `all` in
/// another group (`group` of a triangle; `0` is no group: paired with
/// all).
fn with_every_other(
    loose: &[u32],
    all: &[u32],
    group: impl Fn(u32) -> usize,
    visit: &mut dyn FnMut(u32, u32),
) {
    for (i, &a) in loose.iter().enumerate() {
        let g = group(a);
        for &b in all {
            // A pair of two loose triangles once.
            if b != a && (g == 0 || group(b) != g) && !loose[..i].contains(&b) {
                visit(a, b);
            }
        }
    }
}

/// Visits the pairs of triangles around `v` whose corners at `v` can share
/// a direction, by the angular intervals of the corners around an axis
/// through `v` (see the module documentation). Corners that share a side
/// with more than [`SMALL_FAN`] others (a fan on one edge) are grouped by
/// that side and not paired within the group: such pairs share an edge and
/// are the edge's to test.
fn corners_that_can_overlap(
    ctx: &Context,
    triangles: &[Triangle],
    v: usize,
    star: &[u32],
    visit: &mut dyn FnMut(u32, u32),
) {
    let pv = ctx.position(v);
    // Each corner's two other vertices, in the triangle's order after `v`.
    let ends: Vec<(usize, usize)> = star
        .iter()
        .map(|&t| {
            let vs = triangles[t as usize].vertices;
            let i = vs.iter().position(|&x| x == v).unwrap_or(0);
            (vs[(i + 1) % 3], vs[(i + 2) % 3])
        })
        .collect();
    // Groups: 1 + the index of a side shared by many corners, else 0.
    let mut side_counts: Vec<(usize, usize)> = {
        let mut sides: Vec<usize> = ends.iter().flat_map(|&(a, b)| [a, b]).collect();
        sides.sort_unstable();
        sides
            .chunk_by(|a, b| a == b)
            .filter(|same| same.len() > SMALL_FAN)
            .map(|same| (same[0], 0))
            .collect()
    };
    for (k, entry) in side_counts.iter_mut().enumerate() {
        entry.1 = k + 1;
    }
    let heavy = |x: usize| {
        side_counts
            .binary_search_by_key(&x, |e| e.0)
            .map_or(0, |i| side_counts[i].1)
    };
    let groups: Vec<usize> = ends
        .iter()
        .map(|&(a, b)| {
            let g = heavy(a);
            if g != 0 { g } else { heavy(b) }
        })
        .collect();
    let mut group_by_triangle: Vec<(u32, usize)> =
        star.iter().copied().zip(groups.iter().copied()).collect();
    group_by_triangle.sort_unstable();
    let group_of = |t: u32| {
        group_by_triangle
            .binary_search_by_key(&t, |e| e.0)
            .map_or(0, |i| group_by_triangle[i].1)
    };
    let mut normal = DVec3::ZERO;
    let mut reach = 0.0f64;
    for &(a, b) in &ends {
        let (da, db) = (ctx.position(a) - pv, ctx.position(b) - pv);
        normal += da.cross(db).normalize_or_zero();
        reach = reach
            .max(da.abs().max_element())
            .max(db.abs().max_element());
    }
    // The axis: the corners' mean normal, else a coordinate axis.
    let order = [normal.normalize_or_zero(), DVec3::Z, DVec3::X, DVec3::Y]
        .into_iter()
        .map(|d| pv + d * reach)
        .filter(|&toward| toward != pv && toward.is_finite())
        .find_map(|toward| {
            ends.iter()
                .find(|&&(a, b)| {
                    orient3d(pv, toward, ctx.position(a), ctx.position(b)) != Sign::Zero
                })
                .and_then(|&(a, b)| AxisOrder::new(pv, toward, ctx.position(a), [ctx.position(b)]))
        });
    let Some(order) = order else {
        return all_pairs(star, visit);
    };
    // Each corner as an interval from its first to its last side, turning
    // the positive way (less than a half-turn), or loose.
    let mut loose = Vec::new();
    let mut intervals: Vec<(usize, usize, u32, usize)> = Vec::with_capacity(star.len());
    for ((&t, &(a, b)), &g) in star.iter().zip(&ends).zip(&groups) {
        match order.turn(ctx.position(a), ctx.position(b)) {
            Sign::Positive => intervals.push((a, b, t, g)),
            Sign::Negative => intervals.push((b, a, t, g)),
            Sign::Zero => loose.push(t),
        }
    }
    // The sides' vertices by angle, equal angles sharing a rank.
    let mut sides: Vec<usize> = intervals.iter().flat_map(|&(a, b, ..)| [a, b]).collect();
    sides.sort_unstable();
    sides.dedup();
    let Some(mut keyed) = sides
        .iter()
        .map(|&x| {
            let p = ctx.position(x);
            order.half_turn(p).map(|h| (h, p, x))
        })
        .collect::<Option<Vec<_>>>()
    else {
        // Unreachable: a side of a corner that turns is off the axis.
        return all_pairs(star, visit);
    };
    keyed.sort_by(|a, b| order.compare((a.0, a.1), (b.0, b.1)));
    let mut rank_of: Vec<(usize, usize)> = Vec::with_capacity(keyed.len());
    let mut rank = 0;
    for (i, k) in keyed.iter().enumerate() {
        if i > 0
            && order
                .compare((keyed[i - 1].0, keyed[i - 1].1), (k.0, k.1))
                .is_ne()
        {
            rank += 1;
        }
        rank_of.push((k.2, rank));
    }
    let ranks = rank + 1;
    rank_of.sort_unstable();
    let rank = |x: usize| {
        let i = rank_of.partition_point(|&(y, _)| y < x);
        rank_of[i].1
    };
    // Intervals in rank space; one that passes the reference is cut in two.
    let mut pieces: Vec<(usize, usize, u32, usize)> = Vec::with_capacity(intervals.len() + 8);
    for &(a, b, t, g) in &intervals {
        let (start, end) = (rank(a), rank(b));
        if start <= end {
            pieces.push((start, end, t, g));
        } else {
            pieces.push((start, ranks - 1, t, g));
            pieces.push((0, end, t, g));
        }
    }
    pieces.sort_unstable();
    // The sweep: each piece against the pieces still open where it starts,
    // kept per group so that a group's own pieces are never visited by it.
    let mut active: Vec<Vec<(usize, u32)>> = vec![Vec::new(); side_counts.len() + 1];
    for &(start, end, t, g) in &pieces {
        for (h, open) in active.iter_mut().enumerate() {
            if h != 0 && h == g {
                continue;
            }
            open.retain(|&(e, _)| e >= start);
            for &(_, s) in open.iter() {
                if s != t {
                    visit(s, t);
                }
            }
        }
        active[g].push((end, t));
    }
    with_every_other(&loose, star, group_of, visit);
}
