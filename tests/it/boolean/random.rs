//! Seeded random pairs of solids on a coarse grid (so faces coincide,
//! edges touch and corners meet far more often than by chance): every
//! boolean is a valid solid (touching itself at points or along edges
//! where the operands do) or, rarely, a refusal of a result that rounding
//! to `f64` would break, and the volumes add up.

use glam::{DAffine3, DVec3};
use wingedge::SetOp;
use wingedge::boolean::{BooleanError, BooleanOptions, boolean};
use wingedge::mesh::{Solid, builders};

use crate::common::{mapped_solid, test_rng};

fn random_solid(next: &mut impl FnMut() -> f64) -> Solid {
    let grid = |x: f64| (x * 4.0).floor() / 2.0;
    let kind = (next() * 4.0) as u32;
    let corner = DVec3::new(grid(next()), grid(next()), grid(next()));
    let size = DVec3::new(0.5 + grid(next()), 0.5 + grid(next()), 0.5 + grid(next()));
    match kind {
        0 | 1 => builders::cuboid(corner, corner + size).expect("a box"),
        2 => {
            let quarter = std::f64::consts::FRAC_PI_4 * (next() * 2.0).floor();
            mapped_solid(
                &builders::cube(),
                DAffine3::from_translation(corner)
                    * DAffine3::from_rotation_z(quarter)
                    * DAffine3::from_scale(size * 0.5),
            )
        }
        _ => mapped_solid(
            &builders::octahedron(),
            DAffine3::from_translation(corner) * DAffine3::from_scale(size),
        ),
    }
}

/// Cases per run (`WINGEDGE_BOOLEAN_CASES` to run more).
const CASES: usize = 120;

#[test]
fn random_pairs_on_a_grid_are_valid_and_add_up() {
    let mut uniform = test_rng::uniform(0xB001_EA2D_5EED_0001);
    let mut next = move || uniform();
    let (mut made, mut refused) = (0, 0);
    let cases = std::env::var("WINGEDGE_BOOLEAN_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(CASES);
    for case in 0..cases {
        let a = random_solid(&mut next);
        let b = random_solid(&mut next);
        let mut volumes = [None; 3];
        for (k, op) in [SetOp::Union, SetOp::Intersection, SetOp::Difference]
            .into_iter()
            .enumerate()
        {
            match boolean(&a, &b, op, BooleanOptions::default()) {
                Ok(r) => {
                    made += 1;
                    volumes[k] = Some(r.solid.volume());
                }
                // Only where rounding the exact result would break it
                // (faces of boxes turned by 45° a rounding apart).
                Err(BooleanError::InvalidResult { .. }) => refused += 1,
                Err(e) => panic!("case {case} {op:?}: {e}"),
            }
        }
        let (va, vb) = (a.volume(), b.volume());
        let scale = va.max(vb);
        if let (Some(u), Some(i)) = (volumes[0], volumes[1]) {
            assert!(
                (u + i - va - vb).abs() <= 1e-12 * scale,
                "case {case}: {u} + {i} vs {va} + {vb}"
            );
        }
        if let (Some(d), Some(i)) = (volumes[2], volumes[1]) {
            assert!(
                (d + i - va).abs() <= 1e-12 * scale,
                "case {case}: {d} + {i} vs {va}"
            );
        }
    }
    println!("{made} results, {refused} refused as broken by rounding");
    assert!(
        refused * 100 < made,
        "{refused} refusals of {}",
        made + refused
    );
}

/// Seeded random rotated and offset spheres, cubes and octahedra (general
/// position, slivers where surfaces graze): every boolean valid, volumes
/// adding up.
#[test]
fn random_rotated_pairs_are_valid_and_add_up() {
    let mut uniform = test_rng::uniform(0xB001_EA2D_5EED_0002);
    let mut next = move || uniform();
    let cases = std::env::var("WINGEDGE_BOOLEAN_CASES")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(CASES / 4);
    for case in 0..cases {
        let mut solids = Vec::new();
        for _ in 0..2 {
            let base = match (next() * 3.0) as u32 {
                0 => builders::sphere(6 + (next() * 10.0) as usize),
                1 => builders::cube(),
                _ => builders::octahedron(),
            };
            let axis = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize_or(DVec3::Z);
            let map = DAffine3::from_translation(DVec3::new(next(), next(), next()) * 0.8)
                * DAffine3::from_axis_angle(axis, next() * 6.0);
            solids.push(mapped_solid(&base, map));
        }
        let (a, b) = (&solids[0], &solids[1]);
        let volume = |op| {
            boolean(a, b, op, BooleanOptions::default())
                .unwrap_or_else(|e| panic!("case {case} {op:?}: {e}"))
                .solid
                .volume()
        };
        let (u, i, d) = (
            volume(SetOp::Union),
            volume(SetOp::Intersection),
            volume(SetOp::Difference),
        );
        let (va, vb) = (a.volume(), b.volume());
        assert!((u + i - va - vb).abs() <= 1e-12 * va.max(vb), "case {case}");
        assert!((d + i - va).abs() <= 1e-12 * va.max(vb), "case {case}");
    }
}
