//! Random soups of boxes on a coarse grid — overlapping, sharing faces and
//! edges, with faces turned over, repeated or removed — repair into valid
//! solids that classify every point off the surface exactly as the
//! intended soup's winding number does: inside ⇔ w > ½, here ⇔ inside
//! some box.

use glam::DVec3;
use wingedge::io::to_obj_string;
use wingedge::mesh::PolygonSoup;
use wingedge::query::{Accel, Containment};
use wingedge::repair::{OpenReason, RepairOptions, repair};
use wingedge::validate::{Options, validate_soup};

use crate::common::test_rng;

/// Cases per run (`WINGEDGE_REPAIR_CASES` to run more).
const CASES: usize = 60;

/// The six quads of the box `[lo, hi]`, wound outward, at the end of
/// `soup`.
fn push_box(soup: &mut PolygonSoup, lo: DVec3, hi: DVec3) {
    let base = soup.positions.len();
    for i in 0..8 {
        soup.positions.push(DVec3::new(
            if i & 1 == 0 { lo.x } else { hi.x },
            if i & 2 == 0 { lo.y } else { hi.y },
            if i & 4 == 0 { lo.z } else { hi.z },
        ));
    }
    for quad in [
        [0, 2, 3, 1],
        [4, 5, 7, 6],
        [0, 1, 5, 4],
        [2, 6, 7, 3],
        [0, 4, 6, 2],
        [1, 3, 7, 5],
    ] {
        soup.polygons
            .push(wingedge::mesh::Polygon::new(quad.map(|k| base + k)));
    }
}

#[test]
fn repaired_random_box_soups_classify_points_as_the_winding_number_does() {
    let mut next = test_rng::uniform(0x0EFA_12ED_5EED_0037);
    let cases = std::env::var("WINGEDGE_REPAIR_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(CASES);
    let mut left_open = 0;
    for case in 0..cases {
        let grid = |x: f64| (x * 4.0).floor();
        let count = 1 + (next() * 3.0) as usize;
        let mut boxes = Vec::new();
        let mut soup = PolygonSoup::default();
        for _ in 0..count {
            let lo = DVec3::new(grid(next()), grid(next()), grid(next()));
            let size = DVec3::new(1.0 + grid(next()), 1.0 + grid(next()), 1.0 + grid(next()));
            boxes.push((lo, lo + size));
            push_box(&mut soup, lo, lo + size);
        }
        // Break it: turn a face over, repeat a face, remove a face (its
        // hole to be filled).
        let faces = soup.polygons.len();
        let pick = |u: f64| ((u * faces as f64) as usize).min(faces - 1);
        let breaks = (next() * 4.0) as usize;
        let (a, b, c) = (pick(next()), pick(next()), pick(next()));
        if breaks & 1 == 1 {
            soup.polygons[a].vertices.reverse();
        }
        if breaks & 2 == 2 {
            let copy = soup.polygons[b].clone();
            soup.polygons.push(copy);
        }
        if next() < 0.5 {
            soup.polygons.remove(c);
        }
        // Every case's soup, to reproduce a failure by hand.
        if let Ok(dir) = std::env::var("WINGEDGE_REPAIR_DUMP") {
            let _ = wingedge::io::export_soup(
                &soup,
                &std::path::Path::new(&dir).join(format!("case{case}.obj")),
                wingedge::io::Format::Obj,
            );
        }
        let r =
            repair(&soup, &RepairOptions::default()).unwrap_or_else(|e| panic!("case {case}: {e}"));
        let Some(solid) = r.solid else {
            // A hole whose loop crosses itself in every projection (two
            // removed or turned faces on one edge chain) stays open.
            assert!(
                r.report
                    .left_open
                    .iter()
                    .all(|(_, why)| *why == OpenReason::NotTriangulable),
                "case {case}"
            );
            left_open += 1;
            continue;
        };
        assert!(
            r.validation.as_ref().is_some_and(|v| v.is_valid()),
            "case {case}"
        );
        // Written and read back, still valid.
        if solid.face_count() > 0 {
            let text = to_obj_string(&solid);
            let back = wingedge::io::import_obj_bytes(
                std::path::Path::new("case.obj"),
                text.as_bytes(),
                &wingedge::io::ObjOptions::default(),
            )
            .unwrap();
            let report = validate_soup(&back.soup, None, &Options::default()).unwrap();
            assert!(report.is_valid(), "case {case}: {:?}", report.violations);
        }
        let accel = Accel::new(&solid);
        // Half-integer points are never on a face of a box on the integer grid.
        for _ in 0..200 {
            let p = DVec3::new(
                (next() * 10.0).floor() * 0.5 - 0.25 + 0.0,
                (next() * 10.0).floor() * 0.5 - 0.25,
                (next() * 10.0).floor() * 0.5 - 0.25,
            );
            let expected = boxes
                .iter()
                .any(|(lo, hi)| p.cmpgt(*lo).all() && p.cmplt(*hi).all());
            let got = if solid.face_count() == 0 {
                Containment::Outside
            } else {
                accel.classify(p).unwrap()
            };
            assert_eq!(
                got == Containment::Inside,
                expected,
                "case {case}: {p} ({got:?}), boxes {boxes:?}"
            );
        }
    }
    assert!(left_open * 20 <= cases, "{left_open} of {cases} left open");
}

/// Regression (case 1697 of the random test): two boxes on one floor share
/// their face `x = 3`, one of the two copies turned over. The copies
/// cancel in cleaning, leaving the two open boxes sharing the square's
/// edges, each with two uses that run it the same way; the boxes' bottoms
/// are folded onto each other across those edges. Joined there, one box
/// was turned inside out to match the other and the result was their
/// difference; kept apart, filling closes each box and the result is their
/// union.
#[test]
fn boxes_whose_shared_face_cancelled_are_not_joined_across_a_fold() {
    let mut soup = PolygonSoup::default();
    let boxes = [
        (DVec3::new(3.0, 3.0, 2.0), DVec3::new(5.0, 4.0, 3.0)),
        (DVec3::new(3.0, 3.0, 2.0), DVec3::new(6.0, 4.0, 3.0)),
        (DVec3::new(2.0, 3.0, 3.0), DVec3::new(4.0, 4.0, 6.0)),
    ];
    for (lo, hi) in boxes {
        push_box(&mut soup, lo, hi);
    }
    // The second box's face x = 3, turned over.
    soup.polygons[10].vertices.reverse();
    let r = repair(&soup, &RepairOptions::default()).unwrap();
    let solid = r.solid.unwrap();
    assert!(r.validation.is_some_and(|v| v.is_valid()));
    // The union: 3 (the longer box holds the shorter) + 6, less nothing
    // shared in volume.
    assert!((solid.volume() - 9.0).abs() < 1e-12, "{}", solid.volume());
    let accel = Accel::new(&solid);
    assert_eq!(
        accel.classify(DVec3::new(4.25, 3.75, 2.75)).unwrap(),
        Containment::Inside
    );
}
