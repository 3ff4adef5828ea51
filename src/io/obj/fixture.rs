//! Shared inputs of the reader's unit tests.

use std::path::Path;

use super::error::ObjError;
use super::import::{ObjImport, ObjOptions, import_obj_bytes};

/// Reads `text` as the file `t.obj` with the default options.
pub(super) fn read(text: &str) -> Result<ObjImport, ObjError> {
    import_obj_bytes(Path::new("t.obj"), text.as_bytes(), &ObjOptions::default())
}

/// A closed tetrahedron, faces on lines 5 to 8.
pub(super) const TET: &str =
    "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 2 3 4\nf 3 1 4\n";
