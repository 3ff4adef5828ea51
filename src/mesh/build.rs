//! Building a winged-edge solid from an indexed polygon soup.
//!
//! The build works in index space first (half-edges numbered by polygon
//! corner, a compressed vertex → outgoing half-edges table, sorted by end
//! vertex, to find twins by binary search), checks everything a winged-edge
//! solid cannot represent, and only then fills the slotmap tables. It runs
//! in time O(n log d) for n corners and vertex valence d.

use glam::DVec3;
use rayon::prelude::*;
use slotmap::{Key, SlotMap};

use crate::geom::Plane;

mod around_edge;
mod error;
mod half_edges;
use super::{
    Edge, EdgeId, EdgeUse, Face, FaceId, Loop, LoopId, LoopStart, PolygonSoup, Side, Solid, Vertex,
    VertexId,
};
use around_edge::{EdgeUse as AroundEdge, pair_around_edge};
pub use error::BuildError;
use half_edges::{HalfEdges, Outgoing};

impl Solid {
    /// Builds a solid from positions and polygons given as index lists.
    ///
    /// # Errors
    ///
    /// As for [`Solid::try_from_soup`].
    pub fn try_from_polygons<P: AsRef<[usize]>>(
        positions: &[DVec3],
        polygons: impl IntoIterator<Item = P>,
    ) -> Result<Solid, BuildError> {
        Solid::try_from_soup(&PolygonSoup::new(positions.to_vec(), polygons))
    }

    /// Builds a winged-edge solid from a polygon soup.
    ///
    /// Each polygon becomes a face carrying its attributes; each referenced
    /// soup vertex becomes a vertex (unreferenced ones are left out); each
    /// unordered pair of consecutive corners becomes an edge. An edge used by
    /// one polygon is kept as a boundary edge (open surfaces are
    /// representable). Faces whose vertices are collinear get no plane.
    ///
    /// # Errors
    ///
    /// The first problem found, in polygon order: [`BuildError::NoPolygons`],
    /// [`BuildError::TooFewVertices`], [`BuildError::IndexOutOfRange`],
    /// [`BuildError::RepeatedVertex`], [`BuildError::NonFinitePosition`],
    /// [`BuildError::NonManifoldEdge`] (three or more polygons on an edge),
    /// and [`BuildError::InconsistentOrientation`] (an edge run twice in one
    /// direction). A vertex around which the faces form several fans (a
    /// pinch: two cones sharing a tip, or two holes touching at a corner) is
    /// not an error: each fan after the first gets its own vertex at the same
    /// position with the same soup index
    /// ([`Vertex::source_index`](super::Vertex::source_index)), and a hole
    /// that passes the vertex turns around the fan it borders, so each copy
    /// has at most one boundary edge in and one out. The solid builds and
    /// queries answer; validation reports the pinch and the open edges from
    /// the soup.
    pub fn try_from_soup(soup: &PolygonSoup) -> Result<Solid, BuildError> {
        build(soup, EdgeSharing::Manifold)
    }

    /// Builds a solid from a soup whose sheets may touch along edges, as
    /// the result of a boolean does (two cubes sharing an edge unite into
    /// two cubes touching along it).
    ///
    /// As [`Solid::try_from_soup`], except for an edge used by `2k`
    /// triangles, `k` running it each way: it becomes `k` edges, each
    /// triangle paired with its neighbour around the edge on the side its
    /// solid is on (angles compared exactly), and the vertices at its ends
    /// are then split per fan like pinches. Each sheet is then closed on
    /// its own; the copies touch.
    ///
    /// # Errors
    ///
    /// As [`Solid::try_from_soup`]; [`BuildError::NonManifoldEdge`] also
    /// when the uses of such an edge cannot be paired: a polygon on it is
    /// not a triangle, the uses do not alternate in direction around it
    /// (sheets that would cross there), or two triangles on it lie at one
    /// angle (a fold).
    pub fn try_from_touching_soup(soup: &PolygonSoup) -> Result<Solid, BuildError> {
        build(soup, EdgeSharing::Touching)
    }
}

/// What an edge used by more than two polygons means to the builder.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum EdgeSharing {
    /// It is refused: a face's edge has at most one other face.
    Manifold,
    /// Sheets touch along it: its triangles are paired around it.
    Touching,
}

fn build(soup: &PolygonSoup, sharing: EdgeSharing) -> Result<Solid, BuildError> {
    check_polygons(soup, RepeatedVertices::Refuse)?;
    let mut halves = corner_half_edges(soup, Links::Fill);
    let mut outgoing = Outgoing::new(soup.positions.len(), &halves.from);
    pair_twins(soup, &mut halves, &mut outgoing, sharing)?;
    link_holes(&mut halves);
    split_pinches(soup, &mut halves, &outgoing);
    if sharing == EdgeSharing::Touching {
        check_no_parallel_edges(soup, &halves)?;
    }
    // Freed before the solid's tables are allocated (lowers the peak).
    drop(outgoing);
    Ok(assemble(soup, &halves))
}

/// Whether [`Solid::try_from_soup`] of `soup` succeeds, and its error when
/// not, without building the solid: the build's checks only (polygons,
/// then the pairing of half-edges into twins), which are all the steps
/// that can fail, on tables without the loop links. For a caller that
/// needs the verdict alone (validation's report), at a fraction of the
/// build's memory.
///
/// # Errors
///
/// Exactly the error [`Solid::try_from_soup`] returns.
pub(crate) fn check_buildable(soup: &PolygonSoup) -> Result<(), BuildError> {
    check_polygons(soup, RepeatedVertices::Refuse)?;
    let mut halves = corner_half_edges(soup, Links::Skip);
    let mut outgoing = Outgoing::new(soup.positions.len(), &halves.from);
    pair_twins(soup, &mut halves, &mut outgoing, EdgeSharing::Manifold)
}

/// Whether the half-edge tables get their loop links (`next`, `prev`):
/// the assembly needs them, the pairing of twins of a manifold build does
/// not.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Links {
    /// Filled for every face half-edge.
    Fill,
    /// Left empty.
    Skip,
}

/// Whether a polygon may visit a vertex twice.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum RepeatedVertices {
    /// Refused with [`BuildError::RepeatedVertex`]: a face of a solid is a
    /// simple cycle of edges.
    Refuse,
    /// Accepted: a polygon only fanned into triangles (the winding number of
    /// a soup) may touch itself.
    Allow,
}

/// Checks what every use of a soup's polygons needs, polygon by polygon in
/// order: at least one polygon ([`BuildError::NoPolygons`]), at least three
/// corners each ([`BuildError::TooFewVertices`]), indices in range
/// ([`BuildError::IndexOutOfRange`]), no vertex visited twice unless
/// `repeated` allows it ([`BuildError::RepeatedVertex`]), and finite
/// positions for every vertex used ([`BuildError::NonFinitePosition`]).
///
/// # Errors
///
/// The first of those problems found.
pub(crate) fn check_polygons(
    soup: &PolygonSoup,
    repeated: RepeatedVertices,
) -> Result<(), BuildError> {
    if soup.polygons.is_empty() {
        return Err(BuildError::NoPolygons);
    }
    let len = soup.positions.len();
    let mut seen: Vec<usize> = Vec::new();
    for (polygon, p) in soup.polygons.iter().enumerate() {
        let line = p.attributes.line;
        if p.vertices.len() < 3 {
            return Err(BuildError::TooFewVertices {
                polygon,
                line,
                count: p.vertices.len(),
            });
        }
        if let Some(&index) = p.vertices.iter().find(|&&i| i >= len) {
            return Err(BuildError::IndexOutOfRange {
                polygon,
                line,
                index,
                len,
            });
        }
        if repeated == RepeatedVertices::Refuse {
            seen.clear();
            seen.extend_from_slice(&p.vertices);
            seen.sort_unstable();
            if let Some(w) = seen.windows(2).find(|w| w[0] == w[1]) {
                return Err(BuildError::RepeatedVertex {
                    polygon,
                    line,
                    vertex: w[0],
                });
            }
        }
        if let Some(&vertex) = p.vertices.iter().find(|&&i| !soup.positions[i].is_finite()) {
            return Err(BuildError::NonFinitePosition {
                vertex,
                position: soup.positions[vertex],
            });
        }
    }
    Ok(())
}

fn corner_half_edges(soup: &PolygonSoup, links: Links) -> HalfEdges {
    let corners: usize = soup.polygons.iter().map(|p| p.vertices.len()).sum();
    let linked = if links == Links::Fill { corners } else { 0 };
    let mut h = HalfEdges {
        from: Vec::with_capacity(corners),
        to: Vec::with_capacity(corners),
        polygon: Vec::with_capacity(corners),
        next: Vec::with_capacity(linked),
        prev: Vec::with_capacity(linked),
        twin: Vec::new(),
        face_count: corners,
        split_from: Vec::new(),
    };
    for (index, p) in soup.polygons.iter().enumerate() {
        let base = h.from.len();
        let n = p.vertices.len();
        for i in 0..n {
            h.from.push(p.vertices[i]);
            h.to.push(p.vertices[(i + 1) % n]);
            h.polygon.push(index);
            if links == Links::Fill {
                h.next.push(base + (i + 1) % n);
                h.prev.push(base + (i + n - 1) % n);
            }
        }
    }
    h.twin = vec![usize::MAX; corners];
    h
}

/// How many face half-edges run one half-edge's edge its way (itself
/// included) and the other way, and the first of those the other way.
#[derive(Clone, Copy, Debug)]
struct EdgeUses {
    same: usize,
    opposite: usize,
    first_opposite: Option<usize>,
}

/// Pairs each face half-edge with the one running its edge the other way.
/// The outgoing lists of vertices of high valence are sorted by end vertex
/// once and searched by halving; the short lists of every other vertex are
/// scanned. O(n log d) for n corners and valence d, where a scan of every
/// list once per half-edge cost O(n d).
fn pair_twins(
    soup: &PolygonSoup,
    h: &mut HalfEdges,
    out: &mut Outgoing,
    sharing: EdgeSharing,
) -> Result<(), BuildError> {
    out.sort_by_end(&h.to);
    // Each half-edge's uses are read from the lists in parallel, a chunk
    // of half-edges at a time (the chunk's counts are all that is held);
    // the pairing below then visits the half-edges in order, as a serial
    // scan would, and lists the uses again only where an edge has more
    // than two or two the same way. The counts depend on the lists alone,
    // which the pairing does not change.
    let mut uses: Vec<EdgeUses> = Vec::with_capacity(USES_CHUNK.min(h.face_count));
    for chunk in (0..h.face_count).step_by(USES_CHUNK) {
        let chunk = chunk..(chunk + USES_CHUNK).min(h.face_count);
        uses.clear();
        {
            let (out, h) = (&*out, &*h);
            uses.par_extend(chunk.clone().into_par_iter().map(|e| {
                let (a, b) = (h.from[e], h.to[e]);
                EdgeUses {
                    same: out.count_towards(a, b, &h.to),
                    opposite: out.count_towards(b, a, &h.to),
                    first_opposite: out.towards(b, a, &h.to).next(),
                }
            }));
        }
        for (e, &counted) in chunk.zip(&uses) {
            pair_one(soup, h, out, sharing, e, counted)?;
        }
    }
    Ok(())
}

/// How many half-edges [`pair_twins`] counts the uses of at once.
const USES_CHUNK: usize = 1 << 16;

/// Pairs face half-edge `e`, whose uses are `counted`, unless an earlier
/// half-edge of its edge already did.
fn pair_one(
    soup: &PolygonSoup,
    h: &mut HalfEdges,
    out: &Outgoing,
    sharing: EdgeSharing,
    e: usize,
    counted: EdgeUses,
) -> Result<(), BuildError> {
    let line = |h: &HalfEdges, e: usize| soup.polygons[h.polygon[e]].attributes.line;
    if h.twin[e] != usize::MAX {
        // Paired with the other uses of a shared edge.
        return Ok(());
    }
    let (a, b) = (h.from[e], h.to[e]);
    if counted.same + counted.opposite >= 3 {
        let same: smallvec::SmallVec<[usize; 2]> = out.towards(a, b, &h.to).collect();
        let opposite: smallvec::SmallVec<[usize; 2]> = out.towards(b, a, &h.to).collect();
        let pairs = match sharing {
            EdgeSharing::Touching => pair_touching(soup, h, a, b, &same, &opposite),
            EdgeSharing::Manifold => None,
        };
        if let Some(pairs) = pairs {
            for (g, t) in pairs {
                h.twin[g] = t;
                h.twin[t] = g;
            }
            return Ok(());
        }
        let mut users: Vec<usize> = same.iter().chain(&opposite).copied().collect();
        users.sort_unstable();
        return Err(BuildError::NonManifoldEdge {
            vertices: [a.min(b), a.max(b)],
            polygons: users.iter().map(|&g| h.polygon[g]).collect(),
            lines: users.iter().map(|&g| line(h, g)).collect(),
        });
    }
    if counted.same == 2 {
        let same: smallvec::SmallVec<[usize; 2]> = out.towards(a, b, &h.to).collect();
        return Err(BuildError::InconsistentOrientation {
            vertices: [a, b],
            polygons: [h.polygon[same[0]], h.polygon[same[1]]],
            lines: [line(h, same[0]), line(h, same[1])],
        });
    }
    if let Some(t) = counted.first_opposite {
        h.twin[e] = t;
    }
    Ok(())
}

/// The twins of the half-edges `same` (running `a → b`) and `opposite`
/// around an edge that sheets touch along, when every polygon on it is a
/// triangle and they pair (see [`pair_around_edge`]).
fn pair_touching(
    soup: &PolygonSoup,
    h: &HalfEdges,
    a: usize,
    b: usize,
    same: &[usize],
    opposite: &[usize],
) -> Option<Vec<(usize, usize)>> {
    let uses: Vec<AroundEdge> = same
        .iter()
        .map(|&g| (g, true))
        .chain(opposite.iter().map(|&g| (g, false)))
        .map(|(g, forward)| {
            (soup.polygons[h.polygon[g]].vertices.len() == 3).then(|| AroundEdge {
                half_edge: g,
                forward,
                third: soup.positions[h.to[h.next[g]]],
            })
        })
        .collect::<Option<_>>()?;
    pair_around_edge(soup.positions[a], soup.positions[b], &uses)
}

/// Gives every face half-edge without a twin a twin running around its hole,
/// and links the hole half-edges into loops.
///
/// A hole half-edge arriving at a vertex is followed by the hole half-edge
/// leaving it on the same fan of faces: the one met by turning around the
/// vertex from the arriving half-edge's twin, face by face across shared
/// edges, until a face's incoming edge has no face on its other side. Where
/// only one hole passes a vertex that is the only hole half-edge leaving it;
/// where several holes meet at a vertex (open fans touching at one point),
/// each hole turns around its own fan, so that every fan then has one hole
/// half-edge in and one out, and [`split_pinches`] gives each fan a vertex
/// of its own.
fn link_holes(h: &mut HalfEdges) {
    for e in 0..h.face_count {
        if h.twin[e] != usize::MAX {
            continue;
        }
        let g = h.from.len();
        h.from.push(h.to[e]);
        h.to.push(h.from[e]);
        h.twin.push(e);
        h.twin[e] = g;
    }
    h.next.resize(h.from.len(), usize::MAX);
    h.prev.resize(h.from.len(), usize::MAX);
    for g in h.face_count..h.from.len() {
        // `g` arrives at `from[e]` for its twin `e`. Turning from `e` to the
        // face half-edge across its incoming edge visits the fan's corners
        // in order; no corner is visited twice (the turn is one-to-one and
        // nothing turns into `e`, whose twin is a hole half-edge), so the
        // walk ends within the vertex's valence, at a hole half-edge.
        let mut corner = h.twin[g];
        let next = loop {
            let across = h.twin[h.prev[corner]];
            if across >= h.face_count {
                break across;
            }
            corner = across;
        };
        h.next[g] = next;
        h.prev[next] = g;
    }
}

/// Gives each fan of faces around a pinch vertex (two cones sharing a tip,
/// or holes touching at a corner: see [`link_holes`]) a vertex of its own: the first fan keeps the soup's vertex, each other
/// fan gets a copy at the same position with the same soup index (so
/// reports still name the OBJ vertex). The solid is then a 2-manifold
/// whose copies touch; validation reports the pinch from the soup.
fn split_pinches(soup: &PolygonSoup, h: &mut HalfEdges, out: &Outgoing) {
    // Every edge leaves each endpoint exactly once (as a face or a hole
    // half-edge); a single fan visits them all from any of them.
    let len = soup.positions.len();
    let mut degree = vec![0usize; len];
    for &v in &h.from {
        degree[v] += 1;
    }
    let mut done = vec![false; len];
    let mut seen = vec![false; h.from.len()];
    for e in 0..h.face_count {
        let v = h.from[e];
        if v >= len || done[v] {
            continue;
        }
        done[v] = true;
        if walk_fan(h, e, &mut seen) == degree[v] {
            continue;
        }
        // More than one fan: every other one moves to a copy of `v`.
        for &start in out.of(v) {
            if seen[start] {
                continue;
            }
            let copy = len + h.split_from.len();
            h.split_from.push(v);
            let mut g = start;
            loop {
                seen[g] = true;
                h.from[g] = copy;
                let incoming = h.prev[g];
                h.to[incoming] = copy;
                g = h.twin[incoming];
                if g == start {
                    break;
                }
            }
        }
    }
}

/// Marks the fan of half-edges leaving `e`'s origin that `e` is in; returns
/// its size.
fn walk_fan(h: &HalfEdges, e: usize, seen: &mut [bool]) -> usize {
    let mut size = 0;
    let mut g = e;
    loop {
        seen[g] = true;
        size += 1;
        g = h.twin[h.prev[g]];
        if g == e {
            return size;
        }
    }
}

/// Refuses sheets paired along an edge whose end vertices stayed shared
/// (their fans are joined elsewhere): the copies of the edge would run
/// between the same two vertices, which the winged-edge tables cannot hold.
fn check_no_parallel_edges(soup: &PolygonSoup, h: &HalfEdges) -> Result<(), BuildError> {
    let len = soup.positions.len();
    let soup_vertex = |v: usize| if v < len { v } else { h.split_from[v - len] };
    let mut first: rustc_hash::FxHashMap<(usize, usize), usize> = Default::default();
    for e in 0..h.face_count {
        let t = h.twin[e];
        if t < h.face_count && t < e {
            continue;
        }
        let key = (h.from[e].min(h.to[e]), h.from[e].max(h.to[e]));
        if let Some(&other) = first.get(&key) {
            let mut polygons: Vec<usize> = [e, h.twin[e], other, h.twin[other]]
                .into_iter()
                .filter(|&g| g < h.face_count)
                .map(|g| h.polygon[g])
                .collect();
            polygons.sort_unstable();
            polygons.dedup();
            return Err(BuildError::NonManifoldEdge {
                vertices: [soup_vertex(h.from[e]), soup_vertex(h.to[e])],
                lines: polygons
                    .iter()
                    .map(|&p| soup.polygons[p].attributes.line)
                    .collect(),
                polygons,
            });
        }
        first.insert(key, e);
    }
    Ok(())
}

fn assemble(soup: &PolygonSoup, h: &HalfEdges) -> Solid {
    // Vertices in soup order, referenced ones only.
    let len = soup.positions.len();
    let soup_vertex = |v: usize| if v < len { v } else { h.split_from[v - len] };
    let mut referenced = vec![false; len + h.split_from.len()];
    for &v in &h.from[..h.face_count] {
        referenced[v] = true;
    }
    // The tables get their exact sizes up front: grown by doubling, a
    // million-face solid would hold up to twice the slots it needs, and
    // briefly both the old and the new buffer while growing.
    let edge_count = (0..h.face_count)
        .filter(|&e| h.twin[e] >= h.face_count || e < h.twin[e])
        .count();
    let mut solid = Solid {
        vertices: SlotMap::with_capacity_and_key(referenced.iter().filter(|&&r| r).count()),
        edges: SlotMap::with_capacity_and_key(edge_count),
        faces: SlotMap::with_capacity_and_key(soup.polygons.len()),
        loops: SlotMap::with_capacity_and_key(soup.polygons.len()),
    };
    let vertex_ids: Vec<VertexId> = referenced
        .iter()
        .enumerate()
        .map(|(v, &used)| {
            if !used {
                return VertexId::null();
            }
            solid.vertices.insert(Vertex {
                position: soup.positions[soup_vertex(v)],
                edge: None,
                source_index: Some(soup_vertex(v)),
            })
        })
        .collect();
    // The faces' planes, fitted in parallel (each depends on its polygon
    // alone).
    let planes: Vec<Option<Plane>> = soup
        .polygons
        .par_iter()
        .map(|p| {
            let points: smallvec::SmallVec<[DVec3; 8]> =
                p.vertices.iter().map(|&v| soup.positions[v]).collect();
            Plane::try_fit_newell(&points).ok().map(|fit| fit.plane)
        })
        .collect();
    // Faces first with placeholder loops, so that edges can name them.
    let face_ids: Vec<FaceId> = soup
        .polygons
        .iter()
        .zip(planes)
        .enumerate()
        .map(|(index, (p, plane))| {
            let mut attributes = p.attributes.clone();
            attributes.source_index = Some(index);
            solid.faces.insert(Face {
                plane,
                outer: LoopId::null(),
                rings: Vec::new(),
                attributes,
            })
        })
        .collect();
    // One edge per twin pair, oriented like its first face half-edge.
    let mut edge_of = vec![EdgeId::null(); h.from.len()];
    for e in 0..h.face_count {
        let t = h.twin[e];
        if !edge_of[e].is_null() {
            continue;
        }
        let right_face = (t < h.face_count).then(|| face_ids[h.polygon[t]]);
        let id = solid.edges.insert(Edge {
            origin: vertex_ids[h.from[e]],
            dest: vertex_ids[h.to[e]],
            left_face: face_ids[h.polygon[e]],
            right_face,
            cw_left: EdgeId::null(),
            ccw_left: EdgeId::null(),
            cw_right: EdgeId::null(),
            ccw_right: EdgeId::null(),
        });
        edge_of[e] = id;
        edge_of[t] = id;
    }
    // Wings: for each half-edge, the edges of its neighbours in its loop.
    for g in 0..h.from.len() {
        let id = edge_of[g];
        let (next, prev) = (edge_of[h.next[g]], edge_of[h.prev[g]]);
        let edge = &mut solid.edges[id];
        if vertex_ids[h.from[g]] == edge.origin {
            edge.ccw_left = next;
            edge.cw_left = prev;
        } else {
            edge.ccw_right = next;
            edge.cw_right = prev;
        }
    }
    // Each face's loop starts at the use of its last corner's edge.
    let mut starts: Vec<Option<EdgeUse>> = vec![None; soup.polygons.len()];
    for e in 0..h.face_count {
        let edge = edge_of[e];
        let side = if solid.edges[edge].origin == vertex_ids[h.from[e]] {
            Side::Left
        } else {
            Side::Right
        };
        starts[h.polygon[e]] = Some(EdgeUse { edge, side });
        solid.vertices[vertex_ids[h.from[e]]].edge = Some(edge);
    }
    for (&face, start) in face_ids.iter().zip(starts) {
        let start = LoopStart::Edge(start.expect("a polygon has at least three corners"));
        solid.faces[face].outer = solid.loops.insert(Loop { face, start });
    }
    debug_assert!(
        solid.check_consistency().is_ok(),
        "{:?}",
        solid.check_consistency()
    );
    solid
}
