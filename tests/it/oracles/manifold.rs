//! Cross-checks against manifold3d, the independent oracle.
//!
//! `tests/oracle/manifold_oracle.py` builds meshes with manifold3d's own
//! primitives and booleans (seeded) and records manifold3d's answers about
//! them; these tests read the same meshes with wingedge and compare. The
//! oracle is required: without it these tests fail and say how to install it
//! (`python3 -m pip install -r tests/oracle/requirements.txt`).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use serde_json::Value;
use wingedge::csg::Stats;
use wingedge::geom::Ray;
use wingedge::glam::DVec3;
use wingedge::io::{ObjOptions, import_obj, read_obj};
use wingedge::mesh::Solid;
use wingedge::query::{Accel, Containment, Transition};
use wingedge::scene::Scene;
use wingedge::validate::{Options, validate_import};

use crate::common::rational_parity::{self, Class};
use crate::common::test_rng;

/// Runs the oracle once per test binary and returns its output folder.
fn oracle() -> &'static (PathBuf, Value) {
    static ORACLE: OnceLock<(PathBuf, Value)> = OnceLock::new();
    ORACLE.get_or_init(|| {
        let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("manifold-oracle");
        let fixtures = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/valid");
        // A fresh folder and a fresh nonce: answers left by an earlier run,
        // or a python3 that exits 0 without writing, cannot pass for today's.
        if out.exists() {
            std::fs::remove_dir_all(&out).expect("clears the oracle's folder");
        }
        let nonce = format!(
            "{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .expect("a clock after 1970")
                .as_nanos()
        );
        crate::common::oracle::run(
            "manifold_oracle.py",
            [
                out.as_os_str(),
                "--fixtures".as_ref(),
                fixtures.as_os_str(),
                "--nonce".as_ref(),
                nonce.as_ref(),
            ],
        );
        let text = std::fs::read_to_string(out.join("oracle.json"))
            .expect("the oracle writes oracle.json");
        let report: Value = serde_json::from_str(&text).expect("oracle.json is JSON");
        assert_eq!(
            report["nonce"],
            nonce.as_str(),
            "oracle.json is from this run"
        );
        (out, report)
    })
}

fn load(dir: &Path, name: &str) -> Solid {
    let soup = read_obj(&dir.join(format!("{name}.obj"))).unwrap_or_else(|e| panic!("{name}: {e}"));
    Solid::try_from_soup(&soup).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn counts_genus_and_volume_agree_with_manifold3d() {
    let (dir, report) = oracle();
    let meshes = report["meshes"].as_object().expect("meshes");
    assert!(
        meshes.len() >= 10,
        "the oracle made {} meshes",
        meshes.len()
    );
    for (name, expected) in meshes {
        let solid = load(dir, name);
        solid.check_consistency().unwrap();
        assert_eq!(expected["status"], "NoError", "{name}");
        let counts = (solid.vertex_count(), solid.edge_count(), solid.face_count());
        let want = |k: &str| expected[k].as_u64().expect("count") as usize;
        assert_eq!(
            counts,
            (want("vertices"), want("edges"), want("faces")),
            "{name}: V, E, F"
        );
        assert!(solid.is_closed(), "{name}");
        let shells = solid.shells();
        assert_eq!(shells.len(), 1, "{name}");
        assert_eq!(
            shells[0].genus(),
            expected["genus"].as_i64(),
            "{name}: genus"
        );
        let volume = expected["volume"].as_f64().expect("volume");
        let relative = (solid.volume() - volume).abs() / volume.abs();
        assert!(
            relative <= 1e-9,
            "{name}: volume {} vs manifold3d {volume} (relative {relative:e})",
            solid.volume()
        );
        println!(
            "{name}: V={} E={} F={} genus={:?} volume={} (manifold3d {volume}, rel {relative:.1e})",
            counts.0,
            counts.1,
            counts.2,
            shells[0].genus(),
            solid.volume()
        );
    }
}

/// The solid's faces as triangles (fans: the oracle's meshes are triangle
/// meshes already).
fn triangles(solid: &Solid) -> Vec<[DVec3; 3]> {
    solid
        .faces()
        .flat_map(|(f, _)| {
            let corners: Vec<DVec3> = solid.face_vertices(f).map(|v| solid.position(v)).collect();
            (1..corners.len() - 1)
                .map(move |i| [corners[0], corners[i], corners[i + 1]])
                .collect::<Vec<_>>()
        })
        .collect()
}

/// What exact point classification by the independent reference
/// (`rational_parity`, big-integer ray parity) says about a crossing list:
/// the state implied between consecutive crossings must match the exact
/// class of a sample point there. Returns the first contradiction, if any.
fn contradiction(triangles: &[[DVec3; 3]], ray: &Ray, ts: &[f64], length: f64) -> Option<String> {
    let mut bounds = vec![0.0];
    bounds.extend(ts.iter().copied().filter(|&t| t < length));
    bounds.push(length);
    for (i, w) in bounds.windows(2).enumerate() {
        // Skip gaps too narrow for a rounded sample point to fall inside.
        if w[1] - w[0] <= 1e-9 * length {
            continue;
        }
        let p = ray.at(0.5 * (w[0] + w[1]));
        let implied = if i % 2 == 1 {
            Containment::Inside
        } else {
            Containment::Outside
        };
        let exact = match rational_parity::classify(triangles, p) {
            Class::Inside => Containment::Inside,
            Class::Outside => Containment::Outside,
            Class::Boundary => Containment::OnBoundary,
        };
        if exact != implied && exact != Containment::OnBoundary {
            return Some(format!(
                "between t={} and t={}: implied {implied:?}, exact {exact:?}",
                w[0], w[1]
            ));
        }
    }
    None
}

/// Equal within the comparison tolerance (1e-9 relative).
fn same_t(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-9 * a.abs().max(b.abs()).max(1.0)
}

/// The list without touches: pairs of consecutive crossings at the same `t`
/// (the ray meets the boundary at a point or along a zero-length span and
/// stays on the same side). Such a pair changes nothing about which points of
/// the ray are inside.
fn without_touches(ts: &[f64]) -> Vec<f64> {
    let mut out = Vec::with_capacity(ts.len());
    let mut i = 0;
    while i < ts.len() {
        if i + 1 < ts.len() && same_t(ts[i], ts[i + 1]) {
            i += 2;
        } else {
            out.push(ts[i]);
            i += 1;
        }
    }
    out
}

fn same_list(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(&x, &y)| same_t(x, y))
}

#[test]
fn ray_crossings_agree_with_manifold3d_ray_cast() {
    let (dir, report) = oracle();
    let mut total_rays = 0;
    let mut differences = 0;
    let mut touches = 0;
    for (name, expected) in report["meshes"].as_object().expect("meshes") {
        let solid = load(dir, name);
        let accel = Accel::new(&solid);
        let length = expected["ray_length"].as_f64().expect("ray_length");
        let rays = expected["rays"].as_array().expect("rays");
        let hits = expected["hits"].as_array().expect("hits");
        assert!(rays.len() >= 10_000, "{name}: {} rays", rays.len());
        let mut mesh_touches = 0;
        let mut reference = None;
        for (i, (r, h)) in rays.iter().zip(hits).enumerate() {
            let r: Vec<f64> = r
                .as_array()
                .expect("ray")
                .iter()
                .map(|x| x.as_f64().expect("f64"))
                .collect();
            let ray = Ray::new(DVec3::new(r[0], r[1], r[2]), DVec3::new(r[3], r[4], r[5]));
            let theirs: Vec<f64> = h
                .as_array()
                .expect("hits")
                .iter()
                .map(|x| x.as_f64().expect("t"))
                .collect();
            let ours = accel.ray_crossings(&ray).expect("valid ray");
            assert_eq!(
                ours.origin,
                Containment::Outside,
                "{name} ray {i}: origins lie outside"
            );
            let mine: Vec<f64> = ours
                .hits
                .iter()
                .map(|c| c.t)
                .filter(|&t| t <= length)
                .collect();
            total_rays += 1;
            if same_list(&mine, &theirs) {
                continue;
            }
            if same_list(&without_touches(&mine), &without_touches(&theirs)) {
                // A grazing ray: one side lists a touch (0 or 2 crossings at
                // one point), the other does not. Same inside set.
                touches += 1;
                mesh_touches += 1;
                if mesh_touches <= 3 {
                    println!(
                        "{name} ray {i}: touch listed differently: wingedge {mine:?}, manifold3d {theirs:?}"
                    );
                }
                continue;
            }
            differences += 1;
            // Allowed only where exact arithmetic shows which side is right:
            // ours must agree with exact point classification along the ray
            // and manifold3d's list must contradict it.
            let tris = reference.get_or_insert_with(|| triangles(&solid));
            let ours_wrong = contradiction(tris, &ray, &mine, length);
            let theirs_wrong = contradiction(tris, &ray, &theirs, length);
            println!(
                "{name} ray {i} {ray:?}: wingedge {mine:?}, manifold3d {theirs:?}; exact check: wingedge {}, manifold3d {}",
                ours_wrong.as_deref().unwrap_or("consistent"),
                theirs_wrong.as_deref().unwrap_or("consistent"),
            );
            assert!(
                ours_wrong.is_none(),
                "{name} ray {i}: wingedge contradicts exact classification"
            );
            assert!(
                theirs_wrong.is_some(),
                "{name} ray {i}: a difference that exact arithmetic does not settle"
            );
        }
    }
    println!(
        "{total_rays} rays compared: {touches} grazing touches listed differently, \
         {differences} other differences, each settled by exact arithmetic"
    );
    assert!(total_rays >= 100_000);
}

#[test]
fn valid_and_invalid_verdicts_agree_with_manifold3d_status() {
    let (dir, report) = oracle();
    let mut cases: Vec<(String, bool)> = report["meshes"]
        .as_object()
        .expect("meshes")
        .iter()
        .map(|(name, m)| (name.clone(), m["status"] == "NoError"))
        .collect();
    cases.extend(
        report["broken"]
            .as_object()
            .expect("broken meshes")
            .iter()
            .map(|(name, m)| (name.clone(), m["status"] == "NoError")),
    );
    let refused = cases.iter().filter(|(_, ok)| !ok).count();
    assert!(refused >= 7, "the oracle refuses {refused} meshes, not 7");
    for (name, manifold_ok) in cases {
        let import = import_obj(&dir.join(format!("{name}.obj")), &ObjOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let verdict = validate_import(&import, &Options::default()).expect("validates");
        println!(
            "{name}: manifold3d ok = {manifold_ok}, wingedge: {:?}",
            verdict.validity
        );
        assert_eq!(
            verdict.is_valid(),
            manifold_ok,
            "{name}: {:?}",
            verdict.violations.first()
        );
    }
}

/// The distance from `p` to the nearest triangle of a (triangulated) solid,
/// by brute force: only asked for the few points where answers differ.
fn distance_to_surface(solid: &Solid, p: DVec3) -> f64 {
    solid
        .faces()
        .flat_map(|(f, _)| {
            let corners: Vec<DVec3> = solid.face_vertices(f).map(|v| solid.position(v)).collect();
            (1..corners.len() - 1)
                .map(move |i| point_triangle_distance(p, corners[0], corners[i], corners[i + 1]))
        })
        .fold(f64::INFINITY, f64::min)
}

/// Euclidean distance from `p` to the closed triangle `abc` (Ericson's
/// closest-point regions).
fn point_triangle_distance(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return p.distance(a);
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return p.distance(b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return p.distance(a + ab * (d1 / (d1 - d3)));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return p.distance(c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return p.distance(a + ac * (d2 / (d2 - d6)));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return p.distance(b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))));
    }
    let denom = 1.0 / (va + vb + vc);
    p.distance(a + ab * (vb * denom) + ac * (vc * denom))
}

#[test]
fn csg_trees_agree_with_manifold3d_booleans() {
    let (dir, report) = oracle();
    let cases = report["csg"].as_array().expect("csg cases");
    assert!(cases.len() >= 3, "{} CSG cases", cases.len());
    let mut uniform = test_rng::uniform(0x5DEE_CE66_D1CE_4E5B);
    for case in cases {
        let scene_name = case["scene"].as_str().expect("scene");
        let scene =
            Scene::from_file(&dir.join(scene_name)).unwrap_or_else(|e| panic!("{scene_name}: {e}"));
        if case["empty"].as_bool() == Some(true) {
            // manifold3d's result is empty: no point of the box is inside
            // the tree.
            let bounds = scene.csg.bounds();
            let mut stats = Stats::default();
            for _ in 0..10_000 {
                let p = bounds.min + bounds.size() * DVec3::new(uniform(), uniform(), uniform());
                let ours = scene.csg.classify_point(p, &mut stats);
                assert_ne!(
                    ours,
                    Containment::Inside,
                    "{scene_name}: {p} inside an empty result"
                );
            }
            continue;
        }
        let result_name = case["result"]
            .as_str()
            .expect("result")
            .trim_end_matches(".obj");
        let result = load(dir, result_name);
        let accel = Accel::new(&result);
        let expected = case["volume"].as_f64().expect("volume");
        let bounds = scene.csg.bounds();
        let diagonal = bounds.diagonal();

        // (a) The ray-integrated volume converges to manifold3d's.
        let mut errors = Vec::new();
        for cells in [20.0, 40.0, 80.0, 160.0] {
            let estimate = scene
                .csg
                .try_volume(diagonal / cells)
                .expect("bounded tree");
            errors.push((
                estimate.spacing,
                (estimate.volume - expected).abs() / expected,
            ));
        }
        println!(
            "{scene_name}: manifold3d volume {expected}; relative errors by spacing {errors:?}"
        );
        let finest = errors.last().expect("four spacings").1;
        assert!(
            finest < 5e-3,
            "{scene_name}: volume off by {finest:e} at the finest spacing"
        );
        assert!(
            finest < errors[0].1.max(1e-4),
            "{scene_name}: no convergence {errors:?}"
        );

        // (b) CSG point classification equals point-in-polyhedron on
        // manifold3d's result mesh, except within a tiny distance of it.
        let tiny = 1e-9 * diagonal;
        let (mut differing, mut near) = (0, 0);
        let mut stats = Stats::default();
        for _ in 0..100_000 {
            let p = bounds.min + bounds.size() * DVec3::new(uniform(), uniform(), uniform());
            let ours = scene.csg.classify_point(p, &mut stats);
            let theirs = accel.classify(p).expect("finite point");
            if ours == theirs {
                continue;
            }
            differing += 1;
            let d = distance_to_surface(&result, p);
            if d <= tiny {
                near += 1;
            } else {
                panic!(
                    "{scene_name}: point {p} is {ours:?} in the tree, {theirs:?} in manifold3d's result, {d:e} from its surface"
                );
            }
        }
        println!(
            "{scene_name}: 100000 points, {differing} differ, all {near} within {tiny:e} of the result surface"
        );
        assert!(differing <= 10, "{scene_name}: {differing} points differ");
    }
}

#[test]
fn bundled_closed_fixtures_agree_with_manifold3d() {
    let (_, report) = oracle();
    let fixtures = report["fixtures"].as_object().expect("fixture answers");
    assert!(fixtures.len() >= 10, "{} fixtures judged", fixtures.len());
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures/valid");
    for (name, expected) in fixtures {
        let import = import_obj(&dir.join(name), &ObjOptions::default())
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        let ours = validate_import(&import, &Options::default()).expect("validates");
        assert_eq!(
            ours.is_valid(),
            expected["status"] == "NoError",
            "{name}: {:?}",
            ours.validity
        );
        // Triangulating polygons adds as many edges as faces: χ is kept.
        let euler = ours.vertices as i64 - ours.edges as i64 + ours.faces as i64;
        assert_eq!(
            Some(euler),
            expected["euler"].as_i64(),
            "{name}: Euler characteristic"
        );
        if ours.shells == 1 {
            assert_eq!(ours.genus, expected["genus"].as_i64(), "{name}: genus");
        }
        let volume = expected["volume"].as_f64().expect("volume");
        let ours_volume = ours.volume.expect("closed");
        assert!(
            (ours_volume - volume).abs() <= 1e-9 * volume.abs(),
            "{name}: volume {ours_volume} vs manifold3d {volume}"
        );
        println!(
            "{name}: valid, χ {euler}, genus {:?}, volume {ours_volume} (manifold3d {volume})",
            ours.genus
        );
    }
}

/// The reference that settles disputes is itself checked on a cube, where
/// every answer is known: inside, outside, on faces, edges and corners, and
/// one ulp either side of a face (rays through the cube's edges and corners
/// are degenerate and make it try other directions).
#[test]
fn the_exact_reference_knows_a_cube_to_the_ulp() {
    let cube = triangles(&wingedge::mesh::builders::cube());
    let one = 1.0f64;
    let cases = [
        (DVec3::ZERO, Class::Inside),
        (DVec3::new(0.5, 0.5, 0.5), Class::Inside),
        (DVec3::new(one.next_down(), 0.3, -0.7), Class::Inside),
        (DVec3::new(one.next_up(), 0.3, -0.7), Class::Outside),
        (DVec3::new(1.0, 0.3, -0.7), Class::Boundary),
        (DVec3::new(1.0, 1.0, 0.25), Class::Boundary),
        (DVec3::new(-1.0, -1.0, -1.0), Class::Boundary),
        (DVec3::new(2.0, 2.0, 2.0), Class::Outside),
        (DVec3::new(1e-300, -1e-300, 5e-324), Class::Inside),
        (DVec3::new(-3.0, 0.0, 0.0), Class::Outside),
    ];
    for (p, want) in cases {
        assert_eq!(rational_parity::classify(&cube, p), want, "{p}");
    }
}

/// The profile, revolve and extrude cases of the oracle: `(profile, n or
/// height, manifold3d's volume)`.
fn profile_cases(key: &str, parameter: &str) -> Vec<(Vec<wingedge::glam::DVec2>, f64, f64)> {
    let (_, report) = oracle();
    let cases = report[key].as_array().expect("profile cases");
    assert!(cases.len() >= 3, "{} {key} cases", cases.len());
    cases
        .iter()
        .map(|c| {
            let profile = c["profile"]
                .as_array()
                .expect("profile")
                .iter()
                .map(|p| wingedge::glam::DVec2::new(p[0].as_f64().unwrap(), p[1].as_f64().unwrap()))
                .collect();
            (
                profile,
                c[parameter].as_f64().unwrap(),
                c["volume"].as_f64().unwrap(),
            )
        })
        .collect()
}

/// manifold3d's `CrossSection` rounds vertices to its own grid (Clipper2's
/// fixed precision), so its volumes of the same tessellation differ from
/// the exact ones in the 8th digit: the comparison allows that, no more.
const CROSS_SECTION_ROUNDING: f64 = 1e-7;

#[test]
fn revolves_and_extrusions_agree_with_manifold3d() {
    use wingedge::curve::BSpline;
    use wingedge::shape::{RevolveAxis, Segments, try_revolve, try_sweep};
    for (profile, segments, theirs) in profile_cases("revolve", "segments") {
        let solid = try_revolve(
            &profile,
            &RevolveAxis::Z,
            std::f64::consts::TAU,
            Segments::Count(segments as usize),
        )
        .unwrap_or_else(|e| panic!("{profile:?}: {e}"));
        solid.check_consistency().unwrap();
        let relative = (solid.volume() - theirs).abs() / theirs;
        println!(
            "revolve {profile:?} × {segments}: {} vs manifold3d {theirs} ({relative:.1e})",
            solid.volume()
        );
        assert!(
            relative <= CROSS_SECTION_ROUNDING,
            "{profile:?}: {} vs {theirs}",
            solid.volume()
        );
    }
    for (profile, height, theirs) in profile_cases("extrude", "height") {
        let path =
            BSpline::try_open_uniform(vec![DVec3::ZERO, DVec3::new(0.0, 0.0, height)], 1).unwrap();
        let solid = try_sweep(&profile, &path, 1e-3).unwrap_or_else(|e| panic!("{profile:?}: {e}"));
        let relative = (solid.volume() - theirs).abs() / theirs;
        println!(
            "extrude {profile:?} × {height}: {} vs manifold3d {theirs} ({relative:.1e})",
            solid.volume()
        );
        assert!(
            relative <= CROSS_SECTION_ROUNDING,
            "{profile:?}: {} vs {theirs}",
            solid.volume()
        );
    }
}

/// The volume where exactly one of two closed solids is inside, integrated
/// along a 64 × 64 grid of parallel rays over their common box (a
/// direction off the axes, so that no ray runs along a face): each ray
/// contributes the length of its inside spans that the two do not share.
fn symmetric_difference_by_rays(a: &Solid, b: &Solid) -> f64 {
    let (ba, bb) = (a.bounding_box(), b.bounding_box());
    let (lo, hi) = (ba.min.min(bb.min), ba.max.max(bb.max));
    let size = hi - lo;
    let direction = DVec3::new(1e-3 * 2f64.sqrt(), 1e-3 * 3f64.sqrt(), 1.0);
    let spans = |accel: &Accel, ray: &Ray| -> Vec<(f64, f64)> {
        let answer = accel.ray_crossings(ray).expect("a valid ray");
        assert_eq!(answer.origin, Containment::Outside);
        let mut spans = Vec::new();
        let mut entered = None;
        for hit in &answer.hits {
            match hit.transition {
                Transition::Enter => entered = Some(hit.t),
                Transition::Exit => spans.push((entered.take().expect("an entry first"), hit.t)),
            }
        }
        spans
    };
    let (accel_a, accel_b) = (Accel::new(a), Accel::new(b));
    let n = 64;
    let cell = DVec3::new(size.x / n as f64, size.y / n as f64, 0.0);
    let mut volume = 0.0;
    for i in 0..n {
        for j in 0..n {
            let origin = DVec3::new(
                lo.x + (i as f64 + 0.5) * cell.x,
                lo.y + (j as f64 + 0.5) * cell.y,
                lo.z - 1.0,
            ) - direction * (0.1 * size.z);
            let ray = Ray::new(origin, direction);
            let (sa, sb) = (spans(&accel_a, &ray), spans(&accel_b, &ray));
            // |A xor B| = |A| + |B| − 2 |A ∩ B| along the ray.
            let length = |s: &[(f64, f64)]| s.iter().map(|(t0, t1)| t1 - t0).sum::<f64>();
            let mut common = 0.0;
            for &(a0, a1) in &sa {
                for &(b0, b1) in &sb {
                    common += (a1.min(b1) - a0.max(b0)).max(0.0);
                }
            }
            volume += (length(&sa) + length(&sb) - 2.0 * common) * direction.length();
        }
    }
    // Each ray stands for a cell of the grid, seen along the direction.
    volume * cell.x * cell.y / direction.length() * direction.z
}

/// Boundary evaluation of manifold3d's seeded random trees (mesh leaves of
/// spheres, boxes, cylinders and tori, rotated and offset) gives manifold3d's
/// boolean result: the same volume to 1e-9 relative, the same genus and
/// number of shells, wingedge's own validator accepts it, and the
/// symmetric difference of the two results, integrated along rays, is below
/// 1e-9 of the volume (both evaluate the same leaf triangles, so only the
/// rounding of constructed points may differ).
#[test]
fn boundary_evaluation_agrees_with_manifold3d_booleans() {
    let (dir, report) = oracle();
    let cases = report["csg"].as_array().expect("csg cases");
    assert!(cases.len() >= 8, "{} CSG cases", cases.len());
    let mut evaluated = 0;
    for case in cases {
        let scene_name = case["scene"].as_str().expect("scene");
        let scene =
            Scene::from_file(&dir.join(scene_name)).unwrap_or_else(|e| panic!("{scene_name}: {e}"));
        let result =
            wingedge::csg::evaluate(&scene.csg, &wingedge::csg::EvaluateOptions::default())
                .unwrap_or_else(|e| panic!("{scene_name}: {e}"));
        let expected = case["volume"].as_f64().expect("volume");
        let volume = result.solid.volume();
        println!(
            "{scene_name}: volume {volume} vs manifold3d {expected}; genus {:?} vs {}; shells {} vs {}",
            result.report.genus, case["genus"], result.report.shells, case["shells"]
        );
        if case["empty"].as_bool() == Some(true) {
            assert_eq!(
                result.solid.face_count(),
                0,
                "{scene_name}: manifold3d's result is empty"
            );
            continue;
        }
        assert_eq!(
            result.report.validity,
            wingedge::validate::Validity::ValidSolid,
            "{scene_name}"
        );
        assert!(
            (volume - expected).abs() <= 1e-9 * expected.abs(),
            "{scene_name}: volume {volume}, manifold3d {expected}"
        );
        let theirs = load(
            dir,
            case["result"]
                .as_str()
                .expect("result")
                .trim_end_matches(".obj"),
        );
        let apart = symmetric_difference_by_rays(&result.solid, &theirs);
        assert!(
            apart <= 1e-9 * expected.abs(),
            "{scene_name}: the two results differ by a volume of {apart}"
        );
        assert_eq!(
            result.report.shells as u64,
            case["shells"].as_u64().expect("shells"),
            "{scene_name}: shells"
        );
        if result.report.shells == 1 {
            assert_eq!(
                result.report.genus,
                case["genus"].as_i64(),
                "{scene_name}: genus"
            );
        }
        evaluated += 1;
    }
    assert!(evaluated >= 4, "only {evaluated} non-empty results");
}
