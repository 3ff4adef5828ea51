//! The CSG tree: coincident faces, identities, nesting, culling counts and
//! volume convergence.

use glam::{DAffine3, DVec3};
use proptest::prelude::*;
use wingedge::csg::{
    AxisBox, Containment, Csg, CsgExpr, Cylinder, HalfSpace, Spans, Sphere, Stats,
};
use wingedge::geom::Ray;

fn cube(min: [f64; 3], max: [f64; 3]) -> CsgExpr {
    CsgExpr::leaf(AxisBox::try_new(DVec3::from(min), DVec3::from(max)).unwrap())
}

fn ball(c: [f64; 3], r: f64) -> CsgExpr {
    CsgExpr::leaf(Sphere::try_new(DVec3::from(c), r).unwrap())
}

fn tree(e: CsgExpr) -> Csg {
    Csg::try_new(e).unwrap()
}

fn ts(spans: &Spans) -> Vec<f64> {
    spans.hits.iter().map(|h| h.t).collect()
}

fn spans(csg: &Csg, o: [f64; 3], d: [f64; 3]) -> Spans {
    csg.spans(
        &Ray::new(DVec3::from(o), DVec3::from(d)),
        &mut Stats::default(),
    )
}

fn classify(csg: &Csg, p: [f64; 3]) -> Containment {
    csg.classify_point(DVec3::from(p), &mut Stats::default())
}

#[test]
fn touching_boxes_leave_no_phantom_boundary() {
    let u = tree(cube([0.; 3], [1.; 3]).union(cube([1., 0., 0.], [2., 1., 1.])));
    let s = spans(&u, [-1., 0.5, 0.5], [1., 0., 0.]);
    assert_eq!((s.origin_inside, ts(&s)), (false, vec![1.0, 3.0]));
    // From inside the first box, across the shared face.
    let s = spans(&u, [0.5, 0.5, 0.5], [1., 0., 0.]);
    assert_eq!((s.origin_inside, ts(&s)), (true, vec![1.5]));
    // The first hit from the far side is the outer face, not the shared one.
    let hit = u
        .first_hit(
            &Ray::new(DVec3::new(3., 0.5, 0.5), -DVec3::X),
            &mut Stats::default(),
        )
        .unwrap();
    assert_eq!(hit.t, 1.0);
    // A point on the shared face is inside the union.
    assert_eq!(classify(&u, [1., 0.5, 0.5]), Containment::Inside);
    assert_eq!(classify(&u, [1., 1., 0.5]), Containment::OnBoundary);
    assert_eq!(classify(&u, [2., 0.5, 0.5]), Containment::OnBoundary);
    // Their intersection is a face: no volume, so outside, and no spans.
    let i = tree(cube([0.; 3], [1.; 3]).intersection(cube([1., 0., 0.], [2., 1., 1.])));
    assert!(ts(&spans(&i, [-1., 0.5, 0.5], [1., 0., 0.])).is_empty());
    assert_eq!(classify(&i, [1., 0.5, 0.5]), Containment::Outside);
}

#[test]
fn a_ray_in_the_shared_face_plane_is_in_exactly_one_box() {
    let u = tree(cube([0.; 3], [1.; 3]).union(cube([1., 0., 0.], [2., 1., 1.])));
    let mut stats = Stats::default();
    let s = u.spans(&Ray::new(DVec3::new(1., -1., 0.5), DVec3::Y), &mut stats);
    assert_eq!(ts(&s), vec![1.0, 2.0]);
    assert!(stats.tie_breaks >= 1);
}

#[test]
fn coincident_faces_where_b_cuts_a() {
    // B flush with A's right face: A − B = [0, 1] × [0, 2]².
    let a_minus_b = tree(cube([0.; 3], [2.; 3]).difference(cube([1., 0., 0.], [2., 2., 2.])));
    let s = spans(&a_minus_b, [-1., 0.5, 0.5], [1., 0., 0.]);
    assert_eq!(ts(&s), vec![1.0, 2.0]);
    // A point on the face where B cuts A is on the boundary of A − B.
    assert_eq!(
        classify(&a_minus_b, [1., 0.5, 0.5]),
        Containment::OnBoundary
    );
    // A point on the coincident face x = 2 is outside A − B.
    assert_eq!(classify(&a_minus_b, [2., 0.5, 0.5]), Containment::Outside);
    assert_eq!(classify(&a_minus_b, [0.5, 0.5, 0.5]), Containment::Inside);
    // A hole through the middle: the point on the hole's wall is boundary.
    let drilled = tree(cube([0.; 3], [3.; 3]).difference(cube([1., 1., -1.], [2., 2., 4.])));
    assert_eq!(classify(&drilled, [1., 1.5, 1.5]), Containment::OnBoundary);
    assert_eq!(classify(&drilled, [1.5, 1.5, 1.5]), Containment::Outside);
    assert_eq!(
        ts(&spans(&drilled, [-1., 1.5, 1.5], [1., 0., 0.])),
        vec![1., 2., 3., 4.]
    );
    // The first hit on B's wall has B's normal flipped: it faces the ray.
    let ray = Ray::new(DVec3::new(1.5, 1.5, 1.5), DVec3::X);
    let mut stats = Stats::default();
    let hit = drilled.first_hit(&ray, &mut stats).unwrap();
    assert!(hit.entering && hit.t == 0.5);
    assert_eq!(drilled.hit_normal(&ray, &hit, &mut stats), -DVec3::X);
    assert_eq!(drilled.leaf(hit.leaf).unwrap().label, "box");
}

#[test]
fn a_minus_a_is_empty_and_a_union_a_is_a() {
    for a in [
        || cube([0.; 3], [1., 2., 3.]),
        || ball([0.; 3], 1.5),
        || CsgExpr::leaf(Cylinder::try_new(DVec3::ZERO, DVec3::new(0.3, 1., 2.), 0.7).unwrap()),
    ] {
        let only = tree(a());
        let empty = tree(a().difference(a()));
        let same = tree(a().union(a()));
        let meet = tree(a().intersection(a()));
        for k in 0..200 {
            let f = k as f64;
            let o = [
                (f * 0.37).sin() * 4.,
                (f * 0.91).cos() * 4.,
                (f * 0.13).sin() * 4.,
            ];
            let d = [(f * 1.7).cos(), (f * 2.3).sin(), 0.5 - (f * 0.7).cos()];
            let reference = spans(&only, o, d);
            let e = spans(&empty, o, d);
            assert!(!e.origin_inside && e.hits.is_empty(), "A − A along ray {k}");
            assert_eq!(spans(&same, o, d), reference);
            assert_eq!(ts(&spans(&meet, o, d)), ts(&reference));
            assert_eq!(spans(&meet, o, d).origin_inside, reference.origin_inside);
            assert_eq!(classify(&empty, o), Containment::Outside);
            assert_eq!(classify(&same, o), classify(&only, o));
        }
    }
}

/// ((((A ∪ B) − C) ∩ D) − E), transformed, checked along random rays: the
/// midpoints of spans are inside, the midpoints of gaps outside.
#[test]
fn nested_trees_of_depth_five_agree_with_point_classification() {
    let expr = cube([0.; 3], [2.; 3])
        .union(ball([2., 1., 1.], 0.8))
        .difference(CsgExpr::leaf(
            Cylinder::try_new(DVec3::new(1., 1., -1.), DVec3::new(0., 0., 4.), 0.4).unwrap(),
        ))
        .intersection(CsgExpr::leaf(
            HalfSpace::try_new(DVec3::new(0., 0., 1.5), DVec3::new(0.2, 0.1, 1.)).unwrap(),
        ))
        .difference(ball([0., 0., 0.], 0.7))
        .transformed(DAffine3::from_rotation_y(0.4) * DAffine3::from_translation(DVec3::X));
    let csg = tree(expr);
    assert!(csg.depth() >= 5, "depth {}", csg.depth());
    let mut checked = 0;
    for k in 0..300 {
        let f = k as f64;
        let o = DVec3::new(
            (f * 0.37).sin() * 4.,
            (f * 0.91).cos() * 4.,
            (f * 0.13).sin() * 4.,
        );
        // Aimed at the solid (the point (1.5, 0.7, 0) after the transform).
        let target = DVec3::new(
            1.5 + (f * 1.7).cos(),
            0.7 + (f * 2.3).sin(),
            (f * 0.7).cos(),
        );
        let ray = Ray::new(o, target - o);
        let s = csg.spans(&ray, &mut Stats::default());
        let mut ends = vec![0.0];
        ends.extend(s.hits.iter().map(|h| h.t));
        ends.push(ends.last().unwrap() + 10.0);
        let mut inside = s.origin_inside;
        for w in ends.windows(2) {
            let mid = ray.at(0.5 * (w[0] + w[1]));
            let expected = if inside {
                Containment::Inside
            } else {
                Containment::Outside
            };
            assert_eq!(
                csg.classify_point(mid, &mut Stats::default()),
                expected,
                "ray {k}"
            );
            inside = !inside;
            checked += 1;
        }
    }
    assert!(checked > 600);
}

#[test]
fn a_union_of_a_thousand_boxes_tests_only_the_box_the_ray_meets() {
    let mut boxes = Vec::new();
    for i in 0..10 {
        for j in 0..10 {
            for k in 0..10 {
                let min = [3. * i as f64, 3. * j as f64, 3. * k as f64];
                boxes.push(cube(min, [min[0] + 1., min[1] + 1., min[2] + 1.]));
            }
        }
    }
    let csg = tree(CsgExpr::Union(boxes));
    assert_eq!(csg.leaves().len(), 1000);
    assert!(csg.depth() <= 12, "balanced: depth {}", csg.depth());
    // Enters box (0,0,0) from below and leaves the grid sideways.
    let ray = Ray::new(DVec3::new(0.5, 0.5, -3.), DVec3::new(-0.1, -0.1, 1.));
    let mut stats = Stats::default();
    let s = csg.spans(&ray, &mut stats);
    assert_eq!(ts(&s), vec![3.0, 4.0]);
    assert!(stats.primitive_ray_tests <= 3, "{stats}");
    assert!(stats.culled_subtrees >= 1, "{stats}");
    assert!(stats.bounds_tests <= 60, "{stats}");
    // A ray that misses the whole grid is culled at the root.
    let mut stats = Stats::default();
    let miss = csg.spans(
        &Ray::new(DVec3::new(-5., -5., -5.), -DVec3::ONE),
        &mut stats,
    );
    assert!(miss.hits.is_empty());
    assert_eq!((stats.primitive_ray_tests, stats.culled_subtrees), (0, 1));
    // A ray along a row of ten boxes: ten primitive tests, and a first-hit
    // query stops merging at the first box.
    let row = Ray::new(DVec3::new(-1., 0.5, 0.5), DVec3::X);
    let mut stats = Stats::default();
    assert_eq!(csg.spans(&row, &mut stats).hits.len(), 20);
    assert_eq!(stats.primitive_ray_tests, 10);
    let mut stats = Stats::default();
    assert_eq!(csg.first_hit(&row, &mut stats).unwrap().t, 1.0);
    assert_eq!(stats.early_stops, 1);
    assert_eq!(stats.normals, 0);
    // Points: one box visited.
    let mut stats = Stats::default();
    assert_eq!(
        csg.classify_point(DVec3::new(12.5, 0.5, 27.5), &mut stats),
        Containment::Inside
    );
    assert_eq!(stats.primitive_point_tests, 1, "{stats}");
}

#[test]
fn intersection_and_difference_skip_the_right_side_when_the_left_is_empty() {
    let left = || ball([0.; 3], 1.);
    let right = || cube([-2.; 3], [2.; 3]);
    let ray = Ray::new(DVec3::new(-5., 0.9, 0.9), DVec3::X); // misses the ball
    for csg in [
        tree(left().intersection(right())),
        tree(left().difference(right())),
    ] {
        let mut stats = Stats::default();
        assert!(csg.spans(&ray, &mut stats).hits.is_empty());
        assert_eq!(stats.primitive_ray_tests, 1, "{stats}");
        assert_eq!(stats.skipped_right_sides, 1, "{stats}");
    }
    // A union whose left side holds the whole ray skips its right side.
    let everything = CsgExpr::leaf(HalfSpace::try_new(DVec3::ZERO, DVec3::Z).unwrap());
    let csg = tree(everything.union(ball([0.; 3], 1.)));
    let mut stats = Stats::default();
    let s = csg.spans(&Ray::new(DVec3::new(0., 0., -1.), DVec3::X), &mut stats);
    assert!(s.origin_inside && s.hits.is_empty());
    assert_eq!(stats.skipped_right_sides, 1);
}

#[test]
fn exact_fallbacks_are_counted_for_half_spaces() {
    // A plane through (0.1, 0.1, 0.1) with normal (1, 1, 1) and a point on
    // it up to rounding: the filter cannot decide.
    let csg = tree(CsgExpr::leaf(
        HalfSpace::try_new(DVec3::splat(0.1), DVec3::ONE).unwrap(),
    ));
    let mut stats = Stats::default();
    let _ = csg.classify_point(DVec3::new(0.3, 0., 0.), &mut stats);
    assert!(stats.exact_fallbacks >= 1, "{stats}");
    let mut stats = Stats::default();
    let _ = csg.classify_point(DVec3::new(5., 0., 0.), &mut stats);
    assert_eq!(stats.exact_fallbacks, 0);
}

/// The drilled cube: [−1, 1]³ minus three cylinders of radius ½ along the
/// axes. Its volume is 8 − (3·π r²·2 − 3·16 r³/3 + 8 (2 − √2) r³).
fn drilled_cube() -> (Csg, f64) {
    let r = 0.5;
    let drill = |axis: DVec3| CsgExpr::leaf(Cylinder::try_new(-2.0 * axis, 4.0 * axis, r).unwrap());
    let csg = tree(CsgExpr::Difference(vec![
        cube([-1.; 3], [1.; 3]),
        drill(DVec3::X),
        drill(DVec3::Y),
        drill(DVec3::Z),
    ]));
    let pi = std::f64::consts::PI;
    let cylinders = 3.0 * pi * r * r * 2.0 - 3.0 * 16.0 * r * r * r / 3.0
        + 8.0 * (2.0 - 2f64.sqrt()) * r * r * r;
    (csg, 8.0 - cylinders)
}

#[test]
fn volume_converges_as_the_spacing_shrinks() {
    let (csg, exact) = drilled_cube();
    let mut errors = Vec::new();
    for h in [0.2, 0.1, 0.05, 0.025, 0.0125] {
        let v = csg.try_volume(h).unwrap();
        errors.push(((v.volume - exact) / exact).abs());
        assert!(v.exact.is_none());
    }
    assert!(errors.last().unwrap() < &2e-3, "{errors:?}");
    assert!(errors[4] < errors[0] / 4.0, "{errors:?}");
    // A single leaf also reports its closed-form volume.
    let sphere = tree(ball([1., 2., 3.], 2.));
    let v = sphere.try_volume(0.02).unwrap();
    let exact = v.exact.unwrap();
    assert!(((v.volume - exact) / exact).abs() < 1e-3);
    // An unbounded solid has no volume.
    let half = tree(CsgExpr::leaf(
        HalfSpace::try_new(DVec3::ZERO, DVec3::ONE).unwrap(),
    ));
    assert!(half.try_volume(0.1).is_err());
    assert!(sphere.try_volume(0.0).is_err());
}

fn box_strategy() -> impl Strategy<Value = ([f64; 3], [f64; 3])> {
    // Integer corners in [0, 4]: many shared and coincident faces.
    prop::array::uniform3((0u8..4, 1u8..4)).prop_map(|axes| {
        let mut min = [0.0; 3];
        let mut max = [0.0; 3];
        for (k, (lo, len)) in axes.into_iter().enumerate() {
            min[k] = f64::from(lo);
            max[k] = f64::from(lo) + f64::from(len);
        }
        (min, max)
    })
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(64)))]

    /// A − (B ∪ C) = (A − B) ∩ (A − C), A − (B ∩ C) = (A − B) ∪ (A − C),
    /// A ∩ (B ∪ C) = (A ∩ B) ∪ (A ∩ C) and A ∩ B ⊆ A: the same spans along
    /// rays on the grid of box coordinates (so through shared faces and
    /// edges) and the same class for points on the face planes.
    #[test]
    fn de_morgan_identities_hold_on_rays_and_points(
        a in box_strategy(), b in box_strategy(), c in box_strategy(),
        origin in prop::array::uniform3(-2i8..7), direction in prop::array::uniform3(-3i8..4),
        points in prop::collection::vec((0u8..3, -2i8..7, -0.5f64..4.5, -0.5f64..4.5), 20),
    ) {
        let leaf = |(min, max): ([f64; 3], [f64; 3])| cube(min, max);
        let pairs = [
            (leaf(a).difference(leaf(b).union(leaf(c))),
             leaf(a).difference(leaf(b)).intersection(leaf(a).difference(leaf(c)))),
            (leaf(a).difference(leaf(b).intersection(leaf(c))),
             leaf(a).difference(leaf(b)).union(leaf(a).difference(leaf(c)))),
            (leaf(a).intersection(leaf(b).union(leaf(c))),
             leaf(a).intersection(leaf(b)).union(leaf(a).intersection(leaf(c)))),
        ];
        let o = origin.map(|v| f64::from(v) * 0.5);
        let d = direction.map(f64::from);
        prop_assume!(d != [0.0; 3]);
        for (lhs, rhs) in pairs {
            let (lhs, rhs) = (tree(lhs), tree(rhs));
            let (l, r) = (spans(&lhs, o, d), spans(&rhs, o, d));
            prop_assert_eq!(l.origin_inside, r.origin_inside);
            prop_assert_eq!(ts(&l), ts(&r));
            for &(axis, plane, u, v) in &points {
                // On a face plane x, y or z = k/2, generic in the other two.
                let mut p = [u, v, u];
                p[axis as usize] = f64::from(plane) * 0.5;
                p[(axis as usize + 1) % 3] = u;
                p[(axis as usize + 2) % 3] = v;
                prop_assert_eq!(classify(&lhs, p), classify(&rhs, p), "point {:?}", p);
            }
        }
        // A ∩ B ⊆ A: a span of A ∩ B is never outside A. (A ray lying in
        // one of A's face planes is put inside A by the perturbation; the
        // midpoint of such a span is then on A's boundary.)
        let meet = tree(leaf(a).intersection(leaf(b)));
        let only_a = tree(leaf(a));
        let ray = Ray::new(DVec3::from(o), DVec3::from(d));
        for (s, e) in meet.spans(&ray, &mut Stats::default()).intervals() {
            let mid = ray.at(0.5 * (s + e));
            prop_assert_ne!(only_a.classify_point(mid, &mut Stats::default()), Containment::Outside);
        }
        // And at points: inside A ∩ B implies inside A.
        for &(axis, plane, u, v) in &points {
            let mut p = [u, v, u];
            p[axis as usize] = f64::from(plane) * 0.5;
            p[(axis as usize + 1) % 3] = u;
            p[(axis as usize + 2) % 3] = v;
            if classify(&meet, p) == Containment::Inside {
                prop_assert_eq!(classify(&only_a, p), Containment::Inside);
            }
        }
    }
}

/// The bundled 101-leaf scene: balls touching a slab at a point and boxes
/// standing on it (coincident faces). Its volume is the sum of the leaves'.
#[test]
fn the_many_leaves_scene_has_the_sum_of_its_leaves_volumes() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/fixtures/scenes/many_leaves.json"
    );
    let scene = wingedge::scene::Scene::from_file(std::path::Path::new(path)).unwrap();
    let exact: f64 = scene
        .csg
        .leaves()
        .iter()
        .map(|l| l.primitive.exact_volume().unwrap())
        .sum();
    let v = scene.csg.try_volume(0.01).unwrap();
    assert!(
        ((v.volume - exact) / exact).abs() < 1e-3,
        "{} vs {exact}",
        v.volume
    );
    // A ray down through a box: the box's bottom face and the slab's top
    // face coincide, so the spans are one piece from the box top to the
    // slab's bottom.
    let s = spans(&scene.csg, [-5.0 + 10.0 / 9.0, -5.0, 3.0], [0., 0., -1.]);
    assert_eq!(s.hits.len(), 2, "{s:?}");
    assert_eq!(s.hits[1].t, 3.5);
}

/// A random tree of boxes and balls, up to depth 5.
fn random_tree() -> impl Strategy<Value = CsgExpr> {
    let leaf = prop_oneof![
        box_strategy().prop_map(|(min, max)| cube(min, max)),
        (prop::array::uniform3(0i8..5), 1u8..4)
            .prop_map(|(c, r)| ball(c.map(f64::from), f64::from(r) * 0.5)),
    ];
    leaf.prop_recursive(4, 16, 2, |inner| {
        (inner.clone(), inner, 0u8..3).prop_map(|(a, b, op)| match op {
            0 => a.union(b),
            1 => a.intersection(b),
            _ => a.difference(b),
        })
    })
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(96)))]

    /// Along any ray through a random tree, the midpoints of the spans are
    /// inside and the midpoints of the gaps outside; and the first hit is the
    /// first span boundary.
    #[test]
    fn spans_agree_with_point_classification_on_random_trees(
        expr in random_tree(),
        origin in prop::array::uniform3(-3.0f64..7.0),
        target in prop::array::uniform3(0.0f64..4.0),
    ) {
        let csg = tree(expr);
        let o = DVec3::from(origin);
        let d = DVec3::from(target) - o;
        prop_assume!(d.length() > 0.1);
        let ray = Ray::new(o, d);
        let s = csg.spans(&ray, &mut Stats::default());
        let mut ends = vec![0.0];
        ends.extend(s.hits.iter().map(|h| h.t));
        prop_assert!(ends.windows(2).all(|w| w[0] < w[1]), "ascending {:?}", ends);
        ends.push(ends.last().unwrap() + 100.0);
        let mut inside = s.origin_inside;
        for w in ends.windows(2) {
            let mid = ray.at(0.5 * (w[0] + w[1]));
            let c = csg.classify_point(mid, &mut Stats::default());
            // A midpoint can land exactly on a boundary only by accident.
            if c != Containment::OnBoundary {
                prop_assert_eq!(c == Containment::Inside, inside, "at t = {}", 0.5 * (w[0] + w[1]));
            }
            inside = !inside;
        }
        let first = csg.first_hit(&ray, &mut Stats::default());
        prop_assert_eq!(first.map(|h| h.t), s.hits.first().map(|h| h.t));
    }
}

#[test]
fn perturbation_tie_breaks_inside_polyhedra_are_counted() {
    let cube = wingedge::csg::Polyhedron::try_new(wingedge::mesh::builders::cube()).unwrap();
    let tree = Csg::from_primitive(cube);
    // A generic ray: no tie to break.
    let mut generic = Stats::default();
    let s = tree.spans(
        &Ray::new(DVec3::new(-3., 0.1, 0.2), DVec3::new(1., 0.01, 0.02)),
        &mut generic,
    );
    assert_eq!(ts(&s).len(), 2);
    assert_eq!(generic.tie_breaks, 0);
    // A ray through two opposite vertices of the cube: ties at both, broken
    // by symbolic perturbation, and still one span.
    let mut corner = Stats::default();
    let s = tree.spans(&Ray::new(DVec3::splat(-2.0), DVec3::ONE), &mut corner);
    assert_eq!(ts(&s), vec![1.0, 3.0]);
    assert!(corner.tie_breaks >= 2, "{corner:?}");
}

#[test]
fn non_finite_points_and_invalid_rays_are_errors_in_the_try_forms() {
    // The no-panic audit: the plain forms answer `Outside` and an empty
    // span list; user input goes through the `try_` forms, which refuse.
    let csg = tree(cube([-1.0; 3], [1.0; 3]).difference(ball([0.0; 3], 0.5)));
    let mut stats = Stats::default();
    for p in [
        DVec3::new(f64::NAN, 0.0, 0.0),
        DVec3::new(0.0, f64::INFINITY, 0.0),
        DVec3::new(0.0, 0.0, f64::NEG_INFINITY),
    ] {
        assert!(csg.try_classify_point(p, &mut stats).is_err(), "{p}");
        assert_eq!(csg.classify_point(p, &mut stats), Containment::Outside);
    }
    assert_eq!(
        csg.try_classify_point(DVec3::splat(0.75), &mut stats),
        Ok(Containment::Inside)
    );
    for (o, d) in [
        ([0.0; 3], [0.0; 3]),
        ([f64::NAN, 0.0, 0.0], [1.0, 0.0, 0.0]),
        ([0.0; 3], [1.0, f64::INFINITY, 0.0]),
    ] {
        let ray = Ray::new(DVec3::from(o), DVec3::from(d));
        assert!(csg.try_spans(&ray, &mut stats).is_err(), "{ray:?}");
        assert!(csg.try_first_hit(&ray, &mut stats).is_err(), "{ray:?}");
        assert!(csg.spans(&ray, &mut stats).hits.is_empty());
    }
    let ray = Ray::new(DVec3::new(-3.0, 0.0, 0.0), DVec3::X);
    let spans = csg.try_spans(&ray, &mut stats).unwrap();
    assert_eq!(ts(&spans), [2.0, 2.5, 3.5, 4.0]);
    let hit = csg.try_first_hit(&ray, &mut stats).unwrap().unwrap();
    assert_eq!(hit.t, 2.0);
}
