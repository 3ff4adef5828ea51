//! `wingedge repair`: what is written validates, the report is located,
//! exit codes, and `csg --resolve`.

use serde_json::Value;

use crate::common::cli::wingedge;
use crate::common::temp_dir::TempDir;

#[test]
fn a_broken_fixture_is_written_valid_with_a_located_report() {
    let dir = TempDir::new("repair-json");
    let out = dir.arg("fixed.obj");
    let (code, text, err) = wingedge(&[
        "repair",
        "fixtures/broken/degenerate_face.obj",
        "-o",
        &out,
        "--json",
    ]);
    assert_eq!(code, 0, "{text} {err}");
    let v: Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["validity"], "valid_solid", "{v}");
    assert_eq!(v["dropped"][0]["polygon"], 5);
    assert_eq!(v["dropped"][0]["at"], "line 12");
    let (code, text, _) = wingedge(&["validate", &out]);
    assert_eq!(code, 0, "{text}");
}

#[test]
fn a_hole_over_the_limit_exits_1_and_writes_nothing() {
    let dir = TempDir::new("repair-hole");
    let out = dir.arg("fixed.obj");
    let (code, text, err) = wingedge(&[
        "repair",
        "fixtures/broken/edge_in_one_face.obj",
        "-o",
        &out,
        "--max-hole-edges",
        "2",
    ]);
    assert_eq!(code, 1, "{text} {err}");
    assert!(text.contains("left open: a hole of 3 edges"), "{text}");
    assert!(err.contains("not written"), "{err}");
    assert!(!dir.path().join("fixed.obj").exists());
}

#[test]
fn a_sheet_gives_the_empty_result_saying_why() {
    let dir = TempDir::new("repair-sheet");
    let input = dir.write(
        "sheet.obj",
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n",
    );
    let out = dir.arg("empty.obj");
    let (code, text, err) = wingedge(&["repair", input.to_str().unwrap(), "-o", &out]);
    assert_eq!(code, 0, "{text} {err}");
    assert!(
        text.contains("empty result: the soup encloses no volume"),
        "{text}"
    );
}

#[test]
fn input_that_is_no_mesh_exits_2() {
    let dir = TempDir::new("repair-bad");
    let input = dir.write("bad.obj", "v 0 0 0\nf 1 2 3\n");
    let (code, _, err) = wingedge(&["repair", input.to_str().unwrap(), "-o", &dir.arg("x.obj")]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("error:"), "{err}");
}

#[test]
fn csg_refuses_a_broken_leaf_naming_resolve_and_takes_it_with_resolve() {
    let dir = TempDir::new("repair-csg");
    let root = env!("CARGO_MANIFEST_DIR");
    let scene = dir.write(
        "scene.json",
        format!(
            r#"{{"root": {{"union": [{{"mesh": "{root}/fixtures/broken/self_intersection.obj"}}, {{"box": {{"min": [0.5, 0.5, 0.5], "max": [2, 2, 2]}}}}]}}}}"#
        ),
    );
    let out = dir.arg("u.obj");
    let allow = ["--allow-path", root];
    let mut args = vec!["csg", scene.to_str().unwrap(), "-o", &out];
    args.extend_from_slice(&allow);
    let (code, _, err) = wingedge(&args);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--resolve"), "{err}");
    args.push("--resolve");
    let (code, text, err) = wingedge(&args);
    assert_eq!(code, 0, "{text} {err}");
    let (code, text, _) = wingedge(&["validate", &out]);
    assert_eq!(code, 0, "{text}");
}
