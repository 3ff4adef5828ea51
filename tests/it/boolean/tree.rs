//! Whole set expressions over several solids evaluated in one pass
//! (`boolean::combine`): seeded random trees of boxes on an integer grid
//! against an exact count of unit cells, and trees of turned solids in
//! general position against the same tree evaluated one operator at a
//! time.

use glam::{DAffine3, DVec3};
use wingedge::SetOp;
use wingedge::boolean::{Boolean, BooleanError, BooleanOptions, Expression, boolean, combine};
use wingedge::mesh::{Solid, builders};

use crate::common::mapped_solid;
use wingedge::validate::{Options, Validity, validate_soup};

use crate::common::test_rng;

/// Unit cells per side of the grid the boxes live on.
const SIDE: i32 = 5;

/// A random expression over operands `first..first + count`.
fn random_expression(next: &mut impl FnMut() -> f64, first: usize, count: usize) -> Expression {
    if count == 1 {
        return Expression::Operand(first);
    }
    let left = 1 + ((next() * (count - 1) as f64) as usize).min(count - 2);
    let operation = match (next() * 3.0) as u32 {
        0 => SetOp::Union,
        1 => SetOp::Intersection,
        _ => SetOp::Difference,
    };
    Expression::of(
        operation,
        random_expression(next, first, left),
        random_expression(next, first + left, count - left),
    )
}

/// Whether the cell with lower corner `c` is in the expression's set.
fn cell_inside(expression: &Expression, boxes: &[([i32; 3], [i32; 3])], c: [i32; 3]) -> bool {
    expression
        .contains(&mut |k| {
            let (lo, hi) = boxes[k];
            Ok::<bool, ()>((0..3).all(|i| lo[i] <= c[i] && c[i] < hi[i]))
        })
        .unwrap_or(false)
}

/// Whether the boundary of a set of unit cells touches itself along an
/// edge: two cells of the set and two of its complement around one grid
/// edge, diagonally. (Cells meeting only at a corner give a surface that
/// touches itself at a point, which a winged-edge solid holds as two
/// vertices at one position.)
fn cells_touch_along_an_edge(filled: &impl Fn([i32; 3]) -> bool) -> bool {
    for axis in 0..3 {
        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
        for a in 0..SIDE {
            for b in 0..=SIDE {
                for c in 0..=SIDE {
                    let cell = |du: i32, dv: i32| {
                        let mut p = [0; 3];
                        p[axis] = a;
                        p[u] = b - 1 + du;
                        p[v] = c - 1 + dv;
                        filled(p)
                    };
                    let (x00, x01, x10, x11) = (cell(0, 0), cell(0, 1), cell(1, 0), cell(1, 1));
                    if x00 == x11 && x01 == x10 && x00 != x01 {
                        return true;
                    }
                }
            }
        }
    }
    false
}

/// Trees of 3 to 6 boxes with integer corners (faces coincide, edges and
/// corners touch, three planes meet at grid points): the one-pass result is
/// valid with exactly the volume of the cells inside, also where it
/// touches itself at a point or along an edge.
#[test]
fn trees_of_grid_boxes_have_the_volume_of_their_cells() {
    let mut uniform = test_rng::uniform(0x07EE_50FB_08E5);
    let mut next = move || uniform();
    let mut pinched = 0;
    for case in 0..150 {
        let count = 3 + (next() * 4.0) as usize;
        let mut boxes = Vec::new();
        let mut solids = Vec::new();
        for _ in 0..count {
            let mut lo = [0; 3];
            let mut hi = [0; 3];
            for i in 0..3 {
                let a = (next() * SIDE as f64) as i32;
                let b = (next() * SIDE as f64) as i32;
                lo[i] = a.min(b);
                hi[i] = a.max(b) + 1;
            }
            let corner = |c: [i32; 3]| DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64);
            solids.push(builders::cuboid(corner(lo), corner(hi)).expect("a box"));
            boxes.push((lo, hi));
        }
        let expression = random_expression(&mut next, 0, count);
        let filled = |c: [i32; 3]| {
            (0..3).all(|i| (0..SIDE).contains(&c[i])) && cell_inside(&expression, &boxes, c)
        };
        let mut cells = 0;
        for x in 0..SIDE {
            for y in 0..SIDE {
                for z in 0..SIDE {
                    cells += i32::from(filled([x, y, z]));
                }
            }
        }
        let operands: Vec<&Solid> = solids.iter().collect();
        let r = combine(&operands, &expression, BooleanOptions::default())
            .unwrap_or_else(|e| panic!("case {case} {expression:?}: {e}"));
        if cells == 0 {
            assert_eq!(r.solid.face_count(), 0, "case {case}: empty");
        } else {
            assert_eq!(r.report.validity, Validity::ValidSolid, "case {case}");
            // The whole check on the written result too, every pair of
            // faces tested (the boolean's proof tests the changed ones).
            let report = validate_soup(&r.solid.to_soup(), None, &Options::default()).unwrap();
            assert_eq!(
                report.validity,
                Validity::ValidSolid,
                "case {case}: {:?}",
                report.violations
            );
        }
        let volume = r.solid.volume();
        assert!(
            (volume - f64::from(cells)).abs() < 1e-9,
            "case {case} {expression:?}: volume {volume}, {cells} cells"
        );
        pinched += usize::from(cells_touch_along_an_edge(&filled));
    }
    println!("{pinched} of 150 results touch themselves along an edge");
    assert!(
        pinched >= 10,
        "only {pinched} of 150 trees touch along an edge"
    );
}

/// The expression evaluated one operator at a time, each result rounded
/// and proven before the next operator takes it.
fn one_at_a_time(expression: &Expression, solids: &[Solid]) -> Result<Solid, BooleanError> {
    let (operation, l, r) = match expression {
        Expression::Operand(k) => return Ok(solids[*k].clone()),
        Expression::Union(l, r) => (SetOp::Union, l, r),
        Expression::Intersection(l, r) => (SetOp::Intersection, l, r),
        Expression::Difference(l, r) => (SetOp::Difference, l, r),
    };
    let (a, b) = (one_at_a_time(l, solids)?, one_at_a_time(r, solids)?);
    boolean(&a, &b, operation, BooleanOptions::default()).map(|r: Boolean| r.solid)
}

/// Trees of 3 to 5 turned and offset cubes, octahedra and spheres (general
/// position: the faces of three operands meet in points no operand has):
/// the one-pass result is valid and agrees with the operators evaluated
/// one at a time in volume, shells and genus.
#[test]
fn trees_of_turned_solids_agree_with_one_operator_at_a_time() {
    let mut uniform = test_rng::uniform(0x007E_E50F_7A2E_0002);
    let mut next = move || uniform();
    let mut crossings = 0;
    for case in 0..40 {
        let count = 3 + (next() * 3.0) as usize;
        let mut solids = Vec::new();
        for _ in 0..count {
            let base = match (next() * 3.0) as u32 {
                0 => builders::sphere(6 + (next() * 6.0) as usize),
                1 => builders::cube(),
                _ => builders::octahedron(),
            };
            let axis = DVec3::new(next() - 0.5, next() - 0.5, next() - 0.5).normalize_or(DVec3::Z);
            let map = DAffine3::from_translation(DVec3::new(next(), next(), next()) * 0.9)
                * DAffine3::from_axis_angle(axis, next() * 6.0);
            solids.push(mapped_solid(&base, map));
        }
        let expression = random_expression(&mut next, 0, count);
        let operands: Vec<&Solid> = solids.iter().collect();
        let together = combine(&operands, &expression, BooleanOptions::default())
            .unwrap_or_else(|e| panic!("case {case} {expression:?}: {e}"));
        crossings += together.stats.segment_crossings;
        let apart = one_at_a_time(&expression, &solids)
            .unwrap_or_else(|e| panic!("case {case} one at a time: {e}"));
        let apart_report = wingedge::boolean::prove(&apart).expect("proven");
        let (v1, v2) = (together.solid.volume(), apart.volume());
        let scale = solids.iter().map(Solid::volume).fold(0.0, f64::max);
        assert!(
            (v1 - v2).abs() <= 1e-12 * scale,
            "case {case} {expression:?}: {v1} vs {v2}"
        );
        assert_eq!(together.report.shells, apart_report.shells, "case {case}");
        assert_eq!(together.report.genus, apart_report.genus, "case {case}");
    }
    assert!(crossings > 0, "no three-operand crossing was exercised");
    println!("{crossings} points where three operands' faces meet");
}

/// Bad expressions are refused by name; empty operands drop out.
#[test]
fn unknown_operands_are_refused_and_empty_ones_drop_out() {
    let cube = builders::cube();
    let err = combine(
        &[&cube],
        &Expression::of(SetOp::Union, Expression::Operand(0), Expression::Operand(3)),
        BooleanOptions::default(),
    )
    .unwrap_err();
    assert_eq!(
        err,
        BooleanError::UnknownOperand {
            operand: 3,
            count: 1
        }
    );
    let empty = Solid::default();
    let e = Expression::of(
        SetOp::Difference,
        Expression::of(SetOp::Union, Expression::Operand(0), Expression::Operand(1)),
        Expression::Operand(1),
    );
    let r = combine(&[&cube, &empty], &e, BooleanOptions::default()).unwrap();
    assert_eq!(r.solid.face_count(), cube.face_count());
    assert!((r.solid.volume() - cube.volume()).abs() < 1e-12);
    assert!(r.origins.iter().all(|o| o.operand == 0));
}

/// The 101-leaf scene of balls and boxes on a slab, in one pass: the balls
/// touch the slab at their poles and the boxes stand on it, so the union
/// is 51 shells (the slab with its boxes, and each ball) whose volume is
/// the sum of the leaves' own.
#[test]
fn balls_resting_on_a_slab_union_to_touching_shells() {
    use std::path::Path;
    use wingedge::csg::{EvaluateOptions, evaluate};
    use wingedge::scene::Scene;
    let path = Path::new("fixtures/scenes/many_leaves.json");
    let scene = Scene::from_file(path).expect("the scene");
    let options = EvaluateOptions::default();
    let union = evaluate(&scene.csg, &options).expect("evaluated");
    assert_eq!(union.report.validity, Validity::ValidSolid);
    assert_eq!(union.report.shells, 51);
    // Each leaf evaluated alone, clipped by the same bounds (the slab is a
    // box: no clipping happens).
    let text = std::fs::read_to_string(path).expect("readable");
    let json: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let leaves = json["root"]["union"].as_array().expect("a union");
    assert_eq!(leaves.len(), 101);
    let mut sum = 0.0;
    for (k, leaf) in leaves.iter().enumerate() {
        let alone = serde_json::json!({ "root": leaf }).to_string();
        let one = Scene::from_json(&alone, &format!("leaf {k}"), Path::new(".")).expect("a leaf");
        sum += evaluate(&one.csg, &options).expect("a leaf").solid.volume();
    }
    let volume = union.solid.volume();
    assert!((volume - sum).abs() < 1e-9 * sum, "{volume} vs {sum}");
}

/// Every face of an evaluated tree names the leaf it comes from and the
/// face of that leaf's polyhedron: the faces lie in that face's plane,
/// facing the same way for the block and the other way for the drill
/// taken away from it (a mesh leaf and a moved box leaf).
#[test]
fn evaluated_faces_name_their_leaf_and_its_face() {
    use std::path::Path;
    use wingedge::csg::{EvaluateOptions, evaluate};
    use wingedge::scene::Scene;
    let scene = Scene::from_json(
        r#"{"root": {"difference": [
            {"mesh": "fixtures/valid/cube.obj"},
            {"transform": {"translate": [0.25, 0.25, 0]},
             "child": {"box": {"min": [-0.5, -0.5, -2], "max": [0.5, 0.5, 2]}}}]}}"#,
        "drilled",
        Path::new("."),
    )
    .expect("the scene");
    let options = EvaluateOptions::default();
    let evaluated = evaluate(&scene.csg, &options).expect("evaluated");
    assert_eq!(evaluated.report.genus, Some(1));
    let bounds = scene.csg.bounds();
    let leaf_faces: Vec<Vec<DVec3>> = scene
        .csg
        .leaves()
        .iter()
        .map(|leaf| {
            let solid = leaf
                .primitive
                .tessellate(options.tolerance, &bounds)
                .expect("a polyhedron");
            solid
                .faces()
                .map(|(_, f)| f.plane.expect("a plane").normal)
                .collect()
        })
        .collect();
    let mut from = [0, 0];
    for (_, face) in evaluated.solid.faces() {
        let origin = evaluated.origins[face.attributes.source_index.expect("an origin")];
        let leaf = origin.leaf.0 as usize;
        from[leaf] += 1;
        let theirs = leaf_faces[leaf][origin.face];
        let ours = face.plane.expect("a plane").normal;
        let facing = if leaf == 0 { 1.0 } else { -1.0 };
        assert!(
            (ours - facing * theirs).length() < 1e-12,
            "leaf {leaf} face {}: {ours} vs {theirs}",
            origin.face
        );
    }
    // The cube's six faces (two of them drilled) and the drill's four sides.
    assert_eq!(from, [6, 4]);
}
