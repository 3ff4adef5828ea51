//! Implicit solids: blobby fields, field CSG and marching cubes.
//!
//! A [`Field`] is a scalar function whose solid is `{P : F(P) ≥ ½}`
//! ([`THRESHOLD`]). Kinds:
//!
//! - [`Blobs`]: blobby objects (Blinn 1982), `F(P) = Σ wᵢ g(|P − Pᵢ|, Rᵢ)`
//!   summed from [`Source`]s with a compact [`Falloff`] (default: the
//!   soft-object polynomial of Wyvill, McPheeters and Wyvill 1986). A
//!   uniform grid over the sources' balls makes each sample visit only the
//!   sources whose radius reaches it ([`FieldStats`] shows it).
//! - [`FieldCsg`]: two fields combined by `max` (union), `min`
//!   (intersection) or `min(a, 1 − b)` (difference).
//!
//! [`marching`] meshes any field into a closed, oriented, 2-manifold
//! [`Solid`](crate::mesh::Solid); [`load_json`] reads a field document.
//! Layer: above `geom` and `mesh`, below `scene`.

mod blobs;
mod combine;
mod error;
mod falloff;
mod json;
pub mod marching;
mod scalar_field;
mod source;
mod source_grid;
mod stats;

pub use blobs::Blobs;
pub use combine::FieldCsg;
pub use error::FieldError;
pub use falloff::Falloff;
pub use json::{
    FieldDocument, MAX_DOCUMENT_SOURCES, MAX_JSON_DEPTH, load_json, parse_json, read_document,
};
pub use marching::{
    MAX_SAMPLES, MarchingOptions, Meshed, Placement, SampleGrid, try_mesh, try_mesh_solid,
};
pub use scalar_field::{Field, NodeBox, THRESHOLD, ValueRange};
pub use source::{SOURCE_RANGE, Source};
pub use stats::FieldStats;
