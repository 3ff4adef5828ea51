//! How marching cubes samples and where it puts vertices.

use super::super::error::FieldError;

/// Where a surface vertex sits on its crossed grid edge.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Placement {
    /// Where the linear interpolation of the two samples reaches ½ (kept
    /// [`MarchingOptions::edge_margin`] away from the nodes).
    #[default]
    Interpolated,
    /// At the edge's midpoint, as in the classic presentation: blockier, but
    /// independent of the sample values.
    Midpoint,
}

/// Options of [`try_mesh`](super::try_mesh).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MarchingOptions {
    /// Cells along the longest side of the field's bounds (≥ 1).
    pub resolution: usize,
    /// Where vertices sit on their edges.
    pub placement: Placement,
    /// With [`Placement::Interpolated`], the interpolation parameter is
    /// clamped to `[edge_margin, 1 − edge_margin]` (a fraction of the cell
    /// edge, in `[0, ½]`). A margin > 0 keeps vertices off the grid nodes,
    /// so a sample exactly at ½ cannot put several vertices at one node
    /// (zero-area triangles); it moves the surface by at most that fraction
    /// of a cell. Default 2⁻¹⁰.
    pub edge_margin: f64,
}

impl Default for MarchingOptions {
    fn default() -> MarchingOptions {
        MarchingOptions {
            resolution: 64,
            placement: Placement::Interpolated,
            edge_margin: 1.0 / 1024.0,
        }
    }
}

impl MarchingOptions {
    /// Checks the options.
    ///
    /// # Errors
    ///
    /// [`FieldError::ZeroResolution`] or [`FieldError::BadEdgeMargin`].
    pub fn check(&self) -> Result<(), FieldError> {
        if self.resolution == 0 {
            return Err(FieldError::ZeroResolution);
        }
        if !(0.0..=0.5).contains(&self.edge_margin) {
            return Err(FieldError::BadEdgeMargin(self.edge_margin));
        }
        Ok(())
    }
}
