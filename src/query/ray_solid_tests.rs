//! Tests of `ray_solid.rs`.

use super::*;
use crate::mesh::builders;
use crate::query::Transition;
use crate::query::accel::ray_stream::{self, WalkScratch};
use crate::query::ray_scaling::unit_scaled;
use crate::spatial::bvh::ray_box::{INV_GROW, INV_SHRINK, ORIGIN_WIDEN, Row};
use crate::spatial::bvh::{BoxFrame, Node8, NodeLanes, Portable, RayBox, WIDTH, for_each_lanes};
use glam::DVec3;

/// `count` rays (those valid) from anywhere in `[-2, 2]³` towards points
/// within `spread` of the origin: around and through a unit solid
/// centred there, seeded.
pub(in crate::query) fn rays_towards_the_centre(seed: u64, count: usize, spread: f64) -> Vec<Ray> {
    let mut uniform = crate::test_rng::uniform(seed);
    let mut rand = || DVec3::new(uniform(), uniform(), uniform()) * 4.0 - DVec3::splat(2.0);
    (0..count)
        .map(|_| {
            let origin = rand();
            Ray::new(origin, rand() * spread - origin)
        })
        .filter(Ray::is_valid)
        .collect()
}

/// The `f32` slab test never rejects a box the exact ray enters: boxes
/// and rays at many scales and offsets, including rays grazing a box's
/// face and rays parallel to an axis, checked against the slab test
/// evaluated in `f64` (whose error, ~1e-16 relative, is far below the
/// `f32` margins).
#[test]
fn f32_slab_test_is_conservative() {
    let mut uniform = crate::test_rng::uniform(0x9E37_79B9_7F4A_7C15u64);
    let mut entered = 0;
    for case in 0..20_000 {
        let centre = DVec3::new(uniform(), uniform(), uniform()) * 2e8 - DVec3::splat(1e8);
        let scale = 2f64.powi((uniform() * 40.0) as i32 - 20);
        let frame = BoxFrame { centre, scale };
        let size = 1.0 / scale;
        let mut rand = || DVec3::new(uniform(), uniform(), uniform()) * 2.0 - DVec3::ONE;
        let lo = centre + rand() * size;
        let hi = lo + (rand() + DVec3::ONE) * size * 0.1;
        let origin = centre + rand() * size * 3.0;
        let mut direction = (lo + (hi - lo) * (rand() + DVec3::ONE) * 0.5) - origin;
        if case % 5 == 0 {
            direction[case % 3] = 0.0;
        }
        if direction == DVec3::ZERO {
            continue;
        }
        direction *= 2f64.powi((uniform() * 200.0) as i32 - 100);
        let ray = Ray::new(origin, direction);
        let mut node = Node8 {
            child: [0; WIDTH],
            ..Node8::EMPTY
        };
        for a in 0..3 {
            node.bounds[a] = [f32::INFINITY; WIDTH];
            node.bounds[3 + a] = [f32::NEG_INFINITY; WIDTH];
            node.bounds[a][0] = frame.lower(lo[a], a);
            node.bounds[3 + a][0] = frame.upper(hi[a], a);
        }
        // The slab test in f64 on the exact box, shrunk by 1e-9 of its
        // size so that rounding cannot make it enter spuriously.
        let shrink = (hi - lo) * 1e-9;
        let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
        let mut misses = false;
        for a in 0..3 {
            let (l, h) = (lo[a] + shrink[a], hi[a] - shrink[a]);
            if direction[a] == 0.0 {
                misses |= origin[a] < l || origin[a] > h;
                continue;
            }
            let (ta, tb) = (
                (l - origin[a]) / direction[a],
                (h - origin[a]) / direction[a],
            );
            t0 = t0.max(ta.min(tb));
            t1 = t1.min(ta.max(tb));
        }
        if misses || t0 > t1 {
            continue;
        }
        entered += 1;
        // The slab test sees rays scaled as every query passes them;
        // `t` along the scaled ray is `t / factor`, exactly.
        let (scaled, factor) = unit_scaled(&ray);
        let rb = RayBox::new(&scaled, &frame);
        for_each_lanes!(|lanes| {
            let (entry, mask) = lanes.enter(&rb, &node, rb.limit(f64::INFINITY));
            assert_eq!(mask, 1, "case {case}: {ray:?} misses [{lo}, {hi}]");
            // And with the limit at the exact entry, the box still counts.
            let (_, mask) = lanes.enter(&rb, &node, rb.limit(factor.scaled_t(t0)));
            let entry = entry[0];
            assert_eq!(mask, 1, "case {case}: entry {entry} vs limit {t0}");
        });
    }
    assert!(entered > 5_000, "{entered}");
}

#[test]
fn a_batch_answers_as_single_queries() {
    let accel = Accel::new(&builders::sphere(24));
    // From anywhere around the unit sphere towards points near its
    // centre; several stream chunks and a partial one.
    let rays = rays_towards_the_centre(0xD1B5_4A32_D192_ED03, 5 * STREAM_CHUNK + 123, 0.25);
    let batch = accel.first_hit_batch(&rays).unwrap();
    assert_eq!(batch.len(), rays.len());
    for (ray, hit) in rays.iter().zip(&batch) {
        assert_eq!(accel.first_hit(ray).unwrap(), *hit);
    }
    let hits = batch.iter().filter(|h| h.is_some()).count();
    assert!(hits > rays.len() / 2, "{hits} of {}", rays.len());
}

/// The walk gives the same answers whichever way its nodes are opened
/// (the AVX2 one only runs where the processor has it).
#[test]
fn both_node_openers_give_the_same_hits() {
    let accel = Accel::new(&builders::sphere(24));
    let rays = rays_towards_the_centre(0x3C6E_F372_FE94_F82B, 4000, 0.5);
    type Cast<'a> = &'a dyn Fn(&[Ray], &mut [Option<Crossing>]);
    let cast = |lanes: Cast| {
        let mut out = vec![None; rays.len()];
        lanes(&rays, &mut out);
        out
    };
    let scratch = std::cell::RefCell::new(WalkScratch::new(rays.len()));
    let portable = cast(&|r, o| accel.first_hits_with(Portable, r, o, &mut scratch.borrow_mut()));
    let hits = portable.iter().filter(|h| h.is_some()).count();
    assert!(hits > rays.len() / 2, "{hits} of {}", rays.len());
    for_each_lanes!(|lanes| {
        assert_eq!(
            cast(&|r, o| accel.first_hits_with(lanes, r, o, &mut scratch.borrow_mut())),
            portable
        );
    });
    for (ray, hit) in rays.iter().zip(&portable).step_by(5) {
        assert_eq!(accel.first_hit(ray).unwrap(), *hit);
    }
}

/// `RayBox::new` works on the three axes side by side; its values are
/// bit for bit those of the per-axis definition written out here:
/// origins near and far (beyond the `f32` range too), directions with
/// zero, negative-zero, tiny and unit-size components.
#[test]
fn ray_box_lanes_equal_the_per_axis_definition() {
    fn per_axis(ray: &Ray, frame: &BoxFrame) -> ([[u32; 3]; 4], [Row; 3], [Row; 3]) {
        let mut values = [[0u32; 3]; 4];
        let (mut near_row, mut far_row) = ([Row::LowerX; 3], [Row::LowerX; 3]);
        for a in 0..3 {
            let f = frame.in_frame(ray.origin[a], a) as f32;
            let (lo, hi) = if f.is_finite() {
                let m = f.abs() * ORIGIN_WIDEN + f32::MIN_POSITIVE;
                (f - m, f + m)
            } else {
                (f32::NEG_INFINITY, f32::INFINITY)
            };
            let da = ray.direction[a];
            let recip = (1.0 / da.abs()) as f32;
            let (inv_lo, inv_hi) = if da == 0.0 {
                (f32::INFINITY, f32::INFINITY)
            } else {
                ((recip * INV_SHRINK).min(f32::MAX), recip * INV_GROW)
            };
            let down = da.is_sign_negative();
            let sign = u32::from(down) << 31;
            let (o_near, o_far) = if down { (lo, hi) } else { (hi, lo) };
            values[0][a] = o_near.to_bits();
            values[1][a] = o_far.to_bits();
            values[2][a] = inv_lo.to_bits() | sign;
            values[3][a] = inv_hi.to_bits() | sign;
            near_row[a] = Row::of(a, down);
            far_row[a] = Row::of(a, !down);
        }
        (values, near_row, far_row)
    }
    let frames = [
        BoxFrame {
            centre: DVec3::ZERO,
            scale: 1.0,
        },
        BoxFrame {
            centre: DVec3::new(3.5, -2.25, 1e10),
            scale: 2f64.powi(-33),
        },
        BoxFrame {
            centre: DVec3::new(-1e-300, 0.0, 7.0),
            scale: 2f64.powi(900),
        },
    ];
    let mut uniform = crate::test_rng::uniform(0x510E_527F_ADE6_82D1);
    let special = [
        0.0, -0.0, 1e-300, -1e-300, 5e-324, 1.0, -1.5, 1e38, 1e300, -1e300,
    ];
    let mut checked = 0;
    for case in 0..4000usize {
        let mut pick = |k: usize| {
            if (case + k).is_multiple_of(3) {
                special[(case / 3 + k) % special.len()]
            } else {
                (uniform() - 0.5) * 8.0
            }
        };
        let origin = DVec3::new(pick(0), pick(1), pick(2));
        let direction = DVec3::new(pick(3), pick(4), pick(5));
        let ray = Ray::new(origin, direction);
        if !ray.is_valid() {
            continue;
        }
        let (ray, _) = unit_scaled(&ray);
        for frame in &frames {
            let rb = RayBox::new(&ray, frame);
            let lanes = [rb.o_near, rb.o_far, rb.inv_near, rb.inv_far]
                .map(|v| [v[0].to_bits(), v[1].to_bits(), v[2].to_bits()]);
            assert_eq!(
                (lanes, rb.near_row, rb.far_row),
                per_axis(&ray, frame),
                "case {case}: {ray:?}"
            );
            assert_eq!(rb.t_to_s, frame.scale);
            checked += 1;
        }
    }
    assert!(checked > 9000, "{checked}");
}

/// A tree whose traversal stack would not fit the interleaved walk's
/// is cast one ray at a time, with the same answers.
#[test]
fn batches_over_trees_too_deep_to_interleave_give_the_same_hits() {
    let mut accel = Accel::new(&builders::sphere(24));
    let rays = rays_towards_the_centre(0x9B05_688C_2B3E_6C1F, 2 * STREAM_CHUNK + 57, 0.25);
    let interleaved = accel.first_hit_batch(&rays).unwrap();
    let hits = interleaved.iter().filter(|h| h.is_some()).count();
    assert!(hits > rays.len() / 2, "{hits} of {}", rays.len());
    // The longest stack the interleaved walk holds, and one more (a
    // longer stack length still bounds the tree's stacks).
    for stack_len in [ray_stream::STACK, ray_stream::STACK + 1] {
        accel.bvh.set_stack_len(stack_len);
        assert_eq!(accel.first_hit_batch(&rays).unwrap(), interleaved);
    }
    for (ray, hit) in rays.iter().zip(&interleaved).step_by(7) {
        assert_eq!(accel.first_hit(ray).unwrap(), *hit);
    }
}

#[test]
fn a_tree_deeper_than_the_local_stack_is_walked_in_full() {
    // Tetrahedra at x = 1.2^k: binned splits peel off only the farthest
    // few at each level (as far as the `f32` boxes of the build tell
    // them apart), so the tree is far deeper than a balanced one and
    // traversal stacks spill to the heap.
    let count = 150;
    let corner = |k: i32| (1.2f64.powi(k), 1.2f64.powi(k) / 4.0);
    let mut positions = Vec::new();
    let mut polygons = Vec::new();
    for k in 0..count {
        let (x, s) = corner(k);
        let base = positions.len();
        positions.extend([
            DVec3::new(x, 0.0, 0.0),
            DVec3::new(x + s, 0.0, 0.0),
            DVec3::new(x, s, 0.0),
            DVec3::new(x, 0.0, s),
        ]);
        for f in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
            polygons.push(f.map(|i| base + i));
        }
    }
    let soup = crate::mesh::PolygonSoup::new(positions, polygons);
    let accel = Accel::new(&crate::mesh::Solid::try_from_soup(&soup).unwrap());
    assert!(accel.bvh.stack_len() > 64, "{}", accel.bvh.stack_len());
    // Straight down onto each slanted face `x' + y' + z' = s`.
    let rays: Vec<Ray> = (0..count)
        .map(|k| {
            let (x, s) = corner(k);
            Ray::new(DVec3::new(x + s / 4.0, s / 4.0, 10.0 * s), DVec3::NEG_Z)
        })
        .collect();
    let batch = accel.first_hit_batch(&rays).unwrap();
    for (k, (ray, hit)) in rays.iter().zip(batch).enumerate() {
        let (_, s) = corner(k as i32);
        let hit = hit.unwrap_or_else(|| panic!("tetrahedron {k} missed"));
        assert_eq!(hit.transition, Transition::Enter, "{k}");
        assert!((hit.t - 9.5 * s).abs() <= 1e-12 * s, "{k}: {}", hit.t);
        assert_eq!(accel.first_hit(ray).unwrap(), Some(hit), "{k}");
        assert_eq!(accel.ray_crossings(ray).unwrap().hits.len(), 2, "{k}");
    }
}

#[test]
fn huge_and_tiny_directions_give_the_same_crossings() {
    // Found by the queries fuzz check: a direction component of
    // −f64::MAX overflowed the exact line tests.
    let accel = Accel::new(&builders::l_prism());
    let origin = DVec3::new(0.5, 0.5, 0.5);
    let unit = DVec3::new(0.25, 1.0, -0.125);
    let reference = accel.ray_crossings(&Ray::new(origin, unit)).unwrap();
    assert_eq!(reference.origin, Containment::Inside);
    for scale in [f64::MAX, 1e300, 1e-300, f64::MIN_POSITIVE] {
        let ray = Ray::new(origin, unit * scale);
        let answer = accel.ray_crossings(&ray).unwrap();
        assert_eq!(answer.origin, reference.origin, "{scale}");
        let faces = |r: &RayCrossings| -> Vec<_> {
            r.hits.iter().map(|h| (h.face, h.transition)).collect()
        };
        assert_eq!(faces(&answer), faces(&reference), "{scale}");
        let first = accel.first_hit(&ray).unwrap().unwrap();
        assert_eq!(first.t, answer.hits[0].t);
        assert!(answer.hits.iter().all(|h| h.t > 0.0));
    }
    // Along one axis the parameter is exact: 1 / f64::MAX.
    let down = Ray::new(DVec3::ZERO, DVec3::new(0.0, 0.0, -f64::MAX));
    let cube = Accel::new(&builders::cube());
    let hit = cube.first_hit(&down).unwrap().unwrap();
    assert_eq!(hit.t, 1.0 / f64::MAX);
}

/// A crossing whose `t` overflows (a direction of 5e-324) or
/// underflows to zero (a direction of f64::MAX from beside a face) is
/// refused by name, as the CSG trace refuses it, never answered with
/// `t = ∞` (an audit found `outside inf inf`).
#[test]
fn a_crossing_t_that_overflows_or_underflows_is_refused() {
    let cube = Accel::new(&builders::cube());
    let tiny = Ray::new(DVec3::new(-3.0, 0.1, 0.2), DVec3::new(5e-324, 0.0, 0.0));
    let refused = |e: &QueryError, index: usize, overflow: bool| {
        matches!(e, QueryError::RayOutOfRange { index: i, reason, .. }
            if *i == index && reason.contains(if overflow { "overflows" } else { "underflows" }))
    };
    assert!(refused(&cube.ray_crossings(&tiny).unwrap_err(), 0, true));
    assert!(refused(&cube.first_hit(&tiny).unwrap_err(), 0, true));
    assert!(refused(&cube.first_hit_traced(&tiny).unwrap_err(), 0, true));
    let fine = Ray::new(DVec3::new(-3.0, 0.1, 0.2), DVec3::X);
    let batch = [fine, fine, tiny, tiny];
    assert!(refused(
        &cube.ray_crossings_batch(&batch).unwrap_err(),
        2,
        true
    ));
    assert!(refused(&cube.first_hit_batch(&batch).unwrap_err(), 2, true));
    // The first crossing is 2⁻⁵² from the origin: along f64::MAX,
    // t = 2⁻⁵² / f64::MAX underflows to zero.
    let beside = Ray::new(
        DVec3::new(-1.0 - 2f64.powi(-52), 0.1, 0.2),
        DVec3::new(f64::MAX, 0.0, 0.0),
    );
    assert!(refused(&cube.ray_crossings(&beside).unwrap_err(), 0, false));
    assert!(refused(&cube.first_hit(&beside).unwrap_err(), 0, false));
    // A ray that misses has no t to overflow.
    let away = Ray::new(DVec3::new(-3.0, 0.1, 0.2), DVec3::new(-5e-324, 0.0, 0.0));
    assert_eq!(cube.first_hit(&away), Ok(None));
}

#[test]
fn ray_through_a_cube() {
    let accel = Accel::new(&builders::cube());
    let r = accel
        .ray_crossings(&Ray::new(DVec3::new(-3.0, 0.1, 0.2), DVec3::X))
        .unwrap();
    assert_eq!(r.origin, Containment::Outside);
    assert_eq!(r.hits.len(), 2);
    assert_eq!(r.hits[0].t, 2.0);
    assert_eq!(r.hits[0].transition, Transition::Enter);
    assert_eq!(r.hits[1].t, 4.0);
    let r = accel
        .ray_crossings(&Ray::new(DVec3::ZERO, DVec3::new(1.0, 1.0, 1.0)))
        .unwrap();
    assert_eq!(r.origin, Containment::Inside);
    assert_eq!(r.hits.len(), 1);
    assert_eq!(r.hits[0].t, 1.0);
}

/// The leaves' `f32` filter leaves most of the triangles a ray meets in
/// leaf boxes to no exact test at all (counted, not timed), and the
/// first hits it finds are those of the exact crossings.
#[test]
fn the_leaf_filter_spares_most_exact_tests() {
    let accel = Accel::new(&builders::sphere(40));
    let (mut triangles, mut exact) = (0, 0);
    for k in 0..200 {
        let a = f64::from(k) * 0.37;
        let origin = DVec3::new(3.0 * a.cos(), 3.0 * a.sin(), 0.5 * (a * 0.7).sin());
        let target = DVec3::new(0.3 * (a * 1.3).sin(), 0.2 * a.cos(), 0.4 * (a * 0.9).cos());
        let ray = Ray::new(origin, target - origin);
        let (hit, stats) = accel.first_hit_traced(&ray).unwrap();
        let all = accel.ray_crossings(&ray).unwrap();
        assert_eq!(hit, all.hits.first().copied(), "ray {k}");
        assert!(hit.is_some(), "ray {k} aims inside the sphere");
        assert!(stats.exact_tests <= stats.triangles);
        triangles += stats.triangles;
        exact += stats.exact_tests;
    }
    assert!(4 * exact < triangles, "{exact} exact of {triangles}");
}
