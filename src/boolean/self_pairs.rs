//! The broad phase of one soup against itself: which pairs of its
//! triangles meet.
//!
//! The BVH's self pair walk hands over the pairs of triangles whose boxes
//! overlap. Where long triangles run diagonally across a model (CAD
//! exports and offsets have many), or many triangles fan around one
//! vertex, those pairs are far more than the pairs that meet (manifold's
//! `Generic_Twin_7081`: 22 million pairs of boxes among 11,656 triangles,
//! 1.9 million of them sharing a corner, 64 that cross), and the exact
//! test of each was most of the repair's time. So every pair first meets
//! two fast `f64` filters with Shewchuk's static error bounds (1997),
//! which can only answer "apart" when it is so: one triangle's corners
//! strictly on one side of the other's plane, or an edge of one with the
//! other's corners strictly outside it in the projection along the axis
//! of the first's largest normal component — in both, a corner the two
//! triangles share is passed over (it lies exactly on the plane and on the
//! edges through it). The pairs left are sorted and each decided exactly
//! by `intersect::contact` on all cores.

use rayon::prelude::*;

use crate::geom::{Sign, orient3d, projected_orientation};

use super::intersect::{self, Contact, PointRef, Tri};
use super::operand::Prepared;

/// A triangle's plane as a fast, conservative filter: `separates(t)` only
/// when every corner of `t` lies strictly on one side of it. The sign of
/// `(p − a) · ((b − a) × (c − a))` is read in `f64` and trusted when its
/// magnitude exceeds 2⁻⁴⁹ times the permanent (the same sum of products of
/// absolute values): Shewchuk's static bound for `orient3d` (1997) is
/// `(7 + 56ε)ε` times it, `ε = 2⁻⁵³`, below that.
#[derive(Clone, Copy, Debug)]
struct PlaneFilter {
    corner: glam::DVec3,
    normal: glam::DVec3,
    /// The normal's components with every product taken in absolute value.
    normal_abs: glam::DVec3,
}

impl PlaneFilter {
    fn new([a, b, c]: [glam::DVec3; 3]) -> PlaneFilter {
        let (e, f) = (b - a, c - a);
        let (ea, fa) = (e.abs(), f.abs());
        PlaneFilter {
            corner: a,
            normal: e.cross(f),
            normal_abs: glam::DVec3::new(
                ea.y * fa.z + ea.z * fa.y,
                ea.z * fa.x + ea.x * fa.z,
                ea.x * fa.y + ea.y * fa.x,
            ),
        }
    }

    /// The side of `p`, when the filter can tell it.
    fn side(&self, p: glam::DVec3) -> Sign {
        let w = p - self.corner;
        let det = w.dot(self.normal);
        let bound = w.abs().dot(self.normal_abs) * (1.0 / (1u64 << 49) as f64);
        certain_sign(det, bound)
    }

    /// Whether the corners of `t` (vertex ids `ids`) all lie strictly on
    /// one side, but those that are corners of this plane's own triangle
    /// (`own`: exactly on it), at least one of them (so the two triangles
    /// share no point but their shared corners).
    fn separates(&self, t: &[glam::DVec3; 3], ids: [u32; 3], own: [u32; 3]) -> bool {
        let mut side = Sign::Zero;
        for (p, id) in t.iter().zip(ids) {
            if own.contains(&id) {
                continue;
            }
            let s = self.side(*p);
            if s == Sign::Zero || (side != Sign::Zero && s != side) {
                return false;
            }
            side = s;
        }
        side != Sign::Zero
    }
}

/// Every pair of distinct triangles of the operand that meet, each once
/// (smaller index first, pairs in increasing order), with its contact.
/// Two triangles sharing an edge meet only along it when they are not
/// coplanar or lie on either side of it, and are skipped; a contact that
/// is only shared corners is dropped.
pub(super) fn self_contacts(operand: &Prepared) -> Vec<(u32, u32, Contact)> {
    let planes: Vec<PlaneFilter> = (0..operand.triangles.len() as u32)
        .into_par_iter()
        .map(|t| PlaneFilter::new(operand.corners(t)))
        .collect();
    let (bvh, order) = (&operand.bvh, &operand.order);
    let mut pairs: Vec<(u32, u32)> = bvh.par_self_leaf_pairs(|la, lb, found| {
        let (Some(items_a), Some(items_b)) = (bvh.leaf(la), bvh.leaf(lb)) else {
            return;
        };
        for pa in items_a.range() {
            let ta = order[pa];
            let box_a = operand.bounds[ta as usize];
            for pb in items_b.range() {
                if la == lb && pb <= pa {
                    continue;
                }
                let tb = order[pb];
                if ta == tb
                    || box_a.intersection(operand.bounds[tb as usize]).is_empty()
                    || apart(&planes, operand, ta, tb)
                {
                    continue;
                }
                found.push((ta.min(tb), ta.max(tb)));
            }
        }
    });
    pairs.par_sort_unstable();
    pairs.dedup();
    let tri = |t: u32| Tri {
        corners: operand.corners(t),
        ids: operand.triangles[t as usize],
    };
    pairs
        .into_par_iter()
        .filter_map(|(first, second)| {
            let (a, b) = (
                operand.triangles[first as usize],
                operand.triangles[second as usize],
            );
            if meet_only_along_shared_edge(operand, a, b) {
                return None;
            }
            let contact = intersect::contact(&tri(first), &tri(second))?;
            let shared_only = contact.first_cuts.is_empty()
                && contact.second_cuts.is_empty()
                && contact.coplanar_same.is_none()
                && contact
                    .points
                    .iter()
                    .all(|p| matches!(p, PointRef::Vertex(v) if a.contains(v) && b.contains(v)));
            (!shared_only).then_some((first, second, contact))
        })
        .collect()
}

/// Whether the fast filters prove that triangles `a` and `b` share no
/// point but their shared corners: the corners of one strictly on one side
/// of the other's plane, or their projections along the axis `a`'s normal
/// is largest in apart (an edge of one with the other's corners strictly
/// outside it; disjoint projections are disjoint triangles). A shared
/// corner lies exactly on the other's plane and on its edges through it,
/// and is passed over there: the triangles of a fan around a vertex need
/// no exact test.
fn apart(planes: &[PlaneFilter], operand: &Prepared, a: u32, b: u32) -> bool {
    let (ia, ib) = (operand.triangles[a as usize], operand.triangles[b as usize]);
    let (ca, cb) = (operand.corners(a), operand.corners(b));
    let (pa, pb) = (&planes[a as usize], &planes[b as usize]);
    if pa.separates(&cb, ib, ia) || pb.separates(&ca, ia, ib) {
        return true;
    }
    let axis = pa.normal.abs().max_position();
    let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
    let flat = |t: [glam::DVec3; 3]| t.map(|p| glam::DVec2::new(p[u], p[v]));
    let (fa, fb) = (flat(ca), flat(cb));
    edge_separates(fa, ia, fb, ib) || edge_separates(fb, ib, fa, ia)
}

/// Whether an edge of the flat triangle `t` (vertex ids `ids`) has every
/// corner of `other` strictly on its outer side, but corners that are the
/// edge's own ends (signs by a filtered `orient2d`; an unsure sign never
/// separates).
fn edge_separates(
    t: [glam::DVec2; 3],
    ids: [u32; 3],
    other: [glam::DVec2; 3],
    other_ids: [u32; 3],
) -> bool {
    let own = orient2d_filtered(t[0], t[1], t[2]);
    if own == Sign::Zero {
        return false;
    }
    (0..3).any(|k| {
        let (p, q) = (t[k], t[(k + 1) % 3]);
        let ends = [ids[k], ids[(k + 1) % 3]];
        let mut strict = false;
        for (x, id) in other.iter().zip(other_ids) {
            if ends.contains(&id) {
                continue;
            }
            let s = orient2d_filtered(p, q, *x);
            if s == Sign::Zero || s == own {
                return false;
            }
            strict = true;
        }
        strict
    })
}

/// The sign of `(q − p) × (x − p)` when `f64` can tell it: trusted when
/// its magnitude exceeds 2⁻⁵⁰ times the sum of the products' magnitudes
/// (Shewchuk's static bound for `orient2d` is `(3 + 16ε)ε` times it).
fn orient2d_filtered(p: glam::DVec2, q: glam::DVec2, x: glam::DVec2) -> Sign {
    let (e, f) = (q - p, x - p);
    let (l, r) = (e.x * f.y, e.y * f.x);
    let det = l - r;
    let bound = (l.abs() + r.abs()) * (1.0 / (1u64 << 50) as f64);
    certain_sign(det, bound)
}

/// The sign of a rounded `det` whose error is below `bound`, or `Zero`
/// when the bound does not settle it.
fn certain_sign(det: f64, bound: f64) -> Sign {
    if det > bound {
        Sign::Positive
    } else if det < -bound {
        Sign::Negative
    } else {
        Sign::Zero
    }
}

/// Whether triangles `a` and `b` (vertex indices) share an edge and can
/// meet nowhere else: not coplanar, or coplanar with their third corners
/// on either side of the edge.
fn meet_only_along_shared_edge(operand: &Prepared, a: [u32; 3], b: [u32; 3]) -> bool {
    let mut shared = [0u32; 3];
    let mut count = 0;
    for v in a {
        if b.contains(&v) {
            shared[count] = v;
            count += 1;
        }
    }
    if count != 2 {
        return false;
    }
    let shared = [shared[0], shared[1]];
    let third = |t: [u32; 3]| t.into_iter().find(|v| !shared.contains(v));
    let (Some(x), Some(y)) = (third(a), third(b)) else {
        return false;
    };
    let p = |i: u32| operand.positions[i as usize];
    let (u, v) = (p(shared[0]), p(shared[1]));
    if orient3d(u, v, p(x), p(y)) != Sign::Zero {
        return true;
    }
    (0..3u8).any(|axis| {
        let sx = projected_orientation([u, v, p(x)], axis);
        let sy = projected_orientation([u, v, p(y)], axis);
        sx != Sign::Zero && sy != Sign::Zero && sx != sy
    })
}
