//! The triangles the self-intersection check tests: each face cut into
//! triangles of soup vertices.

use glam::DVec2;
use rayon::prelude::*;

use super::super::super::context::{Context, Shape};

/// A triangle of a face: three soup vertices and the face.
#[derive(Clone, Copy, Debug)]
pub(super) struct Triangle {
    /// The corners, soup vertices, in the face's order.
    pub vertices: [usize; 3],
    /// The face it is cut from.
    pub face: usize,
}

impl Triangle {
    /// How many vertices the two triangles share.
    #[inline]
    pub fn shared_vertices(&self, other: &Triangle) -> usize {
        self.vertices
            .iter()
            .filter(|v| other.vertices.contains(v))
            .count()
    }
}

/// The triangles of every face that the check judges: polygon-shaped, not
/// a later copy of a duplicate, not degenerate.
pub(super) fn triangulate(ctx: &Context) -> Vec<Triangle> {
    (0..ctx.face_count())
        .into_par_iter()
        .filter(|&f| {
            ctx.shape[f] == Shape::Polygon && ctx.duplicate_of[f].is_none() && !ctx.degenerate[f]
        })
        .flat_map_iter(|face| {
            let c = ctx.corners(face);
            let out: Vec<Triangle> = if c.len() == 3 {
                vec![Triangle {
                    vertices: [c[0], c[1], c[2]],
                    face,
                }]
            } else {
                ear_clip(ctx, face)
                    .into_iter()
                    .map(|vertices| Triangle { vertices, face })
                    .collect()
            };
            out
        })
        .collect()
}

/// Triangles covering a polygon: its exact constrained Delaunay
/// triangulation in its axis projection; a fan when the projection is not a
/// simple polygon (other rules report such faces).
fn ear_clip(ctx: &Context, face: usize) -> Vec<[usize; 3]> {
    let corners = ctx.corners(face);
    let projection = ctx.projection(face);
    let p2: Vec<DVec2> = corners
        .iter()
        .map(|&v| projection.apply(ctx.position(v)))
        .collect();
    match crate::geom::triangulate(&p2, &[]) {
        Ok(triangles) => triangles
            .into_iter()
            .map(|t| t.map(|k| corners[k]))
            .collect(),
        Err(_) => (1..corners.len() - 1)
            .map(|i| [corners[0], corners[i], corners[i + 1]])
            .collect(),
    }
}
