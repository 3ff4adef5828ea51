//! Stage 0: an operand as the boolean sees it — the solid's faces
//! triangulated (exactly, rings included), each triangle remembering its
//! face, with a BVH over the triangles.

use glam::DVec3;
use slotmap::SecondaryMap;

use crate::geom::Aabb;
use crate::mesh::{FaceId, Solid, VertexId};
use crate::spatial::Bvh;

use super::BooleanError;

/// The face of an operand a result face came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct FaceOrigin {
    /// Which operand, by its index in the operands' list (for
    /// [`boolean`](super::boolean): 0 is `a`, 1 is `b`).
    pub operand: usize,
    /// The operand's face.
    pub face: FaceId,
}

/// A solid prepared for a boolean.
///
/// # Invariants
///
/// `triangles[t]` are indices into `positions`, counter-clockwise seen from
/// outside, never of zero area; `faces[t]` is the face `t` came from, and
/// a face's triangles are consecutive; `order` lists triangle indices by
/// BVH item position.
pub(crate) struct Prepared<'s> {
    /// The solid the triangles came from; `None` for a soup (whose face
    /// keys are minted for its polygons, see `self_arrangement`).
    pub solid: Option<&'s Solid>,
    /// The operand's index in the operands' list.
    pub index: usize,
    pub positions: Vec<DVec3>,
    pub triangles: Vec<[u32; 3]>,
    pub faces: Vec<FaceId>,
    pub bounds: Vec<Aabb>,
    pub bvh: Bvh,
    pub order: Vec<u32>,
}

impl<'s> Prepared<'s> {
    /// Triangulates every face of `solid` and indexes the triangles.
    pub fn new(solid: &'s Solid, operand: usize) -> Result<Prepared<'s>, BooleanError> {
        let mut index: SecondaryMap<VertexId, u32> =
            SecondaryMap::with_capacity(solid.vertex_count());
        let mut positions = Vec::with_capacity(solid.vertex_count());
        for (id, vertex) in solid.vertices() {
            index.insert(id, positions.len() as u32);
            positions.push(vertex.position);
        }
        let mut triangles = Vec::with_capacity(solid.face_count());
        let mut faces = Vec::with_capacity(solid.face_count());
        for (face, _) in solid.faces() {
            // Most faces are triangles: their own triangulation.
            if let Some(t) = solid.face_as_triangle(face) {
                triangles.push(t.map(|v| index[v]));
                faces.push(face);
                continue;
            }
            let pieces = solid
                .try_triangulate_face(face)
                .map_err(|source| BooleanError::Face {
                    operand,
                    face,
                    reason: source.to_string(),
                })?;
            for t in pieces {
                triangles.push(t.map(|v| index[v]));
                faces.push(face);
            }
        }
        Ok(Prepared::from_tables(
            Some(solid),
            operand,
            positions,
            triangles,
            faces,
        ))
    }

    /// The triangles `triangles` (indices into `positions`, each with its
    /// face in `faces`) indexed by a BVH over their boxes.
    pub fn from_tables(
        solid: Option<&'s Solid>,
        index: usize,
        positions: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
        faces: Vec<FaceId>,
    ) -> Prepared<'s> {
        let bounds: Vec<Aabb> = triangles
            .iter()
            .map(|t| Aabb::from_points(t.iter().map(|&i| positions[i as usize])))
            .collect();
        let (bvh, order) = Bvh::build(&bounds);
        Prepared {
            solid,
            index,
            positions,
            triangles,
            faces,
            bounds,
            bvh,
            order,
        }
    }

    /// Whether triangle `t` is the whole of its face (the face is a
    /// triangle without rings).
    #[must_use]
    pub fn face_is_one_triangle(&self, t: u32) -> bool {
        let t = t as usize;
        let face = self.faces[t];
        (t == 0 || self.faces[t - 1] != face) && self.faces.get(t + 1) != Some(&face)
    }

    /// The corners of triangle `t`.
    #[must_use]
    pub fn corners(&self, t: u32) -> [DVec3; 3] {
        self.triangles[t as usize].map(|i| self.positions[i as usize])
    }

    /// Calls `visit(t)` for every triangle whose box overlaps `query`.
    pub fn triangles_overlapping(&self, query: &Aabb, mut visit: impl FnMut(u32)) {
        self.bvh.items_overlapping(
            query,
            |p| self.bounds[self.order[p] as usize],
            |p| visit(self.order[p]),
        );
    }
}
