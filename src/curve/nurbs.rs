//! Rational B-splines (NURBS): a B-spline in homogeneous coordinates
//! `(w P, w)` projected back by dividing by `w`. Conics, circles among
//! them, are exact (Piegl & Tiller 1997, chapter 7).

use glam::{DVec3, DVec4};

use super::bspline::{check_insertion, check_points};
use super::de_boor::{derivative, insert_knot};
use super::flatten::flatten_homogeneous;
use super::{
    Approach, Curve, CurveError, CurveSample, KnotVector, MAX_RATIONAL_DERIVATIVE, MAX_WEIGHT,
    MIN_WEIGHT,
};

/// A rational B-spline `C(t) = Σ N_i(t) w_i P_i / Σ N_i(t) w_i` of degree
/// `p ≥ 1`.
///
/// # Invariants
///
/// - the knot vector serves exactly as many control points as there are,
///   and there is one weight per control point;
/// - every control point is finite; every weight lies in
///   [`MIN_WEIGHT`, `MAX_WEIGHT`] (2^-64 to 2^64)
///   (so the denominator never vanishes and the curve stays in the convex
///   hull of its control points);
/// - the degree is at least 1.
#[derive(Clone, Debug, PartialEq)]
pub struct Nurbs {
    knots: KnotVector,
    /// `(w_i P_i, w_i)`.
    homogeneous: Vec<DVec4>,
}

impl Nurbs {
    /// A rational B-spline from control points, weights and knots.
    ///
    /// # Errors
    ///
    /// As for [`BSpline::try_new`](super::BSpline::try_new), plus
    /// [`CurveError::WeightCount`], [`CurveError::BadWeight`] for a weight
    /// that is not finite and positive and [`CurveError::WeightOutOfRange`]
    /// for one outside `[MIN_WEIGHT, MAX_WEIGHT]` (2^-64 to 2^64).
    pub fn try_new(
        points: Vec<DVec3>,
        weights: Vec<f64>,
        knots: KnotVector,
    ) -> Result<Nurbs, CurveError> {
        check_points(&points, &knots)?;
        if weights.len() != points.len() {
            return Err(CurveError::WeightCount {
                weights: weights.len(),
                points: points.len(),
            });
        }
        if let Some((index, &value)) = weights
            .iter()
            .enumerate()
            .find(|(_, w)| !(w.is_finite() && **w > 0.0))
        {
            return Err(CurveError::BadWeight { index, value });
        }
        if let Some((index, &value)) = weights
            .iter()
            .enumerate()
            .find(|(_, w)| !(MIN_WEIGHT..=MAX_WEIGHT).contains(*w))
        {
            return Err(CurveError::WeightOutOfRange { index, value });
        }
        let homogeneous = points
            .iter()
            .zip(&weights)
            .map(|(&p, &w)| (p * w).extend(w))
            .collect();
        Ok(Nurbs { knots, homogeneous })
    }

    /// The degree `p`.
    #[must_use]
    pub fn degree(&self) -> usize {
        self.knots.degree()
    }

    /// The knot vector.
    #[must_use]
    pub fn knots(&self) -> &KnotVector {
        &self.knots
    }

    /// The control points `P_i` (each `w_i P_i / w_i`, so rounded).
    #[must_use]
    pub fn control_points(&self) -> Vec<DVec3> {
        self.homogeneous
            .iter()
            .map(|h| h.truncate() / h.w)
            .collect()
    }

    /// The weights `w_i`.
    #[must_use]
    pub fn weights(&self) -> Vec<f64> {
        self.homogeneous.iter().map(|h| h.w).collect()
    }

    /// The `order`-th derivative at `t` from one side, by the quotient
    /// rule on the homogeneous curve `A(t) = w(t) C(t)`:
    /// `C⁽ᵏ⁾ = (A⁽ᵏ⁾ − Σ_{i=1..k} C(k, i) w⁽ⁱ⁾ C⁽ᵏ⁻ⁱ⁾) / w`.
    ///
    /// # Errors
    ///
    /// [`CurveError::ParameterOutOfDomain`] for `t` outside the domain,
    /// [`CurveError::DerivativeOrder`] above
    /// [`MAX_RATIONAL_DERIVATIVE`].
    pub fn try_derivative_limit(
        &self,
        t: f64,
        order: usize,
        approach: Approach,
    ) -> Result<DVec3, CurveError> {
        self.knots.check_parameter(t)?;
        if order > MAX_RATIONAL_DERIVATIVE {
            return Err(CurveError::DerivativeOrder {
                order,
                limit: MAX_RATIONAL_DERIVATIVE,
            });
        }
        let h: Vec<DVec4> = (0..=order)
            .map(|k| derivative(&self.knots, &self.homogeneous, t, k, approach))
            .collect();
        let w = h[0].w;
        let mut c: Vec<DVec3> = Vec::with_capacity(order + 1);
        for k in 0..=order {
            let mut v = h[k].truncate();
            let mut binomial = 1.0;
            for i in 1..=k {
                binomial = binomial * (k + 1 - i) as f64 / i as f64;
                v -= c[k - i] * (binomial * h[i].w);
            }
            c.push(v / w);
        }
        Ok(c[order])
    }

    /// The same curve with the knot `u` inserted once.
    ///
    /// # Errors
    ///
    /// As for [`BSpline::try_insert_knot`](super::BSpline::try_insert_knot).
    pub fn try_insert_knot(&self, u: f64) -> Result<Nurbs, CurveError> {
        check_insertion(&self.knots, u)?;
        let (knots, homogeneous) = insert_knot(&self.knots, &self.homogeneous, u);
        Ok(Nurbs { knots, homogeneous })
    }
}

impl Curve for Nurbs {
    fn domain(&self) -> (f64, f64) {
        self.knots.domain()
    }

    fn try_point_at(&self, t: f64) -> Result<DVec3, CurveError> {
        self.try_derivative_limit(t, 0, Approach::FromAbove)
    }

    fn try_derivative_at(&self, t: f64, order: usize) -> Result<DVec3, CurveError> {
        self.try_derivative_limit(t, order, Approach::FromAbove)
    }

    fn try_flatten(&self, tolerance: f64) -> Result<Vec<CurveSample>, CurveError> {
        flatten_homogeneous(&self.knots, &self.homogeneous, tolerance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quarter circle from `(1, 0)` to `(0, 1)`: a rational quadratic
    /// Bézier with middle weight `√2 / 2`.
    fn quarter() -> Nurbs {
        let knots = KnotVector::try_open_uniform(3, 2).unwrap();
        Nurbs::try_new(
            vec![DVec3::X, DVec3::new(1.0, 1.0, 0.0), DVec3::Y],
            vec![1.0, std::f64::consts::FRAC_1_SQRT_2, 1.0],
            knots,
        )
        .unwrap()
    }

    #[test]
    fn a_rational_quadratic_is_a_circle() {
        let q = quarter();
        for i in 0..=16 {
            let t = i as f64 / 16.0;
            let p = q.try_point_at(t).unwrap();
            assert!((p.length() - 1.0).abs() < 4.0 * f64::EPSILON, "{t}: {p}");
            // The tangent of a circle is perpendicular to the radius.
            let d = q.try_derivative_at(t, 1).unwrap();
            assert!(d.dot(p).abs() < 1e-14 * d.length(), "{t}: {d}");
        }
        // A second derivative that points inward (centripetal).
        let dd = q.try_derivative_at(0.5, 2).unwrap();
        assert!(dd.dot(q.try_point_at(0.5).unwrap()) < 0.0);
        assert!(matches!(
            q.try_derivative_at(0.5, usize::MAX),
            Err(CurveError::DerivativeOrder { .. })
        ));
    }

    #[test]
    fn bad_weights_are_named() {
        let knots = KnotVector::try_open_uniform(3, 2).unwrap();
        let points = vec![DVec3::ZERO; 3];
        for (w, index) in [(0.0, 1), (-1.0, 1), (f64::NAN, 1)] {
            let err = Nurbs::try_new(points.clone(), vec![1.0, w, 1.0], knots.clone());
            assert!(
                matches!(err, Err(CurveError::BadWeight { index: i, .. }) if i == index),
                "{err:?}"
            );
        }
        // Regression: a weight of 1e300 overflowed the homogeneous points
        // and a sweep along the curve said "the path's tangent is zero".
        for (w, shown) in [
            (1e300, "1e300"),
            (1e-300, "1e-300"),
            (MAX_WEIGHT * 2.0, "3.6893488147419103e19"),
        ] {
            let err = Nurbs::try_new(points.clone(), vec![1.0, w, 1.0], knots.clone()).unwrap_err();
            assert_eq!(err, CurveError::WeightOutOfRange { index: 1, value: w });
            assert_eq!(
                err.to_string(),
                format!(
                    "weight 1 is {shown}, outside [2^-64, 2^64] (5.421010862427522e-20 to 1.8446744073709552e19); only the weights' ratios shape a curve: scale them all alike"
                )
            );
        }
        for w in [MIN_WEIGHT, MAX_WEIGHT] {
            assert!(Nurbs::try_new(points.clone(), vec![1.0, w, 1.0], knots.clone()).is_ok());
        }
        assert!(matches!(
            Nurbs::try_new(points, vec![1.0; 2], knots),
            Err(CurveError::WeightCount {
                weights: 2,
                points: 3
            })
        ));
    }

    #[test]
    fn insertion_keeps_the_circle() {
        let q = quarter().try_insert_knot(0.3).unwrap();
        assert_eq!(q.weights().len(), 4);
        for i in 0..=8 {
            let t = i as f64 / 8.0;
            let p = q.try_point_at(t).unwrap();
            assert!((p.length() - 1.0).abs() < 4.0 * f64::EPSILON);
        }
    }
}
