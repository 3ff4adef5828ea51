//! Euler operators: the topological edits of a solid that keep the
//! Euler–Poincaré formula `V − E + F − R = 2 (S − H)` (Mäntylä 1988).
//!
//! Each operator is a method on [`Solid`](super::Solid) that changes a bounded number of
//! records and walks at most the loops and vertex stars it touches (O(1) or
//! O(degree)). Its pre-condition is checked before anything changes: when it
//! does not hold, or an id is stale or names no element of this solid, the
//! operator returns an [`EulerError`] naming the ids and the solid is left
//! exactly as it was. (Ids carry no mark of the solid that issued them: an
//! id of another solid is refused when it names nothing here, as it almost
//! always does, but one that happens to name an element of this solid is
//! taken for that element.) After every operator
//! [`check_consistency`](super::Solid::check_consistency) holds.
//!
//! | operator | inverse | V | E | F | R | S | H |
//! |---|---|---|---|---|---|---|---|
//! | [`mvfs`](super::Solid::mvfs) | [`kvfs`](super::Solid::kvfs) | +1 | | +1 | | +1 | |
//! | [`mev`](super::Solid::mev) | [`kev`](super::Solid::kev) | +1 | +1 | | | | |
//! | [`mef`](super::Solid::mef) | [`kef`](super::Solid::kef) | | +1 | +1 | | | |
//! | [`kemr`](super::Solid::kemr) | [`mekr`](super::Solid::mekr) | | −1 | | +1 | | |
//! | [`kfmrh`](super::Solid::kfmrh) | [`mfkrh`](super::Solid::mfkrh) | | | −1 | +1 | | +1 (or S −1) |
//! | [`split_edge`](super::Solid::split_edge) | [`join_edges`](super::Solid::join_edges) | +1 | +1 | | | | |
//!
//! The operators are topological: they place new vertices where they are
//! told and never move one. A face an operator creates gets the Newell plane
//! of its outer loop; the faces it changes keep their planes.
//! [`split_face`](super::Solid::split_face) and
//! [`extrude_face`](super::Solid::extrude_face) are the editing
//! operations built on them that also keep the geometry right.
//!
//! Operators name a place in a loop by a [`Corner`]: the corner after an edge
//! use (at the vertex where that use ends), or a loop that is a lone vertex.
//! [`corner`](super::Solid::corner) finds the corner of a vertex on a face.
//!
//! # Example: a cube with a square hole through it
//!
//! ```
//! use glam::DVec3;
//! use wingedge::mesh::{EulerError, Solid};
//!
//! # fn main() -> Result<(), EulerError> {
//! let square = |r: f64| [(-r, -r), (r, -r), (r, r), (-r, r)].map(|(x, y)| DVec3::new(x, y, 0.0));
//! // A square lamina (mvfs, 3 × mev, mef): a top face and a bottom face.
//! let (mut solid, top, bottom) = Solid::try_lamina(&square(2.0))?;
//! // A ring in the top face and a face filling it (4 × mev, mef, kemr).
//! let plug = solid.add_ring(top, &square(1.0))?;
//! // The filling face becomes a ring of the bottom face: a hole through.
//! solid.kfmrh(bottom, plug)?;
//! // The top face, outer loop and ring, swept up (8 × mev, 8 × mef).
//! solid.extrude_face(top, DVec3::Z)?;
//! assert_eq!((solid.vertex_count(), solid.edge_count(), solid.face_count()), (16, 24, 10));
//! assert_eq!(solid.ring_count(), 2);
//! assert_eq!(solid.shells()[0].genus(), Some(1));
//! assert_eq!(solid.volume(), 12.0);
//! assert!(solid.check_consistency().is_ok());
//! # Ok(())
//! # }
//! ```

mod corner;
mod edge_face;
mod edge_ring;
mod edge_vertex;
mod edit;
mod error;
mod face_ring;
mod from_polygons;
mod lamina;
mod links;
mod merge_faces;
mod split_edge;
mod vertex_face_shell;

pub use corner::Corner;
pub use error::EulerError;
