//! Ray-cast CSG (Roth's method, 1982): trees of primitives
//! combined by union, intersection and difference, answered along rays.
//!
//! - A [`Primitive`] answers a ray with whether its origin is inside and the
//!   sorted crossings `t > 0`, a point with a [`Containment`], and gives its
//!   bounds. Kinds: [`HalfSpace`] (exact), [`AxisBox`], [`Sphere`],
//!   [`Cylinder`] and [`Transformed`].
//! - A [`Csg`] tree (built from a [`CsgExpr`]) combines two children's
//!   answers with Roth's four-state machine ([`merge()`]).
//! - Answers: [`Spans`] of a ray, the [`FirstHit`] with its normal when
//!   asked, point classification right at coincident faces, and volume by
//!   integrating span lengths ([`VolumeEstimate`]).
//! - Octree cells: how a closed box lies against a primitive
//!   ([`CellRelation`]) and against a tree ([`Csg::cell_verdict`]).
//! - Every query adds to a [`Stats`] value, so tests can check that only the
//!   needed work was done.
//!
//! Scene files (JSON) are read one layer up, in `wingedge::scene`.

mod axis_box;
mod cell_relation;
mod classify;
mod crossing_order;
mod cylinder;
mod evaluate;
mod halfspace;
mod local_cone;
mod merge;
mod polyhedron;
mod primitive;
mod sphere;
mod stats;
mod structure;
mod tessellate;
mod trace;
mod transform;
mod tree;
mod volume;

/// Where a point lies: the query layer's three-way answer.
pub use crate::query::Containment;
pub use axis_box::{AxisBox, AxisBoxError};
pub use cell_relation::{CellRelation, CellVerdict, LeafSides, LeafTileError};
pub use classify::Neighbourhood;
pub use crossing_order::{CrossingPlane, compare_exactly};
pub use cylinder::{Cylinder, CylinderError};
pub use evaluate::{EvaluateError, EvaluateOptions, Evaluated, LeafFace, evaluate};
pub use halfspace::{HalfSpace, HalfSpaceError};
pub use local_cone::{LocalPlane, MAX_PLANES_AT_A_POINT};
pub use merge::{Hit, MergeState, merge, merge_by, oriented_normal};
pub use polyhedron::{Polyhedron, PolyhedronError};
pub use primitive::{Crossing, Primitive, SurfaceId, normal_alignment, perturbed_side};
pub use sphere::{Sphere, SphereError};
pub use stats::Stats;
pub use structure::StructureWork;
pub use tessellate::{DEFAULT_TOLERANCE, MAX_SEGMENTS, TessellateError, segments_for};
pub use trace::{FirstHit, MAX_ORIGIN_DISTANCE, Spans};
pub use transform::{TransformError, Transformed};
pub use tree::{Csg, CsgError, CsgExpr, Leaf, LeafId};
pub use volume::{
    DEFAULT_VOLUME_CELLS, MAX_VOLUME_RAYS, MIN_CELLS_ACROSS_LEAF, Unresolved, VolumeError,
    VolumeEstimate,
};
