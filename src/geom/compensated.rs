//! A second filter for the sign of a 3×3 determinant whose entries are
//! exact differences `plus − minus`: error-free transformations (Ogita,
//! Rump & Oishi 2005) carry the determinant to about twice the working
//! precision, so that a determinant far below the first filter's bound but
//! far above `2⁻⁹⁷` times its permanent is decided without expansion
//! arithmetic. Rays that graze a face or pass next to a vertex make such
//! determinants: their value is a rounding error of the ray's input, about
//! `2⁻⁵³` of the permanent.
//!
//! # The bound
//!
//! Write `u = 2⁻⁵³` and each entry `x = h + l`, `h` the rounded difference
//! and `l` its tail (exact, by `two_sum`), `|l| ≤ u|h|`. With `P` the
//! permanent of `|h|` (the sum over the six permutations of the products'
//! absolute values),
//!
//! `det x = det h + T₁ + R`, where `T₁ = det(l₀, h₁, h₂) + det(h₀, l₁, h₂) +
//! det(h₀, h₁, l₂)` (rows `lᵢ` of tails) and `|R| ≤ (3u² + u³) P` (the terms
//! with two or three tails).
//!
//! `det h` is expanded along its first row: each 2×2 cofactor `ad − bc` is
//! `M + m + δ` with `M` the rounded difference of the rounded products (by
//! `two_product` and `two_sum`, exact), `m` the rounded sum of their three
//! error terms and `|δ| ≤ 4.01 u² q` (`q = |ad| + |bc|`); each `h₀ₖ · M` is
//! split exactly by `two_product` into `T + g`, and the three `T` are summed
//! exactly by `two_sum` into `S + c₁ + c₂`. Everything else — the `g`, the
//! `h₀ₖ · m`, the `c`, `T₁` — is small, at most `8.1 u P` in all, and is
//! summed in floating point into `s`. The error of `S + s` against `det x`:
//!
//! - the cofactors' `δ`, times `h₀ₖ`: `4.01 u² P`;
//! - the roundings of `h₀ₖ · m` and of adding it to `g`: `5.1 u² P`;
//! - `T₁` in floating point: each of its three determinants has a permanent
//!   at most `u P`, so Shewchuk's `o3derrboundA` (`7.01 u`) bounds each
//!   one's error by `7.01 u² P`, and adding the three `6.1 u² P`: `27.2 u² P`;
//! - the small terms, summed by at most nine roundings:
//!   `γ₉ · 8.1 u P ≤ 73 u² P`;
//! - `R`: `3.01 u² P`;
//!
//! at most `113 u² P` in all. The rounded `F = S + s` has the sign of
//! `S + s`, and so of `det x`, when `|F|` exceeds twice that. The permanent
//! `P̂` computed by the first filter is at least `(1 − u)⁵ P`, so the test
//! here, `|F| > 512 u² P̂`, holds a margin of more than 2 over that.
//!
//! Inputs are in the expansion arithmetic's safe range (every number zero or
//! of magnitude in `[2⁻²⁵⁰, 2²⁵⁰]`): every non-zero difference is then a
//! multiple of `2⁻³⁰²` and below `2²⁵¹`, so every product and error term
//! above is a multiple of `2⁻⁹⁰⁶`, far above the subnormal range, and far
//! below overflow; no rounding above loses anything to underflow (an
//! allowance of `64 · UNDERFLOW` is added all the same), and `det x`, when
//! not zero, is at least `2⁻⁹⁰⁶`.

use super::Sign;
use super::expansion::{two_product, two_sum};
use super::predicates::UNDERFLOW;

/// `u² = 2⁻¹⁰⁶`.
const U_SQUARED: f64 = f64::EPSILON * f64::EPSILON / 4.0;
/// The test's factor: `|F| > 512 u² P̂` (see the module's bound).
const BOUND: f64 = 512.0 * U_SQUARED;

/// `ad − bc` as `(M, m)`: `M` the rounded difference of the rounded
/// products, `m` the rounded sum of the three error terms.
#[inline(always)]
fn cofactor(a: f64, b: f64, c: f64, d: f64) -> (f64, f64) {
    let (p1, e1) = two_product(a, d);
    let (p2, e2) = two_product(b, c);
    let (big, f) = two_sum(p1, -p2);
    (big, (f + e1) - e2)
}

/// The floating-point determinant of three rows (first-row expansion).
#[inline(always)]
fn det3(r0: [f64; 3], r1: [f64; 3], r2: [f64; 3]) -> f64 {
    r0[0] * (r1[1] * r2[2] - r1[2] * r2[1])
        + r0[1] * (r1[2] * r2[0] - r1[0] * r2[2])
        + r0[2] * (r1[0] * r2[1] - r1[1] * r2[0])
}

/// The sign of `det(h + l)` when the compensated evaluation certifies it,
/// `None` otherwise. `h` holds the rounded entries, `l` their exact tails
/// (`|l| ≤ u|h|` entrywise), `permanent` the first filter's floating-point
/// permanent of `|h|`; every entry must be in the safe range described in
/// the module documentation.
#[must_use]
pub(super) fn det3_sign(h: [[f64; 3]; 3], l: [[f64; 3]; 3], permanent: f64) -> Option<Sign> {
    let [h0, h1, h2] = h;
    let cofactors = [
        cofactor(h1[1], h1[2], h2[1], h2[2]),
        cofactor(h1[2], h1[0], h2[2], h2[0]),
        cofactor(h1[0], h1[1], h2[0], h2[1]),
    ];
    let mut big = [0.0; 3];
    let mut small = 0.0;
    for (k, &(m_big, m_small)) in cofactors.iter().enumerate() {
        let (t, g) = two_product(h0[k], m_big);
        big[k] = t;
        small += g + h0[k] * m_small;
    }
    let (s1, c1) = two_sum(big[0], big[1]);
    let (s, c2) = two_sum(s1, big[2]);
    let tails = det3(l[0], h1, h2) + det3(h0, l[1], h2) + det3(h0, h1, l[2]);
    let f = s + (c1 + c2 + small + tails);
    let bound = BOUND * permanent + 64.0 * UNDERFLOW;
    (f.is_finite() && (f > bound || -f > bound)).then(|| Sign::of(f))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::exact::{
        Diff, det3_sign as exact_det3_sign, det3_sign_by_expansion as expansion_sign,
    };

    #[test]
    fn decided_signs_are_the_exact_ones_on_near_singular_matrices() {
        // det[d, a − o, b − o] for a line through `o` nearly in the plane of
        // `a`, `b`, `o`: the grazing rays' determinants, many of them far
        // below the first filter's bound.
        let mut u = crate::test_rng::uniform(27);
        let (mut decided, mut total) = (0, 0);
        for _ in 0..20_000 {
            let a = [u(), u(), u()].map(|x| 4.0 * x - 2.0);
            let b = [u(), u(), u()].map(|x| 4.0 * x - 2.0);
            let o = [u(), u(), u()].map(|x| 8.0 * x - 4.0);
            // A direction in the plane of a − o, b − o, rounded.
            let (s, t) = (u() - 0.5, u() - 0.5);
            let d: [f64; 3] = std::array::from_fn(|k| s * (a[k] - o[k]) + t * (b[k] - o[k]));
            let rows = [
                d.map(Diff::value),
                std::array::from_fn(|k| Diff::new(a[k], o[k])),
                std::array::from_fn(|k| Diff::new(b[k], o[k])),
            ];
            let h = rows.map(|r| r.map(|x| x.plus - x.minus));
            let l = rows.map(|r| r.map(|x| two_sum(x.plus, -x.minus).1));
            let p = h[0][0].abs() * (h[1][1] * h[2][2]).abs()
                + h[0][0].abs() * (h[1][2] * h[2][1]).abs()
                + h[0][1].abs() * (h[1][2] * h[2][0]).abs()
                + h[0][1].abs() * (h[1][0] * h[2][2]).abs()
                + h[0][2].abs() * (h[1][0] * h[2][1]).abs()
                + h[0][2].abs() * (h[1][1] * h[2][0]).abs();
            let exact = expansion_sign(rows);
            total += 1;
            if let Some(sign) = det3_sign(h, l, p) {
                decided += 1;
                assert_eq!(sign, exact, "{rows:?}");
            }
            assert_eq!(exact_det3_sign(rows), exact, "{rows:?}");
        }
        // Nearly every one is decided here (the rest are exact zeros or
        // closer to zero than the bound).
        assert!(decided * 10 > total * 9, "{decided} of {total}");
    }

    #[test]
    fn an_exact_zero_is_never_decided() {
        // Two equal rows: the determinant is exactly 0.
        let r = [0.1, 0.7, -0.3];
        let h = [r, r, [0.2, 0.4, 1.1]];
        let l = [[0.0; 3]; 3];
        assert_eq!(det3_sign(h, l, 1.0), None);
    }
}
