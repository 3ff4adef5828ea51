//! The CSG commands on the bundled scenes.

use crate::common::cli::wingedge_stdin as wingedge;
use crate::common::temp_dir::TempDir;

const DRILLED: &str = "fixtures/scenes/drilled_cube.json";

#[test]
fn classify_prints_one_word_per_point() {
    let points = "0 0 0\n0.9 0.9 0.9\n# a comment\n1 0.8 0.8\n3 3 3\n0 0.75 0.75\n";
    let (code, out, err) = wingedge(&["classify", DRILLED, "-"], points);
    assert_eq!(code, 0, "{err}");
    assert_eq!(out, "outside\ninside\nboundary\noutside\ninside\n");
}

#[test]
fn classify_names_a_bad_line() {
    let (code, _, err) = wingedge(&["classify", DRILLED, "-"], "0 0 0\n1 2\n");
    assert_eq!(code, 2);
    assert!(err.contains("-:2:"), "{err}");
    // Non-finite points and zero directions are refused, not answered.
    let (code, out, err) = wingedge(&["classify", DRILLED, "-"], "0 0 0\nNaN 0 0\n");
    assert_eq!((code, out.as_str()), (2, ""), "{err}");
    assert!(err.contains("-:2:"), "{err}");
    let (code, _, err) = wingedge(&["raycast", DRILLED, "-"], "0 0 0 1 0 0\n5 5 5 0 0 0\n");
    assert_eq!(code, 2);
    assert!(err.contains("-:2:"), "{err}");
}

#[test]
fn raycast_prints_spans() {
    // Along the x axis: the x-drill removes everything; at y = z = 0.75 the
    // ray runs through the solid wall from x = −1 to 1.
    let rays = "-3 0 0 1 0 0\n-3 0.75 0.75 1 0 0\n0.9 0.9 0.9 1 0 0\n";
    let (code, out, err) = wingedge(&["raycast", DRILLED, "-", "--stats"], rays);
    assert_eq!(code, 0, "{err}");
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines[0], "outside");
    assert_eq!(lines[1], "outside [2, 4]");
    assert!(lines[2].starts_with("inside [0, 0.09999"), "{out}");
    assert!(err.contains("primitive ray tests"), "{err}");
}

#[test]
fn volume_of_a_scene_and_of_a_mesh() {
    let (code, out, err) = wingedge(&["volume", DRILLED, "--spacing", "0.01"], "");
    assert_eq!(code, 0, "{err}");
    let v: f64 = out.trim().parse().expect("a number");
    let r: f64 = 0.5;
    let exact = 8.0
        - (3.0 * std::f64::consts::PI * r * r * 2.0 - 16.0 * r.powi(3)
            + 8.0 * (2.0 - 2f64.sqrt()) * r.powi(3));
    assert!(((v - exact) / exact).abs() < 1e-3, "{v} vs {exact}");
    let (code, out, _) = wingedge(&["volume", "fixtures/scenes/many_leaves.json"], "");
    assert_eq!(code, 0);
    assert!(out.trim().parse::<f64>().is_ok(), "{out}");
}

#[test]
fn render_writes_a_png_of_the_asked_size() {
    let dir = TempDir::new("render");
    let png = dir.path().join("drilled.png");
    let png_arg = png.to_str().unwrap();
    let (code, _, err) = wingedge(
        &[
            "render", DRILLED, "-o", png_arg, "--size", "64x48", "--stats",
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    let bytes = std::fs::read(&png).unwrap();
    assert_eq!(&bytes[1..4], b"PNG");
    // IHDR: width and height, big-endian, at bytes 16..24.
    assert_eq!(u32::from_be_bytes(bytes[16..20].try_into().unwrap()), 64);
    assert_eq!(u32::from_be_bytes(bytes[20..24].try_into().unwrap()), 48);
    // No progress bar when standard error is not a terminal.
    assert!(!err.contains('#'), "{err}");
    // The drilled cube scene asks for shadows: shadow rays were cast.
    assert!(!err.contains("shadow rays 0"), "{err}");
    let (code, _, err) = wingedge(&["render", DRILLED, "-o", png_arg, "--size", "64by48"], "");
    assert_eq!(code, 2, "{err}");
}

#[test]
fn scene_errors_name_the_json_path() {
    let dir = TempDir::new("scene");
    let scene = dir.write(
        "bad.json",
        r#"{"root": {"difference": [{"box": {"min": [0,0,0], "max": [1,1,1]}}, {"sphere": {"center": [0,0,0], "radius": 0}}]}}"#,
    );
    let (code, _, err) = wingedge(&["volume", scene.to_str().unwrap()], "");
    assert_eq!(code, 2);
    assert!(err.contains("root.difference[1].sphere.radius"), "{err}");
}

/// `wingedge csg` evaluates the drilled cube into a solid that `validate`
/// accepts, whose volume is the ray-integrated volume within the error of
/// inscribing the cylinders (the result holds the true solid and loses at
/// most the ring between each cylinder and its inscribed prism).
#[test]
fn csg_writes_a_valid_solid_of_the_right_volume() {
    let dir = TempDir::new("csg-drilled");
    let out = dir.arg("drilled.obj");
    let (code, text, err) = wingedge(&["csg", DRILLED, "-o", &out, "--json"], "");
    assert_eq!(code, 0, "{err}");
    let report: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    assert_eq!(report["validity"], "valid_solid");
    assert_eq!(report["genus"], 5);
    assert_eq!(report["booleans"], 3);
    let (code, text, err) = wingedge(&["validate", &out], "");
    assert_eq!(code, 0, "{text}{err}");
    let (code, text, err) = wingedge(&["volume", &out], "");
    assert_eq!(code, 0, "{err}");
    let evaluated: f64 = text.split_whitespace().next().unwrap().parse().unwrap();
    let (_, text, _) = wingedge(&["volume", DRILLED], "");
    let integrated: f64 = text.split_whitespace().next().unwrap().parse().unwrap();
    // Three cylinders of volume π/2 each, radius error 1e-3: at most
    // 2e-3 of their volume comes back, plus the integration's own error.
    assert!(
        evaluated >= integrated - 1e-3 && evaluated <= integrated + 2e-3 * 3.0 * 1.6 + 1e-3,
        "evaluated {evaluated}, integrated {integrated}"
    );
    // A coarser tolerance gives fewer faces and is said in the text.
    let (code, text, err) = wingedge(&["csg", DRILLED, "-o", &out, "--tolerance", "0.05"], "");
    assert_eq!(code, 0, "{err}");
    assert!(text.contains("chord tolerance 0.05"), "{text}");
}

/// Bad input is refused with exit 2 and a located message.
#[test]
fn csg_refuses_what_it_cannot_evaluate() {
    let dir = TempDir::new("csg-bad");
    let out = dir.arg("out.obj");
    let (code, _, err) = wingedge(&["csg", "fixtures/scenes/nope.json", "-o", &out], "");
    assert_eq!(code, 2, "{err}");
    let (code, _, err) = wingedge(&["csg", DRILLED, "-o", &out, "--tolerance", "0"], "");
    assert_eq!(code, 2);
    assert!(err.contains("tolerance"), "{err}");
}

/// Balls resting on a slab touch it at one point each: the union is valid,
/// one shell for the slab and its boxes and one per ball. Boxes sharing an
/// edge touch along it.
#[test]
fn csg_evaluates_solids_touching_at_points() {
    let dir = TempDir::new("csg-touch");
    let out = dir.arg("out.obj");
    let (code, text, err) = wingedge(&["csg", "fixtures/scenes/many_leaves.json", "-o", &out], "");
    assert_eq!(code, 0, "{err}");
    assert!(text.contains("shells 51"), "{text}");
    let (code, text, err) = wingedge(&["validate", &out], "");
    assert_eq!(code, 0, "{err}");
    assert!(text.contains("valid closed solid"), "{text}");
    // Two boxes sharing an edge: the union touches itself along it, each
    // box a shell with its own edge there; the written OBJ keeps the two
    // edges (vertices at one position) and validates.
    let scene = dir.arg("edge.json");
    std::fs::write(
        &scene,
        r#"{"root": {"union": [
            {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}},
            {"box": {"min": [1, 1, 0], "max": [2, 2, 1]}}]}}"#,
    )
    .unwrap();
    let (code, text, err) = wingedge(&["csg", &scene, "-o", &out], "");
    assert_eq!(code, 0, "{err}");
    assert!(text.contains("shells 2"), "{text}");
    let (code, text, err) = wingedge(&["validate", &out], "");
    assert_eq!(code, 0, "{err}");
    assert!(text.contains("valid closed solid"), "{text}");
    assert!(
        text.contains("2 shells") || text.contains("shells 2"),
        "{text}"
    );
}

/// The hard cases of the robust-booleans issue through the command line: a
/// prism whose edge lies on the cube's top face and ends inside it (a
/// slit), two cubes turned 1e-14 rad apart, and an empty result. Each exits
/// 0, says what the writing had to fix, and writes a file that `validate`
/// accepts with the volume the command printed.
#[test]
fn csg_writes_slits_turned_copies_and_empty_results_valid() {
    let dir = TempDir::new("csg-hard");
    dir.write(
        "prism.obj",
        "v 1 1 2\nv 3 1 2\nv 1 0.5 1\nv 3 0.5 1\nv 1 1.5 1\nv 3 1.5 1\n\
         f 1 5 3\nf 2 4 6\nf 1 3 4 2\nf 1 2 6 5\nf 3 5 6 4\n",
    );
    let scenes = [
        (
            "slit.json",
            r#"{"root": {"difference": [{"box": {"min": [0,0,0], "max": [2,2,2]}}, {"mesh": "prism.obj"}]}}"#,
            7.5,
            "valid_solid",
        ),
        (
            "turned.json",
            r#"{"root": {"union": [{"box": {"min": [-1,-1,-1], "max": [1,1,1]}},
               {"transform": {"rotate_deg": [0, 0, 5.729577951308232e-13]}, "child": {"box": {"min": [-1,-1,-1], "max": [1,1,1]}}}]}}"#,
            8.0,
            "valid_solid",
        ),
        (
            "empty.json",
            r#"{"root": {"intersection": [{"box": {"min": [0,0,0], "max": [1,1,1]}}, {"box": {"min": [2,0,0], "max": [3,1,1]}}]}}"#,
            0.0,
            "empty",
        ),
    ];
    for (name, scene, volume, validity) in scenes {
        let scene_path = dir.write(name, scene);
        let out = dir.arg(&format!("{name}.obj"));
        let scene_arg = scene_path.to_string_lossy().into_owned();
        let (code, text, err) = wingedge(&["csg", &scene_arg, "-o", &out, "--json"], "");
        assert_eq!(code, 0, "{name}: {err}");
        let report: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        assert_eq!(report["validity"], validity, "{name}: {text}");
        let written = report["volume"].as_f64().unwrap();
        assert!(
            (written - volume).abs() <= 1e-9 * volume.max(1.0),
            "{name}: {written}"
        );
        // The output stage ran, unless the boxes decided (the empty
        // intersection of boxes apart: no boolean at all).
        assert!(
            report["output_work"]["rounds"].as_u64().unwrap() >= 1
                || report["structure"]["by_boxes"].as_u64().unwrap() >= 1,
            "{text}"
        );
        let (code, text, err) = wingedge(&["validate", "--json", &out], "");
        assert_eq!(code, 0, "{name}: {text}{err}");
        let files: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        assert_eq!(files[0]["validity"], validity, "{name}: {text}");
        // The text form says what the writing had to do.
        let (code, text, err) = wingedge(&["csg", &scene_arg, "-o", &out], "");
        assert_eq!(code, 0, "{err}");
        assert!(text.contains("writing: "), "{text}");
    }
}

/// manifold's `SimplifyCracks` union: a cylinder whose caps lie 10⁻¹² rad
/// off a box's faces. Rounding crossed the near-coplanar sheets until the
/// output's last resort put the caps' vertices on the box's planes; the
/// result is valid as written and has manifold3d's volume.
#[test]
fn csg_of_caps_nearly_on_a_box_face_succeeds() {
    let dir = TempDir::new("csg-cracks");
    let out = dir.arg("cracks.obj");
    let (code, text, err) = wingedge(
        &[
            "csg",
            "fixtures/scenes/simplify_cracks.json",
            "-o",
            &out,
            "--json",
        ],
        "",
    );
    assert_eq!(code, 0, "{text}{err}");
    let report: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    assert_eq!(report["validity"], "valid_solid");
    assert_eq!(report["genus"], 0);
    assert!(
        report["output_work"]["welded_vertices"].as_u64() > Some(0),
        "{text}"
    );
    let (code, text, err) = wingedge(&["validate", &out, "--json"], "");
    assert_eq!(code, 0, "{text}{err}");
    let written: serde_json::Value = serde_json::from_str(&text).expect("JSON");
    let volume = written[0]["volume"].as_f64().expect("a volume");
    assert!(
        (volume - 17852.3867581).abs() <= 1e-9 * 17852.4,
        "volume {volume}"
    );
}

/// Two blocks modelled on one slanted plane (a body and a mask in the
/// manner of manifold's `HullMask`): each block's top or bottom is a grid
/// of triangles on `z = ax + by + c` (rounded, so a few ulps off it), the
/// second turned by 10⁻⁸…10⁻¹³ rad, once resting on the first (`above`)
/// and once sunk into it (`below`). The union of the first and the
/// difference of the second crossed their sheets in wedges rounding could
/// not keep valid until the last resort pushed the sheets apart; every
/// operation now succeeds, each written file validates, and the volumes
/// add up.
#[test]
fn csg_of_sheets_nearly_in_one_slanted_plane_succeeds() {
    let dir = TempDir::new("csg-slanted-sheets");
    let fixture = |name: &str| {
        format!(
            "{}/fixtures/scenes/slanted_sheets/{name}.obj",
            env!("CARGO_MANIFEST_DIR")
        )
    };
    let volume_of = |path: &str| {
        let (code, text, err) = wingedge(&["validate", path, "--json"], "");
        assert_eq!(code, 0, "{path}: {text}{err}");
        let report: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        assert_eq!(report[0]["validity"], "valid_solid", "{path}: {text}");
        report[0]["volume"].as_f64().expect("a volume")
    };
    for (mode, once_refused) in [("above", "union"), ("below", "difference")] {
        let (a, b) = (fixture(&format!("{mode}_a")), fixture(&format!("{mode}_b")));
        let (va, vb) = (volume_of(&a), volume_of(&b));
        let mut volume = std::collections::HashMap::new();
        for op in ["union", "intersection", "difference"] {
            let scene = dir.write(
                &format!("{mode}-{op}.json"),
                format!(r#"{{"root": {{"{op}": [{{"mesh": "{a}"}}, {{"mesh": "{b}"}}]}}}}"#),
            );
            let out = dir.arg(&format!("{mode}-{op}.obj"));
            let scene = scene.to_str().expect("a UTF-8 path");
            let (code, text, err) = wingedge(&["csg", scene, "-o", &out, "--json"], "");
            assert_eq!(code, 0, "{mode} {op}: {text}{err}");
            let report: serde_json::Value = serde_json::from_str(&text).expect("JSON");
            if op == once_refused {
                assert!(
                    report["output_work"]["welded_vertices"].as_u64() > Some(0),
                    "{mode} {op}: {text}"
                );
            }
            let v = if report["validity"] == "empty" {
                0.0
            } else {
                volume_of(&out)
            };
            volume.insert(op, v);
        }
        let tolerance = 1e-9 * (va + vb);
        let (u, i, d) = (
            volume["union"],
            volume["intersection"],
            volume["difference"],
        );
        assert!(
            (u + i - va - vb).abs() <= tolerance,
            "{mode}: {u} + {i} ≠ {va} + {vb}"
        );
        assert!((d + i - va).abs() <= tolerance, "{mode}: {d} + {i} ≠ {va}");
    }
}

/// `--one-pass` evaluates the whole tree in one pass over the leaves; the
/// default goes by the tree's structure (boxes on a grid: node by node).
/// Both write the same solid, and `--json` says how the tree was split.
#[test]
fn csg_one_pass_and_by_structure_write_the_same_solid() {
    let dir = TempDir::new("csg-structure");
    let scene = dir.arg("grid.json");
    std::fs::write(
        &scene,
        r#"{"root": {"difference": [
            {"difference": [
                {"box": {"min": [0, 0, 0], "max": [3, 3, 3]}},
                {"box": {"min": [5, 5, 5], "max": [6, 6, 6]}}]},
            {"box": {"min": [1, 1, -1], "max": [2, 2, 4]}},
            {"box": {"min": [-1, 1, 1], "max": [4, 2, 2]}},
            {"box": {"min": [1, -1, 1], "max": [2, 4, 2]}}]}}"#,
    )
    .unwrap();
    let mut seen = Vec::new();
    for flags in [&[][..], &["--one-pass"][..]] {
        let out = dir.arg("out.obj");
        let mut args = vec!["csg", scene.as_str(), "-o", out.as_str(), "--json"];
        args.extend(flags);
        let (code, text, err) = wingedge(&args, "");
        assert_eq!(code, 0, "{err}");
        let report: serde_json::Value = serde_json::from_str(&text).expect("JSON");
        assert_eq!(report["validity"], "valid_solid");
        let (code, text, err) = wingedge(&["validate", &out], "");
        assert_eq!(code, 0, "{text}{err}");
        seen.push(report);
    }
    let (structured, one_pass) = (&seen[0], &seen[1]);
    assert_eq!(structured["volume"], 20.0);
    assert_eq!(structured["volume"], one_pass["volume"]);
    assert_eq!(structured["genus"], 5);
    assert_eq!(structured["genus"], one_pass["genus"]);
    assert_eq!(structured["structure"]["by_structure"], true);
    assert_eq!(one_pass["structure"]["by_structure"], false);
    // The far box is dropped by its box; the tunnels and the cube are
    // evaluated node by node, exactly, with no pass over all leaves.
    assert_eq!(structured["structure"]["by_boxes"], 1);
    assert_eq!(structured["structure"]["set_aside"], 0);
    assert_eq!(structured["structure"]["root_operands"], 0);
}
