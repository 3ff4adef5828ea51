//! Mesh leaves in scene files: defective meshes are refused with the
//! validator's report.

use wingedge::csg::Scene;

#[test]
fn a_defective_mesh_is_refused_with_the_validators_report() {
    // A cube with one face missing.
    let tmp = std::env::temp_dir().join(format!("wingedge-open-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    std::fs::write(
        tmp.join("open.obj"),
        "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n\
         f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n",
    )
    .unwrap();
    std::fs::write(
        tmp.join("scene.json"),
        r#"{"root": {"union": [{"box": {"min": [0,0,0], "max": [1,1,1]}}, {"mesh": "open.obj"}]}}"#,
    )
    .unwrap();
    let error = Scene::from_file(&tmp.join("scene.json"))
        .unwrap_err()
        .to_string();
    assert!(error.starts_with("root.union[1].mesh: mesh "), "{error}");
    assert!(error.contains("open.obj"), "{error}");
    assert!(error.contains("not a valid closed solid"), "{error}");
    assert!(error.contains("edge_in_one_face"), "{error}");
    // A missing file names the file.
    std::fs::write(
        tmp.join("missing.json"),
        r#"{"root": {"mesh": "nowhere.obj"}}"#,
    )
    .unwrap();
    let error = Scene::from_file(&tmp.join("missing.json"))
        .unwrap_err()
        .to_string();
    assert!(
        error.starts_with("root.mesh: mesh ") && error.contains("nowhere.obj"),
        "{error}"
    );
    std::fs::remove_dir_all(&tmp).unwrap();
}
