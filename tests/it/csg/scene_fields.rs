//! Field leaves in scene files: a field document inline or by file, meshed
//! into a polyhedron leaf that takes part in ray-cast CSG, and errors that
//! name the JSON path below the leaf.

use std::path::Path;

use glam::DVec3;
use wingedge::csg::{Containment, Stats};
use wingedge::scene::Scene;

const BLOB: &str = r#"{"resolution": 32, "blobs": [{"center": [0, 0, 0], "radius": 2}]}"#;

fn scene(root: &str) -> Result<Scene, String> {
    Scene::from_json(
        &format!(r#"{{"root": {root}}}"#),
        "<test>",
        Path::new("fixtures/fields"),
    )
    .map_err(|e| e.to_string())
}

#[test]
fn an_inline_field_is_a_leaf_that_classifies_points_and_combines() {
    // A unit ball (radius 2, F = ½ at 1) minus the half-space x > 0 (the
    // normal points out of the half-space).
    let s = scene(&format!(
        r#"{{"difference": [{{"field": {BLOB}}}, {{"halfspace": {{"point": [0, 0, 0], "normal": [-1, 0, 0]}}}}]}}"#
    ))
    .unwrap();
    let mut stats = Stats::default();
    let at = |x: f64, stats: &mut Stats| s.csg.classify_point(DVec3::new(x, 0.1, 0.05), stats);
    assert_eq!(at(-0.5, &mut stats), Containment::Inside);
    assert_eq!(at(0.5, &mut stats), Containment::Outside);
    assert_eq!(at(-1.2, &mut stats), Containment::Outside);
    assert_eq!(at(1.2, &mut stats), Containment::Outside);
}

#[test]
fn a_field_leaf_can_name_a_field_document_file() {
    let s = scene(r#"{"field": "three_blobs.json"}"#).unwrap();
    let mut stats = Stats::default();
    assert_eq!(
        s.csg.classify_point(DVec3::new(0.1, 0.0, 0.0), &mut stats),
        Containment::Inside
    );
    assert_eq!(
        s.csg.classify_point(DVec3::new(9.0, 0.0, 0.0), &mut stats),
        Containment::Outside
    );
}

#[test]
fn field_leaf_errors_name_the_json_path_below_the_leaf() {
    let cases = [
        (
            r#"{"union": [{"sphere": {"center": [0,0,0], "radius": 1}}, {"field": {"blobs": [{"center": [0,0,0], "radius": 0}]}}]}"#,
            "root.union[1].field.blobs[0].radius: expected a positive number, found 0",
        ),
        (
            r#"{"field": {"blobs": [{"center": [0,0,0], "radius": 1, "colour": 2}]}}"#,
            "root.field.blobs[0]: unknown key \"colour\"",
        ),
        (
            r#"{"field": {"resolution": 1000, "blobs": []}}"#,
            "root.field.resolution: resolution 1000 is above the scene limit 256",
        ),
        (
            r#"{"field": {"blobs": []}}"#,
            "root.field: the field is below 1/2 at every sample (resolution 64): the solid is empty",
        ),
        (
            r#"{"field": "none.json"}"#,
            "root.field: fixtures/fields/none.json: cannot read",
        ),
        (r#"{"field": 3}"#, "root.field: expected an object, found 3"),
    ];
    for (root, expected) in cases {
        let e = scene(root).unwrap_err();
        assert!(e.contains(expected), "{root}: {e}");
    }
}
