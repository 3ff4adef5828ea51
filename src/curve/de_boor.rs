//! The algorithms on control points, generic over the point type so that
//! plain B-splines (`DVec3`) and rational ones in homogeneous coordinates
//! (`DVec4`) share them: de Boor's evaluation (de Boor 1972), the control
//! points of derivative curves, and Boehm's knot insertion (Boehm 1980).
//! Piegl & Tiller, *The NURBS Book* (1997), chapters 2–5, give all three.

use std::ops::{Add, Mul, Sub};

use super::basis::ratio;
use super::{Approach, KnotVector};

/// A point type the algorithms can combine affinely.
pub(crate) trait ControlPoint:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<f64, Output = Self>
{
    /// The zero vector.
    const ZERO: Self;
}

impl ControlPoint for glam::DVec3 {
    const ZERO: Self = glam::DVec3::ZERO;
}

impl ControlPoint for glam::DVec4 {
    const ZERO: Self = glam::DVec4::ZERO;
}

/// The curve's `order`-th derivative at `t` (order 0: the point), from the
/// polynomial piece on the given side of `t`. `points` must match `knots`
/// and `t` lie in the domain.
pub(crate) fn derivative<T: ControlPoint>(
    knots: &KnotVector,
    points: &[T],
    t: f64,
    order: usize,
    approach: Approach,
) -> T {
    let p = knots.degree();
    if order > p {
        return T::ZERO;
    }
    let span = knots.span(t, approach);
    let values = knots.values();
    // Only the p + 1 points acting on the span matter.
    let mut local: Vec<T> = points[span - p..=span].to_vec();
    // Derivative control points, `order` times: Q_i = q (P_{i+1} − P_i) /
    // (t_{i+q+1} − t_{i+1}) with q the current degree.
    for r in 0..order {
        let q = p - r;
        for j in 0..q {
            let i = span - q + j;
            let scale = ratio(q as f64, values[i + q + 1] - values[i + 1]);
            local[j] = (local[j + 1] - local[j]) * scale;
        }
        local.pop();
    }
    // de Boor on the remaining degree with the knots shifted by `order`.
    let q = p - order;
    for r in 1..=q {
        for j in (r..=q).rev() {
            let i = span - q + j;
            let alpha = ratio(t - values[i], values[i + q - r + 1] - values[i]);
            local[j] = local[j - 1] * (1.0 - alpha) + local[j] * alpha;
        }
    }
    local[q]
}

/// Boehm's insertion of the knot `u` once: the new knots and control points
/// of the same curve. `u` must lie in the domain with multiplicity at most
/// `p` before insertion.
pub(crate) fn insert_knot<T: ControlPoint>(
    knots: &KnotVector,
    points: &[T],
    u: f64,
) -> (KnotVector, Vec<T>) {
    let p = knots.degree();
    let values = knots.values();
    let span = knots.span(u, Approach::FromAbove);
    let mut inserted = Vec::with_capacity(points.len() + 1);
    for j in 0..=points.len() {
        let point = if j + p <= span {
            points[j]
        } else if j > span {
            points[j - 1]
        } else {
            let alpha = ratio(u - values[j], values[j + p] - values[j]);
            points[j - 1] * (1.0 - alpha) + points[j] * alpha
        };
        inserted.push(point);
    }
    (knots.inserted(u), inserted)
}

#[cfg(test)]
mod tests {
    use glam::DVec3;

    use super::*;

    #[test]
    fn insertion_keeps_the_curve() {
        let knots = KnotVector::try_open_uniform(5, 3).unwrap();
        let points: Vec<DVec3> = (0..5)
            .map(|i| DVec3::new(i as f64, (i * i) as f64 % 3.0, 1.0 - i as f64))
            .collect();
        for u in [0.0, 0.3, 1.0, 1.7, 2.0] {
            let (k2, p2) = insert_knot(&knots, &points, u);
            assert_eq!(p2.len(), 6);
            for t in [0.0, 0.25, 0.9, 1.0, 1.5, 2.0] {
                let a = derivative(&knots, &points, t, 0, Approach::FromAbove);
                let b = derivative(&k2, &p2, t, 0, Approach::FromAbove);
                assert!((a - b).length() < 1e-14, "u {u} t {t}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn derivative_of_a_parabola() {
        // Open-uniform quadratic Bézier on [0, 1]: 2(P1 − P0) at 0.
        let knots = KnotVector::try_open_uniform(3, 2).unwrap();
        let points = [
            DVec3::ZERO,
            DVec3::new(1.0, 2.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
        ];
        let d = derivative(&knots, &points, 0.0, 1, Approach::FromAbove);
        assert_eq!(d, DVec3::new(2.0, 4.0, 0.0));
        let dd = derivative(&knots, &points, 0.5, 2, Approach::FromAbove);
        assert_eq!(dd, DVec3::new(0.0, -8.0, 0.0));
        let ddd = derivative(&knots, &points, 0.5, 3, Approach::FromAbove);
        assert_eq!(ddd, DVec3::ZERO);
    }
}
