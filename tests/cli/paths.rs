//! Scene leaves and the path policy through every command that loads a
//! scene: a leaf outside the scene's folder and the working directory is
//! refused with the JSON path and the `--allow-path` hint, and read when
//! `--allow-path DIR` names its folder; a FIFO leaf is refused, never
//! waited on; the bundled scenes still load from the repository root.

use crate::common::cli::wingedge_stdin as wingedge;
use crate::common::temp_dir::TempDir;

const CUBE: &str = "v -1 -1 -1\nv 1 -1 -1\nv 1 1 -1\nv -1 1 -1\nv -1 -1 1\nv 1 -1 1\nv 1 1 1\nv -1 1 1\n\
f 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\nf 4 1 5 8\n";

/// Every command that loads a scene, on `scene`, with `extra` arguments;
/// outputs go into `out`. Returns each command's arguments and outcome.
fn every_scene_command(
    scene: &str,
    out: &TempDir,
    extra: &[&str],
) -> Vec<(Vec<String>, (i32, String, String))> {
    let obj = out.arg("out.obj");
    let png = out.arg("out.png");
    let commands: Vec<Vec<&str>> = vec![
        vec!["classify", scene, "-"],
        vec!["raycast", scene, "-"],
        vec!["volume", scene],
        vec!["cells", scene, "--depth", "2"],
        vec!["csg", scene, "-o", &obj],
        vec!["render", scene, "-o", &png, "--size", "8x6"],
    ];
    commands
        .into_iter()
        .map(|mut args| {
            args.extend_from_slice(extra);
            let stdin = if args[0] == "raycast" {
                "-3 0 0 1 0 0\n"
            } else {
                "0 0 0\n"
            };
            let outcome = wingedge(&args, stdin);
            (args.iter().map(|s| s.to_string()).collect(), outcome)
        })
        .collect()
}

#[test]
fn a_leaf_outside_is_refused_by_every_command_and_allowed_with_allow_path() {
    let outside = TempDir::new("cli-paths-outside");
    let cube = outside.write("cube.obj", CUBE);
    let dir = TempDir::new("cli-paths-scene");
    let text =
        serde_json::json!({"root": {"union": [{"mesh": cube.to_string_lossy()}]}}).to_string();
    let scene = dir.write("scene.json", text);
    let scene_arg = scene.to_string_lossy().into_owned();
    let out = TempDir::new("cli-paths-out");
    for (args, (code, _, err)) in every_scene_command(&scene_arg, &out, &[]) {
        assert_eq!(code, 2, "{args:?}: {err}");
        assert!(
            err.contains(&format!("{scene_arg}: root.union[0].mesh: ")),
            "{args:?}: {err}"
        );
        assert!(err.contains(&cube.display().to_string()), "{args:?}: {err}");
        assert!(err.contains("--allow-path DIR"), "{args:?}: {err}");
    }
    let allowed = outside.path().to_string_lossy().into_owned();
    for (args, (code, _, err)) in every_scene_command(&scene_arg, &out, &["--allow-path", &allowed])
    {
        assert_eq!(code, 0, "{args:?}: {err}");
    }
    // Repeatable: another folder first does not hide the right one.
    let elsewhere = TempDir::new("cli-paths-elsewhere");
    let (code, out_text, err) = wingedge(
        &[
            "classify",
            &scene_arg,
            "-",
            "--allow-path",
            &elsewhere.path().to_string_lossy(),
            "--allow-path",
            &allowed,
        ],
        "0 0 0\n",
    );
    assert_eq!((code, out_text.as_str()), (0, "inside\n"), "{err}");
}

#[test]
fn dot_dot_escaping_the_scene_folder_and_the_working_directory_is_refused() {
    let top = TempDir::new("cli-paths-dotdot");
    top.write("cube.obj", CUBE);
    std::fs::create_dir(top.path().join("scenes")).unwrap();
    let scene = top.path().join("scenes/scene.json");
    std::fs::write(&scene, r#"{"root": {"mesh": "../cube.obj"}}"#).unwrap();
    let scene_arg = scene.to_string_lossy().into_owned();
    let (code, _, err) = wingedge(&["volume", &scene_arg], "");
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("root.mesh: ") && err.contains("../cube.obj"),
        "{err}"
    );
    assert!(err.contains("--allow-path"), "{err}");
    let (code, out, err) = wingedge(
        &[
            "volume",
            &scene_arg,
            "--allow-path",
            &top.path().to_string_lossy(),
        ],
        "",
    );
    assert_eq!(code, 0, "{err}");
    assert!(out.starts_with('8'), "{out}");
}

#[test]
fn the_bundled_scenes_load_from_the_repository_root() {
    for scene in [
        "fixtures/scenes/drilled_cube.json",
        "fixtures/scenes/mesh_cut.json",
        "fixtures/scenes/platonic.json",
    ] {
        let (code, _, err) = wingedge(&["classify", scene, "-"], "0 0 0\n");
        assert_eq!(code, 0, "{scene}: {err}");
    }
}

#[test]
fn the_help_of_scene_commands_names_allow_path() {
    for command in ["classify", "raycast", "volume", "cells", "csg", "render"] {
        let (code, out, err) = wingedge(&[command, "--help"], "");
        assert_eq!(code, 0, "{command}: {err}");
        assert!(out.contains("--allow-path <DIR>"), "{command}: {out}");
    }
}

#[cfg(target_os = "linux")]
#[test]
fn a_fifo_leaf_is_refused_not_waited_on() {
    use std::os::unix::ffi::OsStrExt;
    let dir = TempDir::new("cli-paths-fifo");
    let fifo = dir.path().join("pipe.obj");
    let c_path = std::ffi::CString::new(fifo.as_os_str().as_bytes()).unwrap();
    // SAFETY: a valid NUL-terminated path; mkfifo only creates the node.
    assert_eq!(unsafe { libc::mkfifo(c_path.as_ptr(), 0o600) }, 0);
    let scene = dir.write("scene.json", r#"{"root": {"mesh": "pipe.obj"}}"#);
    // A hung command is killed by the runner and fails the test.
    let (code, _, err) = wingedge(&["volume", &scene.to_string_lossy()], "");
    assert_eq!(code, 2, "{err}");
    assert!(
        err.contains("root.mesh: ") && err.contains("is a FIFO (named pipe), not a regular file"),
        "{err}"
    );
}

#[test]
fn a_credentials_file_named_by_a_scene_is_not_quoted() {
    let secrets = TempDir::new("cli-paths-secret");
    let secret = secrets.write("credentials", "v s3cr3t-password-123 0 0\n");
    let dir = TempDir::new("cli-paths-secret-scene");
    let text =
        serde_json::json!({"root": {"mesh": {"path": secret.to_string_lossy(), "format": "obj"}}})
            .to_string();
    let scene = dir.write("scene.json", text);
    let (code, _, err) = wingedge(&["volume", &scene.to_string_lossy()], "");
    assert_eq!(code, 2, "{err}");
    assert!(!err.contains("s3cr3t"), "{err}");
    assert!(err.contains("--allow-path"), "{err}");
    // Allowed, a bad line is quoted only as a short excerpt.
    let long = format!("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 {}\n", "x".repeat(1 << 20));
    secrets.write("long.obj", long);
    let scene = dir.write(
        "long.json",
        serde_json::json!({"root": {"mesh": secrets.path().join("long.obj").to_string_lossy()}})
            .to_string(),
    );
    let (code, _, err) = wingedge(
        &[
            "volume",
            &scene.to_string_lossy(),
            "--allow-path",
            &secrets.path().to_string_lossy(),
        ],
        "",
    );
    assert_eq!(code, 2, "{err}");
    assert!(err.len() < 600, "{} bytes: {err:.600}", err.len());
}
