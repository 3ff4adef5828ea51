//! Counters that show how much of a field an evaluation touched.

use std::ops::AddAssign;

/// Work counters of field evaluations.
///
/// Each evaluation adds to a `&mut FieldStats`; parallel samplers keep one
/// per slab and add them up. Comparing [`source_evaluations`](Self::source_evaluations)
/// with `samples ×` [`Blobs::len`](super::Blobs::len) shows how many sources
/// the source grid kept out of each sample.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct FieldStats {
    /// Points at which a field was evaluated (each node of a CSG tree
    /// counts its own).
    pub samples: u64,
    /// Sources whose list entry was looked at: those the source grid lists
    /// for the sample's cell or, when a block of samples is taken at once
    /// ([`Field::sample_nodes`](super::Field::sample_nodes)), for the
    /// block.
    pub candidates: u64,
    /// Falloff evaluations: candidates whose ball actually holds the sample.
    pub source_evaluations: u64,
}

impl AddAssign for FieldStats {
    fn add_assign(&mut self, o: FieldStats) {
        self.samples += o.samples;
        self.candidates += o.candidates;
        self.source_evaluations += o.source_evaluations;
    }
}

impl std::fmt::Display for FieldStats {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "samples {}, source candidates {}, source evaluations {}",
            self.samples, self.candidates, self.source_evaluations
        )
    }
}
