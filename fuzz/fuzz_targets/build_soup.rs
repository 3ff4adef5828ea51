//! Arbitrary polygon soups → `Solid::try_from_soup` → consistency check and
//! measures; see `tests/fuzz_checks/build_soup.rs` for the decoding and the
//! invariants.
#![no_main]

#[path = "../../tests/fuzz_checks/build_soup.rs"]
mod build_soup;

libfuzzer_sys::fuzz_target!(|data: &[u8]| build_soup::run(data));
