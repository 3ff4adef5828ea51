//! What each fuzz target checks, shared by the fuzz targets (`fuzz/`, which
//! include these files by path) and by `tests/it/validate/fuzz_regressions.rs`, which
//! replays every input the fuzzers found under `fixtures/fuzz/<target>/` on
//! stable Rust, without a fuzzer.
//!
//! Each `run` takes the raw bytes of one input and panics when a property
//! fails; a bad input must give an error, never a panic.

#![allow(dead_code)]

pub mod build_soup;
pub mod mesh_formats;
pub mod obj_validate;
pub mod queries;
pub mod scene_load;
