//! Why a curve cannot be built, evaluated or flattened.

use thiserror::Error;

/// A bad argument to a curve: each variant names the argument (knot,
/// control point, weight, parameter, tolerance) and carries its value.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CurveError {
    /// A knot is NaN or infinite.
    #[error("knot {index} is not finite: {}", crate::geom::Readable(*.value))]
    NonFiniteKnot {
        /// Its index in the knot vector.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// The knot vector decreases somewhere.
    #[error("the knots decrease at index {index}: {} is followed by {}", crate::geom::Readable(*.previous), crate::geom::Readable(*.next))]
    DecreasingKnots {
        /// The index of the smaller, later knot.
        index: usize,
        /// The knot before it.
        previous: f64,
        /// The knot at `index`.
        next: f64,
    },
    /// Fewer knots than the degree needs (`2 · (degree + 1)`).
    #[error("{count} knots are too few for degree {degree}: at least {needed} are needed")]
    TooFewKnots {
        /// How many knots were given.
        count: usize,
        /// The degree.
        degree: usize,
        /// The least number of knots for that degree.
        needed: usize,
    },
    /// A knot value repeated more than `degree + 1` times.
    #[error("knot {} at index {index} is repeated {multiplicity} times; degree {degree} allows at most {}", crate::geom::Readable(*.value), .degree + 1)]
    KnotMultiplicity {
        /// Where its run of copies starts.
        index: usize,
        /// The knot.
        value: f64,
        /// How many copies there are.
        multiplicity: usize,
        /// The degree.
        degree: usize,
    },
    /// A curve of degree 0: a set of separate points, not a curve.
    #[error("a curve needs degree 1 or more; degree 0 gives separate points")]
    ZeroDegree,
    /// The parameter domain `[t_p, t_n]` has zero length.
    #[error("the domain [{}, {}] of the knot vector is empty", crate::geom::Readable(*.start), crate::geom::Readable(*.end))]
    EmptyDomain {
        /// `t_p`.
        start: f64,
        /// `t_n` (`n` control points).
        end: f64,
    },
    /// The number of control points does not match the knots and degree.
    #[error(
        "{points} control points do not fit {knots} knots of degree {degree}: {} are needed",
        .knots - .degree - 1
    )]
    ControlPointCount {
        /// How many control points were given.
        points: usize,
        /// How many knots there are.
        knots: usize,
        /// The degree.
        degree: usize,
    },
    /// A control point is NaN or infinite.
    #[error("control point {index} is not finite: {value}")]
    NonFiniteControlPoint {
        /// Its index.
        index: usize,
        /// Its value.
        value: glam::DVec3,
    },
    /// The number of weights differs from the number of control points.
    #[error("{weights} weights for {points} control points")]
    WeightCount {
        /// How many weights were given.
        weights: usize,
        /// How many control points there are.
        points: usize,
    },
    /// A weight that is not a finite positive number.
    #[error("weight {index} is {}; weights must be finite and > 0", crate::geom::Readable(*.value))]
    BadWeight {
        /// Its index.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A weight outside [`MIN_WEIGHT`, `MAX_WEIGHT`]: the rational
    /// evaluation would overflow or underflow.
    ///
    /// [`MIN_WEIGHT`]: super::MIN_WEIGHT
    /// [`MAX_WEIGHT`]: super::MAX_WEIGHT
    #[error(
        "weight {index} is {}, outside [2^-64, 2^64] ({} to {}); only the weights' ratios shape a curve: scale them all alike",
        crate::geom::Readable(*.value),
        crate::geom::Readable(super::MIN_WEIGHT),
        crate::geom::Readable(super::MAX_WEIGHT)
    )]
    WeightOutOfRange {
        /// Its index.
        index: usize,
        /// Its value.
        value: f64,
    },
    /// A parameter outside the curve's domain (or NaN).
    #[error("parameter {} is outside the domain [{}, {}]", crate::geom::Readable(*.t), crate::geom::Readable(*.start), crate::geom::Readable(*.end))]
    ParameterOutOfDomain {
        /// The parameter.
        t: f64,
        /// Start of the domain.
        start: f64,
        /// End of the domain.
        end: f64,
    },
    /// A derivative order beyond what rational evaluation supports.
    #[error("derivative order {order} is above the supported {limit}")]
    DerivativeOrder {
        /// The order asked for.
        order: usize,
        /// The largest supported ([`MAX_RATIONAL_DERIVATIVE`](super::MAX_RATIONAL_DERIVATIVE)).
        limit: usize,
    },
    /// A basis function index beyond the knot vector.
    #[error("basis function N({index}, {order}) needs knot {} but there are {knots}", .index + .order)]
    BasisIndex {
        /// `i` in `N_{i,k}`.
        index: usize,
        /// `k` in `N_{i,k}` (the order, degree + 1).
        order: usize,
        /// How many knots there are.
        knots: usize,
    },
    /// A chord tolerance that is not a finite positive number.
    #[error("the chord tolerance {} must be finite and > 0", crate::geom::Readable(*.tolerance))]
    BadTolerance {
        /// The tolerance (a fraction of the curve's size).
        tolerance: f64,
    },
    /// Flattening to the chord tolerance would need more segments than the
    /// stated limit.
    #[error("flattening to the chord tolerance {} needs more than {limit} segments", crate::geom::Readable(*.tolerance))]
    TooManySegments {
        /// The tolerance (a fraction of the curve's size).
        tolerance: f64,
        /// The limit ([`MAX_SEGMENTS`](super::MAX_SEGMENTS)).
        limit: usize,
    },
}
