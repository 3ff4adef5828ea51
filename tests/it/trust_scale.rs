//! One rule at every scale (issue: trust at every scale): a leaf that does
//! not survive its transform is refused at load, the same for every
//! command; certified volume intervals are finite or refused; the default
//! volume grid resolves every leaf that adds volume; a ray whose `t`
//! overflows is refused by mesh and scene alike.

use std::path::Path;

use glam::DVec3;
use wingedge::csg::{MAX_VOLUME_RAYS, Sphere, SphereError, VolumeError};
use wingedge::geom::Ray;
use wingedge::query::QueryError;
use wingedge::scene::{Scene, SceneError, Target, TargetError};

fn scene(text: &str) -> Result<Scene, SceneError> {
    Scene::from_json(text, "test.json", Path::new("."))
}

/// A unit cube moved by 1e17 rounds to one point: refused at load by name
/// (an audit found `classify` calling its centre outside, `volume` 0 and
/// `render` drawing it, while `csg` and `cells` refused it). The same cube
/// moved by 1e15 survives, exactly.
#[test]
fn a_leaf_that_collapses_under_its_transform_is_refused_at_load() {
    for (child, kind) in [
        (r#"{"box": {"min": [0,0,0], "max": [1,1,1]}}"#, "box"),
        (r#"{"sphere": {"center": [0,0,0], "radius": 1}}"#, "sphere"),
        (
            r#"{"cylinder": {"base": [0,0,0], "axis": [0,0,1], "radius": 1}}"#,
            "cylinder",
        ),
    ] {
        let text = format!(
            r#"{{"root": {{"transform": {{"translate": [1e17, 1e17, 1e17]}}, "child": {child}}}}}"#
        );
        let e = scene(&text).unwrap_err().to_string();
        assert!(
            e.starts_with(&format!("root.child.{kind}: the {kind} moved")),
            "{e}"
        );
        assert!(
            e.contains("does not survive rounding") || e.contains("collapses below f64"),
            "{e}"
        );
        let near = text.replace("1e17", "1e15");
        scene(&near).unwrap_or_else(|e| panic!("{kind} at 1e15: {e}"));
    }
    let moved = scene(
        r#"{"root": {"transform": {"translate": [1e15, 1e15, 1e15]}, "child": {"box": {"min": [0,0,0], "max": [1,1,1]}}}}"#,
    )
    .unwrap();
    let leaf = moved.csg.single_leaf().unwrap();
    assert_eq!(leaf.primitive.exact_volume(), Some(1.0));
}

/// Spheres and cylinders placed (not moved) where f64 cannot resolve them
/// are refused by their constructors, so scenes and code see one rule.
#[test]
fn a_curved_leaf_below_f64_resolution_is_refused() {
    assert!(matches!(
        Sphere::try_new(DVec3::splat(1e17), 1.0),
        Err(SphereError::Collapsed { .. })
    ));
    assert!(Sphere::try_new(DVec3::splat(1e15), 1.0).is_ok());
    assert!(Sphere::try_new(DVec3::ZERO, 1e-300).is_ok());
    let e = scene(r#"{"root": {"sphere": {"center": [1e17, 0, 0], "radius": 1}}}"#)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("root.sphere.radius: sphere of radius 1 at (1e17, 0, 0) collapses"),
        "{e}"
    );
    let e =
        scene(r#"{"root": {"cylinder": {"base": [0, 1e17, 0], "axis": [0,0,1], "radius": 1}}}"#)
            .unwrap_err()
            .to_string();
    assert!(e.contains("collapses below f64's resolution"), "{e}");
}

/// Two unit boxes 1,000 apart: the default grid puts cells across each
/// (before: 400 cells of 2.5 across the pair missed both, volume 0).
#[test]
fn the_default_volume_grid_resolves_every_leaf_that_adds_volume() {
    let two = scene(
        r#"{"root": {"union": [
            {"box": {"min": [0,0,0], "max": [1,1,1]}},
            {"box": {"min": [1000,0,0], "max": [1001,1,1]}}]}}"#,
    )
    .unwrap();
    let v = two.csg.try_default_volume().unwrap();
    assert_eq!(v.volume, 2.0);
    assert!(v.unresolved.is_none());
    // 4 cells across each box along x, not 400 across the pair.
    assert_eq!(v.rays, 4004 * 4);
    // A spacing the user gives is used as given, with the leaves it may
    // miss named.
    let coarse = two.csg.try_volume(2.5).unwrap();
    let missed = coarse.unresolved.expect("both boxes are narrower than 2.5");
    assert_eq!(missed.count, 2);
    assert_eq!(
        two.csg.leaf(missed.narrowest).unwrap().label,
        "root.union[0].box"
    );
    // A needle along x makes the grid fine along y only.
    let needle = scene(
        r#"{"root": {"union": [{"box": {"min": [0,0,0], "max": [1000,1e-3,1]}},
                               {"box": {"min": [0,0.5,0], "max": [1000,1.5,1]}}]}}"#,
    )
    .unwrap();
    let v = needle.csg.try_default_volume().unwrap();
    assert_eq!(v.rays, 400 * 6000);
    assert!((v.volume - 1001.0).abs() < 1e-9, "{}", v.volume);
    // A subtracted leaf does not refine the grid: a tiny hole in a big box.
    let hole = scene(
        r#"{"root": {"difference": [{"box": {"min": [0,0,0], "max": [10,10,10]}},
                                    {"box": {"min": [5,5,0], "max": [5.000001,5.000001,10]}}]}}"#,
    )
    .unwrap();
    let v = hole.csg.try_default_volume().unwrap();
    assert_eq!(v.rays, 400 * 400);
    assert!(v.unresolved.is_some());
    // Leaves far too small for their distance apart: refused, named.
    let far = scene(
        r#"{"root": {"union": [{"box": {"min": [0,0,0], "max": [1e-6,1e-6,1e-6]}},
                               {"box": {"min": [1000,1000,0], "max": [1001,1001,1]}}]}}"#,
    )
    .unwrap();
    let e = far.csg.try_default_volume().unwrap_err();
    assert!(
        matches!(&e, VolumeError::Unresolvable { leaf, limit, .. }
            if leaf == "root.union[0].box" && *limit == MAX_VOLUME_RAYS),
        "{e}"
    );
    assert!(e.to_string().contains("give a spacing"), "{e}");
}

/// A mesh's ray whose `t` overflows is refused by name, as a scene's is
/// (an audit found `outside inf inf`).
#[test]
fn mesh_and_scene_refuse_an_overflowing_t_alike() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let tiny = Ray::new(DVec3::new(-3.0, 0.5, 0.5), DVec3::new(5e-324, 0.0, 0.0));
    for path in [
        "fixtures/valid/cube.obj",
        "fixtures/scenes/drilled_cube.json",
    ] {
        let target = Target::try_load(&root.join(path)).unwrap();
        let e = target.rays(&[tiny], &mut Default::default()).unwrap_err();
        assert!(
            matches!(
                e,
                TargetError::Query {
                    source: QueryError::RayOutOfRange { index: 0, .. },
                    ..
                }
            ),
            "{path}: {e}"
        );
        assert!(e.to_string().contains("t overflows"), "{path}: {e}");
    }
}

/// A blob far from the origin meshes into a valid solid or is refused by
/// name: vertices are kept a few spacings of f64 off the grid nodes, and a
/// cell too small for f64 there is refused (an audit found 3,088
/// degenerate faces for a blob at 1e12, written and called valid).
#[test]
fn a_far_blob_meshes_valid_or_is_refused() {
    use wingedge::field::{FieldError, MarchingOptions, parse_json, try_mesh_solid};
    use wingedge::validate::{Options, Validity, validate_soup};
    let blob = |c: f64, resolution: usize| {
        // Radius 1, or 10 beyond 1e13 (so that a coarse grid sees it).
        let r = if c > 1e13 { 10.0 } else { 1.0 };
        let doc = parse_json(&format!(
            r#"{{"blobs": [{{"center": [{c:e}, {c:e}, {c:e}], "radius": {r}}},
                          {{"center": [{c:e}, {d:e}, {c:e}], "radius": {s}}}]}}"#,
            d = c + r,
            s = 0.8 * r
        ))
        .unwrap();
        let options = MarchingOptions {
            resolution,
            ..MarchingOptions::default()
        };
        try_mesh_solid(doc.field.as_ref(), &options)
    };
    for (c, resolution) in [(1e12, 64), (1e12, 128), (1e13, 8), (1e14, 16)] {
        let (solid, meshed) =
            blob(c, resolution).unwrap_or_else(|e| panic!("{c:e} at {resolution}: {e}"));
        let report = validate_soup(&meshed.soup, None, &Options::default()).unwrap();
        assert_eq!(
            report.validity,
            Validity::ValidSolid,
            "{c:e} at {resolution}: {:?}",
            report.violations.first()
        );
        assert!(solid.volume() > 0.0);
    }
    for (c, resolution) in [(1e13, 64), (1e15, 64), (1e100, 64)] {
        let e = blob(c, resolution).expect_err("refused");
        assert!(
            matches!(e, FieldError::CellBelowResolution { .. }),
            "{c:e} at {resolution}: {e}"
        );
        assert!(e.to_string().contains("use a coarser resolution"), "{e}");
    }
}
