//! The output stage's last resort: operands welded where their vertices
//! lie closer together than `f64` can keep apart, and the boolean run
//! again.
//!
//! Copies of one solid turned by 10⁻¹⁵ rad have vertices a few units in
//! the last place apart. The exact result is a tangle of slivers between
//! near-coincident sheets, and when the output rounds (`output`) cannot
//! make its rounded form valid, moving each such vertex onto its twin in
//! an earlier operand removes the slivers at their source. The move is
//! within the same reach the output's own fixes have (a few ulps, at most
//! a relative 2⁻²⁸ of the operands' size); each welded operand is proven
//! valid before it is used, and the count is reported
//! ([`super::OutputWork::welded_vertices`]).

use glam::DVec3;
use rustc_hash::FxHashMap as HashMap;

use super::apart::{Side, pushed_apart};
use crate::mesh::{Solid, VertexId};

/// The smallest reach tried, in units in the last place of the largest
/// coordinate.
const FIRST_REACH_ULPS: f64 = 64.0;

/// How much the reach grows from one try to the next.
const REACH_GROWTH: f64 = 64.0;

/// The largest reach, as a fraction of the operands' size (2⁻²⁸, as the
/// output's fixes).
const MAX_REACH_OF_SIZE: f64 = 1.0 / (1u64 << 28) as f64;

/// The reaches to try, smallest first, for operands spanning `lo`…`hi`.
pub(super) fn reaches(operands: &[&Solid]) -> Vec<f64> {
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for s in operands {
        for (_, v) in s.vertices() {
            lo = lo.min(v.position);
            hi = hi.max(v.position);
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return Vec::new();
    }
    let largest = lo.abs().max(hi.abs()).max_element();
    let ulp = (largest.next_up() - largest).max(f64::MIN_POSITIVE);
    let cap = (hi - lo).length() * MAX_REACH_OF_SIZE;
    let mut out = Vec::new();
    let mut reach = FIRST_REACH_ULPS * ulp;
    while reach < cap {
        out.push(reach);
        reach *= REACH_GROWTH;
    }
    out.push(cap.max(FIRST_REACH_ULPS * ulp));
    out
}

/// The last resorts, in order, until `attempt` (prove the moved operands
/// valid and evaluate them again) succeeds: at each reach, smallest first,
/// the operands welded ([`welded`]); then, from the welded operands (or
/// the given ones when nothing welded), sheets nearly in one slanted
/// plane pushed apart, the later operand's growing past the earlier's,
/// then shrinking behind it ([`super::apart`]). `attempt` gets the moved
/// operands and how many vertices moved in all.
pub(super) fn retried<T>(
    solids: &[&Solid],
    mut attempt: impl FnMut(&[Solid], usize) -> Option<T>,
) -> Option<T> {
    for reach in reaches(solids) {
        let welded = welded(solids, reach);
        if let Some((welded, moved)) = &welded
            && let Some(answer) = attempt(welded, *moved)
        {
            return Some(answer);
        }
        let (base, welded_count): (Vec<&Solid>, usize) = match &welded {
            Some((w, moved)) => (w.iter().collect(), *moved),
            None => (solids.to_vec(), 0),
        };
        for side in [Side::Grow, Side::Shrink] {
            if let Some((pushed, moved)) = pushed_apart(&base, reach, side)
                && let Some(answer) = attempt(&pushed, welded_count + moved)
            {
                return Some(answer);
            }
        }
    }
    None
}

/// The operands with every vertex of a later operand that lies within
/// `reach` of a vertex of an earlier one (and not on it) moved onto the
/// nearest such vertex, then every other vertex within `reach` of the
/// plane of another operand's axis-aligned face put on that plane (all of
/// a nearly coplanar face moves, not only what lies over the other face) ([`onto_axis_planes`]), and how many moved. Returns
/// `None` when none moved.
pub(super) fn welded(operands: &[&Solid], reach: f64) -> Option<(Vec<Solid>, usize)> {
    // Earlier operands' vertices, by grid cell of side `reach`.
    let cell = |p: DVec3| (p / reach).floor().to_array().map(|x| x as i64);
    let mut anchors: HashMap<[i64; 3], Vec<DVec3>> = HashMap::default();
    let planes = AxisPlanes::of(operands);
    let mut out = Vec::with_capacity(operands.len());
    let mut moved = 0;
    for (k, solid) in operands.iter().enumerate() {
        let mut copy = (*solid).clone();
        let mut moves: Vec<(VertexId, DVec3)> = Vec::new();
        for (v, vertex) in solid.vertices() {
            let p = vertex.position;
            let [x, y, z] = cell(p);
            let mut nearest: Option<(f64, DVec3)> = None;
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        for &q in anchors.get(&[x + dx, y + dy, z + dz]).into_iter().flatten() {
                            let d = (q - p).length();
                            if d <= reach && nearest.is_none_or(|(best, _)| d < best) {
                                nearest = Some((d, q));
                            }
                        }
                    }
                }
            }
            match nearest {
                Some((d, q)) if d > 0.0 => moves.push((v, q)),
                Some(_) => {}
                None => {
                    let q = planes.onto_axis_planes(k, v, p, reach);
                    if q != p {
                        moves.push((v, q));
                    }
                }
            }
        }
        moved += moves.len();
        copy.move_vertices(&moves);
        for (_, vertex) in copy.vertices() {
            anchors
                .entry(cell(vertex.position))
                .or_default()
                .push(vertex.position);
        }
        out.push(copy);
    }
    (moved > 0).then_some((out, moved))
}

/// A face whose vertices all share one coordinate: its plane is exact in
/// `f64`, so a vertex can be put on it exactly.
struct AxisFace {
    operand: usize,
    /// The coordinate all its vertices share.
    value: f64,
}

/// The axis-aligned faces of all operands, per axis, sorted by their
/// coordinate; and the vertices on such faces, per operand and axis.
struct AxisPlanes {
    faces: [Vec<AxisFace>; 3],
    on_own: Vec<[rustc_hash::FxHashSet<VertexId>; 3]>,
}

impl AxisPlanes {
    fn of(operands: &[&Solid]) -> AxisPlanes {
        let mut faces: [Vec<AxisFace>; 3] = Default::default();
        let mut on_own = Vec::with_capacity(operands.len());
        for (k, solid) in operands.iter().enumerate() {
            let mut own: [rustc_hash::FxHashSet<VertexId>; 3] = Default::default();
            for (f, _) in solid.faces() {
                let vertices: Vec<VertexId> = solid.face_vertices(f).collect();
                let points: Vec<DVec3> =
                    vertices.iter().map(|&v| solid.vertex(v).position).collect();
                let Some(first) = points.first() else {
                    continue;
                };
                for axis in 0..3 {
                    if points.iter().any(|p| p[axis] != first[axis]) {
                        continue;
                    }
                    faces[axis].push(AxisFace {
                        operand: k,
                        value: first[axis],
                    });
                    own[axis].extend(vertices.iter().copied());
                }
            }
            on_own.push(own);
        }
        // Only the planes matter: one entry per operand and coordinate.
        for list in &mut faces {
            list.sort_by(|a, b| a.value.total_cmp(&b.value).then(a.operand.cmp(&b.operand)));
            list.dedup_by(|a, b| a.value == b.value && a.operand == b.operand);
        }
        AxisPlanes { faces, on_own }
    }

    /// `p` (vertex `v` of operand `k`) with each coordinate within `reach`
    /// of the plane of another operand's axis-aligned face set to that
    /// face's; a vertex on an axis-aligned face of its own moves only
    /// onto an earlier operand's plane, so two such faces do not move
    /// towards each other.
    fn onto_axis_planes(&self, k: usize, v: VertexId, p: DVec3, reach: f64) -> DVec3 {
        let mut q = p;
        for axis in 0..3 {
            let list = &self.faces[axis];
            let from = list.partition_point(|f| f.value < p[axis] - reach);
            let own = self.on_own[k][axis].contains(&v);
            let best = list[from..]
                .iter()
                .take_while(|f| f.value <= p[axis] + reach)
                .filter(|f| f.operand != k && (!own || f.operand < k))
                .min_by(|a, b| {
                    (a.value - p[axis])
                        .abs()
                        .total_cmp(&(b.value - p[axis]).abs())
                });
            if let Some(face) = best {
                q[axis] = face.value;
            }
        }
        q
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;
    use glam::{DAffine3, DQuat};

    #[test]
    fn a_copy_turned_by_a_few_ulps_is_welded_onto_the_original() {
        let a = builders::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0)).expect("a box");
        let mut b = a.clone();
        assert!(b.move_by(DAffine3::from_quat(DQuat::from_rotation_z(1e-15))));
        let reach = reaches(&[&a, &b])[0];
        let (welded, moved) = welded(&[&a, &b], reach).expect("some vertices moved");
        assert_eq!(moved, 8);
        let positions = |s: &Solid| {
            let mut p: Vec<[u64; 3]> = s
                .vertices()
                .map(|(_, v)| v.position.to_array().map(f64::to_bits))
                .collect();
            p.sort_unstable();
            p
        };
        assert_eq!(positions(&welded[1]), positions(&a));
    }

    #[test]
    fn a_slab_tilted_by_1e_12_rad_is_put_on_the_box_faces_it_nearly_lies_in() {
        let slab = builders::cuboid(DVec3::new(-10.0, 0.0, -10.0), DVec3::new(10.0, 2.0, 10.0))
            .expect("a slab");
        let mut tilted = slab.clone();
        let turn = DAffine3::from_translation(DVec3::Y)
            * DAffine3::from_quat(DQuat::from_rotation_x(1e-12))
            * DAffine3::from_translation(-DVec3::Y);
        assert!(tilted.move_by(turn));
        let block = builders::cuboid(DVec3::new(0.0, 0.0, 0.0), DVec3::new(30.0, 2.0, 5.0))
            .expect("a block");
        let reach = *reaches(&[&tilted, &block]).last().expect("a reach");
        let (welded, moved) = welded(&[&tilted, &block], reach).expect("some vertices moved");
        assert_eq!(moved, 8);
        for (_, v) in welded[0].vertices() {
            assert!(v.position.y == 0.0 || v.position.y == 2.0, "{}", v.position);
        }
        assert!(welded[0].check_consistency().is_ok());
    }

    #[test]
    fn vertices_apart_by_more_than_the_reach_stay() {
        let a = builders::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0)).expect("a box");
        let b = builders::cuboid(DVec3::splat(-0.5), DVec3::splat(1.5)).expect("a box");
        let largest = *reaches(&[&a, &b]).last().expect("a reach");
        assert!(welded(&[&a, &b], largest).is_none());
    }
}
