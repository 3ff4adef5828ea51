//! `wingedge cells`: counts per depth, the certified interval, the .npy
//! array, and refusals.

use crate::common::cli::wingedge;
use crate::common::temp_dir::TempDir;

#[test]
fn cells_of_the_cube_hold_its_volume_and_write_a_numpy_array() {
    let dir = TempDir::new("cells");
    let npy = dir.path().join("cube.npy");
    let (code, out, err) = wingedge(&[
        "cells",
        "fixtures/valid/cube.obj",
        "--depth",
        "4",
        "--npy",
        npy.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let line = out
        .lines()
        .find(|l| l.starts_with("volume in ["))
        .expect(&out);
    let inside = &line["volume in [".len()..line.find(']').unwrap()];
    let (low, high) = inside.split_once(", ").unwrap();
    let (low, high): (f64, f64) = (low.parse().unwrap(), high.parse().unwrap());
    assert!(low <= 8.0 && 8.0 <= high, "{line}");
    assert!(
        out.contains("point classifications (one per region)"),
        "{out}"
    );
    let bytes = std::fs::read(&npy).unwrap();
    assert_eq!(&bytes[..6], b"\x93NUMPY");
    assert_eq!(bytes.len() % 64, 16 * 16 * 16 % 64);
    assert!(err.contains("16×16×16 uint8"), "{err}");
}

#[test]
fn cells_of_a_scene_write_a_valid_solid_of_the_in_cells() {
    let dir = TempDir::new("cells-scene");
    let obj = dir.path().join("drilled.obj");
    let (code, out, err) = wingedge(&[
        "cells",
        "fixtures/scenes/drilled_cube.json",
        "--depth",
        "5",
        "--obj",
        obj.to_str().unwrap(),
    ]);
    assert_eq!(code, 0, "{err}");
    let line = out
        .lines()
        .find(|l| l.starts_with("volume in ["))
        .expect(&out);
    let inside = &line["volume in [".len()..line.find(']').unwrap()];
    let (low, high) = inside.split_once(", ").unwrap();
    let (low, high): (f64, f64) = (low.parse().unwrap(), high.parse().unwrap());
    let exact = 8.0 - 1.5 * std::f64::consts::PI + 2f64.sqrt();
    assert!(low <= exact && exact <= high, "{line}");
    assert!(err.contains(&format!("volume {low};")), "{err}");
    let (code, out, err) = wingedge(&["validate", obj.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert!(out.contains("valid closed solid"), "{out}");
}

#[test]
fn bad_requests_name_what_is_wrong() {
    let dir = TempDir::new("cells-bad");
    let unbounded = dir.path().join("unbounded.json");
    std::fs::write(
        &unbounded,
        r#"{"root": {"halfspace": {"point": [0, 0, 0], "normal": [0, 0, 1]}}}"#,
    )
    .unwrap();
    let (code, _, err) = wingedge(&["cells", unbounded.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(
        err.contains("unbounded.json: the solid is unbounded"),
        "{err}"
    );
    let bad = dir.path().join("bad.json");
    std::fs::write(
        &bad,
        r#"{"root": {"sphere": {"center": [0, 0, 0], "radius": -1}}}"#,
    )
    .unwrap();
    let (code, _, err) = wingedge(&["cells", bad.to_str().unwrap()]);
    assert_eq!(code, 2);
    assert!(err.contains("bad.json") && err.contains("radius"), "{err}");
    let (code, _, err) = wingedge(&[
        "cells",
        "fixtures/scenes/drilled_cube.json",
        "--depth",
        "17",
    ]);
    assert_eq!(code, 2);
    assert!(
        err.contains("drilled_cube.json: depth 17 is beyond the limit of 16"),
        "{err}"
    );
    let (code, _, err) = wingedge(&["cells", "fixtures/valid/cube.obj", "--depth", "17"]);
    assert_eq!(code, 2);
    assert!(err.contains("depth 17 is beyond the limit of 16"), "{err}");
    let (code, _, err) = wingedge(&[
        "cells",
        "fixtures/valid/cube.obj",
        "--depth",
        "10",
        "--npy",
        "x.npy",
    ]);
    assert_eq!(code, 2);
    assert!(err.contains("depth 10 is beyond the limit of 9"), "{err}");
    let (code, _, err) = wingedge(&["cells", "fixtures/no-such.obj"]);
    assert_eq!(code, 2);
    assert!(err.contains("fixtures/no-such.obj"), "{err}");
    let (code, _, err) = wingedge(&["cells", "fixtures/scenes/no-such.json"]);
    assert_eq!(code, 2);
    assert!(err.contains("fixtures/scenes/no-such.json"), "{err}");
}

#[test]
fn help_does_not_claim_an_exact_volume_for_the_obj() {
    // docs/cells.md: the In cells' solid has volume V_in only where no
    // contact along an edge or at a corner was filled; always within
    // [V_in, V_in + V_on]. The help said "volume exactly V_in".
    let (code, out, err) = wingedge(&["cells", "--help"]);
    assert_eq!(code, 0, "{err}");
    let obj = out
        .split("--obj")
        .nth(1)
        .and_then(|rest| rest.split("\n  -").next())
        .unwrap_or_else(|| panic!("no --obj in the help: {out}"));
    assert!(!obj.contains("exact"), "{obj}");
    assert!(obj.contains("[V_in, V_in + V_on]"), "{obj}");
}
