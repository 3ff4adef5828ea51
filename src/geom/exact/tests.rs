use super::*;
use crate::geom::orient3d;

#[test]
fn line_side_matches_orient3d_when_the_direction_is_exact() {
    let o = DVec3::new(0.5, 0.25, -1.0);
    let q = DVec3::new(1.5, 0.75, 2.0);
    let pts = [
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.0, 1.0, 0.5),
        DVec3::new(-1.0, -1.0, 3.0),
        DVec3::new(1.0, 0.5, 0.5),
    ];
    for &a in &pts {
        for &b in &pts {
            assert_eq!(line_side(o, q - o, a, b), orient3d(o, q, a, b));
        }
    }
}

#[test]
fn exact_fallback_decides_tiny_determinants() {
    // A line exactly through a point a: with b chosen so that the segment
    // is coplanar with the line, the sign is zero; one ulp off is not.
    let o = DVec3::new(0.1, 0.2, 0.3);
    let d = DVec3::new(0.7, 0.11, 0.13);
    let a = DVec3::new(1e-3, 5.0, -2.0);
    let b = a + DVec3::new(0.0, 0.0, 1.0);
    let s = line_side(o, d, a, b);
    let b2 = DVec3::new(b.x, b.y, f64::from_bits(b.z.to_bits() + 1));
    let s2 = line_side(o, d, a, b2);
    // Same side or zero, never contradicting a direct exact evaluation.
    assert_eq!(s, -line_side(o, d, b, a));
    assert_eq!(s2, -line_side(o, d, b2, a));
    // Coplanar by construction: the segment lies on a line through o
    // parallel to d.
    let p = o + d * 2.0;
    assert_eq!(line_side(o, d, o, o), Sign::Zero);
    assert_eq!(
        det2_sign(
            [Diff::value(3.0), Diff::value(6.0)],
            [Diff::value(1.0), Diff::value(2.0)]
        ),
        Sign::Zero
    );
    let _ = p;
}

#[test]
fn det3_of_differences_is_exact() {
    // det[(1+u) - 1, ...] with u tiny: the rounded difference is exact
    // here, but the product terms cancel only exactly.
    let u = f64::EPSILON;
    let rows = [
        [Diff::new(1.0 + u, 1.0), Diff::value(1.0), Diff::value(0.0)],
        [Diff::value(1.0), Diff::value(1.0), Diff::value(0.0)],
        [Diff::value(0.0), Diff::value(0.0), Diff::value(1.0)],
    ];
    // det = (1+u-1)*1 - 1*1 = u - 1 < 0.
    assert_eq!(det3_sign(rows), Sign::Negative);
    let rows = [
        [Diff::new(3.0, 1.0), Diff::value(1.0), Diff::value(0.0)],
        [Diff::value(4.0), Diff::value(2.0), Diff::value(0.0)],
        [Diff::value(0.0), Diff::value(0.0), Diff::value(1.0)],
    ];
    assert_eq!(det3_sign(rows), Sign::Zero);
}

/// A point uniform in `[-1, 1)³` from the seeded test generator.
fn point(next: &mut impl FnMut() -> f64) -> DVec3 {
    DVec3::new(uniform(next), uniform(next), uniform(next))
}

/// Uniform in `[-1, 1)` from the seeded test generator.
fn uniform(next: &mut impl FnMut() -> f64) -> f64 {
    2.0 * next() - 1.0
}

/// Checks [`triangle_edge_sides`] against the exact [`line_side`] of each
/// edge: every certified sign must be the exact one.
fn check_shared_filter(o: DVec3, d: DVec3, tri: [DVec3; 3]) -> (bool, bool) {
    let [a, b, c] = tri;
    let rows = |p: DVec3| [p.x - o.x, p.y - o.y, p.z - o.z];
    let sides = triangle_edge_sides(d.to_array(), rows(a), rows(b), rows(c));
    let exact = [
        line_side(o, d, a, b),
        line_side(o, d, b, c),
        line_side(o, d, c, a),
    ];
    for (det, exact) in sides.det.into_iter().zip(exact) {
        if det > sides.bound {
            assert_eq!(exact, Sign::Positive, "{o} {d} {tri:?}");
        }
        if -det > sides.bound {
            assert_eq!(exact, Sign::Negative, "{o} {d} {tri:?}");
        }
    }
    let mixed = sides.certainly_mixed();
    if mixed {
        assert!(exact.contains(&Sign::Positive) && exact.contains(&Sign::Negative));
    }
    let uniform = sides.certainly_uniform();
    if let Some(s) = uniform {
        assert_eq!(exact, [s; 3]);
    }
    (mixed, uniform.is_some())
}

#[test]
fn shared_edge_filter_certifies_only_exact_signs() {
    let mut state = crate::test_rng::uniform(0x9e37_79b9_7f4a_7c15);
    let mut decided = 0;
    let mut total = 0;
    for scale in [1e-60, 1e-9, 1.0, 1e9, 1e60] {
        for offset in [0.0, 1.0, 1e8] {
            for _ in 0..2000 {
                let shift = DVec3::splat(offset * scale);
                let tri = [
                    point(&mut state) * scale + shift,
                    point(&mut state) * scale + shift,
                    point(&mut state) * scale + shift,
                ];
                let o = point(&mut state) * scale * 3.0 + shift;
                // Rays aimed at a random point of the triangle, at a
                // vertex, at an edge midpoint, and random ones.
                let (wa, wb) = (uniform(&mut state).abs(), uniform(&mut state).abs());
                let inside = tri[0] + (tri[1] - tri[0]) * wa * 0.5 + (tri[2] - tri[0]) * wb * 0.5;
                let mid = (tri[0] + tri[1]) * 0.5;
                let targets = [
                    inside,
                    tri[0],
                    tri[2],
                    mid,
                    point(&mut state) * scale + shift,
                ];
                for target in targets {
                    let d = target - o;
                    if d == DVec3::ZERO {
                        continue;
                    }
                    let (m, u) = check_shared_filter(o, d, tri);
                    if target == inside {
                        decided += usize::from(m || u);
                        total += 1;
                    }
                    // The direction nudged by one ulp, and the line
                    // moved to pass exactly through a corner.
                    let d2 = DVec3::new(f64::from_bits(d.x.to_bits() + 1), d.y, d.z);
                    check_shared_filter(o, d2, tri);
                    check_shared_filter(tri[1], d, tri);
                }
            }
        }
    }
    // The filter must also be useful: rays aimed inside the triangle
    // are nearly all decided.
    assert!(decided * 10 > total * 9, "{decided} of {total}");
}

#[test]
fn sos_is_antisymmetric_and_never_zero_for_distinct_points() {
    let o = DVec3::ZERO;
    let d = DVec3::X;
    // Segments the x-axis meets or runs along.
    let cases = [
        (DVec3::new(1.0, -1.0, 0.0), DVec3::new(1.0, 1.0, 0.0)),
        (DVec3::new(1.0, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0)),
        (DVec3::new(0.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0)),
        (DVec3::new(-1.0, 0.0, 0.0), DVec3::new(3.0, 0.0, 0.0)),
        (DVec3::new(1.0, 0.0, 0.0), DVec3::new(1.0, 0.0, 1.0)),
    ];
    for (a, b) in cases {
        let s = line_side_sos(o, d, a, b);
        assert_ne!(s, Sign::Zero, "{a} {b}");
        assert_eq!(s, -line_side_sos(o, d, b, a));
    }
}
