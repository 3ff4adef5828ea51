use std::collections::HashMap;

use proptest::prelude::*;

use super::*;
use crate::geom::dyadic::Dyadic;
use crate::geom::incircle;

fn v(x: f64, y: f64) -> DVec2 {
    DVec2::new(x, y)
}

/// Twice the signed area of a loop, exactly (the shoelace sum in dyadic
/// rationals).
fn double_area(ring: &[DVec2]) -> Dyadic {
    let n = ring.len();
    let mut sum = Dyadic::of(0.0);
    for i in 0..n {
        let (p, q) = (ring[i], ring[(i + 1) % n]);
        let term = &(&Dyadic::of(p.x) * &Dyadic::of(q.y)) - &(&Dyadic::of(p.y) * &Dyadic::of(q.x));
        sum = &sum + &term;
    }
    sum
}

fn abs(d: Dyadic) -> Dyadic {
    if d.sign() == Sign::Negative { -d } else { d }
}

/// Checks everything a triangulation of these loops must satisfy; panics
/// with a message naming the failure.
fn check_triangulation(outer: &[DVec2], holes: &[&[DVec2]], triangles: &[[usize; 3]]) {
    let rings: Vec<&[DVec2]> = std::iter::once(outer)
        .chain(holes.iter().copied())
        .collect();
    let points: Vec<DVec2> = rings.iter().flat_map(|r| r.iter().copied()).collect();
    let n = points.len();
    // The count.
    assert_eq!(triangles.len(), n + 2 * holes.len() - 2, "triangle count");
    // Every triangle counter-clockwise, exactly.
    for t in triangles {
        assert!(t.iter().all(|&i| i < n), "{t:?}");
        let [a, b, c] = t.map(|i| points[i]);
        assert_eq!(
            orient2d(a, b, c),
            Sign::Positive,
            "{t:?} is not counter-clockwise"
        );
    }
    // Areas sum exactly to the outer area minus the holes'.
    let mut expected = abs(double_area(outer));
    for h in holes {
        expected = &expected - &abs(double_area(h));
    }
    let mut sum = Dyadic::of(0.0);
    for t in triangles {
        sum = &sum + &double_area(&t.map(|i| points[i]));
    }
    assert_eq!((&sum - &expected).sign(), Sign::Zero, "areas do not add up");
    // Each directed edge at most once; each loop edge once, with the
    // polygon's inside on its triangle's side; every other edge twice.
    let mut owner: HashMap<(usize, usize), usize> = HashMap::new();
    for (k, t) in triangles.iter().enumerate() {
        for e in 0..3 {
            let edge = (t[e], t[(e + 1) % 3]);
            assert!(owner.insert(edge, k).is_none(), "edge {edge:?} twice");
        }
    }
    let mut offset = 0;
    let mut boundary = std::collections::HashSet::new();
    for (r, ring) in rings.iter().enumerate() {
        let len = ring.len();
        let ccw = double_area(ring).sign() == Sign::Positive;
        for i in 0..len {
            let (a, b) = (offset + i, offset + (i + 1) % len);
            // The inside lies left of the outer loop wound counter-clockwise
            // and of holes wound clockwise.
            let inward = if ccw == (r == 0) { (a, b) } else { (b, a) };
            assert!(owner.contains_key(&inward), "loop edge {inward:?} missing");
            assert!(
                !owner.contains_key(&(inward.1, inward.0)),
                "{inward:?} outside"
            );
            boundary.insert(inward);
        }
        offset += len;
    }
    for (&(a, b), &t) in &owner {
        if boundary.contains(&(a, b)) {
            continue;
        }
        let Some(&u) = owner.get(&(b, a)) else {
            panic!("interior edge {a}–{b} has one triangle");
        };
        // Locally Delaunay: the far vertex not strictly inside the circle.
        let far = triangles[u]
            .into_iter()
            .find(|&x| x != a && x != b)
            .unwrap();
        let [p, q, r] = triangles[t].map(|i| points[i]);
        assert_ne!(
            incircle(p, q, r, points[far]),
            Sign::Positive,
            "edge {a}–{b} is not Delaunay"
        );
    }
}

fn square(x0: f64, y0: f64, size: f64) -> Vec<DVec2> {
    vec![
        v(x0, y0),
        v(x0 + size, y0),
        v(x0 + size, y0 + size),
        v(x0, y0 + size),
    ]
}

#[test]
fn a_square_and_a_square_with_a_hole() {
    let outer = square(0., 0., 4.);
    let t = triangulate(&outer, &[]).unwrap();
    check_triangulation(&outer, &[], &t);
    let mut hole = square(1., 1., 2.);
    hole.reverse();
    let t = triangulate(&outer, &[&hole]).unwrap();
    check_triangulation(&outer, &[&hole], &t);
    // Windings are normalised: the same polygon given the other way round.
    let mut cw_outer = outer.clone();
    cw_outer.reverse();
    let ccw_hole = square(1., 1., 2.);
    let t = triangulate(&cw_outer, &[&ccw_hole]).unwrap();
    check_triangulation(&cw_outer, &[&ccw_hole], &t);
}

#[test]
fn a_non_convex_polygon_with_collinear_vertices_and_three_holes() {
    // A comb (deep notches, many reflex vertices) with collinear vertices
    // along its base, holes in its body.
    let mut outer = vec![v(0., 0.)];
    for k in 1..=8 {
        outer.push(v(f64::from(k), 0.));
    }
    outer.push(v(8., 6.));
    for k in (0..4).rev() {
        let x = 2.0 * f64::from(k);
        outer.push(v(x + 1.5, 6.));
        outer.push(v(x + 1.5, 2.));
        outer.push(v(x + 0.5, 2.));
        outer.push(v(x + 0.5, 6.));
    }
    outer.pop();
    outer.push(v(0., 6.));
    let holes: Vec<Vec<DVec2>> = (0..3)
        .map(|k| square(0.5 + 2.5 * f64::from(k), 0.5, 1.))
        .collect();
    let refs: Vec<&[DVec2]> = holes.iter().map(Vec::as_slice).collect();
    let t = triangulate(&outer, &refs).unwrap();
    check_triangulation(&outer, &refs, &t);
}

#[test]
fn holes_sharing_a_rightmost_column_and_a_hole_beside_a_notch() {
    // Two holes whose rightmost vertices share x, bridged in turn; a third
    // whose visible vertices lie behind a reflex corner.
    let outer = vec![
        v(0., 0.),
        v(10., 0.),
        v(10., 10.),
        v(6., 10.),
        v(6., 5.),
        v(5., 10.),
        v(0., 10.),
    ];
    let a = square(1., 1., 2.);
    let b = square(1., 6., 2.);
    let c = vec![v(4., 6.), v(5., 8.), v(4.5, 6.)];
    let refs: Vec<&[DVec2]> = vec![&a, &b, &c];
    let t = triangulate(&outer, &refs).unwrap();
    check_triangulation(&outer, &refs, &t);
}

#[test]
fn cocircular_points_give_a_valid_delaunay_triangulation() {
    // A regular octagon on a circle of radius 5 with integer coordinates
    // (the Pythagorean points), all cocircular: any triangulation is
    // Delaunay, and the flips must stop.
    let outer = vec![
        v(5., 0.),
        v(4., 3.),
        v(3., 4.),
        v(0., 5.),
        v(-3., 4.),
        v(-4., 3.),
        v(-5., 0.),
        v(-4., -3.),
        v(-3., -4.),
        v(0., -5.),
        v(3., -4.),
        v(4., -3.),
    ];
    let t = triangulate(&outer, &[]).unwrap();
    check_triangulation(&outer, &[], &t);
}

#[test]
fn a_thin_polygon_gets_delaunay_triangles_not_a_fan() {
    // A long strip of 2 × 20 vertices: ear clipping alone would leave a
    // fan of slivers from one end; the flips give the zig-zag.
    let mut outer: Vec<DVec2> = (0..20).map(|k| v(f64::from(k), 0.)).collect();
    outer.extend((0..20).rev().map(|k| v(f64::from(k) + 0.5, 1.)));
    let t = triangulate(&outer, &[]).unwrap();
    check_triangulation(&outer, &[], &t);
    // Every triangle joins the two rows with vertices at most 1.5 apart in x.
    for tri in &t {
        let xs = tri.map(|i| outer[i].x);
        let spread = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - xs.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(spread <= 1.5, "{tri:?} spans {spread}");
    }
}

#[test]
fn hostile_input_is_named() {
    use TriangulateError::*;
    let outer = square(0., 0., 4.);
    let e = |o: &[DVec2], h: &[&[DVec2]]| triangulate(o, h).unwrap_err();
    assert_eq!(
        e(&[v(0., 0.), v(1., 0.)], &[]),
        TooFewVertices {
            ring: Ring::Outer,
            count: 2
        }
    );
    assert_eq!(
        e(&outer, &[&[v(1., 1.)]]),
        TooFewVertices {
            ring: Ring::Hole(0),
            count: 1
        }
    );
    assert_eq!(
        e(&[v(0., 0.), v(f64::NAN, 0.), v(0., 1.)], &[]),
        NonFinite {
            ring: Ring::Outer,
            vertex: 1
        }
    );
    let inf_hole = [v(1., 1.), v(2., 1.), v(1., f64::INFINITY)];
    assert_eq!(
        e(&outer, &[&inf_hole]),
        NonFinite {
            ring: Ring::Hole(0),
            vertex: 6
        }
    );
    assert_eq!(
        e(&[v(0., 0.), v(1., 1.), v(3., 3.)], &[]),
        Collinear { ring: Ring::Outer }
    );
    assert_eq!(e(&[v(2., 2.); 4], &[]), Collinear { ring: Ring::Outer });
    let bowtie = [v(0., 0.), v(1., 1.), v(1., 0.), v(0., 1.)];
    assert_eq!(
        e(&bowtie, &[]),
        SelfIntersecting {
            ring: Ring::Outer,
            first: 0,
            second: 2
        }
    );
    let repeated = [v(0., 0.), v(1., 0.), v(1., 0.), v(0., 1.)];
    assert!(matches!(e(&repeated, &[]), SelfIntersecting { .. }));
    assert_eq!(e(&outer, &[&square(5., 5., 1.)]), HoleOutside { hole: 0 });
    // The outer loop inside the hole is "hole outside" too.
    assert_eq!(
        e(&square(1., 1., 1.), &[&square(0., 0., 4.)]),
        HoleOutside { hole: 0 }
    );
    assert_eq!(
        e(&outer, &[&square(3., 1., 2.)]),
        HoleCrossesOuter {
            hole: 0,
            hole_edge: 4,
            outer_edge: 1
        }
    );
    // Touching the outer loop at one vertex is refused too.
    let touching = [v(4., 2.), v(3., 3.), v(3., 1.)];
    assert!(matches!(
        e(&outer, &[&touching]),
        HoleCrossesOuter { hole: 0, .. }
    ));
    let a = square(1., 1., 1.);
    let overlapping = square(1.5, 1.5, 1.);
    let nested = square(1.25, 1.25, 0.5);
    let touching_a = square(2., 1., 1.);
    for other in [&overlapping, &nested, &touching_a] {
        assert_eq!(
            e(&outer, &[&square(0.2, 3., 0.5), &a, other]),
            HolesOverlap {
                first: 1,
                second: 2
            }
        );
    }
    // Errors print the loop and indices.
    let message = e(&outer, &[&square(3., 1., 2.)]).to_string();
    assert!(
        message.contains("hole 0") && message.contains("vertex 4"),
        "{message}"
    );
}

#[test]
fn exact_far_from_one_and_on_nearly_collinear_input() {
    for scale in [1e-300, 1e-100, 1e100, 1e300] {
        let outer: Vec<DVec2> = square(0., 0., 4.).into_iter().map(|p| p * scale).collect();
        let hole: Vec<DVec2> = square(1., 1., 2.).into_iter().map(|p| p * scale).collect();
        let t = triangulate(&outer, &[&hole]).unwrap();
        check_triangulation(&outer, &[&hole], &t);
    }
    // A vertex one ulp off a long edge's line: a valid, tiny triangle, no
    // flipped one.
    let outer = vec![
        v(0., 0.),
        v(0.5, f64::EPSILON / 4.),
        v(1., 0.),
        v(1., 1.),
        v(0., 1.),
    ];
    let t = triangulate(&outer, &[]).unwrap();
    check_triangulation(&outer, &[], &t);
    let reflex = vec![
        v(0., 0.),
        v(0.5, -f64::EPSILON / 4.),
        v(1., 0.),
        v(1., 1.),
        v(0., 1.),
    ];
    let t = triangulate(&reflex, &[]).unwrap();
    check_triangulation(&reflex, &[], &t);
}

#[test]
fn a_planar_face_in_space() {
    // A square with a square hole in the plane z = x + 2y (exactly
    // representable), wound counter-clockwise around (−1, −2, 1), whose
    // largest component is y: projected along y, flipped.
    let lift = |x: f64, y: f64| DVec3::new(x, y, x + 2.0 * y);
    let outer: Vec<DVec3> = square(0., 0., 4.).iter().map(|p| lift(p.x, p.y)).collect();
    let hole: Vec<DVec3> = square(1., 1., 2.)
        .iter()
        .rev()
        .map(|p| lift(p.x, p.y))
        .collect();
    let t = triangulate_3d(&outer, &[&hole]).unwrap();
    assert_eq!(t.len(), 8);
    let points: Vec<DVec3> = outer.iter().chain(hole.iter()).copied().collect();
    let normal = newell_vector_area(&outer, outer[0]);
    for tri in &t {
        let [a, b, c] = tri.map(|i| points[i]);
        assert!(
            (b - a).cross(c - a).dot(normal) > 0.0,
            "{tri:?} wound against the face"
        );
    }
    // Reversed face: triangles reversed too.
    let reversed: Vec<DVec3> = outer.iter().rev().copied().collect();
    let t = triangulate_3d(&reversed, &[]).unwrap();
    let normal = newell_vector_area(&reversed, reversed[0]);
    for tri in &t {
        let [a, b, c] = tri.map(|i| reversed[i]);
        assert!((b - a).cross(c - a).dot(normal) > 0.0, "{tri:?}");
    }
    // A NaN in the coordinate the projection drops is still refused.
    let mut bad = outer.clone();
    bad[2].y = f64::NAN;
    assert_eq!(
        triangulate_3d(&bad, &[]),
        Err(TriangulateError::NonFinite {
            ring: Ring::Outer,
            vertex: 2
        })
    );
}

/// A star-shaped loop around `centre`: `n` vertices at sorted angles, one
/// in each of `n` equal sectors, radii between `r_min` and `r_max`.
fn star(centre: DVec2, jitter: &[f64], radii: &[f64], r_min: f64, r_max: f64) -> Vec<DVec2> {
    let n = jitter.len();
    (0..n)
        .map(|k| {
            let angle = std::f64::consts::TAU * (k as f64 + jitter[k]) / n as f64;
            let r = r_min + (r_max - r_min) * radii[k];
            centre + r * DVec2::new(angle.cos(), angle.sin())
        })
        .collect()
}

fn unit_list(min: usize, max: usize) -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
    (min..max).prop_flat_map(|n| {
        (
            prop::collection::vec(0.0..1.0f64, n),
            prop::collection::vec(0.0..1.0f64, n),
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Random star-shaped polygons (outer radii 0.5–1, neighbours less than
    /// 120° apart, so the disk of radius 0.25 is inside) with up to four random
    /// star-shaped holes in the quadrants of that disk, on a coarse grid
    /// half the time (collinear and cocircular vertices).
    #[test]
    fn random_star_polygons_with_holes(
        outer in unit_list(6, 40),
        holes in prop::collection::vec(unit_list(3, 9), 0..5),
        snap in any::<bool>(),
    ) {
        let grid = |p: DVec2| if snap { (p * 64.0).round() / 64.0 } else { p };
        let outer_loop: Vec<DVec2> = star(DVec2::ZERO, &outer.0, &outer.1, 0.5, 1.0)
            .into_iter()
            .map(grid)
            .collect();
        let quadrants = [v(0.1, 0.1), v(-0.1, 0.1), v(-0.1, -0.1), v(0.1, -0.1)];
        let hole_loops: Vec<Vec<DVec2>> = holes
            .iter()
            .zip(quadrants)
            .map(|((jitter, radii), centre)| {
                star(centre, jitter, radii, 0.03, 0.07).into_iter().map(grid).collect()
            })
            .collect();
        let refs: Vec<&[DVec2]> = hole_loops.iter().map(Vec::as_slice).collect();
        match triangulate(&outer_loop, &refs) {
            Ok(t) => check_triangulation(&outer_loop, &refs, &t),
            // Snapping can make a small loop collinear or not simple; then
            // the error must say so.
            Err(e) => {
                prop_assert!(snap, "{e}");
                prop_assert!(
                    matches!(e, TriangulateError::Collinear { .. } | TriangulateError::SelfIntersecting { .. }),
                    "{e}"
                );
            }
        }
    }
}
