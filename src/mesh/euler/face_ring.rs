//! `kfmrh` / `mfkrh`: a face turned into a ring of another face (a hole
//! through the solid, or two shells joined), and a ring turned back into a
//! face of its own.

use crate::mesh::{Face, FaceId, LoopId, LoopStart, Solid};

use super::EulerError;

impl Solid {
    /// Kill face, make ring and hole: removes `face`, whose outer loop
    /// becomes a ring of `keep`. When the two faces are on one shell this
    /// makes a hole through it (a handle: `H + 1`); when they are on two
    /// shells it joins them (`S − 1`). Returns the new ring: the loop that
    /// bounded `face`. The faces should be coplanar and the loop inside
    /// `keep`, wound against it; that is geometry, not checked here.
    ///
    /// Euler–Poincaré: `F − 1, R + 1`. O(length of the loop).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownFace`], [`EulerError::SameFace`], and
    /// [`EulerError::FaceHasRings`] when `face` has rings.
    pub fn kfmrh(&mut self, keep: FaceId, face: FaceId) -> Result<LoopId, EulerError> {
        if !self.faces.contains_key(keep) {
            return Err(EulerError::UnknownFace(keep));
        }
        let f = self.faces.get(face).ok_or(EulerError::UnknownFace(face))?;
        if keep == face {
            return Err(EulerError::SameFace(face));
        }
        if !f.rings.is_empty() {
            return Err(EulerError::FaceHasRings {
                face,
                rings: f.rings.len(),
            });
        }
        let ring = f.outer;
        self.move_loop(ring, keep);
        self.insert_ring(keep, ring);
        self.faces.remove(face);
        Ok(ring)
    }

    /// Make face, kill ring and hole: the ring `ring` becomes the outer loop
    /// of a new face, which copies the attributes of the ring's face and
    /// gets the Newell plane of the loop. The inverse of [`Solid::kfmrh`].
    ///
    /// Euler–Poincaré: `F + 1, R − 1`. O(length of the loop).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownLoop`], and [`EulerError::NotARing`] for an
    /// outer loop.
    pub fn mfkrh(&mut self, ring: LoopId) -> Result<FaceId, EulerError> {
        let record = self.loops.get(ring).ok_or(EulerError::UnknownLoop(ring))?;
        let old = record.face;
        if self.faces[old].outer == ring {
            return Err(EulerError::NotARing {
                loop_id: ring,
                face: old,
            });
        }
        let attributes = self.faces[old].attributes.clone();
        let face = self.faces.insert(Face {
            plane: self.loop_plane(ring),
            outer: ring,
            rings: Vec::new(),
            attributes,
        });
        self.remove_ring(old, ring);
        self.move_loop(ring, face);
        Ok(face)
    }

    /// Gives loop `l` and its uses to `face`.
    fn move_loop(&mut self, l: LoopId, face: FaceId) {
        self.loops[l].face = face;
        if let LoopStart::Edge(start) = self.loops[l].start {
            self.claim_loop(start, face);
        }
    }
}
