//! The `wingedge mesh` command: field documents meshed into validated
//! solids, and the errors it gives for bad documents and grids.

use crate::common::cli::wingedge;
use crate::common::temp_dir::TempDir;
use wingedge::io::read_obj;
use wingedge::validate::{Options, validate_soup};

#[test]
fn three_blobs_mesh_into_a_valid_solid_written_as_obj() {
    let dir = TempDir::new("mesh_three_blobs");
    let out = dir.arg("three.obj");
    for extra in [&[][..], &["--midpoints"][..]] {
        let mut args = vec![
            "mesh",
            "fixtures/fields/three_blobs.json",
            "-o",
            &out,
            "--resolution",
            "24",
        ];
        args.extend_from_slice(extra);
        let (code, stdout, err) = wingedge(&args);
        assert_eq!(code, 0, "{stdout}{err}");
        assert!(stdout.contains("3 sources"), "{stdout}");
        assert!(stdout.contains("shells 1  genus 0"), "{stdout}");
        assert!(stdout.contains("valid closed solid"), "{stdout}");
        // The written file is itself a valid closed solid.
        let soup = read_obj(std::path::Path::new(&out)).unwrap();
        let report = validate_soup(&soup, None, &Options::default()).unwrap();
        assert!(report.is_valid(), "{:#?}", report.violations);
        let volume = report.volume.unwrap();
        assert!((volume - 9.67).abs() < 0.3, "{volume}");
    }
}

#[test]
fn the_document_resolution_is_used_unless_the_command_gives_one_and_stats_go_to_stderr() {
    let dir = TempDir::new("mesh_resolution");
    let out = dir.arg("three.obj");
    let (code, stdout, err) = wingedge(&[
        "mesh",
        "fixtures/fields/three_blobs.json",
        "-o",
        &out,
        "--stats",
    ]);
    assert_eq!(code, 0, "{err}");
    // Resolution 48 along the longest side (x: 5.1 units): 49 samples.
    assert!(stdout.contains("grid 49×"), "{stdout}");
    assert!(err.contains("source evaluations of 3 sources"), "{err}");
    let (code, stdout, _) = wingedge(&[
        "mesh",
        "fixtures/fields/three_blobs.json",
        "-o",
        &out,
        "--resolution",
        "8",
    ]);
    assert_eq!(code, 0);
    assert!(stdout.contains("grid 9×"), "{stdout}");
}

#[test]
fn field_csg_documents_mesh_too() {
    let dir = TempDir::new("mesh_csg");
    let doc = dir.write(
        "carved.json",
        r#"{"difference": [
            {"blobs": [{"center": [0, 0, 0], "radius": 2}, {"center": [1.2, 0, 0], "radius": 2}]},
            {"blobs": [{"center": [0.6, 0, 0.9], "radius": 1.2}]}]}"#,
    );
    let out = dir.arg("carved.obj");
    let (code, stdout, err) = wingedge(&[
        "mesh",
        doc.to_str().unwrap(),
        "-o",
        &out,
        "--resolution",
        "20",
    ]);
    assert_eq!(code, 0, "{stdout}{err}");
    assert!(stdout.contains("valid closed solid"), "{stdout}");
}

#[test]
fn an_empty_field_is_said_plainly_and_writes_nothing() {
    let dir = TempDir::new("mesh_empty");
    let out = dir.arg("empty.obj");
    for text in [
        r#"{"blobs": []}"#,
        r#"{"blobs": [{"center": [0, 0, 0], "radius": 1, "strength": -1}]}"#,
        r#"{"intersection": [{"blobs": [{"center": [0, 0, 0], "radius": 1}]}, {"blobs": [{"center": [5, 0, 0], "radius": 1}]}]}"#,
        // Influence boxes that only touch: flat bounds, nothing inside.
        r#"{"intersection": [{"blobs": [{"center": [0, 0, 0], "radius": 1}]}, {"blobs": [{"center": [2, 0, 0], "radius": 1}]}]}"#,
    ] {
        let doc = dir.write("empty.json", text);
        let (code, stdout, err) = wingedge(&["mesh", doc.to_str().unwrap(), "-o", &out]);
        assert_eq!(code, 1, "{text}: {stdout}{err}");
        assert!(
            stdout.contains("empty: the field is below 1/2 at every sample"),
            "{stdout}"
        );
        assert!(!std::path::Path::new(&out).exists());
    }
}

#[test]
fn bad_documents_and_grids_are_errors_naming_the_json_path_or_the_limit() {
    let dir = TempDir::new("mesh_errors");
    let out = dir.arg("out.obj");
    let cases = [
        (
            r#"{"blobs": [{"center": [0, 0, 0], "radius": 0}]}"#,
            "field.blobs[0].radius: expected a positive number, found 0",
        ),
        (
            r#"{"blobs": [{"center": [0, 0, 0], "radius": -1}]}"#,
            "field.blobs[0].radius: expected a positive number, found -1",
        ),
        (
            r#"{"union": [{"blobs": [{"center": [0, "NaN", 0], "radius": 1}]}]}"#,
            "field.union[0].blobs[0].center[1]: expected a finite number",
        ),
        (
            r#"{"resolution": 0, "blobs": []}"#,
            "field.resolution: expected a whole number ≥ 1, found 0",
        ),
        (
            r#"{"blobs": [{"center": [0, 0, 0], "radius": 1, "colour": 1}]}"#,
            "field.blobs[0]: unknown key \"colour\"",
        ),
        ("{\"blobs\": [", "line 1, column 11: not valid JSON"),
        (
            r#"{"blobs": [{"center": [0, 0, 0], "radius": 1e-300}]}"#,
            "field.blobs[0].radius: source 0 (radius 1e-300) is out of range",
        ),
    ];
    for (text, expected) in cases {
        let doc = dir.write("bad.json", text);
        let (code, _, err) = wingedge(&["mesh", doc.to_str().unwrap(), "-o", &out]);
        assert_eq!(code, 2, "{text}");
        assert!(err.contains(expected), "{text}: {err}");
    }
    let (code, _, err) = wingedge(&[
        "mesh",
        "fixtures/fields/three_blobs.json",
        "-o",
        &out,
        "--resolution",
        "0",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("the resolution must be at least 1 cell"),
        "{err}"
    );
    let (code, _, err) = wingedge(&[
        "mesh",
        "fixtures/fields/three_blobs.json",
        "-o",
        &out,
        "--resolution",
        "5000",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("the limit is 33554432"), "{err}");
    let (code, _, err) = wingedge(&["mesh", "fixtures/fields/none.json", "-o", &out]);
    assert_eq!(code, 2);
    assert!(
        err.contains("fixtures/fields/none.json: cannot read"),
        "{err}"
    );
}

/// A field document is read like every other input: bounded, and binary
/// data after valid JSON is refused, not ignored.
#[test]
fn binary_data_in_a_field_document_is_refused() {
    let dir = TempDir::new("field-binary");
    let doc = dir.write(
        "blob.json",
        b"{\"blobs\": [{\"center\": [0,0,0], \"radius\": 1}]}\0\xff\xfe",
    );
    let out = dir.path().join("out.obj");
    let o = crate::common::cli::run(
        &["mesh", doc.to_str().unwrap(), "-o", out.to_str().unwrap()],
        "",
        &[],
    );
    assert_eq!(o.code, 2, "{}", o.stderr);
    assert!(o.stderr.contains("binary data"), "{}", o.stderr);
    assert!(!out.exists());
}

/// A CSG scene meshes over its exact classification: the drilled cube (a
/// cube minus three cylinders) at two resolutions is a valid solid of genus
/// 5 whose volume is within half a cell times the surface area of the
/// exact boolean's, and closer at the finer grid; `validate` accepts the
/// file written.
#[test]
fn a_csg_scene_meshes_over_its_exact_classification() {
    let dir = TempDir::new("mesh_scene");
    let exact_out = dir.arg("exact.obj");
    let (code, _, err) = wingedge(&["csg", "fixtures/scenes/drilled_cube.json", "-o", &exact_out]);
    assert_eq!(code, 0, "{err}");
    let exact = read_obj(std::path::Path::new(&exact_out)).unwrap();
    let exact_solid = wingedge::mesh::Solid::try_from_soup(&exact).unwrap();
    let (volume, area) = (exact_solid.volume(), exact_solid.surface_area());
    let mut errors = Vec::new();
    for (resolution, cell) in [("24", 2.04 / 24.0), ("48", 2.04 / 48.0)] {
        let out = dir.arg(&format!("drilled_{resolution}.obj"));
        let (code, text, err) = wingedge(&[
            "mesh",
            "fixtures/scenes/drilled_cube.json",
            "-o",
            &out,
            "--resolution",
            resolution,
        ]);
        assert_eq!(code, 0, "{text}{err}");
        assert!(text.contains("nodes classified exactly"), "{text}");
        let (code, text, _) = wingedge(&["validate", &out]);
        assert_eq!(code, 0, "{text}");
        assert!(text.contains("genus 5"), "{text}");
        let meshed = read_obj(std::path::Path::new(&out)).unwrap();
        let report = validate_soup(&meshed, None, &Options::default()).unwrap();
        assert!(report.is_valid());
        let solid = wingedge::mesh::Solid::try_from_soup(&meshed).unwrap();
        let error = (solid.volume() - volume).abs();
        assert!(
            error <= 0.5 * cell * area,
            "{resolution}: {error} vs cell {cell}, area {area}"
        );
        errors.push(error);
    }
    assert!(errors[1] < errors[0], "{errors:?}");
}

/// Every other CSG scene among the fixtures meshes at 32 cells into a
/// solid that `validate` accepts, whose volume is within half a cell times
/// the surface area of the exact boolean's (`csg`); for the hundred-leaf
/// scene, whose exact boolean takes most of a minute, of the volume that
/// `volume` integrates along rays (with the meshed solid's area).
#[test]
fn every_csg_fixture_meshes_into_a_valid_solid_near_its_volume() {
    let dir = TempDir::new("mesh_fixtures");
    for (name, boolean) in [
        ("mesh_cut", true),
        ("platonic", true),
        ("turned_part", true),
        ("many_leaves", false),
    ] {
        let scene = format!("fixtures/scenes/{name}.json");
        let out = dir.arg(&format!("{name}.obj"));
        let (code, text, err) = wingedge(&["mesh", &scene, "-o", &out, "--resolution", "32"]);
        assert_eq!(code, 0, "{name}: {text}{err}");
        assert!(text.contains("nodes classified exactly"), "{name}: {text}");
        let cell: f64 = text
            .split("(cell ")
            .nth(1)
            .and_then(|t| t.split(')').next())
            .and_then(|c| c.parse().ok())
            .unwrap_or_else(|| panic!("{name}: no cell size in {text}"));
        let (code, report, _) = wingedge(&["validate", &out]);
        assert_eq!(code, 0, "{name}: {report}");
        let solid = |path: &str| {
            wingedge::mesh::Solid::try_from_soup(&read_obj(std::path::Path::new(path)).unwrap())
                .unwrap()
        };
        let meshed = solid(&out);
        let (reference, area) = if boolean {
            let exact_out = dir.arg(&format!("{name}_exact.obj"));
            let (code, _, err) = wingedge(&["csg", &scene, "-o", &exact_out]);
            assert_eq!(code, 0, "{name}: {err}");
            let exact = solid(&exact_out);
            (exact.volume(), exact.surface_area())
        } else {
            let (code, text, err) = wingedge(&["volume", &scene]);
            assert_eq!(code, 0, "{name}: {err}");
            let volume: f64 = text.lines().next().unwrap().trim().parse().unwrap();
            (volume, meshed.surface_area())
        };
        let error = (meshed.volume() - reference).abs();
        assert!(
            error <= 0.5 * cell * area,
            "{name}: volume {} against {reference}: {error} > half of cell {cell} × area {area}",
            meshed.volume()
        );
    }
}

/// A field document's error names the file, as every other message does.
#[test]
fn field_document_errors_name_the_file() {
    let dir = TempDir::new("mesh_named");
    let doc = dir.write("bad.json", r#"{"camera": 1}"#);
    let out = dir.arg("out.obj");
    let doc = doc.to_string_lossy().into_owned();
    let (code, _, err) = wingedge(&["mesh", &doc, "-o", &out]);
    assert_eq!(code, 2, "{err}");
    assert!(err.contains(&format!("{doc}: ")), "{err}");
    assert!(err.contains("unknown key \"camera\""), "{err}");
}
