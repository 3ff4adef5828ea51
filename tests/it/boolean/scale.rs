//! Booleans far from the origin and at extreme sizes: what is written is
//! what was proven (the OBJ text the result writes reads back valid), the
//! exact answer is written where it is representable, and anything the
//! validator accepts the builders and booleans accept.

use glam::DVec3;
use wingedge::io::{ObjOptions, import_obj_bytes, to_obj_string};
use wingedge::mesh::{Solid, builders};
use wingedge::validate::{Options, Validity, validate_import};

fn cuboid(min: DVec3, max: DVec3) -> Solid {
    builders::cuboid(min, max).expect("a cuboid")
}

/// The validity of the solid's OBJ text, read back as `wingedge validate`
/// reads a file.
fn written_validity(solid: &Solid) -> Validity {
    let text = to_obj_string(solid);
    let import = import_obj_bytes(
        std::path::Path::new("result.obj"),
        text.as_bytes(),
        &ObjOptions::default(),
    )
    .expect("the written file reads back");
    validate_import(&import, &Options::default())
        .expect("validates")
        .validity
}

/// A unit cube at 1e12 minus a bar 0.01 wide through it: every corner of
/// the exact result is representable, so it is written exactly — the
/// written file is valid and the volume is the exact one (the snap
/// rounding this replaced moved corners by ~27 ulps off their faces).
#[test]
fn a_cube_at_1e12_minus_a_thin_bar_is_written_exactly() {
    for offset in [1e8, 1e12, 1e15] {
        let o = DVec3::splat(offset);
        let cube = cuboid(o, o + DVec3::ONE);
        let lo = o + DVec3::new(0.25, 0.5, -1.0);
        // As thin as the offset lets a bar be (0.125 is an ulp at 1e15).
        let width = if offset >= 1e15 { 0.125 } else { 0.015625 };
        let hi = lo + DVec3::new(0.25, width, 3.0);
        let bar = cuboid(lo, hi);
        let result = cube.difference(&bar).expect("a valid result");
        assert_eq!(
            written_validity(&result.solid),
            Validity::ValidSolid,
            "offset {offset}"
        );
        // The bar's cross-section (as its corners were rounded at this
        // offset) times the cube's height is removed, exactly.
        let removed = (hi.x - lo.x) * (hi.y - lo.y);
        let volume = result.solid.volume();
        assert!(
            (volume - (1.0 - removed)).abs() <= 1e-12,
            "offset {offset}: volume {volume}, exactly {}",
            1.0 - removed
        );
    }
}

/// Drilled cubes at 1e8 (a cube minus a bar through it, both with exact
/// coordinates) were refused: the merged face's ring was judged outside
/// its outer loop by an area summed on absolute coordinates.
#[test]
fn drilled_cubes_at_1e8_are_not_refused() {
    let mut next = 0x9E37_79B9_7F4A_7C15u64;
    let mut unit = move || {
        next ^= next << 13;
        next ^= next >> 7;
        next ^= next << 17;
        (next >> 11) as f64 / (1u64 << 53) as f64
    };
    for case in 0..20 {
        let o = DVec3::new(1e8, -3e8, 7e7);
        let size = 1.0 + (unit() * 8.0).floor();
        let cube = cuboid(o, o + DVec3::splat(size));
        let a = (unit() * size * 4.0).floor() / 4.0 * 0.5 + 0.125;
        let b = (unit() * size * 4.0).floor() / 4.0 * 0.5 + 0.125;
        let hole_lo = o + DVec3::new(a, b, -1.0);
        let hole = cuboid(hole_lo, hole_lo + DVec3::new(0.25, 0.25, size + 2.0));
        let drilled = cube
            .difference(&hole)
            .unwrap_or_else(|e| panic!("case {case}: {e}"));
        assert_eq!(drilled.solid.shells()[0].genus(), Some(1), "case {case}");
        assert_eq!(
            written_validity(&drilled.solid),
            Validity::ValidSolid,
            "case {case}"
        );
    }
}

/// Boxes of side 1e-100 to 1e100 build, and their booleans work: the
/// validator accepts such cubes, so the builders and booleans do too
/// (side ≤ 1e-90 was refused as "zero area": the squared length of the
/// face's vector area underflowed).
#[test]
fn boxes_from_1e_minus_100_to_1e100_build_and_combine() {
    for exponent in [-100, -90, -30, 0, 30, 90, 100] {
        let s = 10f64.powi(exponent);
        let a = cuboid(DVec3::ZERO, DVec3::splat(s));
        let b = cuboid(DVec3::splat(s * 0.5), DVec3::splat(s * 1.5));
        assert_eq!(written_validity(&a), Validity::ValidSolid, "side {s:e}");
        let union = a.union(&b).unwrap_or_else(|e| panic!("side {s:e}: {e}"));
        assert_eq!(union.solid.face_count(), 12, "side {s:e}");
        assert_eq!(
            written_validity(&union.solid),
            Validity::ValidSolid,
            "side {s:e}"
        );
    }
}

/// Two spheres at 1e12 (triangulated, offset from each other): every
/// written face is planar within the validator's tolerance, as the proof
/// checks the polygons that are written.
#[test]
fn spheres_at_1e12_are_written_valid() {
    let far = |shift: DVec3| {
        let mut s = builders::sphere(8);
        let moved = s.move_by(glam::DAffine3::from_translation(DVec3::splat(1e12) + shift));
        assert!(moved);
        s
    };
    let a = far(DVec3::ZERO);
    let b = far(DVec3::new(0.375, 0.25, 0.125));
    for result in [a.difference(&b), a.union(&b), a.intersection(&b)] {
        let result = result.expect("a valid result");
        assert_eq!(written_validity(&result.solid), Validity::ValidSolid);
    }
}

/// `A − A`, and the intersection of two cubes that share a face, are the
/// empty solid: written as such, and read back as the empty solid.
#[test]
fn empty_results_are_written_and_read_as_empty() {
    let a = cuboid(DVec3::ZERO, DVec3::ONE);
    let b = cuboid(DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 1.0, 1.0));
    for result in [a.difference(&a), a.intersection(&b)] {
        let result = result.expect("a result");
        assert_eq!(result.solid.face_count(), 0);
        assert_eq!(result.report.validity, Validity::Empty);
        assert_eq!(written_validity(&result.solid), Validity::Empty);
        assert_eq!(result.solid.volume() + 0.0, 0.0);
    }
}
