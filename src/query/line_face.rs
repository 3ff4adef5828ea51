//! Where a line, ray or segment meets one face: the line's parameter at
//! the face's plane, then the point-in-polygon test in the face.

use glam::DVec3;

use crate::geom::exact::{det3_sign, diff_row};
use crate::geom::polygon::{PolygonLocation, locate_with_oracle};
use crate::geom::{Sign, collinear3d, orient3d};
use crate::mesh::{EdgeId, FaceId, Solid, VertexId};

use super::QueryError;

/// Which part of the line `P(u) = P1 + u (P2 − P1)` is meant.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum LineKind {
    /// All real `u`.
    Line,
    /// `u ≥ 0`: the ray from `P1` through `P2`.
    Ray,
    /// `0 ≤ u ≤ 1`: the segment from `P1` to `P2`.
    Segment,
}

/// How a line meets a face.
///
/// The parameter `u` (`P1 + u (P2 − P1)`, from the plane equation
/// `u = (−D − N·P1) / (N·(P2 − P1))`) is a rounded construction, except that
/// it is exactly `0` or `1` when `P1` or `P2` lies in the face's plane. The
/// variant is decided exactly.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum LineFaceHit {
    /// The line meets the face's plane outside the face, or outside the
    /// parameter range of a ray or segment.
    Miss,
    /// The line is parallel to the face's plane and not in it.
    Parallel,
    /// The line lies in the face's plane (for a segment or ray: its carrier
    /// line does).
    InPlane,
    /// The line crosses the face's interior.
    Inside {
        /// The parameter of the crossing point.
        u: f64,
    },
    /// The line crosses the face exactly on the open edge `edge`.
    OnEdge {
        /// The edge.
        edge: EdgeId,
        /// The parameter of the crossing point.
        u: f64,
    },
    /// The line passes exactly through the face's vertex `vertex`.
    OnVertex {
        /// The vertex.
        vertex: VertexId,
        /// The parameter of the crossing point.
        u: f64,
    },
    /// The face has zero area (its corners are collinear): it has no plane.
    DegenerateFace,
}

/// Intersects the line through `p1` and `p2` (or the ray or segment, by
/// `kind`) with face `face` of `solid`.
///
/// Method: the classical line–plane parameter and point-in-polygon test,
/// but exact: the face's plane is that of its pivot
/// triangle ([`Solid::face_pivot`]); "parallel" is the exact sign of
/// `det[P2 − P1, b − a, c − a]`, "in the plane" and the ray/segment range are
/// exact `orient3d` signs of `P1` and `P2`. The hit point `H` is never
/// computed for a decision: the classical test projects `H` and the face onto the axis
/// plane closest to the face and tests the 2-D polygon; every 2-D
/// orientation `orient2d(vᵢ, vⱼ, H)` of that test equals, up to one global
/// sign, `orient3d(P1, P2, vᵢ, vⱼ)`, which is what is evaluated (exactly).
/// Non-convex faces are handled by a fan winding count
/// ([`locate_with_oracle`]). For a face whose corners are not exactly
/// coplanar, the edge tests use the actual corners and the plane tests the
/// pivot triangle.
///
/// # Errors
///
/// [`QueryError::InvalidRay`] when a point is not finite or `p1 == p2`.
///
/// # Panics
///
/// If `face` is not a face of `solid`.
pub fn intersect_line_face(
    solid: &Solid,
    face: FaceId,
    p1: DVec3,
    p2: DVec3,
    kind: LineKind,
) -> Result<LineFaceHit, QueryError> {
    if !p1.is_finite() || !p2.is_finite() || p1 == p2 {
        return Err(QueryError::InvalidRay {
            index: 0,
            origin: p1,
            direction: p2 - p1,
        });
    }
    let Some([a, b, c]) = solid.face_pivot(face) else {
        return Ok(LineFaceHit::DegenerateFace);
    };
    let f1 = orient3d(a, b, c, p1);
    let f2 = orient3d(a, b, c, p2);
    // Sign of N · (P2 − P1).
    let nd = det3_sign([diff_row(p2, p1), diff_row(b, a), diff_row(c, a)]);
    if nd == Sign::Zero {
        return Ok(if f1 == Sign::Zero {
            LineFaceHit::InPlane
        } else {
            LineFaceHit::Parallel
        });
    }
    // u ≥ 0 iff P1 is not strictly beyond the plane along the direction;
    // u ≤ 1 iff P2 is not strictly before it.
    let after_start = f1 != nd;
    let before_end = f2 != -nd;
    let in_range = match kind {
        LineKind::Line => true,
        LineKind::Ray => after_start,
        LineKind::Segment => after_start && before_end,
    };
    if !in_range {
        return Ok(LineFaceHit::Miss);
    }
    // The outer loop, then (for a point inside it) each ring: inside a ring
    // is outside the face.
    let locate = |l| {
        let uses: Vec<_> = solid.loop_uses(l).collect();
        let corners: Vec<VertexId> = uses.iter().map(|&u| solid.use_start(u)).collect();
        let pos: Vec<DVec3> = corners.iter().map(|&v| solid.position(v)).collect();
        let location = locate_with_oracle(
            pos.len(),
            |i, j| orient3d(p1, p2, pos[i], pos[j]),
            |i, j, k| collinear3d(pos[i], pos[j], pos[k]),
        );
        (location, uses, corners)
    };
    let mut loops = solid.face_loops(face);
    let (mut location, mut uses, mut corners) = locate(loops.next().expect("a face has a loop"));
    for ring in loops {
        if location != PolygonLocation::Inside {
            break;
        }
        let (in_ring, ring_uses, ring_corners) = locate(ring);
        (location, uses, corners) = match in_ring {
            PolygonLocation::Outside => continue,
            PolygonLocation::Inside => (PolygonLocation::Outside, ring_uses, ring_corners),
            on => (on, ring_uses, ring_corners),
        };
    }
    let u = if f1 == Sign::Zero {
        0.0
    } else if f2 == Sign::Zero {
        1.0
    } else {
        let n = (b - a).cross(c - a);
        n.dot(a - p1) / n.dot(p2 - p1)
    };
    Ok(match location {
        PolygonLocation::Inside => LineFaceHit::Inside { u },
        PolygonLocation::Outside => LineFaceHit::Miss,
        PolygonLocation::OnEdge(i) => LineFaceHit::OnEdge {
            edge: uses[i].edge,
            u,
        },
        PolygonLocation::OnVertex(i) => LineFaceHit::OnVertex {
            vertex: corners[i],
            u,
        },
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

    fn top_face(solid: &Solid) -> FaceId {
        solid
            .faces()
            .find(|(_, f)| f.plane.is_some_and(|p| p.normal.z > 0.5))
            .map(|(id, _)| id)
            .unwrap()
    }

    #[test]
    fn vertical_lines_through_the_top_of_the_l_prism() {
        let solid = builders::l_prism();
        let top = top_face(&solid);
        let z = solid.bounding_box().max.z;
        let line = |x: f64, y: f64| {
            intersect_line_face(
                &solid,
                top,
                DVec3::new(x, y, z - 1.0),
                DVec3::new(x, y, z + 1.0),
                LineKind::Segment,
            )
            .unwrap()
        };
        let corners: Vec<DVec3> = solid
            .face_vertices(top)
            .map(|v| solid.position(v))
            .collect();
        // Every corner is hit as a vertex, every edge midpoint as an edge.
        for (i, &p) in corners.iter().enumerate() {
            assert!(matches!(line(p.x, p.y), LineFaceHit::OnVertex { u, .. } if u == 0.5));
            let q = corners[(i + 1) % corners.len()];
            let m = (p + q) * 0.5;
            assert!(matches!(line(m.x, m.y), LineFaceHit::OnEdge { .. }), "{m}");
        }
        let b = solid.bounding_box();
        assert_eq!(line(b.max.x + 1.0, b.max.y + 1.0), LineFaceHit::Miss);
        let s = intersect_line_face(
            &solid,
            top,
            DVec3::new(0.0, 0.0, z),
            DVec3::new(1.0, 0.0, z),
            LineKind::Line,
        )
        .unwrap();
        assert_eq!(s, LineFaceHit::InPlane);
        let s = intersect_line_face(
            &solid,
            top,
            DVec3::new(0.0, 0.0, z + 1.0),
            DVec3::new(1.0, 0.0, z + 1.0),
            LineKind::Line,
        )
        .unwrap();
        assert_eq!(s, LineFaceHit::Parallel);
    }

    #[test]
    fn ranges_of_rays_and_segments_and_the_notch_of_a_non_convex_face() {
        let solid = builders::l_prism();
        let top = top_face(&solid);
        let hit =
            |p1: DVec3, p2: DVec3, kind| intersect_line_face(&solid, top, p1, p2, kind).unwrap();
        let below = DVec3::new(0.5, 0.5, 0.0);
        let above = DVec3::new(0.5, 0.5, 2.0);
        // The plane z = 1 is crossed at u = 0.5 going up.
        assert_eq!(
            hit(below, above, LineKind::Segment),
            LineFaceHit::Inside { u: 0.5 }
        );
        // A ray pointing away from the face misses; the line does not.
        assert_eq!(
            hit(above, above + DVec3::Z, LineKind::Ray),
            LineFaceHit::Miss
        );
        assert!(matches!(
            hit(above, above + DVec3::Z, LineKind::Line),
            LineFaceHit::Inside { .. }
        ));
        // A segment ending short of the plane misses; ending on it hits at u = 1.
        let short = DVec3::new(0.5, 0.5, 0.5);
        assert_eq!(hit(below, short, LineKind::Segment), LineFaceHit::Miss);
        assert_eq!(
            hit(below, DVec3::new(0.5, 0.5, 1.0), LineKind::Segment),
            LineFaceHit::Inside { u: 1.0 }
        );
        // The notch of the L (x, y in (1, 2)) is outside the face.
        let notch = |z: f64| DVec3::new(1.5, 1.5, z);
        assert_eq!(
            hit(notch(0.0), notch(2.0), LineKind::Segment),
            LineFaceHit::Miss
        );
        // A slanted line through the reflex corner (1, 1, 1).
        assert!(matches!(
            hit(DVec3::new(0.0, 0.0, 0.0), DVec3::new(2.0, 2.0, 2.0), LineKind::Line),
            LineFaceHit::OnVertex { u, .. } if u == 0.5
        ));
        // Bad input is an error.
        assert!(intersect_line_face(&solid, top, below, below, LineKind::Line).is_err());
        assert!(
            intersect_line_face(&solid, top, below, DVec3::splat(f64::NAN), LineKind::Line)
                .is_err()
        );
    }
}
