//! The command line's tests: everything that runs the `wingedge` binary,
//! one crate with a module per command (`validate`, `info`, `query` for
//! `classify` and `raycast`, `csg` for the scene commands, `mesh`, `cells`)
//! and for the promises every command keeps (`determinism`,
//! `error_catalogue`, `hostile_input`, `paths`). Built with the `cli` feature only.
//! Run one module with a filter: `cargo test --test cli hostile_input::`.

#[path = "../common/mod.rs"]
mod common;

mod bounds;
mod cells;
mod csg;
mod determinism;
mod error_catalogue;
mod formats;
mod hostile_input;
mod info;
mod interrupt;
mod mesh;
mod messages;
mod paths;
mod query;
mod repair;
mod validate;
mod validate_memory;
