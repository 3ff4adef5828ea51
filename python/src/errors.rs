//! The exceptions: one base class, `wingedge.WingedgeError` (a
//! `ValueError`), and one subclass per kind of failure, each carrying the
//! crate's located message (file, OBJ line, element ids, JSON path).

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

create_exception!(
    wingedge,
    WingedgeError,
    PyValueError,
    "Base class of every wingedge error (a ValueError)."
);
create_exception!(
    wingedge,
    FormatError,
    WingedgeError,
    "A mesh file could not be read or written: the message names the file \
     and the place in it (line, byte offset and element, XML or JSON path)."
);
create_exception!(
    wingedge,
    ObjError,
    FormatError,
    "An OBJ file could not be read: the message names the file and line."
);
create_exception!(
    wingedge,
    ValidationError,
    WingedgeError,
    "Input that cannot be a winged-edge solid (bad indices, non-finite \
     positions, non-manifold edges): the message names the elements."
);
create_exception!(
    wingedge,
    QueryError,
    WingedgeError,
    "A query that cannot be answered (non-finite point, zero ray direction, \
     an open solid asked for parity): the message names the query's index."
);

create_exception!(
    wingedge,
    BooleanError,
    WingedgeError,
    "A boolean that produced no solid: an operand that is not a valid closed \
     solid (named, with its defects), a result that rounding would leave \
     invalid (the located defect), or a bad set expression (the offending \
     part named by its place)."
);

/// Adds the exception classes to the module.
pub(crate) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("WingedgeError", py.get_type::<WingedgeError>())?;
    m.add("FormatError", py.get_type::<FormatError>())?;
    m.add("ObjError", py.get_type::<ObjError>())?;
    m.add("ValidationError", py.get_type::<ValidationError>())?;
    m.add("QueryError", py.get_type::<QueryError>())?;
    m.add("BooleanError", py.get_type::<BooleanError>())?;
    Ok(())
}

/// A query error as a Python exception.
pub(crate) fn query(e: wingedge::query::QueryError) -> PyErr {
    QueryError::new_err(e.to_string())
}

/// A build error as a Python exception.
pub(crate) fn build(e: wingedge::mesh::BuildError) -> PyErr {
    ValidationError::new_err(e.to_string())
}

/// A build error of the solid read from `path`, naming the file.
pub(crate) fn build_in(path: &std::path::Path, e: wingedge::mesh::BuildError) -> PyErr {
    ValidationError::new_err(format!("{}: not a winged-edge solid: {e}", path.display()))
}

/// A mesh file's read error: `ObjError` for OBJ, `FormatError` otherwise.
pub(crate) fn import(e: wingedge::io::ImportError) -> PyErr {
    match e {
        wingedge::io::ImportError::Obj(e) => ObjError::new_err(e.to_string()),
        other => FormatError::new_err(other.to_string()),
    }
}

/// A boolean's error as a Python exception, with the crate's message.
pub(crate) fn boolean(e: wingedge::boolean::BooleanError) -> PyErr {
    BooleanError::new_err(e.to_string())
}
