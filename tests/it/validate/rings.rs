//! Checks of faces with rings: a valid face with a hole passes; breaking
//! one thing (a ring outside, crossing, touching, nested, wound the wrong
//! way) gives exactly that violation, located by the solid's ids.

use glam::DVec3;
use wingedge::mesh::{Corner, EdgeUse, FaceId, Side, Solid};
use wingedge::validate::{RingRule, check_rings};

fn square(centre: (f64, f64), r: f64) -> Vec<DVec3> {
    [(-r, -r), (r, -r), (r, r), (-r, r)]
        .map(|(x, y)| DVec3::new(centre.0 + x, centre.1 + y, 0.0))
        .to_vec()
}

/// A ring in `face` through the raw operators (a bridge `mev`, one `mev`
/// per further vertex, `mef`, `kemr`), with no check of where it lies.
/// Points wound like the face give a ring wound against it.
fn raw_ring(solid: &mut Solid, face: FaceId, points: &[DVec3]) {
    let start = solid.face_first_use(face).unwrap();
    let (bridge, _) = solid.mev(Corner::After(start), points[0]).unwrap();
    let up = EdgeUse {
        edge: bridge,
        side: Side::Left,
    };
    let mut corner = Corner::After(up);
    for &p in &points[1..] {
        let (edge, _) = solid.mev(corner, p).unwrap();
        corner = Corner::After(EdgeUse {
            edge,
            side: Side::Left,
        });
    }
    solid.mef(corner, Corner::After(up)).unwrap();
    solid.kemr(bridge).unwrap();
    solid.check_consistency().unwrap();
}

/// A 8 × 8 square lamina with the given rings in its front face; the rules
/// broken, in order, with the front face named by each.
fn rules_with_rings(rings: &[Vec<DVec3>]) -> Vec<RingRule> {
    let (mut solid, front, _) = Solid::try_lamina(&square((0.0, 0.0), 4.0)).unwrap();
    for ring in rings {
        raw_ring(&mut solid, front, ring);
    }
    assert_eq!(solid.face_ring_count(front), rings.len());
    let found = check_rings(&solid);
    for v in &found {
        assert_eq!(v.face, front, "{}", v.message);
        assert!(!v.loops.is_empty() && !v.vertices.is_empty());
        assert!(v.loops.iter().all(|&l| solid.loop_record(l).face == front));
    }
    found.iter().map(|v| v.rule).collect()
}

#[test]
fn a_valid_face_with_holes_passes() {
    assert_eq!(
        rules_with_rings(&[square((-2.0, 0.0), 1.0), square((2.0, 0.0), 1.0)]),
        []
    );
    let frame = wingedge::mesh::builders::frame();
    assert_eq!(check_rings(&frame), []);
}

#[test]
fn a_ring_outside_the_outer_loop() {
    assert_eq!(
        rules_with_rings(&[square((10.0, 0.0), 1.0)]),
        [RingRule::RingNotInsideOuterLoop]
    );
}

#[test]
fn a_ring_crossing_the_outer_loop() {
    assert_eq!(
        rules_with_rings(&[square((3.5, 0.0), 1.0)]),
        [RingRule::LoopsCrossOrTouch]
    );
}

#[test]
fn a_ring_touching_the_outer_loop_at_a_vertex() {
    let diamond = [(4.0, 0.0), (3.0, 1.0), (2.0, 0.0), (3.0, -1.0)]
        .map(|(x, y)| DVec3::new(x, y, 0.0))
        .to_vec();
    assert_eq!(rules_with_rings(&[diamond]), [RingRule::LoopsCrossOrTouch]);
}

#[test]
fn two_rings_crossing_each_other() {
    assert_eq!(
        rules_with_rings(&[square((-0.5, 0.0), 1.0), square((0.5, 0.0), 1.0)]),
        [RingRule::LoopsCrossOrTouch]
    );
}

#[test]
fn a_ring_inside_another_ring() {
    assert_eq!(
        rules_with_rings(&[square((0.0, 0.0), 2.0), square((0.0, 0.0), 0.5)]),
        [RingRule::RingNotInsideOuterLoop]
    );
}

#[test]
fn a_ring_wound_like_the_outer_loop() {
    let mut backwards = square((0.0, 0.0), 1.0);
    backwards.reverse();
    assert_eq!(
        rules_with_rings(&[square((-2.5, 0.0), 1.0), backwards]),
        [RingRule::LoopWoundWrongWay]
    );
}
