//! Topology: the winged-edge solid, its invariants, traversal, builders and
//! measures.
//!
//! A [`Solid`] holds four slotmap tables — vertices, edges, faces and the
//! faces' loops — linked as in Baumgart's winged-edge structure (see
//! [`Edge`]); a face has an outer loop and any number of rings ([`Loop`]).
//! Solids are built from an indexed [`PolygonSoup`] by
//! [`Solid::try_from_soup`] or by the [`builders`], and changed by the
//! Euler operators of [`euler`]; the nine adjacency relations are iterators
//! in [`traverse`](Solid::vertex_edges).

mod build;
pub mod builders;
mod consistency;
mod edge;
pub mod euler;
mod face;
mod face_loop;
mod face_triangles;
mod ids;
mod measure;
mod moved;
mod solid;
mod soup;
mod traverse;
mod vertex;

pub use build::BuildError;
pub(crate) use build::{RepeatedVertices, check_buildable, check_polygons};
pub use consistency::ConsistencyError;
pub use edge::{Edge, EdgeUse, Side};
pub use euler::{Corner, EulerError};
pub use face::{Face, FaceAttributes};
pub use face_loop::{Loop, LoopStart};
pub use ids::{EdgeId, FaceId, LoopId, VertexId};
pub use measure::Shell;
pub use solid::Solid;
pub use soup::{Polygon, PolygonSoup};
pub use traverse::{LoopWalk, StarWalk};
pub use vertex::Vertex;
