//! Sweeping a planar polygon along a curve, with rotation-minimizing frames
//! by double reflection (Wang, Jüttler, Zheng & Liu 2008), and what the
//! sweep, revolve and loft builders share: their error type (in
//! `error.rs`), the profile
//! checks, the stacking and collision tests and the side faces between
//! consecutive sections.
//!
//! A sweep places the profile, given in 2-D, in the plane normal to the
//! path at each sample of the path flattened to the chord tolerance: the
//! profile's `x` along the frame's first normal `r`, its `y` along
//! `s = t × r`. The solid is the two end caps (kept as polygons) and, for
//! each profile edge and path segment, a side quadrilateral when its four
//! corners are exactly coplanar, two triangles otherwise.
//!
//! Folding is decided exactly on the output coordinates: every vertex of
//! section `i + 1` must lie strictly in front of the plane of section `i`
//! and every vertex of section `i` strictly behind the plane of section
//! `i + 1` ([`orient3d`] on three vertices of each section). A path that
//! turns tighter than the profile's reach fails this test and is refused
//! with the section and path parameter where it happens. A path that comes
//! back to meet itself further along is found by an exact test of every
//! two side or cap triangles that share no vertex
//! ([`check_collisions`]) and refused with the two sections. Profiles with
//! holes are not supported yet.

mod collision;
mod error;
mod holed;

use glam::{DVec2, DVec3};

use crate::curve::{Curve, CurveError};
use crate::geom::polygon::find_self_intersection;
use crate::geom::{Sign, orient2d, orient3d, triangulate};

use crate::mesh::{PolygonSoup, Solid};

pub(crate) use collision::check_collisions;

/// The most vertices a sweep or revolve may produce (profile vertices times
/// sections); more is refused with [`SweepError::TooLarge`].
pub const MAX_VERTICES: usize = 1 << 24;

/// `Ok` when `count` vertices are within [`MAX_VERTICES`].
pub(crate) fn check_size(count: usize) -> Result<(), SweepError> {
    if count > MAX_VERTICES {
        Err(SweepError::TooLarge {
            vertices: count,
            limit: MAX_VERTICES,
        })
    } else {
        Ok(())
    }
}
pub use error::{Argument, SolidPart, SweepError};
pub use holed::try_sweep_with_holes;

/// A checked 2-D profile: its vertices counter-clockwise and three of them
/// spanning a triangle of the same winding.
pub(crate) struct Profile2 {
    /// The vertices, counter-clockwise.
    pub(crate) points: Vec<DVec2>,
    /// Indices of three vertices forming the largest counter-clockwise fan
    /// triangle from vertex 0.
    pub(crate) pivot: [usize; 3],
}

/// Checks a 2-D polygon (at least three finite, distinct vertices, simple,
/// non-zero area) and returns it counter-clockwise.
pub(crate) fn check_profile(points: &[DVec2], argument: Argument) -> Result<Profile2, SweepError> {
    let n = points.len();
    if n < 3 {
        return Err(SweepError::TooFewVertices { argument, count: n });
    }
    if let Some(vertex) = points.iter().position(|p| !p.is_finite()) {
        return Err(SweepError::NonFiniteVertex { argument, vertex });
    }
    for first in 0..n {
        if let Some(offset) = points[first + 1..].iter().position(|&q| q == points[first]) {
            return Err(SweepError::RepeatedVertex {
                argument,
                first,
                second: first + 1 + offset,
            });
        }
    }
    if let Some((a, b)) = find_self_intersection(points) {
        return Err(SweepError::SelfIntersecting {
            argument,
            edges: [a, b],
        });
    }
    // The lowest (then leftmost) vertex is convex; its turn is the winding.
    let low = (0..n)
        .min_by(|&a, &b| {
            let (p, q) = (points[a], points[b]);
            p.y.total_cmp(&q.y).then(p.x.total_cmp(&q.x))
        })
        .unwrap_or(0);
    let turn = orient2d(
        points[(low + n - 1) % n],
        points[low],
        points[(low + 1) % n],
    );
    let ccw: Vec<DVec2> = match turn {
        Sign::Zero => return Err(SweepError::ZeroArea { argument }),
        Sign::Positive => points.to_vec(),
        Sign::Negative => points.iter().rev().copied().collect(),
    };
    let area = |i: usize| (ccw[i] - ccw[0]).perp_dot(ccw[i + 1] - ccw[0]);
    let best = (1..n - 1)
        .max_by(|&i, &j| area(i).total_cmp(&area(j)))
        .unwrap_or(1);
    Ok(Profile2 {
        points: ccw,
        pivot: [0, best, best + 1],
    })
}

/// Checks that each section lies strictly beyond the plane of the one
/// before it and strictly behind the plane of the one after it, `pivots`
/// giving three vertices of each section whose normal points forward.
pub(crate) fn check_stacking(
    sections: &[Vec<DVec3>],
    pivots: &[[usize; 3]],
    parameters: Option<&[f64]>,
) -> Result<(), SweepError> {
    for i in 0..sections.len().saturating_sub(1) {
        let (here, next) = (&sections[i], &sections[i + 1]);
        let plane = |s: &[DVec3], pivot: [usize; 3], q: DVec3| {
            orient3d(s[pivot[0]], s[pivot[1]], s[pivot[2]], q)
        };
        let ahead = next
            .iter()
            .position(|&q| plane(here, pivots[i], q) != Sign::Positive);
        let behind = here
            .iter()
            .position(|&q| plane(next, pivots[i + 1], q) != Sign::Negative);
        if let Some(vertex) = ahead.or(behind) {
            return Err(SweepError::Folds {
                section: i + 1,
                parameter: parameters.map(|t| t[i + 1]),
                vertex,
            });
        }
    }
    Ok(())
}

/// The soup of stacked sections (all with the vertices in corresponding
/// order, counter-clockwise seen from the front): a cap at each end and
/// the side faces between consecutive sections.
pub(crate) fn stacked_soup(sections: Vec<Vec<DVec3>>) -> PolygonSoup {
    let n = sections.first().map_or(0, Vec::len);
    let count = sections.len();
    let positions: Vec<DVec3> = sections.into_iter().flatten().collect();
    let at = |section: usize, vertex: usize| section * n + vertex % n;
    let mut polygons: Vec<Vec<usize>> = vec![(0..n).rev().map(|j| at(0, j)).collect()];
    polygons.push((0..n).map(|j| at(count - 1, j)).collect());
    for i in 0..count - 1 {
        for j in 0..n {
            let quad = [at(i, j), at(i, j + 1), at(i + 1, j + 1), at(i + 1, j)];
            push_quad(&mut polygons, &positions, quad);
        }
    }
    PolygonSoup::new(positions, polygons)
}

/// Pushes `quad` as one face when its corners are exactly coplanar, else as
/// two triangles.
pub(crate) fn push_quad(polygons: &mut Vec<Vec<usize>>, positions: &[DVec3], quad: [usize; 4]) {
    let [a, b, c, d] = quad.map(|i| positions[i]);
    if orient3d(a, b, c, d) == Sign::Zero {
        polygons.push(quad.to_vec());
    } else {
        polygons.push(vec![quad[0], quad[1], quad[2]]);
        polygons.push(vec![quad[0], quad[2], quad[3]]);
    }
}

/// Sweeps `profile` along `path`: the profile (2-D, either winding) is
/// placed in the normal plane of the path at each sample of the path
/// flattened to `tolerance` (a fraction of the path's size), oriented by
/// rotation-minimizing frames. The first frame's `r` is the coordinate axis
/// most nearly perpendicular to the start tangent, made perpendicular.
///
/// # Errors
///
/// Profile problems ([`SweepError::TooFewVertices`],
/// [`SweepError::NonFiniteVertex`], [`SweepError::RepeatedVertex`],
/// [`SweepError::SelfIntersecting`], [`SweepError::ZeroArea`]), a bad
/// tolerance ([`SweepError::Curve`]), [`SweepError::ZeroLengthPath`],
/// [`SweepError::ClosedPath`], [`SweepError::ZeroTangent`], and
/// [`SweepError::Folds`] where the path turns tighter than the profile
/// reaches, [`SweepError::Collides`] where it comes back to meet itself,
/// [`SweepError::TooLarge`] beyond [`MAX_VERTICES`].
pub fn try_sweep(
    profile: &[DVec2],
    path: &impl Curve,
    tolerance: f64,
) -> Result<Solid, SweepError> {
    let profile = check_profile(profile, Argument::Profile)?;
    let frames = PathFrames::along(path, tolerance)?;
    check_size(frames.points.len().saturating_mul(profile.points.len()))?;
    let sections = frames.place(&profile.points);
    let pivots = vec![profile.pivot; sections.len()];
    check_stacking(&sections, &pivots, Some(&frames.parameters))?;
    let cap = triangulate(&profile.points, &[])?;
    let soup = stacked_soup(sections);
    check_collisions(
        &soup,
        profile.points.len(),
        [&cap, &cap],
        Some(&frames.parameters),
    )?;
    Ok(Solid::try_from_soup(&soup)?)
}

/// The flattened path with a rotation-minimizing frame at each sample.
pub(crate) struct PathFrames {
    pub(crate) points: Vec<DVec3>,
    pub(crate) frames: Vec<(DVec3, DVec3)>,
    pub(crate) parameters: Vec<f64>,
}

impl PathFrames {
    /// Flattens `path` to `tolerance` and frames it.
    pub(crate) fn along(path: &impl Curve, tolerance: f64) -> Result<PathFrames, SweepError> {
        let curve_error = |source| SweepError::Curve {
            argument: Argument::Path,
            source,
        };
        let samples = path.try_flatten(tolerance).map_err(curve_error)?;
        let (first, last) = match (samples.first(), samples.last()) {
            (Some(f), Some(l)) => (*f, *l),
            _ => return Err(curve_error(CurveError::BadTolerance { tolerance })),
        };
        if samples.iter().all(|s| s.point == first.point) {
            return Err(SweepError::ZeroLengthPath { point: first.point });
        }
        if first.point == last.point {
            return Err(SweepError::ClosedPath { point: first.point });
        }
        let mut tangents = Vec::with_capacity(samples.len());
        for sample in &samples {
            let d = path
                .try_derivative_at(sample.parameter, 1)
                .map_err(curve_error)?;
            let t = d.try_normalize().ok_or(SweepError::ZeroTangent {
                parameter: sample.parameter,
            })?;
            tangents.push(t);
        }
        let points: Vec<DVec3> = samples.iter().map(|s| s.point).collect();
        let frames = rotation_minimizing_frames(&points, &tangents);
        Ok(PathFrames {
            points,
            frames,
            parameters: samples.iter().map(|s| s.parameter).collect(),
        })
    }

    /// The 2-D polygon placed in every frame: one section per sample.
    pub(crate) fn place(&self, polygon: &[DVec2]) -> Vec<Vec<DVec3>> {
        self.points
            .iter()
            .zip(&self.frames)
            .map(|(&x, &(r, s))| polygon.iter().map(|p| x + r * p.x + s * p.y).collect())
            .collect()
    }
}

/// The frames `(r, s)` (with `s = t × r`) at each point, by the double
/// reflection method of Wang, Jüttler, Zheng & Liu (2008): `r` is reflected
/// in the bisector plane of consecutive points, then in the plane that takes
/// the reflected tangent onto the next tangent. `tangents` are unit.
fn rotation_minimizing_frames(points: &[DVec3], tangents: &[DVec3]) -> Vec<(DVec3, DVec3)> {
    let t0 = tangents[0];
    let axis = [DVec3::X, DVec3::Y, DVec3::Z]
        .into_iter()
        .min_by(|a, b| a.dot(t0).abs().total_cmp(&b.dot(t0).abs()))
        .unwrap_or(DVec3::X);
    let mut r = (axis - t0 * axis.dot(t0)).normalize();
    let mut frames = Vec::with_capacity(points.len());
    frames.push((r, t0.cross(r)));
    for i in 0..points.len() - 1 {
        let v1 = points[i + 1] - points[i];
        let c1 = v1.dot(v1);
        let (r_l, t_l) = if c1 == 0.0 {
            (r, tangents[i])
        } else {
            (
                r - v1 * (2.0 / c1 * v1.dot(r)),
                tangents[i] - v1 * (2.0 / c1 * v1.dot(tangents[i])),
            )
        };
        let v2 = tangents[i + 1] - t_l;
        let c2 = v2.dot(v2);
        r = if c2 == 0.0 {
            r_l
        } else {
            r_l - v2 * (2.0 / c2 * v2.dot(r_l))
        };
        // Keep r unit and perpendicular to the tangent against drift.
        let t = tangents[i + 1];
        r = (r - t * r.dot(t)).try_normalize().unwrap_or(frames[i].0);
        frames.push((r, t.cross(r)));
    }
    frames
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::curve::BSpline;

    fn square(half: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(-half, -half),
            DVec2::new(half, -half),
            DVec2::new(half, half),
            DVec2::new(-half, half),
        ]
    }

    #[test]
    fn frames_along_a_helix_stay_orthonormal() {
        let points: Vec<DVec3> = (0..=40)
            .map(|i| {
                let a = i as f64 * 0.2;
                DVec3::new(a.cos(), a.sin(), 0.3 * a)
            })
            .collect();
        let tangents: Vec<DVec3> = (0..=40)
            .map(|i| {
                let a = i as f64 * 0.2;
                DVec3::new(-a.sin(), a.cos(), 0.3).normalize()
            })
            .collect();
        let frames = rotation_minimizing_frames(&points, &tangents);
        for ((r, s), t) in frames.iter().zip(&tangents) {
            assert!((r.length() - 1.0).abs() < 1e-12);
            assert!(r.dot(*t).abs() < 1e-12);
            assert!((r.cross(*s) - *t).length() < 1e-12);
        }
    }

    #[test]
    fn a_straight_sweep_is_a_prism() {
        let path = BSpline::try_open_uniform(
            vec![
                DVec3::ZERO,
                DVec3::new(0.0, 0.0, 1.0),
                DVec3::new(0.0, 0.0, 3.0),
            ],
            2,
        )
        .unwrap();
        let solid = try_sweep(&square(0.5), &path, 1e-3).unwrap();
        solid.check_consistency().unwrap();
        assert!((solid.volume() - 3.0).abs() < 1e-12, "{}", solid.volume());
    }

    #[test]
    fn a_tight_turn_folds() {
        // A quarter turn of radius 0.5 with a profile reaching 1 from it.
        let path = BSpline::try_open_uniform(
            vec![
                DVec3::ZERO,
                DVec3::new(0.5, 0.0, 0.0),
                DVec3::new(0.5, 0.5, 0.0),
            ],
            2,
        )
        .unwrap();
        let err = try_sweep(&square(1.0), &path, 1e-3).unwrap_err();
        assert!(
            matches!(
                err,
                SweepError::Folds {
                    parameter: Some(_),
                    ..
                }
            ),
            "{err}"
        );
    }
}
