//! Whether a solid's boundary meets a closed box, exactly: the faces cut
//! into exact triangles, found by a box query on the shared BVH.

use glam::DVec3;
use thiserror::Error;

use crate::geom::{Aabb, TriangulateError, box_meets_triangle};
use crate::mesh::{FaceId, Solid};
use crate::spatial::Bvh;

/// A face that is not a simple planar polygon cannot be tiled exactly.
#[derive(Clone, Debug, Error, PartialEq)]
#[error("face {face:?} cannot be triangulated: {source}")]
pub struct TileError {
    /// The face.
    pub face: FaceId,
    /// Why.
    pub source: TriangulateError,
}

/// The boundary of a solid as exact triangles with the shared BVH over
/// their boxes, answering whether the boundary meets a closed box.
///
/// Unlike the fan triangles of an [`Accel`](super::Accel), which cover a
/// non-convex face and more, these tile each face exactly
/// ([`Solid::try_triangulate_face`], rings included), so
/// [`meets`](BoundaryTiles::meets) is exact.
///
/// # Invariants
///
/// `triangles` and `boxes` are in the BVH's item order; `boxes[i]` is the
/// exact box of `triangles[i]`.
#[derive(Clone, Debug)]
pub struct BoundaryTiles {
    triangles: Vec<[DVec3; 3]>,
    boxes: Vec<Aabb>,
    bvh: Bvh,
}

impl BoundaryTiles {
    /// Tiles every face of `solid`.
    ///
    /// # Errors
    ///
    /// [`TileError`] naming the first face that is not a simple planar
    /// polygon.
    pub fn try_new(solid: &Solid) -> Result<BoundaryTiles, TileError> {
        let mut triangles = Vec::new();
        for (face, _) in solid.faces() {
            let tiles = solid
                .try_triangulate_face(face)
                .map_err(|source| TileError { face, source })?;
            triangles.extend(tiles.iter().map(|t| t.map(|v| solid.position(v))));
        }
        let boxes: Vec<Aabb> = triangles
            .iter()
            .map(|t| Aabb::from_points(t.iter().copied()))
            .collect();
        let (bvh, order) = Bvh::build(&boxes);
        let triangles = order.iter().map(|&i| triangles[i as usize]).collect();
        let boxes = order.iter().map(|&i| boxes[i as usize]).collect();
        Ok(BoundaryTiles {
            triangles,
            boxes,
            bvh,
        })
    }

    /// Whether the boundary meets the closed box `cell` (touching counts),
    /// decided by [`box_meets_triangle`] on the triangles whose boxes meet
    /// it.
    #[must_use]
    pub fn meets(&self, cell: &Aabb) -> bool {
        let mut met = false;
        self.bvh.items_overlapping(
            cell,
            |p| self.boxes[p],
            |p| met = met || box_meets_triangle(cell, &self.triangles[p]),
        );
        met
    }

    /// Whether one of the triangles `among` (by index; all when `None`)
    /// meets the closed box `cell`: [`BoundaryTiles::meets`] over a list
    /// that [`BoundaryTiles::meeting`] made for a box holding `cell`.
    #[must_use]
    pub fn meets_among(&self, cell: &Aabb, among: Option<&[u32]>) -> bool {
        match among {
            None => self.meets(cell),
            Some(list) => list.iter().any(|&t| self.tile_meets(cell, t)),
        }
    }

    /// The triangles among `among` (by index; all when `None`) that meet
    /// the closed box `cell`, in increasing order.
    ///
    /// Handed down an octree, a cell's list is made from its parent's: a
    /// triangle that meets a cell meets every box holding it, so the
    /// lists stay exact, and each costs what its parent's list holds, not
    /// what the triangles' boxes overlap. The boxes of long thin triangles
    /// (the sides of a cone of many segments, each from its apex to its
    /// rim) overlap most cells near the surface; the triangles themselves
    /// meet few.
    #[must_use]
    pub fn meeting(&self, cell: &Aabb, among: Option<&[u32]>) -> Vec<u32> {
        match among {
            None => {
                let mut found = Vec::new();
                self.bvh.items_overlapping(
                    cell,
                    |p| self.boxes[p],
                    |p| {
                        if box_meets_triangle(cell, &self.triangles[p]) {
                            found.push(p as u32);
                        }
                    },
                );
                found.sort_unstable();
                found
            }
            Some(list) => list
                .iter()
                .copied()
                .filter(|&t| self.tile_meets(cell, t))
                .collect(),
        }
    }

    /// Whether triangle `t` meets the closed box `cell` (its box first).
    fn tile_meets(&self, cell: &Aabb, t: u32) -> bool {
        let t = t as usize;
        !self.boxes[t].intersection(*cell).is_empty()
            && box_meets_triangle(cell, &self.triangles[t])
    }

    /// The number of triangles.
    #[must_use]
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether there are no triangles.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }
}
