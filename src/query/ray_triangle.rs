//! The exact test of a ray against one fan triangle, and the rounded
//! parameter of a crossing.

use glam::DVec3;

use crate::geom::dyadic::Dyadic;

use crate::geom::exact::{line_side_filter_scalar, triangle_edge_sides};
use crate::geom::polygon::coplanar_point_in_closed_triangle;
use crate::geom::{Ray, Sign, line_side_sos, orient3d};

use super::accel::Accel;
use super::ray_answers::{Crossing, Transition};
use super::ray_scaling::pow2;

/// `2⁻⁶⁰⁰`: below this denominator [`Accel::plane_t_bounded`]'s plain formula may
/// have lost `n` to underflow.
const PLANE_T_DENOMINATOR: f64 = pow2(-600);

/// The rounding error of `n·(a − o)` and `n·d` in [`Accel::plane_t_bounded`],
/// relative to the sum of their monomials' magnitudes: `16 u` (eight
/// roundings at most along any monomial's path, doubled for the magnitudes
/// being computed from rounded values).
const T_TERMS_ERROR: f64 = 16.0 * (f64::EPSILON / 2.0);

/// [`Accel::plane_t_bounded`] for triangles or distances of extreme size: the
/// corners and origin are first scaled down by `2⁻⁶⁴` if any coordinate is
/// beyond `2¹⁰⁰⁰` (so that differences cannot overflow), then the edges and
/// `a − o` are each scaled by a power of two to a largest component in
/// `[1, 2)`, so that the cross product neither underflows nor overflows;
/// the powers of two are divided out of the quotient at the end (exactly,
/// unless the true `t` itself is beyond the `f64` range).
#[cold]
#[inline(never)]
fn plane_t_rescaled([a, b, c]: [DVec3; 3], ray: &Ray) -> f64 {
    let far = [a, b, c, ray.origin]
        .iter()
        .any(|p| p.abs().max_element() > pow2(1000));
    let pre = if far { pow2(-64) } else { 1.0 };
    let (a, b, c, o) = (a * pre, b * pre, c * pre, ray.origin * pre);
    // `v · 2^k` with its largest component in [1, 2), and `2^k`.
    let unit = |v: DVec3| {
        let m = v.abs().max_element();
        if m == 0.0 || !m.is_finite() {
            return (v, 1.0);
        }
        let k = (-m.log2().floor() as i32).clamp(-1022, 1022);
        (v * pow2(k), pow2(k))
    };
    let ((e1, _), (e2, _)) = (unit(b - a), unit(c - a));
    let (w, w_scale) = unit(a - o);
    let n = e1.cross(e2);
    // t = n·(a − o) / n·d, and (a − o) = w / w_scale / pre.
    n.dot(w) / n.dot(ray.direction) / w_scale / pre
}

/// The relative error a reported crossing's rounded `t` may keep: `2⁻³⁰`.
/// Beyond it the exact quotient is computed.
pub(super) const T_ACCURACY: f64 = 1.0 / (1u64 << 30) as f64;

/// The exact numerator `n·(a − o)` and denominator `n·d` of the ray's
/// crossing with the plane of `[a, b, c]`, `n = (b − a) × (c − a)`.
pub(super) fn plane_parts([a, b, c]: [DVec3; 3], ray: &Ray) -> (Dyadic, Dyadic) {
    let exact = |v: DVec3| [v.x, v.y, v.z].map(Dyadic::of);
    let minus = |p: DVec3, q: DVec3| {
        let (p, q) = (exact(p), exact(q));
        [&p[0] - &q[0], &p[1] - &q[1], &p[2] - &q[2]]
    };
    let (u, v, e) = (minus(b, a), minus(c, a), minus(a, ray.origin));
    let n = [
        &(&u[1] * &v[2]) - &(&u[2] * &v[1]),
        &(&u[2] * &v[0]) - &(&u[0] * &v[2]),
        &(&u[0] * &v[1]) - &(&u[1] * &v[0]),
    ];
    let dot = |w: &[Dyadic; 3]| &(&(&n[0] * &w[0]) + &(&n[1] * &w[1])) + &(&n[2] * &w[2]);
    (dot(&e), dot(&exact(ray.direction)))
}

/// How a ray meets one triangle.
pub(super) enum TriHit {
    /// No crossing (or, for tests that skip it, the origin on the
    /// triangle).
    Miss,
    /// The origin lies on the triangle.
    Origin,
    /// A crossing in front of the origin; the sign is `+` for an exit.
    Cross(Sign),
}

impl Accel {
    /// The answer for a crossing of triangle `i` at `t` with sign `s`
    /// (`+` for an exit).
    #[inline]
    pub(super) fn crossing(&self, t: f64, i: u32, s: Sign) -> Crossing {
        Crossing {
            t,
            face: self.tri_face[i as usize],
            triangle: i,
            transition: if s == Sign::Positive {
                Transition::Exit
            } else {
                Transition::Enter
            },
        }
    }

    /// The parameter of the crossing with triangle `i`'s plane (known
    /// exactly to be in front of the origin), accurate to [`T_ACCURACY`]
    /// ([`Accel::accurate_t`]).
    pub(super) fn t_of(&self, ray: &Ray, i: u32) -> f64 {
        let (t, error) = self.plane_t_bounded(ray, i);
        self.accurate_t(ray, i, t, error)
    }

    /// The crossing's `t` along `ray` from its rounded value and error
    /// bound: the rounded value (clamped to the smallest positive `f64`)
    /// when the bound is within [`T_ACCURACY`] of it, else the exact
    /// quotient `n·(a − o) / n·d` rounded once (a ray within a rounding of
    /// the face's plane, where the rounded quotient can be off in its third
    /// digit). Crossing lists and first hits both report this value.
    pub(super) fn accurate_t(&self, ray: &Ray, i: u32, t: f64, error: f64) -> f64 {
        // A rounded denominator of zero makes `t` infinite with an infinite
        // bound, which `≤` would accept: only a finite `t` is kept.
        let t = if t.is_finite() && error <= T_ACCURACY * t.abs() {
            t
        } else {
            let (num, den) = plane_parts(self.tris[i as usize].corners(), ray);
            num.quotient_to_f64(&den)
        };
        if t > 0.0 { t } else { f64::MIN_POSITIVE }
    }

    /// The rounded parameter of the ray's crossing with triangle `i`'s
    /// plane, unclamped (any sign, `±∞` or NaN for a parallel ray), and a
    /// bound on its rounding error. `ray` is scaled by [`unit_scaled`]
    /// (largest direction component in `[1, 2)`).
    ///
    /// `t = n·(a − o) / n·d` with `n = (b − a) × (c − a)`. When the
    /// denominator is at least `2⁻⁶⁰⁰` and `t` is finite (nothing
    /// overflowed), every component of `n` that matters is far above the
    /// subnormal range; otherwise (triangles of size `1e-160` or `1e200`,
    /// origins near `f64::MAX`) it is recomputed with the edges and `a − o`
    /// brought to unit size by powers of two ([`plane_t_rescaled`]) and the
    /// bound is `+∞`, as it is when the denominator is not certainly far
    /// from zero. The bound follows the operations: each difference,
    /// product and sum rounds once, so the numerator and the denominator
    /// are each within `16 u` of the sum of the magnitudes of their
    /// monomials, and the quotient's error follows.
    #[inline(always)]
    pub(super) fn plane_t_bounded(&self, ray: &Ray, i: u32) -> (f64, f64) {
        let [a, b, c] = self.tris[i as usize].corners();
        let (u, v, e) = (b - a, c - a, a - ray.origin);
        let n = u.cross(v);
        let den = n.dot(ray.direction);
        let num = n.dot(e);
        let t = num / den;
        if !(den.abs() >= PLANE_T_DENOMINATOR && t.is_finite()) {
            return (plane_t_rescaled([a, b, c], ray), f64::INFINITY);
        }
        let (ua, va) = (u.abs(), v.abs());
        let magnitude = glam::DVec3::new(
            ua.y * va.z + ua.z * va.y,
            ua.z * va.x + ua.x * va.z,
            ua.x * va.y + ua.y * va.x,
        );
        let num_error = T_TERMS_ERROR * magnitude.dot(e.abs()) + f64::MIN_POSITIVE;
        let den_error = T_TERMS_ERROR * magnitude.dot(ray.direction.abs());
        let den_abs = den.abs();
        if den_abs <= 2.0 * den_error {
            return (t, f64::INFINITY);
        }
        let quotient =
            (num.abs() * den_error + den_abs * num_error) / (den_abs * (den_abs - den_error));
        (
            t,
            quotient * (1.0 + 8.0 * f64::EPSILON) + 2.0 * f64::EPSILON * t.abs(),
        )
    }

    /// How `ray` meets triangle `i`; with `ORIGIN = false` the (costlier)
    /// test of the origin lying on the triangle is skipped and reported as
    /// a miss — what first-hit queries need, which list no crossing at the
    /// origin.
    #[inline(always)]
    pub(super) fn hit_triangle<const ORIGIN: bool>(&self, ray: &Ray, i: u32) -> TriHit {
        let [a, b, c] = &self.tris[i as usize].corners();
        let (o, d) = (&ray.origin, &ray.direction);
        let dd = [d.x, d.y, d.z];
        let u = [a.x - o.x, a.y - o.y, a.z - o.z];
        let v = [b.x - o.x, b.y - o.y, b.z - o.z];
        let w = [c.x - o.x, c.y - o.y, c.z - o.z];
        let origin_check = || {
            if ORIGIN {
                self.origin_check(*a, *b, *c, *o)
            } else {
                TriHit::Miss
            }
        };
        // The three edge signs at once with a shared error bound: it
        // certifies most misses and most crossings outright. The exact
        // decision below is the same as the edge-by-edge one it replaces
        // (a crossing needs three equal non-zero signs; certified signs are
        // the exact ones).
        let sides = triangle_edge_sides(dd, u, v, w);
        if sides.certainly_mixed() {
            return origin_check();
        }
        let (s0, side) = match sides.certainly_uniform() {
            Some(s) => (s, None),
            None => {
                // The origin in the triangle's plane: whatever the edge
                // signs, the answer is the origin check (below, a zero
                // side leads there too). Asked first here, where the edge
                // signs are uncertain: a ray lying in a face's plane makes
                // every edge sign an exact zero, each costly to prove and to
                // break by perturbation, for a triangle it cannot cross.
                let side = orient3d(*a, *b, *c, *o);
                if side == Sign::Zero {
                    return origin_check();
                }
                let s0 = line_side_filter_scalar(dd, u, v)
                    .unwrap_or_else(|| line_side_sos(*o, *d, *a, *b));
                let s1 = line_side_filter_scalar(dd, v, w)
                    .unwrap_or_else(|| line_side_sos(*o, *d, *b, *c));
                if s0 != s1 || s0 == Sign::Zero {
                    return origin_check();
                }
                let s2 = line_side_filter_scalar(dd, w, u)
                    .unwrap_or_else(|| line_side_sos(*o, *d, *c, *a));
                if s2 != s0 {
                    return origin_check();
                }
                (s0, Some(side))
            }
        };
        match side.unwrap_or_else(|| orient3d(*a, *b, *c, *o)) {
            Sign::Zero => origin_check(),
            side if side == -s0 => TriHit::Cross(s0),
            _ => TriHit::Miss,
        }
    }

    /// Whether the origin lies on the triangle (cheap rejections first).
    #[inline]
    fn origin_check(&self, a: DVec3, b: DVec3, c: DVec3, o: DVec3) -> TriHit {
        let lo = a.min(b).min(c);
        let hi = a.max(b).max(c);
        if o.cmplt(lo).any() || o.cmpgt(hi).any() {
            return TriHit::Miss;
        }
        if orient3d(a, b, c, o) == Sign::Zero && coplanar_point_in_closed_triangle(a, b, c, o) {
            TriHit::Origin
        } else {
            TriHit::Miss
        }
    }
}
