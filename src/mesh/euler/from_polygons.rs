//! A closed polyhedron of genus 0 built from its polygons by Euler
//! operators alone: a spanning tree of its edges by `mev`, every other edge
//! by `mef`.

use std::collections::{HashMap, VecDeque};

use glam::DVec3;

use crate::geom::Plane;
use crate::mesh::{EdgeId, EdgeUse, LoopStart, PolygonSoup, Side, Solid, VertexId};

use super::{Corner, EulerError};

impl Solid {
    /// Builds the closed, genus-0 polyhedron with the faces `soup.polygons`
    /// (each wound counter-clockwise seen from outside) by Euler operators:
    /// [`Solid::mvfs`] at one vertex, [`Solid::mev`] along a breadth-first
    /// spanning tree of the edges, and [`Solid::mef`] for every other edge.
    /// Each new edge goes into the corner that the polygons' cyclic order
    /// around its vertex asks for, so the faces come out as the polygons.
    /// Faces and vertices then get the polygons' attributes, Newell planes
    /// and soup indices, as [`Solid::try_from_soup`] gives them.
    ///
    /// For builders of known closed solids; imported data goes through
    /// [`Solid::try_from_soup`], which reports what is wrong with it.
    ///
    /// # Errors
    ///
    /// An [`EulerError`] from the first operator that refuses, which happens
    /// when the polygons are not a closed, oriented, genus-0 manifold
    /// surface (for example [`EulerError::DifferentLoops`] for a handle);
    /// [`EulerError::InvalidPolygon`] never.
    pub(crate) fn try_sphere_from_polygons(soup: &PolygonSoup) -> Result<Solid, EulerError> {
        // The cyclic order of neighbours around each vertex, counter-clockwise
        // seen from outside: after `next` comes `prev` for each corner
        // `prev → v → next`.
        let mut after: HashMap<(usize, usize), usize> = HashMap::new();
        let mut neighbours: HashMap<usize, Vec<usize>> = HashMap::new();
        for p in &soup.polygons {
            let n = p.vertices.len();
            for i in 0..n {
                let (prev, v, next) = (
                    p.vertices[(i + n - 1) % n],
                    p.vertices[i],
                    p.vertices[(i + 1) % n],
                );
                after.insert((v, next), prev);
                neighbours.entry(v).or_default().push(next);
            }
        }
        let root = soup.polygons[0].vertices[0];
        let mut solid = Solid::default();
        let mut id: HashMap<usize, VertexId> = HashMap::new();
        let mut edge_of: HashMap<(usize, usize), EdgeId> = HashMap::new();
        let (root_id, _) = solid.mvfs(soup.positions[root])?;
        id.insert(root, root_id);
        // The corner at `v` where the edge towards `w` belongs: after the use
        // arriving from the first present neighbour that follows `w`.
        let corner = |solid: &Solid,
                      edge_of: &HashMap<(usize, usize), EdgeId>,
                      id: &HashMap<usize, VertexId>,
                      v: usize,
                      w: usize| {
            if solid.vertex(id[&v]).edge.is_none() {
                let l = solid
                    .loops()
                    .find(|(_, l)| l.start == LoopStart::Vertex(id[&v]))
                    .map(|(l, _)| l)
                    .expect("a vertex without edges is a lone loop");
                return Corner::Lone(l);
            }
            let mut x = after[&(v, w)];
            while !edge_of.contains_key(&(v.min(x), v.max(x))) {
                x = after[&(v, x)];
            }
            let edge = edge_of[&(v.min(x), v.max(x))];
            let side = if solid.edge(edge).origin == id[&x] {
                Side::Left
            } else {
                Side::Right
            };
            Corner::After(EdgeUse { edge, side })
        };
        let mut queue = VecDeque::from([root]);
        while let Some(v) = queue.pop_front() {
            for &w in &neighbours[&v] {
                if id.contains_key(&w) {
                    continue;
                }
                let at = corner(&solid, &edge_of, &id, v, w);
                let (edge, vertex) = solid.mev(at, soup.positions[w])?;
                id.insert(w, vertex);
                edge_of.insert((v.min(w), v.max(w)), edge);
                queue.push_back(w);
            }
        }
        for p in &soup.polygons {
            let n = p.vertices.len();
            for i in 0..n {
                let (a, b) = (p.vertices[i], p.vertices[(i + 1) % n]);
                if edge_of.contains_key(&(a.min(b), a.max(b))) {
                    continue;
                }
                let from = corner(&solid, &edge_of, &id, a, b);
                let to = corner(&solid, &edge_of, &id, b, a);
                let (edge, _) = solid.mef(from, to)?;
                edge_of.insert((a.min(b), a.max(b)), edge);
            }
        }
        // Each face from the polygon that runs its first use.
        let polygon_of: HashMap<(VertexId, VertexId), usize> = soup
            .polygons
            .iter()
            .enumerate()
            .flat_map(|(index, p)| {
                let n = p.vertices.len();
                let id = &id;
                (0..n).map(move |i| ((id[&p.vertices[i]], id[&p.vertices[(i + 1) % n]]), index))
            })
            .collect();
        let faces: Vec<_> = solid.faces.keys().collect();
        for face in faces {
            let u = solid
                .face_first_use(face)
                .expect("every face of a closed polyhedron has edges");
            let index = polygon_of[&(solid.use_start(u), solid.use_end(u))];
            let polygon = &soup.polygons[index];
            let points: Vec<DVec3> = polygon
                .vertices
                .iter()
                .map(|&v| soup.positions[v])
                .collect();
            let f = &mut solid.faces[face];
            f.plane = Plane::try_fit_newell(&points).ok().map(|fit| fit.plane);
            f.attributes = polygon.attributes.clone();
            f.attributes.source_index = Some(index);
        }
        for (&index, &v) in &id {
            solid.vertices[v].source_index = Some(index);
        }
        Ok(solid)
    }
}
