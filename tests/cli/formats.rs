//! The command line on every mesh format: `validate model.stl`, `--format`,
//! and `convert` (exit codes, what it writes, what it refuses to write).

use crate::common::cli::wingedge;
use crate::common::temp_dir::TempDir;

#[test]
fn validate_reads_stl_and_says_how_many_corners_were_welded() {
    let (code, out, err) = wingedge(&["validate", "fixtures/formats/torus.stl"]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.starts_with("fixtures/formats/torus.stl: valid closed solid\n  vertices 96  edges 288  faces 192  shells 1  holes 0  genus 1"), "{out}");
    assert!(out.contains("  weld: merged 480 corners\n"), "{out}");
    let (code, out, _) = wingedge(&[
        "validate",
        "--json",
        "fixtures/formats/two_boxes.3mf",
        "fixtures/formats/torus.glb",
    ]);
    assert_eq!(code, 0, "{out}");
    let reports: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(reports[0]["shells"], 2);
    assert_eq!(reports[1]["genus"], 1);
}

#[test]
fn every_command_that_reads_a_mesh_takes_format() {
    let dir = TempDir::new("format-flag");
    let bin = dir.write(
        "torus.bin",
        std::fs::read("fixtures/formats/torus.stl").unwrap(),
    );
    let bin = bin.to_str().unwrap();
    // Without --format an unknown extension reads as OBJ, as it always did.
    let (code, _, err) = wingedge(&["validate", bin]);
    assert_eq!(code, 2);
    assert!(err.is_empty());
    let (code, out, err) = wingedge(&["validate", "--format", "stl", bin]);
    assert_eq!(code, 0, "{out}{err}");
    let (code, out, _) = wingedge(&["info", "--format", "stl", bin]);
    assert_eq!(code, 0, "{out}");
    assert!(out.contains("vertices 96  edges 288  faces 192"), "{out}");
    let points = dir.write("points.txt", "0 0 0\n2 0 0\n");
    let (code, out, _) = wingedge(&["classify", "--format", "stl", bin, points.to_str().unwrap()]);
    assert_eq!((code, out.as_str()), (0, "outside\ninside\n"));
    let rays = dir.write("rays.txt", "-5 0 0 1 0 0\n");
    let (code, out, _) = wingedge(&["raycast", "--format", "stl", bin, rays.to_str().unwrap()]);
    assert_eq!(code, 0);
    assert_eq!(
        out.split_whitespace().count(),
        5,
        "outside and four crossings: {out}"
    );
    let (code, out, _) = wingedge(&["volume", "--format", "stl", bin]);
    assert_eq!(code, 0);
    assert!(out.starts_with("16.6311"), "{out}");
    let (code, out, _) = wingedge(&["cells", "--format", "stl", "--depth", "3", bin]);
    assert_eq!(code, 0, "{out}");
    let (code, _, err) = wingedge(&["validate", "--format", "stp", bin]);
    assert_eq!(code, 2);
    assert!(err.contains("unknown format `stp`"), "{err}");
}

#[test]
fn convert_writes_every_format_that_validates_as_the_input() {
    let dir = TempDir::new("convert");
    for to in ["obj", "stl", "ply", "off", "3mf", "gltf", "glb"] {
        let out_path = dir.arg(&format!("torus.{to}"));
        let (code, out, err) = wingedge(&["convert", "fixtures/formats/torus.ply", &out_path]);
        assert_eq!(code, 0, "{to}: {out}{err}");
        assert!(out.starts_with(&format!("fixtures/formats/torus.ply (ply: valid closed solid) -> {out_path} ({to}): vertices 96  faces 192")), "{out}");
        let (code, out, _) = wingedge(&["validate", &out_path]);
        assert_eq!(code, 0, "{to}: {out}");
        assert!(
            out.contains("vertices 96  edges 288  faces 192"),
            "{to}: {out}"
        );
    }
    // From STL: the corners welded are said.
    let (code, out, _) = wingedge(&[
        "convert",
        "fixtures/formats/torus.stl",
        &dir.arg("from_stl.off"),
    ]);
    assert_eq!(code, 0);
    assert!(
        out.contains("(stl, 480 corners welded: valid closed solid)"),
        "{out}"
    );
    // Coordinates f32 cannot hold: a warning with the count, on stderr.
    let (code, _, err) = wingedge(&[
        "convert",
        "fixtures/valid/dodecahedron.obj",
        &dir.arg("d.stl"),
    ]);
    assert_eq!(code, 0);
    assert!(
        err.starts_with(&format!("warning: {}: ", dir.arg("d.stl"))),
        "{err}"
    );
    assert!(
        err.contains("coordinates changed when rounded to f32 (stl holds 32-bit floats"),
        "{err}"
    );
    let (code, _, err) = wingedge(&[
        "convert",
        "fixtures/valid/dodecahedron.obj",
        &dir.arg("d.ply"),
    ]);
    assert_eq!((code, err.as_str()), (0, ""));
    // --to for an extension that names no format.
    let (code, _, err) = wingedge(&["convert", "fixtures/valid/cube.obj", &dir.arg("cube.mesh")]);
    assert_eq!(code, 2);
    assert!(
        err.contains("cannot tell the output format from the extension"),
        "{err}"
    );
    let (code, _, _) = wingedge(&[
        "convert",
        "fixtures/valid/cube.obj",
        &dir.arg("cube.mesh"),
        "--to",
        "off",
    ]);
    assert_eq!(code, 0);
}

#[test]
fn convert_refuses_what_is_not_a_solid_unless_allowed() {
    let dir = TempDir::new("convert-invalid");
    let target = dir.arg("hole.stl");
    let (code, out, _) = wingedge(&["convert", "fixtures/broken/edge_in_one_face.obj", &target]);
    assert_eq!(code, 1, "{out}");
    assert!(out.contains("edge_in_one_face: "), "the report: {out}");
    assert!(out.contains(&format!("{target}: not written: the input is not a valid closed solid (--allow-invalid writes it anyway)")), "{out}");
    assert!(!std::path::Path::new(&target).exists());
    let (code, out, _) = wingedge(&[
        "convert",
        "--allow-invalid",
        "fixtures/broken/edge_in_one_face.obj",
        &target,
    ]);
    assert_eq!(code, 0, "{out}");
    assert!(std::path::Path::new(&target).exists());
    let (code, _, _) = wingedge(&["validate", &target]);
    assert_eq!(code, 1, "the defect is still there");
    // Unreadable input: exit 2, the old output untouched.
    std::fs::write(&target, "old").unwrap();
    let (code, _, err) = wingedge(&["convert", "fixtures/formats/missing.stl", &target]);
    assert_eq!(code, 2);
    assert!(
        err.starts_with("error: fixtures/formats/missing.stl: cannot read"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&target).unwrap(), "old");
}
