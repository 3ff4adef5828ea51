//! Building solids from polygon soups: what is accepted, what is refused and
//! how refusals name the culprits.

use glam::DVec3;
use wingedge::geom::Sign;
use wingedge::mesh::{BuildError, PolygonSoup, Solid, builders};

fn cube_positions() -> Vec<DVec3> {
    let mut v = Vec::new();
    for z in [0.0, 1.0] {
        for y in [0.0, 1.0] {
            for x in [0.0, 1.0] {
                v.push(DVec3::new(x, y, z));
            }
        }
    }
    v
}

/// The unit cube's faces, counter-clockwise from outside (index = x + 2y + 4z).
const CUBE: [[usize; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

#[test]
fn cube_from_soup_matches_the_builder() {
    let solid = Solid::try_from_polygons(&cube_positions(), CUBE).unwrap();
    solid.check_consistency().unwrap();
    assert_eq!(
        (solid.vertex_count(), solid.edge_count(), solid.face_count()),
        (8, 12, 6)
    );
    assert_eq!(solid.volume(), 1.0);
    assert_eq!(solid.centroid(), Some(DVec3::splat(0.5)));
    for (_, face) in solid.faces() {
        assert!(face.attributes.source_index.is_some());
    }
    // Exact side of a face: the bottom face z = 0 (polygon 0).
    let (bottom, _) = solid.faces().next().unwrap();
    let tiny = f64::MIN_POSITIVE;
    assert_eq!(
        solid.face_side(bottom, DVec3::new(0.3, 0.7, 0.0)),
        Sign::Zero
    );
    assert_eq!(
        solid.face_side(bottom, DVec3::new(0.3, 0.7, -tiny)),
        Sign::Positive
    );
    assert_eq!(
        solid.face_side(bottom, DVec3::new(0.3, 0.7, tiny)),
        Sign::Negative
    );
    assert_eq!(
        solid.face_side(bottom, DVec3::new(1e300, -1e300, 0.0)),
        Sign::Zero
    );
}

#[test]
fn an_open_box_is_representable_and_walkable() {
    let solid = Solid::try_from_polygons(&cube_positions(), &CUBE[1..]).unwrap();
    solid.check_consistency().unwrap();
    assert!(!solid.is_closed());
    assert_eq!(solid.boundary_edges().count(), 4);
    let shells = solid.shells();
    assert_eq!(shells.len(), 1);
    assert_eq!(shells[0].boundary_edge_count, 4);
    assert_eq!(shells[0].genus(), None);
    // Every vertex star is complete even on the rim: degree 3 everywhere.
    for (v, _) in solid.vertices() {
        assert_eq!(solid.vertex_degree(v), 3);
        let faces = solid.vertex_faces(v).count();
        assert!(faces == 2 || faces == 3);
    }
}

#[test]
fn two_disjoint_cubes_are_two_shells_and_a_hollow_box_has_an_inward_shell() {
    let mut positions = cube_positions();
    positions.extend(cube_positions().iter().map(|p| *p + DVec3::splat(5.0)));
    let mut polygons: Vec<Vec<usize>> = CUBE.iter().map(|f| f.to_vec()).collect();
    polygons.extend(CUBE.iter().map(|f| f.iter().map(|i| i + 8).collect()));
    let two = Solid::try_from_polygons(&positions, &polygons).unwrap();
    two.check_consistency().unwrap();
    let shells = two.shells();
    assert_eq!(shells.len(), 2);
    assert!(
        shells
            .iter()
            .all(|s| s.genus() == Some(0) && s.signed_volume == 1.0)
    );
    assert_eq!(two.euler_characteristic(), 4);

    // A hollow box: a 4-cube with a reversed unit cube inside.
    let mut positions: Vec<DVec3> = cube_positions().iter().map(|p| *p * 4.0).collect();
    positions.extend(cube_positions().iter().map(|p| *p + DVec3::splat(1.5)));
    let mut polygons: Vec<Vec<usize>> = CUBE.iter().map(|f| f.to_vec()).collect();
    polygons.extend(CUBE.iter().map(|f| f.iter().rev().map(|i| i + 8).collect()));
    let hollow = Solid::try_from_polygons(&positions, &polygons).unwrap();
    hollow.check_consistency().unwrap();
    let shells = hollow.shells();
    assert_eq!(shells[0].signed_volume, 64.0);
    assert_eq!(shells[1].signed_volume, -1.0);
    assert_eq!(hollow.volume(), 63.0);
}

#[test]
fn a_torus_has_genus_one() {
    // A square ring: an 3x3 grid of unit squares minus the centre, extruded.
    let ring = builders::prism(
        &[(0., 0.), (3., 0.), (3., 3.), (0., 3.)].map(|(x, y)| DVec3::new(x, y, 0.)),
        DVec3::Z,
    )
    .unwrap();
    assert_eq!(ring.shells()[0].genus(), Some(0));
    let soup = torus_soup(12, 8);
    let torus = Solid::try_from_soup(&soup).unwrap();
    torus.check_consistency().unwrap();
    assert_eq!(torus.euler_characteristic(), 0);
    assert_eq!(torus.shells()[0].genus(), Some(1));
    assert!(torus.volume() > 0.0);
}

/// A quad-faced torus of major radius 3 and minor radius 1.
fn torus_soup(n: usize, m: usize) -> PolygonSoup {
    let mut positions = Vec::new();
    for i in 0..n {
        let u = std::f64::consts::TAU * i as f64 / n as f64;
        for j in 0..m {
            let v = std::f64::consts::TAU * j as f64 / m as f64;
            let r = 3.0 + v.cos();
            positions.push(DVec3::new(r * u.cos(), r * u.sin(), v.sin()));
        }
    }
    let at = |i: usize, j: usize| (i % n) * m + j % m;
    let polygons: Vec<Vec<usize>> = (0..n)
        .flat_map(|i| {
            (0..m).map(move |j| vec![at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)])
        })
        .collect();
    PolygonSoup::new(positions, polygons)
}

#[test]
fn refusals_name_the_culprits() {
    let p = cube_positions();
    assert_eq!(
        Solid::try_from_polygons(&p, Vec::<Vec<usize>>::new()).unwrap_err(),
        BuildError::NoPolygons
    );
    assert!(matches!(
        Solid::try_from_polygons(&p, [vec![0, 1]]),
        Err(BuildError::TooFewVertices {
            polygon: 0,
            count: 2,
            ..
        })
    ));
    assert!(matches!(
        Solid::try_from_polygons(&p, [vec![0, 1, 2], vec![0, 9, 1]]),
        Err(BuildError::IndexOutOfRange {
            polygon: 1,
            index: 9,
            len: 8,
            ..
        })
    ));
    assert!(matches!(
        Solid::try_from_polygons(&p, [vec![0, 1, 3, 1]]),
        Err(BuildError::RepeatedVertex {
            polygon: 0,
            vertex: 1,
            ..
        })
    ));
    let mut bad = p.clone();
    bad[3].y = f64::NAN;
    assert!(matches!(
        Solid::try_from_polygons(&bad, CUBE),
        Err(BuildError::NonFinitePosition { vertex: 3, .. })
    ));
    // Three faces on edge 0–1.
    let err =
        Solid::try_from_polygons(&p, [vec![0, 1, 2], vec![1, 0, 4], vec![0, 1, 6]]).unwrap_err();
    assert_eq!(
        err,
        BuildError::NonManifoldEdge {
            vertices: [0, 1],
            polygons: vec![0, 1, 2],
            lines: vec![None; 3]
        }
    );
    assert!(err.to_string().contains("used by 3 polygons"));
    // Edge 0→1 run twice in the same direction.
    let err = Solid::try_from_polygons(&p, [vec![0, 1, 2], vec![0, 1, 4]]).unwrap_err();
    assert!(matches!(
        err,
        BuildError::InconsistentOrientation {
            vertices: [0, 1],
            polygons: [0, 1],
            ..
        }
    ));
    // Two tetrahedra sharing only vertex 0 (a pinch point).
    let mut q = vec![DVec3::ZERO];
    for s in [1.0, -1.0] {
        q.extend([
            DVec3::new(s, 0., 0.),
            DVec3::new(s, 1., 0.),
            DVec3::new(s, 0., 1.),
        ]);
    }
    let tet = |o: usize| {
        vec![
            vec![0, o + 2, o + 1],
            vec![0, o + 1, o + 3],
            vec![0, o + 3, o + 2],
            vec![o + 1, o + 2, o + 3],
        ]
    };
    let mut polys = tet(0);
    polys.extend(tet(3));
    // It builds: the second fan at the pinch gets a vertex of its own, at
    // the same position and with the same soup index, so the solid is two
    // closed shells that touch (validation still reports the pinch).
    let solid = Solid::try_from_polygons(&q, &polys).expect("a pinch builds");
    solid.check_consistency().unwrap();
    assert_eq!(
        (solid.vertex_count(), solid.edge_count(), solid.face_count()),
        (8, 12, 8)
    );
    let at_pinch: Vec<_> = solid
        .vertices()
        .filter(|(_, v)| v.position == DVec3::ZERO)
        .map(|(_, v)| v.source_index)
        .collect();
    assert_eq!(at_pinch, vec![Some(0), Some(0)]);
    assert_eq!(solid.shells().len(), 2);
}

#[test]
fn lines_appear_in_messages() {
    let mut soup = PolygonSoup::new(cube_positions(), [vec![0usize, 1, 2], vec![0, 1, 4]]);
    soup.polygons[0].attributes.line = Some(10);
    soup.polygons[1].attributes.line = Some(11);
    let message = Solid::try_from_soup(&soup).unwrap_err().to_string();
    assert!(
        message.contains("Some(10)") || message.contains("10"),
        "{message}"
    );
    let mut soup = PolygonSoup::new(cube_positions(), [vec![0usize, 1]]);
    soup.polygons[0].attributes.line = Some(4711);
    assert!(
        Solid::try_from_soup(&soup)
            .unwrap_err()
            .to_string()
            .contains("line 4711")
    );
}

#[test]
fn degenerate_faces_are_stored_without_a_plane() {
    // A triangular prism whose "cap" on one end is split by a collinear vertex.
    let positions = vec![
        DVec3::new(0., 0., 0.),
        DVec3::new(2., 0., 0.),
        DVec3::new(0., 2., 0.),
        DVec3::new(0., 0., 1.),
        DVec3::new(2., 0., 1.),
        DVec3::new(0., 2., 1.),
        DVec3::new(1., 0., 0.), // on edge 0–1
    ];
    let polygons = vec![
        vec![0, 2, 1, 6],
        vec![3, 4, 5],
        vec![0, 6, 3],
        vec![6, 1, 4, 3],
        vec![1, 2, 5, 4],
        vec![2, 0, 3, 5],
    ];
    let solid = Solid::try_from_polygons(&positions, &polygons).unwrap();
    solid.check_consistency().unwrap();
    assert!(solid.faces().all(|(_, f)| f.plane.is_some()));
    assert!((solid.volume() - 2.0).abs() < 1e-15);
    // Now a sliver with three collinear vertices.
    let sliver = Solid::try_from_polygons(
        &[DVec3::ZERO, DVec3::X, DVec3::X * 2.0, DVec3::Y],
        [vec![0, 1, 2], vec![0, 2, 3]],
    )
    .unwrap();
    let planes: Vec<bool> = sliver.faces().map(|(_, f)| f.plane.is_some()).collect();
    assert_eq!(planes, [false, true]);
}

/// An edge shared by 1,000 triangles: the error keeps every polygon and
/// line, its message shows ten and says how many more.
#[test]
fn a_fan_on_one_edge_gives_a_short_message_and_the_full_lists() {
    let mut positions = vec![DVec3::ZERO, DVec3::Z];
    let mut polygons = Vec::new();
    for k in 0..1000 {
        let angle = f64::from(k) * std::f64::consts::TAU / 1000.0;
        positions.push(DVec3::new(angle.cos(), angle.sin(), 0.5));
        polygons.push(vec![0, 1, k as usize + 2]);
    }
    let err = Solid::try_from_soup(&PolygonSoup::new(positions, polygons)).unwrap_err();
    let BuildError::NonManifoldEdge { polygons, .. } = &err else {
        panic!("{err}");
    };
    assert_eq!(polygons.len(), 1000);
    let message = err.to_string();
    assert!(message.len() < 200, "{} bytes: {message}", message.len());
    assert!(
        message.starts_with(
            "edge 0–1 is used by 1000 polygons [0, 1, 2, 3, 4, 5, 6, 7, 8, 9, … and 990 more]"
        ),
        "{message}"
    );
}

/// A closed cone whose apex and base centre each have valence 3,000 (a fan
/// of 6,000 triangles) builds into the right solid (twins are found by
/// halving the sorted edge lists of such vertices, not by scanning them once
/// per edge).
#[test]
fn a_cone_of_high_valence_builds() {
    let n = 3000;
    let mut positions = vec![DVec3::Z, DVec3::ZERO];
    positions.extend((0..n).map(|i| {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        DVec3::new(a.cos(), a.sin(), 0.0)
    }));
    let mut polygons = Vec::with_capacity(2 * n);
    for i in 0..n {
        let j = (i + 1) % n;
        polygons.push(vec![0, 2 + i, 2 + j]);
        polygons.push(vec![1, 2 + j, 2 + i]);
    }
    let solid = Solid::try_from_polygons(&positions, polygons).unwrap();
    solid.check_consistency().unwrap();
    assert_eq!(
        (solid.vertex_count(), solid.edge_count(), solid.face_count()),
        (n + 2, 3 * n, 2 * n)
    );
    assert!(solid.is_closed());
    let apex = solid
        .vertices()
        .find(|(_, v)| v.position == DVec3::Z)
        .unwrap()
        .0;
    assert_eq!(solid.vertex_degree(apex), n);
    // The volume of the inscribed pyramid: (1/3) · (n/2) sin(2π/n) · 1.
    let want = n as f64 / 6.0 * (std::f64::consts::TAU / n as f64).sin();
    assert!((solid.volume() - want).abs() < 1e-12, "{}", solid.volume());
    // Every edge has its twin: each edge of the apex is shared by two of
    // the apex's triangles.
    assert!(solid.vertex_faces(apex).count() == n);
}

/// The icosahedron's vertices and faces (counter-clockwise from outside).
fn icosahedron_soup() -> (Vec<DVec3>, Vec<Vec<usize>>) {
    let solid = builders::icosahedron();
    let ids: Vec<_> = solid.vertices().map(|(id, _)| id).collect();
    let positions = ids.iter().map(|&id| solid.position(id)).collect();
    let polygons = solid
        .faces()
        .map(|(f, _)| {
            solid
                .face_vertices(f)
                .map(|v| ids.iter().position(|&id| id == v).unwrap())
                .collect()
        })
        .collect();
    (positions, polygons)
}

/// What every solid built from an open soup must be: consistent, with the
/// soup's one-face edges as its boundary edges, every vertex on at most one
/// hole (no or two boundary edges), and every hole a loop that visits each
/// vertex once.
fn assert_holes_are_simple_loops(solid: &Solid, one_face_edges: usize) {
    use wingedge::mesh::{EdgeUse, Side};
    solid.check_consistency().unwrap();
    assert_eq!(solid.boundary_edges().count(), one_face_edges);
    for (v, _) in solid.vertices() {
        let open = solid
            .vertex_edges(v)
            .filter(|&e| solid.edge(e).right_face.is_none())
            .count();
        assert!(open == 0 || open == 2, "{open} boundary edges at a vertex");
    }
    for e in solid.boundary_edges() {
        let start = EdgeUse {
            edge: e,
            side: Side::Right,
        };
        let mut seen = std::collections::HashSet::new();
        let mut u = start;
        loop {
            assert!(solid.use_face(u).is_none(), "a hole loop leaves the hole");
            assert!(
                seen.insert(solid.use_start(u)),
                "a hole visits a vertex twice"
            );
            u = solid.use_next(u);
            if u == start {
                break;
            }
        }
    }
}

/// How many edges of a soup are used by exactly one polygon.
fn one_face_edges(polygons: &[Vec<usize>]) -> usize {
    let mut uses = std::collections::HashMap::new();
    for p in polygons {
        for (i, &a) in p.iter().enumerate() {
            let b = p[(i + 1) % p.len()];
            *uses.entry((a.min(b), a.max(b))).or_insert(0) += 1;
        }
    }
    uses.values().filter(|&&n| n == 1).count()
}

/// Two holes touching at one vertex (an icosahedron without two faces
/// that share only vertex 0): the vertex is split per fan of faces, as a
/// pinch is, so each copy has one boundary edge in and one out and each
/// hole stays a loop of three edges.
#[test]
fn two_holes_meeting_at_a_vertex_build_with_a_vertex_per_fan() {
    let (positions, polygons) = icosahedron_soup();
    let at_0: Vec<usize> = (0..polygons.len())
        .filter(|&f| polygons[f].contains(&0))
        .collect();
    assert_eq!(at_0.len(), 5);
    // Two faces at vertex 0 that share no edge.
    let (a, b) = at_0
        .iter()
        .flat_map(|&a| at_0.iter().map(move |&b| (a, b)))
        .find(|&(a, b)| {
            a < b
                && polygons[a]
                    .iter()
                    .filter(|v| polygons[b].contains(v))
                    .count()
                    == 1
        })
        .unwrap();
    let open: Vec<Vec<usize>> = (0..polygons.len())
        .filter(|&f| f != a && f != b)
        .map(|f| polygons[f].clone())
        .collect();
    let solid = Solid::try_from_polygons(&positions, &open).expect("touching holes build");
    assert_holes_are_simple_loops(&solid, 6);
    assert_eq!(
        (solid.vertex_count(), solid.edge_count(), solid.face_count()),
        (13, 30, 18)
    );
    let at_vertex_0: Vec<_> = solid
        .vertices()
        .filter(|(_, v)| v.source_index == Some(0))
        .map(|(id, _)| solid.vertex_faces(id).count())
        .collect();
    let mut fans = at_vertex_0.clone();
    fans.sort_unstable();
    assert_eq!(fans, vec![1, 2], "the fans of one and two faces");

    // Two triangles sharing only a corner (a bow tie): two holes, three
    // vertices each.
    let bow_tie = Solid::try_from_polygons(
        &[
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 0.0, 0.0),
            DVec3::new(-1.0, -1.0, 0.0),
        ],
        [[0, 1, 2], [0, 3, 4]],
    )
    .unwrap();
    assert_holes_are_simple_loops(&bow_tie, 6);
    assert_eq!(bow_tie.vertex_count(), 6);
}

proptest::proptest! {
    #![proptest_config(crate::common::regressions_beside_source(
        proptest::prelude::ProptestConfig::default()
    ))]

    /// Any subset of the faces of a closed mesh builds: holes touching at
    /// vertices however they fall, pinches with closed and open fans mixed.
    #[test]
    fn every_subset_of_the_faces_of_a_closed_mesh_builds(keep in proptest::collection::vec(proptest::bool::weighted(0.6), 20)) {
        let (positions, polygons) = icosahedron_soup();
        let kept: Vec<Vec<usize>> = polygons
            .iter()
            .zip(&keep)
            .filter(|(_, k)| **k)
            .map(|(p, _)| p.clone())
            .collect();
        if kept.is_empty() {
            return Ok(());
        }
        let solid = Solid::try_from_polygons(&positions, &kept).unwrap();
        assert_holes_are_simple_loops(&solid, one_face_edges(&kept));
        proptest::prop_assert_eq!(solid.face_count(), kept.len());
    }
}
