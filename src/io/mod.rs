//! OBJ in and out: reading with tobj plus a line pass of our own (every face
//! knows its line), welding split vertices, writing.

mod atomic;
pub(crate) mod json_value;
mod obj;
mod obj_write;
mod read;
mod weld;

pub use crate::mesh::PolygonSoup;
pub use atomic::write_atomically;
pub use json_value::JsonError;
pub use obj::{
    DEFAULT_MAX_FACE_CORNERS, ObjError, ObjImport, ObjOptions, import_obj, import_obj_bytes,
    read_obj,
};
pub use obj_write::{to_obj_string, write_obj, written_soup};
pub use read::{MAX_INPUT_BYTES, read_input, read_input_from, text_len};
pub use weld::{WeldMode, WeldRefusal, WeldReport};
