//! The shared bounding-volume hierarchy.
//!
//! `node` holds the tree's types (binary and eight-wide nodes, the frame
//! of their `f32` boxes, a leaf's items); every algorithm is a file of its
//! own that imports them: the binned SAH build (`build`), the collapse
//! into eight-wide nodes (`collapse`), the tree (`tree`), the ray walk
//! generic over a leaf test (`ray_walk`) with its slab set-up
//! (`ray_box`) and one node opener per instruction set (`open`,
//! `open_portable`, `open_avx2`, `open_avx512`, and `open_widest`, which
//! runs a walk with the widest the processor has), the pair walk of
//! broad phases (`pair_walk`) and box queries (`box_query`).

pub(crate) mod box_query;
pub(crate) mod build;
pub(crate) mod collapse;
pub(crate) mod node;
pub(crate) mod open;
#[cfg(target_arch = "x86_64")]
pub(crate) mod open_avx2;
#[cfg(target_arch = "x86_64")]
pub(crate) mod open_avx512;
pub(crate) mod open_portable;
pub(crate) mod open_widest;
pub(crate) mod pair_walk;
pub(crate) mod ray_box;
pub(crate) mod ray_walk;
pub(crate) mod tree;

pub use build::LEAF_SIZE;
pub use node::LeafItems;
pub(crate) use node::{BoxFrame, LEAF, Node8, WIDTH};
pub(crate) use open::NodeLanes;
#[cfg(test)]
pub(crate) use open::for_each_lanes;
#[cfg(test)]
pub(crate) use open_portable::Portable;
pub(crate) use open_widest::{LanesJob, with_widest_lanes};
pub(crate) use ray_box::{Deferred, RayBox, limit_key};
pub(crate) use ray_walk::RayLeaves;
pub use tree::Bvh;
