//! The fan triangulation of a solid's faces, with a canonical apex.

use glam::DVec3;
use rayon::prelude::*;

use crate::mesh::{FaceId, Solid};

/// The fan triangles of every face (apex at [`fan_apex`]) and their faces,
/// in face order.
pub(in crate::query) fn fan_triangles(solid: &Solid) -> (Vec<[DVec3; 3]>, Vec<FaceId>) {
    let ids: Vec<FaceId> = solid.faces().map(|(id, _)| id).collect();
    // Each run of faces makes its triangles into two flat arrays, which are
    // then appended in order (a copy of a few large blocks, not one small
    // vector per face).
    let parts: Vec<(Vec<[DVec3; 3]>, Vec<FaceId>)> = ids
        .par_chunks(FAN_CHUNK)
        .map(|run| {
            let (mut tris, mut faces) =
                (Vec::with_capacity(run.len()), Vec::with_capacity(run.len()));
            let mut corners: Vec<DVec3> = Vec::with_capacity(8);
            for &id in run {
                if solid.face_ring_count(id) > 0 {
                    push_face_with_rings(solid, id, &mut tris, &mut faces);
                    continue;
                }
                corners.clear();
                for v in solid.face_vertices(id) {
                    corners.push(solid.position(v));
                }
                push_fan(&mut corners, id, &mut tris, &mut faces);
            }
            (tris, faces)
        })
        .collect();
    let count: usize = parts.iter().map(|(t, _)| t.len()).sum();
    let (mut tris, mut tri_face) = (Vec::with_capacity(count), Vec::with_capacity(count));
    for (t, f) in &parts {
        tris.extend_from_slice(t);
        tri_face.extend_from_slice(f);
    }
    (tris, tri_face)
}

/// The triangles of a face with rings (a fan cannot cover it): its exact
/// constrained triangulation ([`Solid::try_triangulate_face`]). Loops that
/// do not bound a valid face (validation reports them) are fanned one by
/// one instead: the fans of a ring, wound against the outer loop, cover the
/// hole a second time, so every line still crosses the face an odd number
/// of times exactly where it crosses the face's region.
fn push_face_with_rings(
    solid: &Solid,
    face: FaceId,
    tris: &mut Vec<[DVec3; 3]>,
    faces: &mut Vec<FaceId>,
) {
    let at = |v| solid.position(v);
    match solid.try_triangulate_face(face) {
        Ok(triangles) => {
            for t in triangles {
                tris.push(t.map(at));
                faces.push(face);
            }
        }
        Err(_) => {
            for l in solid.face_loops(face) {
                let corners: Vec<DVec3> = solid.loop_vertices(l).map(at).collect();
                for k in 1..corners.len().saturating_sub(1) {
                    tris.push([corners[0], corners[k], corners[k + 1]]);
                    faces.push(face);
                }
            }
        }
    }
}

/// Appends the fan triangles `(v₀, vₖ, vₖ₊₁)` of the polygon `corners`
/// (rotated in place so that `v₀` is its [`fan_apex`]), each with `face`.
///
/// The canonical apex makes the triangulation of a polygon whose corners
/// are not exactly coplanar independent of where its vertex list starts.
/// Whatever the polygon's shape, its fan's boundary (inner diagonals
/// cancel) is the polygon's own cycle of edges, so the fan has the
/// polygon's winding number about every point off it.
pub(in crate::query) fn push_fan(
    corners: &mut [DVec3],
    face: FaceId,
    tris: &mut Vec<[DVec3; 3]>,
    faces: &mut Vec<FaceId>,
) {
    let apex = fan_apex(corners);
    corners.rotate_left(apex);
    for k in 1..corners.len().saturating_sub(1) {
        tris.push([corners[0], corners[k], corners[k + 1]]);
        faces.push(face);
    }
}

/// Faces per unit of parallel work in [`fan_triangles`].
const FAN_CHUNK: usize = 4096;

/// The index of the lexicographically smallest point `(x, y, z)`: the apex
/// of a face's fan triangulation. Preserved by translations and positive
/// scalings, independent of where the vertex list starts.
fn fan_apex(corners: &[DVec3]) -> usize {
    (0..corners.len())
        .min_by(|&i, &j| {
            let (p, q) = (corners[i], corners[j]);
            p.x.total_cmp(&q.x)
                .then(p.y.total_cmp(&q.y))
                .then(p.z.total_cmp(&q.z))
        })
        .unwrap_or(0)
}
