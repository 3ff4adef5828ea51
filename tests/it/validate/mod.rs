//! Validation and reading: the fixture catalogue, faces with rings, bad
//! input that must not panic, OBJ written and read back, and the fuzzers'
//! findings replayed.

mod catalogue;
mod fuzz_regressions;
mod obj_roundtrip;
mod props;
mod rings;
