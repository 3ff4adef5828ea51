//! Arbitrary bytes as a scene file → load → classify, trace, render and
//! volume; see `tests/fuzz_checks/scene_load.rs` for what is checked. Mesh
//! paths are relative to `fixtures/scenes/`, as for the seed scenes.
#![no_main]

use std::path::Path;

#[path = "../../tests/fuzz_checks/scene_load.rs"]
mod scene_load;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    let base = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../fixtures/scenes"));
    scene_load::run(data, base);
});
