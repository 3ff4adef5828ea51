//! Points and solids shared by the point-in-solid unit tests.

use glam::DVec3;

use super::Accel;
use crate::mesh::builders;

/// Points that stress both ray directions: random points in and around
/// the box, points next to both ends of it in `x`, every vertex and edge
/// midpoint (on the boundary, or on the `x` line through one), the
/// vertices moved along `x` to both sides (rays through vertices), and
/// points just inside and outside the box's `x` ends on those lines.
pub(super) fn stress_points(solid: &crate::mesh::Solid, seed: u64) -> Vec<DVec3> {
    let accel = Accel::new(solid);
    let (min, max) = (accel.bounds().min, accel.bounds().max);
    let size = max - min;
    let mut u = crate::test_rng::uniform(seed);
    let mut points: Vec<DVec3> = (0..3000)
        .map(|_| min - size * 0.1 + DVec3::new(u(), u(), u()) * size * 1.2)
        .collect();
    for _ in 0..500 {
        let (y, z) = (min.y + u() * size.y, min.z + u() * size.z);
        for x in [min.x, max.x, min.x + 1e-9 * size.x, max.x - 1e-9 * size.x] {
            points.push(DVec3::new(x, y, z));
        }
    }
    let corners: Vec<DVec3> = solid.vertices().map(|(_, v)| v.position).collect();
    for (k, &v) in corners.iter().enumerate() {
        let w = corners[(k * 7 + 3) % corners.len()];
        for p in [v, (v + w) * 0.5] {
            points.push(p);
            for x in [
                min.x - 1.0,
                max.x + 1.0,
                min.x,
                max.x,
                (min.x + max.x) * 0.5,
            ] {
                points.push(DVec3::new(x, p.y, p.z));
            }
        }
    }
    points
}

pub(super) fn closed_solids() -> Vec<crate::mesh::Solid> {
    vec![
        builders::cube(),
        builders::l_prism(),
        builders::icosahedron(),
        builders::dodecahedron(),
        builders::sphere(9),
    ]
}
