//! Tests of the self-intersection check: verdicts against testing every
//! pair, and the work and memory the walks take.

use super::*;
use crate::geom::triangles_intersect;
use glam::DVec3;

fn report_for(positions: Vec<DVec3>, polygons: Vec<Vec<usize>>) -> Vec<Vec<usize>> {
    let soup = crate::mesh::PolygonSoup::new(positions, polygons);
    let report =
        crate::validate::validate_soup(&soup, None, &crate::validate::Options::default()).unwrap();
    intersecting(&report)
}

/// The pairs of faces a report names as intersecting.
fn intersecting(report: &crate::validate::Report) -> Vec<Vec<usize>> {
    report
        .of(crate::validate::Rule::SelfIntersection)
        .map(|v| v.faces.clone())
        .collect()
}

/// The restricted check finds a crossing when either of the two faces
/// is marked changed, every pair of marked faces, and nothing between
/// unmarked faces (their caller vouches for them).
#[test]
fn the_check_near_changed_faces_sees_every_pair_with_a_changed_face() {
    // Three triangles: 0 and 1 cross, 2 far away.
    let p = vec![
        v(0., 0., 0.),
        v(2., 0., 0.),
        v(0., 2., 0.),
        v(0.5, 0.5, -1.),
        v(0.5, 0.5, 1.),
        v(1.5, 0.2, 0.),
        v(9., 9., 9.),
        v(10., 9., 9.),
        v(9., 10., 9.),
    ];
    let faces = vec![vec![0, 1, 2], vec![3, 4, 5], vec![6, 7, 8]];
    let soup = crate::mesh::PolygonSoup::new(p, faces);
    let near = |changed: [bool; 3]| -> Vec<Vec<usize>> {
        intersecting(&crate::validate::validate_soup_near_changed(&soup, &changed).unwrap())
    };
    assert_eq!(near([true, false, false]), vec![vec![0, 1]]);
    assert_eq!(near([false, true, false]), vec![vec![0, 1]]);
    assert_eq!(near([true, true, true]), vec![vec![0, 1]]);
    assert!(near([false, false, true]).is_empty());
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
        crate::validate::validate_soup(&soup, None, &crate::validate::Options::default()).unwrap();
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
    let (pairs, counts) = counted_all(positions, polygons);
    (pairs, counts.tested)
}

/// The face pairs and what the check counted.
fn counted_all(positions: Vec<DVec3>, polygons: Vec<Vec<usize>>) -> (Vec<(usize, usize)>, Counts) {
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

/// Two fans of `m` slivers each from hubs 0.1 apart, sloping a little
/// above and along each other over a bumpy plate of small triangles that
/// they cut (the shape of manifold's `Generic_Twin` models: two
/// sheets of long thin fans a hair apart, every sliver's box overlapping
/// thousands of others).
fn twin_fans(m: usize, cells: usize) -> (Vec<DVec3>, Vec<Vec<usize>>) {
    let mut p = Vec::new();
    let mut f = Vec::new();
    let at = |i: usize, j: usize| i * (cells + 1) + j;
    for i in 0..=cells {
        for j in 0..=cells {
            let bump = 0.45 * ((i * 7 + j * 3) % 5) as f64 / 4.0;
            p.push(v(i as f64, j as f64, bump));
        }
    }
    for i in 0..cells {
        for j in 0..cells {
            f.push(vec![at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            f.push(vec![at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    let far = cells as f64 + 1.0;
    for (hub_z, rim_z, shift) in [(0.6, 0.3, 0.0), (0.7, 0.35, 0.5)] {
        let hub = p.len();
        p.push(v(-1., -1., hub_z));
        for k in 0..=m {
            let s = (k as f64 + shift) / (m as f64 + 1.0);
            p.push(v(far - s * (far + 1.0), -1. + s * (far + 1.0), rim_z));
        }
        f.extend((0..m).map(|k| vec![hub, hub + 1 + k, hub + 2 + k]));
    }
    (p, f)
}

#[test]
fn slivers_over_slivers_are_decided_as_found_not_gathered() {
    let (m, cells) = (200, 16);
    let (p, f) = twin_fans(m, cells);
    let triangles = f.len();
    let want = every_pair(p.clone(), f.clone());
    let (found, counts) = counted_all(p, f);
    // The fans cut the plate's bumps; they never meet each other.
    assert!(!want.is_empty());
    assert!(want.iter().all(|&(a, _)| a < 2 * cells * cells), "{want:?}");
    assert_eq!(found, want);
    // Gathering every candidate first would hold at least as many as are
    // tested; one triangle's finds are all that is ever held.
    assert!(
        counts.tested > 20 * counts.held,
        "{} tested, {} held",
        counts.tested,
        counts.held
    );
    assert!(counts.held <= triangles, "{} held", counts.held);
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
fn an_apex_face_folded_in_the_rim_plane_meets_the_faces_it_folds_over() {
    // Rim vertex 10 pulled past the rim within the rim's plane: the far
    // edges of apex faces 9 and 10 each cross the far edge of one other
    // apex face exactly (in that plane, where they pass the rim), so
    // those faces meet along a segment from the apex; no edge passes
    // strictly through a face. A rule that asks for a strict crossing
    // misses these pairs.
    let n = 200;
    for centre_fan in [true, false] {
        let (mut p, f) = cone(n, centre_fan);
        let a = std::f64::consts::TAU / 3.0;
        let rim = if centre_fan { 2 } else { 1 };
        p[rim + 10] = v(1.5 * a.cos(), 1.5 * a.sin(), 0.);
        let want = every_pair(p.clone(), f.clone());
        let (found, _) = counted(p.clone(), f.clone());
        assert_eq!(found, want);
        // Apex faces (0..n) that share only the apex with face 9 or 10.
        let apex_only = |&&(a, b): &&(usize, usize)| (9..=10).contains(&a) && b > 11 && b < n;
        let folded_over: Vec<(usize, usize)> = found.iter().filter(apex_only).copied().collect();
        // Each of the two far edges crosses the rim once more.
        assert_eq!(folded_over.len(), 2, "{found:?}");
        let reported: Vec<(usize, usize)> = report_for(p, f)
            .iter()
            .map(|pair| (pair[0], pair[1]))
            .collect();
        assert!(folded_over.iter().all(|pair| reported.contains(pair)));
    }
}

#[test]
fn faces_on_one_vertex_whose_far_edges_cross_are_reported() {
    // Two upright triangles on the apex (0, 0, 1), far edges crossing at
    // the origin: they meet along the segment from the apex down.
    let p = vec![
        v(0., 0., 1.),
        v(-1., 0., 0.),
        v(1., 0., 0.),
        v(0., -1., 0.),
        v(0., 1., 0.),
    ];
    assert_eq!(
        report_for(p, vec![vec![0, 1, 2], vec![0, 3, 4]]),
        [vec![0, 1]]
    );
    // Two faces of one plane on one vertex, one's side along the other's
    // (a vertex on an edge it is not joined to): they share a segment.
    let q = vec![
        v(0., 0., 0.),
        v(2., 0., 0.),
        v(0., 2., 0.),
        v(0., 1., 0.),
        v(-2., 0., 0.),
    ];
    assert_eq!(
        report_for(q, vec![vec![0, 1, 2], vec![0, 3, 4]]),
        [vec![0, 1]]
    );
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

/// The soups of several solids side by side, each with its own
/// vertices (coincident positions stay distinct vertices).
fn side_by_side(solids: &[crate::mesh::Solid]) -> (Vec<DVec3>, Vec<Vec<usize>>) {
    let (mut positions, mut polygons) = (Vec::new(), Vec::new());
    for solid in solids {
        let soup = solid.to_soup();
        let base = positions.len();
        positions.extend(soup.positions);
        polygons.extend(
            soup.polygons
                .iter()
                .map(|p| p.vertices.iter().map(|&i| base + i).collect()),
        );
    }
    (positions, polygons)
}

/// An octahedron with its equator the unit square's corners (±1, 0, 0),
/// (0, ±1, 0), apexes at heights `up` and `-down`.
fn bipyramid(up: f64, down: f64) -> crate::mesh::Solid {
    let p = vec![
        v(1., 0., 0.),
        v(0., 1., 0.),
        v(-1., 0., 0.),
        v(0., -1., 0.),
        v(0., 0., up),
        v(0., 0., -down),
    ];
    let mut faces = Vec::new();
    for k in 0..4 {
        faces.push(vec![k, (k + 1) % 4, 4]);
        faces.push(vec![(k + 1) % 4, k, 5]);
    }
    crate::mesh::Solid::try_from_polygons(&p, faces).unwrap()
}

/// Sheets that touch along coincident edges are no defect; sheets that
/// cross along a loop of them, or whose solids overlap there, are,
/// though every pair of their triangles meets only along an edge.
#[test]
fn sheets_touching_or_crossing_along_coincident_edges() {
    use crate::mesh::builders::cuboid;
    let a = cuboid(DVec3::ZERO, DVec3::ONE).unwrap();
    let b = cuboid(v(1., 1., 0.), v(2., 2., 1.)).unwrap();
    let (p, f) = side_by_side(&[a, b]);
    let soup = crate::mesh::PolygonSoup::new(p.clone(), f.clone());
    let report =
        crate::validate::validate_soup(&soup, None, &crate::validate::Options::default()).unwrap();
    assert_eq!(
        report.validity,
        crate::validate::Validity::ValidSolid,
        "{:?}",
        report.violations
    );
    assert_eq!(report.shells, 2);
    // Cubes sharing a face: two faces in one place.
    let c = cuboid(v(0., 0., 0.), v(1., 1., 1.)).unwrap();
    let d = cuboid(v(-1., 0., 0.), v(0., 1., 1.)).unwrap();
    assert!(!report_for_solids(&[c, d]).is_empty());
    // Equators at one place: crossing (one apex above the other's,
    // the other below) and nested.
    // At each equator edge, crossing: both wedges hold a face of the
    // other; nested: the outer one holds the inner's.
    for (solids, per_edge) in [
        ([bipyramid(1., 2.), bipyramid(2., 1.)], 2),
        ([bipyramid(1., 1.), bipyramid(2., 2.)], 1),
    ] {
        let pairs = report_for_solids(&solids);
        assert_eq!(pairs.len(), 4 * per_edge, "{pairs:?}");
        assert!(pairs.iter().all(|p| p[0] < 8 && p[1] >= 8), "{pairs:?}");
    }
}

fn report_for_solids(solids: &[crate::mesh::Solid]) -> Vec<Vec<usize>> {
    let (p, f) = side_by_side(solids);
    report_for(p, f)
}

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}
