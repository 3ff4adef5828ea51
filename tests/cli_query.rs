//! The `classify` and `raycast` subcommands, end to end.

use std::io::Write;
use std::path::PathBuf;
use std::process::{Command, Output, Stdio};

use wingedge::io::to_obj_string;
use wingedge::mesh::builders;

fn temp_file(name: &str, text: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wingedge-cli-query-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write temp file");
    path
}

fn run(args: &[&str], stdin: Option<&str>) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_wingedge"))
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run wingedge");
    if let Some(text) = stdin {
        child
            .stdin
            .take()
            .expect("stdin")
            .write_all(text.as_bytes())
            .expect("write stdin");
    } else {
        drop(child.stdin.take());
    }
    child.wait_with_output().expect("wait")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn classify_prints_one_word_per_point_in_order() {
    let mesh = temp_file("l.obj", &to_obj_string(&builders::l_prism()));
    let points = temp_file(
        "points.txt",
        "0.5 0.5 0.5\n1.5 1.5 0.5\n# a comment\n\n1 1 0.5\n  2 0.5 1  \n",
    );
    let m = mesh.to_str().expect("utf-8 path");
    for method in ["parity", "winding"] {
        let o = run(
            &[
                "classify",
                m,
                points.to_str().expect("path"),
                "--method",
                method,
            ],
            None,
        );
        assert!(o.status.success(), "{}", stderr(&o));
        assert_eq!(stdout(&o), "inside\noutside\nboundary\nboundary\n");
    }
    // Standard input.
    let o = run(&["classify", m, "-"], Some("0.5 0.5 0.5\n3 3 3\n"));
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o), "inside\noutside\n");
}

#[test]
fn classify_normals_needs_a_convex_solid() {
    let cube = temp_file("cube.obj", &to_obj_string(&builders::cube()));
    let o = run(
        &[
            "classify",
            cube.to_str().expect("path"),
            "-",
            "--method",
            "normals",
        ],
        Some("0 0 0\n1 0 0\n2 0 0\n"),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(stdout(&o), "inside\nboundary\noutside\n");
    let l = temp_file("l2.obj", &to_obj_string(&builders::l_prism()));
    let o = run(
        &[
            "classify",
            l.to_str().expect("path"),
            "-",
            "--method",
            "normals",
        ],
        Some("0.5 0.5 0.5\n"),
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("convex"), "{}", stderr(&o));
}

#[test]
fn bad_lines_are_errors_naming_the_line() {
    let cube = temp_file("cube2.obj", &to_obj_string(&builders::cube()));
    let m = cube.to_str().expect("path");
    for (input, needle) in [
        ("0 0 0\n1 2\n", "-:2:"),
        ("0 0 0\n\n0 0 zero\n", "-:3:"),
        ("nan 0 0\n", "-:1:"),
        ("0 0 -inf\n", "-:1:"),
        ("0 1e309 0\n", "-:1:"),
        ("0 0 0 0\n", "-:1:"),
    ] {
        let o = run(&["classify", m, "-"], Some(input));
        assert_eq!(o.status.code(), Some(2), "{input:?}");
        assert!(stdout(&o).is_empty());
        assert!(stderr(&o).contains(needle), "{input:?}: {}", stderr(&o));
    }
    let o = run(&["raycast", m, "-"], Some("0 0 0 1 0 0\n0 0 0 0 0 0\n"));
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("-:2:"), "{}", stderr(&o));
    let o = run(&["classify", "/nonexistent/mesh.obj", "-"], Some("0 0 0\n"));
    assert_eq!(o.status.code(), Some(2));
    let o = run(&["classify", m, "/nonexistent/points.txt"], None);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn raycast_prints_origin_and_crossings() {
    let cube = temp_file("cube3.obj", &to_obj_string(&builders::cube()));
    let o = run(
        &["raycast", cube.to_str().expect("path"), "-"],
        Some("-3 0.1 0.2 1 0 0\n0 0 0 0 0 1\n1 0 0 1 0 0\n-2 -2 -2 1 1 1\n"),
    );
    assert!(o.status.success(), "{}", stderr(&o));
    assert_eq!(
        stdout(&o),
        "outside 2.0 4.0\ninside 1.0\nboundary\noutside 1.0 3.0\n"
    );
}
