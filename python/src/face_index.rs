//! Face ids to the indices every answer reports: a face's position in
//! the solid's face order.

use slotmap::SecondaryMap;
use wingedge::mesh::{FaceId, Solid};

/// The position of every face in the solid's face order: an array
/// indexed by the key's slot, so a million lookups cost a million loads.
pub(crate) struct FaceIndex(SecondaryMap<FaceId, i64>);

impl FaceIndex {
    pub(crate) fn new(solid: &Solid) -> FaceIndex {
        FaceIndex(
            solid
                .faces()
                .enumerate()
                .map(|(i, (f, _))| (f, i as i64))
                .collect(),
        )
    }

    pub(crate) fn of(&self, face: FaceId) -> i64 {
        self.0.get(face).copied().unwrap_or(-1)
    }
}
