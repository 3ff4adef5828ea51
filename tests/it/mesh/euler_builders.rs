//! Solids made by Euler operators: prisms with through holes, the Platonic
//! solids built edge by edge equal to the same polygons built as a soup,
//! and the editing operations (extrude, cone, split a face).

use std::collections::BTreeSet;

use glam::DVec3;
use wingedge::mesh::{BuildError, EulerError, FaceId, PolygonSoup, Solid, builders};
use wingedge::validate::{Options, validate_soup};

fn square(centre: (f64, f64), r: f64) -> Vec<DVec3> {
    [(-r, -r), (r, -r), (r, r), (-r, r)]
        .map(|(x, y)| DVec3::new(centre.0 + x, centre.1 + y, 0.0))
        .to_vec()
}

/// Every face as the cycle of its vertex positions, rotated to start at the
/// smallest (faces with rings as outer cycle plus the ring cycles).
fn face_cycles(solid: &Solid) -> BTreeSet<Vec<Vec<[u64; 3]>>> {
    let cycle = |points: Vec<DVec3>| {
        let mut keys: Vec<[u64; 3]> = points
            .iter()
            .map(|p| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()])
            .collect();
        let first = (0..keys.len()).min_by_key(|&i| keys[i]).unwrap();
        keys.rotate_left(first);
        keys
    };
    solid
        .faces()
        .map(|(f, _)| {
            let mut loops: Vec<Vec<[u64; 3]>> = solid
                .face_loops(f)
                .map(|l| cycle(solid.loop_vertices(l).map(|v| solid.position(v)).collect()))
                .collect();
            loops[1..].sort();
            loops
        })
        .collect()
}

/// Consistent, closed, every shell enclosing a positive volume; without
/// rings, also valid for the validator as a polygon soup.
fn assert_valid(solid: &Solid) {
    solid.check_consistency().unwrap();
    assert!(solid.is_closed());
    assert!(solid.shells().iter().all(|s| s.signed_volume > 0.0));
    if solid.ring_count() == 0 {
        let index: std::collections::HashMap<_, usize> = solid
            .vertices()
            .enumerate()
            .map(|(i, (id, _))| (id, i))
            .collect();
        let positions: Vec<DVec3> = solid.vertices().map(|(_, v)| v.position).collect();
        let polygons: Vec<Vec<usize>> = solid
            .faces()
            .map(|(f, _)| solid.face_vertices(f).map(|v| index[&v]).collect())
            .collect();
        let report = validate_soup(
            &PolygonSoup::new(positions, polygons),
            None,
            &Options::default(),
        )
        .unwrap();
        assert!(report.is_valid(), "{:?}", report.violations);
    }
}

#[test]
fn a_prism_with_holes_has_one_handle_per_hole() {
    let outer = square((0.0, 0.0), 4.0);
    let holes = [square((-2.0, -2.0), 1.0), square((2.0, 1.0), 1.0), {
        // Wound the other way: the builder orients every loop itself.
        let mut h = square((-1.5, 2.0), 0.5);
        h.reverse();
        h
    }];
    let hole_refs: Vec<&[DVec3]> = holes.iter().map(Vec::as_slice).collect();
    let solid = builders::prism_with_holes(&outer, &hole_refs, DVec3::new(0.0, 0.0, 2.0)).unwrap();
    solid.check_consistency().unwrap();
    assert_eq!(
        solid.ring_count(),
        6,
        "each hole is a ring of the top and of the bottom"
    );
    let shells = solid.shells();
    assert_eq!(shells.len(), 1);
    assert_eq!(shells[0].genus(), Some(3));
    assert_eq!(solid.euler_characteristic(), 2 * (1 - 3));
    // (64 − 4 − 4 − 1) × 2.
    assert_eq!(solid.volume(), 110.0);
    assert_eq!(solid.vertex_count(), 2 * 16);
    assert_eq!(solid.face_count(), 2 + 16);
}

#[test]
fn holes_that_leave_the_profile_or_touch_are_refused() {
    let outer = square((0.0, 0.0), 2.0);
    let outside = square((3.0, 0.0), 1.5);
    let touching = [square((-1.0, 0.0), 0.5), square((0.0, 0.0), 0.5)];
    assert!(matches!(
        builders::prism_with_holes(&outer, &[&outside], DVec3::Z),
        Err(BuildError::InvalidProfile(_))
    ));
    assert!(matches!(
        builders::prism_with_holes(&outer, &[&touching[0], &touching[1]], DVec3::Z),
        Err(BuildError::InvalidProfile(_))
    ));
}

/// The Platonic solids are built by Euler operators; built from the same
/// polygons as a soup they have exactly the same faces, planes and
/// attributes.
#[test]
fn platonic_solids_by_euler_operators_equal_their_soups() {
    for name in [
        "tetrahedron",
        "cube",
        "octahedron",
        "dodecahedron",
        "icosahedron",
    ] {
        let solid = builders::by_name(name).unwrap();
        assert_valid(&solid);
        let positions: Vec<DVec3> = solid.vertices().map(|(_, v)| v.position).collect();
        let index: std::collections::HashMap<_, usize> = solid
            .vertices()
            .enumerate()
            .map(|(i, (id, _))| (id, i))
            .collect();
        let polygons: Vec<Vec<usize>> = solid
            .faces()
            .map(|(f, _)| solid.face_vertices(f).map(|v| index[&v]).collect())
            .collect();
        let soup = Solid::try_from_soup(&PolygonSoup::new(positions, polygons)).unwrap();
        assert_eq!(face_cycles(&solid), face_cycles(&soup), "{name}");
        assert_eq!(solid.volume(), soup.volume(), "{name}");
        for (_, face) in solid.faces() {
            assert!(face.plane.is_some(), "{name}");
            // The cube is a prism (an extruded lamina), the others are
            // built from their polygons.
            assert_eq!(face.attributes.source_index.is_some(), name != "cube");
        }
    }
}

#[test]
fn extrude_cone_and_split_edit_a_cube() {
    let mut solid = builders::cube();
    let top: FaceId = solid
        .faces()
        .find(|(_, f)| f.plane.unwrap().normal.z > 0.5)
        .unwrap()
        .0;
    solid.extrude_face(top, DVec3::new(0.0, 0.0, 1.0)).unwrap();
    assert_valid(&solid);
    assert_eq!(
        (solid.vertex_count(), solid.edge_count(), solid.face_count()),
        (12, 20, 10)
    );
    assert_eq!(solid.volume(), 12.0);
    // Split the (moved) top along a diagonal, then cone one half.
    let corners: Vec<_> = solid.face_vertices(top).collect();
    let (_, half) = solid.split_face(top, corners[0], corners[2]).unwrap();
    assert_valid(&solid);
    assert_eq!(solid.face_count(), 11);
    let apex = DVec3::new(0.0, 0.0, 5.0);
    solid.cone_face(half, apex).unwrap();
    assert_valid(&solid);
    assert_eq!(solid.face_count(), 13);
    // A diagonal across an edge that is already there, and one outside the
    // face, are refused.
    let side = solid
        .faces()
        .find(|(_, f)| f.plane.unwrap().normal.x > 0.5)
        .unwrap()
        .0;
    let v: Vec<_> = solid.face_vertices(side).collect();
    assert!(matches!(
        solid.split_face(side, v[0], v[1]),
        Err(EulerError::AlreadyJoined { .. })
    ));
}

#[test]
fn a_split_outside_a_non_convex_face_is_refused() {
    let l = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
        .map(|(x, y)| DVec3::new(x, y, 0.));
    let (mut solid, front, _) = Solid::try_lamina(&l).unwrap();
    let v: Vec<_> = solid.face_vertices(front).collect();
    let at = |p: (f64, f64)| {
        *v.iter()
            .find(|&&w| solid.position(w) == DVec3::new(p.0, p.1, 0.0))
            .unwrap()
    };
    // (2, 1) to (1, 2) runs outside the L's reflex corner; (0, 0) to
    // (1, 1) inside.
    let (a, b) = (at((2., 1.)), at((1., 2.)));
    let (c, d) = (at((0., 0.)), at((1., 1.)));
    assert_eq!(
        solid.split_face(front, a, b),
        Err(EulerError::SplitOutsideFace {
            face: front,
            v1: a,
            v2: b
        })
    );
    solid.split_face(front, c, d).unwrap();
    solid.check_consistency().unwrap();
}

#[test]
fn split_face_moves_rings_to_the_part_that_holds_them() {
    let holes = [square((-2.0, -2.0), 0.5), square((2.0, 2.0), 0.5)];
    let mut solid =
        builders::prism_with_holes(&square((0.0, 0.0), 4.0), &[&holes[0], &holes[1]], DVec3::Z)
            .unwrap();
    let top = solid
        .faces()
        .find(|(_, f)| f.plane.unwrap().normal.z > 0.5)
        .unwrap()
        .0;
    assert_eq!(solid.face_ring_count(top), 2);
    let corner = |x: f64, y: f64| {
        solid
            .face_outer_vertices(top)
            .find(|&v| solid.position(v) == DVec3::new(x, y, 1.0))
            .unwrap()
    };
    let (a, b) = (corner(4.0, -4.0), corner(-4.0, 4.0));
    // The other diagonal runs through both rings.
    let (c, d) = (corner(-4.0, -4.0), corner(4.0, 4.0));
    assert_eq!(
        solid.split_face(top, c, d),
        Err(EulerError::SplitOutsideFace {
            face: top,
            v1: c,
            v2: d
        })
    );
    let (_, new) = solid.split_face(top, a, b).unwrap();
    solid.check_consistency().unwrap();
    assert_eq!(
        (solid.face_ring_count(top), solid.face_ring_count(new)),
        (1, 1)
    );
    // One half, with its ring, raised: a step with two holes through.
    solid.extrude_face(new, DVec3::Z).unwrap();
    solid.check_consistency().unwrap();
    assert!(solid.is_closed());
    assert_eq!(solid.shells()[0].genus(), Some(2));
    assert_eq!(solid.volume(), (64.0 - 2.0) + (32.0 - 1.0));
}

/// Queries see the holes: the accel triangulates faces with rings exactly,
/// and parity, winding number and ray casting agree on a frame.
#[test]
fn queries_on_a_solid_with_faces_with_holes() {
    use wingedge::geom::Ray;
    use wingedge::query::{Accel, Containment, Method};
    let frame = builders::frame();
    let accel = Accel::new(&frame);
    let cases = [
        (DVec3::new(0.0, 0.0, 0.5), Containment::Outside),
        (DVec3::new(1.5, 0.0, 0.5), Containment::Inside),
        (DVec3::new(-1.5, 1.7, 0.25), Containment::Inside),
        (DVec3::new(3.0, 0.0, 0.5), Containment::Outside),
        (DVec3::new(1.5, 0.0, 1.0), Containment::OnBoundary),
        (DVec3::new(0.5, 0.5, 1.0), Containment::Outside),
        (DVec3::new(1.0, 0.0, 0.5), Containment::OnBoundary),
    ];
    for (p, want) in cases {
        assert_eq!(accel.classify_with(p, Method::Parity).unwrap(), want, "{p}");
        if want != Containment::OnBoundary {
            let w = accel.winding_number(p).unwrap();
            assert_eq!(w > 0.5, want == Containment::Inside, "{p}: winding {w}");
        }
    }
    // A ray down through the hole hits nothing; one through the material
    // enters the top face at z = 1.
    let down = DVec3::new(0.0, 0.0, -1.0);
    let hole = Ray::new(DVec3::new(0.25, -0.5, 3.0), down);
    assert!(accel.first_hit(&hole).unwrap().is_none());
    let wall = Ray::new(DVec3::new(1.25, -0.5, 3.0), down);
    let hit = accel.first_hit(&wall).unwrap().unwrap();
    assert_eq!(hit.t, 2.0);
    // The line–face test on the top face: through the hole is a miss, on
    // the ring's edge is on an edge, through the material is inside.
    use wingedge::query::{LineFaceHit, LineKind, intersect_line_face};
    let top = frame
        .faces()
        .find(|(_, f)| f.plane.unwrap().normal.z > 0.5)
        .unwrap()
        .0;
    let line = |x: f64, y: f64| {
        intersect_line_face(
            &frame,
            top,
            DVec3::new(x, y, 3.0),
            DVec3::new(x, y, -3.0),
            LineKind::Line,
        )
        .unwrap()
    };
    assert_eq!(line(0.25, -0.5), LineFaceHit::Miss);
    assert!(matches!(line(1.5, 0.0), LineFaceHit::Inside { .. }));
    assert!(matches!(line(1.0, 0.5), LineFaceHit::OnEdge { .. }));
    assert!(matches!(line(1.0, 1.0), LineFaceHit::OnVertex { .. }));
    assert_eq!(line(2.5, 0.0), LineFaceHit::Miss);
}

/// Measures count rings: the frame's top and bottom have a hole each.
#[test]
fn measures_of_a_solid_with_faces_with_holes() {
    let frame = builders::frame();
    // Top and bottom 16 − 4 each, outer sides 4 × 4, inner sides 4 × 2.
    assert_eq!(frame.surface_area(), 12.0 + 12.0 + 16.0 + 8.0);
    assert_eq!(frame.volume(), 12.0);
    assert_eq!(frame.centroid(), Some(DVec3::new(0.0, 0.0, 0.5)));
    assert_eq!(
        (
            frame.vertex_count(),
            frame.edge_count(),
            frame.face_count(),
            frame.ring_count()
        ),
        (16, 24, 10, 2)
    );
    assert_eq!(frame.euler_characteristic(), 0);
    let shell = &frame.shells()[0];
    assert_eq!(
        (shell.ring_count, shell.euler_characteristic, shell.genus()),
        (2, 0, Some(1))
    );
    let top = frame
        .faces()
        .find(|(_, f)| f.plane.unwrap().normal.z > 0.5)
        .unwrap()
        .0;
    assert_eq!(frame.face_area(top), 12.0);
    assert_eq!(frame.face_ring_count(top), 1);
    assert_eq!(frame.face_loops(top).count(), 2);
    assert_eq!(frame.face_vertices(top).count(), 8);
    assert_eq!(frame.face_outer_vertices(top).count(), 4);
}
