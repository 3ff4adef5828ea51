//! Tests of `weld.rs`.

use super::*;
use crate::mesh::Solid;

/// A cube with every face carrying its own four corners (24 vertices).
fn split_cube() -> PolygonSoup {
    let corner =
        |i: usize| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64);
    let faces = [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ];
    let mut positions = Vec::new();
    let mut polygons = Vec::new();
    for f in faces {
        let base = positions.len();
        positions.extend(f.iter().map(|&c| corner(c)));
        polygons.push(vec![base, base + 1, base + 2, base + 3]);
    }
    PolygonSoup::new(positions, polygons)
}

#[test]
fn a_split_cube_is_welded_closed() {
    let soup = split_cube();
    let lines = (1..=24).collect();
    let (welded, lines, numbers, report) = weld(soup, lines, WeldMode::Exact);
    assert_eq!(report.merged, 16);
    assert!(report.refused.is_empty());
    assert_eq!(welded.positions.len(), 8);
    assert_eq!(lines.len(), 8);
    assert_eq!(numbers[0], 1);
    let solid = Solid::try_from_soup(&welded).unwrap();
    assert!(solid.is_closed());
    assert_eq!(solid.euler_characteristic(), 2);
}

#[test]
fn no_weld_and_tolerant_weld() {
    let (s, ..) = weld(split_cube(), (1..=24).collect(), WeldMode::None);
    assert_eq!(s.positions.len(), 24);
    let mut soup = split_cube();
    soup.positions[0].x += 1e-9;
    let (s, _, _, r) = weld(soup.clone(), (1..=24).collect(), WeldMode::Exact);
    assert!(s.positions.len() > 8, "{r:?}");
    let tolerance = Tolerance {
        weld: 1e-6,
        ..Tolerance::default()
    };
    let (s, ..) = weld(soup, (1..=24).collect(), WeldMode::Within(tolerance));
    assert_eq!(s.positions.len(), 8);
}

#[test]
fn a_tolerance_too_small_for_the_grid_still_welds() {
    // Regression (no-panic audit): with `--weld 1e-300` a vertex's grid
    // cell overflows `i64` and saturates; stepping to the neighbouring
    // cells overflowed too (a panic in debug builds).
    let tolerance = Tolerance {
        weld: 1e-300,
        ..Tolerance::default()
    };
    let (s, _, _, r) = weld(
        split_cube(),
        (1..=24).collect(),
        WeldMode::Within(tolerance),
    );
    assert_eq!(s.positions.len(), 8, "{r:?}");
    let mut far = split_cube();
    for p in &mut far.positions {
        *p = *p * 1e300 - DVec3::splat(1e300);
    }
    let (s, ..) = weld(far, (1..=24).collect(), WeldMode::Within(tolerance));
    assert_eq!(s.positions.len(), 8);
}

#[test]
fn two_split_cubes_touching_at_a_corner_weld_into_two_solids() {
    // Each cube's 24 corner copies weld into 8; the shared corner (1,1,1)
    // of the first and (1,1,1) of the second are not merged into one
    // pinch vertex: no edge glues copies of different cubes.
    let a = split_cube();
    let mut soup = a.clone();
    for p in &a.polygons {
        soup.polygons
            .push(crate::mesh::Polygon::new(p.vertices.iter().map(|v| v + 24)));
    }
    soup.positions
        .extend(a.positions.iter().map(|&p| p + DVec3::ONE));
    let (welded, _, _, report) = weld(soup, (1..=48).collect(), WeldMode::Exact);
    assert_eq!(report.merged, 32);
    assert!(report.refused.is_empty());
    assert_eq!(welded.positions.len(), 16);
    let solid = Solid::try_from_soup(&welded).unwrap();
    assert_eq!(solid.shells().len(), 2);
}

#[test]
fn a_weld_that_would_make_a_face_repeat_a_vertex_is_refused() {
    // Quad 0 has corners 1 and 2 a hair apart. Triangle 1 glues to the
    // quad along 0–1 and triangle 2 along 2–3; both triangles use vertex
    // 5, so gluing both would merge corners 1 and 2 of the quad.
    let positions = vec![
        DVec3::new(0., 0., 0.),
        DVec3::new(1., 0., 0.),
        DVec3::new(1., 1e-7, 0.),
        DVec3::new(0., 1., 0.),
        DVec3::new(0., 0., 0.),
        DVec3::new(1., 1e-7, 0.),
        DVec3::new(0.5, -1., 0.),
        DVec3::new(0., 1., 0.),
        DVec3::new(0.5, 2., 0.),
    ];
    let soup = PolygonSoup::new(positions, [vec![0, 1, 2, 3], vec![5, 4, 6], vec![7, 5, 8]]);
    let tolerance = Tolerance {
        weld: 1e-6,
        ..Tolerance::default()
    };
    let (welded, _, _, report) = weld(soup, (1..=9).collect(), WeldMode::Within(tolerance));
    assert!(
        report
            .refused
            .iter()
            .any(|r| matches!(r, WeldRefusal::WouldRepeatVertex { face: 0, .. })),
        "{report:?}"
    );
    let quad = &welded.polygons[0].vertices;
    let mut distinct = quad.to_vec();
    distinct.sort_unstable();
    distinct.dedup();
    assert_eq!(distinct.len(), 4, "{quad:?}");
}

#[test]
fn coincident_corners_without_glued_edges_stay_apart() {
    // Two triangles touching at a corner through two separate vertices:
    // no pair of their open edges joins the same positions, so nothing
    // is merged (a weld by position alone would make a pinch).
    let positions = vec![
        DVec3::ZERO,
        DVec3::X,
        DVec3::Y,
        DVec3::ZERO,
        -DVec3::X,
        -DVec3::Y,
    ];
    let soup = PolygonSoup::new(positions, [[0, 1, 2], [3, 4, 5]]);
    let (s, _, _, report) = weld(soup, (1..=6).collect(), WeldMode::Exact);
    assert_eq!(s.positions.len(), 6, "{report:?}");
}

/// `soup` as a binary STL has it: triangles (fanned), each with three
/// corners of its own.
fn as_stl(soup: &PolygonSoup) -> PolygonSoup {
    let mut positions = Vec::new();
    let mut triangles = Vec::new();
    for p in &soup.polygons {
        for i in 1..p.vertices.len() - 1 {
            let base = positions.len();
            positions.extend([0, i, i + 1].map(|k| soup.positions[p.vertices[k]]));
            triangles.push([base, base + 1, base + 2]);
        }
    }
    PolygonSoup::new(positions, triangles)
}

/// The general weld (glue, refuse, repeat), without the fast path.
fn general_weld(soup: PolygonSoup) -> (PolygonSoup, Vec<usize>, Vec<usize>, WeldReport) {
    let n = soup.positions.len();
    let cluster = clusters(&soup.positions, WeldMode::Exact).unwrap();
    let shared: Vec<bool> = (0..n)
        .map(|v| cluster[v] != v || cluster.iter().enumerate().any(|(w, &c)| c == v && w != v))
        .collect();
    let (uf, refused) = glue(&soup, &cluster, &shared, &[]);
    compact(
        soup,
        Vec::new(),
        (1..=n).collect(),
        uf,
        WeldMode::Exact,
        refused,
    )
}

#[test]
fn the_fast_path_welds_as_the_general_weld_does() {
    let cube = as_stl(&split_cube());
    let mut touching = cube.clone();
    touching.polygons.extend(
        cube.polygons.iter().map(|p| {
            crate::mesh::Polygon::new(p.vertices.iter().map(|v| v + cube.positions.len()))
        }),
    );
    touching
        .positions
        .extend(cube.positions.iter().map(|&p| p + DVec3::ONE));
    let mut open = cube.clone();
    open.polygons.pop();
    let mut unused = cube.clone();
    unused.positions.push(DVec3::ZERO);
    let cases = [
        ("a closed cube", cube, true),
        ("two cubes touching at a corner (a pinch)", touching, false),
        ("an open cube", open, false),
        ("a vertex no triangle uses", unused, false),
    ];
    for (name, soup, fast) in cases {
        let n = soup.positions.len();
        let cluster = clusters(&soup.positions, WeldMode::Exact).unwrap();
        assert_eq!(clusters_close_triangles(&soup, &cluster), fast, "{name}");
        let general = general_weld(soup.clone());
        let welded = weld(soup, Vec::new(), WeldMode::Exact);
        assert_eq!(welded, general, "{name}");
        if fast {
            assert_eq!(welded.3.merged, n - 8, "{name}");
            let solid = Solid::try_from_soup(&welded.0).unwrap();
            assert!(solid.is_closed(), "{name}");
        }
    }
}

#[test]
fn the_torus_stl_takes_the_fast_path_to_the_general_answer() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/formats/torus.stl");
    let bytes = std::fs::read(&path).unwrap();
    let parsed = crate::io::stl::read(&path, &bytes, &crate::io::ImportOptions::default()).unwrap();
    let soup = PolygonSoup {
        positions: parsed.positions,
        polygons: parsed.polygons,
    };
    let cluster = clusters(&soup.positions, WeldMode::Exact).unwrap();
    assert!(clusters_close_triangles(&soup, &cluster));
    let welded = weld(soup.clone(), Vec::new(), WeldMode::Exact);
    assert_eq!(welded, general_weld(soup));
    assert_eq!(welded.3.merged, 192 * 3 - 96);
}
