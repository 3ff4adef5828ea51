//! The Python binding of wingedge: the native module `wingedge._wingedge`,
//! wrapped by the pure-Python package `wingedge` (`python/wingedge/`), which
//! adds array checks, interop with trimesh and manifold3d, and the type stub.
//! Validation reports (`Report`, `Violation`) are native classes the package
//! re-exports as they are.
//!
//! No geometry lives here: every answer comes from the `wingedge` crate.
//! Batch calls copy the caller's array once into the crate's layout, release
//! the interpreter lock (`Python::detach`) and run on the crate's thread pool.
#![warn(missing_docs)]

mod arrays;
mod boolean;
mod defects;
mod errors;
mod expression;
mod face_index;
mod repair;
mod report;
mod scene;
mod solid;
mod soup;

use pyo3::prelude::*;

/// The native module.
#[pymodule]
fn _wingedge(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_class::<solid::PySolid>()?;
    m.add_class::<soup::PySoupWinding>()?;
    m.add_class::<report::PyReport>()?;
    m.add_class::<report::PyViolation>()?;
    scene::register(m)?;
    m.add_function(wrap_pyfunction!(solid::load_obj, m)?)?;
    m.add_function(wrap_pyfunction!(solid::load, m)?)?;
    m.add_function(wrap_pyfunction!(solid::builtin, m)?)?;
    m.add_function(wrap_pyfunction!(solid::cuboid, m)?)?;
    m.add_function(wrap_pyfunction!(solid::prism, m)?)?;
    m.add_function(wrap_pyfunction!(solid::sphere, m)?)?;
    m.add_function(wrap_pyfunction!(boolean::boolean, m)?)?;
    m.add_function(wrap_pyfunction!(boolean::combine, m)?)?;
    m.add_function(wrap_pyfunction!(repair::repair_path, m)?)?;
    m.add_function(wrap_pyfunction!(repair::repair_flat, m)?)?;
    m.add_function(wrap_pyfunction!(report::validate_path, m)?)?;
    m.add_function(wrap_pyfunction!(report::validate_solid, m)?)?;
    m.add_function(wrap_pyfunction!(defects::render_defects_path, m)?)?;
    m.add_function(wrap_pyfunction!(defects::render_defects_solid, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
