//! # wingedge
//!
//! A B-rep polyhedron kernel built on Baumgart's winged-edge structure.
//!
//! ## Conventions
//!
//! - Right-handed coordinates, `f64` throughout ([`glam::DVec3`]).
//! - A face's vertices run counter-clockwise seen from outside the solid, so
//!   face normals point outward.
//! - A plane is `A x + B y + C z + D = 0` with unit `(A, B, C)`;
//!   `A x + B y + C z + D > 0` is the outside (the side the normal points to).
//! - Signs are decided exactly ([`geom::orient3d`]); tolerances exist only for
//!   user-level judgements and are relative to the model's bounding box
//!   ([`geom::Tolerance`]).
//!
//! ## Layers
//!
//! Each layer uses only the layers before it:
//! [`geom`] (numbers: exact predicates, implicit points, planes, polygons) →
//! [`spatial`] (the shared BVH: ray walk, pair walk, box queries) →
//! [`curve`] (B-spline and NURBS curves) → [`mesh`] (the winged-edge
//! topology, Euler operators, builders, measures) → [`shape`] (sweeps,
//! revolves and lofts of curves) → [`io`] (OBJ in and out, JSON readers) →
//! [`query`] (line–face, ray–solid, point-in-polyhedron, winding number) and
//! [`validate`] (named checks and a graded verdict) → [`boolean`] (exact
//! boundary evaluation into valid solids) → [`csg`] (ray-cast CSG:
//! primitives, trees, the span merge, tree evaluation by booleans) →
//! [`field`] (blobby fields, field CSG, marching cubes) and [`cells`]
//! (octree cells, certified volumes) → [`scene`] (the JSON scene format; a
//! mesh or a scene as one query target) → [`render`] (images).
//!
//! [`SetOp`] is the one set operator of booleans, ray-cast CSG and field
//! CSG; [`Error`] wraps every layer's error for callers that use `?`.
#![warn(missing_docs)]

pub mod boolean;
pub mod cells;
mod compressed_rows;
pub mod csg;
pub mod curve;
mod disjoint_sets;
mod error;
pub mod field;
mod fixed_chunks;
pub mod geom;
pub mod io;
pub mod mesh;
pub mod query;
pub mod render;
pub mod repair;
pub mod scene;
mod set_op;
pub mod shape;
pub mod spatial;
#[cfg(test)]
mod test_rng;
pub mod validate;

pub use error::Error;
pub use glam;
pub use set_op::SetOp;

/// The README's code blocks, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
