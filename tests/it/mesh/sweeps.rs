//! Solids from curves: every sweep, revolve and loft passes the validator
//! with a valid-solid verdict, has the expected genus, and the polyhedral
//! volume of the same segment count; bad input is refused with the variant
//! that names it.

use std::f64::consts::{FRAC_1_SQRT_2, PI, TAU};

use glam::{DVec2, DVec3};
use wingedge::curve::{BSpline, CurveError, KnotVector, MAX_SEGMENTS, Nurbs};
use wingedge::mesh::Solid;
use wingedge::shape::{
    Argument, MAX_VERTICES, RevolveAxis, Segments, SweepError, try_loft, try_revolve,
    try_revolve_curve, try_sweep,
};
use wingedge::validate::{Options, Validity, validate_soup};

/// Checks the solid's invariants and the validator's verdict; returns the
/// genus of its single shell.
fn valid_genus(solid: &Solid) -> i64 {
    solid
        .check_consistency()
        .expect("consistent winged-edge solid");
    let report = validate_soup(&solid.to_soup(), None, &Options::default()).unwrap();
    assert_eq!(
        report.validity,
        Validity::ValidSolid,
        "violations: {:?}",
        report.violations
    );
    assert_eq!(report.shells, 1);
    report.genus.expect("closed")
}

fn close(a: f64, b: f64, relative: f64) -> bool {
    (a - b).abs() <= relative * b.abs()
}

fn rectangle(x0: f64, x1: f64, y0: f64, y1: f64) -> Vec<DVec2> {
    vec![
        DVec2::new(x0, y0),
        DVec2::new(x1, y0),
        DVec2::new(x1, y1),
        DVec2::new(x0, y1),
    ]
}

/// The area of the regular `n`-gon inscribed in the unit circle.
fn inscribed(n: usize) -> f64 {
    n as f64 / 2.0 * (TAU / n as f64).sin()
}

#[test]
fn a_revolved_rectangle_is_a_polyhedral_annulus() {
    for n in [3, 8, 33] {
        let ring = try_revolve(
            &rectangle(1.0, 2.5, -0.5, 1.5),
            &RevolveAxis::Z,
            TAU,
            Segments::Count(n),
        )
        .unwrap();
        assert_eq!(valid_genus(&ring), 1, "n = {n}");
        assert_eq!(ring.vertex_count(), 4 * n);
        let want = inscribed(n) * (2.5f64.powi(2) - 1.0) * 2.0;
        assert!(
            close(ring.volume(), want, 1e-12),
            "{n}: {} vs {want}",
            ring.volume()
        );
    }
}

#[test]
fn a_rectangle_on_the_axis_gives_a_cylinder_with_flat_disks() {
    let n = 24;
    let cylinder = try_revolve(
        &rectangle(0.0, 2.0, 0.0, 3.0),
        &RevolveAxis::Z,
        TAU,
        Segments::Count(n),
    )
    .unwrap();
    assert_eq!(valid_genus(&cylinder), 0);
    // Two n-gon disks and n side quadrilaterals; no pole vertex is left.
    assert_eq!(
        (cylinder.vertex_count(), cylinder.face_count()),
        (2 * n, n + 2)
    );
    let want = inscribed(n) * 4.0 * 3.0;
    assert!(close(cylinder.volume(), want, 1e-12));
}

#[test]
fn a_partial_turn_has_caps_and_wedge_volume() {
    let (angle, n) = (PI / 2.0, 5);
    let wedge = try_revolve(
        &rectangle(1.0, 2.0, 0.0, 1.0),
        &RevolveAxis {
            origin: DVec3::new(1.0, 2.0, 3.0),
            direction: DVec3::new(0.0, 2.0, 0.0),
            radial: DVec3::new(1.0, 5.0, 0.0),
        },
        angle,
        Segments::Count(n),
    )
    .unwrap();
    assert_eq!(valid_genus(&wedge), 0);
    let want = n as f64 / 2.0 * (angle / n as f64).sin() * 3.0;
    assert!(close(wedge.volume(), want, 1e-12), "{}", wedge.volume());
    // A triangle touching the axis at one vertex is fine in a partial turn.
    let touching = [
        DVec2::new(0.0, 0.0),
        DVec2::new(1.0, -1.0),
        DVec2::new(1.0, 1.0),
    ];
    let fan = try_revolve(&touching, &RevolveAxis::Z, PI, Segments::Count(6)).unwrap();
    assert_eq!(valid_genus(&fan), 0);
}

#[test]
fn a_revolved_semicircle_is_a_sphere_with_two_poles() {
    // The right half of the unit circle from (0, −1) to (0, 1), rational
    // quadratic; the open curve closes along the axis.
    let knots = KnotVector::try_new(vec![0., 0., 0., 0.5, 0.5, 1., 1., 1.], 2).unwrap();
    let semicircle = Nurbs::try_new(
        [(0., -1.), (1., -1.), (1., 0.), (1., 1.), (0., 1.)]
            .map(|(x, y)| DVec3::new(x, y, 0.0))
            .to_vec(),
        vec![1.0, FRAC_1_SQRT_2, 1.0, FRAC_1_SQRT_2, 1.0],
        knots,
    )
    .unwrap();
    let tolerance = 1e-3;
    let sphere = try_revolve_curve(&semicircle, &RevolveAxis::Z, TAU, tolerance).unwrap();
    assert_eq!(valid_genus(&sphere), 0);
    let poles = sphere
        .vertices()
        .filter(|(_, v)| v.position.x == 0.0 && v.position.y == 0.0)
        .count();
    assert_eq!(poles, 2);
    // Inscribed, and within the chord tolerance of the sphere.
    let exact = 4.0 / 3.0 * PI;
    assert!(sphere.volume() < exact);
    assert!(close(sphere.volume(), exact, 0.01), "{}", sphere.volume());
}

#[test]
fn a_square_swept_along_a_straight_spline_is_a_prism() {
    let direction = DVec3::new(1.0, 2.0, 2.0);
    let path = BSpline::try_open_uniform(
        vec![
            DVec3::ZERO,
            direction * 0.5,
            direction * 1.5,
            direction * 2.0,
        ],
        3,
    )
    .unwrap();
    let solid = try_sweep(&rectangle(-1.0, 1.0, -0.5, 0.5), &path, 1e-4).unwrap();
    assert_eq!(valid_genus(&solid), 0);
    // Cross-section 2, length 2 · |(1, 2, 2)| = 6.
    assert!(close(solid.volume(), 12.0, 1e-12), "{}", solid.volume());
}

#[test]
fn a_square_swept_along_a_quarter_circle_is_a_bent_bar() {
    let radius = 5.0;
    let knots = KnotVector::try_open_uniform(3, 2).unwrap();
    let arc = Nurbs::try_new(
        vec![
            DVec3::new(radius, 0.0, 0.0),
            DVec3::new(radius, radius, 0.0),
            DVec3::new(0.0, radius, 0.0),
        ],
        vec![1.0, FRAC_1_SQRT_2, 1.0],
        knots,
    )
    .unwrap();
    let solid = try_sweep(&rectangle(-1.0, 1.0, -1.0, 1.0), &arc, 1e-4).unwrap();
    assert_eq!(valid_genus(&solid), 0);
    // Pappus: area 4 times the centroid's path length 5π/2, up to the
    // flattening.
    let pappus = 4.0 * radius * PI / 2.0;
    assert!(close(solid.volume(), pappus, 1e-3), "{}", solid.volume());
}

#[test]
fn equal_squares_loft_to_a_box_and_shrinking_ones_to_a_frustum() {
    let square = |half: f64, z: f64| {
        vec![
            DVec3::new(-half, -half, z),
            DVec3::new(half, -half, z),
            DVec3::new(half, half, z),
            DVec3::new(-half, half, z),
        ]
    };
    let boxed = try_loft(&[square(1.0, 0.0), square(1.0, 1.5), square(1.0, 3.0)]).unwrap();
    assert_eq!(valid_genus(&boxed), 0);
    assert!(close(boxed.volume(), 12.0, 1e-12));
    // Wound the other way: the same box.
    let reversed: Vec<Vec<DVec3>> = [square(1.0, 0.0), square(1.0, 3.0)]
        .into_iter()
        .map(|mut s| {
            s.reverse();
            s
        })
        .collect();
    let again = try_loft(&reversed).unwrap();
    assert_eq!(valid_genus(&again), 0);
    assert!(close(again.volume(), 12.0, 1e-12));
    let frustum = try_loft(&[square(2.0, 0.0), square(1.0, 3.0)]).unwrap();
    assert_eq!(valid_genus(&frustum), 0);
    // h/3 (A1 + A2 + √(A1 A2)) = 1 · (16 + 4 + 8).
    assert!(close(frustum.volume(), 28.0, 1e-12));
}

#[test]
fn sweeps_that_fold_are_refused_where_they_fold() {
    // A quarter turn of radius 0.5 with a profile reaching 1 from the path.
    let path = BSpline::try_open_uniform(
        vec![
            DVec3::ZERO,
            DVec3::new(0.5, 0.0, 0.0),
            DVec3::new(0.5, 0.5, 0.0),
        ],
        2,
    )
    .unwrap();
    let tight = try_sweep(&rectangle(-1.0, 1.0, -1.0, 1.0), &path, 1e-3);
    match tight {
        Err(SweepError::Folds {
            section,
            parameter: Some(t),
            ..
        }) => {
            assert!(section >= 1);
            assert!((0.0..=1.0).contains(&t));
        }
        other => panic!("expected a fold, got {other:?}"),
    }
    // The same turn with a profile that fits inside it sweeps fine.
    let thin = try_sweep(&rectangle(-0.2, 0.2, -0.2, 0.2), &path, 1e-3).unwrap();
    assert_eq!(valid_genus(&thin), 0);
}

#[test]
fn bad_sweep_input_is_named() {
    let square = rectangle(-1.0, 1.0, -1.0, 1.0);
    let path = BSpline::try_open_uniform(vec![DVec3::ZERO, DVec3::Z, DVec3::Z * 2.0], 2).unwrap();
    let still = BSpline::try_open_uniform(vec![DVec3::ONE; 3], 2).unwrap();
    assert_eq!(
        try_sweep(&square, &still, 1e-3).unwrap_err(),
        SweepError::ZeroLengthPath { point: DVec3::ONE }
    );
    for tolerance in [0.0, -1.0, f64::NAN] {
        assert!(matches!(
            try_sweep(&square, &path, tolerance),
            Err(SweepError::Curve {
                argument: Argument::Path,
                source: CurveError::BadTolerance { .. }
            })
        ));
    }
    let wavy = BSpline::try_open_uniform(
        vec![
            DVec3::ZERO,
            DVec3::new(3.0, 0.0, 1.0),
            DVec3::new(-3.0, 0.0, 2.0),
            DVec3::Z * 3.0,
        ],
        3,
    )
    .unwrap();
    assert_eq!(
        try_sweep(&[DVec2::ZERO, DVec2::X, DVec2::Y], &wavy, 1e-300).unwrap_err(),
        SweepError::Curve {
            argument: Argument::Path,
            source: CurveError::TooManySegments {
                tolerance: 1e-300,
                limit: MAX_SEGMENTS
            }
        }
    );
    let bow_tie = [DVec2::ZERO, DVec2::ONE, DVec2::X, DVec2::Y];
    assert!(matches!(
        try_sweep(&bow_tie, &path, 1e-3),
        Err(SweepError::SelfIntersecting {
            argument: Argument::Profile,
            ..
        })
    ));
    assert_eq!(
        try_sweep(&square[..2], &path, 1e-3).unwrap_err(),
        SweepError::TooFewVertices {
            argument: Argument::Profile,
            count: 2
        }
    );
    // A clamped path whose first two control points coincide starts with
    // a zero tangent: no frame there.
    let stalled =
        BSpline::try_open_uniform(vec![DVec3::ZERO, DVec3::ZERO, DVec3::Z, DVec3::Z * 2.0], 2)
            .unwrap();
    assert_eq!(
        try_sweep(&square, &stalled, 1e-3).unwrap_err(),
        SweepError::ZeroTangent { parameter: 0.0 }
    );
    let closed = BSpline::try_open_uniform(
        vec![
            DVec3::ZERO,
            DVec3::new(5.0, 0.0, 0.0),
            DVec3::new(5.0, 5.0, 0.0),
            DVec3::ZERO,
        ],
        2,
    )
    .unwrap();
    assert!(matches!(
        try_sweep(&square, &closed, 1e-3),
        Err(SweepError::ClosedPath { .. })
    ));
}

#[test]
fn bad_revolve_input_is_named() {
    let profile = rectangle(1.0, 2.0, 0.0, 1.0);
    let z = RevolveAxis::Z;
    assert_eq!(
        try_revolve(&rectangle(-0.5, 1.0, 0.0, 1.0), &z, TAU, Segments::Count(8)).unwrap_err(),
        SweepError::CrossesAxis {
            vertex: 0,
            radius: -0.5
        }
    );
    for angle in [0.0, -1.0, 7.0, f64::NAN] {
        assert!(matches!(
            try_revolve(&profile, &z, angle, Segments::Count(8)),
            Err(SweepError::BadAngle { .. })
        ));
    }
    for (angle, count, minimum) in [(TAU, 2, 3), (1.0, 0, 1), (TAU, MAX_SEGMENTS + 1, 3)] {
        assert_eq!(
            try_revolve(&profile, &z, angle, Segments::Count(count)).unwrap_err(),
            SweepError::BadSegments {
                segments: count,
                minimum,
                limit: MAX_SEGMENTS
            }
        );
    }
    assert!(matches!(
        try_revolve(&profile, &z, TAU, Segments::Tolerance(0.0)),
        Err(SweepError::Curve {
            source: CurveError::BadTolerance { .. },
            ..
        })
    ));
    assert!(matches!(
        try_revolve(&profile, &z, TAU, Segments::Tolerance(1e-300)),
        Err(SweepError::Curve {
            source: CurveError::TooManySegments { .. },
            ..
        })
    ));
    let round: Vec<DVec2> = (0..200)
        .map(|i| {
            let a = TAU * f64::from(i) / 200.0;
            DVec2::new(2.0 + a.cos(), a.sin())
        })
        .collect();
    assert_eq!(
        try_revolve(&round, &z, TAU, Segments::Count(MAX_SEGMENTS)).unwrap_err(),
        SweepError::TooLarge {
            vertices: 200 * MAX_SEGMENTS,
            limit: MAX_VERTICES
        }
    );
    let parallel = RevolveAxis {
        radial: DVec3::Z * 3.0,
        ..z
    };
    assert!(matches!(
        try_revolve(&profile, &parallel, TAU, Segments::Count(8)),
        Err(SweepError::BadAxis { .. })
    ));
    let tilted = BSpline::try_open_uniform(
        vec![
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(2.0, 1.0, 0.5),
            DVec3::new(1.0, 2.0, 0.0),
        ],
        2,
    )
    .unwrap();
    assert!(matches!(
        try_revolve_curve(&tilted, &z, TAU, 1e-3),
        Err(SweepError::NonPlanar {
            argument: Argument::Profile,
            ..
        })
    ));
}

#[test]
fn bad_loft_input_is_named() {
    let square = |z: f64| {
        vec![
            DVec3::new(0.0, 0.0, z),
            DVec3::new(1.0, 0.0, z),
            DVec3::new(1.0, 1.0, z),
            DVec3::new(0.0, 1.0, z),
        ]
    };
    assert_eq!(
        try_loft(&[square(0.0)]).unwrap_err(),
        SweepError::TooFewSections { count: 1 }
    );
    let mut short = square(1.0);
    short.pop();
    assert_eq!(
        try_loft(&[square(0.0), short]).unwrap_err(),
        SweepError::SectionSize {
            section: 1,
            count: 3,
            expected: 4
        }
    );
    let mut bent = square(1.0);
    bent[2].z = 1.5;
    assert!(matches!(
        try_loft(&[square(0.0), bent]),
        Err(SweepError::NonPlanar {
            argument: Argument::Section(1),
            vertex: _,
            ..
        })
    ));
    let mut against = square(2.0);
    against.reverse();
    assert_eq!(
        try_loft(&[square(0.0), square(1.0), against]).unwrap_err(),
        SweepError::SectionWinding {
            section: 2,
            previous: 1
        }
    );
    assert!(matches!(
        try_loft(&[square(0.0), square(2.0), square(1.0)]),
        Err(SweepError::Folds {
            section: 2,
            parameter: None,
            ..
        })
    ));
}

#[test]
fn a_path_that_crosses_itself_is_refused_with_both_places() {
    // A symmetric cubic whose ends swap sides: x(t) = −x(1 − t) and
    // y(t) = y(1 − t), so it crosses itself at x = 0 for some t < ½ and
    // 1 − t; the square profile (side 1) is small beside its curvature.
    let path = BSpline::try_open_uniform(
        [(-10., 0.), (20., 20.), (-20., 20.), (10., 0.)]
            .map(|(x, y)| DVec3::new(x, y, 0.0))
            .to_vec(),
        3,
    )
    .unwrap();
    let err = try_sweep(&rectangle(-0.5, 0.5, -0.5, 0.5), &path, 1e-4).unwrap_err();
    match err {
        SweepError::Collides {
            parts: [a, b],
            parameters: Some([ta, tb]),
        } => {
            let (a, b) = (a.section(), b.section());
            assert!(b > a + 2, "{a} {b}");
            // Around the crossing, t ≈ 0.2 and 0.8.
            assert!(ta < 0.5 && tb > 0.5, "{ta} {tb}");
        }
        other => panic!("expected a collision, got {other}"),
    }
    // With the inner control points in order, x(t) is monotonic: an arch
    // that does not cross itself sweeps fine.
    let arch = BSpline::try_open_uniform(
        [(-10., 0.), (-5., 10.), (5., 10.), (10., 0.)]
            .map(|(x, y)| DVec3::new(x, y, 0.0))
            .to_vec(),
        3,
    )
    .unwrap();
    let solid = try_sweep(&rectangle(-0.5, 0.5, -0.5, 0.5), &arch, 1e-4).unwrap();
    assert_eq!(valid_genus(&solid), 0);
}

/// A profile with two holes swept along a bent B-spline: a valid solid of
/// genus 2 whose caps are faces with a ring per hole, and whose volume is
/// the outer sweep's minus the holes' sweeps (the same frames, so the same
/// tessellation); its scene leaf too.
#[test]
fn a_profile_with_holes_sweeps_to_a_bar_with_tunnels() {
    let path = BSpline::try_open_uniform(
        vec![
            DVec3::ZERO,
            DVec3::new(0.0, 0.0, 4.0),
            DVec3::new(3.0, 0.0, 6.0),
            DVec3::new(6.0, 1.0, 6.0),
        ],
        3,
    )
    .unwrap();
    let outer = rectangle(-1.0, 1.0, -0.6, 0.6);
    let holes = vec![
        rectangle(-0.8, -0.2, -0.3, 0.3),
        rectangle(0.2, 0.8, -0.3, 0.3),
    ];
    let solid = wingedge::shape::try_sweep_with_holes(&outer, &holes, &path, 1e-3).unwrap();
    solid.check_consistency().unwrap();
    let report = wingedge::boolean::prove(&solid).expect("a valid solid");
    assert_eq!(report.validity, Validity::ValidSolid);
    assert_eq!(report.genus, Some(2));
    assert_eq!(solid.ring_count(), 4);
    let expected = try_sweep(&outer, &path, 1e-3).unwrap().volume()
        - holes
            .iter()
            .map(|h| try_sweep(h, &path, 1e-3).unwrap().volume())
            .sum::<f64>();
    assert!(
        close(solid.volume(), expected, 1e-12),
        "{} vs {expected}",
        solid.volume()
    );
    // Bad holes name themselves.
    let err = wingedge::shape::try_sweep_with_holes(&outer, &[vec![DVec2::ZERO; 3]], &path, 1e-3)
        .unwrap_err();
    assert!(
        matches!(
            err,
            SweepError::RepeatedVertex {
                argument: Argument::Hole(0),
                ..
            }
        ),
        "{err}"
    );
    // The scene leaf: a point in a tunnel is outside, one in the wall inside.
    let scene = wingedge::scene::Scene::from_json(
        r#"{"root": {"sweep": {"profile": [[-1,-0.6],[1,-0.6],[1,0.6],[-1,0.6]],
            "holes": [[[-0.8,-0.3],[-0.2,-0.3],[-0.2,0.3],[-0.8,0.3]]],
            "path": {"degree": 1, "points": [[0,0,0],[0,0,4]]}, "tolerance": 1e-3}}}"#,
        "holed.json",
        std::path::Path::new("."),
    )
    .unwrap();
    let mut stats = wingedge::csg::Stats::default();
    let mut at = |p: DVec3| scene.csg.classify_point(p, &mut stats);
    assert_eq!(
        at(DVec3::new(-0.5, 0.0, 2.0)),
        wingedge::csg::Containment::Outside
    );
    assert_eq!(
        at(DVec3::new(0.5, 0.0, 2.0)),
        wingedge::csg::Containment::Inside
    );
}
