//! `validate` in bounded memory: the whole command (reading, the soup, the
//! checks' context, the self-intersection check, whether the faces build)
//! peaks within 300 bytes per triangle plus a fixed 50 MB on large
//! generated meshes, an ordinary one and one of slivers.

use std::fmt::Write as _;

use crate::common::cli::run;
use crate::common::temp_dir::TempDir;

/// The budget: 300 bytes per triangle plus a fixed 50 MB.
fn budget(triangles: usize) -> u64 {
    300 * triangles as u64 + 50_000_000
}

/// A UV sphere's positions and triangles (0-based), the poles first.
fn uv_sphere(centre: [f64; 3], rings: usize, segments: usize) -> Mesh {
    let mut positions = vec![
        [centre[0], centre[1], centre[2] + 1.0],
        [centre[0], centre[1], centre[2] - 1.0],
    ];
    for i in 1..rings {
        let t = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..segments {
            let a = std::f64::consts::TAU * j as f64 / segments as f64;
            positions.push([
                centre[0] + t.sin() * a.cos(),
                centre[1] + t.sin() * a.sin(),
                centre[2] + t.cos(),
            ]);
        }
    }
    let ring = |i: usize, j: usize| 2 + (i - 1) * segments + j % segments;
    let mut triangles: Vec<[usize; 3]> = (0..segments)
        .map(|j| [0, ring(1, j), ring(1, j + 1)])
        .collect();
    for i in 1..rings - 1 {
        for j in 0..segments {
            triangles.push([ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)]);
            triangles.push([ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)]);
        }
    }
    triangles.extend((0..segments).map(|j| [1, ring(rings - 1, j + 1), ring(rings - 1, j)]));
    (positions, triangles)
}

/// Positions and triangles (0-based indices into them).
type Mesh = (Vec<[f64; 3]>, Vec<[usize; 3]>);

/// Meshes as the OBJ text of one soup.
fn obj(parts: &[Mesh]) -> String {
    let mut text = String::new();
    for (positions, _) in parts {
        for p in positions {
            writeln!(text, "v {:?} {:?} {:?}", p[0], p[1], p[2]).unwrap();
        }
    }
    let mut base = 1;
    for (positions, triangles) in parts {
        for t in triangles {
            writeln!(text, "f {} {} {}", base + t[0], base + t[1], base + t[2]).unwrap();
        }
        base += positions.len();
    }
    text
}

/// A closed cone of `n` rim vertices whose base is fanned from one rim
/// vertex: two hubs of `n` slivers each.
fn corner_fan_cone(n: usize) -> Mesh {
    let mut positions = vec![[0.0, 0.0, 1.0]];
    for k in 0..n {
        let a = std::f64::consts::TAU * k as f64 / n as f64;
        positions.push([a.cos(), a.sin(), 0.0]);
    }
    let mut triangles: Vec<[usize; 3]> = (0..n).map(|k| [0, 1 + k, 1 + (k + 1) % n]).collect();
    triangles.extend((1..n - 1).map(|k| [1, 2 + k, 1 + k]));
    (positions, triangles)
}

/// Validates `text` (of `triangles` triangles) and checks the command's
/// peak resident memory against the budget; returns its report.
#[cfg(target_os = "linux")]
fn validate_within_budget(name: &str, text: &str, triangles: usize) -> String {
    let dir = TempDir::new(name);
    let file = dir.write(&format!("{name}.obj"), text);
    let o = run(&["validate", &file.to_string_lossy()], "", &[]);
    let peak = o.peak_rss.expect("wait4 reports the peak on Linux");
    let limit = budget(triangles);
    assert!(
        peak <= limit,
        "{name}: validate peaked at {} MiB, over the budget of {} MiB for {triangles} triangles",
        peak >> 20,
        limit >> 20
    );
    assert!(
        o.code == 0 || o.code == 1,
        "{name}: {}{}",
        o.out(),
        o.stderr
    );
    o.out()
}

/// Two crossing spheres of 89,400 triangles each (the self-intersection
/// check finds the crossing, so whether the faces build is asked too):
/// within 300 bytes a triangle plus 50 MB (104 MB). The command took
/// 127 MB when the report's verdict built the whole solid beside a copy of
/// the soup, the check listed every edge's triangles at once, and freed
/// tables stayed resident.
#[cfg(target_os = "linux")]
#[test]
fn two_crossing_spheres_validate_within_the_memory_budget() {
    let a = uv_sphere([0.0; 3], 150, 300);
    let b = uv_sphere([1.2, 0.1, 0.05], 150, 300);
    let triangles = a.1.len() + b.1.len();
    assert_eq!(triangles, 178_800);
    let report = validate_within_budget("two-spheres", &obj(&[a, b]), triangles);
    assert!(report.contains("self_intersection: 1232"), "{report}");
}

/// A cone of 40,000 rim vertices with its base fanned from one of them:
/// 80,000 slivers around two hubs, cut into pieces for the check's trees,
/// within 300 bytes a triangle plus 50 MB (74 MB). The command took
/// 118 MB when every group's tree of pieces was held at once.
#[cfg(target_os = "linux")]
#[test]
fn a_cone_of_slivers_validates_within_the_memory_budget() {
    let cone = corner_fan_cone(40_000);
    let triangles = cone.1.len();
    let report = validate_within_budget("sliver-cone", &obj(&[cone]), triangles);
    assert!(report.contains("valid closed solid"), "{report}");
}
