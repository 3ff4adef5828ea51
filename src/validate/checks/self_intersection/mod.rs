//! A face crossing or touching another face anywhere but at the vertices
//! and edges they share.
//!
//! Faces are cut into triangles (the exact constrained Delaunay
//! triangulation of `geom::triangulate` in the face's axis projection; a
//! fan for a face whose projection is not simple), and every pair of
//! triangles of different faces whose boxes overlap (closed boxes: touching
//! counts) is decided exactly: only `orient3d` and `orient2d` signs decide,
//! no epsilon. Not every such pair is handed to the test: pairs that share
//! a vertex or an edge come from the topology, filtered by exact angular
//! order ([`sharing`]), and the others from the shared BVH's pair walks
//! ([`apart`]); each filter drops only pairs the test would answer "no",
//! so the verdicts are those of testing every pair. Pairs are tested in
//! parallel; the defects found are sorted, so their order depends on
//! neither the trees nor the threads.
//!
//! How a pair is tested depends on the vertices its triangles share
//! ([`pair`] derives each rule):
//!
//! - none: any common point is a defect (crossing or touching);
//! - one vertex `v`: any common point other than `v` is a defect, that is
//!   when the two closed corners at `v` share a direction (a fin through a
//!   neighbour, far edges that cross, a far vertex on the other face, a flat
//!   fan that wraps over itself or two corners of one plane along one ray);
//! - an edge `uw`, triangles `(u, w, a)` and `(u, w, b)`: when not coplanar
//!   they meet only along `uw`; when coplanar they overlap (a fold) iff `a`
//!   and `b` lie on the same side of `uw`.
//!
//! Faces that are not polygons, degenerate faces and later copies of
//! duplicate faces are left out: other rules report them.

mod apart;
mod coincident_edges;
mod near;
mod pair;
mod sharing;
mod triangles;

use rayon::prelude::*;

use super::super::context::Context;
use super::super::report::{Rule, Violation};
use crate::geom::Aabb;
use pair::triangles_meet_beyond_shared;
use triangles::{Triangle, triangulate};

/// Every pair of faces that cross or touch without sharing a vertex.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    let triangles = triangulate(ctx);
    let mut pairs = intersecting_face_pairs(ctx, &triangles);
    pairs.extend(coincident_edges::crossing_along_coincident_edges(
        ctx, &triangles,
    ));
    violations(ctx, sorted_once(pairs))
}

/// [`check`] restricted to pairs with at least one face marked in
/// `changed` (by face index): for surfaces whose unchanged faces are known
/// not to meet each other ([`near`]).
pub(crate) fn check_near_changed(ctx: &Context, changed: &[bool]) -> Vec<Violation> {
    let triangles = triangulate(ctx);
    let mut pairs = near::pairs_near_changed(ctx, &triangles, changed);
    // Sheets crossing along coincident edges, changed faces or not: no
    // pairwise test sees it.
    pairs.extend(coincident_edges::crossing_along_coincident_edges(
        ctx, &triangles,
    ));
    violations(ctx, sorted_once(pairs))
}

/// The pairs sorted, each once.
fn sorted_once(mut pairs: Vec<(usize, usize)>) -> Vec<(usize, usize)> {
    pairs.sort_unstable();
    pairs.dedup();
    pairs
}

/// One violation per pair of faces.
fn violations(ctx: &Context, pairs: Vec<(usize, usize)>) -> Vec<Violation> {
    pairs
        .into_iter()
        .map(|(a, b)| {
            let lines: Vec<usize> = [a, b].iter().filter_map(|&f| ctx.face_line(f)).collect();
            Violation {
                rule: Rule::SelfIntersection,
                message: format!(
                    "{} and {} intersect{}",
                    ctx.face_name(a),
                    ctx.face_name(b),
                    if faces_share_a_vertex(ctx, a, b) {
                        " beyond the vertices they share"
                    } else {
                        ""
                    }
                ),
                line: lines.first().copied(),
                lines,
                vertices: Vec::new(),
                faces: vec![a, b],
                value: None,
            }
        })
        .collect()
}

/// The triangle's exact bounding box.
fn bounds(ctx: &Context, t: &Triangle) -> Aabb {
    Aabb::from_points(t.vertices.map(|v| ctx.position(v)))
}

/// The pairs of faces (smaller index first, sorted, each once) of which
/// two triangles meet beyond what they share.
fn intersecting_face_pairs(ctx: &Context, triangles: &[Triangle]) -> Vec<(usize, usize)> {
    intersecting_face_pairs_counted(ctx, triangles).0
}

/// What [`intersecting_face_pairs_counted`] did, beyond its answer (read
/// by the tests, which bound the work and the memory).
#[derive(Clone, Copy, Debug, Default)]
#[cfg_attr(not(test), allow(dead_code))]
struct Counts {
    /// Triangle pairs tested exactly.
    tested: usize,
    /// The most candidate triangles the box walks held at once, waiting
    /// for the test (see [`apart::Apart::held`]).
    held: usize,
}

/// [`intersecting_face_pairs`] and what it counted.
///
/// Pairs that share a vertex or an edge come from the topology
/// ([`sharing`]); the box walks ([`apart`]) hand over every other pair
/// whose boxes overlap.
fn intersecting_face_pairs_counted(
    ctx: &Context,
    triangles: &[Triangle],
) -> (Vec<(usize, usize)>, Counts) {
    if triangles.len() < 2 {
        return (Vec::new(), Counts::default());
    }
    let meet = |a: usize, b: usize| -> Option<(usize, usize)> {
        let (ta, tb) = (&triangles[a], &triangles[b]);
        if ta.face == tb.face {
            return None;
        }
        triangles_meet_beyond_shared(ctx, ta, tb)
            .then(|| (ta.face.min(tb.face), ta.face.max(tb.face)))
    };
    let sharing = sharing::pairs_sharing_corners(ctx, triangles, meet);
    // Boxes are made when asked (three positions each) rather than kept:
    // 48 bytes a triangle at the check's peak.
    let apart = apart::pairs_apart(
        ctx,
        triangles,
        |i| bounds(ctx, &triangles[i]),
        sharing::SMALL_FAN,
        meet,
    );
    let mut pairs = apart.found;
    pairs.extend(sharing.found);
    pairs.par_sort_unstable();
    pairs.dedup();
    let counts = Counts {
        tested: sharing.tested + apart.tested,
        held: apart.held,
    };
    (pairs, counts)
}

fn faces_share_a_vertex(ctx: &Context, a: usize, b: usize) -> bool {
    let (ca, cb) = (ctx.corners(a), ctx.corners(b));
    ca.iter().any(|v| cb.contains(v))
}

#[cfg(test)]
mod tests;
