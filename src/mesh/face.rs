//! The face table.

use std::sync::Arc;

use crate::geom::Plane;

use super::EdgeId;

/// A face: a planar polygon of any size, bounded by one loop of edges.
///
/// # Invariants
///
/// - `edge` has this face as its `left_face` or `right_face`; walking the
///   wings from it visits the face's boundary counter-clockwise seen from
///   outside, through at least three edges, and returns to `edge`.
/// - A face visits each vertex at most once.
/// - `plane` is the Newell plane of the face's vertices, with its normal
///   pointing outward; it is `None` exactly when the face encloses no area
///   (all its vertices collinear), which only imported data can produce.
///   The plane is a rounded construction: sides of a face are decided by
///   [`Solid::face_side`](super::Solid::face_side), not by it.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// The face's plane, `None` for a face with zero area.
    pub plane: Option<Plane>,
    /// One edge of the face's boundary.
    pub edge: EdgeId,
    /// Where the face came from and what it carries.
    pub attributes: FaceAttributes,
}

/// What a face carries besides its geometry: its origin and its labels.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct FaceAttributes {
    /// The index of the polygon in the soup the face was built from.
    pub source_index: Option<usize>,
    /// The 1-based line of the OBJ file that defined the face.
    pub line: Option<usize>,
    /// The OBJ object or group name (`o` / `g`) the face belongs to.
    pub group: Option<Arc<str>>,
    /// The OBJ material (`usemtl`) of the face.
    pub material: Option<Arc<str>>,
}
