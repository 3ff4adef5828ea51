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
//! [`geom`] (numbers) → [`curve`] (B-spline and NURBS curves) →
//! [`spatial`] (the shared BVH: ray walk, pair walk, box queries) →
//! [`mesh`] (topology) → [`io`] (OBJ in and out) → [`validate`] (named
//! checks and a graded verdict) and [`query`] (line–face, ray–solid,
//! point-in-polyhedron) → [`boolean`] (exact boundary evaluation: union,
//! intersection and difference into valid solids) → [`csg`] (ray-cast CSG:
//! primitives, trees, the span merge, tree evaluation by booleans) → [`cells`] (octree cells In, Out or On, certified volumes) →
//! [`field`] (implicit solids: blobby fields, field CSG, marching
//! cubes to a valid solid) → [`scene`] (the JSON scene format; a mesh or a
//! scene as one query target) → [`render`] (images).
#![warn(missing_docs)]

pub mod boolean;
pub mod cells;
mod compressed_rows;
pub mod csg;
pub mod curve;
mod disjoint_sets;
pub mod field;
mod fixed_chunks;
pub mod geom;
pub mod io;
pub mod mesh;
pub mod query;
pub mod render;
pub mod scene;
pub mod shape;
pub mod spatial;
#[cfg(test)]
mod test_rng;
pub mod validate;

pub use glam;

/// The README's code blocks, compiled and run as doctests.
#[doc = include_str!("../README.md")]
#[cfg(doctest)]
pub struct ReadmeDoctests;
