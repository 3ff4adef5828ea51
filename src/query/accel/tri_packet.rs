//! A BVH leaf's triangles four at a time in `f32`: a filter that proves
//! most of a ray's misses before any exact test.
//!
//! A ray meets a BVH leaf's box far more often than it crosses one of the
//! leaf's triangles. Each leaf keeps a copy of its triangles' corners
//! relative to the leaf's own centre, scaled by the scale of the BVH's
//! frame (`spatial::bvh::BoxFrame`) and rounded to `f32`, laid out lane by
//! lane, so that the three edge signs of all four triangles are computed
//! side by side in one pass. Coordinates relative to the leaf keep the rounding error in
//! proportion to the triangles' size, wherever they are and however fine
//! the mesh. A triangle is dropped only when two of its edge signs are
//! *proven* opposite (see [`TriPacket::undecided`] for the bound): then the
//! exact line misses the closed triangle, and the exact test would have
//! said so. Every other triangle — the ones the ray crosses, and misses
//! too close to call — goes on to the exact test on the `f64` input
//! coordinates, which alone decides. The filter changes no answer, only
//! how many exact tests run.

use glam::DVec3;

use crate::geom::{Ray, larger};

use crate::spatial::LEAF_SIZE;
use crate::spatial::raw::lanes::F32x4;

use super::triangle_records::YzTri;

/// Triangles per packet: the most a BVH leaf holds.
pub(in crate::query) const LANES: usize = LEAF_SIZE;

/// The triangles of one BVH leaf: their corners `p` as `(p − centre) ·
/// scale` rounded to the nearest `f32` (through the rounded `f64`
/// difference), stored lane by lane (192 bytes, three cache lines).
///
/// # Invariants
///
/// Lanes `0 .. count` hold the triangles `first .. first + count` of the
/// accel, in order; the other lanes hold zeros and are never reported.
/// `extent` is the largest magnitude of a stored coordinate.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(in crate::query) struct TriPacket {
    /// The middle of the leaf's triangles' box, in input coordinates.
    centre: DVec3,
    /// `corners[3 · c + a][lane]`: axis `a` of corner `c`.
    corners: [[f32; LANES]; 9],
    /// The largest magnitude of a stored coordinate (`+∞` or NaN when a
    /// coordinate is beyond the `f32` range, which disables the filter).
    extent: f32,
    /// The leaf's first triangle (an index into the accel's triangles).
    pub first: u32,
    /// The leaf's number of triangles, `1 ..= LANES`.
    pub count: u32,
}

impl TriPacket {
    /// The packet of the leaf holding `tris[first .. first + count]`, with
    /// the accel's (power-of-two) frame scale `scale`.
    pub(in crate::query) fn new(tris: &[YzTri], first: u32, count: u32, scale: f64) -> TriPacket {
        debug_assert!((1..=LANES as u32).contains(&count));
        let leaf = &tris[first as usize..(first + count) as usize];
        let (lo, hi) = leaf
            .iter()
            .flat_map(YzTri::corners)
            .fold((DVec3::INFINITY, DVec3::NEG_INFINITY), |(lo, hi), p| {
                (lo.min(p), hi.max(p))
            });
        let centre = lo * 0.5 + hi * 0.5;
        let mut corners = [[0.0f32; LANES]; 9];
        for (lane, t) in leaf.iter().enumerate() {
            for (c, p) in t.corners().into_iter().enumerate() {
                for a in 0..3 {
                    corners[3 * c + a][lane] = ((p[a] - centre[a]) * scale) as f32;
                }
            }
        }
        let extent = corners.iter().flatten().fold(0.0f32, |m, &x| {
            if x.abs() > m || x.is_nan() {
                x.abs()
            } else {
                m
            }
        });
        TriPacket {
            centre,
            corners,
            extent,
            first,
            count,
        }
    }

    /// A bit mask of the lanes whose triangle the exact test must still
    /// decide: every lane except those whose miss is proven (bit `k` for
    /// the triangle `first + k`).
    ///
    /// # Why a proven sign is the exact sign
    ///
    /// Let `u = 2⁻²⁴`, `s` the frame scale and `c` the packet's centre. The
    /// ray is `o + t·D`, `D` already scaled so that its largest component
    /// is in `[1, 2)`; `D̃` is `D` rounded to `f32`, `S = |D̃|₁`. For an edge
    /// `(p, q)` of a triangle the exact test decides the sign of
    /// `det[D, p − o, q − o] = s⁻²·det[D, P − V, Q − P]` with the real
    /// `P = (p − c)s`, `Q = (q − c)s`, `V = (o − c)s` (subtracting
    /// `P − V` from the last column changes no determinant). The stored
    /// `P̃` and the ray's `Ṽ` are the rounded `f64` differences, scaled
    /// exactly and rounded to nearest `f32`: `|P̃ − P| ≤ u(1 + 2⁻²²)|P̃| +
    /// 2⁻¹⁴⁹` per coordinate, likewise `Ṽ`.
    ///
    /// With `M = extent` (so `|P̃|∞ ≤ M`) and `R = M + |Ṽ|∞`, the computed
    /// `ũ = fl(P̃ − Ṽ)` has `|ũ|∞ ≤ R(1 + u)` and errs from `P − V` by at
    /// most `2.0001u·R + 2⁻¹⁴⁸`; `ẽ = fl(Q̃ − P̃)` has `|ẽ|∞ ≤ 2M(1 + u)`
    /// and errs from `Q − P` by at most `4.0001u·M + 2⁻¹⁴⁸`. As
    /// `|det[x, y, z]| ≤ |x|₁ · 2|y|∞|z|∞`, replacing `D, P − V, Q − P` by
    /// `D̃, ũ, ẽ` one at a time changes the determinant by at most
    /// `(4 + 8 + 8.001)u·S·R·M`, and evaluating it in `f32` as three terms
    /// `dᵢ·(yⱼzₖ − yₖzⱼ)` summed left to right (at most five roundings on
    /// any path) adds at most `γ₅ · 2S · R · 2M ≤ 20.001u·S·R·M`. Below the
    /// `f32` normal range each rounding may instead err by `2⁻¹⁵⁰`; all
    /// such terms together stay below `2⁻¹²⁶(1 + S(R + M))`. So the error
    /// is below `40.01u·S·R·M + 2⁻¹²⁶(1 + S(R + M))`; the bound used is
    /// `64u·S·R·M + 2⁻¹²⁶(1 + S(R + M))`, whose own `f32` evaluation (a
    /// handful of roundings, `(1 + u)⁸`) keeps it above that. A computed
    /// determinant beyond it in magnitude has the exact sign.
    ///
    /// Two edge signs proven opposite mean the exact line passes strictly
    /// outside one edge's side and strictly inside another's: it misses the
    /// closed triangle (its symbolic perturbation cannot change a non-zero
    /// sign either), so the exact test would report a miss, and the ray's
    /// origin is not on the triangle. Anything beyond the `f32` range makes
    /// the bound `+∞` or NaN, which proves nothing.
    #[inline(always)]
    pub(in crate::query) fn undecided(&self, r: &PacketRay) -> u32 {
        let v = ((r.origin - self.centre) * r.scale).as_vec3().to_array();
        // `v` is never NaN (a finite difference, scaled).
        let reach = self.extent + larger(larger(v[0].abs(), v[1].abs()), v[2].abs());
        let bound = SIDE_BOUND * r.length * reach * self.extent
            + TINY * (1.0 + r.length * (reach + self.extent));
        let (pos, neg) = (F32x4::splat(bound), F32x4::splat(-bound));
        let corner = |c: usize| [0, 1, 2].map(|a| F32x4::load(&self.corners[3 * c + a]));
        let (a, b, c) = (corner(0), corner(1), corner(2));
        let from_origin = |p: &[F32x4; 3]| [0, 1, 2].map(|k| p[k].sub(F32x4::splat(v[k])));
        let edge = |p: &[F32x4; 3], q: &[F32x4; 3]| [0, 1, 2].map(|k| q[k].sub(p[k]));
        let d = &r.direction;
        // det[D, y, z] = D · (y × z), evaluated as in the bound's proof:
        // the three terms summed left to right.
        let side = |y: [F32x4; 3], z: [F32x4; 3]| {
            let t0 = d[0].mul(y[1].mul(z[2]).sub(y[2].mul(z[1])));
            let t1 = d[1].mul(y[2].mul(z[0]).sub(y[0].mul(z[2])));
            let t2 = d[2].mul(y[0].mul(z[1]).sub(y[1].mul(z[0])));
            t0.add(t1).add(t2)
        };
        let e0 = side(from_origin(&a), edge(&a, &b));
        let e1 = side(from_origin(&b), edge(&b, &c));
        let e2 = side(from_origin(&c), edge(&c, &a));
        let any_pos = e0.gt(pos).or(e1.gt(pos)).or(e2.gt(pos));
        let any_neg = e0.lt(neg).or(e1.lt(neg)).or(e2.lt(neg));
        let proven_miss = any_pos.and(any_neg).bits();
        !proven_miss & ((1u32 << self.count) - 1)
    }
}

/// A ray as [`TriPacket::undecided`] sees it.
#[derive(Clone, Copy, Debug)]
pub(in crate::query) struct PacketRay {
    /// The origin, in input coordinates.
    origin: DVec3,
    /// The accel's frame scale (a power of two).
    scale: f64,
    /// `D̃`: the (already scaled) direction rounded to nearest `f32`, per
    /// axis in every lane.
    direction: [F32x4; 3],
    /// `S = |D̃|₁`.
    length: f32,
}

/// `64 · 2⁻²⁴`: the relative part of the bound of [`TriPacket::undecided`].
const SIDE_BOUND: f32 = 64.0 / (1u32 << 24) as f32;
/// `2⁻¹²⁶`: the absolute part, for roundings below the normal range.
const TINY: f32 = f32::MIN_POSITIVE;

impl PacketRay {
    /// This ray with a filter that proves nothing (every triangle goes to
    /// the exact test): for a ray whose direction [`unit_scaled`] had to
    /// round, which the proof of [`TriPacket::undecided`] does not cover.
    /// An infinite `S` makes the bound infinite.
    ///
    /// [`unit_scaled`]: crate::query::ray_scaling::unit_scaled
    #[must_use]
    pub(in crate::query) fn blind(self) -> PacketRay {
        PacketRay {
            length: f32::INFINITY,
            ..self
        }
    }

    /// `ray` (with its direction scaled by
    /// [`unit_scaled`](crate::query::ray_scaling::unit_scaled)) against the packets
    /// of an accel with frame scale `scale`.
    #[inline(always)]
    pub(in crate::query) fn new(ray: &Ray, scale: f64) -> PacketRay {
        let direction = [0, 1, 2].map(|a| ray.direction[a] as f32);
        PacketRay {
            origin: ray.origin,
            scale,
            direction: direction.map(F32x4::splat),
            length: direction[0].abs() + direction[1].abs() + direction[2].abs(),
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
        let mut uniform = crate::test_rng::uniform(0x2545_F491_4F6C_DD1Du64);
        let (mut dropped, mut kept) = (0, 0);
        for case in 0..20_000 {
            let centre = DVec3::new(uniform(), uniform(), uniform()) * 2e6 - DVec3::splat(1e6);
            let scale = 2f64.powi((uniform() * 60.0) as i32 - 30);
            // Triangles from 5% of the solid's size down to 1e-9 of it (a
            // fine mesh: the filter must stay sound, and still useful).
            let size = scale * 0.05 * 10f64.powf(-8.0 * uniform());
            let mut rand = || DVec3::new(uniform(), uniform(), uniform()) * 2.0 - DVec3::ONE;
            let leaf = centre + rand() * scale * 0.9;
            let tris: Vec<YzTri> = (0..LANES)
                .map(|_| {
                    let a = leaf + rand() * size * 3.0;
                    tri([a, a + rand() * size, a + rand() * size])
                })
                .collect();
            let count = 1 + case % LANES as u32;
            let packet = TriPacket::new(&tris, 0, count, 1.0 / scale);
            // Aim at a corner, at a point of an edge, or anywhere, and nudge
            // by a few ulps.
            let target_tri = tris[case as usize % count as usize].corners();
            let aim = match case % 3 {
                0 => target_tri[case as usize % 3],
                1 => target_tri[0].lerp(target_tri[1], rand().x * 0.5 + 0.5),
                _ => leaf + rand() * size * 4.0,
            };
            let nudge = rand() * size * f64::EPSILON * 8.0 * (case % 2) as f64;
            let origin = centre + rand() * scale * 3.0;
            let direction = aim + nudge - origin;
            if direction == DVec3::ZERO {
                continue;
            }
            let (ray, _) = crate::query::ray_scaling::unit_scaled(&Ray::new(origin, direction));
            let r = PacketRay::new(&ray, 1.0 / scale);
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
