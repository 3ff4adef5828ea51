//! Sheets that cross along coincident edges.
//!
//! Two sheets may touch along an edge where each has an edge of its own at
//! the same two positions (two cubes sharing an edge, after a boolean).
//! Pairwise tests see each pair of triangles there meet only along the
//! edge whether the sheets touch or cross: crossing is a matter of the
//! order of all the triangles around the edge.
//!
//! Seen along the axis `a → b` (the edge's positions in a fixed order), a
//! triangle running the edge `a → b` has its solid on its clockwise side,
//! one running `b → a` on its counterclockwise side (its outward normal
//! is a quarter-turn ahead of or behind its third corner). The sheets only
//! touch when every solid wedge is closed by the same edge: sorted
//! counterclockwise (exact, [`sorted_around`]), the triangle after each one that
//! runs `b → a` runs the same vertex edge `a → b`. Otherwise a sheet's
//! wedge holds another sheet's triangle: they cross there, or one sheet's
//! solid overlaps the other's.
//!
//! Only edges whose both ends share their position with another vertex
//! are looked at; a vertex edge that is not used once each way is left to
//! the edge rules. A face's direction along an edge is its loop's (its
//! triangles may be wound either way); a diagonal of a face's
//! triangulation lying along another sheet's edge is a contact inside the
//! face, reported too.

use rustc_hash::FxHashMap as HashMap;

use glam::DVec3;

use super::super::super::context::Context;
use super::triangles::Triangle;
use crate::geom::around_axis::sorted_around;

/// One use of an edge at coincident positions.
#[derive(Clone, Copy, Debug)]
struct Use {
    /// The vertex edge (smaller vertex first).
    edge: (usize, usize),
    /// Whether the face runs the edge from the first position of the key
    /// to the second; `None` when the edge is a diagonal of its face.
    forward: Option<bool>,
    third: DVec3,
    face: usize,
}

/// The pairs of faces (smaller first) whose sheets cross along coincident
/// edges: a solid wedge around such an edge holds the face named second
/// (or two triangles lie at one angle there).
pub(super) fn crossing_along_coincident_edges(
    ctx: &Context,
    triangles: &[Triangle],
) -> Vec<(usize, usize)> {
    let key = |v: usize| (ctx.position(v) + DVec3::ZERO).to_array().map(f64::to_bits);
    // The vertices that share their position with another.
    let mut by_position: HashMap<[u64; 3], (usize, bool)> = HashMap::default();
    for t in triangles {
        for &v in &t.vertices {
            by_position
                .entry(key(v))
                .and_modify(|(first, shared)| *shared |= *first != v)
                .or_insert((v, false));
        }
    }
    if by_position.values().all(|&(_, shared)| !shared) {
        return Vec::new();
    }
    let shared = |v: usize| by_position[&key(v)].1;
    // The uses of each edge between two such vertices, by positions.
    let mut around: HashMap<([u64; 3], [u64; 3]), Vec<Use>> = HashMap::default();
    for t in triangles {
        for k in 0..3 {
            let (u, w) = (t.vertices[k], t.vertices[(k + 1) % 3]);
            if !shared(u) || !shared(w) {
                continue;
            }
            let (ku, kw) = (key(u), key(w));
            // The face's direction along the edge (a face's triangles may
            // be wound either way), or none for a diagonal.
            let corners = ctx.corners(t.face);
            let runs = |x: usize, y: usize| {
                (0..corners.len()).any(|i| corners[i] == x && corners[(i + 1) % corners.len()] == y)
            };
            let along = if runs(u, w) {
                Some(true)
            } else if runs(w, u) {
                Some(false)
            } else {
                None
            };
            let forward = along.map(|along| along == (ku < kw));
            around
                .entry(if ku < kw { (ku, kw) } else { (kw, ku) })
                .or_default()
                .push(Use {
                    edge: (u.min(w), u.max(w)),
                    forward,
                    third: ctx.position(t.vertices[(k + 2) % 3]),
                    face: t.face,
                });
        }
    }
    let mut pairs = Vec::new();
    for ((ka, kb), uses) in around {
        if uses.iter().all(|u| u.edge == uses[0].edge) {
            continue;
        }
        let (a, b) = (
            DVec3::from_array(ka.map(f64::from_bits)),
            DVec3::from_array(kb.map(f64::from_bits)),
        );
        pairs.extend(crossings_around(a, b, &uses));
    }
    pairs
}

/// The face pairs at which the uses around the edge `a → b` do not close
/// each solid wedge with its own edge; nothing when some vertex edge is not
/// used once each way (other rules report that).
fn crossings_around(a: DVec3, b: DVec3, uses: &[Use]) -> Vec<(usize, usize)> {
    // A diagonal of a face along another sheet's edge: a contact inside a
    // face, which should have been an edge of it.
    if let Some(diagonal) = uses.iter().find(|u| u.forward.is_none()) {
        return uses
            .iter()
            .filter(|u| u.face != diagonal.face)
            .map(|u| (u.face.min(diagonal.face), u.face.max(diagonal.face)))
            .collect();
    }
    let mut per_edge: HashMap<(usize, usize), [usize; 2]> = HashMap::default();
    for u in uses {
        per_edge.entry(u.edge).or_default()[usize::from(u.forward == Some(true))] += 1;
    }
    if per_edge.values().any(|&n| n != [1, 1]) {
        return Vec::new();
    }
    let thirds: Vec<DVec3> = uses.iter().map(|u| u.third).collect();
    let Some(sorted) = sorted_around(a, b, &thirds) else {
        // No strict order (two faces at one angle, a fold): every pair of
        // faces of different sheets there.
        let mut pairs = Vec::new();
        for (i, u) in uses.iter().enumerate() {
            for v in &uses[i + 1..] {
                if u.edge != v.edge && u.face != v.face {
                    pairs.push((u.face.min(v.face), u.face.max(v.face)));
                }
            }
        }
        return pairs;
    };
    let n = sorted.len();
    let mut pairs = Vec::new();
    for k in 0..n {
        let (u, next) = (&uses[sorted[k]], &uses[sorted[(k + 1) % n]]);
        let open = u.forward == Some(false) && !(next.forward == Some(true) && next.edge == u.edge);
        if open && u.face != next.face {
            pairs.push((u.face.min(next.face), u.face.max(next.face)));
        }
    }
    pairs
}
