//! The `classify` and `raycast` subcommands, end to end.

mod common;

use common::cli::{Outcome, TempDir};
use wingedge::io::to_obj_string;
use wingedge::mesh::builders;

fn run(args: &[&str], stdin: Option<&str>) -> Outcome {
    common::cli::run(args, stdin.unwrap_or(""), &[])
}

fn stdout(o: &Outcome) -> String {
    o.out()
}

fn stderr(o: &Outcome) -> String {
    o.stderr.clone()
}

#[test]
fn classify_prints_one_word_per_point_in_order() {
    let dir = TempDir::new("cli-query");
    let mesh = dir.write("l.obj", to_obj_string(&builders::l_prism()));
    let points = dir.write(
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
        assert!(o.code == 0, "{}", stderr(&o));
        assert_eq!(stdout(&o), "inside\noutside\nboundary\nboundary\n");
    }
    // Standard input.
    let o = run(&["classify", m, "-"], Some("0.5 0.5 0.5\n3 3 3\n"));
    assert!(o.code == 0, "{}", stderr(&o));
    assert_eq!(stdout(&o), "inside\noutside\n");
}

#[test]
fn classify_normals_needs_a_convex_solid() {
    let dir = TempDir::new("cli-query");
    let cube = dir.write("cube.obj", to_obj_string(&builders::cube()));
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
    assert!(o.code == 0, "{}", stderr(&o));
    assert_eq!(stdout(&o), "inside\nboundary\noutside\n");
    let l = dir.write("l2.obj", to_obj_string(&builders::l_prism()));
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
    assert_eq!(o.code, 2);
    assert!(stderr(&o).contains("convex"), "{}", stderr(&o));
}

#[test]
fn bad_lines_are_errors_naming_the_line() {
    let dir = TempDir::new("cli-query");
    let cube = dir.write("cube2.obj", to_obj_string(&builders::cube()));
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
        assert_eq!(o.code, 2, "{input:?}");
        assert!(stdout(&o).is_empty());
        assert!(stderr(&o).contains(needle), "{input:?}: {}", stderr(&o));
    }
    let o = run(&["raycast", m, "-"], Some("0 0 0 1 0 0\n0 0 0 0 0 0\n"));
    assert_eq!(o.code, 2);
    assert!(stderr(&o).contains("-:2:"), "{}", stderr(&o));
    let o = run(&["classify", "/nonexistent/mesh.obj", "-"], Some("0 0 0\n"));
    assert_eq!(o.code, 2);
    let o = run(&["classify", m, "/nonexistent/points.txt"], None);
    assert_eq!(o.code, 2);
}

#[test]
fn raycast_prints_origin_and_crossings() {
    let dir = TempDir::new("cli-query");
    let cube = dir.write("cube3.obj", to_obj_string(&builders::cube()));
    let o = run(
        &["raycast", cube.to_str().expect("path"), "-"],
        Some("-3 0.1 0.2 1 0 0\n0 0 0 0 0 1\n1 0 0 1 0 0\n-2 -2 -2 1 1 1\n"),
    );
    assert!(o.code == 0, "{}", stderr(&o));
    assert_eq!(
        stdout(&o),
        "outside 2.0 4.0\ninside 1.0\nboundary\noutside 1.0 3.0\n"
    );
}

#[test]
fn a_reader_that_goes_away_ends_the_output_quietly() {
    // `wingedge classify … | head -1`: far more output than a pipe holds,
    // and the reader closes it after the first line. The command stops
    // writing and succeeds; it does not panic or report an error.
    let dir = TempDir::new("cli-pipe");
    let cube = dir.write("cube.obj", to_obj_string(&builders::cube()));
    let points = dir.write("points.txt", "0 0 0\n3 3 3\n".repeat(100_000));
    let rays = dir.write("rays.txt", "-3 0.75 0.75 1 0 0\n".repeat(100_000));
    let (cube, points, rays) = (
        cube.to_str().expect("path"),
        points.to_str().expect("path"),
        rays.to_str().expect("path"),
    );
    let scene = "fixtures/scenes/drilled_cube.json";
    for (args, first) in [
        (["classify", cube, points], "inside\n"),
        (["raycast", cube, rays], "outside 2.0 4.0\n"),
        (["classify", scene, points], "outside\n"),
        (["raycast", scene, rays], "outside [2, 4]\n"),
    ] {
        let o = common::cli::run_first_line_only(&args);
        assert_eq!(o.out(), first, "{args:?}");
        assert_eq!(o.code, 0, "{args:?}: {}", o.stderr);
        assert!(o.stderr.is_empty(), "{args:?}: {}", o.stderr);
    }
}
