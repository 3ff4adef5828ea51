//! Exactness over the WHOLE range of finite `f64`: subnormals, values near
//! `f64::MAX`, and wildly mixed magnitudes within one call.
//!
//! A floating-point filter is sound only while no product underflows or
//! overflows, and expansion arithmetic is exact only in a middle range; the
//! predicates promise exact signs for every finite input. These tests pin
//! that promise for `orient2d`, `orient3d`, `line_side`(`_sos`),
//! `det3_sign`, `det2_sign`, `side_of_plane` and `dot_sign`, and for the
//! queries built on them (classification and ray crossings of solids scaled
//! to the ends of the exponent range).
//!
//! No expected answer comes from the code under test. Configurations have
//! small-integer coordinates (|c| ≤ 2¹⁰) whose signs are computed here in
//! `i128`, exactly degenerate ones and ones a unit off; each predicate is a
//! homogeneous polynomial, so scaling its inputs by a power of two `2^k > 0`
//! — all of them, or one axis, one row or column, one independent argument —
//! keeps the exact sign. Every scaled coordinate is checked bit by bit to be
//! exactly `c · 2^k` ([`sc`]), so the predicates see the intended reals. The
//! other cases have answers evident by construction (triangular matrices,
//! points one ulp off a line or plane, boxes, rays through edges).

use std::fmt::{Debug, Display};

use wingedge::geom::exact::{Diff, det2_sign, det3_sign};
use wingedge::geom::{Ray, Sign, dot_sign, line_side, line_side_sos};
use wingedge::geom::{orient2d, orient3d, side_of_plane};
use wingedge::glam::{DVec2, DVec3};
use wingedge::mesh::{FaceId, PolygonSoup, Solid, builders};
use wingedge::query::{Accel, Containment, Method, QueryError, RayCrossings, Transition};

use Containment::{Inside, OnBoundary, Outside};
use Sign::{Negative, Positive, Zero};

use crate::common::test_rng;

// ------------------------------------------------------------------ numbers

/// `2^k` exactly, for `k` in `-1074..=1023` (subnormal below `-1022`).
fn pow2(k: i32) -> f64 {
    assert!((-1074..=1023).contains(&k), "2^{k} is not a finite double");
    f64::from_bits(if k >= -1022 {
        ((k + 1023) as u64) << 52
    } else {
        1 << (k + 1074)
    })
}

/// Whether `x` is exactly `c · 2^k`, read off its bits.
fn is_exactly(x: f64, c: i128, k: i32) -> bool {
    let biased = ((x.to_bits() >> 52) & 0x7ff) as i32;
    let f = i128::from(x.to_bits() & ((1 << 52) - 1));
    let (m, e) = [(f | 1 << 52, biased - 1075), (f, -1074)][usize::from(biased == 0)];
    let (m, shift) = (m * (1 - 2 * i128::from(x < 0.0)), (e - k).unsigned_abs());
    x.is_finite()
        && match (m == 0 || c == 0, shift > 100, e >= k) {
            (true, _, _) => m == c,
            (_, true, _) => false,
            (_, _, true) => m << shift == c,
            _ => c << shift == m,
        }
}

/// `c · 2^k`, checked exact (the product is exact whenever representable).
fn sc(c: i64, k: i32) -> f64 {
    let x = c as f64 * pow2(k);
    assert!(is_exactly(x, i128::from(c), k), "{c}·2^{k} is not a double");
    x
}

/// The next double towards zero (finite, non-zero `x`).
fn toward_zero(x: f64) -> f64 {
    if x > 0.0 { x.next_down() } else { x.next_up() }
}

/// An assertion context: `c.eq(got, want, case)` names the case and `c`.
struct Ctx(String);
impl Ctx {
    fn eq<T: PartialEq + Debug>(&self, got: T, want: T, case: impl Display) {
        assert_eq!(got, want, "{case}: {}", self.0);
    }
}

// ------------------------------------------- small configurations, exactly

type I2 = [i64; 2];
type I3 = [i64; 3];

/// The sign of `x`, decided here rather than by the crate's `Sign::of`.
fn sgn(x: f64) -> Sign {
    [Negative, Zero, Positive][usize::from(x >= 0.0) + usize::from(x > 0.0)]
}
fn sign(v: i128) -> Sign {
    sgn(v.signum() as f64)
}
fn sub(a: I3, b: I3) -> [i128; 3] {
    [0, 1, 2].map(|i| i128::from(a[i] - b[i]))
}
fn det3(m: [[i128; 3]; 3]) -> i128 {
    let minor = |i: usize, j: usize| m[1][i] * m[2][j] - m[1][j] * m[2][i];
    m[0][0] * minor(1, 2) - m[0][1] * minor(0, 2) + m[0][2] * minor(0, 1)
}
fn orient2d_ref([a, b, c]: [I2; 3]) -> Sign {
    let d = |p: I2, i: usize| i128::from(p[i] - c[i]);
    sign(d(a, 0) * d(b, 1) - d(a, 1) * d(b, 0))
}
fn orient3d_ref([a, b, c, d]: [I3; 4]) -> Sign {
    sign(det3([sub(b, a), sub(c, a), sub(d, a)]))
}
fn line_side_ref([o, d, a, b]: [I3; 4]) -> Sign {
    sign(det3([sub(d, [0; 3]), sub(a, o), sub(b, o)]))
}
/// `a + f·b`.
fn add(a: I3, b: I3, f: i64) -> I3 {
    [0, 1, 2].map(|i| a[i] + f * b[i])
}
/// `p` and its six unit neighbours: one exactly degenerate case, six off by one.
fn and_neighbours(p: I3) -> [I3; 7] {
    let e = |i: usize, s: i64| {
        let mut q = p;
        q[i] += s;
        q
    };
    [p, e(0, 1), e(0, -1), e(1, 1), e(1, -1), e(2, 1), e(2, -1)]
}

/// Deterministic small integers from the shared seeded generator.
struct Rng(Box<dyn FnMut() -> u64>);
impl Rng {
    fn new(seed: u64) -> Rng {
        Rng(Box::new(test_rng::bits(seed)))
    }
    fn int(&mut self, r: i64) -> i64 {
        ((self.0)() % (2 * r as u64 + 1)) as i64 - r
    }
    fn v3(&mut self, r: i64) -> I3 {
        [self.int(r), self.int(r), self.int(r)]
    }
    fn pick<const N: usize>(&mut self, from: &[i32]) -> [i32; N] {
        [0; N].map(|_| from[self.int(1 << 20).unsigned_abs() as usize % from.len()])
    }
}

/// `c` on the line through `a`, `b` (and off by a unit), and random triples.
fn orient2d_cases() -> Vec<[I2; 3]> {
    let mut rng = Rng::new(0x2545_f491_4f6c_dd1d);
    let mut cases = vec![[[0, 0]; 3], [[1, 2], [1, 2], [-3, 7]]];
    for _ in 0..12 {
        let (a, b) = ([rng.int(256), rng.int(256)], [rng.int(256), rng.int(256)]);
        for (p, q) in [(a, b), (b, a)] {
            let c = [2 * q[0] - p[0], 2 * q[1] - p[1], 0];
            let off = and_neighbours(c).map(|c| [a, b, [c[0], c[1]]]);
            cases.extend(&off[..5]);
        }
        cases.push([[rng.int(1024), rng.int(1024)], a, b]);
    }
    cases
}

/// `d` in the plane of `a, b, c` (and off by a unit), and random quadruples.
fn orient3d_cases() -> Vec<[I3; 4]> {
    let mut rng = Rng::new(0x9e37_79b9_7f4a_7c15);
    let mut cases = vec![[[5; 3]; 4], [[1, 0, 0], [2, 0, 0], [3, 0, 0], [9; 3]]];
    for _ in 0..6 {
        let (a, b, c) = (rng.v3(100), rng.v3(100), rng.v3(100));
        let d = add(add(a, add(b, a, -1), rng.int(2)), add(c, a, -1), rng.int(2));
        cases.extend(and_neighbours(d).map(|d| [a, b, c, d]));
        cases.push([a, b, c, rng.v3(1024)]);
    }
    cases
}

/// `[origin, direction, a, b]`: `b` in the plane of the line and `a` (and
/// off by a unit); `a`, `b` on the line; the origin on the segment's line.
fn line_cases() -> Vec<[I3; 4]> {
    let mut rng = Rng::new(0x1234_5678_9abc_def1);
    let mut cases = Vec::new();
    for _ in 0..6 {
        let (o, d, a) = (rng.v3(100), rng.v3(60), rng.v3(100));
        let b = add(add(a, d, rng.int(2)), add(a, o, -1), rng.int(2));
        cases.extend(and_neighbours(b).map(|b| [o, d, a, b]));
        cases.push([o, d, add(o, d, 1), add(o, d, 3)]);
        cases.push([o, d, add(o, d, -2), add(add(o, d, -2), a, 1)]);
        cases.push([o, d, add(o, a, 1), add(o, a, -1)]);
    }
    cases
}

/// `[p, q, n]` with `(p − q) · n = 0` (and off by `±n_i`).
fn plane_cases() -> Vec<[I3; 3]> {
    let mut rng = Rng::new(0x0dd_ba11_cafe_f00d);
    let mut cases = Vec::new();
    for _ in 0..8 {
        let (q, n, m) = (rng.v3(256), rng.v3(16), rng.v3(16));
        let nxm = [1, 2, 0].map(|i| n[i] * m[(i + 1) % 3] - n[(i + 1) % 3] * m[i]);
        cases.extend(and_neighbours(add(q, nxm, 1)).map(|p| [p, q, n]));
    }
    cases
}

/// Matrices of `[plus, minus]` entries, the third row a combination of the
/// first two (and off by a unit).
fn matrix_cases() -> Vec<[[I2; 3]; 3]> {
    let mut rng = Rng::new(0xfeed_beef_1357_9bdf);
    let mut cases = Vec::new();
    for _ in 0..8 {
        let (r0, r1) = (rng.v3(100), rng.v3(100));
        for r2 in and_neighbours(add(add([0; 3], r0, rng.int(3)), r1, rng.int(3))) {
            let mut split = |r: I3| r.map(|v| (rng.int(300), v)).map(|(m, v)| [v + m, m]);
            cases.push([split(r0), split(r1), split(r2)]);
        }
    }
    cases
}

// --------------------------------------------------- 1. scaling invariance

/// Exponents: a sweep from the smallest subnormal to the largest keeping
/// |c| ≤ 2¹⁰ finite, plus the edges of the subnormal range, of the range
/// where expansions are exact (2^±250), and the scales where products of
/// degree 2 (±537, ±511) and 3 (±358, ±341) leave the normal range.
fn exponents() -> Vec<i32> {
    let mut ks: Vec<i32> = (-1074..=1013).step_by(53).collect();
    ks.extend([-1073, -1070, -1064, -1060, -1023, -1022, -1021, -1000]);
    ks.extend([-900, -600, -545, -537, -530, -360, -358, -350, -300]);
    ks.extend([-251, -250, -249, -1, 0, 1, 249, 250, 251, 300, 340]);
    ks.extend([341, 342, 510, 511, 512, 600, 900, 1000, 1012, 1013]);
    ks.sort_unstable();
    ks.dedup();
    ks
}
/// Exponents for per-axis, per-row and per-argument mixes.
const MIX: [i32; 9] = [-1074, -1060, -1000, -537, -250, 0, 341, 900, 1013];

fn v2(p: I2, k: [i32; 2]) -> DVec2 {
    DVec2::new(sc(p[0], k[0]), sc(p[1], k[1]))
}
fn v3(p: I3, k: [i32; 3]) -> DVec3 {
    DVec3::new(sc(p[0], k[0]), sc(p[1], k[1]), sc(p[2], k[2]))
}

/// Axis `i` scaled by `2^k[i]`; also the swapped and rotated orders.
fn check_orient2d(case: [I2; 3], k: [i32; 2]) {
    let (want, [a, b, c]) = (orient2d_ref(case), case.map(|p| v2(p, k)));
    let t = Ctx(format!("orient2d {case:?} scaled by 2^{k:?}"));
    t.eq(orient2d(a, b, c), want, "as given");
    t.eq(orient2d(b, a, c), -want, "a and b swapped");
    t.eq(orient2d(c, a, b), want, "rotated");
}

fn check_orient3d(case: [I3; 4], k: [i32; 3]) {
    let (want, [a, b, c, d]) = (orient3d_ref(case), case.map(|p| v3(p, k)));
    let t = Ctx(format!("orient3d {case:?} scaled by 2^{k:?}"));
    t.eq(orient3d(a, b, c, d), want, "as given");
    t.eq(orient3d(b, a, c, d), -want, "a and b swapped");
    t.eq(orient3d(d, c, b, a), want, "reversed");
}

/// Points scaled by `2^k` per axis, the direction by `2^kd` more. SoS: never
/// Zero for distinct points, antisymmetric, the exact sign when non-zero,
/// and (defined by infinitesimals) the same as for the unscaled integers.
fn check_line(case: [I3; 4], k: [i32; 3], kd: i32) {
    let ([o, _, a, b], d) = (case.map(|p| v3(p, k)), v3(case[1], k.map(|k| k + kd)));
    let (want, s) = (line_side_ref(case), line_side_sos(o, d, a, b));
    let t = Ctx(format!(
        "{case:?} scaled by 2^{k:?}, direction by 2^{kd} more"
    ));
    t.eq(line_side(o, d, a, b), want, "line_side");
    t.eq(line_side(o, d, b, a), -want, "line_side swapped");
    t.eq(s == Zero, case[2] == case[3], "line_side_sos is Zero");
    t.eq(line_side_sos(o, d, b, a), -s, "line_side_sos swapped");
    t.eq(want == Zero || s == want, true, "line_side_sos is exact");
    let [o, d, a, b] = case.map(|p| DVec3::from_array(p.map(|c| c as f64)));
    t.eq(s, line_side_sos(o, d, a, b), "line_side_sos vs unscaled");
}

/// Entries scaled by `2^(r[i] + c[j])`: the determinant by `2^(Σr + Σc)`.
fn check_matrix(m: &[[I2; 3]; 3], r: [i32; 3], c: [i32; 3]) {
    let v = m.map(|r| r.map(|e| i128::from(e[0] - e[1])));
    let e = |i: usize, j: usize| m[i][j].map(|x| sc(x, r[i] + c[j]));
    let e = |i: usize, j: usize| Diff::new(e(i, j)[0], e(i, j)[1]);
    let rows = [0, 1, 2].map(|i| [0, 1, 2].map(|j| e(i, j)));
    let t = Ctx(format!("{m:?}, rows by 2^{r:?}, columns by 2^{c:?}"));
    t.eq(det3_sign(rows), sign(det3(v)), "det3_sign");
    let swapped = [rows[1], rows[0], rows[2]];
    t.eq(det3_sign(swapped), -sign(det3(v)), "det3_sign swapped");
    let want2 = sign(v[0][0] * v[1][1] - v[0][1] * v[1][0]);
    let (r0, r1) = ([e(0, 0), e(0, 1)], [e(1, 0), e(1, 1)]);
    t.eq(det2_sign(r0, r1), want2, "det2_sign");
}

/// `p, q` scaled by `2^k[i]` per axis, `n` by `2^(kn − k[i])`: every term of
/// `(p − q) · n` by `2^kn`.
fn check_plane(case: [I3; 3], k: [i32; 3], kn: i32) {
    let [p, q, n] = case;
    let want = sign((0..3).map(|i| i128::from((p[i] - q[i]) * n[i])).sum());
    let (ps, qs, ns) = (v3(p, k), v3(q, k), v3(n, k.map(|k| kn - k)));
    let ds = v3(add(p, q, -1), k);
    let t = Ctx(format!(
        "{case:?} scaled by 2^{k:?}, normal by 2^({kn} - k)"
    ));
    t.eq(side_of_plane(ps, qs, ns), want, "side_of_plane");
    t.eq(side_of_plane(qs, ps, ns), -want, "side_of_plane swapped");
    t.eq(dot_sign(ds, ns), want, "dot_sign (p − q)·n");
    t.eq(dot_sign(ns, ds), want, "dot_sign n·(p − q)");
}

#[test]
fn orient2d_is_scale_invariant_over_the_whole_range() {
    let mixed = MIX.map(|x| MIX.map(|y| [x, y])).concat();
    for k in exponents().into_iter().map(|k| [k, k]).chain(mixed) {
        orient2d_cases()
            .into_iter()
            .for_each(|c| check_orient2d(c, k));
    }
}

#[test]
fn orient3d_is_scale_invariant_over_the_whole_range() {
    let (cases, mut rng) = (orient3d_cases(), Rng::new(77));
    let mixed: Vec<[i32; 3]> = (0..60).map(|_| rng.pick(&MIX)).collect();
    for k in exponents().into_iter().map(|k| [k; 3]).chain(mixed) {
        cases.iter().for_each(|&c| check_orient3d(c, k));
    }
}

#[test]
fn line_side_is_scale_invariant_over_the_whole_range() {
    let (cases, mut rng) = (line_cases(), Rng::new(78));
    for k in exponents() {
        // Direction coordinates are below 2^6: scaled from 2^-1074 to 2^1017.
        for kd in [0, -1074 - k, (1017 - k).min(300), -300] {
            if (-1074..=1017).contains(&(k + kd)) {
                cases.iter().for_each(|&c| check_line(c, [k; 3], kd));
            }
        }
    }
    for _ in 0..40 {
        let k = rng.pick(&MIX[..8]);
        cases.iter().for_each(|&c| check_line(c, k, 0));
    }
}

#[test]
fn det3_and_det2_are_scale_invariant_over_the_whole_range() {
    let (cases, mut rng) = (matrix_cases(), Rng::new(79));
    for k in exponents() {
        cases.iter().for_each(|m| check_matrix(m, [k; 3], [0; 3]));
    }
    // Rows and columns scaled apart: entries from 2^-1074 to 2^1000 at once.
    let half = [-537, -300, 0, 250, 500];
    for m in &cases {
        (0..12).for_each(|_| check_matrix(m, rng.pick(&half), rng.pick(&half)));
    }
}

#[test]
fn side_of_plane_and_dot_sign_are_scale_invariant_over_the_whole_range() {
    let (cases, mut rng) = (plane_cases(), Rng::new(80));
    for k in exponents().into_iter().filter(|&k| k <= 1012) {
        // The normal scaled apart from the points: like them, to the bottom
        // of the range, and to near the top.
        for kn in [2 * k, k - 1074 - k.min(0), 1000 + k.min(0)] {
            let kn = kn.clamp(k - 1074, k + 1014);
            cases.iter().for_each(|&c| check_plane(c, [k; 3], kn));
        }
    }
    for _ in 0..60 {
        let k: [i32; 3] = rng.pick(&MIX[..8]);
        let (lo, hi) = (*k.iter().min().unwrap(), *k.iter().max().unwrap());
        // Every n_i · 2^(kn − k_i) a double.
        let kn = (hi - 1074 + lo + 1014) / 2;
        cases.iter().for_each(|&c| check_plane(c, k, kn));
    }
}

// ------------------------------------------- 2. mixed magnitudes in one call

#[test]
fn mixed_magnitudes_in_one_call() {
    let (big, tiny, min, max) = (pow2(1000), pow2(-1000), pow2(-1074), f64::MAX);
    let (p2, p3, v, z) = (DVec2::new, DVec3::new, Diff::value, Diff::new(max, max));
    let t = pow2(-1070);
    let (o2, e2, m2, n2) = (DVec2::ZERO, p2(big, 0.0), p2(max, 0.0), p2(-max, 0.0));
    let [a, b, c] = [p3(-max, -max, 0.0), p3(max, -max, 0.0), p3(0.0, max, 0.0)];
    let [sa, sb, sc] = [DVec3::ZERO, p3(t, 0.0, 0.0), p3(0.0, t, 0.0)];
    // Huge base lines along x, huge and subnormal triangles in z = 0: the
    // point's height alone decides.
    for x in [-max, -big, -1.0, 0.0, min, 1.0, big, max] {
        for h in [tiny, min, 0.0, -min, -tiny] {
            let (p, q, want) = (p2(x, h), p3(x, -x, h), sgn(h));
            let t = Ctx(format!("points {p:?} and {q:?}"));
            t.eq(orient2d(o2, e2, p), want, "base line 0 → 2^1000");
            t.eq(orient2d(n2, m2, p), want, "base line -MAX → MAX");
            t.eq(orient3d(a, b, c, q), want, "±MAX triangle in z = 0");
            t.eq(orient3d(sa, sb, sc, q), want, "2^-1070 triangle in z = 0");
        }
    }
    // A subnormal segment on y = x seen from points near y = x far away.
    let (a, b) = (p2(t, t), p2(2.0 * t, 2.0 * t));
    for x in [pow2(900), big, max, -max] {
        let t = Ctx(format!("2^-1070 segment on y = x, far point at {x:e}"));
        t.eq(orient2d(a, b, p2(x, x)), Zero, "on y = x");
        t.eq(
            orient2d(a, b, p2(x, toward_zero(x))),
            sgn(-x),
            "y one ulp in",
        );
        t.eq(
            orient2d(a, b, p2(toward_zero(x), x)),
            sgn(x),
            "x one ulp in",
        );
    }
    // The huge plane x = y (normal (1, −1, 0)), probed by subnormal offsets.
    let [a, b, c] = [p3(-max, -max, 0.0), p3(max, max, 0.0), p3(0.0, 0.0, max)];
    let t = Ctx("plane x = y through ±MAX".into());
    let o3 = |d| orient3d(a, b, c, d);
    t.eq(o3(p3(min, 0.0, 5.0)), Positive, "(2^-1074, 0, 5)");
    t.eq(o3(p3(0.0, min, -3.0)), Negative, "(0, 2^-1074, -3)");
    t.eq(o3(p3(min, min, max)), Zero, "(2^-1074, 2^-1074, MAX)");
    // Triangular matrices: the determinant is the product of the diagonal,
    // whatever the (huge or tiny) entries off it; zeros given as MAX − MAX.
    for (d0, d1, d2) in [(min, big, tiny), (-min, max, tiny), (min, -max, -min)] {
        let want = sgn(d0.signum() * d1.signum() * d2.signum());
        for o in [max, -big, min, -tiny] {
            let upper = [[v(d0), v(o), v(-o)], [z, v(d1), v(o)], [z, z, v(d2)]];
            let lower = [[v(d0), z, z], [v(o), v(d1), z], [v(-o), v(o), v(d2)]];
            let t = Ctx(format!("diagonal {d0:e} {d1:e} {d2:e}, off it {o:e}"));
            t.eq(det3_sign(upper), want, "upper triangular");
            t.eq(det3_sign(lower), want, "lower triangular");
            t.eq(det3_sign([upper[1], upper[0], upper[2]]), -want, "swapped");
            let want2 = sgn(d0.signum() * d1.signum());
            t.eq(det2_sign([v(d0), v(o)], [z, v(d1)]), want2, "det2");
        }
    }
    // Entries that are exact sums no double holds: MAX ± 2^-1074.
    let (m, above, below) = (v(max), Diff::new(max, -min), Diff::new(max, min));
    let rows = |e: Diff| [[m, m, z], [m, e, z], [z, z, v(1.0)]];
    for (e, want) in [(above, Positive), (below, Negative), (m, Zero)] {
        let t = Ctx(format!("MAX·{e:?} − MAX²"));
        t.eq(det3_sign(rows(e)), want, "det3");
        t.eq(det2_sign([m, m], [m, e]), want, "det2");
    }
    let t = Ctx("2^-2148 + MAX²".into());
    t.eq(det2_sign([v(min), m], [v(-max), v(min)]), Positive, "det2");
    // (p − q) · n whose terms underflow or overflow in floating point.
    let (o, l) = (0.0, 1.0);
    let t = Ctx("side_of_plane".into());
    // Terms 0·2^1000 and 2^-1074·(±2^-1074): the second underflows.
    let s = |n| side_of_plane(p3(max, min, o), p3(max, o, o), n);
    t.eq(s(p3(big, min, o)), Positive, "0 + 2^-2148");
    t.eq(s(p3(big, -min, o)), Negative, "0 − 2^-2148");
    // Terms ±2·MAX (overflowing) and their difference.
    let s = |n| side_of_plane(p3(max, -max, o), p3(-max, max, o), n);
    t.eq(s(p3(l, l, o)), Zero, "2 MAX − 2 MAX");
    t.eq(
        s(p3(l, l.next_up(), o)),
        Negative,
        "2 MAX − 2 MAX·(1 + 2^-52)",
    );
    t.eq(
        s(p3(l.next_up(), l, o)),
        Positive,
        "2 MAX·(1 + 2^-52) − 2 MAX",
    );
    let s = |p| side_of_plane(p, p3(max, o, o), p3(o, big, max));
    t.eq(s(p3(-max, o, min)), Positive, "−2 MAX·0 + 2^-1074·MAX");
    let e = pow2(600);
    for bz in [min, 0.0, -min] {
        let (a, b) = (p3(e, e, min), p3(e, -e, bz));
        let t = Ctx(format!("dot_sign of {a:?} and {b:?}"));
        t.eq(dot_sign(a, b), sgn(bz), "a · b");
        t.eq(dot_sign(b, a), sgn(bz), "b · a");
    }
    // Lines: subnormal directions against huge segments, and back.
    let (a, b, z3) = (p3(0.0, big, 0.0), p3(0.0, 0.0, big), DVec3::ZERO);
    let d = p3(min, 0.0, 0.0);
    let t = Ctx("line_side".into());
    t.eq(line_side(z3, d, a, b), Positive, "2^-1074 x, 2^1000 yz");
    t.eq(line_side(z3, d, b, a), Negative, "2^-1074 x, swapped");
    t.eq(line_side(z3, d, a, p3(max, max, 0.0)), Zero, "all in z = 0");
    let (o, a, b) = (p3(-max, 0.0, 0.0), p3(max, 1.0, 0.0), p3(max, 0.0, 1.0));
    t.eq(line_side(o, d, a, b), Positive, "2^-1074 x, -MAX to MAX");
    let (a, b) = (p3(max, min, 0.0), p3(max, 0.0, min));
    t.eq(line_side(o, -o, a, b), Positive, "MAX x, 2^-1074 offsets");
}

// ------------------------------------- 3. near-cancellation at extreme scale

#[test]
fn one_ulp_off_collinear_and_coplanar_at_extreme_scales() {
    for k in [-1074, -1064, -1060, -1000, -600, 0, 600, 900, 1000, 1019] {
        let (s2, s3) = (|p: I2| v2(p, [k; 2]), |p: I3| v3(p, [k; 3]));
        let (a, b, c) = (s2([1, 2]), s2([3, 5]), s2([5, 8]));
        let t = Ctx(format!("(1,2) (3,5) (5,8) at 2^{k}, the third point"));
        t.eq(orient2d(a, b, c), Zero, "on the line");
        for (p, want) in [
            ([c.x, c.y.next_up()], Positive),
            ([c.x, c.y.next_down()], Negative),
            ([c.x.next_up(), c.y], Negative),
            ([c.x.next_down(), c.y], Positive),
        ] {
            t.eq(
                orient2d(a, b, p.into()),
                want,
                format!("one ulp off, {p:?}"),
            );
        }
        // d = b + c − a in the plane of a, b, c; (b − a) × (c − a) = (−6, −1, 11).
        // Lines through a along b − a (also given at 2^-1074), segment c → d.
        let (a, b, c, d) = (s3([1, 2, 3]), s3([4, 6, 5]), s3([2, 7, 4]), s3([5, 11, 6]));
        let dirs = [b - a, DVec3::new(3.0, 4.0, 2.0) * pow2(-1074)];
        let t = Ctx(format!("plane (1,2,3) (4,6,5) (2,7,4) at 2^{k}"));
        t.eq(orient3d(a, b, c, d), Zero, "orient3d, (5,11,6) in it");
        for dir in dirs {
            let m = format!("line_side along {dir:?}");
            t.eq(line_side(a, dir, c, d), Zero, m);
        }
        for (i, normal) in [(0, Negative), (1, Negative), (2, Positive)] {
            for (f, want) in [
                (f64::next_up as fn(f64) -> f64, normal),
                (f64::next_down, -normal),
            ] {
                let mut e = d;
                e[i] = f(e[i]);
                t.eq(orient3d(a, b, c, e), want, format!("orient3d, {e:?}"));
                for dir in dirs {
                    let m = format!("line_side along {dir:?} to {e:?}");
                    t.eq(line_side(a, dir, c, e), want, m);
                }
            }
        }
    }
    // Points on y = x near 2^1000 and near MAX, one ulp off.
    let (a, b) = (DVec2::splat(pow2(1000)), DVec2::splat(3.0 * pow2(1000)));
    let (min, max, big) = (pow2(-1074), f64::MAX, pow2(1000));
    for x in [min, 1.0, pow2(999), 5.0 * big, pow2(1023), max] {
        let t = Ctx(format!("y = x through ±(2^1000, 3·2^1000), near {x:e}"));
        for (p, want) in [
            ([x, x], Zero),
            ([x, x.next_down()], Negative),
            ([x.next_down(), x], Positive),
        ] {
            let p = DVec2::from_array(p);
            t.eq(orient2d(a, b, p), want, format!("{p:?}"));
            t.eq(orient2d(-a, -b, -p), want, format!("-{p:?}"));
        }
    }
}

// --------------------------------------------- 4. translation invariance

#[test]
fn translation_by_powers_of_two_keeps_signs() {
    let (cases2, cases3) = (orient2d_cases(), orient3d_cases());
    for j in [-1074, -1060, -1022, -1000, -600, 0, 300, 600, 900, 960] {
        // Coordinates c·2^j moved by ±2^(j+|s|): (c ± 2^|s|)·2^j, exact.
        for sh in [[40, 30, 52], [52, -52, 45], [-30, 52, -40]] {
            let mv = |c: i64, s: i32| {
                let x = sc(c, j) + sc(s.signum().into(), j + s.abs());
                let exact = i128::from(c) + (i128::from(s.signum()) << s.abs());
                assert!(is_exactly(x, exact, j), "{c}·2^{j} + 2^{}", j + s);
                x
            };
            let mv3 = |p: I3| DVec3::new(mv(p[0], sh[0]), mv(p[1], sh[1]), mv(p[2], sh[2]));
            let t = Ctx(format!("translated by ±2^{sh:?} · 2^{j}"));
            for case in &cases2 {
                let [a, b, c] = case.map(|p| DVec2::new(mv(p[0], sh[0]), mv(p[1], sh[1])));
                t.eq(orient2d(a, b, c), orient2d_ref(*case), format!("{case:?}"));
            }
            for case in &cases3 {
                let [a, b, c, d] = case.map(mv3);
                let want = orient3d_ref(*case);
                t.eq(orient3d(a, b, c, d), want, format!("{case:?}"));
            }
        }
    }
}

// ------------------------------------------ 5. queries on extreme solids

/// `solid` (integer coordinates) with every coordinate times `2^k`, built
/// from its soup (the builders' profile check fits a plane in floating
/// point, which underflows or overflows at these scales).
fn scaled(solid: &Solid, k: i32) -> Solid {
    let ids: Vec<_> = solid.vertices().map(|(id, _)| id).collect();
    let at = |v| DVec3::from_array(solid.position(v).to_array().map(|c| sc(c as i64, k)));
    let index = |v| ids.iter().position(|&w| w == v).unwrap();
    let faces = solid
        .faces()
        .map(|(f, _)| solid.face_vertices(f).map(index));
    let faces: Vec<Vec<usize>> = faces.map(Iterator::collect).collect();
    let soup = PolygonSoup::new(ids.iter().map(|&v| at(v)).collect(), faces);
    Solid::try_from_soup(&soup).expect("scaled solid")
}

/// A solid under test: classifications and ray crossings, checked.
struct Probe {
    accel: Accel,
    convex: bool,
    what: String,
}

impl Probe {
    fn new(solid: &Solid, convex: bool, what: String) -> Probe {
        Probe {
            accel: Accel::new(solid),
            convex,
            what,
        }
    }

    /// Classifies `p` by every method that applies; each must answer `want`.
    fn at(&self, p: DVec3, want: Containment, case: &str) {
        for m in &[Method::Parity, Method::Winding, Method::Normals][..2 + usize::from(self.convex)]
        {
            let got = self.accel.classify_with(p, *m).unwrap();
            assert_eq!(got, want, "{}: {case}: {m:?} at {p:?}", self.what);
        }
    }

    /// The crossings of the ray `o + t·d` from outside, checked consistent —
    /// `t > 0` ascending, transitions alternating `Enter`, `Exit`, …, ending
    /// outside — and `n` of them when given (else an even number).
    fn ray(&self, o: DVec3, d: DVec3, n: Option<usize>, case: &str) -> RayCrossings {
        let rc = self.accel.ray_crossings(&Ray::new(o, d)).unwrap();
        let t = Ctx(format!(
            "{}: {case}: ray {o:?} + t·{d:?}: {:?}",
            self.what, rc.hits
        ));
        t.eq(rc.origin, Outside, "origin");
        t.eq(rc.hits.len(), n.unwrap_or(rc.hits.len() / 2 * 2), "count");
        for (i, h) in rc.hits.iter().enumerate() {
            let want = [Transition::Enter, Transition::Exit][i % 2];
            t.eq(h.transition, want, format!("transition {i}"));
        }
        t.eq(rc.hits.iter().all(|h| h.t > 0.0), true, "t > 0");
        let sorted = rc.hits.windows(2).all(|w| w[0].t <= w[1].t);
        t.eq(sorted, true, "t order");
        rc
    }
}

/// Whether every corner of `face` has coordinate `axis` equal to `v`.
fn face_on(solid: &Solid, face: FaceId, axis: usize, v: f64) -> bool {
    solid
        .face_vertices(face)
        .all(|id| solid.position(id)[axis] == v)
}

/// The box `[2, 4] × [3, 5] × [4, 6]` scaled by `2^k`, and `c ↦ c·2^(k−2)`.
fn box_at(k: i32) -> (Solid, impl Fn(i64) -> f64) {
    let unit = builders::cuboid(DVec3::new(8.0, 12.0, 16.0), DVec3::new(16.0, 20.0, 24.0));
    (scaled(&unit.expect("box"), k - 2), move |c| sc(c, k - 2))
}

fn check_box_classification(k: i32) {
    let ((solid, q), max, min) = (box_at(k), f64::MAX, pow2(-1074));
    let b = Probe::new(&solid, true, format!("box [2,4]x[3,5]x[4,6] at 2^{k}"));
    let p = |x, y, z| DVec3::new(q(x), q(y), q(z));
    let c = p(12, 16, 20);
    b.at(c, Inside, "centre");
    for far in [
        p(400, 16, 20),
        DVec3::ZERO,
        DVec3::splat(min),
        DVec3::new(-max, max, 0.0),
    ] {
        b.at(far, Outside, "far point");
    }
    // Corners, edge midpoints, face centres and face points off the diagonals.
    for on in [
        p(8, 12, 16),
        p(16, 20, 24),
        p(12, 12, 16),
        p(16, 16, 20),
        p(16, 13, 18),
    ] {
        b.at(on, OnBoundary, "corner, edge or face point");
    }
    for (i, lo, hi) in [(0, 8, 16), (1, 12, 20), (2, 16, 24)] {
        let moved = |v: f64| {
            let mut e = c;
            e[i] = v;
            e
        };
        for (v, want, m) in [
            (q(hi).next_up(), Outside, "above the max"),
            (q(hi).next_down(), Inside, "below the max"),
            (q(lo).next_down(), Outside, "below the min"),
            (q(lo).next_up(), Inside, "above the min"),
        ] {
            b.at(moved(v), want, &format!("one ulp {m} of axis {i}"));
        }
    }
}

/// The L prism (profile (0,0) (2,0) (2,1) (1,1) (1,2) (0,2), height 1)
/// scaled by `2^k`: not convex, its bottom in the plane z = 0.
fn check_l_prism_classification(k: i32) {
    let l = [(0, 0), (4, 0), (4, 2), (2, 2), (2, 4), (0, 4)];
    let profile = l.map(|(x, y)| DVec3::new(f64::from(x), f64::from(y), 0.0));
    let unit = builders::prism(&profile, DVec3::new(0.0, 0.0, 2.0)).expect("L prism");
    let l = Probe::new(&scaled(&unit, k - 1), false, format!("L prism at 2^{k}"));
    let (q, min) = (|c: i64| sc(c, k - 1), pow2(-1074));
    let (p, one, half) = (|x, y, z| DVec3::new(q(x), q(y), z), q(2), q(1));
    l.at(p(1, 1, half), Inside, "inside");
    l.at(p(3, 3, half), Outside, "in the notch");
    l.at(p(2, 2, half), OnBoundary, "on the reflex edge");
    l.at(p(2, 3, half), OnBoundary, "on a face of the notch");
    let notch = |x| DVec3::new(x, q(3), half);
    l.at(notch(one.next_up()), Outside, "one ulp into the notch");
    l.at(notch(one.next_down()), Inside, "one ulp from the notch");
    l.at(p(3, 1, one.next_up()), Outside, "one ulp above the top");
    l.at(p(3, 1, one.next_down()), Inside, "one ulp below the top");
    l.at(p(3, 1, min), Inside, "2^-1074 above the bottom");
    l.at(p(3, 1, 0.0), OnBoundary, "on the bottom");
    l.at(p(3, 1, -min), Outside, "2^-1074 below the bottom");
}

#[test]
fn classification_of_solids_at_extreme_scales() {
    for k in [-1000, -600, 0, 600, 900] {
        check_box_classification(k);
        check_l_prism_classification(k);
    }
}

#[test]
fn classification_of_solids_at_the_ends_of_the_range() {
    for k in [-1070, -1060, 1010, 1017] {
        check_box_classification(k);
        check_l_prism_classification(k);
    }
}

#[test]
fn ray_crossings_at_extreme_scales() {
    for k in [-1000, -600, 0, 600, 900] {
        let (solid, q) = box_at(k);
        let b = Probe::new(&solid, true, format!("box [2,4]x[3,5]x[4,6] at 2^{k}"));
        let p = |x, y, z| DVec3::new(q(x), q(y), q(z));
        // Through the centre, directions at three scales: in at x = 2·2^k,
        // out at x = 4·2^k.
        for dx in [1.0, q(4), pow2(-1074)] {
            // The crossings' t (out at 4·2^k / dx) overflow f64 for the
            // smallest direction unless the box is tiny: refused by name,
            // as a scene refuses it, never answered with t = inf.
            if !(q(16) / dx).is_finite() {
                let e = b
                    .accel
                    .ray_crossings(&Ray::new(p(0, 16, 20), DVec3::X * dx));
                assert!(
                    matches!(e, Err(QueryError::RayOutOfRange { .. })),
                    "{}: {e:?}",
                    b.what
                );
                continue;
            }
            let rc = b.ray(p(0, 16, 20), DVec3::X * dx, Some(2), "through the centre");
            let t = Ctx(format!("{}: ray through the centre: {:?}", b.what, rc.hits));
            let on = |i: usize, x| face_on(&solid, rc.hits[i].face, 0, q(x));
            t.eq(on(0, 8), true, "enters at x min");
            t.eq(on(1, 16), true, "leaves at x max");
        }
        // In through an edge, out through the opposite one; corner to corner.
        b.ray(p(12, 8, 12), p(0, 4, 4), Some(2), "edge to edge");
        b.ray(p(4, 8, 12), p(4, 4, 4), Some(2), "corner to corner");
        // Grazing an edge or a corner, along an edge, in a face's plane: even.
        b.ray(p(12, 8, 20), p(0, 4, -4), None, "grazing an edge");
        b.ray(p(4, 8, 20), p(4, 4, -4), None, "grazing a corner");
        b.ray(p(0, 12, 16), p(4, 0, 0), None, "along an edge");
        b.ray(p(0, 16, 16), p(4, 0, 0), None, "in the plane of a face");
    }
}

#[test]
fn rays_from_subnormal_heights_through_edges() {
    // The box [−1, 1]² × [0, 2] scaled by 2^k: its bottom edges lie in z = 0,
    // so rays from heights ±h (h = 2^-1070) can be aimed exactly at them.
    let (h, min) = (pow2(-1070), pow2(-1074));
    // (At 2^4 already, a direction (64, 0, 2^-1069) scaled to unit size loses its
    // z: the exact answer is for the ray as given.)
    for k in [-1000, -600, 0, 4, 600, 900] {
        let s = pow2(k);
        let unit = builders::cuboid(DVec3::new(-1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 2.0));
        let solid = scaled(&unit.expect("box"), k);
        let b = Probe::new(&solid, true, format!("box [-1,1]²x[0,2] at 2^{k}"));
        let from = |z| DVec3::new(-3.0 * s, 0.0, z);
        let d = |dz| DVec3::new(4.0 * s, 0.0, dz);
        b.at(from(h), Outside, "ray origin");
        b.at(DVec3::new(0.0, 0.0, h), Inside, "2^-1070 above the bottom");
        // In through the face x = −s at height h/2, out through the edge (s, ·, 0).
        b.ray(from(h), d(-h), Some(2), "from +h out through an edge");
        // In through the edge (−s, ·, 0), out through the face x = s at height h.
        b.ray(from(-h), d(2.0 * h), Some(2), "from -h in through an edge");
        // Below the box until it touches the edge (s, ·, 0), then beyond it.
        b.ray(from(-h), d(h), None, "from -h grazing an edge");
        // Horizontal at heights 2^-1074, −2^-1074 and 0 (in the bottom's plane).
        b.ray(from(min), DVec3::X, Some(2), "at height 2^-1074");
        b.ray(from(-min), DVec3::X, Some(0), "at height -2^-1074");
        b.ray(from(0.0), DVec3::X, None, "in the plane of the bottom");
    }
}

/// Crossing parameters are rounded constructions, but the order of the
/// crossings (and `first_hit`) rests on them: they must stay finite and
/// close to the truth when the solid's coordinates are extreme.
#[test]
fn ray_parameters_at_extreme_scales() {
    for k in [-1000, -600, 0, 600, 900] {
        let ((solid, q), o) = (box_at(k), DVec3::new(0.0, sc(4, k), sc(5, k)));
        let (accel, ray) = (Accel::new(&solid), Ray::new(o, DVec3::X));
        let near = |t: f64, w: f64| (t - w).abs() <= w * 1e-12;
        let rc = accel.ray_crossings(&ray).unwrap();
        let ts: Vec<f64> = rc.hits.iter().map(|h| h.t).collect();
        let ok = ts.len() == 2 && near(ts[0], q(8)) && near(ts[1], q(16));
        assert!(ok, "box at 2^{k}: t {ts:?}, want 2^{k}·[2, 4]");
        let first = accel.first_hit(&ray).unwrap().expect("a hit");
        let ok = face_on(&solid, first.face, 0, q(8)) && near(first.t, q(8));
        assert!(
            ok,
            "box at 2^{k}: first hit {first:?}, want x min at 2^{k}·2"
        );
    }
}
