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

/// The smallest weight a [`Nurbs`] takes, 2^-64: with weights in
/// `[MIN_WEIGHT, MAX_WEIGHT]` the homogeneous control points `w P` and their
/// derivatives stay far inside f64 for coordinates up to 1e100 (a weight of
/// 1e300 overflowed them, and the overflow read as a zero tangent). Only
/// ratios of weights shape a curve: scale them all alike to bring them in.
pub const MIN_WEIGHT: f64 = 5.421010862427522e-20;

/// The largest weight a [`Nurbs`] takes, 2^64 (see [`MIN_WEIGHT`]).
pub const MAX_WEIGHT: f64 = 18446744073709551616.0;
