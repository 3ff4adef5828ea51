//! Why a field or a sample grid cannot be built or meshed.

use glam::DVec3;
use thiserror::Error;

use crate::geom::{Readable, ReadableVec};

/// Why a field, a sample grid or a meshing request is refused.
///
/// Source numbers are 0-based indices into the list given to
/// [`Blobs::try_new`](super::Blobs::try_new).
#[derive(Clone, Debug, Error, PartialEq)]
pub enum FieldError {
    /// A source center with a NaN or infinite coordinate.
    #[error("source {source_index} has a non-finite center {}", ReadableVec(*.center))]
    NonFiniteCenter {
        /// The source.
        source_index: usize,
        /// Its center.
        center: DVec3,
    },
    /// A source radius that is zero, negative, NaN or infinite.
    #[error("source {source_index} has radius {}; a radius must be finite and > 0", Readable(*.radius))]
    BadRadius {
        /// The source.
        source_index: usize,
        /// Its radius.
        radius: f64,
    },
    /// A source center or radius outside the range where squared distances
    /// neither overflow nor underflow `f64`.
    #[error(
        "source {source_index} ({what} {}) is out of range: centers must lie within ±2^500 and radii in [2^-500, 2^500]",
        Readable(*.value)
    )]
    OutOfRange {
        /// The source.
        source_index: usize,
        /// `"center coordinate"` or `"radius"`.
        what: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A source strength that is NaN or infinite.
    #[error("source {source_index} has a non-finite strength {}", Readable(*.strength))]
    BadStrength {
        /// The source.
        source_index: usize,
        /// Its strength.
        strength: f64,
    },
    /// A marching-cubes resolution of 0 cells.
    #[error("the resolution must be at least 1 cell")]
    ZeroResolution,
    /// A sample grid with more samples than meshing allows.
    #[error("a grid of {dims:?} samples has {samples} samples; the limit is {limit}")]
    GridTooLarge {
        /// Samples along x, y and z.
        dims: [usize; 3],
        /// Their product (saturated).
        samples: usize,
        /// [`MAX_SAMPLES`](super::MAX_SAMPLES).
        limit: usize,
    },
    /// A sample grid with no sample along some axis.
    #[error("a grid of {dims:?} samples is empty; each axis needs at least one")]
    EmptyGrid {
        /// Samples along x, y and z.
        dims: [usize; 3],
    },
    /// Sample values whose count does not match the grid's dimensions.
    #[error("the grid has {dims:?} = {expected} samples but {found} values were given")]
    SampleCount {
        /// Samples along x, y and z.
        dims: [usize; 3],
        /// Their product.
        expected: usize,
        /// Values given.
        found: usize,
    },
    /// A sample value that is NaN or infinite.
    #[error("sample ({i}, {j}, {k}) has the non-finite value {}", Readable(*.value))]
    NonFiniteSample {
        /// Index along x.
        i: usize,
        /// Index along y.
        j: usize,
        /// Index along z.
        k: usize,
        /// The value.
        value: f64,
    },
    /// A grid origin or cell size that is not finite, or a cell size ≤ 0.
    #[error(
        "grid origin {} and cell size {} must be finite, the cell size > 0",
        ReadableVec(*.origin),
        Readable(*.cell)
    )]
    BadGridFrame {
        /// The grid's first sample.
        origin: DVec3,
        /// The edge length of a cell.
        cell: f64,
    },
    /// A grid cell too small for `f64` where the grid lies: vertices on
    /// its edges could not be kept apart from its nodes once rounded (the
    /// meshed surface would have degenerate faces), so the field is not
    /// meshed there; a coarser resolution, or a field nearer the origin,
    /// is.
    #[error(
        "a grid cell of {} is below f64's resolution at coordinate {} (neighbouring f64 are {} apart; a cell needs at least {} of them): use a coarser resolution",
        Readable(*.cell),
        Readable(*.coordinate),
        Readable(*.spacing),
        .needed
    )]
    CellBelowResolution {
        /// The edge length of a cell.
        cell: f64,
        /// The grid's farthest coordinate (largest magnitude).
        coordinate: f64,
        /// The spacing of `f64` there.
        spacing: f64,
        /// How many such spacings a cell needs
        /// (`field::MIN_CELL_ULPS`).
        needed: f64,
    },
    /// An edge margin outside `[0, ½]`.
    #[error("the edge margin {} must lie in [0, 0.5]", Readable(*.0))]
    BadEdgeMargin(f64),
    /// The field is below ½ everywhere (no source, only negative sources, an
    /// empty intersection): there is no surface to mesh.
    #[error("the field is below 1/2 everywhere: the solid is empty")]
    Empty,
    /// The surface found by marching cubes could not be built into a solid
    /// (a bug: the output is closed and manifold by construction).
    #[error("the marching-cubes surface is not a solid: {0}")]
    NotASolid(String),
}
