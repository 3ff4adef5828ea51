//! One check per file, each named after what is wrong.
//!
//! Soup checks take the shared [`Context`](super::context::Context) and
//! work on any input; [`shell_oriented_inward`] needs the winged-edge solid.

pub(crate) mod degenerate_face;
pub(crate) mod duplicate_face;
pub(crate) mod edge_in_more_than_two_faces;
pub(crate) mod edge_in_one_face;
pub(crate) mod edge_without_two_distinct_vertices;
pub(crate) mod face_with_fewer_than_three_edges;
pub(crate) mod face_with_fewer_than_three_vertices;
pub(crate) mod inconsistent_orientation;
pub(crate) mod non_manifold_vertex;
pub(crate) mod non_planar_face;
pub(crate) mod self_intersection;
pub(crate) mod shell_oriented_inward;
pub(crate) mod unreferenced_vertex;
pub(crate) mod vertex_in_fewer_than_three_edges;
pub(crate) mod vertex_in_fewer_than_three_faces;
