//! Space subdivision: the cells of an octree laid over a solid, each `In`,
//! `Out` or `On` its boundary, decided exactly, with a certified volume
//! interval.
//!
//! `box_triangle` is the exact closed box–triangle test; `octree` refines
//! the cells the boundary meets and labels the others by propagation;
//! `npy` writes the dense voxel array numpy reads.

mod in_shell;
mod npy;
mod octree;
mod target;

pub use crate::geom::box_meets_triangle;
pub use in_shell::{InShell, SUBDIVISION};
pub use npy::write_npy;
pub use octree::{Cell, CellsError, Label, LevelCounts, MAX_DENSE_DEPTH, MAX_DEPTH, Octree};
