//! The hard cases of booleans: touching solids, coincident and nearly
//! coincident input, extreme offsets and scales, a Menger sponge.

use glam::{DAffine3, DVec3};
use wingedge::boolean::{Boolean, BooleanError};
use wingedge::csg::{AxisBox, Csg, CsgExpr, EvaluateOptions, evaluate};
use wingedge::mesh::{Solid, builders};

use crate::common::mapped_solid;
use wingedge::validate::Validity;

fn cuboid(min: [f64; 3], max: [f64; 3]) -> Solid {
    builders::cuboid(DVec3::from(min), DVec3::from(max)).expect("a cuboid")
}

fn valid(result: &Boolean) -> f64 {
    assert_eq!(result.report.validity, Validity::ValidSolid);
    result.solid.volume()
}

#[test]
fn cubes_sharing_an_edge_or_a_vertex() {
    let a = cuboid([0.0; 3], [1.0; 3]);
    for b in [
        cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]),
        cuboid([1.0, 1.0, 1.0], [2.0, 2.0, 2.0]),
    ] {
        // Nothing in common: empty; a minus it: a, untouched.
        let i = a.intersection(&b).unwrap();
        assert_eq!(i.solid.face_count(), 0);
        let d = a.difference(&b).unwrap();
        assert_eq!(valid(&d), 1.0);
        assert_eq!(d.solid.face_count(), 6);
    }
    // The union touching itself at a vertex: two shells, each with its own
    // vertex at the shared corner.
    let corner = a.union(&cuboid([1.0; 3], [2.0; 3])).unwrap();
    assert_eq!(valid(&corner), 2.0);
    assert_eq!(corner.report.shells, 2);
    assert_eq!(corner.solid.vertex_count(), 16);
    // Touching along the edge: two shells, each with its own edge (and
    // vertices) along the shared one.
    let edge = a.union(&cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0])).unwrap();
    assert_eq!(valid(&edge), 2.0);
    assert_eq!(edge.report.shells, 2);
    assert_eq!(edge.solid.vertex_count(), 16);
    assert_eq!(edge.solid.edge_count(), 24);
}

/// The whole validator (every pair of faces, not only the changed ones the
/// boolean's proof tests) on a result.
fn fully_valid(result: &Boolean) {
    let report = wingedge::validate::validate_soup(
        &result.solid.to_soup(),
        None,
        &wingedge::validate::Options::default(),
    )
    .unwrap();
    assert_eq!(
        report.validity,
        Validity::ValidSolid,
        "{:?}",
        report.violations
    );
}

/// Touching along an edge inside one shell (two legs under a slab, meeting
/// along an edge), and along a slanted edge at arbitrary coordinates.
#[test]
fn results_touching_along_an_edge() {
    let legs = cuboid([0.0; 3], [1.0; 3])
        .union(&cuboid([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]))
        .unwrap();
    let table = legs
        .solid
        .union(&cuboid([0.0, 0.0, 1.0], [2.0, 2.0, 2.0]))
        .unwrap();
    assert_eq!(valid(&table), 6.0);
    assert_eq!((table.report.shells, table.report.genus), (1, Some(0)));
    fully_valid(&table);
    // Two tetrahedra on either side of the edge from p to q, each with its
    // own two further corners.
    let (p, q) = (DVec3::new(0.1, -0.3, 0.7), DVec3::new(1.3, 0.9, -0.2));
    let tetrahedron = |c: DVec3, d: DVec3| {
        let points = [p, q, c, d];
        let mut faces = vec![vec![0, 1, 2], vec![0, 2, 3], vec![0, 3, 1], vec![1, 3, 2]];
        let solid = Solid::try_from_polygons(&points, faces.clone()).unwrap();
        if solid.volume() < 0.0 {
            faces.iter_mut().for_each(|f| f.reverse());
        }
        Solid::try_from_polygons(&points, faces).unwrap()
    };
    let a = tetrahedron(DVec3::new(1.1, -0.4, 1.5), DVec3::new(0.9, 0.8, 1.3));
    let b = tetrahedron(DVec3::new(0.2, 0.5, -1.1), DVec3::new(0.7, -0.6, -0.9));
    let union = a.union(&b).unwrap();
    assert!((valid(&union) - a.volume() - b.volume()).abs() < 1e-15);
    assert_eq!(union.report.shells, 2);
    assert_eq!(union.solid.vertex_count(), 8);
    fully_valid(&union);
    assert_eq!(a.intersection(&b).unwrap().solid.face_count(), 0);
}

#[test]
fn a_cube_against_itself_turned_by_a_trillionth_of_a_radian() {
    let a = cuboid([-1.0; 3], [1.0; 3]);
    let b = mapped_solid(&a, DAffine3::from_rotation_z(1e-12));
    let u = valid(&a.union(&b).unwrap());
    let i = valid(&a.intersection(&b).unwrap());
    let d = valid(&a.difference(&b).unwrap());
    assert!((u - 8.0).abs() < 1e-9 && (i - 8.0).abs() < 1e-9, "{u} {i}");
    assert!((0.0..1e-9).contains(&d), "{d}");
    assert!((u + i - a.volume() - b.volume()).abs() < 1e-12);
}

#[test]
fn cubes_one_unit_in_the_last_place_apart() {
    let a = cuboid([0.0; 3], [1.0; 3]);
    let up = 1.0f64.next_up();
    let b = cuboid([0.0, 0.0, 0.0], [up, up, up]);
    assert!((valid(&a.union(&b).unwrap()) - b.volume()).abs() < 1e-15);
    assert!((valid(&a.intersection(&b).unwrap()) - 1.0).abs() < 1e-15);
    // The difference is a shell thinner than the rounding of its volume.
    match b.difference(&a) {
        Ok(d) => assert!(valid(&d) < 1e-14),
        Err(e) => assert!(matches!(e, BooleanError::InvalidResult { .. }), "{e}"),
    }
    let shifted = mapped_solid(
        &a,
        DAffine3::from_translation(DVec3::new(f64::EPSILON, 0.0, 0.0)),
    );
    let i = valid(&a.intersection(&shifted).unwrap());
    assert!((i - (1.0 - f64::EPSILON)).abs() < 1e-15, "{i}");
}

#[test]
fn far_from_the_origin_and_tiny() {
    let a = builders::sphere(10);
    let b = mapped_solid(&a, DAffine3::from_translation(DVec3::new(0.3, 0.2, 0.1)));
    let reference = [
        valid(&a.union(&b).unwrap()),
        valid(&a.intersection(&b).unwrap()),
        valid(&a.difference(&b).unwrap()),
    ];
    for (scale, offset) in [(1.0, 1e8), (1e-8, 0.0), (1e-8, 1.0)] {
        let map = DAffine3::from_translation(DVec3::splat(offset))
            * DAffine3::from_scale(DVec3::splat(scale));
        let (a, b) = (mapped_solid(&a, map), mapped_solid(&b, map));
        let volumes = [
            valid(&a.union(&b).unwrap()),
            valid(&a.intersection(&b).unwrap()),
            valid(&a.difference(&b).unwrap()),
        ];
        for (v, r) in volumes.iter().zip(reference) {
            let expected = r * scale.powi(3);
            // Moving the input by `offset` rounds each vertex by half a unit
            // in the last place of the offset, `offset / scale · ε / 2` of
            // the object's size, which moves the volume by a few hundred
            // times that at most; scaling alone rounds by one part in 1e16.
            let relative = 1e-12 + 300.0 * f64::EPSILON * offset / scale;
            assert!(
                (v - expected).abs() <= relative * expected,
                "scale {scale} offset {offset}: {v} vs {expected}"
            );
        }
    }
}

/// The Menger sponge of depth 3 on a cube of side 27 (integer
/// coordinates): the cube minus 273 square tunnels, evaluated as one
/// difference of a balanced union. Volume exactly 20³; genus by the
/// Euler characteristic.
#[test]
fn a_menger_sponge_by_differences() {
    let mut tunnels = Vec::new();
    for level in 1..=3u32 {
        let n = 3i32.pow(level);
        let s = 27.0 / n as f64;
        for a in (1..n).step_by(3) {
            for b in (1..n).step_by(3) {
                let (lo_a, hi_a) = (a as f64 * s, (a + 1) as f64 * s);
                let (lo_b, hi_b) = (b as f64 * s, (b + 1) as f64 * s);
                for axis in 0..3 {
                    let mut min = [lo_a, lo_b, -1.0];
                    let mut max = [hi_a, hi_b, 28.0];
                    min.rotate_right(axis);
                    max.rotate_right(axis);
                    let tunnel = AxisBox::try_new(DVec3::from(min), DVec3::from(max)).unwrap();
                    tunnels.push(CsgExpr::leaf(tunnel));
                }
            }
        }
    }
    assert_eq!(tunnels.len(), 273);
    let cube = AxisBox::try_new(DVec3::ZERO, DVec3::splat(27.0)).unwrap();
    let expr = CsgExpr::leaf(cube).difference(CsgExpr::Union(tunnels));
    let csg = Csg::try_new(expr).unwrap();
    let sponge = evaluate(&csg, &EvaluateOptions::default()).unwrap();
    assert_eq!(sponge.report.validity, Validity::ValidSolid);
    // Every coordinate is an integer: the solid is exact; its volume sum
    // rounds.
    assert!(
        (sponge.solid.volume() - 8000.0).abs() < 1e-9,
        "{}",
        sponge.solid.volume()
    );
    assert_eq!(sponge.report.shells, 1);
    // manifold3d 3.5.4's batch union of the same tunnels subtracted from the
    // cube has genus 1409 too (benches/peers/boolean_hard_cases.py).
    assert_eq!(sponge.report.genus, Some(1409));
    println!(
        "Menger sponge: {} faces, {} rings, genus {:?}",
        sponge.solid.face_count(),
        sponge.solid.ring_count(),
        sponge.report.genus
    );
}
