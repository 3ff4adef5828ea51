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
//! How a pair is tested depends on the vertices its triangles share:
//!
//! - none: any common point is a defect (crossing or touching);
//! - one vertex `v`, triangles `(v, a, b)` and `(v, c, d)`: reported when
//!   they cross, that is when segment `ab` passes strictly through the
//!   interior of the second triangle or `cd` through the first (a fin
//!   through a neighbour), or, when the two are coplanar, when their
//!   corners at `v` overlap (a flat fan that wraps over itself). Contacts
//!   only along boundaries beyond `v` (a vertex on a neighbour's edge, as a
//!   zero-area sliver produces) are not reported: the degenerate face that
//!   causes them is;
//! - an edge `uw`, triangles `(u, w, a)` and `(u, w, b)`: when not coplanar
//!   they meet only along `uw`; when coplanar they overlap (a fold) iff `a`
//!   and `b` lie on the same side of `uw`.
//!
//! Faces that are not polygons, degenerate faces and later copies of
//! duplicate faces are left out: other rules report them.

mod apart;
mod around_axis;
mod sharing;
mod triangles;

use glam::{DVec2, DVec3};
use rayon::prelude::*;

use super::super::context::Context;
use super::super::report::{Rule, Violation};
use crate::geom::polygon::Projection;
use crate::geom::{Aabb, Sign, orient2d, orient3d, triangles_intersect};
use triangles::{Triangle, triangulate};

/// Every pair of faces that cross or touch without sharing a vertex.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    let triangles = triangulate(ctx);
    let pairs = intersecting_face_pairs(ctx, &triangles);
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

/// [`intersecting_face_pairs`] and the number of triangle pairs it tested
/// exactly.
///
/// Pairs that share a vertex or an edge come from the topology
/// ([`sharing`]); the box walks ([`apart`]) hand over every other pair
/// whose boxes overlap.
fn intersecting_face_pairs_counted(
    ctx: &Context,
    triangles: &[Triangle],
) -> (Vec<(usize, usize)>, usize) {
    if triangles.len() < 2 {
        return (Vec::new(), 0);
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
    let boxes: Vec<Aabb> = triangles.par_iter().map(|t| bounds(ctx, t)).collect();
    let apart = apart::pairs_apart(ctx, triangles, &boxes, sharing::SMALL_FAN, meet);
    let mut pairs = apart.found;
    pairs.extend(sharing.found);
    pairs.par_sort_unstable();
    pairs.dedup();
    (pairs, sharing.tested + apart.tested)
}

fn faces_share_a_vertex(ctx: &Context, a: usize, b: usize) -> bool {
    let (ca, cb) = (ctx.corners(a), ctx.corners(b));
    ca.iter().any(|v| cb.contains(v))
}

/// Whether two triangles of different faces meet anywhere but at the
/// vertices (or the edge) they share; see the module documentation.
fn triangles_meet_beyond_shared(ctx: &Context, a: &Triangle, b: &Triangle) -> bool {
    let pa = a.vertices.map(|v| ctx.position(v));
    let pb = b.vertices.map(|v| ctx.position(v));
    let shared: smallvec::SmallVec<[(usize, usize); 3]> = (0..3)
        .filter_map(|i| {
            (0..3)
                .find(|&j| b.vertices[j] == a.vertices[i])
                .map(|j| (i, j))
        })
        .collect();
    match shared[..] {
        [] => triangles_intersect(pa, pb),
        [(i, j)] => {
            let (a1, a2) = (pa[(i + 1) % 3], pa[(i + 2) % 3]);
            let (b1, b2) = (pb[(j + 1) % 3], pb[(j + 2) % 3]);
            let v = pa[i];
            let side_a = |p: DVec3| orient3d(pa[0], pa[1], pa[2], p);
            let (s1, s2) = (side_a(b1), side_a(b2));
            if s1 == Sign::Zero && s2 == Sign::Zero {
                // Coplanar. Near v each triangle is its corner: interiors
                // overlap iff the two corners do.
                let projection = projection_of(pa);
                let p = |x: DVec3| projection.apply(x);
                return corners_overlap(p(v), [p(a1), p(a2)], [p(b1), p(b2)]);
            }
            let side_b = |p: DVec3| orient3d(pb[0], pb[1], pb[2], p);
            (s1 != Sign::Zero && s2 == -s1 && crosses_inside(b1, b2, pa)) || {
                let (t1, t2) = (side_b(a1), side_b(a2));
                t1 != Sign::Zero && t2 == -t1 && crosses_inside(a1, a2, pb)
            }
        }
        [(i0, _), (i1, _)] => {
            let (u, w) = (pa[i0], pa[i1]);
            let a_far = pa[3 - i0 - i1];
            let b_far = pb[(0..3)
                .find(|&k| !a.vertices.contains(&b.vertices[k]))
                .unwrap_or(0)];
            if orient3d(u, w, a_far, b_far) != Sign::Zero {
                return false;
            }
            let projection = projection_of(pa);
            let (u2, w2) = (projection.apply(u), projection.apply(w));
            let sa = orient2d(u2, w2, projection.apply(a_far));
            sa != Sign::Zero && sa == orient2d(u2, w2, projection.apply(b_far))
        }
        // The same three vertices: a duplicate, reported as such.
        _ => false,
    }
}

/// Whether the corners at `v` of two coplanar triangles `(v, a…)` and
/// `(v, b…)` (each less than a half-turn) share an open set of directions:
/// a side ray of one strictly inside the other, or the same two side rays.
/// Exact (2-D orientations and coordinate comparisons).
fn corners_overlap(v: DVec2, a: [DVec2; 2], b: [DVec2; 2]) -> bool {
    let ccw = |[p, q]: [DVec2; 2]| {
        if orient2d(v, p, q) == Sign::Negative {
            [q, p]
        } else {
            [p, q]
        }
    };
    let (a, b) = (ccw(a), ccw(b));
    let strictly_inside = |[p, q]: [DVec2; 2], r: DVec2| {
        orient2d(v, p, r) == Sign::Positive && orient2d(v, r, q) == Sign::Positive
    };
    // Same ray from v: collinear and every coordinate on the same side of v.
    let same_ray = |p: DVec2, q: DVec2| {
        let side = |x: f64, o: f64| Sign::of(x - o);
        orient2d(v, p, q) == Sign::Zero
            && side(p.x, v.x) == side(q.x, v.x)
            && side(p.y, v.y) == side(q.y, v.y)
    };
    b.iter().any(|&r| strictly_inside(a, r))
        || a.iter().any(|&r| strictly_inside(b, r))
        || (same_ray(a[0], b[0]) && same_ray(a[1], b[1]))
}

/// For a segment `ab` whose ends lie strictly on opposite sides of the
/// plane of triangle `t`: whether it crosses that plane strictly inside `t`
/// (the line passes all three edges on the same side). Exact.
fn crosses_inside(a: DVec3, b: DVec3, t: [DVec3; 3]) -> bool {
    let s = orient3d(a, b, t[0], t[1]);
    s != Sign::Zero && orient3d(a, b, t[1], t[2]) == s && orient3d(a, b, t[2], t[0]) == s
}

/// An axis projection under which `t` keeps a non-zero area (checked
/// exactly), or the one along its rounded normal for a degenerate `t`.
fn projection_of(t: [DVec3; 3]) -> Projection {
    Projection::of_triangle(t)
        .unwrap_or_else(|| Projection::along((t[1] - t[0]).cross(t[2] - t[0])))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn report_for(positions: Vec<DVec3>, polygons: Vec<Vec<usize>>) -> Vec<Vec<usize>> {
        let soup = crate::mesh::PolygonSoup::new(positions, polygons);
        let report =
            crate::validate::validate_soup(&soup, None, &crate::validate::Options::default())
                .unwrap();
        report
            .of(crate::validate::Rule::SelfIntersection)
            .map(|v| v.faces.clone())
            .collect()
    }

    #[test]
    fn a_model_wider_than_f64_max_does_not_overflow_the_grid() {
        // Found by fuzzing (fixtures/fuzz/obj_validate/): the model's size
        // overflowed to infinity, the cell fell back to 1 and the cell count
        // `size / cell + 1` overflowed `u64`.
        let big = 1e308;
        let p = vec![
            v(-big, 0., 0.),
            v(big, 0., 0.),
            v(0., big, 0.),
            v(0., 0., big),
            v(0., 0., -big),
        ];
        let faces = vec![vec![0, 1, 2], vec![0, 1, 3], vec![1, 2, 4], vec![2, 0, 4]];
        assert!(report_for(p, faces).is_empty());
    }

    #[test]
    fn neighbours_that_fold_or_cross() {
        let p = vec![
            v(0., 0., 0.),
            v(1., 0., 0.),
            v(0., 1., 0.),
            v(1., 1., 0.),
            v(0.3, 0.4, 0.),
            v(0.5, 0.5, 1.),
        ];
        // Sharing edge 0–1: opposite sides (a flat square), no defect; same
        // side (a fold), a defect; with a dihedral angle, none.
        assert!(report_for(p.clone(), vec![vec![0, 1, 3], vec![0, 3, 2]]).is_empty());
        assert_eq!(
            report_for(p.clone(), vec![vec![0, 1, 2], vec![1, 0, 4]]),
            [vec![0, 1]]
        );
        assert!(report_for(p.clone(), vec![vec![0, 1, 2], vec![1, 0, 5]]).is_empty());
        // Sharing vertex 0: a fin through the other triangle, and one that
        // only touches at the shared vertex.
        let q = vec![
            v(0., 0., 0.),
            v(2., 0., 0.),
            v(0., 2., 0.),
            v(0.5, 0.5, -1.),
            v(0.5, 0.5, 1.),
            v(-1., -1., -1.),
            v(-1., -2., 1.),
        ];
        assert_eq!(
            report_for(q.clone(), vec![vec![0, 1, 2], vec![0, 3, 4]]),
            [vec![0, 1]]
        );
        assert!(report_for(q, vec![vec![0, 1, 2], vec![0, 5, 6]]).is_empty());
        // Sharing vertex 0 in one plane: corners that overlap, and corners
        // that only meet along a ray.
        let r = vec![
            v(0., 0., 0.),
            v(2., 0., 0.),
            v(0., 2., 0.),
            v(1., 0.5, 0.),
            v(0.5, 1., 0.),
            v(-2., 0., 0.),
        ];
        assert_eq!(
            report_for(r.clone(), vec![vec![0, 1, 2], vec![0, 3, 4]]),
            [vec![0, 1]]
        );
        assert!(report_for(r, vec![vec![0, 1, 2], vec![0, 2, 5]]).is_empty());
    }

    #[test]
    fn a_huge_triangle_is_tested_against_everything() {
        // A 40 × 40 plate of small triangles and a huge slanted triangle
        // through it, spanning about 30 cells along each axis: far more
        // than MAX_CELLS_PER_TRIANGLE.
        let n = 40;
        let mut positions = Vec::new();
        for i in 0..=n {
            for j in 0..=n {
                positions.push(DVec3::new(i as f64, j as f64, 0.0));
            }
        }
        let at = |i: usize, j: usize| i * (n + 1) + j;
        let mut polygons = Vec::new();
        for i in 0..n {
            for j in 0..n {
                polygons.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
                polygons.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
            }
        }
        let base = positions.len();
        let big = [
            DVec3::new(-1e4, -1e4, -1e4),
            DVec3::new(1e4, 1e4, -1e4),
            DVec3::new(0.0, 35.0, 1e4),
        ];
        positions.extend(big);
        polygons.push(vec![base, base + 1, base + 2]);
        let soup = crate::mesh::PolygonSoup::new(positions.clone(), polygons.clone());
        let expected = polygons[..polygons.len() - 1]
            .iter()
            .filter(|p| triangles_intersect([0, 1, 2].map(|k| positions[p[k]]), big))
            .count();
        assert!(expected > n, "{expected}");
        let report =
            crate::validate::validate_soup(&soup, None, &crate::validate::Options::default())
                .unwrap();
        assert_eq!(
            report.count(crate::validate::Rule::SelfIntersection),
            expected
        );
    }

    /// The positions and faces of a closed cone of `n` sides.
    fn cone(n: usize, centre_fan: bool) -> (Vec<DVec3>, Vec<Vec<usize>>) {
        use crate::mesh::builders::{ConeBase, cone_soup};
        let base = if centre_fan {
            ConeBase::CentreFan
        } else {
            ConeBase::CornerFan
        };
        let soup = cone_soup(n, base);
        let faces = soup.polygons.iter().map(|f| f.vertices.to_vec()).collect();
        (soup.positions, faces)
    }

    /// The face pairs and the number of triangle pairs tested.
    fn counted(positions: Vec<DVec3>, polygons: Vec<Vec<usize>>) -> (Vec<(usize, usize)>, usize) {
        let soup = crate::mesh::PolygonSoup::new(positions, polygons);
        let ctx = Context::new(&soup, None, crate::geom::Tolerance::default());
        intersecting_face_pairs_counted(&ctx, &triangulate(&ctx))
    }

    /// What testing every pair of triangles whose boxes overlap finds.
    fn every_pair(positions: Vec<DVec3>, polygons: Vec<Vec<usize>>) -> Vec<(usize, usize)> {
        let soup = crate::mesh::PolygonSoup::new(positions, polygons);
        let ctx = Context::new(&soup, None, crate::geom::Tolerance::default());
        let triangles = triangulate(&ctx);
        let mut pairs = Vec::new();
        for (i, a) in triangles.iter().enumerate() {
            for b in &triangles[i + 1..] {
                if a.face != b.face
                    && apart::overlap(&bounds(&ctx, a), &bounds(&ctx, b))
                    && triangles_meet_beyond_shared(&ctx, a, b)
                {
                    pairs.push((a.face.min(b.face), a.face.max(b.face)));
                }
            }
        }
        pairs.sort_unstable();
        pairs.dedup();
        pairs
    }

    #[test]
    fn cones_and_fans_test_a_bounded_number_of_pairs_per_triangle() {
        // Around an apex of valence n a box walk tests n²/2 pairs; here the
        // pairs tested stay a small multiple of the triangles.
        let n = 600;
        for centre_fan in [true, false] {
            let (p, f) = cone(n, centre_fan);
            let triangles = f.len();
            let (pairs, tested) = counted(p, f);
            assert!(pairs.is_empty(), "{pairs:?}");
            // About 5 per triangle with a centre fan, 12 with a corner fan
            // (whose long chords run along the rim); every pair would be
            // over 100 per triangle.
            assert!(
                tested <= 16 * triangles,
                "{tested} pairs for {triangles} triangles"
            );
        }
        // A fan of n triangles on one edge: n²/2 pairs share the edge.
        let fan = crate::mesh::builders::edge_fan_soup(n);
        let faces = fan.polygons.iter().map(|f| f.vertices.to_vec()).collect();
        let (pairs, tested) = counted(fan.positions, faces);
        assert!(pairs.is_empty(), "{pairs:?}");
        assert!(tested <= 8 * n, "{tested} pairs for {n} triangles");
    }

    #[test]
    fn an_apex_face_folded_through_its_neighbours_is_found() {
        // Rim vertex 10 pulled out past the rim at a third of a turn: the two
        // apex faces at it cross the apex faces they sweep over (sharing
        // only the apex with them) and the base.
        let n = 200;
        for centre_fan in [true, false] {
            let (mut p, f) = cone(n, centre_fan);
            let a = std::f64::consts::TAU / 3.0;
            let rim = if centre_fan { 2 } else { 1 };
            p[rim + 10] = v(1.5 * a.cos(), 1.5 * a.sin(), 0.1);
            let want = every_pair(p.clone(), f.clone());
            let (found, _) = counted(p, f);
            assert_eq!(found, want);
            // Apex faces 9 and 10 against apex faces they share only the
            // apex with.
            assert!(
                found
                    .iter()
                    .any(|&(a, b)| (9..=10).contains(&a) && b > 11 && b < n),
                "{found:?}"
            );
        }
    }

    #[test]
    fn the_angular_filters_find_what_every_pair_finds() {
        let mut unit = crate::test_rng::uniform(21);
        let mut random = |lo: f64, hi: f64| lo + (hi - lo) * unit();
        // A flat fan that wraps over itself 1.3 times.
        let m = 120;
        let mut p = vec![v(0., 0., 0.)];
        p.extend((0..=m).map(|i| {
            let a = 1.3 * std::f64::consts::TAU * i as f64 / m as f64;
            v(a.cos(), a.sin(), 0.)
        }));
        let f: Vec<Vec<usize>> = (0..m).map(|i| vec![0, i + 1, i + 2]).collect();
        let want = every_pair(p.clone(), f.clone());
        assert!(!want.is_empty());
        assert_eq!(counted(p, f).0, want);
        // A fan on one edge with repeated half-planes, some opposite.
        let mut p = vec![v(0., 0., 0.), v(0., 0., 1.)];
        let mut f = Vec::new();
        for k in 0..80 {
            let a = std::f64::consts::TAU * (k % 30) as f64 / 30.0;
            let r = 1.0 + 0.1 * k as f64;
            p.push(v(r * a.cos(), r * a.sin(), [0.5, 1.5, -0.5][k % 3]));
            f.push(vec![0, 1, k + 2]);
        }
        let want = every_pair(p.clone(), f.clone());
        assert!(!want.is_empty());
        assert_eq!(counted(p, f).0, want);
        // Random stars around one vertex, and cones with random rim
        // vertices.
        for round in 0..6 {
            let (mut p, f) = if round % 2 == 0 {
                let mut p = vec![v(0., 0., 0.)];
                p.extend((0..60).map(|_| v(random(-1., 1.), random(-1., 1.), random(-1., 1.))));
                let f = (0..60).map(|k| vec![0, 1 + k, 1 + (k + 1) % 60]).collect();
                (p, f)
            } else {
                cone(100, round % 4 == 1)
            };
            if round % 2 == 1 {
                for k in [7, 31, 64] {
                    p[k] = v(random(-1.2, 1.2), random(-1.2, 1.2), random(-0.3, 0.8));
                }
            }
            let want = every_pair(p.clone(), f.clone());
            assert!(!want.is_empty(), "round {round}");
            assert_eq!(counted(p, f).0, want, "round {round}");
        }
    }

    fn v(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }
}
