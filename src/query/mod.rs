//! Queries: line–face intersection, ray–solid crossings and point-in-polyhedron.
//!
//! A polygon soup that cannot be built into a solid (an edge of three
//! faces, faces wound against their neighbours) still has a winding number:
//! [`SoupWinding`] builds the same triangles and answers inside/outside by
//! it.
//!
//! Every query runs against an [`Accel`], built once per solid
//! ([`Accel::new`]) and shared (it is `Sync`) by any number of queries and
//! threads. The accel holds a fan triangulation of every face (exact input
//! coordinates, each triangle remembering its [`FaceId`](crate::mesh::FaceId)),
//! a bounding-volume hierarchy for rays in any direction (`f32` boxes stored
//! relative to the solid's centre, rounded outward, so culling works as well
//! far from the origin as near it; each leaf's triangles also in `f32`,
//! four side by side, for a filter that proves most misses before the exact
//! test), and a uniform grid over the `yz` projection for the `±x` parity
//! rays of point classification, each cell's triangles sorted by their
//! smallest `x` (built by the first point query: a scene that only casts
//! rays never pays for it).
//!
//! # What "exact" means here
//!
//! - Every sign is decided by exact predicates on input coordinates
//!   ([`orient2d`](crate::geom::orient2d), [`orient3d`](crate::geom::orient3d),
//!   [`line_side`](crate::geom::line_side)): a point exactly on a face, edge or
//!   vertex is [`Containment::OnBoundary`]; a point one ulp away is not.
//! - Rays through edges and vertices, and rays lying in a face's plane, are
//!   resolved by Simulation of Simplicity: the ray is moved symbolically (see
//!   [`line_side_sos`](crate::geom::line_side_sos) and [`Accel::classify`]),
//!   deterministically and independently of face order. A ray through an edge
//!   or a vertex therefore crosses once, a ray grazing a silhouette crosses 0
//!   or 2 times, never 1.
//! - Crossing parameters `t` and the generalized winding number are rounded
//!   constructions; no decision depends on them, except that crossings are
//!   *listed* in order of their rounded `t`.

mod accel;
mod boundary_tiles;
mod first_hit;
mod line_face;
mod point_batch;
mod point_in_convex;
mod point_in_solid;
mod ray_answers;
mod ray_scaling;
mod ray_solid;
mod ray_triangle;
mod soup_winding;
#[cfg(test)]
mod stress_points;
mod winding;
mod x_direction;
mod x_ray;
mod x_ray_triangle;

pub use accel::NotConvex;
pub use accel::{Accel, AccelStats};
pub use boundary_tiles::{BoundaryTiles, TileError};
pub use line_face::{LineFaceHit, LineKind, intersect_line_face};
pub use point_in_solid::Method;
pub use ray_answers::{Crossing, RayCrossings, Transition, TraversalStats};
pub use soup_winding::SoupWinding;

use thiserror::Error;

/// Where a point is relative to a solid.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Containment {
    /// Strictly inside.
    Inside,
    /// Strictly outside.
    Outside,
    /// Exactly on a face, edge or vertex.
    OnBoundary,
}

impl Containment {
    /// The word used by the command line: `inside`, `outside` or `boundary`.
    #[must_use]
    pub fn as_word(self) -> &'static str {
        match self {
            Containment::Inside => "inside",
            Containment::Outside => "outside",
            Containment::OnBoundary => "boundary",
        }
    }
}

/// Why a query could not be answered.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum QueryError {
    /// A query point has a NaN or infinite coordinate.
    #[error("point {index} {} has a non-finite coordinate", crate::geom::ReadableVec(*point))]
    NonFinitePoint {
        /// The point's index in the batch (0 for a single query).
        index: usize,
        /// The point.
        point: glam::DVec3,
    },
    /// A ray has a non-finite origin or direction, or a zero direction.
    #[error(
        "ray {index} (origin {}, direction {}) is not valid: origin and direction must be finite and the direction non-zero",
        crate::geom::ReadableVec(*origin),
        crate::geom::ReadableVec(*direction)
    )]
    InvalidRay {
        /// The ray's index in the batch (0 for a single query).
        index: usize,
        /// Its origin.
        origin: glam::DVec3,
        /// Its direction.
        direction: glam::DVec3,
    },
    /// A valid ray whose answer `f64` cannot hold: its origin lies so far
    /// from a scene that `t` could not tell the scene's features apart, or
    /// a crossing's `t` overflows (a direction too short) or underflows (too
    /// long).
    #[error(
        "ray {index} (origin {}, direction {}) cannot be answered in f64: {reason}",
        crate::geom::ReadableVec(*origin),
        crate::geom::ReadableVec(*direction)
    )]
    RayOutOfRange {
        /// The ray's index in the batch (0 for a single query).
        index: usize,
        /// Its origin.
        origin: glam::DVec3,
        /// Its direction.
        direction: glam::DVec3,
        /// What does not fit.
        reason: &'static str,
    },
    /// Parity and ray crossings need a closed surface (every edge with two
    /// faces); use the winding number for open input.
    #[error(
        "the solid is not closed ({boundary_edges} edges have only one face); inside/outside by parity is undefined, use the winding number"
    )]
    NotClosed {
        /// How many boundary edges the solid has.
        boundary_edges: usize,
    },
    /// The normals method was asked of a solid that is not convex.
    #[error("the normals method needs a convex solid: {0}")]
    NotConvex(NotConvex),
}
