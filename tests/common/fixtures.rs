//! Closed solids with hard features for the query tests, generated in
//! code: a hollow box, a sliver, a nearly flat pyramid, a nearly coplanar
//! pair of faces, and the list of every valid closed fixture.

use glam::DVec3;
use wingedge::mesh::{PolygonSoup, Solid, builders};

/// Builds a solid from a soup (fixtures are valid by construction).
pub fn build(soup: &PolygonSoup) -> Solid {
    Solid::try_from_soup(soup).expect("valid fixture")
}

/// A box `[-2, 2]³` with a box-shaped cavity `[-1, 1]³` (two shells; the
/// inner one faces inward).
pub fn hollow_box() -> Solid {
    let outer = builders::cuboid(DVec3::splat(-2.0), DVec3::splat(2.0))
        .expect("box")
        .to_soup();
    let inner = builders::cube().to_soup();
    let mut positions = outer.positions.clone();
    let base = positions.len();
    positions.extend(&inner.positions);
    let mut polygons: Vec<Vec<usize>> =
        outer.polygons.iter().map(|p| p.vertices.to_vec()).collect();
    for p in &inner.polygons {
        polygons.push(p.vertices.iter().rev().map(|&i| i + base).collect());
    }
    build(&PolygonSoup::new(positions, polygons))
}

/// A tetrahedron with one sliver face: its base is a triangle whose third
/// corner is `1e-9` off the line of the other two.
pub fn sliver_tetrahedron() -> Solid {
    let positions = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.5, 1e-9, 0.0),
        DVec3::new(0.5, 0.25, 1.0),
    ];
    // Base seen from below (normal −z): 0, 2, 1.
    build(&PolygonSoup::new(
        positions,
        [vec![0, 2, 1], vec![0, 1, 3], vec![1, 2, 3], vec![2, 0, 3]],
    ))
}

/// A square pyramid so flat that its four side faces are nearly coplanar
/// with each other (apex `1e-12` above the base centre... lifted to keep it
/// valid): dihedral angles within about `1e-12` of flat.
pub fn nearly_flat_pyramid() -> Solid {
    let base = [
        DVec3::new(-1.0, -1.0, 0.0),
        DVec3::new(1.0, -1.0, 0.0),
        DVec3::new(1.0, 1.0, 0.0),
        DVec3::new(-1.0, 1.0, 0.0),
    ];
    builders::pyramid(&base, DVec3::new(0.0, 0.0, 1e-12)).expect("flat pyramid")
}

/// A triangular prism whose top is tilted by a tiny amount, so that two
/// adjacent quads are nearly coplanar.
pub fn nearly_coplanar_pair() -> Solid {
    // A box whose top face is split along a ridge raised by 2^-40.
    let h = 2f64.powi(-40);
    let positions = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(2.0, 0.0, 0.0),
        DVec3::new(2.0, 1.0, 0.0),
        DVec3::new(0.0, 1.0, 0.0),
        DVec3::new(0.0, 0.0, 1.0),
        DVec3::new(2.0, 0.0, 1.0),
        DVec3::new(2.0, 1.0, 1.0),
        DVec3::new(0.0, 1.0, 1.0),
        DVec3::new(1.0, 0.0, 1.0 + h),
        DVec3::new(1.0, 1.0, 1.0 + h),
    ];
    let polygons = vec![
        vec![0, 3, 2, 1],
        vec![0, 1, 5, 8, 4],
        vec![1, 2, 6, 5],
        vec![2, 3, 7, 9, 6],
        vec![3, 0, 4, 7],
        vec![4, 8, 9, 7],
        vec![8, 5, 6, 9],
    ];
    build(&PolygonSoup::new(positions, polygons))
}

/// Every valid closed fixture with a name.
pub fn closed_fixtures() -> Vec<(&'static str, Solid)> {
    vec![
        ("tetrahedron", builders::tetrahedron()),
        ("cube", builders::cube()),
        ("octahedron", builders::octahedron()),
        ("dodecahedron", builders::dodecahedron()),
        ("icosahedron", builders::icosahedron()),
        ("l_prism", builders::l_prism()),
        ("hollow_box", hollow_box()),
        ("sliver_tetrahedron", sliver_tetrahedron()),
        ("nearly_flat_pyramid", nearly_flat_pyramid()),
        ("nearly_coplanar_pair", nearly_coplanar_pair()),
    ]
}
