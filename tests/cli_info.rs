//! The `wingedge info` command on bundled fixtures and built-ins.

mod common;

use common::cli::wingedge;

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
