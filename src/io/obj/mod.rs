//! Reading Wavefront OBJ into a polygon soup: tobj parses, a cheap line pass
//! of our own locates.
//!
//! tobj does the parsing (numbers, `v x y z w`, colours, relative indices)
//! but reports neither the line a face came from nor the original vertex
//! numbers (it renumbers the vertices of each object) and drops vertices no
//! face uses. A single pass over the raw bytes ([`scan`](scan::scan))
//! records, for every `v` line and every face line, its line number, the
//! original vertex indices, and the group and material in force; it also
//! catches every error that tobj would report without a line (index zero or
//! out of range, a face with fewer than three corners, binary data) so that
//! each error names the file and the line. tobj runs only on bytes the
//! pass accepted: the pass also checks texture and normal indices, which
//! tobj overflows on when they are far out of range. Both split words at
//! Unicode whitespace, so they agree on which lines are elements. The two are then aligned face by face.
//!
//! Welding of coincident vertices is done afterwards by
//! [`weld`](crate::io::weld).
//!
//! The files follow the pipeline: [`precheck`] (no parsing), [`scan`] (the
//! line pass, with [`corner`] and [`attribute_index`] for the corner texts),
//! [`run_tobj`], [`align`], all driven by [`import`]; [`error`] is the one
//! error type.

mod align;
mod attribute_index;
mod corner;
mod error;
#[cfg(test)]
mod fixture;
mod hex_float;
mod import;
mod precheck;
mod run_tobj;
mod scan;

pub use error::ObjError;
pub use import::{
    DEFAULT_MAX_FACE_CORNERS, ObjImport, ObjOptions, import_obj, import_obj_bytes, read_obj,
};
