//! The three places a cell can be, and a labelled leaf of the octree.

/// Where a cell is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Label {
    /// Inside the solid: the boundary does not meet the closed cell.
    In,
    /// Outside the solid: the boundary does not meet the closed cell.
    Out,
    /// The boundary meets the closed cell (only at the finest depth); for
    /// a CSG tree with curved leaves, may meet it.
    On,
}

/// A leaf of the octree: cell `(x, y, z)` of the `2^depth` cells along each
/// side at `depth`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Cell {
    /// Its depth (0: the root).
    pub depth: u32,
    /// Its index along `x` at its depth.
    pub x: u32,
    /// Its index along `y`.
    pub y: u32,
    /// Its index along `z`.
    pub z: u32,
    /// Where it is.
    pub label: Label,
}
