//! Arbitrary bytes as an OBJ file → import → build → every validation check;
//! see `tests/fuzz_checks/obj_validate.rs` for what is checked.
#![no_main]

#[path = "../../tests/fuzz_checks/obj_validate.rs"]
mod obj_validate;

libfuzzer_sys::fuzz_target!(|data: &[u8]| obj_validate::run(data));
