//! Non-rational B-spline curves: evaluation by de Boor's algorithm,
//! derivatives, knot insertion.

use glam::{DVec3, DVec4};

use super::de_boor::{derivative, insert_knot};
use super::flatten::flatten_homogeneous;
use super::{Approach, Curve, CurveError, CurveSample, KnotVector};

/// A B-spline curve `C(t) = Σ N_{i,p+1}(t) P_i` of degree `p ≥ 1` over the
/// domain `[t_p, t_n]`.
///
/// # Invariants
///
/// - the knot vector serves exactly as many control points as there are;
/// - every control point is finite;
/// - the degree is at least 1.
#[derive(Clone, Debug, PartialEq)]
pub struct BSpline {
    knots: KnotVector,
    points: Vec<DVec3>,
}

impl BSpline {
    /// A B-spline from its control points and knots (whose degree it
    /// takes).
    ///
    /// # Errors
    ///
    /// [`CurveError::ZeroDegree`], [`CurveError::ControlPointCount`],
    /// [`CurveError::NonFiniteControlPoint`].
    pub fn try_new(points: Vec<DVec3>, knots: KnotVector) -> Result<BSpline, CurveError> {
        check_points(&points, &knots)?;
        Ok(BSpline { knots, points })
    }

    /// A clamped B-spline of degree `degree` on the open uniform knot
    /// vector ([`KnotVector::try_open_uniform`]): it starts at the first
    /// control point and ends at the last.
    ///
    /// # Errors
    ///
    /// As for [`BSpline::try_new`] and [`KnotVector::try_open_uniform`].
    pub fn try_open_uniform(points: Vec<DVec3>, degree: usize) -> Result<BSpline, CurveError> {
        let knots = KnotVector::try_open_uniform(points.len(), degree)?;
        BSpline::try_new(points, knots)
    }

    /// A B-spline of degree `degree` on the uniform knot vector
    /// ([`KnotVector::try_uniform`]).
    ///
    /// # Errors
    ///
    /// As for [`BSpline::try_new`] and [`KnotVector::try_uniform`].
    pub fn try_uniform(points: Vec<DVec3>, degree: usize) -> Result<BSpline, CurveError> {
        let knots = KnotVector::try_uniform(points.len(), degree)?;
        BSpline::try_new(points, knots)
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

    /// The control points.
    #[must_use]
    pub fn control_points(&self) -> &[DVec3] {
        &self.points
    }

    /// The `order`-th derivative at `t` from one side: at a knot the two
    /// neighbouring polynomial pieces may disagree.
    ///
    /// # Errors
    ///
    /// [`CurveError::ParameterOutOfDomain`] for `t` outside the domain.
    pub fn try_derivative_limit(
        &self,
        t: f64,
        order: usize,
        approach: Approach,
    ) -> Result<DVec3, CurveError> {
        self.knots.check_parameter(t)?;
        Ok(derivative(&self.knots, &self.points, t, order, approach))
    }

    /// The same curve with the knot `u` inserted once (Boehm 1980): one more
    /// control point, the shape unchanged.
    ///
    /// # Errors
    ///
    /// [`CurveError::ParameterOutOfDomain`] for `u` outside the domain,
    /// [`CurveError::KnotMultiplicity`] when `u` is already there
    /// `p + 1` times.
    pub fn try_insert_knot(&self, u: f64) -> Result<BSpline, CurveError> {
        check_insertion(&self.knots, u)?;
        let (knots, points) = insert_knot(&self.knots, &self.points, u);
        Ok(BSpline { knots, points })
    }
}

impl Curve for BSpline {
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
        let homogeneous: Vec<DVec4> = self.points.iter().map(|p| p.extend(1.0)).collect();
        flatten_homogeneous(&self.knots, &homogeneous, tolerance)
    }
}

/// Checks a control polygon against its knots (shared with
/// [`Nurbs`](super::Nurbs)).
pub(crate) fn check_points(points: &[DVec3], knots: &KnotVector) -> Result<(), CurveError> {
    if knots.degree() == 0 {
        return Err(CurveError::ZeroDegree);
    }
    if points.len() != knots.control_point_count() {
        return Err(CurveError::ControlPointCount {
            points: points.len(),
            knots: knots.values().len(),
            degree: knots.degree(),
        });
    }
    if let Some((index, &value)) = points.iter().enumerate().find(|(_, p)| !p.is_finite()) {
        return Err(CurveError::NonFiniteControlPoint { index, value });
    }
    Ok(())
}

/// Whether `u` may be inserted into `knots`.
pub(crate) fn check_insertion(knots: &KnotVector, u: f64) -> Result<(), CurveError> {
    knots.check_parameter(u)?;
    let multiplicity = knots.multiplicity(u);
    if multiplicity > knots.degree() {
        return Err(CurveError::KnotMultiplicity {
            index: knots.values().partition_point(|&k| k < u),
            value: u,
            multiplicity: multiplicity + 1,
            degree: knots.degree(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wave() -> BSpline {
        let points = (0..6)
            .map(|i| DVec3::new(i as f64, if i % 2 == 0 { 0.0 } else { 1.0 }, 0.0))
            .collect();
        BSpline::try_open_uniform(points, 3).unwrap()
    }

    #[test]
    fn clamped_curves_interpolate_their_end_points() {
        let c = wave();
        assert_eq!(c.domain(), (0.0, 3.0));
        assert_eq!(c.try_point_at(0.0).unwrap(), DVec3::ZERO);
        assert_eq!(c.try_point_at(3.0).unwrap(), DVec3::new(5.0, 1.0, 0.0));
        // End tangent of a clamped curve: p (P1 − P0) / (t_{p+1} − t_1).
        assert_eq!(
            c.try_derivative_at(0.0, 1).unwrap(),
            DVec3::new(3.0, 3.0, 0.0)
        );
    }

    #[test]
    fn bad_arguments_are_errors() {
        let c = wave();
        assert!(matches!(
            c.try_point_at(3.5),
            Err(CurveError::ParameterOutOfDomain { .. })
        ));
        assert!(c.try_point_at(f64::NAN).is_err());
        let knots = KnotVector::try_open_uniform(4, 2).unwrap();
        assert!(matches!(
            BSpline::try_new(vec![DVec3::ZERO; 3], knots.clone()),
            Err(CurveError::ControlPointCount { points: 3, .. })
        ));
        let mut points = vec![DVec3::ZERO; 4];
        points[2].y = f64::INFINITY;
        assert!(matches!(
            BSpline::try_new(points, knots),
            Err(CurveError::NonFiniteControlPoint { index: 2, .. })
        ));
        let k0 = KnotVector::try_new(vec![0., 1.], 0).unwrap();
        assert_eq!(
            BSpline::try_new(vec![DVec3::ZERO], k0),
            Err(CurveError::ZeroDegree)
        );
    }

    #[test]
    fn knot_insertion_up_to_full_multiplicity() {
        let mut c = wave();
        for _ in 0..3 {
            c = c.try_insert_knot(1.5).unwrap();
        }
        assert_eq!(c.knots().multiplicity(1.5), 3);
        // At multiplicity p the curve passes through a control point.
        let at = c.try_point_at(1.5).unwrap();
        assert!(
            c.control_points()
                .iter()
                .any(|p| (*p - at).length() < 1e-14),
            "{at} is not a control point"
        );
        c = c.try_insert_knot(1.5).unwrap();
        assert!(matches!(
            c.try_insert_knot(1.5),
            Err(CurveError::KnotMultiplicity {
                multiplicity: 5,
                ..
            })
        ));
    }
}
