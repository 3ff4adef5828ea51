//! OBJ in and out.

mod obj_read;
mod obj_write;

pub use crate::mesh::PolygonSoup;
pub use obj_read::{ObjError, read_obj};
pub use obj_write::{to_obj_string, write_obj};
