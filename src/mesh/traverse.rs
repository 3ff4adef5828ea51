//! The nine adjacency relations, derived by walking the wings.
//!
//! Nothing here is stored: every relation is an iterator that follows the
//! winged-edge links, in cyclic order, in time proportional to the degree of
//! the element asked about.
//!
//! | from \ to | vertices | edges | faces |
//! |---|---|---|---|
//! | vertex | [`Solid::vertex_vertices`] | [`Solid::vertex_edges`] | [`Solid::vertex_faces`] |
//! | edge | [`Solid::edge_vertices`] | [`Solid::edge_wings`] | [`Solid::edge_faces`] |
//! | face | [`Solid::face_vertices`] | [`Solid::face_edges`] | [`Solid::face_neighbours`] |
//!
//! Vertex relations run counter-clockwise around the vertex seen from outside;
//! face relations run counter-clockwise around the face seen from outside and
//! visit all of a face's loops: the outer loop first, then each ring.
//! [`Solid::face_loops`] lists a face's loops and [`Solid::loop_uses`] walks
//! one of them.

use super::{Edge, EdgeId, EdgeUse, FaceId, LoopId, LoopStart, Side, Solid, VertexId};

impl Solid {
    /// The vertex an edge use starts at.
    #[must_use]
    pub fn use_start(&self, u: EdgeUse) -> VertexId {
        let e = &self.edges[u.edge];
        match u.side {
            Side::Left => e.origin,
            Side::Right => e.dest,
        }
    }

    /// The vertex an edge use ends at.
    #[must_use]
    pub fn use_end(&self, u: EdgeUse) -> VertexId {
        self.use_start(u.opposite())
    }

    /// The face on an edge use's side, `None` for the hole side of a boundary
    /// edge.
    #[must_use]
    pub fn use_face(&self, u: EdgeUse) -> Option<FaceId> {
        let e = &self.edges[u.edge];
        match u.side {
            Side::Left => Some(e.left_face),
            Side::Right => e.right_face,
        }
    }

    /// The next edge use counter-clockwise around the same face (or hole):
    /// the one that starts where `u` ends.
    #[must_use]
    pub fn use_next(&self, u: EdgeUse) -> EdgeUse {
        self.use_next_from(u, &self.edges[u.edge]).0
    }

    /// [`Solid::use_next`] from `u`'s edge record `e` in hand; also returns
    /// the next use's edge record (one lookup per step of a walk).
    fn use_next_from(&self, u: EdgeUse, e: &Edge) -> (EdgeUse, &Edge) {
        let (next, end) = match u.side {
            Side::Left => (e.ccw_left, e.dest),
            Side::Right => (e.ccw_right, e.origin),
        };
        let n = &self.edges[next];
        let side = if n.origin == end {
            Side::Left
        } else {
            Side::Right
        };
        (EdgeUse { edge: next, side }, n)
    }

    /// The previous edge use around the same face (or hole): the one that ends
    /// where `u` starts.
    #[must_use]
    pub fn use_prev(&self, u: EdgeUse) -> EdgeUse {
        let e = &self.edges[u.edge];
        let (prev, start) = match u.side {
            Side::Left => (e.cw_left, e.origin),
            Side::Right => (e.cw_right, e.dest),
        };
        let side = if self.edges[prev].dest == start {
            Side::Left
        } else {
            Side::Right
        };
        EdgeUse { edge: prev, side }
    }

    /// The first edge use of `face`'s outer loop, `None` when that loop is
    /// a lone vertex.
    #[must_use]
    pub fn face_first_use(&self, face: FaceId) -> Option<EdgeUse> {
        match self.loops[self.faces[face].outer].start {
            LoopStart::Edge(u) => Some(u),
            LoopStart::Vertex(_) => None,
        }
    }

    /// The use of `vertex`'s stored edge that leaves `vertex`, `None` for a
    /// vertex without edges.
    #[must_use]
    pub fn vertex_first_use(&self, vertex: VertexId) -> Option<EdgeUse> {
        let edge = self.vertices[vertex].edge?;
        let side = if self.edges[edge].origin == vertex {
            Side::Left
        } else {
            Side::Right
        };
        Some(EdgeUse { edge, side })
    }

    /// The loops of `face`: its outer loop, then its rings.
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    pub fn face_loops(&self, face: FaceId) -> impl Iterator<Item = LoopId> + '_ {
        let f = &self.faces[face];
        std::iter::once(f.outer).chain(f.rings.iter().copied())
    }

    /// The edge uses of one loop, in its order (counter-clockwise around the
    /// face seen from outside for an outer loop, clockwise for a ring);
    /// nothing for a loop that is a lone vertex.
    ///
    /// # Panics
    ///
    /// If `id` is not a loop of this solid.
    pub fn loop_uses(&self, id: LoopId) -> LoopWalk<'_> {
        match self.loops[id].start {
            LoopStart::Edge(u) => self.loop_from(u),
            LoopStart::Vertex(_) => LoopWalk {
                solid: self,
                start: None,
                current: None,
                budget: 0,
            },
        }
    }

    /// The vertices of one loop in its order: the start of each use, or the
    /// lone vertex of a loop without edges.
    ///
    /// # Panics
    ///
    /// If `id` is not a loop of this solid.
    pub fn loop_vertices(&self, id: LoopId) -> impl Iterator<Item = VertexId> + '_ {
        let lone = match self.loops[id].start {
            LoopStart::Vertex(v) => Some(v),
            LoopStart::Edge(_) => None,
        };
        let mut walk = self.loop_uses(id);
        lone.into_iter().chain(std::iter::from_fn(move || {
            walk.next_with_edge().map(|(u, e)| match u.side {
                Side::Left => e.origin,
                Side::Right => e.dest,
            })
        }))
    }

    /// The number of rings (inner loops) of `face`.
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    #[must_use]
    pub fn face_ring_count(&self, face: FaceId) -> usize {
        self.faces[face].rings.len()
    }

    /// The edge uses bounding `face`: its outer loop counter-clockwise seen
    /// from outside, then each ring (clockwise), each loop from its stored
    /// start.
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    pub fn face_loop(&self, face: FaceId) -> impl Iterator<Item = EdgeUse> + '_ {
        self.face_loops(face).flat_map(|l| self.loop_uses(l))
    }

    /// The edge uses of the loop (face or hole) that `start` belongs to,
    /// beginning with `start`.
    pub fn loop_from(&self, start: EdgeUse) -> LoopWalk<'_> {
        LoopWalk {
            solid: self,
            start: Some(start),
            current: Some((start, &self.edges[start.edge])),
            budget: self.edges.len() * 2,
        }
    }

    /// The edge uses leaving `vertex`, counter-clockwise around it seen from
    /// outside. Holes are crossed, so a boundary vertex yields all its edges.
    ///
    /// # Panics
    ///
    /// If `vertex` is not a vertex of this solid.
    pub fn vertex_star(&self, vertex: VertexId) -> StarWalk<'_> {
        let start = self.vertex_first_use(vertex);
        StarWalk {
            solid: self,
            start,
            current: start,
            budget: self.edges.len() * 2,
        }
    }

    /// Vertex → edges: the edges at `vertex`, in cyclic order.
    pub fn vertex_edges(&self, vertex: VertexId) -> impl Iterator<Item = EdgeId> + '_ {
        self.vertex_star(vertex).map(|u| u.edge)
    }

    /// Vertex → faces: the faces around `vertex`, in cyclic order (holes are
    /// skipped; a vertex without edges yields nothing).
    pub fn vertex_faces(&self, vertex: VertexId) -> impl Iterator<Item = FaceId> + '_ {
        self.vertex_star(vertex).filter_map(|u| self.use_face(u))
    }

    /// Vertex → vertices: the vertices joined to `vertex` by an edge, in
    /// cyclic order.
    pub fn vertex_vertices(&self, vertex: VertexId) -> impl Iterator<Item = VertexId> + '_ {
        self.vertex_star(vertex).map(|u| self.use_end(u))
    }

    /// Edge → vertices: `[origin, dest]`.
    #[must_use]
    pub fn edge_vertices(&self, edge: EdgeId) -> [VertexId; 2] {
        let e = &self.edges[edge];
        [e.origin, e.dest]
    }

    /// Edge → faces: the left face, then the right face if the edge has one.
    pub fn edge_faces(&self, edge: EdgeId) -> impl Iterator<Item = FaceId> + '_ {
        let e = &self.edges[edge];
        std::iter::once(e.left_face).chain(e.right_face)
    }

    /// Edge → edges: the four wings `[cw_left, ccw_left, cw_right, ccw_right]`.
    /// For a boundary edge the right-hand wings are the neighbours around the
    /// hole.
    #[must_use]
    pub fn edge_wings(&self, edge: EdgeId) -> [EdgeId; 4] {
        let e = &self.edges[edge];
        [e.cw_left, e.ccw_left, e.cw_right, e.ccw_right]
    }

    /// Face → vertices: the corners of `face`, loop by loop as in
    /// [`Solid::face_loop`] (a lone-vertex loop gives its vertex).
    pub fn face_vertices(&self, face: FaceId) -> impl Iterator<Item = VertexId> + '_ {
        self.face_loops(face).flat_map(|l| self.loop_vertices(l))
    }

    /// The corners of `face`'s outer loop, counter-clockwise seen from
    /// outside.
    ///
    /// # Panics
    ///
    /// If `face` is not a face of this solid.
    pub fn face_outer_vertices(&self, face: FaceId) -> impl Iterator<Item = VertexId> + '_ {
        self.loop_vertices(self.faces[face].outer)
    }

    /// Face → edges: the edges bounding `face`, counter-clockwise.
    pub fn face_edges(&self, face: FaceId) -> impl Iterator<Item = EdgeId> + '_ {
        self.face_loop(face).map(|u| u.edge)
    }

    /// Face → faces: the faces across each edge of `face`, counter-clockwise
    /// (edges on a hole contribute nothing).
    pub fn face_neighbours(&self, face: FaceId) -> impl Iterator<Item = FaceId> + '_ {
        self.face_loop(face)
            .filter_map(|u| self.use_face(u.opposite()))
    }

    /// The number of edge uses around `face`, over all its loops.
    #[must_use]
    pub fn face_degree(&self, face: FaceId) -> usize {
        self.face_loop(face).count()
    }

    /// The number of edges at `vertex`.
    #[must_use]
    pub fn vertex_degree(&self, vertex: VertexId) -> usize {
        self.vertex_star(vertex).count()
    }
}

/// An iterator over the edge uses of one loop; see [`Solid::loop_uses`] and
/// [`Solid::loop_from`].
///
/// It stops after one turn. A `budget` of twice the edge count guards the
/// walk: on a consistent solid it is never reached.
#[derive(Clone, Debug)]
pub struct LoopWalk<'a> {
    solid: &'a Solid,
    start: Option<EdgeUse>,
    /// The next use and its edge's record (looked up once per step: it
    /// names the use after it).
    current: Option<(EdgeUse, &'a Edge)>,
    budget: usize,
}

impl<'a> LoopWalk<'a> {
    /// The next use with its edge's record.
    fn next_with_edge(&mut self) -> Option<(EdgeUse, &'a Edge)> {
        let (u, e) = self.current?;
        self.budget = self.budget.checked_sub(1)?;
        let (next, n) = self.solid.use_next_from(u, e);
        self.current = (Some(next) != self.start).then_some((next, n));
        Some((u, e))
    }
}

impl Iterator for LoopWalk<'_> {
    type Item = EdgeUse;

    fn next(&mut self) -> Option<EdgeUse> {
        self.next_with_edge().map(|(u, _)| u)
    }
}

/// An iterator over the edge uses leaving one vertex; see
/// [`Solid::vertex_star`].
#[derive(Clone, Debug)]
pub struct StarWalk<'a> {
    solid: &'a Solid,
    start: Option<EdgeUse>,
    current: Option<EdgeUse>,
    budget: usize,
}

impl Iterator for StarWalk<'_> {
    type Item = EdgeUse;

    fn next(&mut self) -> Option<EdgeUse> {
        let u = self.current?;
        self.budget = self.budget.checked_sub(1)?;
        // The previous use around u's face ends at u's start; its opposite
        // leaves the same vertex in the next face counter-clockwise.
        let next = self.solid.use_prev(u).opposite();
        self.current = (Some(next) != self.start).then_some(next);
        Some(u)
    }
}
