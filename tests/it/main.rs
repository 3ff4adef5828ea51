//! The library's integration tests, one crate (one binary to build and
//! link) with a module per subject. Run one subject or one file with a
//! filter: `cargo test --test it boolean::`, `cargo test --test it
//! query::hard_cases`. The command line's tests are the crate `tests/cli/`.

#[path = "../common/mod.rs"]
mod common;

mod boolean;
mod csg;
mod fields;
mod formats;
mod mesh;
mod oracles;
mod query;
mod repair;
mod trust_scale;
mod validate;
