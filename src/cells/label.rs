//! The three places a cell can be.

/// Where a cell is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Label {
    /// Inside the solid: the boundary does not meet the closed cell.
    In,
    /// Outside the solid: the boundary does not meet the closed cell.
    Out,
    /// The boundary meets the closed cell (only at the finest depth); for
    /// a CSG tree with curved or transformed leaves, may meet it.
    On,
}
