//! `wingedge validate`: exit codes, the JSON contract, unreadable input.

use std::path::PathBuf;

use serde_json::Value;

use crate::common::cli::wingedge;
use crate::common::temp_dir::TempDir;

fn json(args: &[&str]) -> (i32, Vec<Value>) {
    let mut all = vec!["validate", "--json"];
    all.extend_from_slice(args);
    let (code, out, err) = wingedge(&all);
    let value: Value = serde_json::from_str(&out).unwrap_or_else(|e| panic!("{e}: {out} {err}"));
    (code, value.as_array().expect("an array").clone())
}

#[test]
fn valid_files_exit_0() {
    let (code, out, _) = wingedge(&[
        "validate",
        "fixtures/valid/cube.obj",
        "fixtures/valid/hollow_ball.obj",
        "fixtures/valid/exporter_cube.obj",
    ]);
    assert_eq!(code, 0, "{out}");
    assert!(
        out.contains("fixtures/valid/cube.obj: valid closed solid"),
        "{out}"
    );
    assert!(out.contains("weld: merged 16 vertices"), "{out}");
}

#[test]
fn a_defect_exits_1_and_is_located() {
    let (code, out, _) = wingedge(&[
        "validate",
        "fixtures/valid/cube.obj",
        "fixtures/broken/non_manifold_vertex.obj",
    ]);
    assert_eq!(code, 1);
    assert!(out.contains("not a surface"), "{out}");
    assert!(
        out.contains("non_manifold_vertex: 1\n    vertex 3 (line 5) is a pinch point"),
        "{out}"
    );
}

#[test]
fn an_unreadable_file_exits_2_even_among_invalid_ones() {
    let (code, out, _) = wingedge(&[
        "validate",
        "fixtures/broken/duplicate_face.obj",
        "fixtures/no_such_file.obj",
    ]);
    assert_eq!(code, 2);
    assert!(
        out.contains("fixtures/no_such_file.obj: unreadable"),
        "{out}"
    );
}

#[test]
fn json_contract() {
    let (code, files) = json(&[
        "fixtures/valid/hollow_ball.obj",
        "fixtures/broken/edge_in_one_face.obj",
        "fixtures/broken/edge_in_more_than_two_faces.obj",
    ]);
    assert_eq!(code, 1);
    assert_eq!(files.len(), 3);
    for f in &files {
        for key in [
            "file",
            "valid",
            "vertices",
            "edges",
            "faces",
            "shells",
            "genus",
            "volume",
            "violations",
        ] {
            assert!(f.get(key).is_some(), "missing {key} in {f}");
        }
        for v in f["violations"].as_array().unwrap() {
            assert!(v["rule"].is_string() && v["message"].is_string(), "{v}");
            assert!(v["line"].is_u64(), "{v}");
        }
    }
    let ball = &files[0];
    assert_eq!(ball["valid"], true);
    assert_eq!(ball["shells"], 2);
    assert_eq!(ball["genus"], 0);
    assert!(ball["volume"].as_f64().unwrap() > 0.0);
    assert_eq!(ball["violations"].as_array().unwrap().len(), 0);

    let holed = &files[1];
    assert_eq!(holed["valid"], false);
    assert_eq!(holed["genus"], Value::Null);
    assert_eq!(holed["volume"], Value::Null);
    assert_eq!(holed["counts"]["edge_in_one_face"], 3);
    assert_eq!(holed["holes"], 1);
    let first = &holed["violations"][0];
    assert_eq!(first["rule"], "edge_in_one_face");

    let fin = &files[2];
    assert_eq!(fin["violations"][0]["rule"], "edge_in_more_than_two_faces");
    assert_eq!(fin["violations"][0]["line"], 19);
    assert_eq!(fin["violations"][0]["faces"].as_array().unwrap().len(), 4);
}

#[test]
fn unreadable_input_names_file_and_line() {
    let scratch = TempDir::new("cli-validate");
    let dir = std::env::temp_dir();
    let cases: Vec<(PathBuf, Option<u64>, &str)> = vec![
        (PathBuf::from("fixtures/missing.obj"), None, "cannot read"),
        (dir.clone(), None, "is a directory"),
        (
            scratch.write("junk.obj", b"v 0 0 0\n\x00\x01\x02\xff\xfe"),
            Some(2),
            "binary",
        ),
        (
            scratch.write("zero.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n"),
            Some(4),
            "index 0",
        ),
        (
            scratch.write("range.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
            Some(4),
            "out of range",
        ),
        (
            scratch.write("nan.obj", b"v 0 0 0\nv 1 inf 0\nv 0 1 0\nf 1 2 3\n"),
            Some(2),
            "non-finite",
        ),
        (
            scratch.write("two.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\n\nf 1 2\n"),
            Some(5),
            "at least 3 corners",
        ),
    ];
    for (path, line, words) in cases {
        let p = path.to_string_lossy().into_owned();
        let (code, files) = json(&[&p]);
        assert_eq!(code, 2, "{p}");
        let f = &files[0];
        assert_eq!(f["valid"], false);
        let error = f["error"].as_str().unwrap();
        assert!(error.contains(words), "{p}: {error}");
        assert!(error.starts_with(&p), "{p}: {error}");
        assert_eq!(f["line"].as_u64(), line, "{p}: {error}");
        if let Some(l) = line {
            assert!(error.contains(&format!(":{l}:")), "{error}");
        }
    }
}

#[test]
fn weld_flags() {
    let scratch = TempDir::new("cli-validate");
    let (code, files) = json(&["--no-weld", "fixtures/valid/exporter_cube.obj"]);
    assert_eq!(code, 1);
    assert_eq!(files[0]["weld"]["merged"], 0);
    assert_eq!(files[0]["counts"]["edge_in_one_face"], 24);
    // Nudge one corner copy by 1e-9: the exact weld leaves an open seam, a
    // tolerant weld closes it.
    let text = std::fs::read_to_string("fixtures/valid/exporter_cube.obj")
        .unwrap()
        .replacen("v 0 0 0\n", "v 0 0 1e-9\n", 1);
    let nudged = scratch.write("nudged.obj", text.as_bytes());
    let p = nudged.to_string_lossy().into_owned();
    let (code, _) = json(&[&p]);
    assert_eq!(code, 1);
    let (code, files) = json(&["--weld", "1e-6", &p]);
    assert_eq!(code, 0, "{files:?}");
    assert_eq!(files[0]["weld"]["merged"], 16);
}

#[test]
fn bad_tolerances_are_refused() {
    for flag in ["--weld=-1", "--planarity=NaN"] {
        let (code, _, err) = wingedge(&["validate", flag, "fixtures/valid/cube.obj"]);
        assert_eq!(code, 2, "{err}");
        assert!(err.contains("tolerance"), "{err}");
    }
}

#[test]
fn indices_at_the_ends_of_i64_are_errors_naming_the_line() {
    // The no-panic audit: `-9223372036854775808` has no positive
    // counterpart in `i64`, and texture or normal indices far out of range
    // once overflowed inside the OBJ parser.
    let tetra = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nvt 0 0\nvn 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\n";
    let scratch = TempDir::new("cli-validate");
    for (name, face) in [
        ("min.obj", "f 3 1 -9223372036854775808\n"),
        ("max.obj", "f 3 1 9223372036854775807\n"),
        ("vn.obj", "f 3/1/-125 1 4\n"),
        ("vt.obj", "f 3/6148914691236517207 1 4\n"),
    ] {
        let path = scratch.write(name, format!("{tetra}{face}"));
        let (code, out, err) = wingedge(&["validate", path.to_str().expect("path")]);
        assert_eq!(code, 2, "{name}: {out}{err}");
        let located = format!("{}:10:", path.display());
        assert!(out.contains(&located), "{name}: {out}");
    }
}

/// The empty solid is a solid: what `csg` writes for an empty result (a
/// comment, no vertices, no faces), an empty file and a file of comments
/// validate as it, exit 0; vertices without faces stay unreadable.
#[test]
fn empty_files_are_the_empty_solid() {
    let scratch = TempDir::new("cli-validate-empty");
    for (name, text) in [
        ("empty.obj", ""),
        ("comments.obj", "# nothing\n\n# here\n"),
        ("written.obj", "# the empty solid: no vertices, no faces\n"),
    ] {
        let path = scratch.write(name, text.as_bytes());
        let p = path.to_string_lossy().into_owned();
        let (code, files) = json(&[&p]);
        assert_eq!(code, 0, "{p}: {files:?}");
        assert_eq!(files[0]["valid"], true, "{p}");
        assert_eq!(files[0]["validity"], "empty", "{p}: {files:?}");
        assert_eq!(files[0]["faces"], 0, "{p}");
    }
    let only = scratch.write("only.obj", b"v 0 0 0\nv 1 0 0\n");
    let (code, files) = json(&[&only.to_string_lossy()]);
    assert_eq!(code, 2, "{files:?}");
}

/// The size and pixels of a PNG file.
fn read_png(path: &std::path::Path) -> (u32, u32, Vec<[u8; 3]>) {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(std::io::BufReader::new(file))
        .read_info()
        .expect("a PNG header");
    let mut bytes = vec![0; reader.output_buffer_size().expect("a size")];
    let info = reader.next_frame(&mut bytes).expect("a PNG image");
    assert_eq!(info.color_type, png::ColorType::Rgb);
    let pixels = bytes[..info.buffer_size()]
        .chunks(3)
        .map(|c| [c[0], c[1], c[2]])
        .collect();
    (info.width, info.height, pixels)
}

#[test]
fn image_draws_the_defects_at_the_size_asked_and_keeps_the_exit_code() {
    let dir = TempDir::new("validate-image");
    let picture = dir.path().join("hole.png");
    let (code, out, err) = wingedge(&[
        "validate",
        "fixtures/broken/edge_in_one_face.obj",
        "--image",
        &picture.display().to_string(),
        "--image-size",
        "320x200",
    ]);
    assert_eq!(code, 1, "{out}{err}");
    assert!(out.contains("edge_in_one_face: 3"), "{out}");
    let (width, height, pixels) = read_png(&picture);
    assert_eq!((width, height), (320, 200));
    let rim = wingedge::render::defect_colour(wingedge::validate::Rule::EdgeInOneFace);
    let drawn = pixels.iter().filter(|&&p| p == rim).count();
    // The legend's 7 × 7 swatch at this width, and the rim's lines.
    assert!(drawn > 49 + 50, "{drawn} pixels in the rim's colour");
}

#[test]
fn image_of_a_valid_solid_exits_0_and_is_800_by_600() {
    let dir = TempDir::new("validate-image-valid");
    let picture = dir.path().join("cube.png");
    let (code, out, err) = wingedge(&[
        "validate",
        "fixtures/valid/cube.obj",
        "--image",
        &picture.display().to_string(),
    ]);
    assert_eq!(code, 0, "{out}{err}");
    let (width, height, pixels) = read_png(&picture);
    assert_eq!((width, height), (800, 600));
    assert!(
        pixels.iter().all(|p| p[0] == p[1] && p[1] == p[2]),
        "greys only"
    );
}

#[test]
fn image_refuses_several_files_and_writes_nothing() {
    let dir = TempDir::new("validate-image-two");
    let picture = dir.path().join("two.png");
    let (code, out, err) = wingedge(&[
        "validate",
        "fixtures/valid/cube.obj",
        "fixtures/broken/edge_in_one_face.obj",
        "--image",
        &picture.display().to_string(),
    ]);
    assert_eq!(code, 2, "{out}");
    assert!(
        err.contains("--image draws one file's defects, but 2 files were given"),
        "{err}"
    );
    assert!(!picture.exists());
    let (code, _, err) = wingedge(&[
        "validate",
        "fixtures/valid/cube.obj",
        "--image-size",
        "10x10",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("--image"), "{err}");
}
