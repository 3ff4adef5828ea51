//! Whether a solid's boundary meets a closed box, exactly: the faces cut
//! into exact triangles, found by a box query on the shared BVH.

use glam::DVec3;
use thiserror::Error;

use crate::geom::{Aabb, TriangleFilter, TriangulateError, box_meets_triangle};
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
/// `triangles`, `boxes` and `filters` are in the BVH's item order;
/// `boxes[i]` is the exact box of `triangles[i]` and `filters[i]` its
/// floating-point filter, which rejects only boxes the triangle misses.
#[derive(Clone, Debug)]
pub struct BoundaryTiles {
    triangles: Vec<[DVec3; 3]>,
    boxes: Vec<Aabb>,
    filters: Vec<TriangleFilter>,
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
        let triangles: Vec<[DVec3; 3]> = order.iter().map(|&i| triangles[i as usize]).collect();
        let boxes = order.iter().map(|&i| boxes[i as usize]).collect();
        let filters = triangles.iter().map(TriangleFilter::new).collect();
        Ok(BoundaryTiles {
            triangles,
            boxes,
            filters,
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
            |p| met = met || self.filtered_meets(cell, p),
        );
        met
    }

    /// Whether one of the triangles `among` (by index) meets the closed box
    /// `cell`, exactly: [`BoundaryTiles::meets`] over a list that holds
    /// every triangle meeting `cell` (and perhaps more), as
    /// [`BoundaryTiles::meeting_children`] makes them.
    #[must_use]
    pub fn meets_among(&self, cell: &Aabb, among: &[u32]) -> bool {
        among.iter().any(|&t| self.tile_meets(cell, t))
    }

    /// The triangles that meet the closed box `cell`, exactly, in
    /// increasing order: the start of the lists handed down an octree.
    #[must_use]
    pub fn meeting(&self, cell: &Aabb) -> Vec<u32> {
        let mut found = Vec::new();
        self.bvh.items_overlapping(
            cell,
            |p| self.boxes[p],
            |p| {
                if self.filtered_meets(cell, p) {
                    found.push(p as u32);
                }
            },
        );
        found.sort_unstable();
        found
    }

    /// Sorts the triangles of `parent` — a list holding every triangle
    /// that meets a box made of the eight `children` — among the children,
    /// in one pass over `parent`: a triangle is tried only on the children
    /// its box meets.
    ///
    /// Handed down an octree, a cell's list is made from its parent's: a
    /// triangle that meets a cell meets every box holding it, so each list
    /// holds every triangle that meets its cell, and costs what its
    /// parent's list holds, not what the triangles' boxes overlap. The
    /// boxes of long thin triangles (the sides of a cone of many segments,
    /// each from its apex to its rim) overlap most cells near the surface;
    /// the triangles themselves meet few.
    ///
    /// A list is kept by the floating-point filter alone, so it may hold
    /// a few triangles that only come close (decide with
    /// [`BoundaryTiles::meets_among`]). With `finest`, the children are not
    /// split again and need only whether the boundary meets them: each
    /// list then stops at its first triangle, and that triangle meets the
    /// child exactly.
    #[must_use]
    pub fn meeting_children(
        &self,
        parent: &[u32],
        children: &[Aabb; 8],
        finest: bool,
    ) -> [Vec<u32>; 8] {
        let mut lists: [Vec<u32>; 8] = Default::default();
        for &t in parent {
            let i = t as usize;
            let bounds = self.boxes[i];
            for (child, list) in children.iter().zip(lists.iter_mut()) {
                if finest && !list.is_empty()
                    || bounds.intersection(*child).is_empty()
                    || !self.filters[i].may_meet(child)
                {
                    continue;
                }
                if !finest || box_meets_triangle(child, &self.triangles[i]) {
                    list.push(t);
                }
            }
        }
        lists
    }

    /// Whether triangle `t` meets the closed box `cell` (its box first).
    fn tile_meets(&self, cell: &Aabb, t: u32) -> bool {
        let t = t as usize;
        !self.boxes[t].intersection(*cell).is_empty() && self.filtered_meets(cell, t)
    }

    /// [`box_meets_triangle`] after the triangle's floating-point filter,
    /// which settles most boxes a triangle misses without the exact test.
    fn filtered_meets(&self, cell: &Aabb, t: usize) -> bool {
        self.filters[t].may_meet(cell) && box_meets_triangle(cell, &self.triangles[t])
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
