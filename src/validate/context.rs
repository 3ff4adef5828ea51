//! What every check needs, computed once from the soup: faces with repeated
//! corners collapsed, each face's shape class, duplicates, the edge table
//! and vertex incidence.
//!
//! All of it is index arithmetic on the soup (sorting, no hashing of
//! geometry), so it works on input that no winged-edge solid can hold.

use glam::DVec3;
use rayon::prelude::*;

use crate::compressed_rows::compressed_rows;
use crate::geom::polygon::{Projection, find_self_intersection};
use crate::geom::{Tolerance, collinear3d};
use crate::mesh::PolygonSoup;

/// How a face is shaped, before any geometry is judged.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Shape {
    /// At least three distinct vertices and edges.
    Polygon,
    /// Fewer than three distinct vertices.
    TooFewVertices,
    /// At least three distinct vertices but fewer than three distinct edges.
    TooFewEdges,
}

/// One use of an edge by a face (8 bytes: a million-face mesh has three
/// million).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct EdgeUse {
    face: u32,
    /// Whether the face runs the edge from its lower to its higher vertex.
    pub forward: bool,
}

impl EdgeUse {
    /// The face.
    pub fn face(&self) -> usize {
        self.face as usize
    }
}

/// An undirected edge between two distinct vertices (16 bytes).
#[derive(Clone, Debug)]
pub(crate) struct EdgeRecord {
    low: u32,
    high: u32,
    /// Where its uses are in [`Context::edge_uses`].
    start: u32,
    end: u32,
}

impl EdgeRecord {
    /// The lower vertex.
    pub fn low(&self) -> usize {
        self.low as usize
    }

    /// The higher vertex.
    pub fn high(&self) -> usize {
        self.high as usize
    }
}

/// The largest vertex, face or corner count validation accepts: tables
/// store them as 32-bit numbers to halve their memory.
pub(crate) const MAX_ELEMENTS: usize = u32::MAX as usize;

/// The checks' shared view of a soup.
///
/// # Invariants
///
/// Every face has at least one corner and no two equal corners in a row
/// (cyclically). Faces counted in the topology (`in_topology`) are
/// polygon-shaped and not later copies of duplicates; only they contribute
/// edges and vertex incidences. Edges are sorted by `(low, high)` with
/// `low < high`, each with at least one use.
pub(crate) struct Context<'a> {
    pub soup: &'a PolygonSoup,
    /// `v` line of each vertex, when known.
    pub vertex_lines: Option<&'a [usize]>,
    pub tolerance: Tolerance,
    /// Bounding box of the referenced vertices.
    pub bounds: crate::geom::Aabb,
    /// Its diagonal: the model size tolerances are scaled by.
    pub diagonal: f64,
    /// Corners of each face with consecutive repeats (cyclically) removed.
    /// (Offsets as `u32`: there are at most [`MAX_ELEMENTS`] corners.)
    corner_offsets: Vec<u32>,
    corner_list: Vec<usize>,
    /// Faces that listed a vertex twice in a row: (face, vertex).
    pub loop_edges: Vec<(usize, usize)>,
    pub shape: Vec<Shape>,
    /// For a later copy of a duplicate face: the first copy.
    pub duplicate_of: Vec<Option<u32>>,
    /// Whether the face counts in the edge and vertex tables.
    pub in_topology: Vec<bool>,
    /// Whether a polygon-shaped face is degenerate (see [`Context::degeneracy`]).
    pub degenerate: Vec<bool>,
    pub edges: Vec<EdgeRecord>,
    pub edge_uses: Vec<EdgeUse>,
    /// Vertex → faces (in topology), as offsets into a list.
    vertex_face_offsets: Vec<u32>,
    vertex_face_list: Vec<u32>,
    /// Vertex → edges, as offsets into a list.
    vertex_edge_offsets: Vec<usize>,
    vertex_edge_list: Vec<u32>,
    /// Whether any face (in topology or not) uses the vertex.
    pub referenced: Vec<bool>,
}

impl<'a> Context<'a> {
    pub fn new(
        soup: &'a PolygonSoup,
        vertex_lines: Option<&'a [usize]>,
        tolerance: Tolerance,
    ) -> Context<'a> {
        let n = soup.positions.len();
        let mut referenced = vec![false; n];
        let mut corner_offsets = Vec::with_capacity(soup.polygons.len() + 1);
        let mut corner_list = Vec::with_capacity(soup.polygons.len() * 3);
        let mut loop_edges = Vec::new();
        corner_offsets.push(0);
        for (face, p) in soup.polygons.iter().enumerate() {
            let start = corner_list.len();
            for &v in &p.vertices {
                if v < n {
                    referenced[v] = true;
                }
                if corner_list.len() > start && corner_list.last() == Some(&v) {
                    loop_edges.push((face, v));
                    continue;
                }
                corner_list.push(v);
            }
            while corner_list.len() > start + 1 && corner_list.last() == corner_list.get(start) {
                let v = corner_list.pop().unwrap_or_default();
                loop_edges.push((face, v));
            }
            if corner_list.len() == start + 1 && p.vertices.len() > 1 {
                // Every corner was the same vertex: the closing edge loops too.
                loop_edges.push((face, corner_list[start]));
            }
            corner_offsets.push(corner_list.len() as u32);
        }
        let bounds = crate::geom::Aabb::from_points(
            soup.positions
                .iter()
                .zip(&referenced)
                .filter(|(_, r)| **r)
                .map(|(p, _)| *p),
        );
        let diagonal = bounds.diagonal();
        let mut context = Context {
            soup,
            vertex_lines,
            tolerance,
            bounds,
            diagonal,
            corner_offsets,
            corner_list,
            loop_edges,
            shape: Vec::new(),
            duplicate_of: Vec::new(),
            in_topology: Vec::new(),
            degenerate: Vec::new(),
            edges: Vec::new(),
            edge_uses: Vec::new(),
            vertex_face_offsets: Vec::new(),
            vertex_face_list: Vec::new(),
            vertex_edge_offsets: Vec::new(),
            vertex_edge_list: Vec::new(),
            referenced,
        };
        context.classify_shapes();
        context.find_duplicates();
        context.in_topology = (0..soup.polygons.len())
            .map(|f| context.shape[f] == Shape::Polygon && context.duplicate_of[f].is_none())
            .collect();
        context.degenerate = (0..soup.polygons.len())
            .into_par_iter()
            .map(|f| context.shape[f] == Shape::Polygon && context.degeneracy(f).is_some())
            .collect();
        context.build_edges();
        context.build_incidence();
        context
    }

    /// Whether the soup's faces are exactly the faces of the topology: no
    /// repeats in a row, no duplicates, every face a polygon.
    pub fn is_clean(&self) -> bool {
        self.loop_edges.is_empty() && self.in_topology.iter().all(|&t| t)
    }

    /// The number of faces.
    pub fn face_count(&self) -> usize {
        self.soup.polygons.len()
    }

    /// The corners of `face`, consecutive repeats removed.
    pub fn corners(&self, face: usize) -> &[usize] {
        &self.corner_list
            [self.corner_offsets[face] as usize..self.corner_offsets[face + 1] as usize]
    }

    /// The position of vertex `v`.
    pub fn position(&self, v: usize) -> DVec3 {
        self.soup.positions[v]
    }

    /// The OBJ line of `face`.
    pub fn face_line(&self, face: usize) -> Option<usize> {
        self.soup.polygons[face].attributes.line
    }

    /// The `v` line of `vertex`.
    pub fn vertex_line(&self, vertex: usize) -> Option<usize> {
        self.vertex_lines.and_then(|l| l.get(vertex).copied())
    }

    /// "face 3 (line 17)".
    pub fn face_name(&self, face: usize) -> String {
        match self.face_line(face) {
            Some(l) => format!("face {face} (line {l})"),
            None => format!("face {face}"),
        }
    }

    /// "vertex 7 (line 9)".
    pub fn vertex_name(&self, vertex: usize) -> String {
        match self.vertex_line(vertex) {
            Some(l) => format!("vertex {vertex} (line {l})"),
            None => format!("vertex {vertex}"),
        }
    }

    /// The faces (in topology) around `vertex`, in face order.
    pub fn vertex_faces(&self, vertex: usize) -> &[u32] {
        &self.vertex_face_list[self.vertex_face_offsets[vertex] as usize
            ..self.vertex_face_offsets[vertex + 1] as usize]
    }

    /// The edges at `vertex`.
    pub fn vertex_edges(&self, vertex: usize) -> &[u32] {
        &self.vertex_edge_list
            [self.vertex_edge_offsets[vertex]..self.vertex_edge_offsets[vertex + 1]]
    }

    /// The uses of edge `edge`.
    pub fn uses(&self, edge: usize) -> &[EdgeUse] {
        let r = &self.edges[edge];
        &self.edge_uses[r.start as usize..r.end as usize]
    }

    /// Whether a face's corners (after collapsing) repeat a vertex or include
    /// two distinct vertices at one position, or are all collinear: the
    /// degenerate-face conditions, with the reason.
    pub fn degeneracy(&self, face: usize) -> Option<String> {
        let c = self.corners(face);
        if c.len() == 3 {
            let [a, b, d] = [c[0], c[1], c[2]].map(|v| self.position(v));
            if c[0] != c[1] && c[1] != c[2] && c[0] != c[2] && a != b && b != d && a != d {
                return collinear3d(a, b, d)
                    .then(|| "has all its vertices on one line (zero area)".to_string());
            }
        }
        let mut sorted: smallvec::SmallVec<[usize; 8]> = c.iter().copied().collect();
        sorted.sort_unstable();
        if let Some(w) = sorted.windows(2).find(|w| w[0] == w[1]) {
            return Some(format!("visits vertex {} twice", w[0]));
        }
        let mut by_position: smallvec::SmallVec<[(usize, DVec3); 8]> =
            c.iter().map(|&v| (v, self.position(v))).collect();
        by_position.sort_unstable_by(|a, b| {
            a.1.to_array()
                .partial_cmp(&b.1.to_array())
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        if let Some(w) = by_position.windows(2).find(|w| w[0].1 == w[1].1) {
            return Some(format!(
                "has vertices {} and {} at the same position",
                w[0].0.min(w[1].0),
                w[0].0.max(w[1].0)
            ));
        }
        let a = self.position(c[0]);
        let b = self.position(c[1]);
        if c[2..].iter().all(|&v| collinear3d(a, b, self.position(v))) {
            return Some("has all its vertices on one line (zero area)".to_string());
        }
        if c.len() > 3 {
            let projection = self.projection(face);
            let points: smallvec::SmallVec<[glam::DVec2; 8]> = c
                .iter()
                .map(|&v| projection.apply(self.position(v)))
                .collect();
            if let Some((i, j)) = find_self_intersection(&points) {
                return Some(format!(
                    "is not simple: its edges {}–{} and {}–{} meet",
                    c[i],
                    c[(i + 1) % c.len()],
                    c[j],
                    c[(j + 1) % c.len()]
                ));
            }
        }
        None
    }

    /// The axis projection for a face: the axis plane nearest to its Newell
    /// plane, or, when the Newell vector is zero (a bow tie whose loops
    /// cancel), nearest to the largest triangle fanned from its first corner.
    /// Only proposes the axis; decisions in the projection are exact.
    pub fn projection(&self, face: usize) -> Projection {
        let c = self.corners(face);
        let o = self.position(c[0]);
        let points: smallvec::SmallVec<[DVec3; 8]> = c.iter().map(|&v| self.position(v)).collect();
        let newell = crate::geom::newell_vector_area(&points, o);
        if newell != DVec3::ZERO {
            return Projection::along(newell);
        }
        let largest = (1..c.len().saturating_sub(1))
            .map(|i| (points[i] - o).cross(points[i + 1] - o))
            .fold(DVec3::ZERO, |best, n| {
                if n.length_squared() > best.length_squared() {
                    n
                } else {
                    best
                }
            });
        Projection::along(largest)
    }

    fn classify_shapes(&mut self) {
        self.shape = (0..self.face_count())
            .into_par_iter()
            .map(|f| {
                let c = self.corners(f);
                if c.len() == 3 && c[0] != c[1] && c[1] != c[2] && c[2] != c[0] {
                    return Shape::Polygon;
                }
                let mut vertices: smallvec::SmallVec<[usize; 8]> = c.iter().copied().collect();
                vertices.sort_unstable();
                vertices.dedup();
                if vertices.len() < 3 {
                    return Shape::TooFewVertices;
                }
                let k = c.len();
                let mut edges: smallvec::SmallVec<[(usize, usize); 8]> = (0..k)
                    .map(|i| {
                        let (a, b) = (c[i], c[(i + 1) % k]);
                        (a.min(b), a.max(b))
                    })
                    .collect();
                edges.sort_unstable();
                edges.dedup();
                if edges.len() < 3 {
                    Shape::TooFewEdges
                } else {
                    Shape::Polygon
                }
            })
            .collect();
    }

    /// A face's cycle in canonical form: rotated to start at its smallest
    /// vertex, and of the two directions the lexicographically smaller.
    fn canonical_cycle(corners: &[usize]) -> Vec<usize> {
        let k = corners.len();
        let start = (0..k).min_by_key(|&i| corners[i]).unwrap_or(0);
        let forward: Vec<usize> = (0..k).map(|i| corners[(start + i) % k]).collect();
        let backward: Vec<usize> = (0..k).map(|i| corners[(start + k - i) % k]).collect();
        forward.min(backward)
    }

    fn find_duplicates(&mut self) {
        // Sort by a hash of the canonical cycle; compare cycles only within
        // runs of equal hashes.
        // Independent of rotation and direction, so equal cycles hash alike.
        let hash = |c: &[usize]| {
            let mix = |v: usize| {
                let mut x = (v as u64).wrapping_add(0x9e37_79b9_7f4a_7c15);
                x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
                x ^ (x >> 31)
            };
            let (sum, xor) = c.iter().fold((c.len() as u64, 0u64), |(s, x), &v| {
                (s.wrapping_add(mix(v)), x ^ mix(v).rotate_left(23))
            });
            sum ^ xor.rotate_left(7)
        };
        let mut keyed: Vec<(u64, usize)> = (0..self.face_count())
            .into_par_iter()
            .filter(|&f| self.shape[f] == Shape::Polygon)
            .map(|f| (hash(self.corners(f)), f))
            .collect();
        keyed.par_sort_unstable();
        self.duplicate_of = vec![None; self.face_count()];
        for run in keyed.chunk_by(|a, b| a.0 == b.0).filter(|r| r.len() > 1) {
            let cycles: Vec<Vec<usize>> = run
                .iter()
                .map(|&(_, f)| Context::canonical_cycle(self.corners(f)))
                .collect();
            for i in 1..run.len() {
                if let Some(j) = (0..i).find(|&j| cycles[j] == cycles[i]) {
                    // Face numbers fit: there are at most `MAX_ELEMENTS`.
                    let first = self.duplicate_of[run[j].1].unwrap_or(run[j].1 as u32);
                    self.duplicate_of[run[i].1] = Some(first);
                }
            }
        }
    }

    /// Edge uses sorted by their undirected edge: keys pack the two vertex
    /// numbers into 64 bits and the face and direction into another 64, so
    /// the sort moves 16-byte items.
    fn build_edges(&mut self) {
        let mut half: Vec<(u64, u64)> = Vec::with_capacity(self.corner_list.len());
        for face in 0..self.face_count() {
            if !self.in_topology[face] {
                continue;
            }
            let c = self.corners(face);
            let k = c.len();
            for i in 0..k {
                let (a, b) = (c[i] as u64, c[(i + 1) % k] as u64);
                let key = (a.min(b) << 32) | a.max(b);
                half.push((key, ((face as u64) << 1) | u64::from(a < b)));
            }
        }
        half.par_sort_unstable();
        let mut edges = Vec::with_capacity(half.len() / 2 + 1);
        let mut start = 0;
        for group in half.chunk_by(|x, y| x.0 == y.0) {
            edges.push(EdgeRecord {
                low: (group[0].0 >> 32) as u32,
                high: (group[0].0 & 0xffff_ffff) as u32,
                start: start as u32,
                end: (start + group.len()) as u32,
            });
            start += group.len();
        }
        self.edge_uses = half
            .into_iter()
            .map(|(_, use_)| EdgeUse {
                face: (use_ >> 1) as u32,
                forward: use_ & 1 == 1,
            })
            .collect();
        self.edges = edges;
    }

    fn build_incidence(&mut self) {
        let n = self.soup.positions.len();
        // The two tables are independent: built side by side.
        let ((face_offsets, face_list), (edge_offsets, edge_list)) = rayon::join(
            || {
                compressed_rows(
                    n,
                    (0..self.face_count())
                        .filter(|&f| self.in_topology[f])
                        .flat_map(|f| self.corners(f).iter().map(move |&v| (v, f as u32))),
                )
            },
            || {
                compressed_rows(
                    n,
                    self.edges
                        .iter()
                        .enumerate()
                        .flat_map(|(e, r)| [(r.low(), e as u32), (r.high(), e as u32)]),
                )
            },
        );
        // The face offsets fit `u32`: they count corners, at most
        // `MAX_ELEMENTS`.
        self.vertex_face_offsets = face_offsets.into_iter().map(|o| o as u32).collect();
        self.vertex_face_list = face_list;
        self.vertex_edge_offsets = edge_offsets;
        self.vertex_edge_list = edge_list;
    }
}
