use super::*;
use TriTriContact::*;
use proptest::prelude::*;

fn v(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

const T: [DVec3; 3] = [
    DVec3::new(0., 0., 0.),
    DVec3::new(2., 0., 0.),
    DVec3::new(0., 2., 0.),
];

#[test]
fn crossing_touching_and_apart() {
    // Pierces the interior.
    assert_eq!(
        triangle_contact(T, [v(0.5, 0.5, -1.), v(0.5, 0.5, 1.), v(3., 3., 0.5)]),
        Crossing
    );
    // A vertex on T's edge, the rest below and above: touching.
    assert_eq!(
        triangle_contact(T, [v(1., 0., 0.), v(1., -1., 1.), v(1., -1., -1.)]),
        Touching
    );
    // Above, apart.
    assert_eq!(
        triangle_contact(T, [v(0., 0., 1.), v(1., 0., 1.), v(0., 1., 2.)]),
        Disjoint
    );
    // The planes' line crosses both triangles, which miss each other on it.
    assert_eq!(
        triangle_contact(T, [v(3., 3., -1.), v(3., 3., 1.), v(4., 2., 0.)]),
        Disjoint
    );
    // One ulp above the plane: apart, decided exactly; a vertex on it: touching.
    let up = f64::EPSILON;
    assert_eq!(
        triangle_contact(T, [v(0.5, 0.5, up), v(1.5, 0.1, up), v(0.1, 1.5, 2.)]),
        Disjoint
    );
    assert_eq!(
        triangle_contact(T, [v(0.5, 0.5, 0.), v(1.5, 0.1, up), v(0.1, 1.5, 2.)]),
        Touching
    );
}

#[test]
fn touching_at_a_vertex_an_edge_and_along_a_fin() {
    // Only the corner (0, 0, 0) in common.
    assert_eq!(
        triangle_contact(T, [v(0., 0., 0.), v(-1., 0., 1.), v(0., -1., 1.)]),
        Touching
    );
    // A shared edge, at a dihedral angle.
    assert_eq!(
        triangle_contact(T, [v(0., 0., 0.), v(2., 0., 0.), v(1., -1., 1.)]),
        Touching
    );
    // A fin standing on T's interior (an edge lying in T): touching, not
    // crossing, because the fin has no interior point in T's plane.
    assert_eq!(
        triangle_contact(T, [v(0.2, 0.2, 0.), v(1., 0.5, 0.), v(0.5, 0.5, 3.)]),
        Touching
    );
    // A triangle through T whose crossing segment ends exactly on T's edge
    // x = 0 from outside: the segments meet in one point only.
    assert_eq!(
        triangle_contact(T, [v(-1., 1., -1.), v(-1., 1., 1.), v(0., 1., 0.)]),
        Touching
    );
    // Two triangles crossing in an X whose intervals on the common line
    // overlap in one point: touching.
    let a = [v(0., 0., -1.), v(0., 0., 1.), v(1., 0., 0.)];
    let b = [v(1., -1., 0.), v(1., 1., 0.), v(2., 0., 0.)];
    assert_eq!(triangle_contact(a, b), Touching);
    let b_shifted = [v(0.5, -1., 0.), v(0.5, 1., 0.), v(2., 0., 0.)];
    assert_eq!(triangle_contact(a, b_shifted), Crossing);
}

#[test]
fn coplanar_overlap_touch_and_apart() {
    assert_eq!(
        triangle_contact(T, [v(1., 1., 0.), v(3., 1., 0.), v(1., 3., 0.)]),
        CoplanarTouching
    );
    assert_eq!(
        triangle_contact(T, [v(0.5, 0.5, 0.), v(3., 1., 0.), v(1., 3., 0.)]),
        CoplanarOverlap
    );
    assert_eq!(
        triangle_contact(T, [v(2., 2., 0.), v(3., 2., 0.), v(2., 3., 0.)]),
        Disjoint
    );
    // The same triangle, reversed: overlap.
    assert_eq!(triangle_contact(T, [T[2], T[1], T[0]]), CoplanarOverlap);
    // A mirror image across an edge: touching along it.
    assert_eq!(
        triangle_contact(T, [v(0., 0., 0.), v(2., 0., 0.), v(0., -2., 0.)]),
        CoplanarTouching
    );
    // A star of David: no vertex inside the other, still overlapping.
    let up = [v(0., 0., 0.), v(6., 0., 0.), v(3., 6., 0.)];
    let down = [v(0., 4., 0.), v(3., -2., 0.), v(6., 4., 0.)];
    assert_eq!(triangle_contact(up, down), CoplanarOverlap);
    // Coplanar in a slanted plane (projection along the largest normal
    // component) touching at one vertex only.
    let a = [v(0., 0., 0.), v(1., 0., 1.), v(0., 1., 1.)];
    let b = [v(1., 0., 1.), v(2., 0., 2.), v(2., -1., 1.)];
    assert_eq!(orient3d(a[0], a[1], a[2], b[2]), Sign::Zero);
    assert_eq!(triangle_contact(a, b), CoplanarTouching);
}

#[test]
fn degenerate_triangles_are_the_segments_they_cover() {
    // A needle through T's interior: touching (it has no interior).
    let needle = [v(0.5, 0.5, -1.), v(0.5, 0.5, 1.), v(0.5, 0.5, 0.3)];
    assert_eq!(triangle_contact(T, needle), Touching);
    assert_eq!(triangle_contact(needle, T), Touching);
    // The same needle beside T.
    let beside = needle.map(|p| p + DVec3::new(3., 0., 0.));
    assert_eq!(triangle_contact(T, beside), Disjoint);
    // A point triangle on T's edge, and just off it.
    let point = [v(1., 0., 0.); 3];
    assert_eq!(triangle_contact(T, point), Touching);
    let off = [v(1., -f64::EPSILON, 0.); 3];
    assert_eq!(triangle_contact(T, off), Disjoint);
    // Two needles: crossing, collinear apart, collinear overlapping, skew.
    let x = [v(-1., 0., 0.), v(1., 0., 0.), v(0., 0., 0.)];
    let y = [v(0., -1., 0.), v(0., 1., 0.), v(0., 0.5, 0.)];
    assert_eq!(triangle_contact(x, y), Touching);
    let far = [v(2., 0., 0.), v(3., 0., 0.), v(2.5, 0., 0.)];
    assert_eq!(triangle_contact(x, far), Disjoint);
    let near = [v(1., 0., 0.), v(3., 0., 0.), v(2.5, 0., 0.)];
    assert_eq!(triangle_contact(x, near), Touching);
    let skew = [v(0., -1., 1.), v(0., 1., 1.), v(0., 0., 1.)];
    assert_eq!(triangle_contact(x, skew), Disjoint);
    // The middle of three collinear points is not an end.
    let long = [v(-5., 0., 0.), v(5., 0., 0.), v(1., 0., 0.)];
    assert_eq!(triangle_contact(long, far), Touching);
}

#[test]
fn decided_exactly_far_from_one() {
    // The crossing case scaled to the ends of the range.
    for scale in [1e-300, 1e-150, 1e150, 1e300] {
        let a = T.map(|p| p * scale);
        let b = [v(0.5, 0.5, -1.), v(0.5, 0.5, 1.), v(3., 3., 0.5)].map(|p| p * scale);
        assert_eq!(triangle_contact(a, b), Crossing, "{scale:e}");
        let c = [v(3., 3., -1.), v(3., 3., 1.), v(4., 2., 0.)].map(|p| p * scale);
        assert_eq!(triangle_contact(a, c), Disjoint, "{scale:e}");
    }
}

/// Exact rationals for the reference: `n / d` with `d > 0`, reduced.
#[derive(Clone, Copy, Debug)]
struct Q(i128, i128);

impl Q {
    fn int(n: i128) -> Q {
        Q(n, 1)
    }
    fn new(n: i128, d: i128) -> Q {
        let g = gcd(n.abs(), d.abs()).max(1);
        let s = if d < 0 { -1 } else { 1 };
        Q(s * n / g, s * d / g)
    }
    fn add(self, o: Q) -> Q {
        Q::new(self.0 * o.1 + o.0 * self.1, self.1 * o.1)
    }
    fn sub(self, o: Q) -> Q {
        Q::new(self.0 * o.1 - o.0 * self.1, self.1 * o.1)
    }
    fn mul(self, o: Q) -> Q {
        Q::new(self.0 * o.0, self.1 * o.1)
    }
    fn cmp(self, o: Q) -> std::cmp::Ordering {
        (self.0 * o.1).cmp(&(o.0 * self.1))
    }
    fn sign(self) -> i128 {
        self.0.signum()
    }
}

fn gcd(a: i128, b: i128) -> i128 {
    if b == 0 { a } else { gcd(b, a % b) }
}

type I3 = [i128; 3];

fn sub3(a: I3, b: I3) -> I3 {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}
fn cross(a: I3, b: I3) -> I3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}
fn dot(a: I3, b: I3) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The reference: intervals on the planes' common line computed as exact
/// rationals (non-coplanar), candidate points tested in both triangles
/// (coplanar). Independent of the orientation tricks of the code under test.
fn reference(p: [I3; 3], q: [I3; 3]) -> TriTriContact {
    let normal = |t: [I3; 3]| cross(sub3(t[1], t[0]), sub3(t[2], t[0]));
    let (np, nq) = (normal(p), normal(q));
    let sides = |t: [I3; 3], n: I3, o: I3| t.map(|x| dot(n, sub3(x, o)));
    let sq = sides(q, np, p[0]);
    if sq.iter().all(|&s| s == 0) {
        return coplanar_reference(p, q, np);
    }
    let sp = sides(p, nq, q[0]);
    let d = cross(np, nq);
    // Where the triangle meets the other plane, as values along d.
    let on_line = |t: [I3; 3], s: [i128; 3]| {
        let mut values = Vec::new();
        for i in 0..3 {
            let j = (i + 1) % 3;
            if s[i] == 0 {
                values.push(Q::int(dot(d, t[i])));
            }
            if s[i] * s[j] < 0 {
                let f = Q::new(s[i], s[i] - s[j]);
                values.push(Q::int(dot(d, t[i])).add(f.mul(Q::int(dot(d, sub3(t[j], t[i]))))));
            }
        }
        let lo = values.iter().copied().min_by(|a, b| a.cmp(*b));
        let hi = values.iter().copied().max_by(|a, b| a.cmp(*b));
        lo.zip(hi)
    };
    let (Some((lo_p, hi_p)), Some((lo_q, hi_q))) = (on_line(p, sp), on_line(q, sq)) else {
        return Disjoint;
    };
    let low = if lo_p.cmp(lo_q).is_ge() { lo_p } else { lo_q };
    let high = if hi_p.cmp(hi_q).is_le() { hi_p } else { hi_q };
    let straddles = |s: [i128; 3]| s.iter().any(|&x| x > 0) && s.iter().any(|&x| x < 0);
    match low.cmp(high) {
        std::cmp::Ordering::Greater => Disjoint,
        std::cmp::Ordering::Less if straddles(sp) && straddles(sq) => Crossing,
        _ => Touching,
    }
}

fn coplanar_reference(p: [I3; 3], q: [I3; 3], n: I3) -> TriTriContact {
    // Drop the axis of the largest normal component.
    let k = (0..3).max_by_key(|&k| n[k].abs()).unwrap_or(2);
    let (u, w) = ((k + 1) % 3, (k + 2) % 3);
    let flat = |t: [I3; 3]| t.map(|x| [Q::int(x[u]), Q::int(x[w])]);
    let (p2, q2) = (flat(p), flat(q));
    let orient = |a: [Q; 2], b: [Q; 2], c: [Q; 2]| {
        b[0].sub(a[0])
            .mul(c[1].sub(a[1]))
            .sub(b[1].sub(a[1]).mul(c[0].sub(a[0])))
            .sign()
    };
    let ccw = |t: [[Q; 2]; 3]| {
        if orient(t[0], t[1], t[2]) < 0 {
            [t[0], t[2], t[1]]
        } else {
            t
        }
    };
    let (p2, q2) = (ccw(p2), ccw(q2));
    let inside = |t: [[Q; 2]; 3], x: [Q; 2], strict: bool| {
        (0..3).all(|i| {
            let s = orient(t[i], t[(i + 1) % 3], x);
            if strict { s > 0 } else { s >= 0 }
        })
    };
    let mut candidates: Vec<[Q; 2]> = p2.iter().chain(q2.iter()).copied().collect();
    for i in 0..3 {
        for j in 0..3 {
            let (a, b) = (p2[i], p2[(i + 1) % 3]);
            let (c, e) = (q2[j], q2[(j + 1) % 3]);
            // a + t (b − a) on the line through c and e.
            let den = b[0]
                .sub(a[0])
                .mul(e[1].sub(c[1]))
                .sub(b[1].sub(a[1]).mul(e[0].sub(c[0])));
            if den.sign() == 0 {
                continue;
            }
            let num = c[0]
                .sub(a[0])
                .mul(e[1].sub(c[1]))
                .sub(c[1].sub(a[1]).mul(e[0].sub(c[0])));
            let t = Q::new(num.0 * den.1, num.1 * den.0);
            candidates.push([
                a[0].add(t.mul(b[0].sub(a[0]))),
                a[1].add(t.mul(b[1].sub(a[1]))),
            ]);
        }
    }
    let common: Vec<[Q; 2]> = candidates
        .into_iter()
        .filter(|&x| inside(p2, x, false) && inside(q2, x, false))
        .collect();
    if common.is_empty() {
        return Disjoint;
    }
    // Positive area iff three common points are not collinear; then their
    // centroid is interior to both.
    for a in 0..common.len() {
        for b in a + 1..common.len() {
            for c in b + 1..common.len() {
                let (x, y, z) = (common[a], common[b], common[c]);
                if orient(x, y, z) != 0 {
                    let third = Q::new(1, 3);
                    let g = [
                        x[0].add(y[0]).add(z[0]).mul(third),
                        x[1].add(y[1]).add(z[1]).mul(third),
                    ];
                    assert!(inside(p2, g, true) && inside(q2, g, true));
                    return CoplanarOverlap;
                }
            }
        }
    }
    CoplanarTouching
}

fn small_triangle() -> impl Strategy<Value = [I3; 3]> {
    prop::array::uniform3(prop::array::uniform3(-2i128..3))
}

fn to_f64(t: [I3; 3]) -> [DVec3; 3] {
    t.map(|p| DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64))
}

fn non_degenerate(t: &[I3; 3]) -> bool {
    cross(sub3(t[1], t[0]), sub3(t[2], t[0])) != [0, 0, 0]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(4000))]

    /// On a small integer grid (full of coplanar, collinear and touching
    /// cases) the classification equals the rational reference.
    #[test]
    fn agrees_with_the_rational_reference(p in small_triangle(), q in small_triangle()) {
        prop_assume!(non_degenerate(&p) && non_degenerate(&q));
        prop_assert_eq!(triangle_contact(to_f64(p), to_f64(q)), reference(p, q));
    }

    /// Coplanar pairs are rare among random triangles: here `q` is built in
    /// the plane of `p` (integer combinations of `p`'s corners).
    #[test]
    fn coplanar_pairs_agree_with_the_reference(
        p in small_triangle(),
        weights in prop::array::uniform3(prop::array::uniform2(-2i128..3)),
    ) {
        prop_assume!(non_degenerate(&p));
        let e1 = sub3(p[1], p[0]);
        let e2 = sub3(p[2], p[0]);
        let q = weights.map(|[s, t]| [0, 1, 2].map(|k| p[0][k] + s * e1[k] + t * e2[k]));
        prop_assume!(non_degenerate(&q));
        let expected = reference(p, q);
        prop_assert!(matches!(expected, Disjoint | CoplanarOverlap | CoplanarTouching));
        prop_assert_eq!(triangle_contact(to_f64(p), to_f64(q)), expected);
    }

    /// The answer does not depend on argument order, on which vertex comes
    /// first, or on winding; degenerate triangles included.
    #[test]
    fn the_answer_is_symmetric(p in small_triangle(), q in small_triangle()) {
        let (p, q) = (to_f64(p), to_f64(q));
        let base = triangle_contact(p, q);
        prop_assert_eq!(triangle_contact(q, p), base);
        prop_assert_eq!(triangle_contact([p[1], p[2], p[0]], q), base);
        prop_assert_eq!(triangle_contact([p[0], p[2], p[1]], [q[2], q[1], q[0]]), base);
        // Sharing a vertex position means meeting.
        if p.iter().any(|v| q.contains(v)) {
            prop_assert!(base.meets());
        }
        prop_assert_eq!(triangles_intersect(p, q), base.meets());
    }
}
