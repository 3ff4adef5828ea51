//! The triangles of an accel by index and by a point they hold: what the
//! CSG layer asks to compare crossings exactly and to decide a boundary
//! point where several faces meet.

use glam::{DVec2, DVec3};

use super::Accel;
use crate::geom::polygon::{PolygonLocation, locate_point_in_polygon};
use crate::geom::{Aabb, Sign, orient2d, orient3d};
use crate::mesh::FaceId;

impl Accel {
    /// The corners of triangle `i` of the accel's fan triangulation (the
    /// index a [`Crossing`](crate::query::Crossing) names) and the face it is part
    /// of; `None` past the last triangle.
    pub(crate) fn triangle(&self, i: u32) -> Option<([DVec3; 3], FaceId)> {
        let i = i as usize;
        (i < self.tris.len()).then(|| (self.tris[i].corners(), self.tri_face[i]))
    }

    /// The corners of every triangle of the accel's fan triangulation whose
    /// closed triangle holds `p`: exactly in its plane (`orient3d`) and
    /// inside it or on its rim, decided in a coordinate projection that keeps
    /// the triangle's area (`orient2d`). Triangles whose corners are
    /// collinear bound nothing and are left out. Found by a box query on the
    /// BVH, so the cost follows the triangles near `p`.
    pub(crate) fn triangles_holding(&self, p: DVec3) -> Vec<[DVec3; 3]> {
        let mut out = Vec::new();
        if !p.is_finite() {
            return out;
        }
        let query = Aabb { min: p, max: p };
        self.bvh.items_overlapping(
            &query,
            |i| Aabb::from_points(self.tris[i].corners()),
            |i| {
                let corners = self.tris[i].corners();
                if holds(corners, p) {
                    out.push(corners);
                }
            },
        );
        out
    }
}

/// Whether the closed, non-degenerate triangle holds `p`.
fn holds([a, b, c]: [DVec3; 3], p: DVec3) -> bool {
    if orient3d(a, b, c, p) != Sign::Zero {
        return false;
    }
    // Drop the axis the triangle's normal leans on most, or any axis that
    // keeps its area: a non-degenerate triangle has at least one.
    let n = (b - a).cross(c - a).abs();
    let mut axes = [0usize, 1, 2];
    axes.sort_by(|&i, &j| n[j].total_cmp(&n[i]));
    for axis in axes {
        let drop = |q: DVec3| DVec2::new(q[(axis + 1) % 3], q[(axis + 2) % 3]);
        let (a2, b2, c2) = (drop(a), drop(b), drop(c));
        if orient2d(a2, b2, c2) == Sign::Zero {
            continue;
        }
        return locate_point_in_polygon(&[a2, b2, c2], drop(p)) != PolygonLocation::Outside;
    }
    false
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

    #[test]
    fn the_triangles_holding_a_point_are_found_exactly() {
        let cube = builders::cuboid(DVec3::ZERO, DVec3::ONE).unwrap();
        let accel = Accel::new(&cube);
        let at_corner = accel.triangles_holding(DVec3::ONE);
        // Each of the three faces has one or two fan triangles there.
        assert!((3..=6).contains(&at_corner.len()), "{}", at_corner.len());
        assert!(at_corner.iter().all(|t| holds(*t, DVec3::ONE)));
        // The centre of the top face is on both diagonals; a point off them
        // is in one triangle; the centre of the cube and a point one ulp
        // above the top face are in none.
        assert_eq!(accel.triangles_holding(DVec3::new(0.5, 0.5, 1.0)).len(), 2);
        assert_eq!(accel.triangles_holding(DVec3::new(0.25, 0.5, 1.0)).len(), 1);
        assert!(accel.triangles_holding(DVec3::splat(0.5)).is_empty());
        let above = DVec3::new(0.25, 0.5, 1.0_f64.next_up());
        assert!(accel.triangles_holding(above).is_empty());
    }
}
