//! The internal consistency check: every invariant of the winged-edge tables,
//! verified from scratch.
//!
//! Construction keeps these invariants by design; this check exists so that
//! tests (and debug builds) can prove it after every construction.

use std::collections::{HashMap, HashSet};

use thiserror::Error;

use super::{EdgeId, EdgeUse, FaceId, Side, Solid, VertexId};

/// A broken invariant of a [`Solid`]: always a bug in wingedge, never a
/// property of user input.
#[derive(Clone, Debug, Error, PartialEq, Eq)]
pub enum ConsistencyError {
    /// A stored id names no element of the solid.
    #[error("{what} refers to a missing element")]
    DanglingId {
        /// Which link.
        what: String,
    },
    /// An edge whose two ends are the same vertex.
    #[error("edge {0:?} starts and ends at the same vertex")]
    LoopEdge(EdgeId),
    /// Two edges join the same pair of vertices.
    #[error("edges {0:?} and {1:?} join the same two vertices")]
    ParallelEdges(EdgeId, EdgeId),
    /// A vertex's stored edge does not touch it.
    #[error("vertex {0:?} stores edge {1:?}, which does not touch it")]
    VertexEdgeMismatch(VertexId, EdgeId),
    /// A face's stored edge does not border it.
    #[error("face {0:?} stores edge {1:?}, which does not border it")]
    FaceEdgeMismatch(FaceId, EdgeId),
    /// A wing does not continue its loop at the shared vertex, or the loop
    /// changes face, or `next` and `prev` disagree.
    #[error("the loop through {0:?} is broken: {1}")]
    BrokenLoop(EdgeUse, String),
    /// A face with fewer than three edges, or one that visits a vertex twice.
    #[error("face {0:?} has a loop of {1} edges or repeats a vertex")]
    BadFaceLoop(FaceId, usize),
    /// The faces around a vertex do not form one fan.
    #[error("vertex {0:?}: walking its star visits {1} of its {2} edges")]
    SplitStar(VertexId, usize, usize),
    /// A face's stored plane is missing although the face has area, or a
    /// vertex position is not finite.
    #[error("{0}")]
    BadGeometry(String),
}

impl Solid {
    /// Verifies every invariant of the winged-edge tables.
    ///
    /// Runs in time linear in the size of the solid. Tests call it after
    /// every construction.
    ///
    /// # Errors
    ///
    /// The first broken invariant found.
    pub fn check_consistency(&self) -> Result<(), ConsistencyError> {
        self.check_links()?;
        self.check_loops()?;
        self.check_stars()
    }

    fn check_links(&self) -> Result<(), ConsistencyError> {
        let dangling = |what: String| ConsistencyError::DanglingId { what };
        let mut pairs: HashMap<(VertexId, VertexId), EdgeId> =
            HashMap::with_capacity(self.edges.len());
        for (id, e) in &self.edges {
            for (name, v) in [("origin", e.origin), ("dest", e.dest)] {
                if !self.vertices.contains_key(v) {
                    return Err(dangling(format!("edge {id:?} {name}")));
                }
            }
            let faces = [Some(e.left_face), e.right_face];
            if faces.iter().flatten().any(|&f| !self.faces.contains_key(f)) {
                return Err(dangling(format!("edge {id:?} face")));
            }
            for wing in [e.cw_left, e.ccw_left, e.cw_right, e.ccw_right] {
                if !self.edges.contains_key(wing) {
                    return Err(dangling(format!("edge {id:?} wing")));
                }
            }
            if e.origin == e.dest {
                return Err(ConsistencyError::LoopEdge(id));
            }
            let key = (e.origin.min(e.dest), e.origin.max(e.dest));
            if let Some(&other) = pairs.get(&key) {
                return Err(ConsistencyError::ParallelEdges(other, id));
            }
            pairs.insert(key, id);
        }
        for (id, v) in &self.vertices {
            let e = self
                .edges
                .get(v.edge)
                .ok_or_else(|| dangling(format!("vertex {id:?} edge")))?;
            if e.origin != id && e.dest != id {
                return Err(ConsistencyError::VertexEdgeMismatch(id, v.edge));
            }
            if !v.position.is_finite() {
                return Err(ConsistencyError::BadGeometry(format!(
                    "vertex {id:?} is not finite"
                )));
            }
        }
        for (id, f) in &self.faces {
            let e = self
                .edges
                .get(f.edge)
                .ok_or_else(|| dangling(format!("face {id:?} edge")))?;
            if e.left_face != id && e.right_face != Some(id) {
                return Err(ConsistencyError::FaceEdgeMismatch(id, f.edge));
            }
        }
        Ok(())
    }

    /// Every edge use continues at its end vertex, `prev` inverts `next`,
    /// and every use of a loop has the same face; faces have ≥ 3 edges and
    /// distinct vertices; every use belongs to exactly one loop.
    fn check_loops(&self) -> Result<(), ConsistencyError> {
        let broken = |u: EdgeUse, why: &str| ConsistencyError::BrokenLoop(u, why.to_string());
        for (edge, _) in &self.edges {
            for side in [Side::Left, Side::Right] {
                let u = EdgeUse { edge, side };
                let next = self.use_next(u);
                if self.use_start(next) != self.use_end(u) {
                    return Err(broken(u, "next does not start where it ends"));
                }
                if self.use_prev(next) != u {
                    return Err(broken(u, "prev(next) is not itself"));
                }
                if self.use_face(next) != self.use_face(u) {
                    return Err(broken(u, "next lies on another face"));
                }
            }
        }
        let mut seen: HashSet<EdgeUse> = HashSet::with_capacity(self.edges.len() * 2);
        for (face, _) in &self.faces {
            let uses: Vec<EdgeUse> = self.face_loop(face).collect();
            if self.use_next(*uses.last().expect("a loop has at least one use")) != uses[0] {
                return Err(broken(uses[0], "the face loop does not close"));
            }
            let vertices: HashSet<VertexId> = uses.iter().map(|&u| self.use_start(u)).collect();
            if uses.len() < 3 || vertices.len() != uses.len() {
                return Err(ConsistencyError::BadFaceLoop(face, uses.len()));
            }
            for u in uses {
                if self.use_face(u) != Some(face) || !seen.insert(u) {
                    return Err(broken(u, "a use belongs to two loops"));
                }
            }
        }
        let face_uses = seen.len();
        let expected = self
            .edges
            .values()
            .filter(|e| e.right_face.is_some())
            .count()
            + self.edges.len();
        if face_uses != expected {
            return Err(ConsistencyError::BadGeometry(format!(
                "face loops cover {face_uses} edge uses, expected {expected}"
            )));
        }
        Ok(())
    }

    fn check_stars(&self) -> Result<(), ConsistencyError> {
        let mut degree: HashMap<VertexId, usize> = HashMap::with_capacity(self.vertices.len());
        for e in self.edges.values() {
            *degree.entry(e.origin).or_default() += 1;
            *degree.entry(e.dest).or_default() += 1;
        }
        for (v, _) in &self.vertices {
            let expected = degree.get(&v).copied().unwrap_or(0);
            let walked = self.vertex_star(v).count();
            if walked != expected {
                return Err(ConsistencyError::SplitStar(v, walked, expected));
            }
            if self.vertex_star(v).any(|u| self.use_start(u) != v) {
                return Err(ConsistencyError::SplitStar(v, walked, expected));
            }
        }
        Ok(())
    }
}
