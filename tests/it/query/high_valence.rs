//! Valid inputs whose faces meet at one vertex of high valence — closed
//! cones, UV spheres with many segments — and a fan of faces on one edge:
//! the work per triangle stays bounded (grid entries, pairs tested), and
//! the answers are those of the exact methods that do not use the grid.

use glam::DVec3;
use wingedge::mesh::builders::{ConeBase, cone_soup, edge_fan_soup, sphere_soup, uv_sphere_soup};
use wingedge::mesh::{PolygonSoup, Solid};
use wingedge::query::{Accel, Containment, Method};
use wingedge::validate::{Options, Rule, validate_soup};

use crate::common::test_rng;

/// The soup with its coordinates cycled `k` times (`(x, y, z) → (z, x, y)`),
/// so that the apex's axis runs along `z`, `x` or `y`.
fn turned(soup: &PolygonSoup, k: usize) -> PolygonSoup {
    let mut turned = soup.clone();
    for p in &mut turned.positions {
        for _ in 0..k {
            *p = DVec3::new(p.z, p.x, p.y);
        }
    }
    turned
}

/// Grid entries per triangle after one point query, in units of the
/// grid's side (the square root of its cell count): a sliver that crosses
/// the whole grid meets about one side's worth of cells.
fn grid_entries_per_triangle(accel: &Accel) -> f64 {
    accel.classify(DVec3::new(0.1, 0.2, 0.3)).unwrap();
    let stats = accel.stats();
    stats.grid_entries as f64 / stats.triangles as f64 / (stats.grid_cells as f64).sqrt()
}

#[test]
fn a_cone_lists_each_triangle_in_few_grid_cells() {
    // 4,000 triangles: a 63 × 63 grid. A cone's slivers cross the grid
    // from the apex to the rim; listed in every cell of their boxes they
    // took hundreds of entries each (about 20 sides' worth), listed in the
    // cells they meet about one side's worth.
    for base in [ConeBase::CentreFan, ConeBase::CornerFan] {
        for axis in 0..3 {
            let soup = turned(&cone_soup(2000, base), axis);
            let accel = Accel::new(&Solid::try_from_soup(&soup).unwrap());
            let per_triangle = grid_entries_per_triangle(&accel);
            assert!(per_triangle < 2.0, "{base:?} axis {axis}: {per_triangle}");
        }
    }
    // A sphere's triangles are small: one or two cells each.
    let sphere = Accel::new(&Solid::try_from_soup(&sphere_soup(32)).unwrap());
    let per_triangle = grid_entries_per_triangle(&sphere);
    assert!(per_triangle < 0.2, "{per_triangle}");
}

#[test]
fn a_cone_grid_holds_a_bounded_number_of_entries_per_triangle() {
    // 40,000 triangles: at one cell per triangle (a 283-cell side) each
    // sliver would take a side's worth of entries, over a hundred. The
    // grid's sides are halved until the expected entries are at most 32 per
    // triangle; a UV sphere keeps its cells (its poles' slivers take a few
    // entries more than its other triangles).
    for base in [ConeBase::CentreFan, ConeBase::CornerFan] {
        for axis in 0..3 {
            let soup = turned(&cone_soup(20_000, base), axis);
            let accel = Accel::new(&Solid::try_from_soup(&soup).unwrap());
            accel.classify(DVec3::new(0.1, 0.2, 0.3)).unwrap();
            let stats = accel.stats();
            let per_triangle = stats.grid_entries as f64 / stats.triangles as f64;
            assert!(per_triangle <= 40.0, "{base:?} axis {axis}: {per_triangle}");
            assert!(
                stats.grid_cells * 16 < stats.triangles,
                "{base:?} axis {axis}"
            );
        }
    }
    // A sphere of 39,600 triangles is small enough for 4 cells per
    // triangle: each small triangle then lies in a few of them, well
    // within the grid's budget of 32 entries per triangle.
    let sphere = Accel::new(&Solid::try_from_soup(&sphere_soup(100)).unwrap());
    sphere.classify(DVec3::new(0.1, 0.2, 0.3)).unwrap();
    let stats = sphere.stats();
    assert!(stats.grid_cells > 2 * stats.triangles, "{stats:?}");
    assert!(stats.grid_entries < 20 * stats.triangles, "{stats:?}");
}

#[test]
fn a_cone_classifies_as_the_normals_method_does() {
    // The cone is convex, so the normals method (no grid) is a reference:
    // random points, points on the rim, on the base and on the axis.
    let mut unit = test_rng::uniform(7);
    let mut random = |lo: f64, hi: f64| lo + (hi - lo) * unit();
    for base in [ConeBase::CentreFan, ConeBase::CornerFan] {
        for axis in 0..3 {
            let soup = turned(&cone_soup(500, base), axis);
            let accel = Accel::new(&Solid::try_from_soup(&soup).unwrap());
            let mut points: Vec<DVec3> = (0..3000)
                .map(|_| DVec3::new(random(-1.2, 1.2), random(-1.2, 1.2), random(-0.2, 1.2)))
                .collect();
            points.extend(soup.positions.iter().step_by(7));
            points.extend((0..50).map(|k| DVec3::new(0.0, 0.0, k as f64 / 49.0)));
            points.extend((0..50).map(|k| DVec3::new(k as f64 / 100.0, 0.0, 0.0)));
            let points: Vec<DVec3> = points.iter().map(|&p| turned_point(p, axis)).collect();
            let mut boundary = 0;
            for &p in &points {
                let parity = accel.classify(p).unwrap();
                let normals = accel.classify_with(p, Method::Normals).unwrap();
                assert_eq!(parity, normals, "{base:?} axis {axis} at {p}");
                boundary += usize::from(parity == Containment::OnBoundary);
            }
            assert!(boundary > 40, "{boundary}");
            let batch = accel.classify_batch(&points, Method::Parity).unwrap();
            let one_by_one: Vec<Containment> =
                points.iter().map(|&p| accel.classify(p).unwrap()).collect();
            assert_eq!(batch, one_by_one);
        }
    }
}

fn turned_point(mut p: DVec3, k: usize) -> DVec3 {
    for _ in 0..k {
        p = DVec3::new(p.z, p.x, p.y);
    }
    p
}

#[test]
fn cones_poles_and_edge_fans_validate() {
    for base in [ConeBase::CentreFan, ConeBase::CornerFan] {
        let report = validate_soup(&cone_soup(3000, base), None, &Options::default()).unwrap();
        assert!(report.is_valid(), "{base:?}");
    }
    // Poles of valence 600.
    let report = validate_soup(&sphere_soup(300), None, &Options::default()).unwrap();
    assert!(report.is_valid());
    // Poles of valence 3,000 on a sphere of 5 rings: bands of long slivers.
    let poles = uv_sphere_soup(5, 3000);
    assert_eq!(poles.polygons.len(), 24_000);
    let report = validate_soup(&poles, None, &Options::default()).unwrap();
    assert!(report.is_valid());
    let accel = Accel::new(&Solid::try_from_soup(&poles).unwrap());
    // Not exactly convex (rounded sines): answers known from the geometry.
    for (p, want) in [
        (DVec3::ZERO, Containment::Inside),
        (DVec3::new(0.3, 0.2, 0.8), Containment::Inside),
        (DVec3::new(0.0, 0.0, 1.0), Containment::OnBoundary),
        (DVec3::new(0.0, 0.0, -1.0), Containment::OnBoundary),
        (DVec3::new(0.0, 0.0, 1.2), Containment::Outside),
        (DVec3::new(0.5, 0.5, 0.9), Containment::Outside),
    ] {
        assert_eq!(accel.classify(p).unwrap(), want, "{p}");
    }
    // 3,000 faces on one edge: reported as such, and no two of them cross.
    let report = validate_soup(&edge_fan_soup(3000), None, &Options::default()).unwrap();
    assert_eq!(report.count(Rule::EdgeInMoreThanTwoFaces), 1);
    assert_eq!(report.count(Rule::SelfIntersection), 0);
}

#[test]
fn an_apex_face_folded_through_another_is_reported() {
    // Rim vertex 10 of 400 pulled out past the rim a third of a turn
    // away: the apex faces at it cross apex faces they share only the apex
    // with.
    let mut soup = cone_soup(400, ConeBase::CentreFan);
    let angle = std::f64::consts::TAU / 3.0;
    soup.positions[2 + 10] = DVec3::new(1.5 * angle.cos(), 1.5 * angle.sin(), 0.1);
    let report = validate_soup(&soup, None, &Options::default()).unwrap();
    let apex_pairs = report
        .of(Rule::SelfIntersection)
        .filter(|v| v.faces.iter().all(|&f| f < 400) && v.faces.contains(&10))
        .count();
    assert!(apex_pairs > 0);
}
