//! Implicit points (intersections kept as their definitions) and exact
//! predicates on them: the numbers of boundary evaluation.
//!
//! See [`ImplicitPoint`] for why a constructed point is never rounded
//! before every decision about it is made.

mod arithmetic;
mod double_double;
mod interval;
mod point;
mod predicates;

pub(crate) use arithmetic::Arithmetic;
pub(crate) use interval::Interval;
pub use point::ImplicitPoint;
pub(crate) use point::{Centroid, HasHomogeneous, Homogeneous, enclosing_box, kept_axes};
pub(crate) use predicates::{
    XRayCrossing, compare_axis, orient2d_projected, rounded_point, times, x_ray_crossing,
};
pub use predicates::{compare_points, orient2d_points, point_side_of_plane, rounded};
