//! Arbitrary bytes as a mesh file of the format the first byte picks
//! (binary STL, binary PLY, 3MF, GLB, OFF, glTF) → import → build → write
//! back; see `tests/fuzz_checks/mesh_formats.rs` for what is checked.
#![no_main]

#[path = "../../tests/fuzz_checks/mesh_formats.rs"]
mod mesh_formats;

libfuzzer_sys::fuzz_target!(|data: &[u8]| mesh_formats::run(data));
