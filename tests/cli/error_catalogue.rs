//! The error catalogue: every file in `tests/bad_inputs/` is run through
//! the command line as `tests/bad_inputs/expect.txt` says, and must give
//! the exit code it lists (2 unreadable, 1 read but invalid) and a message
//! naming the file and the OBJ line or JSON path.

use std::collections::BTreeSet;

use crate::common::cli::run;
use crate::common::temp_dir::TempDir;

const FOLDER: &str = "tests/bad_inputs";

/// One row of the manifest.
#[derive(Debug)]
struct Expectation {
    file: String,
    command: String,
    code: i32,
    fragment: String,
}

fn manifest() -> Vec<Expectation> {
    let text = std::fs::read_to_string(format!("{FOLDER}/expect.txt")).expect("the manifest");
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|(i, l)| {
            let fields: Vec<&str> = l.splitn(4, '|').map(str::trim).collect();
            assert_eq!(fields.len(), 4, "expect.txt:{}: {l}", i + 1);
            Expectation {
                file: fields[0].to_string(),
                command: fields[1].to_string(),
                code: fields[2]
                    .parse()
                    .unwrap_or_else(|_| panic!("expect.txt:{}: exit code", i + 1)),
                fragment: fields[3].to_string(),
            }
        })
        .collect()
}

#[test]
fn every_bad_input_is_in_the_manifest_and_every_row_has_its_file() {
    let rows = manifest();
    let listed: BTreeSet<&str> = rows.iter().map(|r| r.file.as_str()).collect();
    let present: BTreeSet<String> = std::fs::read_dir(FOLDER)
        .expect("the catalogue folder")
        .map(|e| {
            e.expect("an entry")
                .file_name()
                .to_string_lossy()
                .into_owned()
        })
        .filter(|name| name != "expect.txt" && name != "README.md")
        .collect();
    for name in &present {
        assert!(
            listed.contains(name.as_str()),
            "{name} has no row in expect.txt"
        );
    }
    for name in &listed {
        assert_eq!(
            present.contains(*name),
            !name.starts_with("missing."),
            "{name}: only `missing.*` rows may name absent files"
        );
    }
    // Every class the catalogue promises.
    for class in [
        "missing.obj",
        "directory.obj",
        "binary.obj",
        "vertices_only.obj",
        "two_corners.obj",
        "index_zero.obj",
        "index_out_of_range.obj",
        "nan_coordinate.obj",
        "truncated_vertex.obj",
        "slash_garbage.obj",
        "bad_json.json",
        "unknown_scene_key.json",
        "negative_radius.json",
        "missing_mesh.json",
        "wrong_type.json",
    ] {
        assert!(listed.contains(class), "no {class} in the catalogue");
    }
}

#[test]
fn every_bad_input_gets_its_exit_code_and_a_located_message() {
    let scratch = TempDir::new("catalogue");
    let png = scratch.arg("out.png");
    let mut failures = Vec::new();
    for row in manifest() {
        let path = format!("{FOLDER}/{}", row.file);
        let (args, stdin): (Vec<&str>, &str) = match row.command.as_str() {
            "classify" => (vec!["classify", &path, "-"], "0 0 0\n"),
            "raycast" => (vec!["raycast", &path, "-"], "0 0 0 1 0 0\n"),
            "render" => (vec!["render", &path, "-o", &png, "--size", "8x8"], ""),
            other => (vec![other, &path], ""),
        };
        let o = run(&args, stdin, &[]);
        let said = format!("{}{}", o.out(), o.stderr);
        let names_file = if row.code == 2 {
            said.lines()
                .any(|l| l.contains(&path) && l.contains(&row.fragment))
        } else {
            said.contains(&path) && said.contains(&row.fragment)
        };
        if o.code != row.code || !names_file {
            failures.push(format!(
                "wingedge {}: exit {} (expected {}), expected {:?} with the file named; said:\n{said}",
                args.join(" "),
                o.code,
                row.code,
                row.fragment
            ));
        }
        // Refused input never leaves an image behind.
        assert!(!std::path::Path::new(&png).exists(), "{path}");
    }
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
