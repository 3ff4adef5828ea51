//! User-level tolerances, the only place where closeness is judged.
//!
//! Tolerances never decide a sign: they answer user questions such as "is this
//! imported face flat enough?" or "should these two vertices be welded?".
//! Every one is relative to the model's size (its bounding-box diagonal) so
//! that the same setting means the same thing at every scale.

/// Tolerances for judging imported geometry, as fractions of the model's
/// bounding-box diagonal.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tolerance {
    /// A face is reported as non-planar when a vertex lies farther than
    /// `planarity × diagonal` from the face's Newell plane. Default `1e-6`.
    pub planarity: f64,
    /// Vertices closer than `weld × diagonal` are merged by a tolerant weld.
    /// Default `0` (only bit-identical positions are merged).
    pub weld: f64,
}

impl Default for Tolerance {
    fn default() -> Tolerance {
        Tolerance {
            planarity: 1e-6,
            weld: 0.0,
        }
    }
}

impl Tolerance {
    /// The absolute planarity limit for a model whose bounding box has the
    /// given diagonal.
    #[must_use]
    pub fn planarity_limit(&self, diagonal: f64) -> f64 {
        self.planarity * diagonal
    }

    /// The absolute weld distance for a model whose bounding box has the
    /// given diagonal.
    #[must_use]
    pub fn weld_distance(&self, diagonal: f64) -> f64 {
        self.weld * diagonal
    }
}
