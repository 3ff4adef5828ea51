//! Polyhedral leaves: the query layer's exact crossings inside CSG trees,
//! mesh scenes, and defective meshes refused with the validator's report.

use std::path::Path;

use crate::common::temp_dir::TempDir;
use glam::DVec3;
use wingedge::csg::{AxisBox, Containment, Csg, CsgExpr, Polyhedron, Stats};
use wingedge::geom::Ray;
use wingedge::mesh::{Solid, builders};
use wingedge::scene::Scene;

fn mesh(solid: Solid) -> CsgExpr {
    CsgExpr::leaf(Polyhedron::try_new(solid).unwrap())
}

fn cuboid(min: [f64; 3], max: [f64; 3]) -> Solid {
    builders::cuboid(DVec3::from(min), DVec3::from(max)).unwrap()
}

fn tree(e: CsgExpr) -> Csg {
    Csg::try_new(e).unwrap()
}

fn ts(csg: &Csg, o: DVec3, d: DVec3) -> (bool, Vec<f64>) {
    let s = csg.spans(&Ray::new(o, d), &mut Stats::default());
    (s.origin_inside, s.hits.iter().map(|h| h.t).collect())
}

#[test]
fn a_cube_mesh_answers_like_a_box() {
    let as_mesh = tree(mesh(builders::cube()));
    let as_box = tree(CsgExpr::leaf(
        AxisBox::try_new(DVec3::splat(-1.0), DVec3::ONE).unwrap(),
    ));
    for k in 0..400 {
        let f = f64::from(k);
        // Half-integer grid points: many on faces, edges and corners.
        let p = DVec3::new(
            ((f * 0.7).sin() * 3.0).round() * 0.5,
            ((f * 1.3).cos() * 3.0).round() * 0.5,
            ((f * 0.3).sin() * 3.0).round() * 0.5,
        );
        assert_eq!(
            as_mesh.classify_point(p, &mut Stats::default()),
            as_box.classify_point(p, &mut Stats::default()),
            "{p}"
        );
        let o = DVec3::new(
            (f * 0.37).sin() * 4.,
            (f * 0.91).cos() * 4.,
            (f * 0.13).sin() * 4.,
        );
        let d = DVec3::new((f * 1.7).cos(), (f * 2.3).sin(), 0.5 - (f * 0.7).cos());
        let (a, b) = (ts(&as_mesh, o, d), ts(&as_box, o, d));
        assert_eq!(a.0, b.0, "ray {k}");
        assert_eq!(a.1.len(), b.1.len(), "ray {k}");
        for (x, y) in a.1.iter().zip(&b.1) {
            assert!(
                (x - y).abs() <= 1e-12 * x.abs().max(1.0),
                "ray {k}: {x} vs {y}"
            );
        }
    }
}

#[test]
fn touching_mesh_cubes_merge_without_a_phantom_face() {
    let u = tree(mesh(cuboid([0.; 3], [1.; 3])).union(mesh(cuboid([1., 0., 0.], [2., 1., 1.]))));
    assert_eq!(
        ts(&u, DVec3::new(-1., 0.5, 0.5), DVec3::X),
        (false, vec![1.0, 3.0])
    );
    let mut stats = Stats::default();
    assert_eq!(
        u.classify_point(DVec3::new(1., 0.5, 0.5), &mut stats),
        Containment::Inside
    );
    assert_eq!(
        u.classify_point(DVec3::new(1., 1., 0.5), &mut stats),
        Containment::OnBoundary
    );
    // The face where B cuts A is the boundary of A − B.
    let d =
        tree(mesh(cuboid([0.; 3], [2.; 3])).difference(mesh(cuboid([1., -1., -1.], [3., 3., 3.]))));
    assert_eq!(
        d.classify_point(DVec3::new(1., 0.5, 0.5), &mut stats),
        Containment::OnBoundary
    );
    assert_eq!(
        ts(&d, DVec3::new(-1., 0.5, 0.5), DVec3::X),
        (false, vec![1.0, 2.0])
    );
    // A mesh and a box with coincident faces behave the same way.
    let mixed = tree(mesh(cuboid([0.; 3], [1.; 3])).union(CsgExpr::leaf(
        AxisBox::try_new(DVec3::new(1., 0., 0.), DVec3::new(2., 1., 1.)).unwrap(),
    )));
    assert_eq!(
        ts(&mixed, DVec3::new(-1., 0.5, 0.5), DVec3::X),
        (false, vec![1.0, 3.0])
    );
}

#[test]
fn a_minus_a_is_empty_and_a_union_a_is_a_for_meshes() {
    let a = || mesh(builders::dodecahedron());
    let only = tree(a());
    let empty = tree(a().difference(a()));
    let same = tree(a().union(a()));
    for k in 0..300 {
        let f = f64::from(k);
        let o = DVec3::new(
            (f * 0.37).sin() * 4.,
            (f * 0.91).cos() * 4.,
            (f * 0.13).sin() * 4.,
        );
        let d = DVec3::new((f * 1.7).cos(), (f * 2.3).sin(), 0.5 - (f * 0.7).cos());
        assert_eq!(ts(&empty, o, d), (false, vec![]), "ray {k}");
        assert_eq!(ts(&same, o, d), ts(&only, o, d), "ray {k}");
    }
}

#[test]
fn a_single_mesh_has_its_divergence_theorem_volume_and_integration_agrees() {
    let solid = builders::dodecahedron();
    let exact = solid.volume();
    let csg = tree(mesh(solid));
    let v = csg.try_volume(0.01).unwrap();
    assert_eq!(v.exact, Some(exact));
    assert!(
        ((v.volume - exact) / exact).abs() < 1e-3,
        "{} vs {exact}",
        v.volume
    );
}

#[test]
fn a_ray_through_one_of_a_hundred_polyhedra_tests_few_leaves() {
    let mut leaves = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            let min = [3.0 * f64::from(i), 3.0 * f64::from(j), 0.0];
            leaves.push(mesh(cuboid(min, [min[0] + 1., min[1] + 1., 1.])));
        }
    }
    let csg = tree(CsgExpr::Union(leaves));
    let mut stats = Stats::default();
    let ray = Ray::new(DVec3::new(0.5, 0.5, -3.), DVec3::new(-0.1, -0.1, 1.));
    assert_eq!(csg.spans(&ray, &mut stats).hits.len(), 2);
    assert!(stats.primitive_ray_tests <= 3, "{stats}");
}

#[test]
fn bundled_mesh_scenes_load_and_defective_meshes_are_refused() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/scenes");
    for name in ["mesh_cut.json", "platonic.json"] {
        let scene = Scene::from_file(&dir.join(name)).unwrap();
        let v = scene.csg.try_volume(0.05).unwrap();
        assert!(v.volume > 0.0, "{name}");
    }
    // The cut dodecahedron is a subset of the dodecahedron.
    let cut = Scene::from_file(&dir.join("mesh_cut.json")).unwrap();
    let whole = builders::dodecahedron().volume();
    let v = cut.csg.try_volume(0.02).unwrap().volume;
    assert!(v > 0.2 * whole && v < whole, "{v}");

    // A cube with one face missing: refused with the validator's verdict.
    let tmp = TempDir::new("open");
    tmp.write(
        "open.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
         f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n",
    );
    tmp.write(
        "scene.json",
        r#"{"root": {"union": [{"box": {"min": [0,0,0], "max": [1,1,1]}}, {"mesh": "open.obj"}]}}"#,
    );
    let error = Scene::from_file(&tmp.path().join("scene.json"))
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("scene.json: root.union[1].mesh: mesh "),
        "{error}"
    );
    assert!(error.contains("open.obj"), "{error}");
    assert!(error.contains("not a valid closed solid"), "{error}");
}

#[test]
fn a_ray_through_a_reflex_edge_leaves_no_zero_length_span() {
    // Found while preparing the scene_load fuzz run
    // (fixtures/fuzz/scene_load/): the L-prism's crossings out and back in
    // at the reflex edge share one `t`, and a lone leaf passed both on, so
    // the spans were not strictly ascending.
    let text = r#"{"root": {"transform": {"scale": [-1, 1, 1]},
                             "child": {"mesh": "../valid/prism.obj"}}}"#;
    let base = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/scenes");
    let csg = Scene::from_json(text, "mirrored.json", &base).unwrap().csg;
    // From beside the box to its centre, on the reflex edge x = −1, y = 1.
    let eye = DVec3::new(2.0, 3.0, 1.5);
    let ray = Ray::new(eye, DVec3::new(-1.0, 1.0, 0.5) - eye);
    let spans = csg.spans(&ray, &mut Stats::default());
    let ts: Vec<f64> = spans.hits.iter().map(|h| h.t).collect();
    assert!(ts.windows(2).all(|w| w[0] < w[1]), "{ts:?}");
    assert_eq!(ts.len() % 2, 0, "{ts:?}");
    let hit = csg.first_hit(&ray, &mut Stats::default()).unwrap();
    assert_eq!(hit.t, ts[0]);
}
