//! What sweeps and revolves need from a curve, whether plain or rational.

use glam::DVec3;

use super::CurveError;

/// One point of a flattened curve: its parameter and position.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CurveSample {
    /// The curve parameter.
    pub parameter: f64,
    /// The curve's point there.
    pub point: DVec3,
}

/// A parametric curve over a closed domain: [`BSpline`](super::BSpline)
/// and [`Nurbs`](super::Nurbs).
pub trait Curve {
    /// The parameter domain `[start, end]`.
    fn domain(&self) -> (f64, f64);

    /// The point at `t`.
    ///
    /// # Errors
    ///
    /// [`CurveError::ParameterOutOfDomain`] for `t` outside the domain.
    fn try_point_at(&self, t: f64) -> Result<DVec3, CurveError>;

    /// The `order`-th derivative at `t` (order 0 is the point), from the
    /// piece starting at `t` (from below at the end of the domain).
    ///
    /// # Errors
    ///
    /// [`CurveError::ParameterOutOfDomain`] for `t` outside the domain.
    fn try_derivative_at(&self, t: f64, order: usize) -> Result<DVec3, CurveError>;

    /// A polyline within `tolerance × size` of the curve, where `size` is
    /// the diagonal of the control points' bounding box (which holds the
    /// curve): samples from the start of the domain to its end, in order.
    ///
    /// # Errors
    ///
    /// [`CurveError::BadTolerance`] unless `tolerance` is finite and
    /// positive; [`CurveError::TooManySegments`] when more than
    /// [`MAX_SEGMENTS`](super::MAX_SEGMENTS) segments would be needed.
    fn try_flatten(&self, tolerance: f64) -> Result<Vec<CurveSample>, CurveError>;
}
