//! Marching cubes (Lorensen & Cline 1987) on any [`Field`], producing a
//! closed, oriented, 2-manifold surface.
//!
//! Pipeline: the field is sampled on a regular grid over its bounds
//! ([`SampleGrid`]), padded by a layer of zero samples so that the surface
//! closes at the border; every cell's eight signs (`F ≥ ½` inside) index a
//! 256-entry case table *generated* from 17 base cases by the cube's 48
//! symmetries and by complement (`table`, `base_cases`); each crossed grid
//! edge gets one vertex (welded), placed by linear interpolation or at the
//! midpoint ([`Placement`]).
//!
//! Ambiguous faces (corners alternating inside/outside around a face) are
//! decided by one fixed rule read from the face's four signs alone: the
//! inside corners are separated. Both cells sharing a face apply it
//! identically, which is what makes the surface closed; see `base_cases` for
//! why complements of cases 3, 6 and 7 need their own entries.
//!
//! Marching cubes lives in the field layer (not in `mesh`) because it reads
//! fields; it writes a [`PolygonSoup`] and builds the [`Solid`] through
//! [`Solid::try_from_soup`].

mod base_cases;
mod blocks;
mod cube;
mod extract;
mod grid;
mod options;
mod table;

use crate::mesh::{PolygonSoup, Solid};

use super::error::FieldError;
use super::scalar_field::Field;
use super::stats::FieldStats;

pub use extract::MarchStats;
use grid::GridFrame;
pub use grid::{MAX_SAMPLES, MIN_CELL_ULPS, SampleGrid, VERTEX_ULPS};
pub use options::{MarchingOptions, Placement};

/// A meshed field: the welded triangles and the work done.
#[derive(Clone, Debug, Default)]
pub struct Meshed {
    /// The surface: triangles counter-clockwise seen from outside (`F < ½`),
    /// one vertex per crossed grid edge. Empty when no sample reaches ½.
    pub soup: PolygonSoup,
    /// Samples along x, y and z (without the padding).
    pub dims: [usize; 3],
    /// The edge length of a cell.
    pub cell: f64,
    /// Field evaluations while sampling.
    pub field: FieldStats,
    /// What the march found.
    pub march: MarchStats,
}

/// Samples `field` over its bounds and marches the grid, doing only the
/// work the surface calls for.
///
/// The grid is the one [`SampleGrid::try_sample`] lays over the field, cut
/// into blocks of 8³ cells; a block that the field's
/// [`bound`](Field::bound) shows to be all inside or all outside is
/// neither sampled nor marched, and the others are. The soup is the one
/// [`march_grid`] makes of the whole sampled grid, bit for bit; only the
/// work counters differ.
///
/// # Errors
///
/// Bad options ([`MarchingOptions::check`]), [`FieldError::Empty`] when the
/// field's bounds are empty, [`FieldError::GridTooLarge`] beyond
/// [`MAX_SAMPLES`], [`FieldError::NonFiniteSample`] when the field returns
/// a value that is not finite.
pub fn try_mesh(field: &dyn Field, options: &MarchingOptions) -> Result<Meshed, FieldError> {
    options.check()?;
    let frame = GridFrame::try_new(field, options.resolution)?;
    let (soup, field_stats, march) = blocks::march_blocks(field, &frame, options)?;
    Ok(Meshed {
        soup,
        dims: frame.dims,
        cell: frame.cell,
        field: field_stats,
        march,
    })
}

/// The name of the base case a configuration's table entry was generated
/// from (`"0"` to `"13"`, or `"3c"`, `"6c"`, `"7c"` for the complements
/// that the ambiguity rule does not let a reversal give); bit `c` of
/// `config` set = corner `c` (at `(c & 1, c >> 1 & 1, c >> 2 & 1)`) inside.
#[must_use]
pub fn base_case(config: u8) -> &'static str {
    table::case_table().case(config).base
}

/// Marches an already sampled grid (outside it counts as `F = 0`).
#[must_use]
pub fn march_grid(grid: &SampleGrid, options: &MarchingOptions) -> (PolygonSoup, MarchStats) {
    extract::march(grid, options)
}

/// [`try_mesh`], then the winged-edge solid.
///
/// # Errors
///
/// As [`try_mesh`]; [`FieldError::Empty`] also when no sample reaches ½ (the
/// solid is smaller than the grid can see, or empty).
pub fn try_mesh_solid(
    field: &dyn Field,
    options: &MarchingOptions,
) -> Result<(Solid, Meshed), FieldError> {
    let meshed = try_mesh(field, options)?;
    let solid = solid_of(&meshed.soup)?;
    Ok((solid, meshed))
}

/// The solid of a marched soup.
///
/// # Errors
///
/// [`FieldError::Empty`] for an empty soup; [`FieldError::NotASolid`] if the
/// soup cannot be built (never for a march's output).
pub fn solid_of(soup: &PolygonSoup) -> Result<Solid, FieldError> {
    if soup.polygons.is_empty() {
        return Err(FieldError::Empty);
    }
    Solid::try_from_soup(soup).map_err(|e| FieldError::NotASolid(e.to_string()))
}
