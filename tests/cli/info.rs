//! The `wingedge info` command on bundled fixtures and built-ins.

use crate::common::cli::wingedge;
use crate::common::temp_dir::TempDir;

#[test]
fn info_on_the_bundled_dodecahedron() {
    let (code, out, _) = wingedge(&["info", "fixtures/valid/dodecahedron.obj"]);
    assert_eq!(code, 0);
    assert!(
        out.contains("vertices 20  edges 30  faces 12  euler characteristic 2"),
        "{out}"
    );
    assert!(out.contains("genus 0"), "{out}");
    assert!(out.contains("volume 14.4721359550"), "{out}");
}

#[test]
fn info_on_builtins_and_bad_names() {
    let (code, out, _) = wingedge(&["info", "--builtin", "prism"]);
    assert_eq!(code, 0);
    assert!(out.contains("volume 3.0000000000"), "{out}");
    let (code, _, err) = wingedge(&["info", "--builtin", "sphere"]);
    assert_eq!(code, 2);
    assert!(err.contains("unknown built-in solid 'sphere'"), "{err}");
}

#[test]
fn info_on_a_missing_file_is_an_error_naming_it() {
    let (code, _, err) = wingedge(&["info", "fixtures/no-such-file.obj"]);
    assert_eq!(code, 2);
    assert!(err.contains("fixtures/no-such-file.obj"), "{err}");
}

/// A valid tetrahedron with coordinates up to 1e308: its topology and
/// checks are exact, but its volume and area overflow `f64`. Every command
/// says so, in words and with a non-zero exit, never a bare NaN.
#[test]
fn measures_that_overflow_are_reported_not_printed_as_nan() {
    let dir = TempDir::new("overflow");
    let tet = dir.write(
        "tet.obj",
        "v 0 0 0\nv 1e308 0 0\nv 0 1e308 0\nv 0 0 1e308\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n",
    );
    let tet = tet.to_str().expect("a UTF-8 temp path");

    let (code, out, _) = wingedge(&["validate", tet]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("valid closed solid"), "{out}");
    assert!(out.contains("volume overflow  area overflow"), "{out}");
    assert!(
        out.contains("warning: volume, area, shell volume overflow f64"),
        "{out}"
    );
    assert!(!out.contains("NaN") && !out.contains("inf"), "{out}");

    let (code, out, _) = wingedge(&["validate", "--json", tet]);
    assert_eq!(code, 1);
    let report: serde_json::Value = serde_json::from_str(&out).expect("JSON");
    assert_eq!(
        report[0]["overflow"],
        serde_json::json!(["volume", "area", "shell volume"])
    );
    assert!(report[0]["volume"].is_null());

    let (code, out, err) = wingedge(&["info", tet]);
    assert_eq!(code, 1);
    assert!(
        out.contains("volume overflow  surface area overflow"),
        "{out}"
    );
    assert!(
        out.contains("bounding box (0, 0, 0) .. (1e308, 1e308, 1e308)"),
        "{out}"
    );
    assert!(err.contains("overflows f64"), "{err}");

    let (code, out, err) = wingedge(&["volume", tet]);
    assert_eq!(code, 2);
    assert!(out.is_empty(), "{out}");
    assert!(err.contains("overflows f64"), "{err}");
}

#[test]
fn info_prints_rings_of_a_frame_and_writes_its_faces_with_holes_as_triangles() {
    let dir = std::env::temp_dir().join(format!("wingedge-info-frame-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("frame.obj");
    let (code, out, _) = wingedge(&[
        "info",
        "--builtin",
        "frame",
        "--write",
        path.to_str().unwrap(),
    ]);
    assert_eq!(code, 0);
    assert!(out.contains("shells 1  rings 2"), "{out}");
    assert!(
        out.contains("rings 2  boundary edges 0  χ 0  genus 1"),
        "{out}"
    );
    assert!(out.contains("volume 12.0000000000"), "{out}");
    // OBJ has no holes: the written file (top and bottom triangulated)
    // reads back as a valid closed solid of genus 1 with the same volume.
    let (code, out, _) = wingedge(&["info", path.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert!(out.contains("rings 0"), "{out}");
    assert!(out.contains("genus 1"), "{out}");
    assert!(out.contains("volume 12.0000000000"), "{out}");
    let (code, out, _) = wingedge(&["validate", path.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}");
    std::fs::remove_dir_all(&dir).unwrap();
}
