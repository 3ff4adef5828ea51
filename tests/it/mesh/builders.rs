//! Every builder yields a consistent, closed, outward solid with the known
//! counts and measures.

use glam::DVec3;
use wingedge::mesh::{BuildError, Solid, builders};

const PHI: f64 = 1.618_033_988_749_895;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-12 * b.abs().max(1.0)
}

struct Expect {
    v: usize,
    e: usize,
    f: usize,
    volume: f64,
    area: f64,
}

fn check(name: &str, solid: &Solid, want: Expect) {
    solid
        .check_consistency()
        .unwrap_or_else(|e| panic!("{name}: {e}"));
    assert_eq!(
        (solid.vertex_count(), solid.edge_count(), solid.face_count()),
        (want.v, want.e, want.f),
        "{name} counts"
    );
    assert_eq!(solid.euler_characteristic(), 2, "{name}");
    assert!(solid.is_closed(), "{name}");
    let shells = solid.shells();
    assert_eq!(shells.len(), 1, "{name}");
    assert_eq!(shells[0].genus(), Some(0), "{name}");
    assert!(
        close(solid.volume(), want.volume),
        "{name} volume {} vs {}",
        solid.volume(),
        want.volume
    );
    assert!(
        close(solid.surface_area(), want.area),
        "{name} area {} vs {}",
        solid.surface_area(),
        want.area
    );
    // Outward: every face's plane has the centroid on its inner side.
    let c = solid.centroid().expect("non-zero volume");
    for (id, face) in solid.faces() {
        let plane = face.plane.expect("builder faces have area");
        assert!(
            plane.signed_distance(c) < 0.0,
            "{name}: face {id:?} faces inward"
        );
        assert_eq!(solid.face_side(id, c), wingedge::geom::Sign::Negative);
    }
}

#[test]
fn platonic_solids_have_their_closed_form_measures() {
    let s3 = 3f64.sqrt();
    let s5 = 5f64.sqrt();
    let a = 2.0 * 2f64.sqrt();
    check(
        "tetrahedron",
        &builders::tetrahedron(),
        Expect {
            v: 4,
            e: 6,
            f: 4,
            volume: a.powi(3) / (6.0 * 2f64.sqrt()),
            area: s3 * a * a,
        },
    );
    check(
        "cube",
        &builders::cube(),
        Expect {
            v: 8,
            e: 12,
            f: 6,
            volume: 8.0,
            area: 24.0,
        },
    );
    let a = 2f64.sqrt();
    check(
        "octahedron",
        &builders::octahedron(),
        Expect {
            v: 6,
            e: 12,
            f: 8,
            volume: 2f64.sqrt() / 3.0 * a.powi(3),
            area: 2.0 * s3 * a * a,
        },
    );
    let a = 2.0 / PHI;
    check(
        "dodecahedron",
        &builders::dodecahedron(),
        Expect {
            v: 20,
            e: 30,
            f: 12,
            volume: (15.0 + 7.0 * s5) / 4.0 * a.powi(3),
            area: 3.0 * (25.0 + 10.0 * s5).sqrt() * a * a,
        },
    );
    let a: f64 = 2.0;
    check(
        "icosahedron",
        &builders::icosahedron(),
        Expect {
            v: 12,
            e: 30,
            f: 20,
            volume: 5.0 / 12.0 * (3.0 + s5) * a.powi(3),
            area: 5.0 * s3 * a * a,
        },
    );
}

#[test]
fn dodecahedron_faces_are_pentagons() {
    let solid = builders::dodecahedron();
    for (id, _) in solid.faces() {
        assert_eq!(solid.face_degree(id), 5);
    }
    for (id, _) in solid.vertices() {
        assert_eq!(solid.vertex_degree(id), 3);
    }
}

#[test]
fn box_prism_and_pyramid() {
    let b = builders::cuboid(DVec3::new(-1., 2., 3.), DVec3::new(4., 3., 6.)).unwrap();
    check(
        "box",
        &b,
        Expect {
            v: 8,
            e: 12,
            f: 6,
            volume: 15.0,
            area: 2.0 * (5.0 + 15.0 + 3.0),
        },
    );
    check(
        "L prism",
        &builders::l_prism(),
        Expect {
            v: 12,
            e: 18,
            f: 8,
            volume: 3.0,
            area: 14.0,
        },
    );

    // A non-convex profile wound clockwise, swept along a slanted vector:
    // volume = area × (sweep · unit normal).
    let star: Vec<DVec3> = (0..10)
        .map(|i| {
            let angle = -(i as f64) * std::f64::consts::TAU / 10.0;
            let r = if i % 2 == 0 { 2.0 } else { 0.8 };
            DVec3::new(r * angle.cos(), r * angle.sin(), 1.0)
        })
        .collect();
    let sweep = DVec3::new(0.5, -0.25, 3.0);
    let prism = builders::prism(&star, sweep).unwrap();
    let area = 10.0 * 0.5 * 2.0 * 0.8 * (std::f64::consts::TAU / 10.0).sin();
    let lateral = prism.surface_area() - 2.0 * area;
    check(
        "star prism",
        &prism,
        Expect {
            v: 20,
            e: 30,
            f: 12,
            volume: area * 3.0,
            area: 2.0 * area + lateral,
        },
    );

    let square = [
        DVec3::new(0., 0., 0.),
        DVec3::new(2., 0., 0.),
        DVec3::new(2., 2., 0.),
        DVec3::new(0., 2., 0.),
    ];
    for apex in [DVec3::new(1., 1., 3.), DVec3::new(7., -2., -3.)] {
        let p = builders::pyramid(&square, apex).unwrap();
        let slant: f64 = p.surface_area() - 4.0;
        check(
            "pyramid",
            &p,
            Expect {
                v: 5,
                e: 8,
                f: 5,
                volume: 4.0,
                area: 4.0 + slant,
            },
        );
    }
}

#[test]
fn bad_builder_input_gives_errors_not_panics() {
    let p = |x: f64, y: f64| DVec3::new(x, y, 0.0);
    let up = DVec3::Z;
    assert!(matches!(
        builders::prism(&[p(0., 0.), p(1., 0.)], up),
        Err(BuildError::TooFewVertices { count: 2, .. })
    ));
    assert!(matches!(
        builders::prism(&[], up),
        Err(BuildError::TooFewVertices { count: 0, .. })
    ));
    assert!(matches!(
        builders::prism(&[p(0., 0.), p(1., 0.), p(0., 0.), p(0., 1.)], up),
        Err(BuildError::RepeatedVertex { .. })
    ));
    assert!(matches!(
        builders::prism(&[p(0., 0.), p(1., 1.), p(2., 2.)], up),
        Err(BuildError::ZeroArea)
    ));
    assert!(matches!(
        builders::prism(&[p(0., 0.), p(f64::NAN, 0.), p(0., 1.)], up),
        Err(BuildError::NonFinitePosition { vertex: 1, .. })
    ));
    assert!(matches!(
        builders::prism(
            &[p(0., 0.), p(1., 0.), p(0., 1.)],
            DVec3::new(f64::INFINITY, 0., 0.)
        ),
        Err(BuildError::NonFinitePosition { .. })
    ));
    assert!(matches!(
        builders::prism(&[p(0., 0.), p(1., 0.), p(0., 1.)], DVec3::X),
        Err(BuildError::Flat)
    ));
    assert!(matches!(
        builders::prism(&[p(0., 0.), p(2., 2.), p(2., 0.), p(0., 1.)], up),
        Err(BuildError::SelfIntersecting(..))
    ));
    assert!(matches!(
        builders::pyramid(&[p(0., 0.), p(1., 0.), p(0., 1.)], p(5., 5.)),
        Err(BuildError::Flat)
    ));
    assert!(matches!(
        builders::pyramid(&[p(0., 0.), p(1., 0.)], up),
        Err(BuildError::TooFewVertices { .. })
    ));
    assert!(matches!(
        builders::cuboid(DVec3::ONE, DVec3::ZERO),
        Err(BuildError::Flat)
    ));
    assert!(matches!(
        builders::cuboid(DVec3::ZERO, DVec3::new(1., f64::NAN, 1.)),
        Err(BuildError::NonFinitePosition { .. })
    ));
}

#[test]
fn builders_by_name() {
    for name in builders::NAMES {
        let solid = builders::by_name(name).unwrap();
        solid.check_consistency().unwrap();
        assert!(solid.volume() > 0.0);
    }
    assert!(builders::by_name("klein bottle").is_none());
}

#[test]
fn uv_sphere_is_closed_and_converges_to_the_ball() {
    for rings in [2, 3, 16, 64] {
        let sphere = builders::sphere(rings);
        sphere.check_consistency().unwrap();
        assert_eq!(sphere.face_count(), 4 * rings * (rings - 1));
        assert_eq!(sphere.euler_characteristic(), 2);
        assert!(sphere.is_closed());
        assert!(sphere.volume() > 0.0 && sphere.volume() < 4.0 / 3.0 * std::f64::consts::PI);
    }
    let fine = builders::sphere(256).volume();
    assert!(
        (fine - 4.0 / 3.0 * std::f64::consts::PI).abs() < 1e-3,
        "{fine}"
    );
    assert_eq!(
        builders::sphere_soup(0).polygons.len(),
        8,
        "fewer than 2 rings means 2"
    );
}
