//! The last resort after the weld: sheets of two operands that lie nearly
//! in one slanted plane pushed apart, so that they no longer cross.
//!
//! Two operands modelled on one surface (a body and the mask cut from it)
//! can have faces a few units in the last place apart and turned by
//! 10⁻⁸ rad against each other. Their exact boolean is a tangle of wedges
//! a few ulps thick along the lines where the sheets cross, which no
//! rounding to `f64` keeps valid; and unlike axis-aligned faces
//! (`weld::onto_axis_planes`), a slanted plane holds almost no `f64`
//! point, so the sheets cannot be made to coincide. Instead each vertex of
//! such a face is moved along the other face's normal until it lies at
//! least the reach away, on one side: a later operand's face either grows
//! past the earlier one's (moves along its own outward normal) or shrinks
//! behind it; `combine` tries both. The sheets then meet nowhere, or only
//! transversally, and the wedges are gone. The move is within the weld's
//! reach (at most 2⁻²⁸ of the operands' size, plus the face's own
//! deviation); the moved operands are proven valid before they are used,
//! and the moved vertices are counted with the welded ones.

use glam::DVec3;
use rustc_hash::FxHashMap as HashMap;

use crate::geom::{Aabb, Sign, orient3d};
use crate::mesh::{FaceId, Solid, VertexId};
use crate::spatial::Bvh;

/// Which way a later operand's nearly coincident sheet moves against an
/// earlier operand's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Side {
    /// Along the later operand's outward normal: past the earlier sheet.
    Grow,
    /// Against it: behind the earlier sheet.
    Shrink,
}

/// One face, as the push needs it: its vertices, a unit normal pointing
/// out of its solid, a point of it, and three vertices spanning it (the
/// largest triangle of its fan) for the exact coplanarity test.
struct SheetFace {
    vertices: Vec<VertexId>,
    points: Vec<DVec3>,
    normal: DVec3,
    spanning: [DVec3; 3],
    bounds: Aabb,
}

impl SheetFace {
    fn of(solid: &Solid, f: FaceId) -> Option<SheetFace> {
        let plane = solid.face(f).plane?;
        let vertices: Vec<VertexId> = solid.face_vertices(f).collect();
        let points: Vec<DVec3> = vertices.iter().map(|&v| solid.vertex(v).position).collect();
        let first = *points.first()?;
        let spanning = points
            .windows(2)
            .skip(1)
            .map(|w| [first, w[0], w[1]])
            .max_by(|a, b| area(a).total_cmp(&area(b)))?;
        let bounds = Aabb::from_points(points.iter().copied());
        Some(SheetFace {
            vertices,
            points,
            normal: plane.normal,
            spanning,
            bounds,
        })
    }

    /// The signed distance of `p` from the face's plane (through its first
    /// spanning vertex), along its normal.
    fn height(&self, p: DVec3) -> f64 {
        (p - self.spanning[0]).dot(self.normal)
    }

    /// Whether every point of `other` lies within `reach` of this face's
    /// plane and at least one lies off it (decided exactly).
    fn nearly_holds(&self, other: &SheetFace, reach: f64) -> bool {
        other.points.iter().all(|&p| self.height(p).abs() <= reach)
            && other.points.iter().any(|&p| {
                let [a, b, c] = self.spanning;
                orient3d(a, b, c, p) != Sign::Zero
            })
    }
}

fn area(t: &[DVec3; 3]) -> f64 {
    (t[1] - t[0]).cross(t[2] - t[0]).length()
}

/// The faces of one solid that can be pushed, with a tree over their
/// boxes.
struct Sheets {
    faces: Vec<SheetFace>,
    tree: Bvh,
    order: Vec<u32>,
}

impl Sheets {
    fn of(solid: &Solid) -> Sheets {
        let faces: Vec<SheetFace> = solid
            .faces()
            .filter_map(|(f, _)| SheetFace::of(solid, f))
            .collect();
        let (tree, order) = Bvh::build_by(faces.len(), |i| faces[i].bounds);
        Sheets { faces, tree, order }
    }

    /// Calls `visit` with every face whose box comes within `reach` of
    /// `bounds`.
    fn near(&self, bounds: &Aabb, reach: f64, mut visit: impl FnMut(&SheetFace)) {
        let query = Aabb {
            min: bounds.min - DVec3::splat(reach),
            max: bounds.max + DVec3::splat(reach),
        };
        self.tree.items_overlapping(
            &query,
            |p| self.faces[self.order[p] as usize].bounds,
            |p| visit(&self.faces[self.order[p] as usize]),
        );
    }
}

/// The largest push each vertex needs: the direction (a unit normal) and
/// how far along it.
#[derive(Default)]
struct Pushes(HashMap<VertexId, (DVec3, f64)>);

impl Pushes {
    /// Asks that `v`, at `p`, end at least `reach` from the plane of
    /// `face` on the side `direction` (± its normal) points to.
    fn ask(&mut self, v: VertexId, p: DVec3, face: &SheetFace, direction: DVec3, reach: f64) {
        let height = (p - face.spanning[0]).dot(direction);
        let shift = reach - height;
        if shift <= 0.0 {
            return;
        }
        let entry = self.0.entry(v).or_insert((direction, 0.0));
        if shift > entry.1 {
            *entry = (direction, shift);
        }
    }

    fn moves(&self, solid: &Solid) -> Vec<(VertexId, DVec3)> {
        let mut moves: Vec<(VertexId, DVec3)> = self
            .0
            .iter()
            .map(|(&v, &(direction, shift))| (v, solid.vertex(v).position + direction * shift))
            .collect();
        moves.sort_unstable_by_key(|&(v, _)| v);
        moves
    }
}

/// The operands with every face of a later operand that lies nearly (not
/// exactly) in the plane of an earlier operand's face moved to lie at
/// least `reach` from it on `side`, and the earlier operand's faces that
/// lie nearly in a later face's plane moved the opposite way; and how
/// many vertices moved. `None` when nothing lies nearly in another
/// operand's plane.
pub(super) fn pushed_apart(
    operands: &[&Solid],
    reach: f64,
    side: Side,
) -> Option<(Vec<Solid>, usize)> {
    let sheets: Vec<Sheets> = operands.iter().map(|s| Sheets::of(s)).collect();
    let mut pushes: Vec<Pushes> = operands.iter().map(|_| Pushes::default()).collect();
    let sign = match side {
        Side::Grow => 1.0,
        Side::Shrink => -1.0,
    };
    for (k, later) in sheets.iter().enumerate() {
        for (j, earlier) in sheets.iter().enumerate().take(k) {
            for face in &later.faces {
                earlier.near(&face.bounds, reach, |other| {
                    // The later face moves along its outward normal (grow)
                    // or against it, away from the earlier face's plane.
                    let toward = sign * face.normal;
                    if other.nearly_holds(face, reach) {
                        let direction = other.normal * toward.dot(other.normal).signum();
                        for (&v, &p) in face.vertices.iter().zip(&face.points) {
                            pushes[k].ask(v, p, other, direction, reach);
                        }
                    }
                    if face.nearly_holds(other, reach) {
                        let direction = -toward;
                        for (&v, &p) in other.vertices.iter().zip(&other.points) {
                            pushes[j].ask(v, p, face, direction, reach);
                        }
                    }
                });
            }
        }
    }
    let mut moved = 0;
    let out: Vec<Solid> = operands
        .iter()
        .zip(&pushes)
        .map(|(solid, push)| {
            let moves = push.moves(solid);
            moved += moves.len();
            let mut copy = (*solid).clone();
            copy.move_vertices(&moves);
            copy
        })
        .collect();
    (moved > 0).then_some((out, moved))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;
    use glam::{DAffine3, DQuat};

    /// A slab whose top is turned by 10⁻¹³ rad about a slanted axis lies
    /// nearly in the plane of a tilted block's top: pushed to grow, every
    /// vertex of its top ends at least the reach above the block's top
    /// plane; the slab stays a consistent solid.
    #[test]
    fn a_nearly_coplanar_slanted_top_is_pushed_past_the_other() {
        let tilt = DAffine3::from_quat(DQuat::from_rotation_x(0.3) * DQuat::from_rotation_y(0.2));
        let mut block = builders::cuboid(DVec3::new(-5.0, -5.0, -2.0), DVec3::new(5.0, 5.0, 0.0))
            .expect("a block");
        assert!(block.move_by(tilt));
        let mut slab = builders::cuboid(DVec3::new(-2.0, -2.0, -1.0), DVec3::new(2.0, 2.0, 0.0))
            .expect("a slab");
        assert!(slab.move_by(tilt * DAffine3::from_quat(DQuat::from_rotation_x(1e-13))));
        let reach = 1e-9;
        let (pushed, moved) =
            pushed_apart(&[&block, &slab], reach, Side::Grow).expect("the top moved");
        assert!(moved >= 4, "{moved}");
        let up = tilt.transform_vector3(DVec3::Z);
        let top = tilt.transform_point3(DVec3::ZERO);
        let mut above = 0;
        for (_, v) in pushed[1].vertices() {
            let h = (v.position - top).dot(up);
            if h.abs() < 0.5 {
                assert!(h >= reach * 0.99, "{h}");
                above += 1;
            }
        }
        assert_eq!(above, 4);
        assert!(pushed[1].check_consistency().is_ok());
    }

    /// Faces exactly in one plane (a box on another's top) stay where they
    /// are: they need no push, the exact stages handle them.
    #[test]
    fn exactly_coplanar_faces_are_not_pushed() {
        let a = builders::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0)).expect("a box");
        let b = builders::cuboid(DVec3::new(-0.5, -0.5, 1.0), DVec3::splat(1.5)).expect("a box");
        assert!(pushed_apart(&[&a, &b], 1e-6, Side::Grow).is_none());
    }
}
