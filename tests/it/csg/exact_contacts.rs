//! Where leaves of a CSG tree touch: points where surfaces meet at an
//! angle — shared corners and edges of touching solids, faces of two meshes
//! whose rounded normals differ — are classified exactly (regularised),
//! checked against an independent answer (the class of the points a little
//! way off in every cell around the point); and rays through a plane two
//! meshes share cross it once for both, not twice an ulp apart.

use crate::common::test_rng;

use glam::{DAffine3, DQuat, DVec3, EulerRot};
use wingedge::csg::{
    AxisBox, Containment, Csg, CsgExpr, EvaluateOptions, HalfSpace, Polyhedron, Primitive, Stats,
    evaluate, normal_alignment,
};
use wingedge::geom::{Ray, Sign};
use wingedge::mesh::{PolygonSoup, Solid, builders};
use wingedge::query::Accel;

fn boxed(min: [f64; 3], max: [f64; 3]) -> CsgExpr {
    CsgExpr::leaf(AxisBox::try_new(DVec3::from(min), DVec3::from(max)).unwrap())
}

fn mesh_box(min: [f64; 3], max: [f64; 3]) -> CsgExpr {
    let solid = builders::cuboid(DVec3::from(min), DVec3::from(max)).unwrap();
    CsgExpr::leaf(Polyhedron::try_new(solid).unwrap())
}

fn tree(e: CsgExpr) -> Csg {
    Csg::try_new(e).unwrap()
}

fn class(csg: &Csg, p: [f64; 3]) -> Containment {
    csg.classify_point(DVec3::from(p), &mut Stats::default())
}

#[test]
fn the_shared_corners_of_boxes_touching_along_a_face_are_outside_their_intersection() {
    for leaf in [boxed, mesh_box] {
        let a = || leaf([0.0; 3], [1.0; 3]);
        let b = || leaf([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
        let i = tree(a().intersection(b()));
        for p in [
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 1.0],
            [1.0, 0.5, 0.0],
            [1.0, 0.5, 0.5],
        ] {
            assert_eq!(class(&i, p), Containment::Outside, "{p:?}");
        }
        let u = tree(a().union(b()));
        assert_eq!(class(&u, [1.0, 0.5, 0.5]), Containment::Inside);
        // On the union's bottom edge and face: boundary.
        assert_eq!(class(&u, [1.0, 0.0, 0.0]), Containment::OnBoundary);
        assert_eq!(class(&u, [1.0, 0.5, 0.0]), Containment::OnBoundary);
        let d = tree(a().difference(b()));
        assert_eq!(class(&d, [1.0, 0.0, 0.0]), Containment::OnBoundary);
        assert_eq!(class(&d, [1.0, 0.5, 0.5]), Containment::OnBoundary);
    }
}

#[test]
fn boxes_touching_along_an_edge_or_at_a_corner() {
    for far in [[2.0, 2.0, 1.0], [2.0, 2.0, 2.0]] {
        let near = [1.0, 1.0, if far[2] == 1.0 { 0.0 } else { 1.0 }];
        let i = tree(boxed([0.0; 3], [1.0; 3]).intersection(mesh_box(near, far)));
        let u = tree(boxed([0.0; 3], [1.0; 3]).union(mesh_box(near, far)));
        let d = tree(boxed([0.0; 3], [1.0; 3]).difference(mesh_box(near, far)));
        let shared = [1.0, 1.0, 1.0];
        assert_eq!(class(&i, shared), Containment::Outside);
        assert_eq!(class(&u, shared), Containment::OnBoundary);
        assert_eq!(class(&d, shared), Containment::OnBoundary);
    }
    // A cube minus itself is empty, corners and all.
    let empty = tree(boxed([0.0; 3], [1.0; 3]).difference(mesh_box([0.0; 3], [1.0; 3])));
    for p in [[0.0; 3], [1.0, 0.0, 0.5], [1.0, 1.0, 1.0]] {
        assert_eq!(class(&empty, p), Containment::Outside, "{p:?}");
    }
    // A notch filled exactly: an L of two boxes plus the missing quarter is
    // a cube, whose inner (once reflex) edge is inside.
    let cube = tree(
        boxed([0.0; 3], [2.0, 1.0, 2.0])
            .union(mesh_box([0.0, 1.0, 0.0], [1.0, 2.0, 2.0]))
            .union(boxed([1.0, 1.0, 0.0], [2.0, 2.0, 2.0])),
    );
    assert_eq!(class(&cube, [1.0, 1.0, 1.0]), Containment::Inside);
    assert_eq!(class(&cube, [1.0, 1.0, 0.0]), Containment::OnBoundary);
    // A half-space cut flush with a box's corner.
    let cut = tree(boxed([0.0; 3], [1.0; 3]).intersection(CsgExpr::leaf(
        HalfSpace::try_new(DVec3::ONE, DVec3::new(-1.0, -1.0, -1.0)).unwrap(),
    )));
    // Only the corner (1, 1, 1) of the cube is in x + y + z ≥ 3.
    assert_eq!(class(&cut, [1.0, 1.0, 1.0]), Containment::Outside);
}

/// The regularised class of `p` for a tree of boxes whose coordinates are
/// integers, from the eight points `p + (±¼, ±¼, ±¼)` (one in each octant
/// of the axis planes through `p`, the only planes there; none of them on
/// a boundary), classified the ordinary way.
fn octant_oracle(csg: &Csg, p: DVec3) -> Containment {
    let (mut inside, mut outside) = (0, 0);
    for k in 0..8 {
        let d = DVec3::new(
            if k & 1 == 0 { -0.25 } else { 0.25 },
            if k & 2 == 0 { -0.25 } else { 0.25 },
            if k & 4 == 0 { -0.25 } else { 0.25 },
        );
        match csg.classify_point(p + d, &mut Stats::default()) {
            Containment::Inside => inside += 1,
            Containment::Outside => outside += 1,
            Containment::OnBoundary => panic!("{:?} is on a boundary", p + d),
        }
    }
    match (inside, outside) {
        (8, 0) => Containment::Inside,
        (0, 8) => Containment::Outside,
        _ => Containment::OnBoundary,
    }
}

#[test]
fn random_box_trees_agree_with_the_octants_at_every_grid_point() {
    let mut bits = test_rng::bits(0x5eed_c0de);
    let mut below = move |n: u64| bits() % n;
    let mut analyses = 0;
    for _ in 0..60 {
        let leaf = |below: &mut dyn FnMut(u64) -> u64| {
            let lo = [0, 1, 2].map(|_| below(3) as f64);
            let hi = lo.map(|x| x + 1.0 + below(2) as f64);
            if below(2) == 0 {
                boxed(lo, hi)
            } else {
                mesh_box(lo, hi)
            }
        };
        let mut e = leaf(&mut below);
        for _ in 0..3 {
            let other = leaf(&mut below);
            e = match below(3) {
                0 => e.union(other),
                1 => e.intersection(other),
                _ => e.difference(other),
            };
        }
        let csg = tree(e);
        for x in 0..5 {
            for y in 0..5 {
                for z in 0..5 {
                    let p = DVec3::new(x as f64, y as f64, z as f64);
                    let mut stats = Stats::default();
                    let got = csg.classify_point(p, &mut stats);
                    analyses += stats.direction_analyses;
                    assert_eq!(got, octant_oracle(&csg, p), "{p}");
                }
            }
        }
    }
    assert!(analyses > 1000, "{analyses}");
}

/// The solid of these polygons, wound outward (turned if they were not).
fn outward(positions: Vec<DVec3>, mut faces: Vec<Vec<usize>>) -> Solid {
    let solid = Solid::try_from_soup(&PolygonSoup::new(positions.clone(), &faces)).unwrap();
    if solid.volume() > 0.0 {
        return solid;
    }
    for f in &mut faces {
        f.reverse();
    }
    Solid::try_from_soup(&PolygonSoup::new(positions, &faces)).unwrap()
}

/// The tetrahedron on the triangle `base` with its apex at `apex`.
fn tetrahedron(base: [DVec3; 3], apex: DVec3) -> Solid {
    let faces = vec![vec![0, 1, 2], vec![1, 0, 3], vec![2, 1, 3], vec![0, 2, 3]];
    outward(vec![base[0], base[1], base[2], apex], faces)
}

/// A pyramid on the parallelogram `base` (in boundary order) with its apex
/// at `apex`.
fn pyramid(base: [DVec3; 4], apex: DVec3) -> Solid {
    let mut faces = vec![vec![0, 1, 2, 3]];
    faces.extend((0..4).map(|k| vec![(k + 1) % 4, k, 4]));
    let mut positions = base.to_vec();
    positions.push(apex);
    outward(positions, faces)
}

#[test]
fn meshes_sharing_a_tilted_plane_whose_rounded_normals_differ() {
    let mut bits = test_rng::bits(7);
    // Coordinates on a 2^-30 grid in [0.5, 1): sums of two and halves are
    // exact, so p = (a + b + 2c) / 4 lies exactly inside the triangle,
    // while the face normals (products of 30-bit numbers) are rounded.
    let mut coordinate = || 0.5 + ((bits() % (1 << 29)) as f64) * f64::powi(2.0, -30);
    let mut found = 0;
    for _ in 0..400 {
        let [a, b, c] = [0, 1, 2].map(|_| DVec3::new(coordinate(), coordinate(), coordinate()));
        let n = (b - a).cross(c - a);
        if n.length() < 1e-3 {
            continue;
        }
        // The parallelogram a, b, b + c − a, c (exactly flat) under the
        // tilted plane, and the triangle a, b, c (half of it) above.
        let base = [a, b, b + c - a, c];
        let lower = Polyhedron::try_new(pyramid(base, a - n)).unwrap();
        let upper = Polyhedron::try_new(tetrahedron([a, b, c], a + n)).unwrap();
        let p = (a + b + 2.0 * c) / 4.0;
        let (nl, nu) = (lower.boundary_normal(p), upper.boundary_normal(p));
        let (Some(nl), Some(nu)) = (nl, nu) else {
            panic!("p is inside both faces")
        };
        if normal_alignment(nl, nu) != Sign::Zero {
            // The rounded normals happen to be exactly opposite: the
            // coincident faces are recognised without the analysis.
            continue;
        }
        found += 1;
        let leaf = |p: &Polyhedron| CsgExpr::leaf(p.clone());
        let u = tree(leaf(&lower).union(leaf(&upper)));
        let i = tree(leaf(&lower).intersection(leaf(&upper)));
        let d = tree(leaf(&lower).difference(leaf(&upper)));
        let mut stats = Stats::default();
        assert_eq!(u.classify_point(p, &mut stats), Containment::Inside);
        assert_eq!(stats.direction_analyses, 1);
        assert_eq!(i.classify_point(p, &mut stats), Containment::Outside);
        assert_eq!(d.classify_point(p, &mut stats), Containment::OnBoundary);
    }
    assert!(found >= 10, "{found}");
}

#[test]
fn rays_through_a_tilted_plane_two_meshes_share_cross_it_once() {
    let mut bits = test_rng::bits(11);
    let mut coordinate = || 0.5 + ((bits() % (1 << 29)) as f64) * f64::powi(2.0, -30);
    let (mut rounded_apart, mut stats) = (0, Stats::default());
    for _ in 0..200 {
        let [a, b, c] = [0, 1, 2].map(|_| DVec3::new(coordinate(), coordinate(), coordinate()));
        let n = (b - a).cross(c - a);
        if n.length() < 1e-3 {
            continue;
        }
        let lower = Polyhedron::try_new(pyramid([a, b, b + c - a, c], a - n)).unwrap();
        let upper = Polyhedron::try_new(tetrahedron([a, b, c], a + n)).unwrap();
        let leaf = |p: &Polyhedron| CsgExpr::leaf(p.clone());
        let u = tree(leaf(&lower).union(leaf(&upper)));
        let i = tree(leaf(&lower).intersection(leaf(&upper)));
        let d = tree(leaf(&lower).difference(leaf(&upper)));
        // From below the lower apex, through a point inside the triangle
        // (not on an edge of either fan).
        let target = (a + b + 2.0 * c) / 4.0 + (b - a) * 0.01;
        let ray = Ray::new(
            a - 2.0 * n + (c - a) * 0.1,
            target - (a - 2.0 * n + (c - a) * 0.1),
        );
        let mut lower_ts = Vec::new();
        lower.intersect_ray(&ray, &mut lower_ts, &mut Stats::default());
        let mut upper_ts = Vec::new();
        upper.intersect_ray(&ray, &mut upper_ts, &mut Stats::default());
        if lower_ts.len() != 2 || upper_ts.len() != 2 {
            continue;
        }
        if lower_ts[1].t != upper_ts[0].t {
            rounded_apart += 1;
        }
        let spans = u.spans(&ray, &mut stats);
        assert_eq!(spans.hits.len(), 2, "{:?}", spans.hits);
        assert!(i.spans(&ray, &mut stats).hits.is_empty());
        assert_eq!(d.spans(&ray, &mut stats).hits.len(), 2);
    }
    // The case is real: the two meshes rounded the shared crossing apart,
    // and the exact comparison took them together.
    assert!(rounded_apart >= 5, "{rounded_apart}");
    assert!(stats.exact_orders > 0);
}

#[test]
fn a_transformed_mesh_sharing_a_tilted_plane_is_one_solid_for_rays_points_and_evaluation() {
    // The upper tetrahedron is given in its own frame and turned into the
    // world; the lower one is built in the world on the rounded images of
    // the upper one's base corners (how a transform moves a mesh's
    // vertices), so the two share that tilted triangle exactly.
    let mut bits = test_rng::bits(23);
    let mut unit = || (bits() % (1 << 30)) as f64 / f64::from(1u32 << 30);
    let (mut rounded_apart, mut stats) = (0, Stats::default());
    for case in 0..60 {
        let [a, b, c] = [0, 1, 2].map(|_| DVec3::new(unit(), unit(), unit()));
        let n = (b - a).cross(c - a);
        if n.length() < 1e-2 {
            continue;
        }
        let local = tetrahedron([a, b, c], a + n);
        let map = DAffine3::from_rotation_translation(
            DQuat::from_euler(EulerRot::XYZ, unit() * 3.0, unit() * 3.0, unit() * 3.0),
            DVec3::new(unit() - 0.5, unit() - 0.5, unit() - 0.5),
        );
        let [wa, wb, wc] = [a, b, c].map(|p| map.transform_point3(p));
        let wn = (wb - wa).cross(wc - wa);
        let lower = Polyhedron::try_new(tetrahedron([wa, wb, wc], wa - wn)).unwrap();
        let local_leaf = Polyhedron::try_new(local).unwrap();
        let upper = CsgExpr::leaf(local_leaf.clone()).transformed(map);
        let both = |join: fn(CsgExpr, CsgExpr) -> CsgExpr| {
            tree(join(CsgExpr::leaf(lower.clone()), upper.clone()))
        };
        let u = both(CsgExpr::union);
        let i = both(CsgExpr::intersection);
        let d = both(CsgExpr::difference);
        // A ray from below the lower apex through a point inside the shared
        // triangle.
        let target = (wa + wb + 2.0 * wc) / 4.0 + (wb - wa) * 0.01;
        let from = wa - 2.0 * wn + (wc - wa) * 0.1;
        let ray = Ray::new(from, target - from);
        let mut lower_ts = Vec::new();
        lower.intersect_ray(&ray, &mut lower_ts, &mut Stats::default());
        // What the upper mesh answers in its own frame, on the ray mapped
        // there (rounded).
        let inverse = map.inverse();
        let mapped_ray = Ray::new(
            inverse.transform_point3(ray.origin),
            inverse.transform_vector3(ray.direction),
        );
        let mut local_ts = Vec::new();
        local_leaf.intersect_ray(&mapped_ray, &mut local_ts, &mut Stats::default());
        assert_eq!((lower_ts.len(), local_ts.len()), (2, 2), "case {case}");
        if lower_ts[1].t != local_ts[0].t {
            rounded_apart += 1;
        }
        assert_eq!(u.spans(&ray, &mut stats).hits.len(), 2, "case {case}");
        assert!(i.spans(&ray, &mut stats).hits.is_empty(), "case {case}");
        assert_eq!(d.spans(&ray, &mut stats).hits.len(), 2, "case {case}");
        // Boundary evaluation makes the same solids: the intersection is
        // empty, and ray casting and the evaluated union agree on points
        // near the shared triangle (on it, too).
        let options = EvaluateOptions::default();
        assert_eq!(evaluate(&i, &options).unwrap().solid.face_count(), 0);
        let union = evaluate(&u, &options).unwrap();
        let accel = Accel::new(&union.solid);
        let centre = (wa + wb + wc) / 3.0;
        for k in 0..40 {
            let p = centre + (DVec3::new(unit(), unit(), unit()) - 0.5) * wn.length().sqrt() * 0.5;
            let p = if k % 4 == 0 {
                // A point of the shared triangle (in its plane up to
                // rounding).
                wa + (wb - wa) * 0.25 + (wc - wa) * 0.5
            } else {
                p
            };
            assert_eq!(
                u.classify_point(p, &mut stats),
                accel.classify(p).unwrap(),
                "case {case}, point {p}"
            );
            assert_eq!(
                i.classify_point(p, &mut stats),
                Containment::Outside,
                "case {case}, point {p}"
            );
        }
    }
    // The case is real: in the upper mesh's own frame the shared crossing
    // rounds apart from the lower mesh's.
    assert!(rounded_apart >= 5, "{rounded_apart}");
}
