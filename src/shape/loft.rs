//! Lofting: a solid through a sequence of planar sections.
//!
//! Section `i` and section `i + 1` are joined vertex to vertex (vertex `j`
//! to vertex `j`), so all sections need the same vertex count; side faces
//! are quadrilaterals when exactly planar, pairs of triangles otherwise, and
//! the first and last sections are the end caps. Each section must lie
//! strictly beyond the plane of the one before it and the one before
//! strictly behind its plane (decided exactly, as for a sweep), and all
//! sections must be wound the same way around the direction of travel.
//! As for a sweep, faces that meet without being neighbours (far sections
//! coming back to cross near ones) are found exactly and refused.

use glam::DVec3;

use crate::geom::polygon::Projection;
use crate::geom::{Aabb, Plane, Sign, Tolerance, orient3d, triangulate_3d};

use super::sweep::{
    Argument, SweepError, check_collisions, check_profile, check_stacking, stacked_soup,
};
use crate::mesh::Solid;

/// Lofts a solid through `sections`: at least two planar, simple polygons
/// with the same vertex count, each strictly beyond the previous one,
/// wound alike (either way). Planarity is judged with the default
/// planarity tolerance ([`Tolerance::planarity`], a fraction of the
/// diagonal of all sections' bounding box).
///
/// # Errors
///
/// [`SweepError::TooFewSections`], [`SweepError::SectionSize`], per-section
/// polygon problems (as for [`try_sweep`](super::try_sweep), plus
/// [`SweepError::NonPlanar`]), [`SweepError::SectionWinding`] when a section
/// is wound against the one before it, [`SweepError::Folds`] when
/// sections do not follow one another, [`SweepError::Collides`] when
/// faces that are not neighbours meet.
pub fn try_loft(sections: &[Vec<DVec3>]) -> Result<Solid, SweepError> {
    if sections.len() < 2 {
        return Err(SweepError::TooFewSections {
            count: sections.len(),
        });
    }
    let expected = sections[0].len();
    if let Some((section, s)) = sections
        .iter()
        .enumerate()
        .find(|(_, s)| s.len() != expected)
    {
        return Err(SweepError::SectionSize {
            section,
            count: s.len(),
            expected,
        });
    }
    for (section, s) in sections.iter().enumerate() {
        if let Some(vertex) = s.iter().position(|p| !p.is_finite()) {
            return Err(SweepError::NonFiniteVertex {
                argument: Argument::Section(section),
                vertex,
            });
        }
    }
    let diagonal = Aabb::from_points(sections.iter().flatten().copied()).diagonal();
    let limit = Tolerance::default().planarity_limit(diagonal);
    let mut ordered: Vec<Vec<DVec3>> = sections.to_vec();
    let mut pivots = pivots_of(&ordered, limit)?;
    let side = |ordered: &[Vec<DVec3>], pivots: &[[usize; 3]], i: usize, j: usize| {
        let [a, b, c] = pivots[i].map(|k| ordered[i][k]);
        orient3d(a, b, c, ordered[j][0])
    };
    if side(&ordered, &pivots, 0, 1) == Sign::Negative {
        // Wound clockwise seen from the front: reverse every section alike.
        for s in &mut ordered {
            s.reverse();
        }
        pivots = pivots_of(&ordered, limit)?;
    }
    for i in 0..ordered.len() - 1 {
        if side(&ordered, &pivots, i, i + 1) == Sign::Positive
            && side(&ordered, &pivots, i + 1, i) == Sign::Positive
        {
            return Err(SweepError::SectionWinding {
                section: i + 1,
                previous: i,
            });
        }
    }
    check_stacking(&ordered, &pivots, None)?;
    let first = triangulate_3d(&ordered[0], &[])?;
    let last = triangulate_3d(&ordered[ordered.len() - 1], &[])?;
    let soup = stacked_soup(ordered);
    check_collisions(&soup, expected, [&first, &last], None)?;
    Ok(Solid::try_from_soup(&soup)?)
}

/// Each section's pivot (see [`section_pivot`]).
fn pivots_of(sections: &[Vec<DVec3>], limit: f64) -> Result<Vec<[usize; 3]>, SweepError> {
    sections
        .iter()
        .enumerate()
        .map(|(i, s)| section_pivot(s, Argument::Section(i), limit))
        .collect()
}

/// Checks one section (at least three distinct vertices, planar within
/// `limit`, simple, non-zero area) and returns three of its vertices whose
/// triangle has the section's winding: the largest fan triangle from
/// vertex 0 measured along the section's Newell normal.
fn section_pivot(
    points: &[DVec3],
    argument: Argument,
    limit: f64,
) -> Result<[usize; 3], SweepError> {
    if points.len() < 3 {
        return Err(SweepError::TooFewVertices {
            argument,
            count: points.len(),
        });
    }
    let fit = Plane::try_fit_newell(points).map_err(|_| SweepError::ZeroArea { argument })?;
    if let Some((vertex, deviation)) = points
        .iter()
        .map(|&p| fit.plane.signed_distance(p).abs())
        .enumerate()
        .find(|&(_, d)| d > limit)
    {
        return Err(SweepError::NonPlanar {
            argument,
            vertex,
            deviation,
            limit,
        });
    }
    let projection = Projection::along(fit.plane.normal);
    let flat: Vec<_> = points.iter().map(|&p| projection.apply(p)).collect();
    check_profile(&flat, argument)?;
    let normal = fit.plane.normal;
    let area = |i: usize| {
        (points[i] - points[0])
            .cross(points[i + 1] - points[0])
            .dot(normal)
    };
    let best = (1..points.len() - 1)
        .max_by(|&i, &j| area(i).total_cmp(&area(j)))
        .unwrap_or(1);
    Ok([0, best, best + 1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shape::SolidPart;

    /// The unit square at height `z`, turned by `quarter_turns` × 90°.
    fn square(z: f64, quarter_turns: usize) -> Vec<DVec3> {
        let corners = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];
        (0..4)
            .map(|k| {
                let (x, y) = corners[(k + quarter_turns) % 4];
                DVec3::new(x, y, z)
            })
            .collect()
    }

    #[test]
    fn a_twisted_band_is_named_once_with_both_its_sections() {
        // Regression: a loft whose second band is turned by half a turn
        // was refused "near section 1 and section 1".
        let error = try_loft(&[square(0.0, 0), square(1.0, 0), square(2.0, 2)]).unwrap_err();
        assert!(
            matches!(
                error,
                SweepError::Collides {
                    parts: [SolidPart::Side(1), SolidPart::Side(1)],
                    parameters: None,
                }
            ),
            "{error:?}"
        );
        assert_eq!(
            error.to_string(),
            "the solid meets itself: the side between sections 1 and 2 crosses itself"
        );
        // Untwisted, the same sections loft.
        assert!(try_loft(&[square(0.0, 0), square(1.0, 0), square(2.0, 0)]).is_ok());
    }
}
