//! Neighbouring faces merged into one by Euler operators: the clean-up
//! of a boolean's triangle pieces and of triangulated caps.

use rustc_hash::FxHashSet as HashSet;

use glam::DVec3;
use rayon::prelude::*;

use crate::mesh::{EdgeId, FaceId, LoopId, Solid, VertexId};

impl Solid {
    /// Merges neighbouring faces for which `mergeable(solid, a, b)` says
    /// so: `kef` across each edge between two such faces (killing the one
    /// without rings; faces that both have rings, or that touch at a vertex
    /// off their shared edges, stay apart so that no loop is pinched); then
    /// inside the merged faces `kev` for each dangling edge, `kemr` for each
    /// edge bridging two loops (keeping the loop that winds
    /// counter-clockwise about the face's normal outer), and `join_edges`
    /// for each vertex left with two edges. Each step is an Euler operator,
    /// so the solid stays consistent; one that refuses is skipped.
    pub fn merge_faces_where(&mut self, mut mergeable: impl FnMut(&Solid, FaceId, FaceId) -> bool) {
        let edges: Vec<EdgeId> = self.edges().map(|(e, _)| e).collect();
        for &e in &edges {
            let Some(edge) = self.get_edge(e) else {
                continue;
            };
            let (left, Some(right)) = (edge.left_face, edge.right_face) else {
                continue;
            };
            if left == right
                || !mergeable(self, left, right)
                || !touch_only_along_shared_edges(self, left, right)
            {
                continue;
            }
            let victim = if self.face(right).rings.is_empty() {
                right
            } else if self.face(left).rings.is_empty() {
                left
            } else {
                continue;
            };
            let _ = self.kef(e, victim);
        }
        tidy_inside_faces(self);
    }
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
            let origin = solid
                .loop_vertices(outer)
                .next()
                .map_or(DVec3::ZERO, |v| solid.position(v));
            if loop_area(solid, ring, face, origin) > loop_area(solid, outer, face, origin) {
                solid.swap_outer_loop(face, ring);
            }
        } else {
            break;
        }
    }
    // Joining the two edges at a vertex changes no other vertex's degree
    // (each neighbour trades one edge for the joined one), so the vertices
    // of degree two are found once, in parallel, and joined in order.
    let vertices: Vec<VertexId> = {
        let solid = &*solid;
        let all: Vec<VertexId> = solid.vertices().map(|(v, _)| v).collect();
        all.into_par_iter()
            .filter(|&v| solid.vertex_degree(v) == 2)
            .collect()
    };
    for v in vertices {
        if solid.get_vertex(v).is_some() && solid.vertex_degree(v) == 2 {
            let _ = solid.join_edges(v);
        }
    }
}

/// The loop's signed area about the face's normal (Newell): positive for
/// a loop wound counter-clockwise seen from outside. Summed relative to
/// `origin` (a point of the face): on absolute coordinates far from the
/// origin the products' rounding would exceed the area itself.
fn loop_area(solid: &Solid, l: LoopId, face: FaceId, origin: DVec3) -> f64 {
    let points: Vec<DVec3> = solid.loop_vertices(l).map(|v| solid.position(v)).collect();
    let normal = solid.face(face).plane.map(|p| p.normal).unwrap_or(DVec3::Z);
    crate::geom::newell_vector_area(&points, origin).dot(normal)
}
