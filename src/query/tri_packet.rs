//! A BVH leaf's triangles four at a time in `f32`: a filter that proves
//! most of a ray's misses before any exact test.
//!
//! A ray meets a BVH leaf's box far more often than it crosses one of the
//! leaf's triangles. Each leaf keeps a copy of its triangles' corners in the
//! accel's [`BoxFrame`], rounded to `f32` and laid out lane by lane, so that
//! the three edge signs of all four triangles are computed side by side in
//! one pass. A triangle is dropped only when two of its edge signs are
//! *proven* opposite (see [`PacketRay`] for the bound): then the exact line
//! misses the closed triangle, and the exact test would have said so. Every
//! other triangle — the ones the ray crosses, and misses too close to call —
//! goes on to the exact test on the `f64` input coordinates, which alone
//! decides. The filter changes no answer, only how many exact tests run.

use crate::geom::Ray;

use super::accel::{BoxFrame, YzTri};
use super::lanes::F32x4;

/// Triangles per packet: the most a BVH leaf holds.
pub(super) const LANES: usize = 4;

/// The triangles of one BVH leaf: their corners in the accel's
/// [`BoxFrame`], each the `f64` frame coordinate rounded to the nearest
/// `f32`, stored lane by lane (160 bytes).
///
/// # Invariants
///
/// Lanes `0 .. count` hold the triangles `first .. first + count` of the
/// accel, in order; the other lanes hold zeros and are never reported.
/// Every stored coordinate is at most the accel's `packet_extent` in
/// magnitude.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(32))]
pub(super) struct TriPacket {
    /// `corners[3 · c + a][lane]`: axis `a` of corner `c`.
    corners: [[f32; LANES]; 9],
    /// The leaf's first triangle (an index into the accel's triangles).
    pub first: u32,
    /// The leaf's number of triangles, `1 ..= LANES`.
    pub count: u32,
}

impl TriPacket {
    /// The packet of the leaf holding `tris[first .. first + count]`.
    pub(super) fn new(tris: &[YzTri], first: u32, count: u32, frame: &BoxFrame) -> TriPacket {
        debug_assert!((1..=LANES as u32).contains(&count));
        let mut corners = [[0.0f32; LANES]; 9];
        for lane in 0..count as usize {
            let t = &tris[first as usize + lane];
            for c in 0..3 {
                let p = [t.x[c], t.y[c], t.z[c]];
                for a in 0..3 {
                    corners[3 * c + a][lane] = frame.in_frame(p[a], a) as f32;
                }
            }
        }
        TriPacket {
            corners,
            first,
            count,
        }
    }

    /// The largest magnitude of a stored coordinate.
    pub(super) fn extent(&self) -> f32 {
        self.corners
            .iter()
            .flatten()
            .fold(0.0f32, |m, &x| m.max(x.abs()))
    }

    /// A bit mask of the lanes whose triangle the exact test must still
    /// decide: every lane except those whose miss is proven (bit `k` for
    /// the triangle `first + k`). Branch-free over the four lanes, so that
    /// the compiler keeps each quantity of all four in one vector register.
    #[inline(always)]
    pub(super) fn undecided(&self, r: &PacketRay) -> u32 {
        let rel = |row: usize| F32x4::load(&self.corners[row]).sub(r.origin[row % 3]);
        let u = [rel(0), rel(1), rel(2)];
        let v = [rel(3), rel(4), rel(5)];
        let w = [rel(6), rel(7), rel(8)];
        let d = &r.direction;
        // det[d, p, q] = d · (p × q), evaluated as in the bound's proof:
        // the three terms summed left to right.
        let side = |p: &[F32x4; 3], q: &[F32x4; 3]| {
            let t0 = d[0].mul(p[1].mul(q[2]).sub(p[2].mul(q[1])));
            let t1 = d[1].mul(p[2].mul(q[0]).sub(p[0].mul(q[2])));
            let t2 = d[2].mul(p[0].mul(q[1]).sub(p[1].mul(q[0])));
            t0.add(t1).add(t2)
        };
        let (e0, e1, e2) = (side(&u, &v), side(&v, &w), side(&w, &u));
        let (pos, neg) = (r.bound, r.neg_bound);
        let any_pos = e0.gt(pos).or(e1.gt(pos)).or(e2.gt(pos));
        let any_neg = e0.lt(neg).or(e1.lt(neg)).or(e2.lt(neg));
        let proven_miss = any_pos.and(any_neg).bits();
        !proven_miss & ((1u32 << self.count) - 1)
    }
}

/// A ray as [`TriPacket::undecided`] sees it: origin and direction rounded
/// to `f32` in the accel's frame, and the error bound that proves signs.
///
/// # Why a proven sign is the exact sign
///
/// Let `u = 2⁻²⁴`. The ray is `o + t·D` with `D` already scaled so that its
/// largest component is in `[1, 2)` (so `D` and its `f32` rounding `D̃`
/// are far from overflow; `|D̃ᵢ − Dᵢ| ≤ u·|D̃ᵢ| + 2⁻¹⁵⁰`). In the frame, a
/// corner `p` is the real `P = (p − c)·s` and the origin `O = (o − c)·s`;
/// the stored `P̃` and `Õ` are the `f64` frame coordinates rounded to
/// nearest `f32`, so `|P̃ − P| ≤ u·(1 + 2⁻²²)·|P̃| + 2⁻¹⁴⁹`, and likewise
/// for `Õ`. For an edge `(p, q)` the exact test decides the sign of
/// `E = det[D, P − O, Q − O] = s²·det[D, p − o, q − o]` (`s > 0`), the
/// same sign.
///
/// With `R = max(M + |Õ|∞, 2⁻⁴⁰)`, `M` the accel's largest stored
/// coordinate, and `S = |D̃|₁`: the computed `ũ = fl(P̃ − Õ)` has
/// `|ũ|∞ ≤ R(1 + u)` and `|ũ − (P − O)|∞ ≤ u·R + u(1 + 2⁻²²)·R + 2⁻¹⁴⁸ ≈
/// 2u·R`. Since `|det[x, y, z]| ≤ |x|₁ · 2|y|∞|z|∞`, replacing `D, P − O,
/// Q − O` by `D̃, ũ, ṽ` one at a time changes the determinant by at most
/// `2u·S·R² + 4u·S·R² + 4u·S·R²`; evaluating it in `f32` as three terms
/// `dᵢ·(pⱼqₖ − pₖqⱼ)` summed left to right (at most five roundings on any
/// term's path) adds at most `γ₅·2S·R² ≈ 10u·S·R²`. The total is below
/// `21u·S·R²` (the absolute terms of `f32` underflow are below `2⁻¹⁴⁰·S·R`,
/// negligible as `R ≥ 2⁻⁴⁰`). The bound used is `32u·S·R²`, computed in
/// `f32` with at most five roundings, so still above `31u·S·R²`: a computed
/// determinant beyond it in magnitude has the exact sign of `E`.
///
/// Two edge signs proven opposite mean the exact line passes strictly
/// outside one edge's side and strictly inside another's: it misses the
/// closed triangle (its symbolic perturbation cannot change a non-zero sign
/// either), so the exact test would report a miss, and the ray's origin is
/// not on the triangle. A non-finite origin (beyond the `f32` range) makes
/// the bound `+∞` or NaN, which proves nothing.
#[derive(Clone, Copy, Debug)]
pub(super) struct PacketRay {
    /// `Õ`: the origin in the frame, rounded to nearest `f32`, per axis in
    /// every lane.
    origin: [F32x4; 3],
    /// `D̃`: the (already scaled) direction rounded to nearest `f32`.
    direction: [F32x4; 3],
    /// `32u·S·R²` (see above).
    bound: F32x4,
    /// `−bound`.
    neg_bound: F32x4,
}

/// `32 · 2⁻²⁴`: the factor of [`PacketRay::bound`].
const SIDE_BOUND: f32 = 32.0 / (1u32 << 24) as f32;

impl PacketRay {
    /// `ray` (with its direction scaled by
    /// [`unit_scaled`](super::ray_solid::unit_scaled)) against the packets
    /// of an accel with frame `frame` and largest stored coordinate
    /// `extent`.
    pub(super) fn new(ray: &Ray, frame: &BoxFrame, extent: f32) -> PacketRay {
        let origin = [0, 1, 2].map(|a| frame.in_frame(ray.origin[a], a) as f32);
        let direction = [0, 1, 2].map(|a| ray.direction[a] as f32);
        let s = direction[0].abs() + direction[1].abs() + direction[2].abs();
        let reach = extent + origin[0].abs().max(origin[1].abs()).max(origin[2].abs());
        let r = reach.max(1.0 / (1u64 << 40) as f32);
        let bound = SIDE_BOUND * s * (r * r);
        PacketRay {
            origin: origin.map(F32x4::splat),
            direction: direction.map(F32x4::splat),
            bound: F32x4::splat(bound),
            neg_bound: F32x4::splat(-bound),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::{Sign, line_side_sos};
    use glam::DVec3;

    fn tri(p: [DVec3; 3]) -> YzTri {
        YzTri {
            x: [p[0].x, p[1].x, p[2].x],
            y: [p[0].y, p[1].y, p[2].y],
            z: [p[0].z, p[1].z, p[2].z],
            sigma: 0,
        }
    }

    /// Every triangle the filter drops is missed by the exact line (two
    /// exact edge signs opposite): random triangles and rays at many
    /// scales and offsets, many of them grazing an edge or a vertex to
    /// within a few ulps, where the `f32` values are pure noise.
    #[test]
    fn a_dropped_triangle_is_an_exact_miss() {
        let mut state = 0x2545_F491_4F6C_DD1Du64;
        let mut uniform = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut dropped, mut kept) = (0, 0);
        for case in 0..20_000 {
            let centre = DVec3::new(uniform(), uniform(), uniform()) * 2e6 - DVec3::splat(1e6);
            let scale = 2f64.powi((uniform() * 60.0) as i32 - 30);
            let frame = BoxFrame {
                centre,
                scale: 1.0 / scale,
            };
            let mut rand = || DVec3::new(uniform(), uniform(), uniform()) * 2.0 - DVec3::ONE;
            let tris: Vec<YzTri> = (0..LANES)
                .map(|_| {
                    let a = centre + rand() * scale * 0.9;
                    tri([a, a + rand() * scale * 0.05, a + rand() * scale * 0.05])
                })
                .collect();
            let count = 1 + case % LANES as u32;
            let packet = TriPacket::new(&tris, 0, count, &frame);
            let extent = packet.extent();
            // Aim at a corner, at a point of an edge, or anywhere, and nudge
            // by a few ulps.
            let target_tri = tris[case as usize % count as usize].corners();
            let aim = match case % 3 {
                0 => target_tri[case as usize % 3],
                1 => target_tri[0].lerp(target_tri[1], rand().x * 0.5 + 0.5),
                _ => centre + rand() * scale,
            };
            let nudge = rand() * scale * f64::EPSILON * 8.0 * (case % 2) as f64;
            let origin = centre + rand() * scale * 3.0;
            let direction = aim + nudge - origin;
            if direction == DVec3::ZERO {
                continue;
            }
            let (ray, _) = super::super::ray_solid::unit_scaled(&Ray::new(origin, direction));
            let r = PacketRay::new(&ray, &frame, extent);
            let mask = packet.undecided(&r);
            assert_eq!(mask >> count, 0, "case {case}: lanes beyond the leaf");
            for (lane, t) in tris.iter().enumerate().take(count as usize) {
                if mask & (1 << lane) != 0 {
                    kept += 1;
                    continue;
                }
                dropped += 1;
                let [a, b, c] = t.corners();
                let signs = [(a, b), (b, c), (c, a)]
                    .map(|(p, q)| line_side_sos(ray.origin, ray.direction, p, q));
                assert!(
                    signs.contains(&Sign::Positive) && signs.contains(&Sign::Negative),
                    "case {case} lane {lane}: dropped but exact signs {signs:?}"
                );
            }
        }
        assert!(
            dropped > 10_000 && kept > 5_000,
            "{dropped} dropped, {kept} kept"
        );
    }
}
