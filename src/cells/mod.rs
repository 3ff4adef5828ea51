//! Space subdivision: the cells of an octree laid over a solid or a CSG
//! tree, each `In`, `Out` or `On` its boundary, with a certified volume
//! interval.
//!
//! `target` says how a cell lies against a solid or a tree; `octree`
//! refines the cells the boundary may meet and labels the others; `npy`
//! writes the dense voxel array numpy reads; `in_shell` makes the `In`
//! cells' outer faces a valid closed solid. The exact closed box–triangle
//! test is [`box_meets_triangle`] (in `geom`).

mod in_shell;
mod label;
mod npy;
mod octree;
mod target;
mod walk;

pub use crate::geom::box_meets_triangle;
pub use in_shell::{InShell, SUBDIVISION};
pub use label::{Cell, Label};
pub use npy::write_npy;
pub use octree::{CellsError, LevelCounts, MAX_DENSE_DEPTH, MAX_DEPTH, Octree};
