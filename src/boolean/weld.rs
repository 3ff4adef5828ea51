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

/// The operands with every vertex of a later operand that lies within
/// `reach` of a vertex of an earlier one (and not on it) moved onto the
/// nearest such vertex, and how many moved. Returns `None` when none
/// moved.
pub(super) fn welded(operands: &[&Solid], reach: f64) -> Option<(Vec<Solid>, usize)> {
    // Earlier operands' vertices, by grid cell of side `reach`.
    let cell = |p: DVec3| (p / reach).floor().to_array().map(|x| x as i64);
    let mut anchors: HashMap<[i64; 3], Vec<DVec3>> = HashMap::default();
    let mut out = Vec::with_capacity(operands.len());
    let mut moved = 0;
    for solid in operands {
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
            if let Some((d, q)) = nearest
                && d > 0.0
            {
                moves.push((v, q));
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
    fn vertices_apart_by_more_than_the_reach_stay() {
        let a = builders::cuboid(DVec3::splat(-1.0), DVec3::splat(1.0)).expect("a box");
        let b = builders::cuboid(DVec3::splat(-0.5), DVec3::splat(1.5)).expect("a box");
        let largest = *reaches(&[&a, &b]).last().expect("a reach");
        assert!(welded(&[&a, &b], largest).is_none());
    }
}
