//! The face table.

use std::sync::Arc;

use crate::geom::Plane;

use super::LoopId;

/// A face: a planar polygon of any size, bounded by one outer loop and zero
/// or more rings (inner loops: holes through the face).
///
/// # Invariants
///
/// - `outer` and every id in `rings` name loops ([`super::Loop`]) whose
///   `face` is this face; `rings` is sorted and holds no duplicate, and no
///   loop is both outer and a ring.
/// - `plane` is the Newell plane of the outer loop, with its normal pointing
///   outward, or `None` when that loop encloses no area. The plane is a
///   rounded construction: sides of a face are decided by
///   [`Solid::face_side`](super::Solid::face_side), not by it. The Euler
///   operators ([`Solid::mef`](super::Solid::mef) and friends) are
///   topological: a face they create gets the Newell plane of its outer
///   loop and the faces they change keep their planes; the builders and the
///   editing operations refit the planes of the faces they move.
///
/// Faces of a solid built from a polygon soup have no rings and an outer
/// loop of at least three distinct vertices. A solid under construction by
/// Euler operators may have faces whose loops have one or two edges, or a
/// lone vertex, or visit a vertex twice (a "strut" edge used from both
/// sides); validation reports such faces.
#[derive(Clone, Debug, PartialEq)]
pub struct Face {
    /// The face's plane, `None` for a face with zero area.
    pub plane: Option<Plane>,
    /// The outer loop.
    pub outer: LoopId,
    /// The inner loops (rings), sorted by id.
    pub rings: Vec<LoopId>,
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
