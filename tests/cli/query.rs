//! The `classify` and `raycast` subcommands, end to end.

use crate::common::cli::Outcome;
use crate::common::temp_dir::TempDir;
use wingedge::io::to_obj_string;
use wingedge::mesh::builders;

fn run(args: &[&str], stdin: Option<&str>) -> Outcome {
    crate::common::cli::run(args, stdin.unwrap_or(""), &[])
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
        let o = crate::common::cli::run_first_line_only(&args);
        assert_eq!(o.out(), first, "{args:?}");
        assert_eq!(o.code, 0, "{args:?}: {}", o.stderr);
        assert!(o.stderr.is_empty(), "{args:?}: {}", o.stderr);
    }
}

/// A closed mesh with a pinch vertex (two tetrahedra sharing their tip)
/// answers point and ray queries, and answers them as the same mesh with
/// the tip split by hand into one vertex per tetrahedron does; `validate`
/// still reports the pinch.
#[test]
fn a_pinch_vertex_is_queried_like_the_same_mesh_split_by_hand() {
    let pinched = "fixtures/broken/non_manifold_vertex.obj";
    let text = std::fs::read_to_string(pinched).unwrap();
    // The second tetrahedron's corners at the tip (OBJ vertex 4) become a
    // new vertex 8 at the same place.
    let split = text
        .replacen("v 0 -1 2\n", "v 0 -1 2\nv 0 0 1\n", 1)
        .replace("f 4 6 5\nf 4 7 6\nf 4 5 7\n", "f 8 6 5\nf 8 7 6\nf 8 5 7\n");
    assert_ne!(split, text);
    let dir = TempDir::new("pinch");
    let split = dir.write("split.obj", split);
    let split = split.to_str().unwrap();
    let points = "0.1 0.1 0.3\n0 0 1\n-0.1 -0.1 1.8\n0 0 1.5\n2 2 2\n0 0 0.5\n0.2 0.2 0.2\n0 0 1.000000001\n";
    let rays = "-1 0.1 0.3 1 0 0\n0 0 -1 0 0 1\n-0.1 -0.1 5 0 0 -1\n0.05 0.05 3 0 0 -1\n";
    for (command, input) in [("classify", points), ("raycast", rays)] {
        let a = run(&[command, pinched, "-"], Some(input));
        let b = run(&[command, split, "-"], Some(input));
        assert_eq!(a.code, 0, "{}", stderr(&a));
        assert_eq!(stdout(&a), stdout(&b), "{command}");
    }
    assert_eq!(
        stdout(&run(&["classify", pinched, "-"], Some(points))),
        // The last point is on the second tetrahedron's edge along z.
        "inside\nboundary\ninside\nboundary\noutside\nboundary\ninside\nboundary\n"
    );
    let v = run(&["validate", pinched], None);
    assert_eq!(v.code, 1);
    assert!(
        stdout(&v).contains("non_manifold_vertex: 1"),
        "{}",
        stdout(&v)
    );
}

/// A mesh that cannot be a solid (a cube with a fin: three faces on an
/// edge) is answered by `--method winding` from its triangles, with a
/// one-line note that parity is undefined and why; its answers are the
/// cube's without the fin. Parity, normals and rays still fail with the
/// located build error.
#[test]
fn a_mesh_that_is_no_solid_is_answered_by_the_winding_number() {
    let fin = "fixtures/soups/fin.obj";
    let text = std::fs::read_to_string(fin).unwrap();
    let dir = TempDir::new("soup");
    let cube = dir.write("cube.obj", text.replace("f 2 3 10 9\n", ""));
    let cube = cube.to_str().unwrap();
    let points = "0.5 0.5 0.5\n1.5 0.5 0.5\n0.9 0.1 0.1\n1.2 0.5 -0.1\n3 3 3\n0.5 0.5 1\n";
    let a = run(&["classify", fin, "-", "--method", "winding"], Some(points));
    assert_eq!(a.code, 0, "{}", stderr(&a));
    let b = run(
        &["classify", cube, "-", "--method", "winding"],
        Some(points),
    );
    assert_eq!(stdout(&a), stdout(&b));
    assert_eq!(
        stdout(&a),
        "inside\noutside\ninside\noutside\noutside\nboundary\n"
    );
    assert!(stderr(&b).is_empty(), "{}", stderr(&b));
    let note = stderr(&a);
    assert_eq!(note.lines().count(), 1, "{note}");
    assert!(
        note.starts_with("note: fixtures/soups/fin.obj: parity is undefined for this mesh")
            && note.contains("edge 1–2 is used by 3 polygons [0, 3, 6] (lines 12, 15, 18)")
            && note.contains("generalized winding number"),
        "{note}"
    );
    let rays = "0.5 0.5 0.5 1 0 0\n";
    for (args, input) in [
        (&["classify", fin, "-"][..], points),
        (&["classify", fin, "-", "--method", "normals"], points),
        (&["raycast", fin, "-"], rays),
    ] {
        let o = run(args, Some(input));
        assert_eq!(o.code, 2, "{args:?}");
        assert!(stdout(&o).is_empty(), "{args:?}");
        assert!(
            stderr(&o).contains("fin.obj: edge 1–2 is used by 3 polygons"),
            "{args:?}: {}",
            stderr(&o)
        );
        assert_eq!(
            stderr(&o).contains("--method winding answers a mesh that is no solid"),
            args[0] == "classify",
            "{args:?}: {}",
            stderr(&o)
        );
    }
    // A NaN coordinate is still an error, not an answer.
    let nan = dir.write("nan.obj", text.replace("v 2 1 -1", "v 2 nan -1"));
    let o = run(
        &[
            "classify",
            nan.to_str().unwrap(),
            "-",
            "--method",
            "winding",
        ],
        Some(points),
    );
    assert_eq!(o.code, 2);
    assert!(stdout(&o).is_empty());
    assert!(stderr(&o).contains("nan.obj"), "{}", stderr(&o));
    // So is a mesh without faces.
    let empty = dir.write("empty.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n");
    let o = run(
        &[
            "classify",
            empty.to_str().unwrap(),
            "-",
            "--method",
            "winding",
        ],
        Some(points),
    );
    assert_eq!(o.code, 2);
    assert!(stdout(&o).is_empty());
    assert!(stderr(&o).contains("no faces"), "{}", stderr(&o));
}

/// Two holes touching at a vertex no longer stop the build: the winding
/// number answers, parity says the mesh is open.
#[test]
fn holes_touching_at_a_vertex_are_queried() {
    let mesh = "fixtures/soups/touching_holes.obj";
    let o = run(
        &["classify", mesh, "-", "--method", "winding"],
        Some("0 0 0\n0.1 0.2 0.3\n5 5 5\n"),
    );
    assert_eq!(o.code, 0, "{}", stderr(&o));
    assert_eq!(stdout(&o), "inside\ninside\noutside\n");
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
    let o = run(&["classify", mesh, "-"], Some("0 0 0\n"));
    assert_eq!(o.code, 2);
    assert!(
        stderr(&o).contains("6 edges have only one face"),
        "{}",
        stderr(&o)
    );
}
