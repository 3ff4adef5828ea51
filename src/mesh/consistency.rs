//! The internal consistency check: every invariant of the winged-edge tables,
//! verified from scratch.
//!
//! Construction and the Euler operators keep these invariants by design;
//! this check exists so that tests (and debug builds) can prove it after
//! every construction and every operator.

use std::collections::{HashMap, HashSet};

use thiserror::Error;

use super::{EdgeId, EdgeUse, FaceId, LoopId, LoopStart, Side, Solid, VertexId};

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
    /// A vertex's stored edge does not touch it, or a vertex without an
    /// edge is not a lone-vertex loop.
    #[error("vertex {0:?} stores edge {1:?}, which does not touch it")]
    VertexEdgeMismatch(VertexId, Option<EdgeId>),
    /// A face's loop does not name the face back, or a loop is listed by no
    /// face or by two.
    #[error("face {0:?} and loop {1:?} do not name each other")]
    FaceLoopMismatch(FaceId, LoopId),
    /// A wing does not continue its loop at the shared vertex, or the loop
    /// changes face, or `next` and `prev` disagree.
    #[error("the loop through {0:?} is broken: {1}")]
    BrokenLoop(EdgeUse, String),
    /// A loop's start is not on its face, or a lone vertex is in two loops.
    #[error("loop {0:?} is broken: {1}")]
    BadLoop(LoopId, String),
    /// The faces around a vertex do not form one fan.
    #[error("vertex {0:?}: walking its star visits {1} of its {2} edges")]
    SplitStar(VertexId, usize, usize),
    /// A vertex position is not finite.
    #[error("{0}")]
    BadGeometry(String),
}

impl Solid {
    /// Verifies every invariant of the winged-edge tables.
    ///
    /// Runs in time linear in the size of the solid. Tests call it after
    /// every construction and every Euler operator.
    ///
    /// # Errors
    ///
    /// The first broken invariant found.
    pub fn check_consistency(&self) -> Result<(), ConsistencyError> {
        self.check_links()?;
        self.check_faces_and_loops()?;
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
            if let Some(edge) = v.edge {
                let e = self
                    .edges
                    .get(edge)
                    .ok_or_else(|| dangling(format!("vertex {id:?} edge")))?;
                if e.origin != id && e.dest != id {
                    return Err(ConsistencyError::VertexEdgeMismatch(id, v.edge));
                }
            }
            if !v.position.is_finite() {
                return Err(ConsistencyError::BadGeometry(format!(
                    "vertex {id:?} is not finite"
                )));
            }
        }
        Ok(())
    }

    /// Faces and loops name each other; every loop is listed by exactly one
    /// face; rings are sorted; loop starts lie on their face; lone vertices
    /// have no edge and are in exactly one loop, and every vertex without an
    /// edge is lone.
    fn check_faces_and_loops(&self) -> Result<(), ConsistencyError> {
        let mut listed: HashSet<LoopId> = HashSet::with_capacity(self.loops.len());
        for (face, f) in &self.faces {
            if !f.rings.windows(2).all(|w| w[0] < w[1]) {
                return Err(ConsistencyError::BadLoop(
                    f.outer,
                    format!("the rings of face {face:?} are not sorted"),
                ));
            }
            for l in std::iter::once(f.outer).chain(f.rings.iter().copied()) {
                match self.loops.get(l) {
                    Some(record) if record.face == face && listed.insert(l) => {}
                    _ => return Err(ConsistencyError::FaceLoopMismatch(face, l)),
                }
            }
        }
        let mut lone: HashSet<VertexId> = HashSet::new();
        for (id, l) in &self.loops {
            if !listed.contains(&id) {
                return Err(ConsistencyError::FaceLoopMismatch(l.face, id));
            }
            match l.start {
                LoopStart::Edge(u) => {
                    if !self.edges.contains_key(u.edge) {
                        return Err(ConsistencyError::DanglingId {
                            what: format!("loop {id:?} start"),
                        });
                    }
                    if self.use_face(u) != Some(l.face) {
                        return Err(ConsistencyError::BadLoop(
                            id,
                            "its start is not on its face".to_string(),
                        ));
                    }
                }
                LoopStart::Vertex(v) => {
                    let Some(vertex) = self.vertices.get(v) else {
                        return Err(ConsistencyError::DanglingId {
                            what: format!("loop {id:?} vertex"),
                        });
                    };
                    if vertex.edge.is_some() || !lone.insert(v) {
                        return Err(ConsistencyError::BadLoop(
                            id,
                            format!("lone vertex {v:?} has an edge or is in two loops"),
                        ));
                    }
                }
            }
        }
        for (id, v) in &self.vertices {
            if v.edge.is_none() && !lone.contains(&id) {
                return Err(ConsistencyError::VertexEdgeMismatch(id, None));
            }
        }
        Ok(())
    }

    /// Every edge use continues at its end vertex, `prev` inverts `next`,
    /// and every use of a loop has the same face; every face use belongs to
    /// exactly one loop.
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
        for (id, l) in &self.loops {
            let LoopStart::Edge(start) = l.start else {
                continue;
            };
            let mut count = 0;
            for u in self.loop_from(start) {
                count += 1;
                if self.use_face(u) != Some(l.face) || !seen.insert(u) {
                    return Err(broken(u, "a use belongs to two loops"));
                }
            }
            let last = self.loop_from(start).last();
            if count == 0 || last.map(|u| self.use_next(u)) != Some(start) {
                return Err(ConsistencyError::BadLoop(
                    id,
                    "the loop does not close".to_string(),
                ));
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
