//! The B-spline basis and curves: the Cox–de Boor worked example with a
//! triple knot reproduced value by value, the basis properties (partition
//! of unity, non-negativity, local support, continuity) as properties, the
//! exact circle of a rational quadratic, and flattening within tolerance.

use glam::DVec3;
use proptest::prelude::*;
use wingedge::curve::{
    Approach, BSpline, Curve, CurveError, KnotVector, MAX_SEGMENTS, Nurbs, basis,
};

/// The knots `t_i = i` except for the triple knot 5: `0 1 2 3 4 5 5 5 6 7`.
fn worked_knots() -> KnotVector {
    KnotVector::try_new(vec![0., 1., 2., 3., 4., 5., 5., 5., 6., 7.], 3).unwrap()
}

/// `f` on `[lo, hi)`, 0 elsewhere.
fn piece(t: f64, lo: f64, hi: f64, f: impl Fn(f64) -> f64) -> f64 {
    if lo <= t && t < hi { f(t) } else { 0.0 }
}

#[test]
fn the_worked_example_value_by_value() {
    let k = worked_knots();
    type Expected = Box<dyn Fn(f64) -> f64>;
    let cases: Vec<(usize, usize, Expected)> = vec![
        (4, 1, Box::new(|t| piece(t, 4., 5., |_| 1.0))),
        (5, 1, Box::new(|_| 0.0)),
        (6, 1, Box::new(|_| 0.0)),
        (7, 1, Box::new(|t| piece(t, 5., 6., |_| 1.0))),
        (8, 1, Box::new(|t| piece(t, 6., 7., |_| 1.0))),
        (4, 2, Box::new(|t| piece(t, 4., 5., |t| t - 4.0))),
        (5, 2, Box::new(|_| 0.0)),
        (6, 2, Box::new(|t| piece(t, 5., 6., |t| 6.0 - t))),
        (4, 3, Box::new(|t| piece(t, 4., 5., |t| (t - 4.0).powi(2)))),
        (5, 3, Box::new(|t| piece(t, 5., 6., |t| (6.0 - t).powi(2)))),
        (
            4,
            4,
            Box::new(|t| {
                piece(t, 4., 5., |t| (t - 4.0).powi(3)) + piece(t, 5., 6., |t| (6.0 - t).powi(3))
            }),
        ),
    ];
    let mut nonzero = 0;
    for (i, order, expected) in &cases {
        // Every sixteenth from 3 to 8, knots included.
        for step in 48..=128 {
            let t = f64::from(step) / 16.0;
            let got = basis(&k, *i, *order, t).unwrap();
            let want = expected(t);
            assert!(
                (got - want).abs() <= 1e-14,
                "N({i},{order})({t}) = {got}, expected {want}"
            );
            if want != 0.0 {
                nonzero += 1;
            }
        }
    }
    assert!(nonzero > 100, "the comparisons cover the pieces");
    // Both pieces of N_{4,4} at sample points, spelled out.
    assert_eq!(basis(&k, 4, 4, 4.5).unwrap(), 0.125);
    assert_eq!(basis(&k, 4, 4, 5.0).unwrap(), 1.0);
    assert_eq!(basis(&k, 4, 4, 5.5).unwrap(), 0.125);
    assert_eq!(basis(&k, 4, 4, 6.0).unwrap(), 0.0);
}

#[test]
fn the_triple_knot_leaves_only_continuity_of_value() {
    // The curve x(t) = N_{4,4}(t): control values one-hot at 4, on the
    // worked knots extended by 8 and 9 so that the domain [3, 6] holds both
    // pieces.
    let mut knots = worked_knots().values().to_vec();
    knots.extend([8.0, 9.0]);
    let knots = KnotVector::try_new(knots, 3).unwrap();
    assert_eq!(knots.domain(), (3.0, 6.0));
    let points = (0..8)
        .map(|i| if i == 4 { DVec3::X } else { DVec3::ZERO })
        .collect();
    let c = BSpline::try_new(points, knots).unwrap();
    let below = |order| {
        c.try_derivative_limit(5.0, order, Approach::FromBelow)
            .unwrap()
    };
    let above = |order| {
        c.try_derivative_limit(5.0, order, Approach::FromAbove)
            .unwrap()
    };
    assert_eq!(below(0), DVec3::X);
    assert_eq!(above(0), DVec3::X);
    // d/dt (t − 4)³ = 3 and d/dt (6 − t)³ = −3 at t = 5.
    assert!((below(1).x - 3.0).abs() < 1e-12, "{}", below(1));
    assert!((above(1).x + 3.0).abs() < 1e-12, "{}", above(1));
}

#[test]
fn uniform_cubic_basis_values() {
    let k = KnotVector::try_uniform(4, 3).unwrap();
    for (t, want) in [
        (1.0, 1.0 / 6.0),
        (2.0, 4.0 / 6.0),
        (3.0, 1.0 / 6.0),
        (4.0, 0.0),
    ] {
        assert!((basis(&k, 0, 4, t).unwrap() - want).abs() < 1e-15, "{t}");
    }
    assert_eq!(basis(&k, 0, 4, 0.5).unwrap(), 0.125 / 6.0);
}

/// The unit circle in the `xy` plane: nine control points on the square,
/// corner weights `√2 / 2`, knots `0 0 0 ¼ ¼ ½ ½ ¾ ¾ 1 1 1`.
fn unit_circle() -> Nurbs {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let points = [
        (1., 0.),
        (1., 1.),
        (0., 1.),
        (-1., 1.),
        (-1., 0.),
        (-1., -1.),
        (0., -1.),
        (1., -1.),
        (1., 0.),
    ]
    .map(|(x, y)| DVec3::new(x, y, 0.0))
    .to_vec();
    let weights = vec![1., w, 1., w, 1., w, 1., w, 1.];
    let knots = KnotVector::try_new(
        vec![0., 0., 0., 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1., 1., 1.],
        2,
    )
    .unwrap();
    Nurbs::try_new(points, weights, knots).unwrap()
}

#[test]
fn a_rational_quadratic_gives_the_exact_circle() {
    let c = unit_circle();
    for i in 0..=1000 {
        let t = f64::from(i) / 1000.0;
        let p = c.try_point_at(t).unwrap();
        assert!(
            (p.length() - 1.0).abs() <= 4.0 * f64::EPSILON,
            "t {t}: radius {}",
            p.length()
        );
        assert_eq!(p.z, 0.0);
    }
    assert_eq!(c.try_point_at(0.25).unwrap(), DVec3::Y);
    assert_eq!(c.try_point_at(0.5).unwrap(), -DVec3::X);
    // A non-rational quadratic on the same polygon is not a circle.
    let plain = BSpline::try_new(c.control_points(), c.knots().clone()).unwrap();
    let off = plain.try_point_at(0.125).unwrap().length();
    assert!((off - 1.0).abs() > 1e-3, "{off}");
}

#[test]
fn flattening_the_circle_keeps_every_chord_within_tolerance() {
    let c = unit_circle();
    let size = 8.0_f64.sqrt(); // the control points' box is [−1, 1]².
    for tolerance in [1e-2, 1e-4, 1e-6] {
        let samples = c.try_flatten(tolerance).unwrap();
        assert_eq!(samples[0].point, DVec3::X);
        assert_eq!(samples.last().unwrap().parameter, 1.0);
        for pair in samples.windows(2) {
            assert!(pair[0].parameter < pair[1].parameter);
            // A chord of the unit circle strays most at its middle.
            let middle = 0.5 * (pair[0].point + pair[1].point);
            assert!(1.0 - middle.length() <= tolerance * size * (1.0 + 1e-9));
        }
        // Not wastefully fine: within a factor 4 of the fewest chords.
        let fewest = std::f64::consts::PI / (1.0 - tolerance * size).acos();
        assert!(
            (samples.len() as f64) < 4.0 * fewest + 8.0,
            "{tolerance}: {} samples for {fewest}",
            samples.len()
        );
    }
    assert_eq!(
        c.try_flatten(1e-300),
        Err(CurveError::TooManySegments {
            tolerance: 1e-300,
            limit: MAX_SEGMENTS
        })
    );
    assert!(matches!(
        c.try_flatten(0.0),
        Err(CurveError::BadTolerance { .. })
    ));
}

#[test]
fn bad_input_is_a_named_error() {
    assert!(matches!(
        KnotVector::try_new(vec![0., 1., 0.5, 2.], 1),
        Err(CurveError::DecreasingKnots { index: 2, .. })
    ));
    assert!(matches!(
        KnotVector::try_new(vec![0., 1., 2., 3., 4., 5., 6.], 3),
        Err(CurveError::TooFewKnots {
            count: 7,
            degree: 3,
            needed: 8
        })
    ));
    let knots = KnotVector::try_open_uniform(3, 2).unwrap();
    let points = vec![DVec3::ZERO, DVec3::X, DVec3::Y];
    for (index, w) in [(0, 0.0), (2, -0.5)] {
        let mut weights = vec![1.0; 3];
        weights[index] = w;
        assert_eq!(
            Nurbs::try_new(points.clone(), weights, knots.clone()),
            Err(CurveError::BadWeight { index, value: w })
        );
    }
}

/// A degree, then a knot vector for it (non-decreasing, repeats allowed
/// up to the degree inside) and a parameter in its domain.
fn knots_and_parameter() -> impl Strategy<Value = (KnotVector, f64)> {
    (1usize..=4)
        .prop_flat_map(|p| {
            let gaps = prop::collection::vec(prop_oneof![Just(0.0), 0.1f64..2.0], 2 * p + 2..12);
            (Just(p), gaps, 0.0f64..1.0)
        })
        .prop_filter_map("a valid knot vector", |(p, gaps, s)| {
            let knots: Vec<f64> = gaps
                .iter()
                .scan(0.0, |acc, g| {
                    *acc += g;
                    Some(*acc)
                })
                .collect();
            let k = KnotVector::try_new(knots, p).ok()?;
            let (a, b) = k.domain();
            let t = a + s * (b - a);
            (t < b).then_some((k, t))
        })
}

proptest! {
    #![proptest_config(crate::common::regressions_beside_source(ProptestConfig::with_cases(200)))]

    #[test]
    fn basis_properties((k, t) in knots_and_parameter()) {
        let order = k.degree() + 1;
        let n = k.control_point_count();
        let values: Vec<f64> = (0..n).map(|i| basis(&k, i, order, t).unwrap()).collect();
        // Partition of unity on the domain.
        let sum: f64 = values.iter().sum();
        prop_assert!((sum - 1.0).abs() < 1e-12, "sum {}", sum);
        let v = k.values();
        for (i, &value) in values.iter().enumerate() {
            // Non-negativity.
            prop_assert!(value >= 0.0);
            // Local support: zero outside [t_i, t_{i+k}).
            if t < v[i] || t >= v[i + order] {
                prop_assert_eq!(value, 0.0);
            }
        }
        // At most `order` functions are non-zero at any t.
        prop_assert!(values.iter().filter(|&&x| x != 0.0).count() <= order);
    }

    #[test]
    fn continuity_at_knots_is_degree_minus_multiplicity(
        (k, _) in knots_and_parameter(),
        seed in prop::collection::vec(-5.0f64..5.0, 36),
    ) {
        let p = k.degree();
        let points: Vec<DVec3> = (0..k.control_point_count())
            .map(|i| DVec3::new(seed[3 * i % 36], seed[(3 * i + 1) % 36], seed[(3 * i + 2) % 36]))
            .collect();
        let c = BSpline::try_new(points, k.clone()).unwrap();
        let (a, b) = c.domain();
        for u in k.breakpoints().into_iter().filter(|&u| a < u && u < b) {
            let m = k.multiplicity(u);
            for order in 0..(p + 1).saturating_sub(m) {
                let below = c.try_derivative_limit(u, order, Approach::FromBelow).unwrap();
                let above = c.try_derivative_limit(u, order, Approach::FromAbove).unwrap();
                let scale = 1.0 + below.length().max(above.length());
                prop_assert!(
                    (below - above).length() <= 1e-9 * scale,
                    "order {} at knot {} (multiplicity {}): {} vs {}", order, u, m, below, above
                );
            }
        }
    }

    #[test]
    fn knot_insertion_keeps_the_curve(
        (k, t) in knots_and_parameter(),
        s in 0.0f64..1.0,
    ) {
        let n = k.control_point_count();
        let points: Vec<DVec3> = (0..n)
            .map(|i| DVec3::new(i as f64, ((i * 7) % 5) as f64, ((i * 3) % 4) as f64))
            .collect();
        let c = BSpline::try_new(points, k.clone()).unwrap();
        let (a, b) = c.domain();
        let u = a + s * (b - a);
        match c.try_insert_knot(u) {
            Ok(refined) => {
                prop_assert_eq!(refined.control_points().len(), n + 1);
                let before = c.try_point_at(t).unwrap();
                let after = refined.try_point_at(t).unwrap();
                prop_assert!((before - after).length() < 1e-10 * (1.0 + before.length()));
            }
            Err(e) => {
                let is_multiplicity = matches!(e, CurveError::KnotMultiplicity { .. });
                prop_assert!(is_multiplicity, "{}", e);
                prop_assert_eq!(k.multiplicity(u), k.degree() + 1);
            }
        }
    }
}
