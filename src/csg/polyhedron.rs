//! The main kind of leaf: a validated closed polyhedral solid.

use std::sync::{Arc, OnceLock};

use glam::DVec3;
use thiserror::Error;

use super::{
    CellRelation, Containment, Crossing, CrossingPlane, LocalPlane, Primitive, Stats, SurfaceId,
};
use crate::geom::polygon::{PolygonLocation, Projection, locate_point_in_polygon};
use crate::geom::{Aabb, Ray, Sign};
use crate::mesh::{FaceId, Solid};
use crate::query::{Accel, BoundaryTiles, RayCrossings, TileError, Transition};

/// Why a solid cannot be a CSG leaf.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum PolyhedronError {
    /// Rays need a closed surface: these edges have one face.
    #[error("the solid is not closed: {boundary_edges} edge(s) have only one face")]
    NotClosed {
        /// How many boundary edges.
        boundary_edges: usize,
    },
    /// A solid without faces bounds nothing.
    #[error("the solid has no faces")]
    Empty,
}

/// A closed polyhedral solid as a CSG leaf, answered by the query layer's
/// exact ray–solid crossings and point classification.
///
/// # Exactness
///
/// Whether and where (in order) a ray crosses the boundary, whether its
/// origin is inside, and the class of a point are decided exactly on the
/// input coordinates ([`Accel::ray_crossings`], [`Accel::classify`]); rays
/// through edges and vertices or lying in a face's plane are resolved by the
/// query layer's symbolic perturbation (0 or 2 crossings at a silhouette,
/// never 1). The `t` values are rounded constructions. The normal of a face
/// for shading and for coincident-face decisions is the face's Newell plane
/// normal (rounded; axis-aligned faces get exact axis normals).
///
/// # Invariants
///
/// The solid is closed and has faces; a crossing's surface id is the index
/// of the accel triangle crossed (see [`Polyhedron::face`]).
#[derive(Clone, Debug)]
pub struct Polyhedron {
    solid: Arc<Solid>,
    accel: Arc<Accel>,
    faces: Vec<FaceId>,
    /// The exact face tiles of box tests, built on first use.
    tiles: Arc<OnceLock<Result<BoundaryTiles, TileError>>>,
}

impl Polyhedron {
    /// A leaf of a closed solid (validate imported meshes first, as the
    /// scene layer does: it refuses a defective mesh with the validator's
    /// report). Builds the query acceleration once.
    ///
    /// # Errors
    ///
    /// [`PolyhedronError`] for an open or empty solid.
    pub fn try_new(solid: Solid) -> Result<Polyhedron, PolyhedronError> {
        if solid.face_count() == 0 {
            return Err(PolyhedronError::Empty);
        }
        let boundary_edges = solid.boundary_edges().count();
        if boundary_edges > 0 {
            return Err(PolyhedronError::NotClosed { boundary_edges });
        }
        let accel = Accel::new(&solid);
        let faces: Vec<FaceId> = solid.faces().map(|(id, _)| id).collect();
        Ok(Polyhedron {
            solid: Arc::new(solid),
            accel: Arc::new(accel),
            faces,
            tiles: Arc::new(OnceLock::new()),
        })
    }

    /// The solid.
    #[must_use]
    pub fn solid(&self) -> &Solid {
        &self.solid
    }

    /// The face a crossing's surface id names (the face of the accel
    /// triangle crossed).
    #[must_use]
    pub fn face(&self, surface: SurfaceId) -> Option<FaceId> {
        self.accel.triangle(surface).map(|(_, face)| face)
    }

    /// The exact face tiles, built once.
    fn tiles(&self) -> &Result<BoundaryTiles, TileError> {
        self.tiles
            .get_or_init(|| BoundaryTiles::try_new(&self.solid))
    }

    fn face_normal(&self, face: FaceId) -> DVec3 {
        self.solid
            .face(face)
            .plane
            .map_or(DVec3::ZERO, |plane| plane.normal)
    }

    /// Whether `p` (exactly in the face's plane) lies strictly inside the
    /// face (inside its outer loop, outside its rings), and not on one of
    /// its edges or vertices.
    fn strictly_inside_face(&self, face: FaceId, p: DVec3) -> bool {
        let normal = self.face_normal(face);
        if normal == DVec3::ZERO {
            return false;
        }
        let projection = Projection::along(normal);
        let q = projection.apply(p);
        // Strictly inside the outer loop and strictly outside every ring.
        self.solid.face_loops(face).enumerate().all(|(i, l)| {
            let points: smallvec::SmallVec<[_; 8]> = self
                .solid
                .loop_vertices(l)
                .map(|v| projection.apply(self.solid.position(v)))
                .collect();
            let want = if i == 0 {
                PolygonLocation::Inside
            } else {
                PolygonLocation::Outside
            };
            locate_point_in_polygon(&points, q) == want
        })
    }
}

/// Whether a ray is inside just after its origin: the origin's class, or
/// for an origin on the boundary, whether the first transition leaves.
fn inside_after_origin(answer: &RayCrossings) -> bool {
    match answer.origin {
        Containment::Inside => true,
        Containment::Outside => false,
        Containment::OnBoundary => answer
            .hits
            .first()
            .is_some_and(|h| h.transition == Transition::Exit),
    }
}

impl Primitive for Polyhedron {
    fn intersect_ray(&self, ray: &Ray, crossings: &mut Vec<Crossing>, _stats: &mut Stats) -> bool {
        let Ok(answer) = self.accel.ray_crossings(ray) else {
            // Only invalid rays (checked by the tree) or open solids
            // (refused by `try_new`) fail.
            debug_assert!(
                false,
                "ray_crossings failed on a checked ray and closed solid"
            );
            return false;
        };
        let inside = inside_after_origin(&answer);
        crossings.extend(answer.hits.iter().map(|h| Crossing {
            t: h.t,
            surface: h.triangle,
        }));
        inside
    }

    fn classify_point(&self, p: DVec3) -> Containment {
        self.accel.classify(p).unwrap_or(Containment::Outside)
    }

    fn boundary_normal(&self, p: DVec3) -> Option<DVec3> {
        if !self.solid.bounding_box().contains(p) {
            return None;
        }
        let mut found = None;
        for &face in &self.faces {
            if self.solid.face_side(face, p) != Sign::Zero {
                continue;
            }
            if !self.strictly_inside_face(face, p) {
                // In the plane but on the face's rim or outside it.
                continue;
            }
            if found.is_some() {
                return None;
            }
            found = Some(face);
        }
        // A point on an edge or vertex is in no face strictly: `None`.
        found.map(|f| self.face_normal(f))
    }

    /// The plane of the accel triangle crossed.
    fn crossing_plane(&self, surface: SurfaceId) -> Option<CrossingPlane> {
        self.accel
            .triangle(surface)
            .map(|(corners, _)| CrossingPlane::Triangle(corners))
    }

    /// The planes of the fan triangles the ray and point queries use that
    /// hold `p` (a face that is not exactly flat contributes the planes of
    /// its triangles there).
    fn planes_through(&self, p: DVec3, planes: &mut Vec<LocalPlane>) -> bool {
        planes.extend(
            self.accel
                .triangles_holding(p)
                .into_iter()
                .filter_map(LocalPlane::from_triangle),
        );
        true
    }

    /// The exact ray from `p` along `d`: `p + ε d` is inside when the
    /// first crossing after `p` leaves the solid.
    fn inside_along(&self, p: DVec3, d: DVec3) -> Option<bool> {
        let answer = self.accel.ray_crossings(&Ray::new(p, d)).ok()?;
        Some(inside_after_origin(&answer))
    }

    fn normal(&self, _p: DVec3, surface: SurfaceId) -> DVec3 {
        self.face(surface)
            .map_or(DVec3::ZERO, |f| self.face_normal(f))
    }

    fn bounds(&self) -> Aabb {
        self.solid.bounding_box()
    }

    /// Exact: the cell is `Outside` when it misses the solid's box, else
    /// `Meets` or `Apart` by the exact box–triangle test on the faces'
    /// tiles (a box query on the shared BVH). Without tiles (a face that
    /// cannot be tiled, reported by `prepare_cells`) every cell in the box
    /// is `Meets`.
    fn cell_relation(&self, cell: &Aabb) -> CellRelation {
        let b = self.accel.bounds();
        if cell.max.cmplt(b.min).any() || cell.min.cmpgt(b.max).any() {
            return CellRelation::Outside;
        }
        match self.tiles() {
            Ok(tiles) if !tiles.meets(cell) => CellRelation::Apart,
            _ => CellRelation::Meets,
        }
    }

    fn prepare_cells(&self) -> Result<(), TileError> {
        self.tiles().as_ref().map(|_| ()).map_err(Clone::clone)
    }

    fn exact_volume(&self) -> Option<f64> {
        Some(self.solid.volume())
    }

    fn kind(&self) -> &'static str {
        "mesh"
    }

    fn is_polyhedral(&self) -> bool {
        true
    }

    fn tessellate(
        &self,
        _tolerance: f64,
        _clip: &Aabb,
    ) -> Result<crate::mesh::Solid, super::TessellateError> {
        Ok(self.solid().clone())
    }
}
