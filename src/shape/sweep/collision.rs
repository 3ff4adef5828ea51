//! The global self-intersection test of a sweep or loft: no two faces that
//! share no vertex may meet, decided exactly on the output coordinates
//! (the triangle–triangle test of [`geom::triangles_intersect`]), with a
//! broad phase that sorts the triangles' boxes along the longest axis and
//! sweeps
//! (sort and sweep, Baraff 1992).
//!
//! Faces sharing a vertex are neighbours; whether they fold onto each other
//! is the stacking test of consecutive sections, not this one.
//!
//! [`geom::triangles_intersect`]: crate::geom::triangles_intersect

use glam::DVec3;

use crate::geom::{Aabb, triangles_intersect};

use super::{SolidPart, SweepError};
use crate::mesh::PolygonSoup;

/// One triangle of the stacked solid: soup indices and the cap or band of
/// side faces it belongs to.
struct Piece {
    corners: [usize; 3],
    part: SolidPart,
    bounds: Aabb,
}

/// Checks a stacked soup (as built by `stacked_soup`: the first and last
/// caps, then side faces of three or four corners) for two faces that meet
/// without sharing a vertex. `caps` triangulate the first and last section
/// (indices within a section of `section_size` vertices).
pub(crate) fn check_collisions(
    soup: &PolygonSoup,
    section_size: usize,
    caps: [&[[usize; 3]]; 2],
    parameters: Option<&[f64]>,
) -> Result<(), SweepError> {
    let n = section_size.max(1);
    let last = soup.positions.len() / n - 1;
    let mut pieces: Vec<Piece> = Vec::new();
    let mut push = |corners: [usize; 3], cap: bool, positions: &[DVec3]| {
        let section = corners.iter().min().map_or(0, |&c| c / n);
        let part = if cap {
            SolidPart::Cap(section)
        } else {
            SolidPart::Side(section)
        };
        let bounds = Aabb::from_points(corners.map(|c| positions[c]));
        pieces.push(Piece {
            corners,
            part,
            bounds,
        });
    };
    for (cap, offset) in caps.into_iter().zip([0, last * n]) {
        for t in cap {
            push(t.map(|k| offset + k), true, &soup.positions);
        }
    }
    for polygon in soup.polygons.iter().skip(2) {
        let v = &polygon.vertices;
        for k in 1..v.len() - 1 {
            push([v[0], v[k], v[k + 1]], false, &soup.positions);
        }
    }
    let size = Aabb::from_points(soup.positions.iter().copied()).size();
    let axis = if size.x >= size.y && size.x >= size.z {
        0
    } else if size.y >= size.z {
        1
    } else {
        2
    };
    pieces.sort_by(|a, b| a.bounds.min[axis].total_cmp(&b.bounds.min[axis]));
    let corners = |p: &Piece| p.corners.map(|c| soup.positions[c]);
    for (i, a) in pieces.iter().enumerate() {
        for b in &pieces[i + 1..] {
            if b.bounds.min[axis] > a.bounds.max[axis] {
                break;
            }
            let overlap =
                a.bounds.min.cmple(b.bounds.max).all() && b.bounds.min.cmple(a.bounds.max).all();
            let neighbours = a.corners.iter().any(|c| b.corners.contains(c));
            if overlap && !neighbours && triangles_intersect(corners(a), corners(b)) {
                // Along the solid: a cap before the side that starts at
                // its section.
                let mut parts = [a.part, b.part];
                parts.sort_unstable_by_key(|p| (p.section(), matches!(p, SolidPart::Side(_))));
                let sections = match parts {
                    [SolidPart::Side(s), SolidPart::Side(r)] if s == r => [s, s + 1],
                    _ => parts.map(SolidPart::section),
                };
                return Err(SweepError::Collides {
                    parts,
                    parameters: parameters.map(|t| sections.map(|s| t[s])),
                });
            }
        }
    }
    Ok(())
}
