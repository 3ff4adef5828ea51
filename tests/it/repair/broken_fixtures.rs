//! Every fixture of `fixtures/broken/` that describes a solid comes out of
//! `repair` valid, and its written OBJ reads back valid; each change is
//! the one the fixture's defect calls for.

use std::path::Path;

use wingedge::io::{read_mesh, to_obj_string};
use wingedge::mesh::PolygonSoup;
use wingedge::repair::{DropReason, RepairOptions, Repaired, repair};
use wingedge::validate::{Options, validate_soup};

fn repaired(name: &str) -> Repaired {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures/broken")
        .join(name);
    let soup = read_mesh(&path).expect("the fixture reads");
    repair(&soup, &RepairOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// The solid is valid, and so is its OBJ read back.
fn assert_valid(name: &str, r: &Repaired) {
    let solid = r.solid.as_ref().expect("a solid");
    assert!(
        r.validation.as_ref().is_some_and(|v| v.is_valid()),
        "{name}"
    );
    let text = to_obj_string(solid);
    let back = wingedge::io::import_obj_bytes(
        Path::new("back.obj"),
        text.as_bytes(),
        &wingedge::io::ObjOptions::default(),
    )
    .expect("reads back");
    let report = validate_soup(&back.soup, None, &Options::default()).unwrap();
    assert!(report.is_valid(), "{name}: {:?}", report.violations);
}

/// The fixtures (every one describes a solid), with the volume the repair
/// should give (0: any positive volume).
const SOLIDS: [(&str, f64); 15] = [
    ("degenerate_face.obj", 1.0 / 6.0),
    ("duplicate_face.obj", 1.0),
    ("edge_in_more_than_two_faces.obj", 2.0),
    ("edge_in_one_face.obj", 0.0),
    ("edge_without_two_distinct_vertices.obj", 1.0),
    ("face_with_fewer_than_three_edges.obj", 1.0),
    ("face_with_fewer_than_three_vertices.obj", 1.0),
    ("inconsistent_orientation.obj", 1.0 / 6.0),
    ("non_manifold_vertex.obj", 1.0 / 3.0),
    ("non_planar_face.obj", 0.0),
    ("self_intersection.obj", 0.0),
    ("shell_oriented_inward.obj", 1.0),
    ("unreferenced_vertex.obj", 0.0),
    ("vertex_in_fewer_than_three_edges.obj", 0.0),
    ("vertex_in_fewer_than_three_faces.obj", 0.0),
];

#[test]
fn every_broken_fixture_that_describes_a_solid_comes_out_valid() {
    for (name, volume) in SOLIDS {
        let r = repaired(name);
        assert_valid(name, &r);
        let after = r.report.volume_after;
        assert!(after > 0.0, "{name}: {after}");
        if volume > 0.0 {
            assert!(
                (after - volume).abs() < 1e-12,
                "{name}: {after} vs {volume}"
            );
        }
    }
}

#[test]
fn each_change_is_the_one_the_defect_calls_for() {
    let r = repaired("degenerate_face.obj");
    assert_eq!(r.report.dropped.len(), 1);
    assert_eq!(r.report.dropped[0].reason, DropReason::ZeroArea);
    assert!(r.report.resolved);
    let r = repaired("inconsistent_orientation.obj");
    assert_eq!(r.report.turned_over_count(), 1);
    assert_eq!(r.report.turned_over[0].polygons, vec![2]);
    let r = repaired("shell_oriented_inward.obj");
    assert_eq!(r.report.turned_over_count(), 6);
    assert!(r.report.turned_over[0].whole_piece);
    let r = repaired("edge_in_one_face.obj");
    assert_eq!(r.report.filled.len(), 1);
    assert_eq!(r.report.filled[0].edges, 3);
    let r = repaired("self_intersection.obj");
    assert!(r.report.resolved);
    assert!(!r.report.crossing_pairs.is_empty());
    // The union of a cube and a tetrahedron poking out of it.
    assert!(r.report.volume_after > 1.0);
    assert!(r.report.volume_after < r.report.volume_before);
}

#[test]
fn a_hole_over_the_limit_stays_open_and_no_solid_is_made() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/broken/edge_in_one_face.obj");
    let soup = read_mesh(&path).unwrap();
    let options = RepairOptions {
        max_hole_edges: Some(2),
        ..RepairOptions::default()
    };
    let r = repair(&soup, &options).unwrap();
    assert!(r.solid.is_none());
    assert_eq!(r.report.left_open.len(), 1);
    assert!(r.report.filled.is_empty());
}

#[test]
fn a_sheet_encloses_nothing_and_gives_the_empty_solid_saying_why() {
    let soup = PolygonSoup::new(
        vec![
            glam::DVec3::new(0.0, 0.0, 0.0),
            glam::DVec3::new(1.0, 0.0, 0.0),
            glam::DVec3::new(1.0, 1.0, 0.0),
            glam::DVec3::new(0.0, 1.0, 0.0),
            glam::DVec3::new(0.5, 0.5, 0.3),
        ],
        [vec![0, 1, 4], vec![1, 2, 4], vec![2, 3, 4]],
    );
    let r = repair(&soup, &RepairOptions::default()).unwrap();
    let solid = r.solid.expect("the empty solid");
    assert_eq!(solid.face_count(), 0);
    assert!(r.report.empty_because.is_some());
    assert_eq!(r.report.volume_after, 0.0);
}
