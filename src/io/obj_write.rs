//! Writing solids as Wavefront OBJ, polygons kept.

use std::fmt::Write as _;
use std::io;
use std::path::Path;

use slotmap::SecondaryMap;

use crate::mesh::{Solid, VertexId};

/// The solid as OBJ text: one `v` line per vertex (shortest decimal that
/// reads back as the same `f64`), then one `f` line per face with its
/// vertices counter-clockwise seen from outside (polygons are not
/// triangulated). Faces carrying a group name are preceded by a `g` line when
/// the group changes.
#[must_use]
pub fn to_obj_string(solid: &Solid) -> String {
    let mut out = String::with_capacity(solid.vertex_count() * 40 + solid.face_count() * 24);
    out.push_str("# written by wingedge\n");
    let mut index: SecondaryMap<VertexId, usize> =
        SecondaryMap::with_capacity(solid.vertex_count());
    for (i, (id, v)) in solid.vertices().enumerate() {
        index.insert(id, i + 1);
        let p = v.position;
        let _ = writeln!(out, "v {:?} {:?} {:?}", p.x, p.y, p.z);
    }
    let mut group: Option<&str> = None;
    for (id, face) in solid.faces() {
        let g = face.attributes.group.as_deref();
        if g.is_some() && g != group {
            let _ = writeln!(out, "g {}", g.unwrap_or_default());
            group = g;
        }
        out.push('f');
        for v in solid.face_vertices(id) {
            let _ = write!(out, " {}", index[v]);
        }
        out.push('\n');
    }
    out
}

/// Writes the solid to `path` as OBJ; see [`to_obj_string`].
///
/// # Errors
///
/// Any error from creating or writing the file.
pub fn write_obj(solid: &Solid, path: &Path) -> io::Result<()> {
    std::fs::write(path, to_obj_string(solid))
}
