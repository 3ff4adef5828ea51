//! What messages say: numbers in the notation the docs promise (plain for
//! ordinary magnitudes, scientific beyond: never hundreds of digits), the
//! JSON path or argument of the value at fault, and keys given twice.

use crate::common::cli::wingedge;
use crate::common::temp_dir::TempDir;

/// The longest run of decimal digits in `text`.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

#[test]
fn extreme_coordinates_are_shown_in_scientific_notation() {
    let dir = TempDir::new("messages-numbers");
    // 1e999 reads as infinity: the vertex is refused, and its finite
    // coordinate 1e300 was printed with 301 digits.
    let obj = dir.write(
        "far.obj",
        "v 1e300 1e999 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf 1 4 2\nf 2 4 3\n",
    );
    let obj = obj.to_str().unwrap();
    for args in [vec!["validate", obj], vec!["volume", obj]] {
        let (_, out, err) = wingedge(&args);
        let said = format!("{out}{err}");
        assert!(
            said.contains("vertex 1 has a non-finite coordinate (1e300, inf, 0)"),
            "{args:?}: {said}"
        );
        assert!(longest_digit_run(&said) < 20, "{args:?}: {said}");
    }
    // A box the wrong way round, far out and tiny: Debug's DVec3(2e300,
    // 0.0, 0.0) before.
    let scene = dir.write(
        "box.json",
        r#"{"root": {"box": {"min": [2e300, 0, 1e-300], "max": [1e300, 1, 1]}}}"#,
    );
    let (code, _, err) = wingedge(&["volume", scene.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("root.box.max: box min (2e300, 0, 1e-300) is not below max (1e300, 1, 1)"),
        "{err}"
    );
    let scale = dir.write(
        "flat.json",
        r#"{"root": {"transform": {"scale": [1e300, 0, 1]}, "child": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}}}"#,
    );
    let (code, _, err) = wingedge(&["volume", scale.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("root.transform.scale: scale (1e300, 0, 1) has a zero component"),
        "{err}"
    );
}

#[test]
fn a_transform_beyond_f64_is_refused_at_its_scale() {
    // The determinant overflows (1e300 · 1e300) or underflows (1e-200
    // cubed): the scale is at fault, but the message named the leaf the
    // transform moves, `root.child.box`.
    let dir = TempDir::new("messages-scale");
    for (scale, determinant) in [
        ("[1e300, 1e300, 1]", "inf"),
        ("[1e-200, 1e-200, 1e-200]", "0"),
    ] {
        let scene = dir.write(
            "scaled.json",
            format!(
                r#"{{"root": {{"transform": {{"scale": {scale}}}, "child": {{"box": {{"min": [0, 0, 0], "max": [1, 1, 1]}}}}}}}}"#
            ),
        );
        let (code, _, err) = wingedge(&["volume", scene.to_str().unwrap()]);
        assert_eq!(code, 2, "{err}");
        assert!(
            err.contains("scaled.json: root.transform.scale: scale ("),
            "{err}"
        );
        assert!(
            err.contains(&format!(
                "the determinant {determinant}, beyond f64's range"
            )),
            "{err}"
        );
    }
}

#[test]
fn a_bad_spacing_names_the_argument() {
    let dir = TempDir::new("messages-spacing");
    let scene = dir.write(
        "box.json",
        r#"{"root": {"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}}"#,
    );
    for spacing in ["inf", "0", "1e-400", "NaN"] {
        let (code, _, err) = wingedge(&["volume", scene.to_str().unwrap(), "--spacing", spacing]);
        assert_eq!(code, 2, "{spacing}: {err}");
        assert!(err.contains("--spacing: ray spacing "), "{spacing}: {err}");
    }
}

#[test]
fn a_key_given_twice_is_refused_with_file_path_and_key() {
    let dir = TempDir::new("messages-duplicate");
    // serde_json keeps the last of two equal keys: this box read as
    // min [0,0,0] and its volume was 1.
    let scene = dir.write(
        "scene.json",
        r#"{"root": {"box": {"min": [0.5, 0.5, 0.5], "max": [1, 1, 1], "min": [0, 0, 0]}}}"#,
    );
    let name = scene.to_str().unwrap();
    for args in [vec!["volume", name], vec!["cells", name]] {
        let (code, out, err) = wingedge(&args);
        assert_eq!(code, 2, "{args:?}: {out}{err}");
        assert!(
            err.contains(&format!("{name}: root.box: key \"min\" appears twice")),
            "{args:?}: {err}"
        );
    }
    // In an included scene, and in a field document.
    dir.write(
        "part.json",
        r#"{"root": {"union": [{"box": {"min": [0, 0, 0], "max": [1, 1, 1]}}, {"sphere": {"center": [0, 0, 0], "radius": 1, "radius": 2}}]}}"#,
    );
    let whole = dir.write("whole.json", r#"{"root": {"scene": "part.json"}}"#);
    let (code, _, err) = wingedge(&["volume", whole.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("part.json: root.union[1].sphere: key \"radius\" appears twice"),
        "{err}"
    );
    let field = dir.write(
        "field.json",
        r#"{"blobs": [{"center": [0, 0, 0], "radius": 1, "center": [1, 0, 0]}]}"#,
    );
    let out = dir.arg("out.obj");
    let (code, _, err) = wingedge(&["mesh", field.to_str().unwrap(), "-o", &out]);
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains(&format!(
            "{}: field.blobs[0]: key \"center\" appears twice",
            field.display()
        )),
        "{err}"
    );
}

#[test]
fn a_huge_weight_is_refused_as_a_weight_not_a_zero_tangent() {
    // The weight overflowed the rational evaluation and the sweep said
    // "the path's tangent is zero".
    let dir = TempDir::new("messages-weight");
    let scene = dir.write(
        "swept.json",
        r#"{"root": {"sweep": {"profile": [[-0.5, -0.5], [0.5, -0.5], [0.5, 0.5], [-0.5, 0.5]],
            "path": {"degree": 2, "points": [[0, 0, 0], [0, 0, 5], [5, 0, 10]], "weights": [1, 1e300, 1]}}}}"#,
    );
    let (code, _, err) = wingedge(&["volume", scene.to_str().unwrap()]);
    assert_eq!(code, 2, "{err}");
    assert!(!err.contains("tangent"), "{err}");
    assert!(
        err.contains("root.sweep.path.weights[1]: weight 1 is 1e300, outside [2^-64, 2^64]"),
        "{err}"
    );
}
