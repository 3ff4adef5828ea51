//! Stage 7: coplanar neighbours merged back into polygon faces.
//!
//! The pieces are triangles; the result should have the faces a person
//! expects (a box minus a smaller box: 6 + 6 faces, a drilled face: one
//! face with a ring). Two neighbouring faces are merged when they came
//! from the same operand face, or when the operand triangles they came from
//! lie exactly in one plane (four `orient3d` = 0) facing the same way. The
//! merge runs through Euler operators only: `kef` across the shared edge,
//! then `kev` for an edge left dangling inside a face, `kemr` for an edge
//! left bridging two loops of one face (the ring of a drilled face), and
//! `join_edges` for a vertex left with two edges — such a vertex lies on
//! the line where its two faces' planes meet, so removing it changes no
//! shape, and it drops the near-collinear points that rounding could
//! otherwise fold.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use glam::DVec3;

use crate::geom::{Sign, orient3d};
use crate::mesh::{EdgeId, FaceId, Solid, VertexId};

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

/// Merges every pair of neighbouring faces that [`mergeable`] allows, then
/// removes the edges and vertices the merge left inside faces.
pub(crate) fn merge_faces(solid: &mut Solid, sources: &[PieceSource]) {
    let source_of = |solid: &Solid, f| solid.face(f).attributes.source_index.map(|i| sources[i]);
    let mut coplanar_cache: HashMap<(FaceOrigin, FaceOrigin), bool> = HashMap::default();
    let edges: Vec<EdgeId> = solid.edges().map(|(e, _)| e).collect();
    for &e in &edges {
        let Some(edge) = solid.get_edge(e) else {
            continue;
        };
        let (left, Some(right)) = (edge.left_face, edge.right_face) else {
            continue;
        };
        if left == right {
            continue;
        }
        let (Some(l), Some(r)) = (source_of(solid, left), source_of(solid, right)) else {
            continue;
        };
        let merge = l.origin == r.origin
            || *coplanar_cache
                .entry((l.origin, r.origin))
                .or_insert_with(|| same_plane_same_way(&l.plane, &r.plane));
        if !merge || !touch_only_along_shared_edges(solid, left, right) {
            continue;
        }
        // Kill the face without rings (kef refuses the other); when both
        // have rings the faces stay apart.
        let victim = if solid.face(right).rings.is_empty() {
            right
        } else if solid.face(left).rings.is_empty() {
            left
        } else {
            continue;
        };
        let _ = solid.kef(e, victim);
    }
    tidy_inside_faces(solid);
}

/// Whether every vertex the two faces have in common lies on an edge
/// between them: then merging them makes loops that are simple (shared
/// chains become dangling edges or ring boundaries). A vertex where the
/// faces only touch would become a pinch of the merged face's loop, so
/// such faces stay apart.
fn touch_only_along_shared_edges(solid: &Solid, a: FaceId, b: FaceId) -> bool {
    let of_b: HashSet<VertexId> = solid.face_vertices(b).collect();
    solid
        .face_vertices(a)
        .filter(|v| of_b.contains(v))
        .all(|v| {
            solid.vertex_edges(v).any(|e| {
                let edge = solid.edge(e);
                let faces = (edge.left_face, edge.right_face);
                faces == (a, Some(b)) || faces == (b, Some(a))
            })
        })
}

/// Edges with one face on both sides and vertices with two edges, left by
/// the merge, removed: dangling edges first (`kev`, until none is left, so
/// that `kemr` never leaves a loop without edges), then one bridge at a
/// time (`kemr`, keeping the loop that winds counter-clockwise about the
/// face's normal as the outer one), then vertices of degree two.
fn tidy_inside_faces(solid: &mut Solid) {
    loop {
        let inner: Vec<EdgeId> = solid
            .edges()
            .filter(|(_, edge)| edge.right_face == Some(edge.left_face))
            .map(|(e, _)| e)
            .collect();
        let mut changed = false;
        for &e in &inner {
            let Some(edge) = solid.get_edge(e) else {
                continue;
            };
            let (origin, dest) = (edge.origin, edge.dest);
            if solid.vertex_degree(dest) == 1 {
                changed |= solid.kev(e, dest).is_ok();
            } else if solid.vertex_degree(origin) == 1 {
                changed |= solid.kev(e, origin).is_ok();
            }
        }
        if changed {
            continue;
        }
        let Some(&bridge) = inner.iter().find(|&&e| solid.get_edge(e).is_some()) else {
            break;
        };
        let face = solid.edge(bridge).left_face;
        if let Ok(ring) = solid.kemr(bridge) {
            let outer = solid.face(face).outer;
            if loop_area(solid, ring, face) > loop_area(solid, outer, face) {
                solid.swap_outer_loop(face, ring);
            }
        } else {
            break;
        }
    }
    let vertices: Vec<_> = solid.vertices().map(|(v, _)| v).collect();
    for v in vertices {
        if solid.get_vertex(v).is_some() && solid.vertex_degree(v) == 2 {
            let _ = solid.join_edges(v);
        }
    }
}

/// The loop's signed area about the face's normal (Newell): positive for
/// a loop wound counter-clockwise seen from outside.
fn loop_area(solid: &Solid, l: crate::mesh::LoopId, face: FaceId) -> f64 {
    let points: Vec<DVec3> = solid.loop_vertices(l).map(|v| solid.position(v)).collect();
    let normal = solid.face(face).plane.map(|p| p.normal).unwrap_or(DVec3::Z);
    let n = points.len();
    (0..n)
        .map(|i| points[i].cross(points[(i + 1) % n]))
        .sum::<DVec3>()
        .dot(normal)
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
