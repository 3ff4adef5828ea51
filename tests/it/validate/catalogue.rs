//! The fixture catalogue: every valid fixture validates as a valid solid with
//! the expected counts, and every broken fixture reports exactly its rule,
//! at the right elements and OBJ lines, and nothing else.

use std::path::{Path, PathBuf};

use wingedge::io::{ObjOptions, import_obj};
use wingedge::validate::{Options, Report, Rule, Validity, validate_import};

fn fixture(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join(path)
}

fn validate(path: &str) -> Report {
    let import = import_obj(&fixture(path), &ObjOptions::default()).expect("fixture reads");
    validate_import(&import, &Options::default()).expect("fixture validates")
}

struct Valid {
    file: &'static str,
    vertices: usize,
    edges: usize,
    faces: usize,
    shells: usize,
    genus: i64,
    volume: f64,
}

#[test]
fn valid_fixtures_are_valid_solids() {
    let phi = (1.0 + 5f64.sqrt()) / 2.0;
    let ico = |r: f64| {
        // Edge 2r, volume (5/12)(3 + √5) a³.
        5.0 / 12.0 * (3.0 + 5f64.sqrt()) * (2.0 * r).powi(3)
    };
    let cases = [
        Valid {
            file: "valid/tetrahedron.obj",
            vertices: 4,
            edges: 6,
            faces: 4,
            shells: 1,
            genus: 0,
            volume: 8.0 / 3.0,
        },
        Valid {
            file: "valid/cube.obj",
            vertices: 8,
            edges: 12,
            faces: 6,
            shells: 1,
            genus: 0,
            volume: 8.0,
        },
        Valid {
            file: "valid/octahedron.obj",
            vertices: 6,
            edges: 12,
            faces: 8,
            shells: 1,
            genus: 0,
            volume: 4.0 / 3.0,
        },
        Valid {
            file: "valid/dodecahedron.obj",
            // Vertices (±1, ±1, ±1) and cyclic (0, ±1/φ, ±φ): edge 2/φ.
            vertices: 20,
            edges: 30,
            faces: 12,
            shells: 1,
            genus: 0,
            volume: (15.0 + 7.0 * 5f64.sqrt()) / 4.0 * (2.0 / phi).powi(3),
        },
        Valid {
            file: "valid/icosahedron.obj",
            // Vertices cyclic (0, ±1, ±φ): edge 2.
            vertices: 12,
            edges: 30,
            faces: 20,
            shells: 1,
            genus: 0,
            volume: ico(1.0),
        },
        Valid {
            file: "valid/prism.obj",
            vertices: 12,
            edges: 18,
            faces: 8,
            shells: 1,
            genus: 0,
            volume: 3.0, // an L of area 3, height 1
        },
        Valid {
            file: "valid/torus_genus1.obj",
            vertices: 32,
            edges: 64,
            faces: 32,
            shells: 1,
            genus: 1,
            volume: 8.0,
        },
        Valid {
            file: "valid/double_torus_genus2.obj",
            vertices: 48,
            edges: 100,
            faces: 50,
            shells: 1,
            genus: 2,
            volume: 13.0,
        },
        Valid {
            file: "valid/hollow_ball.obj",
            vertices: 24,
            edges: 60,
            faces: 40,
            shells: 2,
            genus: 0,
            volume: ico(2.0) - ico(1.0),
        },
        Valid {
            file: "valid/exporter_cube.obj",
            vertices: 8,
            edges: 12,
            faces: 6,
            shells: 1,
            genus: 0,
            volume: 1.0,
        },
    ];
    for c in cases {
        let r = validate(c.file);
        assert_eq!(
            r.validity,
            Validity::ValidSolid,
            "{}: {:#?}",
            c.file,
            r.violations
        );
        assert!(r.violations.is_empty());
        assert_eq!(
            (r.vertices, r.edges, r.faces, r.shells, r.genus),
            (c.vertices, c.edges, c.faces, c.shells, Some(c.genus)),
            "{}",
            c.file
        );
        let volume = r.volume.expect("closed");
        assert!(
            (volume - c.volume).abs() < 1e-9 * c.volume,
            "{}: {volume} vs {}",
            c.file,
            c.volume
        );
    }
}

#[test]
fn the_hollow_ball_has_an_outer_shell_and_a_cavity() {
    let r = validate("valid/hollow_ball.obj");
    let depths: Vec<_> = r.shell_details.iter().map(|s| s.depth).collect();
    assert_eq!(depths, [Some(0), Some(1)]);
    assert_eq!(r.shell_details[1].parent, Some(0));
    assert!(r.shell_details[1].volume < 0.0);
}

#[test]
fn faces_with_five_or_more_vertices_are_kept() {
    let import = import_obj(&fixture("valid/prism.obj"), &ObjOptions::default()).unwrap();
    assert!(import.soup.polygons.iter().any(|p| p.vertices.len() == 6));
    let import = import_obj(&fixture("valid/dodecahedron.obj"), &ObjOptions::default()).unwrap();
    assert!(import.soup.polygons.iter().all(|p| p.vertices.len() == 5));
}

#[test]
fn the_exporter_cube_welds_closed_and_keeps_groups_and_materials() {
    let import = import_obj(&fixture("valid/exporter_cube.obj"), &ObjOptions::default()).unwrap();
    assert_eq!(import.weld.merged, 16);
    let p = &import.soup.polygons;
    assert_eq!(p[0].attributes.group.as_deref(), Some("bottom"));
    assert_eq!(p[0].attributes.material.as_deref(), Some("grey"));
    assert_eq!(p[5].attributes.group.as_deref(), Some("sides"));
    assert_eq!(p[5].attributes.material.as_deref(), Some("red"));
    let lines: Vec<_> = p.iter().map(|p| p.attributes.line.unwrap()).collect();
    assert_eq!(lines, [15, 21, 29, 35, 41, 47]);
    // Without the weld every edge is open.
    let options = ObjOptions {
        weld: wingedge::io::WeldMode::None,
        ..ObjOptions::default()
    };
    let import = import_obj(&fixture("valid/exporter_cube.obj"), &options).unwrap();
    let r = validate_import(&import, &Options::default()).unwrap();
    assert_eq!(r.count(Rule::EdgeInOneFace), 24);
    assert!(r.validity < Validity::ClosedOrientedSurface);
}

/// One expected violation: its rule, the elements it names (faces for face
/// and edge rules, vertices for vertex rules) and its line.
struct Expect(Rule, &'static [usize], usize);

fn check_broken(file: &str, expected: &[Expect]) {
    let r = validate(&format!("broken/{file}.obj"));
    let mut got: Vec<(Rule, Vec<usize>, Option<usize>)> = r
        .violations
        .iter()
        .map(|v| {
            let mut ids = match v.rule {
                Rule::VertexInFewerThanThreeEdges
                | Rule::VertexInFewerThanThreeFaces
                | Rule::UnreferencedVertex
                | Rule::NonManifoldVertex => v.vertices.clone(),
                _ => v.faces.clone(),
            };
            ids.sort_unstable();
            (v.rule, ids, v.line)
        })
        .collect();
    let mut want: Vec<(Rule, Vec<usize>, Option<usize>)> = expected
        .iter()
        .map(|Expect(rule, ids, line)| {
            let mut ids = ids.to_vec();
            ids.sort_unstable();
            (*rule, ids, Some(*line))
        })
        .collect();
    got.sort();
    want.sort();
    assert_eq!(got, want, "{file}: {:#?}", r.violations);
    assert!(!r.is_valid());
}

#[test]
fn validity_rule_1_vertex_in_fewer_than_three_edges() {
    // On a surface without holes a vertex has as many faces as edges, so
    // validity rules 1 and 2 break together; no fixture can break one alone.
    check_broken(
        "vertex_in_fewer_than_three_edges",
        &[
            Expect(Rule::VertexInFewerThanThreeEdges, &[8], 10),
            Expect(Rule::VertexInFewerThanThreeFaces, &[8], 10),
        ],
    );
}

#[test]
fn validity_rule_2_vertex_in_fewer_than_three_faces() {
    check_broken(
        "vertex_in_fewer_than_three_faces",
        &[
            Expect(Rule::VertexInFewerThanThreeEdges, &[4], 6),
            Expect(Rule::VertexInFewerThanThreeFaces, &[4], 6),
        ],
    );
}

#[test]
fn validity_rule_3_edge_without_two_distinct_vertices() {
    check_broken(
        "edge_without_two_distinct_vertices",
        &[Expect(Rule::EdgeWithoutTwoDistinctVertices, &[1], 11)],
    );
}

#[test]
fn validity_rule_4_edge_in_one_face() {
    // A hole is a loop: the smallest has three edges.
    check_broken(
        "edge_in_one_face",
        &[
            Expect(Rule::EdgeInOneFace, &[16], 30),
            Expect(Rule::EdgeInOneFace, &[15], 29),
            Expect(Rule::EdgeInOneFace, &[4], 18),
        ],
    );
}

#[test]
fn validity_rule_4_edge_in_more_than_two_faces() {
    check_broken(
        "edge_in_more_than_two_faces",
        &[Expect(Rule::EdgeInMoreThanTwoFaces, &[3, 4, 8, 11], 19)],
    );
}

#[test]
fn validity_rule_5_face_with_fewer_than_three_vertices() {
    check_broken(
        "face_with_fewer_than_three_vertices",
        &[Expect(Rule::FaceWithFewerThanThreeVertices, &[6], 16)],
    );
}

#[test]
fn validity_rule_6_face_with_fewer_than_three_edges() {
    check_broken(
        "face_with_fewer_than_three_edges",
        &[Expect(Rule::FaceWithFewerThanThreeEdges, &[6], 16)],
    );
}

#[test]
fn unreferenced_vertex() {
    check_broken(
        "unreferenced_vertex",
        &[Expect(Rule::UnreferencedVertex, &[8], 10)],
    );
}

#[test]
fn duplicate_face() {
    check_broken(
        "duplicate_face",
        &[Expect(Rule::DuplicateFace, &[3, 6], 16)],
    );
}

#[test]
fn inconsistent_orientation() {
    // One flipped triangle disagrees with its three neighbours.
    check_broken(
        "inconsistent_orientation",
        &[
            Expect(Rule::InconsistentOrientation, &[0, 2], 6),
            Expect(Rule::InconsistentOrientation, &[1, 2], 7),
            Expect(Rule::InconsistentOrientation, &[2, 3], 8),
        ],
    );
}

#[test]
fn non_manifold_vertex() {
    check_broken(
        "non_manifold_vertex",
        &[Expect(Rule::NonManifoldVertex, &[3], 5)],
    );
}

#[test]
fn non_planar_face() {
    check_broken("non_planar_face", &[Expect(Rule::NonPlanarFace, &[0], 7)]);
    let r = validate("broken/non_planar_face.obj");
    let deviation = r.violations[0].value.unwrap();
    assert!((deviation - 0.0025).abs() < 1e-6, "{deviation}");
    // A looser tolerance accepts it.
    let import = import_obj(
        &fixture("broken/non_planar_face.obj"),
        &ObjOptions::default(),
    )
    .unwrap();
    let mut options = Options::default();
    options.tolerance.planarity = 0.01;
    assert!(validate_import(&import, &options).unwrap().is_valid());
}

#[test]
fn degenerate_face() {
    // Vertex 5 lies on the edge 1–2 of face 0, closed only by the sliver
    // (face 5): faces 1 (1 5 4) and 2 (5 2 4) each share one vertex with
    // face 0 and lie along its edge beyond it (segments 1–5 and 5–2), a
    // contact the sliver causes and the self-intersection rule reports.
    check_broken(
        "degenerate_face",
        &[
            Expect(Rule::DegenerateFace, &[5], 12),
            Expect(Rule::SelfIntersection, &[0, 1], 7),
            Expect(Rule::SelfIntersection, &[0, 2], 7),
        ],
    );
}

#[test]
fn shell_oriented_inward() {
    check_broken(
        "shell_oriented_inward",
        &[Expect(Rule::ShellOrientedInward, &[0], 10)],
    );
}

#[test]
fn self_intersection() {
    check_broken(
        "self_intersection",
        &[
            Expect(Rule::SelfIntersection, &[1, 6], 15),
            Expect(Rule::SelfIntersection, &[1, 7], 15),
            Expect(Rule::SelfIntersection, &[1, 8], 15),
        ],
    );
}

#[test]
fn every_rule_has_a_broken_fixture() {
    for rule in Rule::ALL {
        assert!(
            fixture(&format!("broken/{}.obj", rule.name())).exists(),
            "no fixture for {rule}"
        );
    }
}

#[test]
fn the_teapot_is_open_and_not_a_surface() {
    let r = validate("real/teapot.obj");
    assert_eq!(r.validity, Validity::NotASurface);
    assert!(r.count(Rule::EdgeInOneFace) > 0);
    assert!(r.count(Rule::NonManifoldVertex) > 0);
    // Two holes touch at the pinch: the solid builds with a vertex per fan
    // there, and the pinch is still reported, saying so.
    assert_eq!(r.not_built, None);
    assert!(
        r.violations
            .iter()
            .any(|v| v.rule == Rule::NonManifoldVertex
                && v.message
                    .contains("2 of them border holes, which touch there")),
        "{:?}",
        r.violations
    );
    assert!(r.violations.iter().all(|v| v.line.is_some()));
    // The teapot's patches meet at (-2, 0.9, 0) in two fans: welding their
    // corner copies would pinch them, so the weld refuses and says so.
    let import = import_obj(&fixture("real/teapot.obj"), &ObjOptions::default()).unwrap();
    // It builds, vertex 355 once per fan, and the winding number answers.
    let solid = wingedge::mesh::Solid::try_from_soup(&import.soup).unwrap();
    assert_eq!(solid.vertex_count(), import.soup.positions.len() + 1);
    let accel = wingedge::query::Accel::new(&solid);
    let classes = accel
        .classify_batch(
            &[
                glam::DVec3::new(0.0, 1.0, 0.0),
                glam::DVec3::new(5.0, 5.0, 5.0),
                glam::DVec3::new(-2.0, 0.9, 0.0),
            ],
            wingedge::query::Method::Winding,
        )
        .unwrap();
    use wingedge::query::Containment::{Inside, OnBoundary, Outside};
    assert_eq!(classes, [Inside, Outside, OnBoundary]);
    assert!(import.weld.merged > 0);
    assert!(
        import
            .weld
            .refused
            .iter()
            .any(|r| matches!(r, wingedge::io::WeldRefusal::WouldPinch { .. }))
    );
}

#[test]
fn suzanne_is_open_with_non_planar_quads() {
    let r = validate("real/suzanne.obj");
    assert_eq!(r.validity, Validity::OrientedSurface);
    assert_eq!(r.shells, 3);
    assert!(r.count(Rule::NonPlanarFace) > 0);
    assert!(r.count(Rule::EdgeInOneFace) > 0);
}

#[test]
fn shell_measures_agree_with_the_winged_edge_solid() {
    // Validation measures shells on the soup's topology (in parallel); the
    // winged-edge solid's own traversal must give the same shells.
    for file in [
        "valid/hollow_ball.obj",
        "valid/double_torus_genus2.obj",
        "valid/prism.obj",
        "real/suzanne.obj",
        "broken/edge_in_one_face.obj",
    ] {
        let import = import_obj(&fixture(file), &ObjOptions::default()).unwrap();
        let (report, solid) =
            wingedge::validate::validate_and_build(&import, &Options::default()).unwrap();
        let solid = solid.expect("buildable");
        let mut ours: Vec<(usize, usize, usize, i64, Option<i64>)> = report
            .shell_details
            .iter()
            .map(|s| {
                (
                    s.faces,
                    s.edges,
                    s.vertices,
                    s.euler_characteristic,
                    s.genus,
                )
            })
            .collect();
        let mut theirs: Vec<(usize, usize, usize, i64, Option<i64>)> = solid
            .shells()
            .iter()
            .map(|s| {
                (
                    s.faces.len(),
                    s.edge_count,
                    s.vertex_count,
                    s.euler_characteristic,
                    s.genus(),
                )
            })
            .collect();
        ours.sort_unstable();
        theirs.sort_unstable();
        assert_eq!(ours, theirs, "{file}");
        for (s, t) in report.shell_details.iter().zip(solid.shells()) {
            if s.closed {
                assert!((s.volume - t.signed_volume).abs() < 1e-9 * s.volume.abs().max(1.0));
            }
        }
    }
}

/// Two holes touching at a vertex (`soups/touching_holes.obj`): the solid
/// builds (a vertex per fan there), and validation reports every open edge
/// and the vertex where the holes touch, each with its OBJ line.
#[test]
fn holes_touching_at_a_vertex_build_and_are_reported() {
    let import = import_obj(&fixture("soups/touching_holes.obj"), &ObjOptions::default()).unwrap();
    let (r, solid) = wingedge::validate::validate_and_build(&import, &Options::default()).unwrap();
    assert_eq!(r.not_built, None);
    let solid = solid.expect("the solid builds");
    assert_eq!(solid.boundary_edges().count(), 6);
    assert_eq!(solid.vertex_count(), 13, "vertex 0 once per fan");
    assert_eq!(r.validity, Validity::NotASurface);
    assert_eq!(r.count(Rule::EdgeInOneFace), 6);
    assert_eq!(r.count(Rule::NonManifoldVertex), 1);
    assert_eq!(r.violations.len(), 7, "{:#?}", r.violations);
    let pinch = r
        .violations
        .iter()
        .find(|v| v.rule == Rule::NonManifoldVertex)
        .unwrap();
    assert_eq!(pinch.vertices, vec![0]);
    assert_eq!(pinch.line, Some(2));
    assert!(
        pinch.message.contains(
            "its 3 faces form 2 separate fans; 2 of them border holes, which touch there"
        ),
        "{}",
        pinch.message
    );
    assert!(r.violations.iter().all(|v| v.line.is_some()));
    // Holes joined through the shared vertex count once.
    assert_eq!(r.holes, 1);
}
