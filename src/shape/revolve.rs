//! Revolving a planar profile about an axis.
//!
//! The profile is given in its own half-plane: `x` is the distance from the
//! axis (never negative), `y` the height along it. Turning it by `angle`
//! in `segments` equal steps gives, for each profile edge, a band of
//! quadrilaterals (kept when exactly planar, split into two triangles
//! otherwise). A profile vertex with `x = 0` lies on the axis and becomes
//! one pole vertex, so bands touching it are fans of triangles, not
//! degenerate quadrilaterals; an edge on the axis gives no face; an edge
//! from a pole at constant height gives one flat polygon (a disk, or a
//! sector of one). A full turn (`angle = 2π`) closes up; a partial one
//! adds the profile as a cap at each end.

use glam::{DVec2, DVec3};

use crate::curve::{Curve, CurveError, MAX_SEGMENTS};

use super::sweep::{Argument, SweepError, check_profile, check_size, push_quad};
use crate::mesh::{PolygonSoup, Solid};

/// The most steps around a revolve may take: a profile edge from the
/// axis at constant height becomes one flat face of that many corners, and
/// the validator refuses faces of more than
/// [`DEFAULT_MAX_FACE_CORNERS`](crate::io::DEFAULT_MAX_FACE_CORNERS) (4,096).
pub const MAX_TURN_STEPS: usize = 4096;

/// The most sliver pieces a revolve may make: per profile edge, the steps
/// around times how many of its quadrilaterals' widths (the chord at its
/// outer radius) fit in its radial extent, at least one. The validator's
/// self-intersection check pays about that many box overlaps: a profile
/// `[[1,0],[2,0.5],[2,1]]` turned in 131,072 steps took 95 s before this
/// limit (quadratic in the steps); at the limit it takes about 1 s.
pub const MAX_TURN_SLIVERS: u64 = 1 << 21;

/// An axis of revolution with the direction of angle 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RevolveAxis {
    /// A point on the axis: profile height 0.
    pub origin: DVec3,
    /// The axis direction (any length); angles turn counter-clockwise seen
    /// from its tip (right-handed).
    pub direction: DVec3,
    /// The direction in which the profile's `x` points at angle 0; only its
    /// part perpendicular to `direction` counts.
    pub radial: DVec3,
}

impl RevolveAxis {
    /// The `z` axis through the origin, angle 0 along `x`.
    pub const Z: RevolveAxis = RevolveAxis {
        origin: DVec3::ZERO,
        direction: DVec3::Z,
        radial: DVec3::X,
    };
}

/// How finely to divide the turn.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Segments {
    /// Exactly this many equal steps: at least 3 for a full turn, 1 for a
    /// partial one, at most [`MAX_SEGMENTS`].
    Count(usize),
    /// As few equal steps as keep every chord within `tolerance × size` of
    /// its circle, `size` being the diagonal of the solid's extent across
    /// the axis (`√((2 R)² + H²)` for a profile of largest radius `R` and
    /// height `H`).
    Tolerance(f64),
}

/// Revolves the 2-D `profile` (`x` = distance from the axis, `y` = height;
/// either winding) about `axis` by `angle` radians in `(0, 2π]`; exactly
/// `2π` (`std::f64::consts::TAU`) is a full turn.
///
/// # Errors
///
/// Profile problems as for [`try_sweep`](super::try_sweep),
/// [`SweepError::CrossesAxis`], [`SweepError::PinchOnAxis`],
/// [`SweepError::BadAxis`], [`SweepError::BadAngle`],
/// [`SweepError::BadSegments`], [`SweepError::Curve`] for a bad or too
/// small tolerance, and [`SweepError::TooLarge`] beyond
/// [`MAX_VERTICES`](super::MAX_VERTICES).
pub fn try_revolve(
    profile: &[DVec2],
    axis: &RevolveAxis,
    angle: f64,
    segments: Segments,
) -> Result<Solid, SweepError> {
    let checked = check_profile(profile, Argument::Profile)?;
    let points = checked.points;
    let n = points.len();
    if let Some((vertex, p)) = profile.iter().enumerate().find(|(_, p)| p.x < 0.0) {
        return Err(SweepError::CrossesAxis {
            vertex,
            radius: p.x,
        });
    }
    let frame = axis_frame(axis)?;
    if !(angle.is_finite() && angle > 0.0 && angle <= std::f64::consts::TAU) {
        return Err(SweepError::BadAngle { angle });
    }
    let full = angle == std::f64::consts::TAU;
    let pole = |j: usize| points[j % n].x == 0.0;
    if full && let Some(j) = (0..n).find(|&j| pole(j) && !pole(j + n - 1) && !pole(j + 1)) {
        let vertex = profile.iter().position(|&p| p == points[j]).unwrap_or(j);
        return Err(SweepError::PinchOnAxis { vertex });
    }
    let steps = step_count(&points, angle, full, segments)?;

    // Ring k of vertex j: angle `angle · k / steps`; a full turn wraps.
    let rings = if full { steps } else { steps + 1 };
    check_size(n.saturating_mul(rings))?;
    check_turn_cost(&points, angle, steps)?;
    let position = |j: usize, k: usize| {
        let p = points[j];
        let theta = angle * (k as f64) / (steps as f64);
        let (sin, cos) = if k == 0 { (0.0, 1.0) } else { theta.sin_cos() };
        frame.0 + frame.1 * p.y + (frame.2 * cos + frame.3 * sin) * p.x
    };
    let mut positions: Vec<DVec3> = Vec::new();
    let mut index: Vec<Vec<Option<usize>>> = vec![vec![None; rings]; n];
    let mut vertex = |j: usize, k: usize, positions: &mut Vec<DVec3>| -> usize {
        let j = j % n;
        let k = if pole(j) { 0 } else { k % rings };
        *index[j][k].get_or_insert_with(|| {
            positions.push(position(j, k));
            positions.len() - 1
        })
    };

    let mut polygons: Vec<Vec<usize>> = Vec::new();
    for j in 0..n {
        let (a, b) = (j, j + 1);
        match (pole(a), pole(b)) {
            (true, true) => {}
            (true, false) | (false, true) if points[a].y == points[b % n].y => {
                // A flat disk (or sector) around the pole.
                let ring = if pole(a) { b } else { a };
                let mut disk: Vec<usize> = (0..rings)
                    .map(|k| vertex(ring, k, &mut positions))
                    .collect();
                if !full {
                    disk.push(vertex(if pole(a) { a } else { b }, 0, &mut positions));
                }
                if pole(a) {
                    disk.reverse();
                }
                polygons.push(disk);
            }
            _ => {
                for k in 0..steps {
                    let quad = [
                        vertex(a, k, &mut positions),
                        vertex(a, k + 1, &mut positions),
                        vertex(b, k + 1, &mut positions),
                        vertex(b, k, &mut positions),
                    ];
                    if pole(a) {
                        polygons.push(vec![quad[0], quad[2], quad[3]]);
                    } else if pole(b) {
                        polygons.push(vec![quad[0], quad[1], quad[2]]);
                    } else {
                        push_quad(&mut polygons, &positions, quad);
                    }
                }
            }
        }
    }
    if !full {
        polygons.push((0..n).map(|j| vertex(j, 0, &mut positions)).collect());
        polygons.push(
            (0..n)
                .rev()
                .map(|j| vertex(j, steps, &mut positions))
                .collect(),
        );
    }
    Ok(Solid::try_from_soup(&PolygonSoup::new(
        positions, polygons,
    ))?)
}

/// Revolves a profile curve: the curve is flattened to `tolerance` (a
/// fraction of its size) and the turn divided to the same tolerance. The
/// curve lies in the `z = 0` plane of the profile half-plane (its `x` the
/// distance from the axis, its `y` the height); a closed curve (ending where
/// it starts) is the whole profile, an open one is closed by a straight
/// edge from its end back to its start.
///
/// # Errors
///
/// As for [`try_revolve`], plus [`SweepError::NonPlanar`] for a flattened
/// point off `z = 0`.
pub fn try_revolve_curve(
    profile: &impl Curve,
    axis: &RevolveAxis,
    angle: f64,
    tolerance: f64,
) -> Result<Solid, SweepError> {
    let samples = profile
        .try_flatten(tolerance)
        .map_err(|source| SweepError::Curve {
            argument: Argument::Profile,
            source,
        })?;
    if let Some((vertex, s)) = samples.iter().enumerate().find(|(_, s)| s.point.z != 0.0) {
        return Err(SweepError::NonPlanar {
            argument: Argument::Profile,
            vertex,
            deviation: s.point.z.abs(),
            limit: 0.0,
        });
    }
    let mut points: Vec<DVec2> = samples.iter().map(|s| s.point.truncate()).collect();
    if points.len() > 1 && points.first() == points.last() {
        points.pop();
    }
    try_revolve(&points, axis, angle, Segments::Tolerance(tolerance))
}

/// `(origin, unit axis d, unit radial u, v = d × u)`.
fn axis_frame(axis: &RevolveAxis) -> Result<(DVec3, DVec3, DVec3, DVec3), SweepError> {
    let bad = SweepError::BadAxis {
        direction: axis.direction,
        radial: axis.radial,
    };
    if !(axis.origin.is_finite() && axis.direction.is_finite() && axis.radial.is_finite()) {
        return Err(bad);
    }
    let d = axis.direction.try_normalize().ok_or(bad.clone())?;
    let u = (axis.radial - d * axis.radial.dot(d))
        .try_normalize()
        .ok_or(bad)?;
    Ok((axis.origin, d, u, d.cross(u)))
}

/// Refuses a turn of `steps` beyond [`MAX_TURN_STEPS`] or
/// [`MAX_TURN_SLIVERS`] (see [`SweepError::TurnTooFine`]).
fn check_turn_cost(points: &[DVec2], angle: f64, steps: usize) -> Result<(), SweepError> {
    let step_angle = angle / steps as f64;
    let n = points.len();
    let slivers: u64 = (0..n)
        .map(|j| {
            let (a, b) = (points[j], points[(j + 1) % n]);
            let outer = a.x.max(b.x);
            let chord = outer * step_angle;
            let pieces = if chord > 0.0 {
                ((a.x - b.x).abs() / chord).ceil().clamp(1.0, 1e12) as u64
            } else {
                1
            };
            (steps as u64).saturating_mul(pieces)
        })
        .fold(0u64, u64::saturating_add);
    if steps > MAX_TURN_STEPS || slivers > MAX_TURN_SLIVERS {
        return Err(SweepError::TurnTooFine {
            segments: steps,
            slivers,
            step_limit: MAX_TURN_STEPS,
            sliver_limit: MAX_TURN_SLIVERS,
        });
    }
    Ok(())
}

/// The number of steps for the turn.
fn step_count(
    points: &[DVec2],
    angle: f64,
    full: bool,
    segments: Segments,
) -> Result<usize, SweepError> {
    let minimum = if full { 3 } else { 1 };
    match segments {
        Segments::Count(count) => {
            if (minimum..=MAX_SEGMENTS).contains(&count) {
                Ok(count)
            } else {
                Err(SweepError::BadSegments {
                    segments: count,
                    minimum,
                    limit: MAX_SEGMENTS,
                })
            }
        }
        Segments::Tolerance(tolerance) => {
            let curve_error = |source| SweepError::Curve {
                argument: Argument::Profile,
                source,
            };
            if !(tolerance.is_finite() && tolerance > 0.0) {
                return Err(curve_error(CurveError::BadTolerance { tolerance }));
            }
            let radius = points.iter().map(|p| p.x).fold(0.0, f64::max);
            let (low, high) = points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                    (l.min(p.y), h.max(p.y))
                });
            let size = (2.0 * radius).hypot(high - low);
            // A chord of angle Δ on radius R strays R (1 − cos(Δ/2)) from the
            // circle: Δ = 4 asin(√(e/2)) for the relative sagitta e.
            let sagitta = (tolerance * size / radius).min(2.0);
            let step = 4.0 * (sagitta / 2.0).sqrt().asin();
            let count = (angle / step).ceil();
            if !(count.is_finite() && count <= MAX_SEGMENTS as f64) {
                return Err(curve_error(CurveError::TooManySegments {
                    tolerance,
                    limit: MAX_SEGMENTS,
                }));
            }
            Ok((count as usize).max(minimum))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rectangle(x0: f64, x1: f64, h: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(x0, 0.0),
            DVec2::new(x1, 0.0),
            DVec2::new(x1, h),
            DVec2::new(x0, h),
        ]
    }

    #[test]
    fn a_full_turn_of_a_rectangle_off_the_axis_is_a_ring() {
        let n = 12;
        let s = try_revolve(
            &rectangle(1.0, 2.0, 1.0),
            &RevolveAxis::Z,
            std::f64::consts::TAU,
            Segments::Count(n),
        )
        .unwrap();
        s.check_consistency().unwrap();
        let shells = s.shells();
        assert_eq!(shells[0].genus(), Some(1));
        let polygon = n as f64 / 2.0 * (std::f64::consts::TAU / n as f64).sin();
        assert!((s.volume() - polygon * 3.0).abs() < 1e-12, "{}", s.volume());
    }

    /// An 80-byte scene's revolve in 131,072 steps took 95 s (the
    /// validator's self-intersection check is quadratic in the steps for
    /// long radial quadrilaterals): refused before anything is built, by
    /// the estimate of that work; a fine turn of a short profile is not.
    #[test]
    fn a_turn_too_fine_to_check_is_refused_before_it_is_built() {
        let profile = [
            DVec2::new(1.0, 0.0),
            DVec2::new(2.0, 0.5),
            DVec2::new(2.0, 1.0),
        ];
        let full = std::f64::consts::TAU;
        for steps in [131_072, 8192] {
            let e =
                try_revolve(&profile, &RevolveAxis::Z, full, Segments::Count(steps)).unwrap_err();
            assert!(
                matches!(e, SweepError::TurnTooFine { segments, .. } if segments == steps),
                "{e}"
            );
        }
        assert!(try_revolve(&profile, &RevolveAxis::Z, full, Segments::Count(512)).is_ok());
        // A ring of short radial extent at the step limit: few slivers.
        let thin = rectangle(100.0, 100.01, 1.0);
        check_turn_cost(&thin, full, MAX_TURN_STEPS).unwrap();
        assert!(check_turn_cost(&thin, full, MAX_TURN_STEPS + 1).is_err());
    }

    #[test]
    fn a_profile_on_the_axis_gives_poles_or_disks() {
        // A triangle with one edge on the axis: a cone with a pole tip and
        // a disk base.
        let cone = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, 1.0),
        ];
        let s = try_revolve(
            &cone,
            &RevolveAxis::Z,
            std::f64::consts::TAU,
            Segments::Count(8),
        )
        .unwrap();
        s.check_consistency().unwrap();
        assert_eq!((s.vertex_count(), s.face_count()), (9, 9));
        assert!(s.volume() > 0.0);
        // Touching the axis at one vertex only pinches in a full turn.
        let diamond = [
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, -1.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(1.0, 1.0),
        ];
        assert_eq!(
            try_revolve(
                &diamond,
                &RevolveAxis::Z,
                std::f64::consts::TAU,
                Segments::Count(8)
            )
            .unwrap_err(),
            SweepError::PinchOnAxis { vertex: 0 }
        );
        let half = try_revolve(&diamond, &RevolveAxis::Z, 3.0, Segments::Count(8)).unwrap();
        half.check_consistency().unwrap();
    }
}
