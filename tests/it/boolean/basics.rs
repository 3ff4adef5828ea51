//! Exact booleans: volumes against closed forms, validity of every result,
//! the touching and coplanar cases.

use glam::DVec3;
use wingedge::boolean::{Boolean, BooleanError};
use wingedge::mesh::{Solid, builders};
use wingedge::validate::Validity;

fn cuboid(min: [f64; 3], max: [f64; 3]) -> Solid {
    builders::cuboid(DVec3::from(min), DVec3::from(max)).expect("a cuboid")
}

fn check(result: &Boolean, volume: f64) {
    assert_eq!(result.report.validity, Validity::ValidSolid);
    let v = result.solid.volume();
    assert!(
        (v - volume).abs() <= 1e-12 * volume.abs().max(1.0),
        "volume {v}, expected {volume}"
    );
}

#[test]
fn overlapping_cubes() {
    let a = cuboid([0.0; 3], [2.0; 3]);
    let b = cuboid([1.0, 1.0, 1.0], [3.0, 3.0, 3.0]);
    check(&a.union(&b).unwrap(), 15.0);
    check(&a.intersection(&b).unwrap(), 1.0);
    check(&a.difference(&b).unwrap(), 7.0);
    check(&b.difference(&a).unwrap(), 7.0);
}

#[test]
fn tilted_cubes() {
    let a = cuboid([0.0; 3], [2.0; 3]);
    let b = cuboid([0.5, 0.5, 0.5], [1.5, 1.5, 3.0]);
    check(&a.union(&b).unwrap(), 9.0);
    check(&a.intersection(&b).unwrap(), 1.5);
    let drilled = a
        .difference(&cuboid([0.5, 0.5, -1.0], [1.5, 1.5, 3.0]))
        .unwrap();
    check(&drilled, 6.0);
    assert_eq!(drilled.report.genus, Some(1));
}

#[test]
fn spheres() {
    let a = builders::sphere(12);
    let mut b = builders::sphere(12);
    let _ = &mut b;
    let moved = shifted(&a, DVec3::new(0.3, 0.2, 0.1));
    let u = a.union(&moved).unwrap();
    let i = a.intersection(&moved).unwrap();
    let d = a.difference(&moved).unwrap();
    let (va, vb) = (a.volume(), moved.volume());
    assert_eq!(u.report.validity, Validity::ValidSolid);
    assert_eq!(i.report.validity, Validity::ValidSolid);
    assert_eq!(d.report.validity, Validity::ValidSolid);
    let (vu, vi, vd) = (u.solid.volume(), i.solid.volume(), d.solid.volume());
    assert!(
        (vu + vi - va - vb).abs() < 1e-9,
        "{vu} + {vi} vs {va} + {vb}"
    );
    assert!((vd + vi - va).abs() < 1e-9, "{vd} + {vi} vs {va}");
}

fn shifted(s: &Solid, by: DVec3) -> Solid {
    let mut soup = s.to_soup();
    for p in &mut soup.positions {
        *p += by;
    }
    Solid::try_from_soup(&soup).unwrap()
}

#[test]
fn touching_and_coplanar() {
    let a = cuboid([0.0; 3], [1.0; 3]);
    let b = cuboid([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    let u = a.union(&b).unwrap();
    check(&u, 2.0);
    assert_eq!(u.report.genus, Some(0));
    let i = a.intersection(&b).unwrap();
    assert_eq!(i.solid.face_count(), 0);
    check(&a.difference(&b).unwrap(), 1.0);
    // A cube minus itself is empty; with itself, itself.
    assert_eq!(a.difference(&a).unwrap().solid.face_count(), 0);
    check(&a.union(&a).unwrap(), 1.0);
    check(&a.intersection(&a).unwrap(), 1.0);
    // A box with a coplanar top.
    let c = cuboid([0.25, 0.25, 0.5], [0.75, 0.75, 1.0]);
    check(&a.difference(&c).unwrap(), 1.0 - 0.125);
    check(&a.union(&c).unwrap(), 1.0);
}

#[test]
fn an_open_operand_is_refused() {
    let a = cuboid([0.0; 3], [1.0; 3]);
    let mut soup = a.to_soup();
    soup.polygons.pop();
    let open = Solid::try_from_soup(&soup).unwrap();
    let err = a.union(&open).unwrap_err();
    assert!(matches!(err, BooleanError::InvalidOperand { .. }), "{err}");
}

#[test]
fn faces_are_merged_back_into_polygons() {
    let a = cuboid([0.0; 3], [3.0; 3]);
    // A box minus a box inside it: two shells of six faces.
    let hollow = a.difference(&cuboid([1.0; 3], [2.0; 3])).unwrap();
    check(&hollow, 26.0);
    assert_eq!(hollow.solid.face_count(), 12);
    assert_eq!(hollow.report.shells, 2);
    // Drilled through: the top and bottom faces each get a ring.
    let drilled = a
        .difference(&cuboid([1.0, 1.0, -1.0], [2.0, 2.0, 4.0]))
        .unwrap();
    check(&drilled, 24.0);
    assert_eq!(drilled.solid.face_count(), 10);
    assert_eq!(drilled.solid.ring_count(), 2);
    // Two cubes sharing a face unite into one box.
    let b = cuboid([3.0, 0.0, 0.0], [6.0, 3.0, 3.0]);
    let joined = a.union(&b).unwrap();
    assert_eq!(joined.solid.face_count(), 6);
    assert_eq!(joined.solid.vertex_count(), 8);
    // Every face says where it came from.
    for (_, face) in joined.solid.faces() {
        let i = face.attributes.source_index.expect("an origin");
        assert!(i < joined.origins.len());
    }
}

#[test]
fn a_boolean_beyond_its_limit_says_so() {
    let a = builders::sphere(12);
    let b = cuboid([0.0; 3], [2.0; 3]);
    let options = wingedge::boolean::BooleanOptions {
        max_contacts: 10,
        ..Default::default()
    };
    let err = wingedge::boolean::boolean(&a, &b, wingedge::SetOp::Union, options).unwrap_err();
    assert!(
        matches!(err, BooleanError::TooLarge { limit: 10, .. }),
        "{err}"
    );
}
