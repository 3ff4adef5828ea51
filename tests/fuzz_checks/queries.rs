//! Arbitrary points and rays against fixed solids: every classification
//! method, ray crossings, first hits, the batch forms, and a small CSG tree.
//! Any panic is a bug, and so is a broken invariant:
//!
//! - a non-finite point or an invalid ray (non-finite, or zero direction)
//!   gives an error, never an answer;
//! - on these closed solids parity, winding and (on convex ones) the face
//!   normals classify every finite point alike, and the winding number is a
//!   finite number;
//! - ray crossings are ascending with `t > 0`, their transitions alternate
//!   from the origin's class and end with an exit, the origin's class is the
//!   point's class and the first hit is one of the crossings — for every
//!   finite ray (the predicates are exact over the whole `f64` range);
//! - batch answers equal the single answers, and a batch error names the
//!   first bad element;
//! - the CSG trees refuse non-finite points and invalid rays (the `try_`
//!   forms); their spans are strictly ascending with `t > 0`, the first hit
//!   is the first span boundary, and on exact leaves a point strictly inside
//!   or outside agrees with the spans of a ray from it (both are boolean
//!   combinations of the leaves' exact decisions, for every finite ray).
//!
//! Coordinates are decoded from the bytes: one tag byte picks a special
//! value (NaN, ±∞, ±0, subnormals, ±1e308, the solids' vertex coordinates,
//! `1e8 ± 1`) or says that the next eight bytes are a raw `f64`.

use std::sync::LazyLock;

use wingedge::csg::{AxisBox, Csg, CsgExpr, HalfSpace, Polyhedron, Sphere, Stats};
use wingedge::geom::Ray;
use wingedge::glam::DVec3;
use wingedge::mesh::{Solid, builders};
use wingedge::query::{Accel, Containment, Method, QueryError, Transition};

struct Fixed {
    name: &'static str,
    accel: Accel,
    convex: bool,
}

static SOLIDS: LazyLock<Vec<Fixed>> = LazyLock::new(|| {
    let shifted = builders::cuboid(DVec3::splat(1e8 - 1.0), DVec3::splat(1e8 + 1.0))
        .expect("a cube translated by 1e8 is a box");
    let fixed = |name, solid: Solid, convex| Fixed {
        name,
        accel: Accel::new(&solid),
        convex,
    };
    vec![
        fixed("cube", builders::cube(), true),
        fixed("l_prism", builders::l_prism(), false),
        fixed("icosahedron", builders::icosahedron(), true),
        fixed("cube+1e8", shifted, true),
    ]
});

/// `(l_prism ∪ icosahedron) − box`, cut by a half-space: exact leaves only,
/// so that point classes and ray spans must agree exactly.
static EXACT_TREE: LazyLock<Csg> = LazyLock::new(|| {
    let leaf = |s: Solid| CsgExpr::leaf(Polyhedron::try_new(s).expect("a closed solid"));
    let cut = AxisBox::try_new(DVec3::new(0.5, 0.5, -2.0), DVec3::new(1.5, 1.5, 0.5))
        .expect("a proper box");
    let half = HalfSpace::try_new(DVec3::new(0.0, 0.0, 0.75), DVec3::new(0.0, 1.0, 1.0))
        .expect("a non-zero normal");
    let expr = leaf(builders::l_prism())
        .union(leaf(builders::icosahedron()))
        .difference(CsgExpr::leaf(cut))
        .intersection(CsgExpr::leaf(half));
    Csg::try_new(expr).expect("a well-formed tree")
});

/// A tree with a rounded leaf (a sphere): only no-panic and the span
/// invariants are checked.
static ROUND_TREE: LazyLock<Csg> = LazyLock::new(|| {
    let ball = Sphere::try_new(DVec3::new(1.0, 1.0, 0.5), 0.75).expect("a positive radius");
    let shifted = builders::cuboid(DVec3::splat(1e8 - 1.0), DVec3::splat(1e8 + 1.0))
        .expect("a cube translated by 1e8 is a box");
    let expr = CsgExpr::leaf(Polyhedron::try_new(builders::cube()).expect("closed"))
        .difference(CsgExpr::leaf(ball))
        .union(CsgExpr::leaf(Polyhedron::try_new(shifted).expect("closed")));
    Csg::try_new(expr).expect("a well-formed tree")
});

const SPECIAL: [f64; 24] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    0.0,
    -0.0,
    f64::MIN_POSITIVE,
    5e-324,
    -5e-324,
    1e308,
    -1e308,
    f64::MAX,
    f64::MIN,
    1.0,
    -1.0,
    2.0,
    0.5,
    1.618_033_988_749_895,
    -1.618_033_988_749_895,
    1e8,
    1e8 + 1.0,
    1e8 - 1.0,
    1e-300,
    3.0,
    f64::EPSILON,
];

struct Bytes<'a>(&'a [u8]);

impl Bytes<'_> {
    fn byte(&mut self) -> Option<u8> {
        let (&b, rest) = self.0.split_first()?;
        self.0 = rest;
        Some(b)
    }

    fn number(&mut self) -> Option<f64> {
        let tag = self.byte()?;
        let index = usize::from(tag);
        if index < SPECIAL.len() * 8 {
            return Some(SPECIAL[index % SPECIAL.len()]);
        }
        let (raw, rest) = self.0.split_first_chunk::<8>()?;
        self.0 = rest;
        Some(f64::from_le_bytes(*raw))
    }

    fn vec3(&mut self) -> Option<DVec3> {
        Some(DVec3::new(self.number()?, self.number()?, self.number()?))
    }
}

fn check_point(solid: &Fixed, p: DVec3) {
    let accel = &solid.accel;
    let parity = accel.classify(p);
    let winding = accel.classify_with(p, Method::Winding);
    let normals = accel.classify_with(p, Method::Normals);
    let number = accel.winding_number(p);
    if !p.is_finite() {
        let refused = QueryError::NonFinitePoint { index: 0, point: p };
        // NaN != NaN: compare the variant and the index.
        for e in [&parity, &winding, &normals] {
            assert!(
                matches!(e, Err(QueryError::NonFinitePoint { index: 0, .. })),
                "{}: {p} gave {e:?}, want {refused:?}",
                solid.name
            );
        }
        assert!(number.is_err(), "{}: {p}", solid.name);
        return;
    }
    let parity = parity.expect("a closed solid classifies every finite point");
    let winding = winding.expect("winding classifies every finite point");
    assert_eq!(
        parity, winding,
        "{}: parity vs winding at {p:?}",
        solid.name
    );
    // The solid-angle sum is a rounded construction: within rounding
    // distance of the surface it may be anything, but never NaN.
    let number = number.expect("a finite point has a winding number");
    assert!(
        number.is_finite(),
        "{}: winding number {number} at {p:?}",
        solid.name
    );
    match normals {
        Ok(c) => {
            assert!(
                solid.convex,
                "{}: normals answered on a non-convex solid",
                solid.name
            );
            assert_eq!(c, parity, "{}: normals vs parity at {p:?}", solid.name);
        }
        Err(QueryError::NotConvex(_)) => assert!(!solid.convex, "{}", solid.name),
        Err(e) => panic!("{}: normals at {p:?}: {e}", solid.name),
    }
}

fn check_ray(solid: &Fixed, ray: &Ray) {
    let accel = &solid.accel;
    let crossings = accel.ray_crossings(ray);
    let first = accel.first_hit(ray);
    if !ray.is_valid() {
        assert!(
            matches!(crossings, Err(QueryError::InvalidRay { index: 0, .. })),
            "{}: {ray:?} gave {crossings:?}",
            solid.name
        );
        assert!(
            matches!(first, Err(QueryError::InvalidRay { index: 0, .. })),
            "{}: {ray:?} gave {first:?}",
            solid.name
        );
        return;
    }
    // A crossing whose t overflows or underflows is refused by name; the
    // first hit is refused only when its own t is.
    let crossings = match crossings {
        Err(QueryError::RayOutOfRange { index: 0, .. }) => {
            assert!(
                matches!(
                    first,
                    Ok(_) | Err(QueryError::RayOutOfRange { index: 0, .. })
                ),
                "{}: {ray:?} gave {first:?}",
                solid.name
            );
            return;
        }
        other => other.expect("a valid ray on a closed solid"),
    };
    let first = first.expect("a valid ray whose crossings are in range");
    let at = accel.classify(ray.origin).expect("a finite origin");
    assert_eq!(
        crossings.origin, at,
        "{}: origin class of {ray:?}",
        solid.name
    );
    let mut inside = match crossings.origin {
        Containment::Inside => true,
        Containment::Outside => false,
        Containment::OnBoundary => crossings
            .hits
            .first()
            .is_some_and(|h| h.transition == Transition::Exit),
    };
    let mut previous = 0.0;
    for hit in &crossings.hits {
        assert!(hit.t > 0.0, "{}: t {} on {ray:?}", solid.name, hit.t);
        assert!(hit.t >= previous, "{}: unsorted on {ray:?}", solid.name);
        previous = hit.t;
        let want = if inside {
            Transition::Exit
        } else {
            Transition::Enter
        };
        assert_eq!(
            hit.transition, want,
            "{}: {ray:?}: {crossings:?}",
            solid.name
        );
        inside = !inside;
    }
    assert!(
        !inside,
        "{}: {ray:?} ends inside: {crossings:?}",
        solid.name
    );
    match (first, crossings.hits.first()) {
        (None, None) => {}
        (Some(a), Some(_)) => {
            // Crossings whose rounded `t` tie or are inverted (a ray
            // through a vertex, or starting beside one) are listed in the
            // perturbed ray's order, keeping the `t` slots ascending; the
            // first hit is chosen by rounded `t`, ties by triangle order
            // (fuzzing findings): it is one of the crossings, not
            // necessarily the first one listed.
            assert!(
                crossings
                    .hits
                    .iter()
                    .any(|h| h.face == a.face && h.transition == a.transition),
                "{}: first hit {a:?} is no crossing of {ray:?}",
                solid.name
            );
        }
        (a, b) => panic!(
            "{}: first hit {a:?} vs first crossing {b:?} on {ray:?}",
            solid.name
        ),
    }
}

fn check_batches(solid: &Fixed, points: &[DVec3], rays: &[Ray]) {
    let accel = &solid.accel;
    let bad_point = points.iter().position(|p| !p.is_finite());
    for method in [Method::Parity, Method::Normals, Method::Winding] {
        let batch = accel.classify_batch(points, method);
        match (bad_point, batch) {
            (Some(i), Err(QueryError::NonFinitePoint { index, .. })) => assert_eq!(i, index),
            (Some(i), other) => panic!("{}: point {i} is not finite: {other:?}", solid.name),
            (None, Ok(classes)) => {
                let singles: Vec<_> = points
                    .iter()
                    .map(|&p| accel.classify_with(p, method).expect("as the batch"))
                    .collect();
                assert_eq!(classes, singles, "{}: {method:?} batch", solid.name);
            }
            (None, Err(QueryError::NotConvex(_))) => assert!(!solid.convex),
            (None, Err(e)) => panic!("{}: {method:?} batch: {e}", solid.name),
        }
    }
    let numbers = accel.winding_number_batch(points);
    assert_eq!(numbers.is_err(), bad_point.is_some(), "{}", solid.name);
    let bad_ray = rays.iter().position(|r| !r.is_valid());
    let firsts = accel.first_hit_batch(rays);
    let all = accel.ray_crossings_batch(rays);
    match bad_ray {
        Some(i) => {
            for e in [firsts.err(), all.err()] {
                assert!(
                    matches!(e, Some(QueryError::InvalidRay { index, .. }) if index == i),
                    "{}: ray {i} is invalid: {e:?}",
                    solid.name
                );
            }
        }
        None => {
            // Out of range: refused as the single queries refuse it.
            let (firsts, all) = match (firsts, all) {
                (Ok(f), Ok(a)) => (f, a),
                (firsts, all) => {
                    for e in [firsts.err(), all.err()].into_iter().flatten() {
                        let QueryError::RayOutOfRange { index, .. } = e else {
                            panic!("{}: valid rays refused: {e}", solid.name)
                        };
                        assert!(accel.ray_crossings(&rays[index]).is_err());
                    }
                    return;
                }
            };
            for ((ray, first), crossings) in rays.iter().zip(firsts).zip(all) {
                assert_eq!(
                    first,
                    accel.first_hit(ray).expect("valid"),
                    "{}",
                    solid.name
                );
                assert_eq!(crossings, accel.ray_crossings(ray).expect("valid"));
            }
        }
    }
}

fn check_tree(tree: &Csg, exact: bool, p: DVec3, ray: &Ray) {
    let mut stats = Stats::default();
    let class = tree.try_classify_point(p, &mut stats);
    assert_eq!(class.is_err(), !p.is_finite(), "{p:?}: {class:?}");
    let spans = tree.try_spans(ray, &mut stats);
    let first = tree.try_first_hit(ray, &mut stats);
    if !ray.is_valid() {
        assert!(
            matches!(spans, Err(QueryError::InvalidRay { .. })),
            "{ray:?}"
        );
        assert!(
            matches!(first, Err(QueryError::InvalidRay { .. })),
            "{ray:?}"
        );
        let plain = tree.spans(ray, &mut stats);
        assert!(plain.hits.is_empty() && !plain.origin_inside);
        return;
    }
    let (spans, first) = (spans.expect("a valid ray"), first.expect("a valid ray"));
    let mut previous = 0.0;
    for hit in &spans.hits {
        assert!(
            hit.t > previous,
            "spans not strictly ascending: {spans:?} on {ray:?}"
        );
        previous = hit.t;
    }
    match (&first, spans.hits.first()) {
        (None, None) => {}
        (Some(a), Some(b)) => {
            assert_eq!(a.t, b.t, "first hit on {ray:?}");
            assert_eq!(a.entering, !spans.origin_inside, "{ray:?}");
        }
        (a, b) => panic!("first hit {a:?} vs first span boundary {b:?} on {ray:?}"),
    }
    if let Some(hit) = first {
        let _ = tree.hit_normal(ray, &hit, &mut stats);
    }
    let _ = (spans.intervals(), spans.total_length());
    if let (true, Ok(class)) = (exact, class) {
        let from_p = tree.spans(&Ray::new(p, ray.direction), &mut stats);
        match class {
            Containment::Inside => assert!(from_p.origin_inside, "{p:?} inside, ray {ray:?}"),
            Containment::Outside => assert!(!from_p.origin_inside, "{p:?} outside, ray {ray:?}"),
            Containment::OnBoundary => {}
        }
    }
}

/// Checks one input.
pub fn run(data: &[u8]) {
    let mut bytes = Bytes(data);
    let mut points = Vec::new();
    let mut rays = Vec::new();
    while points.len() < 8 {
        let Some(p) = bytes.vec3() else { break };
        points.push(p);
        let Some(d) = bytes.vec3() else { break };
        rays.push(Ray::new(p, d));
    }
    for solid in SOLIDS.iter() {
        for &p in &points {
            check_point(solid, p);
        }
        for ray in &rays {
            check_ray(solid, ray);
        }
        check_batches(solid, &points, &rays);
    }
    for (ray, &p) in rays.iter().zip(&points) {
        check_tree(&EXACT_TREE, true, p, ray);
        check_tree(&ROUND_TREE, false, p, ray);
    }
}
