//! Sweep, revolve and loft leaves in scene files: built, validated, usable
//! in CSG, with closed-form volumes, and refused by JSON path when bad.

use std::f64::consts::{PI, TAU};
use std::path::Path;

use wingedge::csg::{Containment, Stats};
use wingedge::glam::DVec3;
use wingedge::scene::{Scene, SceneError};

fn scene(text: &str) -> Result<Scene, SceneError> {
    Scene::from_json(text, "test.json", Path::new("."))
}

fn single_volume(text: &str) -> f64 {
    let s = scene(text).unwrap_or_else(|e| panic!("{e}"));
    let leaf = s.csg.single_leaf().expect("one leaf");
    leaf.primitive
        .exact_volume()
        .expect("a polyhedron's volume")
}

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs()
}

#[test]
fn a_revolved_rectangle_has_the_volume_of_its_polygonal_ring() {
    // Radii 1..2, height 1, 64 equal steps: the ring between two regular
    // 64-gons, area (n/2) sin(2π/n) r² each.
    let v = single_volume(
        r#"{"root": {"revolve": {"profile": [[1,0],[2,0],[2,1],[1,1]], "segments": 64}}}"#,
    );
    let n = 64.0;
    let polygon = |r: f64| n / 2.0 * (TAU / n).sin() * r * r;
    assert!(close(v, polygon(2.0) - polygon(1.0)), "{v}");
    // Half a turn about +y through (0, 0, 5): half of it.
    let half = single_volume(
        r#"{"root": {"revolve": {"profile": [[1,0],[2,0],[2,1],[1,1]], "segments": 32,
             "origin": [0,0,5], "axis": [0,1,0], "radial": [1,0,0], "angle_deg": 180}}}"#,
    );
    assert!(close(half, (polygon(2.0) - polygon(1.0)) / 2.0), "{half}");
}

#[test]
fn a_square_swept_along_a_straight_curve_and_a_loft_of_two_squares_are_prisms() {
    let swept = single_volume(
        r#"{"root": {"sweep": {"profile": [[-0.5,-0.5],[0.5,-0.5],[0.5,0.5],[-0.5,0.5]],
             "path": {"degree": 1, "points": [[0,0,0],[0,0,3]]}}}}"#,
    );
    assert!(close(swept, 3.0), "{swept}");
    let lofted = single_volume(
        r#"{"root": {"loft": {"sections": [[[0,0,0],[2,0,0],[2,2,0],[0,2,0]],
                                          [[0,0,1],[2,0,1],[2,2,1],[0,2,1]]]}}}"#,
    );
    assert!(close(lofted, 4.0), "{lofted}");
}

#[test]
fn a_nurbs_profile_revolves_to_nearly_a_sphere_and_a_swept_hole_drills_it() {
    // A rational quadratic half circle of radius 1 in the profile plane
    // (x ≥ 0), turned about z: a sphere to the tolerance.
    let sphere = r#"{"revolve": {"profile": {"degree": 2,
            "points": [[0,-1,0],[1,-1,0],[1,0,0],[1,1,0],[0,1,0]],
            "knots": [0,0,0,0.5,0.5,1,1,1],
            "weights": [1,0.7071067811865476,1,0.7071067811865476,1]},
          "tolerance": 1e-4}}"#;
    let v = single_volume(&format!(r#"{{"root": {sphere}}}"#));
    assert!(v < 4.0 / 3.0 * PI && v > 0.999 * 4.0 / 3.0 * PI, "{v}");
    // Drilled along x by a square swept on a straight B-spline.
    let part = scene(&format!(
        r#"{{"root": {{"difference": [{sphere},
            {{"sweep": {{"profile": [[-0.2,-0.2],[0.2,-0.2],[0.2,0.2],[-0.2,0.2]],
                       "path": {{"degree": 2, "points": [[-2,0,0],[0,0,0],[2,0,0]]}}}}}}]}}}}"#
    ))
    .unwrap();
    let mut stats = Stats::default();
    let at = |p: DVec3, stats: &mut Stats| part.csg.classify_point(p, stats);
    assert_eq!(
        at(DVec3::new(0.0, 0.5, 0.5), &mut stats),
        Containment::Inside
    );
    assert_eq!(at(DVec3::ZERO, &mut stats), Containment::Outside);
    assert_eq!(
        at(DVec3::new(0.0, 0.2, 0.0), &mut stats),
        Containment::OnBoundary
    );
    let drilled = part.csg.try_volume(0.01).unwrap().volume;
    let hole = 0.4 * 0.4 * 2.0 * (1.0 - 0.04f64).sqrt(); // the bore, to first order
    assert!(
        (drilled - (v - hole)).abs() < 0.02 * v,
        "{drilled} vs {}",
        v - hole
    );
}

#[test]
fn bad_leaves_are_refused_at_their_json_path() {
    let refusal = |text: &str| match scene(text) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    };
    let ring = r#""profile": [[1,0],[2,0],[2,1],[1,1]]"#;
    let cases = [
        (
            format!(r#"{{"root": {{"revolve": {{{ring}, "segments": 8, "tolerance": 0.1}}}}}}"#),
            "root.revolve: give \"segments\" or \"tolerance\", not both",
        ),
        (
            format!(r#"{{"root": {{"revolve": {{{ring}, "angle_deg": 400}}}}}}"#),
            "root.revolve.angle_deg: expected an angle in (0, 360] degrees",
        ),
        (
            format!(r#"{{"root": {{"revolve": {{{ring}, "segments": 0}}}}}}"#),
            "root.revolve.segments: expected a whole number of at least 1",
        ),
        (
            r#"{"root": {"revolve": {"profile": [[-1,0],[2,0],[2,1]]}}}"#.to_string(),
            "root.revolve: ",
        ),
        (
            r#"{"root": {"revolve": {"profile": [[1,0],[2,0],[2,"x"]]}}}"#.to_string(),
            "root.revolve.profile[2][1]: expected a finite number",
        ),
        (
            r#"{"root": {"sweep": {"profile": [[0,0],[1,0],[0,1]], "path": {"degree": 2, "points": [[0,0,0],[0,0,1],[0,0,2]], "knots": [0,1,0,1,1,1]}}}}"#.to_string(),
            "root.sweep.path.knots: ",
        ),
        (
            r#"{"root": {"sweep": {"profile": [[0,0],[1,0],[0,1]], "path": {"degree": 1, "points": [[0,0,0],[0,0,1]], "weights": [1, 0]}}}}"#.to_string(),
            "root.sweep.path.weights[1]: weight 1 is 0",
        ),
        (
            r#"{"root": {"sweep": {"profile": [[0,0],[1,0],[0,1]], "path": {"degree": 1, "points": [[0,0,0],[0,0,0]]}}}}"#.to_string(),
            "root.sweep: ",
        ),
        (
            r#"{"root": {"sweep": {"profile": [[0,0],[1,0],[0,1]], "path": {"degree": 1, "points": [[0,0,0],[0,0,1]]}, "tolerance": -1}}}"#.to_string(),
            "root.sweep.tolerance: expected a positive number",
        ),
        (
            r#"{"root": {"loft": {"sections": [[[0,0,0],[1,0,0],[0,1,0]], [[0,0,1],[1,0,1]]]}}}"#.to_string(),
            "root.loft: ",
        ),
        (
            r#"{"root": {"loft": {"sections": [[[0,0,0],[1,0,0],[0,1,0]]], "twist": 1}}}"#.to_string(),
            "root.loft: unknown key \"twist\"",
        ),
    ];
    for (text, want) in cases {
        let message = refusal(&text);
        assert!(
            message.starts_with(want),
            "{text}\n  gave: {message}\n  want: {want}…"
        );
    }
}
