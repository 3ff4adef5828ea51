//! B-spline and NURBS curves: the Cox–de Boor basis, de Boor evaluation,
//! derivatives, knot insertion and adaptive flattening to a chord
//! tolerance.
//!
//! This layer sits above [`geom`](crate::geom) and below
//! [`mesh`](crate::mesh), whose sweep, revolve and loft builders take
//! curves. Degrees are `p`, orders `k = p + 1`; knots and control points
//! are indexed from 0. Curves are evaluated in floating point
//! (constructions); no sign is decided here.

mod basis;
mod bspline;
mod de_boor;
mod error;
mod flatten;
mod knots;
mod nurbs;
mod parametric;

pub use basis::basis;
pub use bspline::BSpline;
pub use error::CurveError;
pub use knots::{Approach, KnotVector};
pub use nurbs::Nurbs;
pub use parametric::{Curve, CurveSample};

/// The most segments a flattening (or a revolve) may produce; a tolerance
/// that would need more is refused with [`CurveError::TooManySegments`].
pub const MAX_SEGMENTS: usize = 1 << 17;

/// The highest derivative order of a [`Nurbs`] (the quotient rule needs all
/// lower ones); plain [`BSpline`] derivatives of any order are fine.
pub const MAX_RATIONAL_DERIVATIVE: usize = 32;
