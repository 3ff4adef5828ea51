//! One triangle against a point's `±x` ray: a floating-point filter for
//! the three projected orientations, exact predicates where it cannot
//! decide, and Simulation of Simplicity for ties.

use glam::{DVec2, DVec3};

use super::accel::triangle_records::YzTri;
use super::x_direction::XDirection;
use crate::geom::polygon::coplanar_point_in_closed_triangle;
use crate::geom::{Sign, UNDERFLOW, orient2d, orient3d};

/// What one triangle adds to a point's ray.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum Step {
    /// Nothing: not crossed in the ray's direction, `p` not on it.
    Miss,
    /// The point lies exactly on the triangle.
    OnBoundary,
    /// The ray crosses it: the contribution to the `+x` winding.
    Crossing(i32),
}

/// The triangle `t` against the ray from `p` (with `q = (p.y, p.z)`) along
/// `direction`: exact, as described at
/// [`Accel::classify_with`](crate::query::Accel::classify_with).
#[inline(always)]
pub(super) fn triangle_step(t: &YzTri, p: DVec3, q: DVec2, direction: XDirection) -> Step {
    match cross_x(t, q) {
        Cross::No => Step::Miss,
        Cross::Degenerate => {
            let [a, b, c] = t.corners();
            if orient3d(a, b, c, p) == Sign::Zero && coplanar_point_in_closed_triangle(a, b, c, p) {
                Step::OnBoundary
            } else {
                Step::Miss
            }
        }
        Cross::Closed(perturbed_inside) => {
            let [a, b, c] = t.corners();
            let side = orient3d(a, b, c, p);
            if side == Sign::Zero {
                return Step::OnBoundary;
            }
            if !perturbed_inside {
                return Step::Miss;
            }
            let sigma = Sign::of(f64::from(t.sigma));
            match direction {
                // In front of `p`: `p` is on the triangle's inner side as
                // seen along `+x`.
                XDirection::Plus if side == -sigma => Step::Crossing(i32::from(t.sigma)),
                // Behind `p`: counted with the opposite sign, so that the sum
                // is the `+x` winding on an oriented closed surface.
                XDirection::Minus if side == sigma => Step::Crossing(-i32::from(t.sigma)),
                _ => Step::Miss,
            }
        }
    }
}

/// How the `+x` line through a point meets a triangle's `yz` projection.
enum Cross {
    /// The projected point is outside the closed projected triangle.
    No,
    /// The projection has zero area: only an on-boundary check applies.
    Degenerate,
    /// The projected point is in the closed projected triangle; the flag says
    /// whether the symbolically moved point is inside.
    Closed(bool),
}

/// Shewchuk's `ccwerrboundA`, `(3 + 16ε)ε` with `ε = 2⁻⁵³`: the relative
/// error bound of the rounded 2-D orientation determinant.
const ORIENT2D_BOUND: f64 = (3.0 + 16.0 * HALF_EPSILON) * HALF_EPSILON;
/// Half a unit in the last place of 1.0.
const HALF_EPSILON: f64 = f64::EPSILON / 2.0;
/// [`ORIENT2D_BOUND`] times 2 with a margin for the rounding of the shared
/// bound's own evaluation (see [`cross_x`]).
const SHARED_ORIENT2D_BOUND: f64 = ORIENT2D_BOUND * 2.0 * (1.0 + 64.0 * f64::EPSILON);

/// How the `x` line through `q = (y, z)` meets the triangle's projection.
///
/// First a floating-point filter for the three `orient2d(corner, next corner,
/// q)` at once, evaluated exactly as [`orient2d`] evaluates each (the
/// differences `corner − q`, then `left − right` with `left = Δy₀·Δz₁`,
/// `right = Δz₀·Δy₁`), but with one error bound shared by all three. Why the
/// bound is valid: [`orient2d`] certifies the sign of its rounded `det` when
/// `|det| > B · P`, `B` = [`ORIENT2D_BOUND`] (Shewchuk's `ccwerrboundA`,
/// which also covers the rounding of the differences) and `P = |left| +
/// |right|` evaluated in floating point. With `m` the largest `|Δ|` of the
/// three rounded differences, each rounded product is at most `m²(1 + ε)`,
/// so `P ≤ 2m²(1 + ε)²` and the rounded `B · P` is at most `2Bm²(1 + ε)³`.
/// The bound used here, `(K · m) · m` with `K = 2B(1 + 64ε)`
/// ([`SHARED_ORIENT2D_BOUND`]), is at least `Km²(1 − ε)²`, which exceeds
/// `2Bm²(1 + ε)³`. So a sign this filter certifies is one [`orient2d`] would
/// certify, the exact sign. Roundings in the subnormal range add at most
/// `2η(1 + ε)` (`η = 2⁻¹⁰⁷⁵`) to each determinant's error, covered by
/// [`UNDERFLOW`]; overflow makes the bound or a determinant infinite or NaN,
/// which certifies nothing. Every case the filter leaves open goes to the
/// exact tests of [`cross_x_exact`].
///
/// Multiplying each determinant by the projection's sign `σ = ±1` is exact,
/// so the filter decides [`Cross::No`] when one of them is certainly `−σ`
/// (as [`cross_x_exact`] does on meeting any such sign) and
/// [`Cross::Closed`]`(true)` when all three are certainly `σ` (no tie).
#[inline(always)]
fn cross_x(t: &YzTri, q: DVec2) -> Cross {
    if t.sigma != 0 {
        let (y0, y1, y2) = (t.y[0] - q.x, t.y[1] - q.x, t.y[2] - q.x);
        let (z0, z1, z2) = (t.z[0] - q.y, t.z[1] - q.y, t.z[2] - q.y);
        let sigma = f64::from(t.sigma);
        let d0 = sigma * (y0 * z1 - z0 * y1);
        let d1 = sigma * (y1 * z2 - z1 * y2);
        let d2 = sigma * (y2 * z0 - z2 * y0);
        let m = y0
            .abs()
            .max(y1.abs())
            .max(y2.abs())
            .max(z0.abs())
            .max(z1.abs())
            .max(z2.abs());
        let bound = SHARED_ORIENT2D_BOUND * m * m + UNDERFLOW;
        if (d0 < -bound) | (d1 < -bound) | (d2 < -bound) {
            return Cross::No;
        }
        if (d0 > bound) & (d1 > bound) & (d2 > bound) {
            return Cross::Closed(true);
        }
    }
    cross_x_exact(t, q)
}

/// [`cross_x`] by three [`orient2d`] and the perturbation of ties.
#[inline(never)]
fn cross_x_exact(t: &YzTri, q: DVec2) -> Cross {
    if t.sigma == 0 {
        let (ymin, ymax) = (
            t.y[0].min(t.y[1]).min(t.y[2]),
            t.y[0].max(t.y[1]).max(t.y[2]),
        );
        let (zmin, zmax) = (
            t.z[0].min(t.z[1]).min(t.z[2]),
            t.z[0].max(t.z[1]).max(t.z[2]),
        );
        return if q.x >= ymin && q.x <= ymax && q.y >= zmin && q.y <= zmax {
            Cross::Degenerate
        } else {
            Cross::No
        };
    }
    let sigma = Sign::of(f64::from(t.sigma));
    let a = DVec2::new(t.y[0], t.z[0]);
    let b = DVec2::new(t.y[1], t.z[1]);
    let c = DVec2::new(t.y[2], t.z[2]);
    let s0 = orient2d(a, b, q);
    if s0 == -sigma {
        return Cross::No;
    }
    let s1 = orient2d(b, c, q);
    if s1 == -sigma {
        return Cross::No;
    }
    let s2 = orient2d(c, a, q);
    if s2 == -sigma {
        return Cross::No;
    }
    if s0 != Sign::Zero && s1 != Sign::Zero && s2 != Sign::Zero {
        return Cross::Closed(true);
    }
    let inside = [(s0, a, b), (s1, b, c), (s2, c, a)]
        .iter()
        .all(|&(s, u, v)| s != Sign::Zero || perturbed_orient(u, v) == sigma);
    Cross::Closed(inside)
}

/// `orient2d(u, v, q')` for `q' = q + (ε, ε²)` when `orient2d(u, v, q) = 0`:
/// the sign of `u.y − v.y`, or of `v.x − u.x` when that is zero (2-D names:
/// `x` is the 3-D `y`, `y` the 3-D `z`).
#[inline]
fn perturbed_orient(u: DVec2, v: DVec2) -> Sign {
    crate::geom::count_tie_break();
    match Sign::of(u.y - v.y) {
        Sign::Zero => Sign::of(v.x - u.x),
        s => s,
    }
}
