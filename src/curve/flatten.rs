//! Adaptive flattening of a (rational) B-spline to a polyline within a
//! chord tolerance.
//!
//! The curve is cut into Bézier pieces by knot insertion (every breakpoint
//! raised to multiplicity `p`), then each piece is halved by de Casteljau
//! subdivision until its control polygon lies within the tolerance of the
//! chord between its ends. Since the piece lies in the convex hull of its
//! control points (weights are positive), and that hull lies within the
//! tolerance of the chord, the chord is within the tolerance of the curve:
//! the bound holds for the curve itself, not only at sampled points
//! (Lane & Riesenfeld 1980 for the subdivision, Piegl & Tiller 1997 §5.4
//! for the extraction).

use glam::{DVec3, DVec4};

use super::de_boor::insert_knot;
use super::{CurveError, CurveSample, KnotVector, MAX_SEGMENTS};

/// Flattens the rational B-spline with homogeneous control points
/// `(w P, w)` to `tolerance × size`, `size` being the diagonal of the box of
/// the control points `P`.
pub(crate) fn flatten_homogeneous(
    knots: &KnotVector,
    homogeneous: &[DVec4],
    tolerance: f64,
) -> Result<Vec<CurveSample>, CurveError> {
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(CurveError::BadTolerance { tolerance });
    }
    let too_many = CurveError::TooManySegments {
        tolerance,
        limit: MAX_SEGMENTS,
    };
    let project = |h: DVec4| h.truncate() / h.w;
    let (low, high) = homogeneous.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &h| (lo.min(project(h)), hi.max(project(h))),
    );
    let limit = tolerance * (high - low).length();

    let p = knots.degree();
    let mut knots = knots.clone();
    let mut points = homogeneous.to_vec();
    for breakpoint in knots.breakpoints() {
        while knots.multiplicity(breakpoint) < p {
            (knots, points) = insert_knot(&knots, &points, breakpoint);
        }
    }

    let values = knots.values();
    let (start, _) = knots.domain();
    let mut samples = vec![CurveSample {
        parameter: start,
        point: project(points[first_point(&knots)]),
    }];
    for span in p..knots.control_point_count() {
        let (a, b) = (values[span], values[span + 1]);
        if a == b {
            continue;
        }
        let piece = points[span - p..=span].to_vec();
        let mut stack = vec![(piece, a, b)];
        while let Some((piece, a, b)) = stack.pop() {
            let ends = (project(piece[0]), project(piece[p]));
            let flat = piece[1..p]
                .iter()
                .all(|&h| distance_to_segment(project(h), ends.0, ends.1) <= limit);
            if flat {
                samples.push(CurveSample {
                    parameter: b,
                    point: ends.1,
                });
                if samples.len() > MAX_SEGMENTS + 1 {
                    return Err(too_many);
                }
                continue;
            }
            let middle = 0.5 * (a + b);
            if !(a < middle && middle < b) || stack.len() > MAX_SEGMENTS {
                return Err(too_many);
            }
            let (left, right) = halve(&piece);
            stack.push((right, middle, b));
            stack.push((left, a, middle));
        }
    }
    Ok(samples)
}

/// The index of the first control point acting at the start of the domain:
/// `span − p` for the first non-empty span.
fn first_point(knots: &KnotVector) -> usize {
    let (start, _) = knots.domain();
    knots.span(start, super::Approach::FromAbove) - knots.degree()
}

/// De Casteljau's halving of a Bézier piece (in homogeneous coordinates,
/// which also halves rational pieces).
fn halve(piece: &[DVec4]) -> (Vec<DVec4>, Vec<DVec4>) {
    let mut work = piece.to_vec();
    let n = work.len();
    let mut left = Vec::with_capacity(n);
    let mut right = Vec::with_capacity(n);
    left.push(work[0]);
    right.push(work[n - 1]);
    for level in 1..n {
        for j in 0..n - level {
            work[j] = 0.5 * (work[j] + work[j + 1]);
        }
        left.push(work[0]);
        right.push(work[n - 1 - level]);
    }
    right.reverse();
    (left, right)
}

/// The distance from `q` to the segment `a b` (a construction, compared with
/// the user's tolerance only).
fn distance_to_segment(q: DVec3, a: DVec3, b: DVec3) -> f64 {
    let ab = b - a;
    let length2 = ab.length_squared();
    let s = if length2 > 0.0 {
        ((q - a).dot(ab) / length2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (q - (a + ab * s)).length()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(points: &[DVec3]) -> Vec<DVec4> {
        points.iter().map(|p| p.extend(1.0)).collect()
    }

    #[test]
    fn a_straight_control_polygon_gives_one_segment_per_span() {
        let knots = KnotVector::try_open_uniform(4, 2).unwrap();
        let h = line(&[
            DVec3::ZERO,
            DVec3::X,
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(3.0, 0.0, 0.0),
        ]);
        let s = flatten_homogeneous(&knots, &h, 1e-3).unwrap();
        assert_eq!(s.len(), 3);
        assert_eq!(s[0].point, DVec3::ZERO);
        assert_eq!(s[2].point, DVec3::new(3.0, 0.0, 0.0));
        assert_eq!(s[2].parameter, 2.0);
    }

    #[test]
    fn tolerances_are_checked() {
        let knots = KnotVector::try_open_uniform(3, 2).unwrap();
        let h = line(&[DVec3::ZERO, DVec3::Y, DVec3::X]);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                flatten_homogeneous(&knots, &h, bad),
                Err(CurveError::BadTolerance { .. })
            ));
        }
        assert!(matches!(
            flatten_homogeneous(&knots, &h, 1e-300),
            Err(CurveError::TooManySegments { .. })
        ));
    }

    #[test]
    fn halving_meets_in_the_middle() {
        let piece = line(&[DVec3::ZERO, DVec3::Y * 2.0, DVec3::X * 2.0]);
        let (l, r) = halve(&piece);
        assert_eq!(l[2], r[0]);
        assert_eq!(l[0], piece[0]);
        assert_eq!(r[2], piece[2]);
        assert_eq!(l[2].truncate(), DVec3::new(0.5, 1.0, 0.0));
    }
}
