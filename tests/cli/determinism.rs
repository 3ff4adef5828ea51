//! The same input gives byte-identical output across runs and across
//! thread counts: `validate --json`, `classify`, `raycast`, `volume` and
//! `render` are run on bundled fixtures with rayon's default pool (twice)
//! and with `RAYON_NUM_THREADS` = 1, 2 and 3, and every standard output and
//! every image must match the first run's bytes.

use crate::common::cli::run;
use crate::common::temp_dir::TempDir;

/// Thread settings to compare: the default pool (twice), then fixed sizes.
const THREADS: [Option<&str>; 5] = [None, None, Some("1"), Some("2"), Some("3")];

/// Seeded numbers in `[-2.5, 2.5)` (a 64-bit LCG), written `n` per line.
fn seeded_lines(lines: usize, per_line: usize, mut state: u64) -> String {
    let mut text = String::new();
    for _ in 0..lines {
        let row: Vec<String> = (0..per_line)
            .map(|_| {
                state = state
                    .wrapping_mul(6_364_136_223_846_793_005)
                    .wrapping_add(1_442_695_040_888_963_407);
                let unit = (state >> 11) as f64 / (1u64 << 53) as f64;
                format!("{}", unit * 5.0 - 2.5)
            })
            .collect();
        text += &row.join(" ");
        text.push('\n');
    }
    text
}

/// Runs `args` under every thread setting; `output` names a file the
/// command writes (`{}` in `args` is replaced by a fresh path for it).
/// Returns the first run's standard output.
fn same_bytes_everywhere(dir: &TempDir, args: &[&str]) -> Vec<u8> {
    let mut first: Option<(Vec<u8>, Option<Vec<u8>>)> = None;
    for (k, threads) in THREADS.iter().enumerate() {
        let file = dir.arg(&format!("out-{k}.png"));
        let args: Vec<&str> = args
            .iter()
            .map(|&a| if a == "{}" { file.as_str() } else { a })
            .collect();
        let env: Vec<(&str, &str)> = threads.iter().map(|&n| ("RAYON_NUM_THREADS", n)).collect();
        let o = run(&args, "", &env);
        assert!(o.code <= 1, "{args:?}: exit {}: {}", o.code, o.stderr);
        let written = args.contains(&file.as_str()).then(|| {
            std::fs::read(&file).unwrap_or_else(|e| panic!("{args:?} wrote no {file}: {e}"))
        });
        match &first {
            None => first = Some((o.stdout, written)),
            Some((stdout, image)) => {
                assert!(
                    *stdout == o.stdout,
                    "{args:?}: standard output differs with RAYON_NUM_THREADS={threads:?}"
                );
                assert!(
                    *image == written,
                    "{args:?}: the written file differs with RAYON_NUM_THREADS={threads:?}"
                );
            }
        }
    }
    first.expect("at least one run").0
}

#[test]
fn validate_json_is_byte_identical() {
    let dir = TempDir::new("determinism-validate");
    let out = same_bytes_everywhere(
        &dir,
        &[
            "validate",
            "--json",
            "fixtures/valid/hollow_ball.obj",
            "fixtures/valid/double_torus_genus2.obj",
            "fixtures/valid/exporter_cube.obj",
            "fixtures/broken/self_intersection.obj",
            "fixtures/broken/edge_in_more_than_two_faces.obj",
            "fixtures/broken/non_planar_face.obj",
            "fixtures/real/suzanne.obj",
            "fixtures/real/teapot.obj",
        ],
    );
    // Volumes and areas are printed: their last bits are compared too.
    assert!(String::from_utf8_lossy(&out).contains("\"area\""));
}

#[test]
fn classify_and_raycast_are_byte_identical() {
    let dir = TempDir::new("determinism-query");
    let points = dir.write("points.txt", seeded_lines(3000, 3, 1));
    let rays = dir.write("rays.txt", seeded_lines(3000, 6, 2));
    let (points, rays) = (points.to_string_lossy(), rays.to_string_lossy());
    for target in [
        "fixtures/valid/torus_genus1.obj",
        "fixtures/scenes/drilled_cube.json",
        "fixtures/scenes/platonic.json",
    ] {
        let out = same_bytes_everywhere(&dir, &["classify", target, &points]);
        assert_eq!(out.iter().filter(|&&b| b == b'\n').count(), 3000);
        same_bytes_everywhere(&dir, &["raycast", target, &rays]);
    }
    same_bytes_everywhere(
        &dir,
        &[
            "classify",
            "fixtures/valid/double_torus_genus2.obj",
            &points,
            "--method",
            "winding",
        ],
    );
}

#[test]
fn volume_is_byte_identical() {
    let dir = TempDir::new("determinism-volume");
    for args in [
        &[
            "volume",
            "fixtures/scenes/drilled_cube.json",
            "--spacing",
            "0.02",
        ][..],
        &["volume", "fixtures/scenes/many_leaves.json"][..],
        &["volume", "fixtures/valid/torus_genus1.obj", "--integrate"][..],
    ] {
        let out = same_bytes_everywhere(&dir, args);
        assert!(String::from_utf8_lossy(&out).trim().parse::<f64>().is_ok());
    }
}

#[test]
fn render_is_byte_identical() {
    let dir = TempDir::new("determinism-render");
    for scene in [
        "fixtures/scenes/drilled_cube.json",
        "fixtures/scenes/platonic.json",
    ] {
        same_bytes_everywhere(&dir, &["render", scene, "-o", "{}", "--size", "96x72"]);
    }
}
