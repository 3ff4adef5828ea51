//! Stage 7: coplanar neighbours merged back into polygon faces.
//!
//! The pieces are triangles; the result should have the faces a person
//! expects (a box minus a smaller box: 6 + 6 faces, a drilled face: one
//! face with a ring). Two neighbouring faces are merged when they came
//! from the same operand face, or when the operand triangles they came from
//! lie exactly in one plane (four `orient3d` = 0) facing the same way; the
//! merge itself is [`Solid::merge_faces_where`] (Euler operators only). A
//! vertex it leaves with two edges lies on the line where its two faces'
//! planes meet, so removing it changes no shape, and it drops the
//! near-collinear points that rounding could otherwise fold.

use rustc_hash::FxHashMap as HashMap;

use glam::DVec3;

use crate::geom::{Sign, orient3d};
use crate::mesh::{FaceId, Solid};

use super::intersect::projection;
use super::operand::FaceOrigin;

/// What the merge needs to know about each polygon of the soup the solid
/// was built from (indexed by the faces' `source_index`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PieceSource {
    pub origin: FaceOrigin,
    /// The operand triangle the piece lies in, wound as the piece faces.
    pub plane: [DVec3; 3],
}

/// Merges every pair of neighbouring faces from the same operand face or
/// exactly one plane facing one way ([`Solid::merge_faces_where`]).
pub(crate) fn merge_faces(solid: &mut Solid, sources: &[PieceSource]) {
    let source_of =
        |solid: &Solid, f: FaceId| solid.face(f).attributes.source_index.map(|i| sources[i]);
    let mut coplanar_cache: HashMap<(FaceOrigin, FaceOrigin), bool> = HashMap::default();
    solid.merge_faces_where(|solid, left, right| {
        let (Some(l), Some(r)) = (source_of(solid, left), source_of(solid, right)) else {
            return false;
        };
        l.origin == r.origin
            || *coplanar_cache
                .entry((l.origin, r.origin))
                .or_insert_with(|| same_plane_same_way(&l.plane, &r.plane))
    });
}

/// Whether two triangles lie exactly in one plane and face the same way.
fn same_plane_same_way(a: &[DVec3; 3], b: &[DVec3; 3]) -> bool {
    if b.iter()
        .any(|&p| orient3d(a[0], a[1], a[2], p) != Sign::Zero)
    {
        return false;
    }
    let (axis, facing) = projection(a);
    let flat = |p: DVec3| {
        let (u, v) = crate::geom::implicit::kept_axes(axis);
        glam::DVec2::new(p[u], p[v])
    };
    crate::geom::orient2d(flat(b[0]), flat(b[1]), flat(b[2])) == facing
}
