//! `mvfs` / `kvfs`: a new shell of one vertex and one face, and its removal.

use glam::DVec3;
use slotmap::Key;

use crate::mesh::{Face, FaceAttributes, FaceId, Loop, LoopId, LoopStart, Solid, Vertex, VertexId};

use super::EulerError;
use super::links::check_position;

impl Solid {
    /// Make vertex, face, shell: a new shell made of one vertex at
    /// `position` and one face whose only loop is that vertex. The face has
    /// no plane.
    ///
    /// Euler–Poincaré: `V + 1, F + 1, S + 1`. O(1).
    ///
    /// # Errors
    ///
    /// [`EulerError::NonFinitePosition`].
    pub fn mvfs(&mut self, position: DVec3) -> Result<(VertexId, FaceId), EulerError> {
        check_position(position)?;
        let vertex = self.vertices.insert(Vertex {
            position,
            edge: None,
            source_index: None,
        });
        let face = self.faces.insert(Face {
            plane: None,
            outer: LoopId::null(),
            rings: Vec::new(),
            attributes: FaceAttributes::default(),
        });
        let outer = self.loops.insert(Loop {
            face,
            start: LoopStart::Vertex(vertex),
        });
        self.faces[face].outer = outer;
        Ok((vertex, face))
    }

    /// Kill vertex, face, shell: removes a shell made of one face whose only
    /// loop is a lone vertex (what [`Solid::mvfs`] makes). The inverse of
    /// [`Solid::mvfs`].
    ///
    /// Euler–Poincaré: `V − 1, F − 1, S − 1`. O(1).
    ///
    /// # Errors
    ///
    /// [`EulerError::UnknownFace`], [`EulerError::FaceHasRings`] and
    /// [`EulerError::NotLoneShell`] when the face's outer loop has edges.
    pub fn kvfs(&mut self, face: FaceId) -> Result<(), EulerError> {
        let f = self.faces.get(face).ok_or(EulerError::UnknownFace(face))?;
        if !f.rings.is_empty() {
            return Err(EulerError::FaceHasRings {
                face,
                rings: f.rings.len(),
            });
        }
        let LoopStart::Vertex(vertex) = self.loops[f.outer].start else {
            return Err(EulerError::NotLoneShell(face));
        };
        let outer = f.outer;
        self.loops.remove(outer);
        self.faces.remove(face);
        self.vertices.remove(vertex);
        Ok(())
    }
}
