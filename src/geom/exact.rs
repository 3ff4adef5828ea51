//! Exact signs of small determinants whose entries are differences of input
//! numbers, and the line predicates built on them.
//!
//! [`orient3d`](super::orient3d) covers determinants of the form
//! `det[b − a, c − a, d − a]`. Rays given as an origin and a *direction*
//! need `det[d, a − o, b − o]`, where `d` is not a difference of two points
//! that could be handed to `orient3d` without rounding `o + d`. This module
//! evaluates such determinants exactly: a floating-point filter with
//! Shewchuk's error bounds first, then a compensated second filter
//! (`compensated`), then, only when neither can decide,
//! exact expansion arithmetic (Shewchuk 1997: `two_sum`, `two_product` via
//! FMA, `grow_expansion`). Fallbacks are counted in the same per-thread
//! counter as the other predicates ([`exact_fallbacks`](super::exact_fallbacks)).
//!
//! Expansion arithmetic is exact only while no intermediate product
//! overflows or underflows; entries outside the range where that is certain
//! (`dyadic`) are decided by exact big-integer arithmetic instead, and the
//! filters allow for roundings in the subnormal range (the predicates'
//! `UNDERFLOW`). So every sign here is
//! exact for every finite input.

use glam::{DVec2, DVec3};

use super::compensated;
use super::dyadic::{self, Dyadic, in_safe_range};
use super::expansion::{Expansion, two_sum};
use super::predicates::{UNDERFLOW, count_fallback};
use super::{Sign, larger, orient2d};

/// Half a unit in the last place of 1.0.
const HALF_EPSILON: f64 = f64::EPSILON / 2.0;
/// Shewchuk's `ccwerrboundA`.
const DET2_BOUND: f64 = (3.0 + 16.0 * HALF_EPSILON) * HALF_EPSILON;
/// Shewchuk's `o3derrboundA`.
const DET3_BOUND: f64 = (7.0 + 56.0 * HALF_EPSILON) * HALF_EPSILON;

/// One matrix entry: the exact difference `plus − minus` of two input numbers.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Diff {
    /// The minuend.
    pub plus: f64,
    /// The subtrahend (0 for a plain input number).
    pub minus: f64,
}

impl Diff {
    /// The entry `plus − minus`.
    #[must_use]
    pub const fn new(plus: f64, minus: f64) -> Diff {
        Diff { plus, minus }
    }

    /// The entry `value` (no subtraction).
    #[must_use]
    pub const fn value(value: f64) -> Diff {
        Diff {
            plus: value,
            minus: 0.0,
        }
    }

    fn rounded(self) -> f64 {
        self.plus - self.minus
    }

    fn expansion(self) -> Expansion {
        Expansion::difference(self.plus, self.minus)
    }

    /// `plus − minus − rounded()`, exactly (`two_sum`).
    fn tail(self) -> f64 {
        two_sum(self.plus, -self.minus).1
    }

    fn dyadic(self) -> Dyadic {
        Dyadic::difference(self.plus, self.minus)
    }

    /// Whether both numbers are in the range where expansion arithmetic is
    /// exact (see `dyadic`).
    fn in_safe_range(self) -> bool {
        in_safe_range(&[self.plus, self.minus])
    }

    fn is_finite(self) -> bool {
        self.plus.is_finite() && self.minus.is_finite()
    }
}

/// The rows of `p − q` for 3-vectors: `[p.x − q.x, p.y − q.y, p.z − q.z]`.
#[must_use]
pub fn diff_row(p: DVec3, q: DVec3) -> [Diff; 3] {
    [
        Diff::new(p.x, q.x),
        Diff::new(p.y, q.y),
        Diff::new(p.z, q.z),
    ]
}

/// The row of a plain vector `v`.
#[must_use]
pub fn value_row(v: DVec3) -> [Diff; 3] {
    [Diff::value(v.x), Diff::value(v.y), Diff::value(v.z)]
}

/// The exact sign of the 3×3 determinant whose rows are `rows` (each entry
/// the exact difference of two input numbers).
#[must_use]
pub fn det3_sign(rows: [[Diff; 3]; 3]) -> Sign {
    let m = rows.map(|r| r.map(Diff::rounded));
    let m12 = m[1][1] * m[2][2];
    let m21 = m[1][2] * m[2][1];
    let n12 = m[1][2] * m[2][0];
    let n21 = m[1][0] * m[2][2];
    let o12 = m[1][0] * m[2][1];
    let o21 = m[1][1] * m[2][0];
    let det = m[0][0] * (m12 - m21) + m[0][1] * (n12 - n21) + m[0][2] * (o12 - o21);
    let permanent = m[0][0].abs() * (m12.abs() + m21.abs())
        + m[0][1].abs() * (n12.abs() + n21.abs())
        + m[0][2].abs() * (o12.abs() + o21.abs());
    let bound =
        DET3_BOUND * permanent + UNDERFLOW * (m[0][0].abs() + m[0][1].abs() + m[0][2].abs() + 1.0);
    if det > bound || -det > bound {
        return Sign::of(det);
    }
    let entries = rows.as_flattened();
    if !entries.iter().all(|e| e.is_finite()) {
        // Unspecified for non-finite input (never a panic).
        return Sign::of(det);
    }
    count_fallback();
    // A row or a column of exact zeros (a ray lying in an axis-aligned
    // face: every row's component along that axis is zero): exactly zero.
    let zero = |d: &Diff| d.plus == d.minus;
    if (0..3).any(|k| rows[k].iter().all(zero) || rows.iter().all(|r| zero(&r[k]))) {
        return Sign::Zero;
    }
    if !entries.iter().all(|e| e.in_safe_range()) {
        return dyadic::det3_sign(&rows.map(|r| r.map(Diff::dyadic)));
    }
    // Near-singular but not singular (a ray grazing a face or passing next
    // to a vertex): decided in about twice the working precision.
    if let Some(sign) = compensated::det3_sign(m, rows.map(|r| r.map(Diff::tail)), permanent) {
        return sign;
    }
    det3_sign_by_expansion(rows)
}

/// The exact sign of a 3×3 determinant of differences by expansion
/// arithmetic alone (no filter): the last resort of [`det3_sign`] and the
/// reference its filters are tested against.
#[must_use]
pub(crate) fn det3_sign_by_expansion(rows: [[Diff; 3]; 3]) -> Sign {
    const PERMS: [([usize; 3], bool); 6] = [
        ([0, 1, 2], false),
        ([1, 2, 0], false),
        ([2, 0, 1], false),
        ([0, 2, 1], true),
        ([1, 0, 2], true),
        ([2, 1, 0], true),
    ];
    let mut total = Expansion::default();
    for (p, negative) in PERMS {
        let prod = rows[0][p[0]]
            .expansion()
            .mul(&rows[1][p[1]].expansion())
            .mul(&rows[2][p[2]].expansion());
        total.grow_expansion(&prod, negative);
    }
    total.sign()
}

/// The exact sign of the 2×2 determinant `r0[0]·r1[1] − r0[1]·r1[0]`.
#[must_use]
pub fn det2_sign(r0: [Diff; 2], r1: [Diff; 2]) -> Sign {
    let left = r0[0].rounded() * r1[1].rounded();
    let right = r0[1].rounded() * r1[0].rounded();
    let det = left - right;
    let bound = DET2_BOUND * (left.abs() + right.abs()) + UNDERFLOW;
    let entries = [r0[0], r0[1], r1[0], r1[1]];
    if det > bound || -det > bound || !entries.iter().all(|e| e.is_finite()) {
        return Sign::of(det);
    }
    count_fallback();
    if !entries.iter().all(|e| e.in_safe_range()) {
        let [a, b, c, d] = entries.map(Diff::dyadic);
        return dyadic::det2_sign(&a, &b, &c, &d);
    }
    let mut total = Expansion::default();
    total.grow_expansion(&r0[0].expansion().mul(&r1[1].expansion()), false);
    total.grow_expansion(&r0[1].expansion().mul(&r1[0].expansion()), true);
    total.sign()
}

/// The floating-point filter of [`line_side`] alone: the sign of
/// `det[d, u, v]` where `u = a − o` and `v = b − o` are the *rounded*
/// differences, when Shewchuk's error bound proves it equal to the exact
/// [`line_side`]; `None` when it cannot (then call [`line_side_sos`]).
#[must_use]
#[inline]
pub fn line_side_filter(d: DVec3, u: DVec3, v: DVec3) -> Option<Sign> {
    line_side_filter_scalar(d.to_array(), u.to_array(), v.to_array())
}

/// [`line_side_filter`] on scalar coordinates: `d = (dx, dy, dz)`,
/// `u = a − o`, `v = b − o` (rounded). Written on plain `f64`s so that hot
/// loops keep everything in registers.
#[must_use]
#[inline(always)]
pub fn line_side_filter_scalar(d: [f64; 3], u: [f64; 3], v: [f64; 3]) -> Option<Sign> {
    let m12 = u[1] * v[2];
    let m21 = u[2] * v[1];
    let n12 = u[2] * v[0];
    let n21 = u[0] * v[2];
    let o12 = u[0] * v[1];
    let o21 = u[1] * v[0];
    let det = d[0] * (m12 - m21) + d[1] * (n12 - n21) + d[2] * (o12 - o21);
    let permanent = d[0].abs() * (m12.abs() + m21.abs())
        + d[1].abs() * (n12.abs() + n21.abs())
        + d[2].abs() * (o12.abs() + o21.abs());
    let bound = DET3_BOUND * permanent + UNDERFLOW * (d[0].abs() + d[1].abs() + d[2].abs() + 1.0);
    if det > bound {
        Some(Sign::Positive)
    } else if -det > bound {
        Some(Sign::Negative)
    } else {
        None
    }
}

/// The three edge determinants of a triangle seen from a line, rounded, with
/// one error bound shared by all three (see [`triangle_edge_sides`]).
#[derive(Clone, Copy, Debug)]
pub struct EdgeSides {
    /// The rounded `det[d, u, v]`, `det[d, v, w]`, `det[d, w, u]`.
    pub det: [f64; 3],
    /// A bound on each one's rounding error: a value above `bound` has an
    /// exact value that is positive, one below `−bound` a negative one.
    pub bound: f64,
}

impl EdgeSides {
    /// Whether two of the three exact signs are certainly opposite: then the
    /// line misses the triangle (or only grazes it, which the exact
    /// [`line_side_sos`] also counts as a miss, since its three signs are
    /// then not all equal).
    #[must_use]
    #[inline(always)]
    pub fn certainly_mixed(&self) -> bool {
        let b = self.bound;
        let [e0, e1, e2] = self.det;
        let pos = (e0 > b) | (e1 > b) | (e2 > b);
        let neg = (-e0 > b) | (-e1 > b) | (-e2 > b);
        pos & neg
    }

    /// The common sign when all three exact signs are certainly that sign.
    #[must_use]
    #[inline(always)]
    pub fn certainly_uniform(&self) -> Option<Sign> {
        let b = self.bound;
        let [e0, e1, e2] = self.det;
        if (e0 > b) & (e1 > b) & (e2 > b) {
            Some(Sign::Positive)
        } else if (-e0 > b) & (-e1 > b) & (-e2 > b) {
            Some(Sign::Negative)
        } else {
            None
        }
    }
}

/// Shewchuk's bound times 2 with a margin for the rounding of the bound's
/// own evaluation (see [`triangle_edge_sides`]).
const SHARED_SIDE_BOUND: f64 = DET3_BOUND * 2.0 * (1.0 + 64.0 * f64::EPSILON);

/// The floating-point filter of [`line_side`] for the three edges of a
/// triangle `a, b, c` at once: `u = a − o`, `v = b − o`, `w = c − o` (rounded
/// differences) and the line's direction `d`. Cheaper than three
/// [`line_side_filter`]s: one bound serves all three determinants.
///
/// Why the bound is valid: [`line_side_filter`] certifies a sign when
/// `|det| > DET3_BOUND · P`, `P` the permanent evaluated in floating point
/// (Shewchuk's `o3derrboundA`, which also covers the rounding of the
/// differences). With `m` the largest `|coordinate|` of `u, v, w` and
/// `s = |dx| + |dy| + |dz|`, every exact permanent is at most `2·s·m²`
/// (each term `|d_i|·(|u_j v_k| + |u_k v_j|)` is at most `|d_i|·2m²`). The
/// floating-point `P` exceeds its exact value by at most a factor
/// `(1 + ε)⁵`, and the floating-point `2·s·m²·DET3_BOUND` falls short of its
/// exact value by at most `(1 − ε)⁵`; the margin `1 + 64ε` covers both. So
/// the bound returned is at least `DET3_BOUND · P` for each determinant, and
/// a sign it certifies is the exact sign. Roundings in the subnormal range
/// add at most `(1 + ε)³ · 2η · s + 3η(1 + ε)²` to each determinant's error
/// (`η = 2⁻¹⁰⁷⁵`, see the predicates' `UNDERFLOW`), covered by the term
/// `UNDERFLOW · (s + 1)`;
/// overflow makes the bound or a determinant infinite or NaN, which
/// certifies nothing.
#[must_use]
#[inline(always)]
pub fn triangle_edge_sides(d: [f64; 3], u: [f64; 3], v: [f64; 3], w: [f64; 3]) -> EdgeSides {
    let side = |p: [f64; 3], q: [f64; 3]| {
        d[0] * (p[1] * q[2] - p[2] * q[1])
            + d[1] * (p[2] * q[0] - p[0] * q[2])
            + d[2] * (p[0] * q[1] - p[1] * q[0])
    };
    let det = [side(u, v), side(v, w), side(w, u)];
    // Differences of finite numbers are never NaN.
    let m3 = |p: [f64; 3]| larger(larger(p[0].abs(), p[1].abs()), p[2].abs());
    let m = larger(larger(m3(u), m3(v)), m3(w));
    let s = d[0].abs() + d[1].abs() + d[2].abs();
    let bound = SHARED_SIDE_BOUND * s * (m * m) + UNDERFLOW * (s + 1.0);
    EdgeSides { det, bound }
}

/// Which side of the line through `origin` with direction `direction` the
/// directed segment `a → b` passes: the exact sign of
/// `det[direction, a − origin, b − origin]` (the permuted inner product of
/// the two lines' Plücker coordinates).
///
/// Positive when, looking along `direction`, the segment passes the line
/// counter-clockwise (the line sees `a → b` turning left around it); zero
/// when the two lines are coplanar (they meet or are parallel). With
/// `direction = q − origin` it equals [`orient3d`](super::orient3d)`(origin,
/// q, a, b)`. Antisymmetric in `a`, `b`.
#[must_use]
pub fn line_side(origin: DVec3, direction: DVec3, a: DVec3, b: DVec3) -> Sign {
    det3_sign([
        value_row(direction),
        diff_row(a, origin),
        diff_row(b, origin),
    ])
}

/// [`line_side`] with ties broken by Simulation of Simplicity: never
/// [`Sign::Zero`] unless `a == b`.
///
/// The line is perturbed symbolically: its direction by `(ε, ε², ε³)` and,
/// infinitely less, its origin by `(η, η², η³)` with `η ≪ ε³`. The sign
/// returned is that of the determinant for that perturbed line, read off the
/// first non-zero coefficient of its expansion in `ε` and `η`:
///
/// 1. `det[d, a − o, b − o]` itself;
/// 2. the components of `(a − o) × (b − o)` (`orient2d` of the projections of
///    `o`, `a`, `b` onto the `yz`, `zx` and `xy` planes) — the rotated
///    direction decides when the line meets the segment's line or is
///    parallel to it;
/// 3. the components of `d × (b − a)` and of `b − a` — the shifted origin
///    decides when `o` itself lies on the segment's line.
///
/// Because every answer is the sign for one and the same (infinitesimally)
/// moved line, answers for different segments are mutually consistent: the
/// moved line passes through no vertex and along no edge, so a ray through an
/// edge or a vertex is counted in exactly the faces a generic nearby ray
/// crosses. The perturbation depends on coordinates only, never on ids or
/// order. Antisymmetric in `a`, `b`.
#[must_use]
pub fn line_side_sos(origin: DVec3, direction: DVec3, a: DVec3, b: DVec3) -> Sign {
    let s = line_side(origin, direction, a, b);
    if s != Sign::Zero {
        return s;
    }
    line_side_tie(origin, direction, a, b)
}

/// The perturbation steps of [`line_side_sos`] (the unperturbed sign is 0).
fn line_side_tie(o: DVec3, d: DVec3, a: DVec3, b: DVec3) -> Sign {
    super::predicates::count_tie_break();
    let yz = |p: DVec3| DVec2::new(p.y, p.z);
    let zx = |p: DVec3| DVec2::new(p.z, p.x);
    let xy = |p: DVec3| DVec2::new(p.x, p.y);
    // ε, ε², ε³: δ · ((a − o) × (b − o)).
    for s in [
        orient2d(yz(o), yz(a), yz(b)),
        orient2d(zx(o), zx(a), zx(b)),
        orient2d(xy(o), xy(a), xy(b)),
    ] {
        if s != Sign::Zero {
            return s;
        }
    }
    // The origin lies on the line through a and b. With w = b − a the
    // remaining terms are δ'·(d × w) − det[δ, δ', w], in the order
    // η, ηε², ηε³, η², η²ε, η²ε³, η³, η³ε, η³ε².
    let wx = || Sign::of(b.x - a.x);
    let wy = || Sign::of(b.y - a.y);
    let wz = || Sign::of(b.z - a.z);
    let dxw_x = || {
        det2_sign(
            [Diff::value(d.y), Diff::value(d.z)],
            [Diff::new(b.y, a.y), Diff::new(b.z, a.z)],
        )
    };
    let dxw_y = || {
        det2_sign(
            [Diff::value(d.z), Diff::value(d.x)],
            [Diff::new(b.z, a.z), Diff::new(b.x, a.x)],
        )
    };
    let dxw_z = || {
        det2_sign(
            [Diff::value(d.x), Diff::value(d.y)],
            [Diff::new(b.x, a.x), Diff::new(b.y, a.y)],
        )
    };
    let steps: [&dyn Fn() -> Sign; 9] = [
        &dxw_x,
        &wz,
        &|| -wy(),
        &dxw_y,
        &|| -wz(),
        &wx,
        &dxw_z,
        &wy,
        &|| -wx(),
    ];
    for step in steps {
        let s = step();
        if s != Sign::Zero {
            return s;
        }
    }
    Sign::Zero
}

#[cfg(test)]
mod tests;
