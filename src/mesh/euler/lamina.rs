//! Building blocks made of Euler operators: a polygonal lamina (a flat
//! solid of two faces) and a polygonal ring added to a face.

use glam::{DVec2, DVec3};

use crate::geom::polygon::Projection;
use crate::geom::{Sign, orient2d, triangulate_3d};
use crate::mesh::{EdgeUse, FaceId, Side, Solid};

use super::{Corner, EulerError};

impl Solid {
    /// A lamina: the flat solid of two faces bounded by one polygon, made by
    /// [`Solid::mvfs`], one [`Solid::mev`] per further vertex and one
    /// [`Solid::mef`]. Returns the solid, the face wound like `polygon`
    /// (its front) and the face wound the other way (its back).
    ///
    /// # Errors
    ///
    /// [`EulerError::InvalidPolygon`] for fewer than three vertices, a
    /// non-finite coordinate, collinear vertices or a polygon that is not
    /// simple (decided exactly in the projection onto the axis plane
    /// closest to the polygon's plane).
    pub fn try_lamina(polygon: &[DVec3]) -> Result<(Solid, FaceId, FaceId), EulerError> {
        triangulate_3d(polygon, &[])?;
        let mut solid = Solid::default();
        let (_, back) = solid.mvfs(polygon[0])?;
        let mut corner = Corner::Lone(solid.faces[back].outer);
        let mut first = None;
        for &p in &polygon[1..] {
            let (edge, _) = solid.mev(corner, p)?;
            let up = EdgeUse {
                edge,
                side: Side::Left,
            };
            first.get_or_insert(up);
            corner = Corner::After(up);
        }
        let first = first.expect("a valid polygon has at least three vertices");
        // The new face runs the new edge from the last vertex to the first,
        // then the chain in the polygon's order.
        let (_, front) = solid.mef(corner, Corner::After(first.opposite()))?;
        solid.refit_plane(back);
        Ok((solid, front, back))
    }

    /// Adds a ring bounded by `polygon` to `face`, and a new face filling
    /// it, made by a bridge [`Solid::mev`] from the face's outer loop, one
    /// [`Solid::mev`] per further vertex, a [`Solid::mef`] closing the
    /// polygon and a [`Solid::kemr`] removing the bridge. The new face is
    /// wound like `face` (the polygon is reversed if it is wound the other
    /// way) and is returned; the ring runs the other way. Turn the new face
    /// into a ring of the opposite face with [`Solid::kfmrh`] to make a
    /// hole through a lamina.
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownFace`]; [`EulerError::InvalidPolygon`] when the
    /// polygon is not simple or not strictly inside the face's outer loop,
    /// or touches one of its rings (decided exactly in the projection onto
    /// the axis plane closest to the face; the polygon is assumed to lie in
    /// the face's plane); [`EulerError::LoopNotSimple`] for a face whose
    /// loops are not simple polygons.
    pub fn add_ring(&mut self, face: FaceId, polygon: &[DVec3]) -> Result<FaceId, EulerError> {
        if !self.faces.contains_key(face) {
            return Err(EulerError::UnknownFace(face));
        }
        self.check_simple_loops(face)?;
        let loops: Vec<Vec<DVec3>> = self
            .face_loops(face)
            .map(|l| self.loop_vertices(l).map(|v| self.position(v)).collect())
            .collect();
        let mut holes: Vec<&[DVec3]> = loops[1..].iter().map(Vec::as_slice).collect();
        holes.push(polygon);
        triangulate_3d(&loops[0], &holes)?;
        let projection = Projection::along(crate::geom::newell_vector_area(&loops[0], loops[0][0]));
        let mut points = polygon.to_vec();
        if counter_clockwise(&loops[0], projection) != counter_clockwise(&points, projection) {
            points.reverse();
        }
        let start = self
            .face_first_use(face)
            .expect("a face with simple loops has edges");
        let (bridge, _) = self.mev(Corner::After(start), points[0])?;
        let bridge_up = EdgeUse {
            edge: bridge,
            side: Side::Left,
        };
        let mut corner = Corner::After(bridge_up);
        for &p in &points[1..] {
            let (edge, _) = self.mev(corner, p)?;
            corner = Corner::After(EdgeUse {
                edge,
                side: Side::Left,
            });
        }
        let (_, filling) = self.mef(corner, Corner::After(bridge_up))?;
        self.kemr(bridge)?;
        Ok(filling)
    }

    /// Refuses a face with a lone-vertex loop or a loop that visits a vertex
    /// twice or has fewer than three edges.
    pub(super) fn check_simple_loops(&self, face: FaceId) -> Result<(), EulerError> {
        for l in self.face_loops(face) {
            let mut seen = std::collections::HashSet::new();
            let mut count = 0;
            for v in self.loop_vertices(l) {
                count += 1;
                if !seen.insert(v) {
                    return Err(EulerError::LoopNotSimple {
                        loop_id: l,
                        face,
                        vertex: v,
                    });
                }
            }
            if count < 3 || self.loop_uses(l).next().is_none() {
                let vertex = self.loop_vertices(l).next().expect("a loop has a vertex");
                return Err(EulerError::LoopNotSimple {
                    loop_id: l,
                    face,
                    vertex,
                });
            }
        }
        Ok(())
    }
}

/// Whether the simple polygon `points` runs counter-clockwise in the 2-D
/// projection, decided exactly at its lowest-leftmost vertex (a convex
/// corner).
pub(super) fn counter_clockwise(points: &[DVec3], projection: Projection) -> bool {
    let flat: Vec<DVec2> = points.iter().map(|&p| projection.apply(p)).collect();
    let n = flat.len();
    let lowest = (0..n)
        .min_by(|&i, &j| {
            (flat[i].x, flat[i].y)
                .partial_cmp(&(flat[j].x, flat[j].y))
                .unwrap_or(std::cmp::Ordering::Equal)
        })
        .unwrap_or(0);
    let prev = flat[(lowest + n - 1) % n];
    let next = flat[(lowest + 1) % n];
    orient2d(prev, flat[lowest], next) == Sign::Positive
}
