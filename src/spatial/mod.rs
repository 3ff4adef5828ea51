//! Spatial structures shared by every layer above: the bounding-volume
//! hierarchy ([`Bvh`]) with its ray walk (generic over a leaf test), pair
//! walk (broad phases over two trees, or one tree with itself) and box
//! queries, and the low-level memory and lane code they need.
//!
//! This layer knows items only by their boxes: it imports [`geom`](crate::geom)
//! and nothing above it. What an item is (a fan triangle, a face, a CSG
//! child) and what is done at a leaf belong to the caller (`query`,
//! `validate`, `csg`). No answer depends on the trees' shapes: every walk
//! is conservative (it may visit a leaf it could have skipped, never skip
//! one it must visit), and the callers decide with exact predicates.

pub mod bvh;
pub(crate) mod raw;
pub(crate) mod rounding;

pub use bvh::{Bvh, LEAF_SIZE, LeafItems};
pub use raw::large_frees::return_large_frees_to_the_system;
