//! Replays every input the fuzzers found (`fixtures/fuzz/<target>/`, origins
//! in `fixtures/README.md`) through the same checks the fuzz targets run
//! (`tests/fuzz_checks/`), so that each finding stays fixed on stable Rust
//! without a fuzzer. The seed corpora (the OBJ and scene fixtures) are
//! replayed too.

#[path = "../../fuzz_checks/mod.rs"]
mod fuzz_checks;

use std::path::{Path, PathBuf};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("fixtures")
}

/// The files of a folder, sorted, each with its bytes.
fn inputs(folder: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(folder)
        .unwrap_or_else(|e| panic!("{}: {e}", folder.display()))
        .map(|entry| entry.expect("a readable folder").path())
        .filter(|p| p.is_file())
        .collect();
    paths.sort();
    paths
        .into_iter()
        .map(|p| {
            let bytes = std::fs::read(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            (p, bytes)
        })
        .collect()
}

/// Runs `check` on every input of `fixtures/fuzz/<target>/`, naming the file
/// of the first failure.
fn replay(target: &str, check: impl Fn(&[u8])) -> usize {
    let found = inputs(&fixtures().join("fuzz").join(target));
    for (path, bytes) in &found {
        eprintln!("replaying {}", path.display());
        check(bytes);
    }
    found.len()
}

#[test]
fn obj_validate_findings_stay_fixed() {
    let count = replay("obj_validate", fuzz_checks::obj_validate::run);
    assert!(count > 0, "no pinned obj_validate inputs");
}

#[test]
fn scene_load_findings_stay_fixed() {
    let base = fixtures().join("scenes");
    let count = replay("scene_load", |bytes| {
        fuzz_checks::scene_load::run(bytes, &base)
    });
    assert!(count > 0, "no pinned scene_load inputs");
}

#[test]
fn queries_findings_stay_fixed() {
    let count = replay("queries", fuzz_checks::queries::run);
    assert!(count > 0, "no pinned queries inputs");
}

#[test]
fn build_soup_inputs_stay_fixed() {
    let count = replay("build_soup", fuzz_checks::build_soup::run);
    assert!(count > 0, "no pinned build_soup inputs");
}

#[test]
fn mesh_formats_inputs_stay_fixed() {
    let count = replay("mesh_formats", fuzz_checks::mesh_formats::run);
    assert!(count > 0, "no pinned mesh_formats inputs");
}

proptest::proptest! {
    #![proptest_config(crate::common::regressions_beside_source(
        proptest::prelude::ProptestConfig::with_cases(2000)
    ))]

    /// The `build_soup` check on random bytes, on stable Rust: small soups
    /// with coincident vertices, special values and stray indices either
    /// build a consistent solid or are refused, never a panic.
    #[test]
    fn build_soup_holds_on_random_bytes(bytes in proptest::collection::vec(proptest::prelude::any::<u8>(), 0..160)) {
        fuzz_checks::build_soup::run(&bytes);
    }
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(256))]

    /// The `mesh_formats` check on the format fixtures with bytes changed:
    /// counts, offsets and indices that lie are refused, never a panic.
    #[test]
    fn mesh_formats_hold_on_damaged_fixtures(
        pick in 0usize..8,
        edits in proptest::collection::vec((proptest::prelude::any::<usize>(), proptest::prelude::any::<u8>()), 1..8),
        cut in proptest::prelude::any::<usize>(),
    ) {
        let names = ["torus.stl", "torus.ply", "torus.3mf", "torus.glb", "torus.off", "torus.gltf", "two_boxes.3mf", "two_boxes.glb"];
        let formats = [0u8, 1, 2, 3, 4, 5, 2, 3];
        let mut bytes = std::fs::read(fixtures().join("formats").join(names[pick])).unwrap();
        for (at, value) in edits {
            let at = at % bytes.len();
            bytes[at] = value;
        }
        bytes.truncate(bytes.len() - cut % 64);
        let mut input = vec![formats[pick]];
        input.extend_from_slice(&bytes);
        fuzz_checks::mesh_formats::run(&input);
    }
}

#[test]
fn the_seed_corpora_pass_the_fuzz_checks() {
    for folder in ["valid", "broken", "real"] {
        for (path, bytes) in inputs(&fixtures().join(folder)) {
            eprintln!("checking {}", path.display());
            fuzz_checks::obj_validate::run(&bytes);
        }
    }
    let base = fixtures().join("scenes");
    for (path, bytes) in inputs(&base) {
        eprintln!("checking {}", path.display());
        fuzz_checks::scene_load::run(&bytes, &base);
    }
}
