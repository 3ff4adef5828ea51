//! Builders for the classic solids: the five Platonic solids, a box, prisms
//! swept from any simple polygon (with holes: through holes), and pyramids.
//!
//! Every builder makes its solid with Euler operators ([`super::euler`]):
//! prisms are a lamina extruded ([`Solid::extrude_face`]), pyramids a lamina
//! coned to the apex ([`Solid::cone_face`]), the Platonic solids a spanning
//! tree of `mev`s closed by `mef`s. Every builder returns an
//! outward-oriented closed solid that passes [`Solid::check_consistency`].

use glam::DVec3;

use crate::geom::polygon::{Projection, find_self_intersection};
use crate::geom::{Plane, Sign, orient3d, triangulate_3d};

use super::{BuildError, PolygonSoup, Solid};

/// The golden ratio `φ = (1 + √5) / 2`.
const PHI: f64 = 1.618_033_988_749_895;

/// The names accepted by [`by_name`], in a stable order.
pub const NAMES: [&str; 7] = [
    "tetrahedron",
    "cube",
    "octahedron",
    "dodecahedron",
    "icosahedron",
    "prism",
    "frame",
];

/// A built-in solid by name: the Platonic solids (`tetrahedron`, `cube`,
/// `octahedron`, `dodecahedron`, `icosahedron`), `prism`, an L-shaped
/// (non-convex) prism, and `frame`, a square frame with a square hole
/// through it (genus 1, faces with rings). `None` for an unknown name.
#[must_use]
pub fn by_name(name: &str) -> Option<Solid> {
    Some(match name {
        "tetrahedron" => tetrahedron(),
        "cube" | "hexahedron" => cube(),
        "octahedron" => octahedron(),
        "dodecahedron" => dodecahedron(),
        "icosahedron" => icosahedron(),
        "prism" => l_prism(),
        "frame" => frame(),
        _ => return None,
    })
}

/// The regular tetrahedron with vertices `(1,1,1)`, `(1,−1,−1)`, `(−1,1,−1)`,
/// `(−1,−1,1)`: edge `2√2`, volume `8/3`.
#[must_use]
pub fn tetrahedron() -> Solid {
    let vertices = [
        DVec3::new(1., 1., 1.),
        DVec3::new(1., -1., -1.),
        DVec3::new(-1., 1., -1.),
        DVec3::new(-1., -1., 1.),
    ];
    // Each face is opposite a vertex: its normal is minus that vertex.
    let normals: Vec<DVec3> = vertices.iter().map(|&v| -v).collect();
    regular(&vertices, &normals, 3)
}

/// The cube `[−1, 1]³`: edge 2, volume 8.
#[must_use]
pub fn cube() -> Solid {
    cuboid(DVec3::splat(-1.0), DVec3::splat(1.0)).expect("the unit cube is a valid box")
}

/// The regular octahedron with vertices `(±1, 0, 0)`, `(0, ±1, 0)`,
/// `(0, 0, ±1)`: edge `√2`, volume `4/3`.
#[must_use]
pub fn octahedron() -> Solid {
    let vertices = [
        DVec3::X,
        -DVec3::X,
        DVec3::Y,
        -DVec3::Y,
        DVec3::Z,
        -DVec3::Z,
    ];
    regular(&vertices, &cube_corners(), 3)
}

/// The regular icosahedron with vertices `(0, ±φ, ±1)` and their cyclic
/// permutations: edge 2, volume `(5/12)(3 + √5)·8`.
#[must_use]
pub fn icosahedron() -> Solid {
    regular(&icosahedron_vertices(), &dodecahedron_vertices(), 3)
}

/// The regular dodecahedron with vertices `(±1, ±1, ±1)`, `(0, ±1/φ, ±φ)` and
/// cyclic permutations: edge `2/φ`, volume `((15 + 7√5)/4)(2/φ)³`.
#[must_use]
pub fn dodecahedron() -> Solid {
    regular(&dodecahedron_vertices(), &icosahedron_vertices(), 5)
}

/// The axis-aligned box `[min, max]`, six quadrilateral faces.
///
/// # Errors
///
/// [`BuildError::NonFinitePosition`] for non-finite corners,
/// [`BuildError::Flat`] unless `min < max` in every coordinate.
pub fn cuboid(min: DVec3, max: DVec3) -> Result<Solid, BuildError> {
    if !min.is_finite() || !max.is_finite() {
        let position = if min.is_finite() { max } else { min };
        return Err(BuildError::NonFinitePosition {
            vertex: 0,
            position,
        });
    }
    if !min.cmplt(max).all() {
        return Err(BuildError::Flat);
    }
    let bottom = [
        DVec3::new(min.x, min.y, min.z),
        DVec3::new(max.x, min.y, min.z),
        DVec3::new(max.x, max.y, min.z),
        DVec3::new(min.x, max.y, min.z),
    ];
    prism(&bottom, DVec3::new(0.0, 0.0, max.z - min.z))
}

/// The prism swept from a simple polygon along `sweep`: the polygon, a copy
/// moved by `sweep`, and one quadrilateral per polygon edge. The polygon may
/// be convex or not and wound either way; the solid is oriented outward.
///
/// # Errors
///
/// [`BuildError::TooFewVertices`], [`BuildError::RepeatedVertex`],
/// [`BuildError::NonFinitePosition`] (also for a non-finite sweep),
/// [`BuildError::ZeroArea`], [`BuildError::SelfIntersecting`], and
/// [`BuildError::Flat`] when `sweep` lies in the polygon's plane (decided
/// exactly).
pub fn prism(profile: &[DVec3], sweep: DVec3) -> Result<Solid, BuildError> {
    prism_with_holes(profile, &[], sweep)
}

/// The prism swept from a polygon with holes along `sweep`: a solid with one
/// through hole per hole of the profile (genus = number of holes). Built as
/// a lamina ([`Solid::try_lamina`]), a ring per hole ([`Solid::add_ring`])
/// turned into a ring of the opposite face ([`Solid::kfmrh`]), and the
/// extrusion of the face with the rings ([`Solid::extrude_face`]). Polygons
/// may be wound either way; the solid is oriented outward.
///
/// # Errors
///
/// Those of [`prism`] for the outer polygon, and
/// [`BuildError::InvalidProfile`] when a hole is not simple, not strictly
/// inside the outer polygon or touches another hole (decided exactly in the
/// projection onto the axis plane closest to the profile; holes are assumed
/// to lie in the outer polygon's plane).
pub fn prism_with_holes(
    profile: &[DVec3],
    holes: &[&[DVec3]],
    sweep: DVec3,
) -> Result<Solid, BuildError> {
    let base = checked_profile(profile)?;
    if !sweep.is_finite() {
        return Err(BuildError::NonFinitePosition {
            vertex: profile.len(),
            position: sweep,
        });
    }
    triangulate_3d(profile, holes)?;
    let side = orient3d(
        base.pivot[0],
        base.pivot[1],
        base.pivot[2],
        base.pivot[0] + sweep,
    );
    let ring: Vec<DVec3> = match side {
        Sign::Zero => return Err(BuildError::Flat),
        Sign::Positive => profile.to_vec(),
        Sign::Negative => profile.iter().rev().copied().collect(),
    };
    // `ring` now runs counter-clockwise seen from the sweep direction: the
    // lamina's front faces along the sweep and is the face extruded.
    let (mut solid, front, back) = Solid::try_lamina(&ring)?;
    for hole in holes {
        let filling = solid.add_ring(front, hole)?;
        solid.kfmrh(back, filling)?;
    }
    solid.extrude_face(front, sweep)?;
    Ok(solid)
}

/// The pyramid over a simple polygon with the given apex.
///
/// # Errors
///
/// As for [`prism`], with [`BuildError::Flat`] when the apex lies in the
/// polygon's plane.
pub fn pyramid(base: &[DVec3], apex: DVec3) -> Result<Solid, BuildError> {
    let checked = checked_profile(base)?;
    if !apex.is_finite() {
        return Err(BuildError::NonFinitePosition {
            vertex: base.len(),
            position: apex,
        });
    }
    let side = orient3d(checked.pivot[0], checked.pivot[1], checked.pivot[2], apex);
    let ring: Vec<DVec3> = match side {
        Sign::Zero => return Err(BuildError::Flat),
        Sign::Positive => base.to_vec(),
        Sign::Negative => base.iter().rev().copied().collect(),
    };
    // `ring` runs counter-clockwise seen from the apex: the lamina's front
    // faces the apex and is coned to it, its back is the base.
    let (mut solid, front, _) = Solid::try_lamina(&ring)?;
    solid.cone_face(front, apex)?;
    Ok(solid)
}

/// A closed triangulated unit sphere (a UV sphere) as a soup: `rings`
/// latitude bands (at least 2) and `2 · rings` longitude segments, giving
/// `4 · rings · (rings − 1)` triangles wound outward, with poles at `±z`.
/// Benchmarks and tests use it as a scalable curved mesh.
///
/// # Panics
///
/// When `rings` is so large that the triangle count overflows `usize` or
/// the soup does not fit in memory (a programmer's choice of size, not
/// user data).
#[must_use]
pub fn sphere_soup(rings: usize) -> PolygonSoup {
    let rings = rings.max(2);
    uv_sphere_soup(rings, 2 * rings)
}

/// A closed triangulated unit sphere (a UV sphere) as a soup with any
/// number of longitude `segments` (at least 3) and `rings` latitude bands
/// (at least 2): `2 · segments · (rings − 1)` triangles wound outward, with
/// poles at `±z` of valence `segments`. Few rings and many segments make
/// the poles' fans of slivers that revolved parts have; benchmarks and
/// tests use it so.
///
/// # Panics
///
/// As for [`sphere_soup`].
#[must_use]
pub fn uv_sphere_soup(rings: usize, segments: usize) -> PolygonSoup {
    let rings = rings.max(2);
    let segments = segments.max(3);
    let mut positions = vec![DVec3::Z, -DVec3::Z];
    for i in 1..rings {
        let theta = std::f64::consts::PI * i as f64 / rings as f64;
        for j in 0..segments {
            let phi = std::f64::consts::TAU * j as f64 / segments as f64;
            positions.push(DVec3::new(
                theta.sin() * phi.cos(),
                theta.sin() * phi.sin(),
                theta.cos(),
            ));
        }
    }
    let at = |i: usize, j: usize| 2 + (i - 1) * segments + j % segments;
    let mut polygons: Vec<[usize; 3]> = Vec::with_capacity(2 * segments * (rings - 1));
    for j in 0..segments {
        polygons.push([0, at(1, j), at(1, j + 1)]);
        polygons.push([1, at(rings - 1, j + 1), at(rings - 1, j)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segments {
            polygons.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)]);
            polygons.push([at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
        }
    }
    PolygonSoup::new(positions, polygons)
}

/// How [`cone_soup`] closes the cone's base.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ConeBase {
    /// A fan from a vertex at the base's centre: `n` triangles.
    CentreFan,
    /// A fan from the first base vertex, as CAD exporters write caps:
    /// `n − 2` triangles.
    CornerFan,
}

/// A closed triangulated cone as a soup: the apex `(0, 0, 1)` (vertex 0)
/// joined to `segments` base vertices on the unit circle at `z = 0` (at
/// least 3), the base closed by a fan, wound outward. With
/// [`ConeBase::CentreFan`] the centre is vertex 1 and the base vertices
/// follow; with [`ConeBase::CornerFan`] they start at vertex 1. The apex
/// (and the centre) has valence `segments`: benchmarks and tests use it as
/// the valid input whose faces all meet at one vertex.
///
/// # Panics
///
/// When the soup does not fit in memory (a programmer's choice of size).
#[must_use]
pub fn cone_soup(segments: usize, base: ConeBase) -> PolygonSoup {
    let n = segments.max(3);
    let mut positions = vec![DVec3::Z];
    if base == ConeBase::CentreFan {
        positions.push(DVec3::ZERO);
    }
    let first = positions.len();
    positions.extend((0..n).map(|i| {
        let angle = std::f64::consts::TAU * i as f64 / n as f64;
        DVec3::new(angle.cos(), angle.sin(), 0.0)
    }));
    let rim = |i: usize| first + i % n;
    let mut polygons: Vec<[usize; 3]> = (0..n).map(|i| [0, rim(i), rim(i + 1)]).collect();
    match base {
        ConeBase::CentreFan => polygons.extend((0..n).map(|i| [1, rim(i + 1), rim(i)])),
        ConeBase::CornerFan => polygons.extend((1..n - 1).map(|i| [first, rim(i + 1), rim(i)])),
    }
    PolygonSoup::new(positions, polygons)
}

/// `pages` triangles on one edge, from `(0, 0, 0)` to `(0, 0, 1)`, their
/// third vertices around it on the unit circle at `z = ½`: not a solid (an
/// edge of more than two faces), the input on which every pair of faces
/// shares an edge. For benchmarks and tests of refusals.
#[must_use]
pub fn edge_fan_soup(pages: usize) -> PolygonSoup {
    let mut positions = vec![DVec3::ZERO, DVec3::Z];
    positions.extend((0..pages).map(|k| {
        let angle = std::f64::consts::TAU * k as f64 / pages as f64;
        DVec3::new(angle.cos(), angle.sin(), 0.5)
    }));
    PolygonSoup::new(positions, (0..pages).map(|k| [0, 1, k + 2]))
}

/// The solid of [`sphere_soup`].
#[must_use]
pub fn sphere(rings: usize) -> Solid {
    Solid::try_from_soup(&sphere_soup(rings)).expect("a UV sphere is a closed manifold")
}

/// An L-shaped, non-convex prism of height 1 over the polygon
/// `(0,0) (2,0) (2,1) (1,1) (1,2) (0,2)`: volume 3, 8 faces.
#[must_use]
pub fn l_prism() -> Solid {
    let l = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)]
        .map(|(x, y)| DVec3::new(x, y, 0.));
    prism(&l, DVec3::Z).expect("the L profile is simple")
}

/// A square frame of height 1: the square `[−2, 2]²` with the square hole
/// `[−1, 1]²` through it, swept along `z` (volume 12, genus 1; its top and
/// bottom faces each have one ring).
#[must_use]
pub fn frame() -> Solid {
    let square = |r: f64| [(-r, -r), (r, -r), (r, r), (-r, r)].map(|(x, y)| DVec3::new(x, y, 0.));
    prism_with_holes(&square(2.0), &[&square(1.0)], DVec3::Z)
        .expect("the inner square is strictly inside the outer one")
}

struct CheckedProfile {
    /// Three vertices spanning the polygon's plane, in its winding.
    pivot: [DVec3; 3],
}

fn checked_profile(profile: &[DVec3]) -> Result<CheckedProfile, BuildError> {
    let n = profile.len();
    if n < 3 {
        return Err(BuildError::TooFewVertices {
            polygon: 0,
            line: None,
            count: n,
        });
    }
    if let Some((vertex, &position)) = profile.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(BuildError::NonFinitePosition { vertex, position });
    }
    for i in 0..n {
        if profile[i + 1..].contains(&profile[i]) {
            return Err(BuildError::RepeatedVertex {
                polygon: 0,
                line: None,
                vertex: i,
            });
        }
    }
    let fit = Plane::try_fit_newell(profile).map_err(|_| BuildError::ZeroArea)?;
    let projection = Projection::along(fit.plane.normal);
    let flat: Vec<_> = profile.iter().map(|&p| projection.apply(p)).collect();
    if let Some((a, b)) = find_self_intersection(&flat) {
        return Err(BuildError::SelfIntersecting(a, b));
    }
    // The largest fan triangle from vertex 0 that agrees with the winding.
    let a = profile[0];
    let pivot = (1..n - 1)
        .map(|i| [a, profile[i], profile[i + 1]])
        .max_by(|s, t| {
            let area = |q: &[DVec3; 3]| (q[1] - q[0]).cross(q[2] - q[0]).dot(fit.plane.normal);
            area(s).total_cmp(&area(t))
        })
        .ok_or(BuildError::ZeroArea)?;
    Ok(CheckedProfile { pivot })
}

fn cube_corners() -> Vec<DVec3> {
    let mut v = Vec::with_capacity(8);
    for x in [-1.0, 1.0] {
        for y in [-1.0, 1.0] {
            for z in [-1.0, 1.0] {
                v.push(DVec3::new(x, y, z));
            }
        }
    }
    v
}

fn icosahedron_vertices() -> Vec<DVec3> {
    let mut v = Vec::with_capacity(12);
    for s in [-1.0, 1.0] {
        for t in [-PHI, PHI] {
            v.push(DVec3::new(0.0, t, s));
            v.push(DVec3::new(t, s, 0.0));
            v.push(DVec3::new(s, 0.0, t));
        }
    }
    v
}

fn dodecahedron_vertices() -> Vec<DVec3> {
    let mut v = cube_corners();
    for s in [-1.0 / PHI, 1.0 / PHI] {
        for t in [-PHI, PHI] {
            v.push(DVec3::new(0.0, s, t));
            v.push(DVec3::new(s, t, 0.0));
            v.push(DVec3::new(t, 0.0, s));
        }
    }
    v
}

/// A regular convex polyhedron from its vertices and the directions of its
/// face normals (the vertices of its dual): each face is the `k` vertices
/// farthest along its normal, ordered counter-clockwise around it; the
/// solid is built from those faces by Euler operators.
fn regular(vertices: &[DVec3], normals: &[DVec3], k: usize) -> Solid {
    let polygons: Vec<Vec<usize>> = normals
        .iter()
        .map(|&normal| {
            let mut ranked: Vec<usize> = (0..vertices.len()).collect();
            ranked.sort_by(|&a, &b| vertices[b].dot(normal).total_cmp(&vertices[a].dot(normal)));
            ranked.truncate(k);
            let centre = ranked.iter().map(|&i| vertices[i]).sum::<DVec3>() / k as f64;
            let u = (vertices[ranked[0]] - centre).normalize();
            let w = normal.normalize().cross(u);
            ranked.sort_by(|&a, &b| {
                let angle = |i: usize| {
                    let d = vertices[i] - centre;
                    d.dot(w).atan2(d.dot(u))
                };
                angle(a).total_cmp(&angle(b))
            });
            ranked
        })
        .collect();
    Solid::try_sphere_from_polygons(&PolygonSoup::new(vertices.to_vec(), polygons))
        .expect("a regular polyhedron's faces form a closed genus-0 manifold")
}
