//! Sweeps of a profile with holes: the outer polygon and each hole swept
//! along the same frames, the hole walls facing into the holes, and each
//! end cap one face with a ring per hole.
//!
//! The caps are built as the exact constrained triangulation of the
//! profile with its holes (which also refuses holes that are not strictly
//! inside the profile or that touch each other), and the triangles of each
//! cap are merged into one face by Euler operators
//! ([`Solid::merge_faces_where`]).

use glam::DVec2;

use crate::curve::Curve;
use crate::geom::triangulate;

use super::{
    Argument, PathFrames, SweepError, check_collisions, check_profile, check_size, check_stacking,
    push_quad, stacked_soup, try_sweep,
};
use crate::mesh::{Polygon, PolygonSoup, Solid};

/// Sweeps `profile` with `holes` (2-D polygons, either winding, strictly
/// inside the profile and apart from each other) along `path`, as
/// [`try_sweep`] does for a profile without holes; the result has a
/// through hole along the path for each hole (genus = number of holes),
/// and its two caps are faces with one ring per hole.
///
/// # Errors
///
/// As for [`try_sweep`], with [`Argument::Hole`] naming a bad hole, and
/// the triangulation's error for holes outside the profile or touching.
pub fn try_sweep_with_holes(
    profile: &[DVec2],
    holes: &[Vec<DVec2>],
    path: &impl Curve,
    tolerance: f64,
) -> Result<Solid, SweepError> {
    if holes.is_empty() {
        return try_sweep(profile, path, tolerance);
    }
    let outer = check_profile(profile, Argument::Profile)?;
    let inner = holes
        .iter()
        .enumerate()
        .map(|(k, h)| check_profile(h, Argument::Hole(k)))
        .collect::<Result<Vec<_>, _>>()?;
    let hole_points: Vec<&[DVec2]> = inner.iter().map(|h| h.points.as_slice()).collect();
    let cap = triangulate(&outer.points, &hole_points)?;
    let frames = PathFrames::along(path, tolerance)?;
    let per_section = outer.points.len() + hole_points.iter().map(|h| h.len()).sum::<usize>();
    check_size(frames.points.len().saturating_mul(per_section))?;

    // The outer tube decides folds and collisions; every hole lies inside
    // it in each section, but its stacking is checked exactly too.
    let outer_sections = frames.place(&outer.points);
    check_stacking(
        &outer_sections,
        &vec![outer.pivot; outer_sections.len()],
        Some(&frames.parameters),
    )?;
    let outer_cap = triangulate(&outer.points, &[])?;
    let outer_soup = stacked_soup(outer_sections.clone());
    check_collisions(
        &outer_soup,
        outer.points.len(),
        [&outer_cap, &outer_cap],
        Some(&frames.parameters),
    )?;
    let hole_sections: Vec<Vec<Vec<_>>> = inner.iter().map(|h| frames.place(&h.points)).collect();
    for (h, sections) in inner.iter().zip(&hole_sections) {
        check_stacking(
            sections,
            &vec![h.pivot; sections.len()],
            Some(&frames.parameters),
        )?;
    }

    // Positions section by section: the outer polygon, then each hole, in
    // the order the cap triangulation numbers them.
    let count = frames.points.len();
    let mut positions = Vec::with_capacity(count * per_section);
    for i in 0..count {
        positions.extend_from_slice(&outer_sections[i]);
        for sections in &hole_sections {
            positions.extend_from_slice(&sections[i]);
        }
    }
    let at = |section: usize, k: usize| section * per_section + k;
    let mut polygons: Vec<Vec<usize>> = Vec::new();
    // The caps first: the start cap turned to face backwards.
    for t in &cap {
        polygons.push(vec![at(0, t[0]), at(0, t[2]), at(0, t[1])]);
    }
    for t in &cap {
        polygons.push(t.iter().map(|&k| at(count - 1, k)).collect());
    }
    let cap_faces = polygons.len();
    let mut ring_start = 0;
    let rings = std::iter::once(outer.points.len()).chain(hole_points.iter().map(|h| h.len()));
    for (r, n) in rings.enumerate() {
        for i in 0..count - 1 {
            for j in 0..n {
                let k = |j: usize| ring_start + j % n;
                let quad = [
                    at(i, k(j)),
                    at(i, k(j + 1)),
                    at(i + 1, k(j + 1)),
                    at(i + 1, k(j)),
                ];
                // Hole walls face into the hole (the same diagonal as the
                // hole's own sweep, wound the other way).
                let quad = if r == 0 {
                    quad
                } else {
                    [quad[0], quad[3], quad[2], quad[1]]
                };
                push_quad(&mut polygons, &positions, quad);
            }
        }
        ring_start += n;
    }
    let soup = PolygonSoup {
        positions,
        polygons: polygons.into_iter().map(Polygon::new).collect(),
    };
    let mut solid = Solid::try_from_soup(&soup)?;
    let half = cap_faces / 2;
    let cap_of = |solid: &Solid, f| {
        solid
            .face(f)
            .attributes
            .source_index
            .filter(|&i| i < cap_faces)
            .map(|i| i / half)
    };
    solid.merge_faces_where(
        |solid, a, b| matches!((cap_of(solid, a), cap_of(solid, b)), (Some(x), Some(y)) if x == y),
    );
    Ok(solid)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;
    use crate::curve::BSpline;

    fn square(half: f64, centre: DVec2) -> Vec<DVec2> {
        [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
            .iter()
            .map(|&(x, y)| centre + half * DVec2::new(x, y))
            .collect()
    }

    /// A quadratic B-spline along z from 0 to 2 (a straight line).
    fn straight_path() -> BSpline {
        BSpline::try_open_uniform(
            vec![
                DVec3::ZERO,
                DVec3::new(0.0, 0.0, 1.0),
                DVec3::new(0.0, 0.0, 2.0),
            ],
            2,
        )
        .unwrap()
    }

    #[test]
    fn a_straight_sweep_with_two_holes_is_a_block_with_two_tunnels() {
        let path = straight_path();
        let holes = vec![
            square(0.25, DVec2::new(-0.5, 0.0)),
            square(0.25, DVec2::new(0.5, 0.0)),
        ];
        let solid = try_sweep_with_holes(&square(1.0, DVec2::ZERO), &holes, &path, 1e-3).unwrap();
        solid.check_consistency().unwrap();
        // 4 − 2 · 0.25 of cross-section, 2 long.
        assert!((solid.volume() - 7.0).abs() < 1e-12, "{}", solid.volume());
        assert_eq!(solid.ring_count(), 4);
        assert_eq!(solid.shells()[0].genus(), Some(2));
        // Caps are one face each: 2 caps + 4 outer walls + 2 × 4 hole walls.
        assert_eq!(solid.face_count(), 14);
    }

    #[test]
    fn a_hole_outside_the_profile_is_refused() {
        let path = straight_path();
        let holes = vec![square(0.25, DVec2::new(2.0, 0.0))];
        assert!(try_sweep_with_holes(&square(1.0, DVec2::ZERO), &holes, &path, 1e-3).is_err());
        let bad = vec![vec![DVec2::ZERO, DVec2::X]];
        let err = try_sweep_with_holes(&square(1.0, DVec2::ZERO), &bad, &path, 1e-3).unwrap_err();
        assert!(err.to_string().contains("hole 0"), "{err}");
    }
}
