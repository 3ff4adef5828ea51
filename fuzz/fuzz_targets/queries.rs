//! Arbitrary points and rays → every classification method, ray crossings,
//! first hits, batches and a small CSG tree; see
//! `tests/fuzz_checks/queries.rs` for the invariants.
#![no_main]

#[path = "../../tests/fuzz_checks/queries.rs"]
mod queries;

libfuzzer_sys::fuzz_target!(|data: &[u8]| queries::run(data));
