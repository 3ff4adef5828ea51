//! Mesh files in and out: OBJ (tobj plus a line pass of its own: every face
//! knows its line), STL, PLY, OFF, 3MF and glTF, each polygon located in
//! its file; welding split vertices; writing every format, `f64` kept where
//! the format can hold it.

mod atomic;
mod export;
mod format;
mod gltf;
mod gltf_buffers;
mod import;
mod import_error;
#[cfg(target_os = "linux")]
mod interrupt;
pub(crate) mod json_value;
mod location;
mod obj;
mod obj_write;
mod off;
mod parsed;
mod ply;
mod ply_header;
mod read;
mod stl;
mod text;
mod threemf;
mod threemf_model;
mod weld;
mod weld_closed;
mod weld_groups;

pub use crate::mesh::PolygonSoup;
pub use atomic::write_atomically;
pub use export::{ExportError, ExportReport, export, export_bytes, export_soup};
pub use format::{Format, UnknownFormat};
pub use import::{Import, ImportOptions, MAX_PLACED_TRIANGLES, import, import_bytes, read_mesh};
pub use import_error::ImportError;
#[cfg(target_os = "linux")]
pub use interrupt::remove_partial_files_on_signal;
pub use json_value::{JsonError, MAX_JSON_BYTES, MAX_JSON_VALUES};
pub use location::{Location, Sources};
pub use obj::{
    DEFAULT_MAX_FACE_CORNERS, ObjError, ObjImport, ObjOptions, import_obj, import_obj_bytes,
    read_obj,
};
pub use obj_write::{to_obj_string, write_obj, written_soup};
pub use read::{
    MAX_INPUT_BYTES, read_binary_input, read_input, read_input_at_most, read_input_from, text_len,
};
pub use weld::{WeldMode, WeldRefusal, WeldReport};
