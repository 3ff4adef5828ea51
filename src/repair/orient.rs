//! Stage 2 and 4: every connected piece wound consistently (neighbours
//! across an edge of exactly two polygons run it in opposite directions),
//! and then each closed piece turned to face out when its signed volume
//! is negative, unless it lies inside an odd number of other pieces (a
//! cavity stays a cavity). A piece that is not closed by itself (a face
//! whose every edge is shared by three or more) is left as it is: its
//! edges stay unbalanced, and filling closes them with the same plane
//! wound the other way, which gives the winding number the face would have
//! given wound right.
//!
//! Two polygons join across an edge only when it has exactly two uses and
//! they lie on either side of it: two coplanar polygons folded onto each
//! other across their shared edge (the bottoms of two boxes standing on
//! one floor, left sharing an edge when the boxes' common face cancelled
//! in cleaning) overlap rather than continue each other, and joining them
//! would turn one box inside out to match the other.

use glam::DVec3;

use crate::disjoint_sets::DisjointSets;
use crate::geom::{Sign, orient3d};
use crate::mesh::PolygonSoup;
use crate::query::{Containment, SoupWinding};

use crate::geom::projected_orientation;

/// One use of an undirected edge by a polygon.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct EdgeUse {
    /// The edge's smaller vertex.
    low: usize,
    /// The edge's larger vertex.
    high: usize,
    /// The polygon.
    polygon: usize,
    /// Whether the polygon runs the edge `low → high`.
    forward: bool,
    /// The polygon's corner after the edge: on the polygon's side of it
    /// (for a polygon convex at that corner, as triangles are).
    beyond: usize,
}

/// The uses of each undirected edge, sorted so that an edge's uses are
/// consecutive.
fn edge_uses(soup: &PolygonSoup) -> Vec<EdgeUse> {
    let mut uses = Vec::new();
    for (p, polygon) in soup.polygons.iter().enumerate() {
        let n = polygon.vertices.len();
        for k in 0..n {
            let (u, v) = (polygon.vertices[k], polygon.vertices[(k + 1) % n]);
            uses.push(EdgeUse {
                low: u.min(v),
                high: u.max(v),
                polygon: p,
                forward: u < v,
                beyond: polygon.vertices[(k + 2) % n],
            });
        }
    }
    uses.sort_unstable();
    uses
}

/// Whether the two uses' polygons are coplanar and on one side of their
/// shared edge (folded onto each other), exactly.
fn folded(soup: &PolygonSoup, a: EdgeUse, b: EdgeUse) -> bool {
    let p = |i: usize| soup.positions[i];
    let (u, v, x, y) = (p(a.low), p(a.high), p(a.beyond), p(b.beyond));
    if orient3d(u, v, x, y) != Sign::Zero {
        return false;
    }
    (0..3u8).any(|axis| {
        let sx = projected_orientation([u, v, x], axis);
        let sy = projected_orientation([u, v, y], axis);
        sx != Sign::Zero && sx == sy
    })
}

/// The pairs of polygons across edges of exactly two uses that are not
/// folded onto each other, with whether they run the edge the same way
/// (disagree).
fn manifold_pairs(soup: &PolygonSoup) -> Vec<(usize, usize, bool)> {
    let uses = edge_uses(soup);
    uses.chunk_by(|a, b| (a.low, a.high) == (b.low, b.high))
        .filter(|run| {
            run.len() == 2 && run[0].polygon != run[1].polygon && !folded(soup, run[0], run[1])
        })
        .map(|run| {
            (
                run[0].polygon,
                run[1].polygon,
                run[0].forward == run[1].forward,
            )
        })
        .collect()
}

/// Turns polygons over so that each piece is consistent; returns the
/// polygons turned and how many pieces could not be made consistent.
pub(crate) fn make_consistent(soup: &mut PolygonSoup) -> (Vec<usize>, usize) {
    let n = soup.polygons.len();
    let pairs = manifold_pairs(soup);
    let mut neighbours: Vec<Vec<(usize, bool)>> = vec![Vec::new(); n];
    for &(a, b, disagree) in &pairs {
        neighbours[a].push((b, disagree));
        neighbours[b].push((a, disagree));
    }
    let mut flip: Vec<Option<bool>> = vec![None; n];
    let mut non_orientable = 0;
    let mut stack = Vec::new();
    for seed in 0..n {
        if flip[seed].is_some() {
            continue;
        }
        // Keep the orientation most of the piece already has: walk it
        // first, then turn over the smaller side.
        let mut members = vec![seed];
        flip[seed] = Some(false);
        stack.push(seed);
        let mut conflict = false;
        while let Some(p) = stack.pop() {
            let fp = flip[p].unwrap_or(false);
            for &(q, disagree) in &neighbours[p] {
                let want = fp ^ disagree;
                match flip[q] {
                    None => {
                        flip[q] = Some(want);
                        members.push(q);
                        stack.push(q);
                    }
                    Some(f) if f != want => conflict = true,
                    Some(_) => {}
                }
            }
        }
        if conflict {
            non_orientable += 1;
            for &m in &members {
                flip[m] = Some(false);
            }
            continue;
        }
        let turned = members.iter().filter(|&&m| flip[m] == Some(true)).count();
        if 2 * turned > members.len() {
            for &m in &members {
                flip[m] = flip[m].map(|f| !f);
            }
        }
    }
    let turned: Vec<usize> = (0..n).filter(|&p| flip[p] == Some(true)).collect();
    for &p in &turned {
        soup.polygons[p].vertices.reverse();
    }
    (turned, non_orientable)
}

/// The connected pieces (polygons joined across edges of two uses), each
/// a sorted list of polygons, in order of their first polygon.
pub(crate) fn pieces(soup: &PolygonSoup) -> Vec<Vec<usize>> {
    let n = soup.polygons.len();
    let mut sets = DisjointSets::new(n);
    for (a, b, _) in manifold_pairs(soup) {
        sets.union(a, b);
    }
    let mut by_root: std::collections::BTreeMap<usize, Vec<usize>> = Default::default();
    let mut first_of_root: Vec<Option<usize>> = vec![None; n];
    for p in 0..n {
        let r = sets.find(p);
        let first = *first_of_root[r].get_or_insert(p);
        by_root.entry(first).or_default().push(p);
    }
    by_root.into_values().collect()
}

/// The signed volume of polygons (each fanned from its first corner),
/// relative to `origin`.
pub(crate) fn signed_volume(soup: &PolygonSoup, polygons: &[usize], origin: DVec3) -> f64 {
    let mut total = 0.0;
    for &p in polygons {
        let v = &soup.polygons[p].vertices;
        let a = soup.positions[v[0]] - origin;
        for k in 1..v.len().saturating_sub(1) {
            let b = soup.positions[v[k]] - origin;
            let c = soup.positions[v[k + 1]] - origin;
            total += a.dot(b.cross(c));
        }
    }
    total / 6.0
}

/// Whether the polygons run each of their edges as often one way as the
/// other.
fn closed(soup: &PolygonSoup, polygons: &[usize]) -> bool {
    let mut net: std::collections::HashMap<(usize, usize), i64> = Default::default();
    for &p in polygons {
        let v = &soup.polygons[p].vertices;
        for k in 0..v.len() {
            let (a, b) = (v[k], v[(k + 1) % v.len()]);
            *net.entry((a.min(b), a.max(b))).or_default() += if a < b { 1 } else { -1 };
        }
    }
    net.values().all(|&c| c == 0)
}

/// Turns each piece to face out (see the module's documentation); returns
/// the pieces turned over.
pub(crate) fn face_out(soup: &mut PolygonSoup) -> Vec<Vec<usize>> {
    let all = pieces(soup);
    let centre = crate::geom::Aabb::from_points(soup.positions.iter().copied()).center();
    let volumes: Vec<f64> = all
        .iter()
        .map(|piece| signed_volume(soup, piece, centre))
        .collect();
    // Pieces as soups of their own, each wound outward, for nesting.
    let outward: Vec<PolygonSoup> = all
        .iter()
        .zip(&volumes)
        .map(|(piece, &v)| {
            let mut local: std::collections::HashMap<usize, usize> = Default::default();
            let mut positions = Vec::new();
            let polygons = piece
                .iter()
                .map(|&p| {
                    let mut corners: Vec<usize> = soup.polygons[p]
                        .vertices
                        .iter()
                        .map(|&c| {
                            *local.entry(c).or_insert_with(|| {
                                positions.push(soup.positions[c]);
                                positions.len() - 1
                            })
                        })
                        .collect();
                    if v < 0.0 {
                        corners.reverse();
                    }
                    corners
                })
                .collect::<Vec<_>>();
            PolygonSoup::new(positions, polygons)
        })
        .collect();
    let boxes: Vec<crate::geom::Aabb> = all
        .iter()
        .map(|piece| {
            crate::geom::Aabb::from_points(
                piece
                    .iter()
                    .flat_map(|&p| soup.polygons[p].vertices.iter().map(|&v| soup.positions[v])),
            )
        })
        .collect();
    let mut windings: Vec<Option<SoupWinding>> = vec![None; all.len()];
    let mut turned = Vec::new();
    for (i, piece) in all.iter().enumerate() {
        let probe = soup.positions[soup.polygons[piece[0]].vertices[0]];
        let mut depth = 0;
        for j in 0..all.len() {
            if j == i || !boxes[j].contains(probe) {
                continue;
            }
            if windings[j].is_none() {
                windings[j] = SoupWinding::try_new(&outward[j]).ok();
            }
            if let Some(winding) = &windings[j]
                && matches!(winding.classify(probe), Ok(Containment::Inside))
            {
                depth += 1;
            }
        }
        // Only a closed piece has an inside to face away from.
        if !closed(soup, piece) {
            continue;
        }
        // Inward and not nested: turned out. (An outward piece is left as
        // it is even when nested: shells that cross each other give
        // nesting no meaning, and it only adds to the winding number.)
        if volumes[i] < 0.0 && depth % 2 == 0 {
            for &p in piece {
                soup.polygons[p].vertices.reverse();
            }
            turned.push(piece.clone());
        }
    }
    turned
}
