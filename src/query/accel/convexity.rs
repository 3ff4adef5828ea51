//! The exact convexity test of the normals method, on the fan triangles.

use glam::DVec3;
use rayon::prelude::*;
use thiserror::Error;

use crate::disjoint_sets::DisjointSets;
use crate::geom::polygon::{Axis, Projection};
use crate::geom::{Sign, orient2d, orient3d};
use crate::mesh::FaceId;

use super::triangle_records::YzTri;

/// Why a solid is not convex (the normals method refuses it).
///
/// Decided exactly on the fan triangles: every edge of the triangulation
/// (face edges and fan diagonals) must be shared with one triangle running it
/// the other way, whose third corner is not strictly above the first
/// triangle's plane and, when exactly in it, lies across the edge (no fold).
/// A closed connected surface that is convex at every edge bounds a convex
/// body.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum NotConvex {
    /// The surface has holes (an edge of a triangle has no partner running it
    /// the other way).
    #[error("the surface is not closed")]
    NotClosed,
    /// The surface has more than one connected shell.
    #[error("the surface has {count} shells")]
    Shells {
        /// How many shells.
        count: usize,
    },
    /// Across an edge of face `face`, the neighbouring corner `point` lies
    /// strictly outside the face's plane: a reflex edge (or a face whose
    /// corners are not exactly coplanar, bent outward).
    #[error("the corner {} lies strictly outside the plane of face {face:?}", crate::geom::ReadableVec(*.point))]
    ReflexEdge {
        /// The face.
        face: FaceId,
        /// The offending corner.
        point: DVec3,
    },
    /// Two coplanar triangles of face `face` fold over each other across an
    /// edge: the face has a reflex corner.
    #[error("face {face:?} folds over itself near {} (a reflex corner)", crate::geom::ReadableVec(*.point))]
    ReflexCorner {
        /// The face.
        face: FaceId,
        /// The offending corner.
        point: DVec3,
    },
}

/// The exact convexity test on the fan triangles; see [`NotConvex`].
pub(in crate::query) fn check_convexity(
    tris: &[YzTri],
    tri_face: &[FaceId],
    boundary_edges: usize,
) -> Result<(), NotConvex> {
    if boundary_edges > 0 {
        return Err(NotConvex::NotClosed);
    }
    let key = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    // Every directed edge (by exact corner coordinates) with its triangle and
    // the triangle's third corner; sorted so that partners can be found.
    let mut edges: Vec<([u64; 3], [u64; 3], u32, u8)> = tris
        .par_iter()
        .enumerate()
        .flat_map_iter(|(i, t)| {
            let c = t.corners();
            (0..3).map(move |k| {
                (
                    key(c[k]),
                    key(c[(k + 1) % 3]),
                    i as u32,
                    ((k + 2) % 3) as u8,
                )
            })
        })
        .collect();
    edges.par_sort_unstable();
    let partner = |from: [u64; 3], to: [u64; 3]| {
        edges
            .binary_search_by(|e| (e.0, e.1).cmp(&(from, to)))
            .ok()
            .map(|j| edges[j])
    };
    // Local test at every edge, in parallel; the first failure in edge order
    // is reported.
    let local = edges.par_iter().find_map_first(|&(from, to, t, _)| {
        let Some((_, _, u, opposite)) = partner(to, from) else {
            return Some(NotConvex::NotClosed);
        };
        let [a, b, c] = tris[t as usize].corners();
        let d = tris[u as usize].corners()[opposite as usize];
        let face = tri_face[t as usize];
        match orient3d(a, b, c, d) {
            Sign::Positive => Some(NotConvex::ReflexEdge { face, point: d }),
            Sign::Negative => None,
            Sign::Zero => {
                // Coplanar neighbours must lie across the shared edge.
                let (p, q) = (from, to);
                let [pp, qq] = [p, q].map(|k| {
                    DVec3::new(
                        f64::from_bits(k[0]),
                        f64::from_bits(k[1]),
                        f64::from_bits(k[2]),
                    )
                });
                let r = [a, b, c]
                    .into_iter()
                    .find(|&v| key(v) != p && key(v) != q)
                    .unwrap_or(a);
                folded(pp, qq, r, d).then_some(NotConvex::ReflexCorner { face, point: d })
            }
        }
    });
    if let Some(reason) = local {
        return Err(reason);
    }
    let shells = count_shells(tris.len(), &edges);
    if shells != 1 {
        return Err(NotConvex::Shells { count: shells });
    }
    Ok(())
}

/// Whether `r` and `s`, coplanar with the edge `p q`, lie strictly on the
/// same side of it (decided in an axis plane where `p, q, r` do not
/// collapse). Degenerate triangles never fold.
fn folded(p: DVec3, q: DVec3, r: DVec3, s: DVec3) -> bool {
    for axis in [Axis::X, Axis::Y, Axis::Z] {
        let proj = Projection {
            axis,
            flipped: false,
        };
        let [pp, qq, rr, ss] = [p, q, r, s].map(|v| proj.apply(v));
        let side_r = orient2d(pp, qq, rr);
        if side_r != Sign::Zero {
            return orient2d(pp, qq, ss) == side_r;
        }
    }
    false
}

/// The number of edge-connected components of the triangles, from the
/// sorted directed edges.
fn count_shells(n: usize, edges: &[([u64; 3], [u64; 3], u32, u8)]) -> usize {
    let mut shells = DisjointSets::new(n);
    for &(from, to, t, _) in edges {
        if let Ok(j) = edges.binary_search_by(|e| (e.0, e.1).cmp(&(to, from))) {
            shells.union(t as usize, edges[j].2 as usize);
        }
    }
    (0..n).filter(|&i| shells.is_root(i)).count()
}
