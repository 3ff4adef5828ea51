//! A tree evaluated by its structure (node by node where every
//! intermediate result is exact, sides whose boxes do not meet decided by
//! the boxes) gives the solid the one pass over all leaves gives: valid,
//! the same volume, genus and shells, on random trees of boxes on an
//! integer grid, Menger sponges, turned cubes sharing planes, disjoint and
//! nested leaves, and leaves dropped by their boxes.

use glam::{DAffine3, DVec3};
use proptest::prelude::*;
use wingedge::csg::{AxisBox, Csg, CsgExpr, EvaluateOptions, Evaluated, Sphere, evaluate};
use wingedge::validate::Validity;

fn cube(min: [f64; 3], max: [f64; 3]) -> CsgExpr {
    CsgExpr::leaf(AxisBox::try_new(DVec3::from(min), DVec3::from(max)).expect("a box"))
}

/// The tree evaluated both ways.
fn both(expr: &CsgExpr) -> (Evaluated, Evaluated) {
    let csg = Csg::try_new(expr.clone()).expect("a tree");
    let structured = evaluate(&csg, &EvaluateOptions::default()).expect("by structure");
    let one_pass = evaluate(
        &csg,
        &EvaluateOptions {
            by_structure: false,
            ..EvaluateOptions::default()
        },
    )
    .expect("one pass");
    (structured, one_pass)
}

/// Both valid, with the same volume, genus and shells; every face traced
/// to a leaf. `exact`: the volumes are equal to the last bit (integer
/// coordinates, small enough that the volume's sums are exact).
fn assert_same(structured: &Evaluated, one_pass: &Evaluated, exact: bool) {
    for e in [structured, one_pass] {
        if e.solid.face_count() > 0 {
            assert_eq!(e.report.validity, Validity::ValidSolid);
        }
        for (_, face) in e.solid.faces() {
            let index = face.attributes.source_index.expect("traced");
            assert!(index < e.origins.len());
        }
    }
    let (a, b) = (structured.solid.volume(), one_pass.solid.volume());
    if exact {
        assert_eq!(a, b, "volume by structure {a}, in one pass {b}");
    } else {
        assert!(
            (a - b).abs() <= 1e-12 * b.abs().max(1.0),
            "volume by structure {a}, in one pass {b}"
        );
    }
    assert_eq!(structured.report.genus, one_pass.report.genus);
    assert_eq!(structured.report.shells, one_pass.report.shells);
}

/// The Menger sponge of depth `depth` on a cube of side `3^depth`.
fn sponge(depth: u32) -> CsgExpr {
    let side = 3f64.powi(depth as i32);
    let mut tunnels = Vec::new();
    for level in 1..=depth {
        let n = 3i64.pow(level);
        let s = side / n as f64;
        for a in (1..n).step_by(3) {
            for b in (1..n).step_by(3) {
                for axis in 0..3 {
                    let mut min = [a as f64 * s, b as f64 * s, -1.0];
                    let mut max = [(a + 1) as f64 * s, (b + 1) as f64 * s, side + 1.0];
                    min.rotate_right(axis);
                    max.rotate_right(axis);
                    tunnels.push(cube(min, max));
                }
            }
        }
    }
    cube([0.0; 3], [side; 3]).difference(CsgExpr::Union(tunnels))
}

/// A sponge of depth 2 is evaluated node by node, every intermediate
/// exact (its coordinates are integers), with no pass over all leaves.
#[test]
fn a_sponge_is_evaluated_node_by_node() {
    let (structured, one_pass) = both(&sponge(2));
    assert_same(&structured, &one_pass, true);
    assert_eq!(structured.solid.volume(), 400.0);
    let work = structured.structure;
    assert!(work.exact > 0, "{work:?}");
    assert_eq!(work.set_aside, 0, "{work:?}");
    assert_eq!(work.root_operands, 0, "{work:?}");
}

/// Cubes turned about `z` share their top and bottom planes; their
/// crossings are not `f64` points, so nothing is tried node by node: one
/// pass over the leaves, as before.
#[test]
fn turned_cubes_sharing_planes_stay_one_pass() {
    let cube = AxisBox::try_new(DVec3::splat(-1.0), DVec3::splat(1.0)).unwrap();
    let leaves: Vec<CsgExpr> = (0..6)
        .map(|i| {
            let angle = f64::from(i) * std::f64::consts::FRAC_PI_2 / 6.0;
            CsgExpr::leaf(cube).transformed(DAffine3::from_rotation_z(angle))
        })
        .collect();
    let (structured, one_pass) = both(&CsgExpr::Union(leaves));
    assert_same(&structured, &one_pass, false);
    assert_eq!(structured.structure.set_aside, 0);
    assert_eq!(structured.structure.root_operands, 6);
    assert_eq!(structured.structure.booleans, 1);
}

/// Disjoint spheres, a box nested in one of them and a box crossing
/// another: the disjoint ones are never cut against each other.
#[test]
fn disjoint_and_nested_leaves() {
    let mut leaves: Vec<CsgExpr> = (0..4)
        .map(|i| {
            CsgExpr::leaf(Sphere::try_new(DVec3::new(3.0 * f64::from(i), 0.0, 0.0), 1.0).unwrap())
        })
        .collect();
    leaves.push(cube([-0.25; 3], [0.25; 3]));
    leaves.push(cube([2.5, -0.25, -0.25], [4.5, 0.25, 0.25]));
    let (structured, one_pass) = both(&CsgExpr::Union(leaves));
    assert_same(&structured, &one_pass, false);
    assert_eq!(structured.report.shells, 4);
}

/// A subtracted leaf apart from what it is subtracted from, and an
/// intersection of leaves apart, are decided by their boxes: no boolean.
#[test]
fn leaves_apart_are_dropped_by_their_boxes() {
    let a = cube([0.0; 3], [1.0; 3]);
    let far = cube([2.0; 3], [3.0; 3]);
    // Touching along a face: still no interior in common.
    let touching = cube([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    let difference = a
        .clone()
        .difference(far.clone())
        .difference(touching.clone());
    let (structured, one_pass) = both(&difference);
    assert_same(&structured, &one_pass, true);
    assert_eq!(structured.solid.volume(), 1.0);
    assert_eq!(structured.structure.by_boxes, 2);
    assert_eq!(
        structured.structure.booleans, 1,
        "only the leaf itself, as it is"
    );
    let intersection = a.intersection(touching).union(far);
    let (structured, one_pass) = both(&intersection);
    assert_same(&structured, &one_pass, true);
    assert_eq!(structured.solid.volume(), 1.0);
    assert_eq!(structured.structure.by_boxes, 1);
}

/// A random tree of boxes with integer corners in `[0, 6]`.
fn tree_strategy() -> impl Strategy<Value = CsgExpr> {
    let leaf =
        (prop::array::uniform3(0u8..6), prop::array::uniform3(1u8..4)).prop_map(|(lo, size)| {
            let min = lo.map(f64::from);
            let max = [0, 1, 2].map(|k| f64::from(lo[k] + size[k]));
            cube(min, max)
        });
    leaf.prop_recursive(4, 24, 2, |inner| {
        (inner.clone(), inner, 0u8..3).prop_map(|(a, b, op)| match op {
            0 => a.union(b),
            1 => a.intersection(b),
            _ => a.difference(b),
        })
    })
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(48)))]

    /// Boxes on an integer grid: every intermediate result is exact, so
    /// the tree is evaluated node by node; it is the one-pass solid.
    #[test]
    fn trees_of_boxes_by_structure_equal_one_pass(expr in tree_strategy()) {
        let (structured, one_pass) = both(&expr);
        assert_same(&structured, &one_pass, true);
    }
}
