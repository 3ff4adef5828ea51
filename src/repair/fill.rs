//! Stage 3: holes filled. The edge uses that have no partner running them
//! the other way form closed loops (at every vertex as many leave as
//! arrive); each loop, split into simple cycles, is triangulated exactly
//! (`geom::triangulate_3d`: the projection along the axis its Newell normal
//! is largest in, decided by exact orientation tests) and the triangles are
//! wound against the loop, so every edge is then run as often one way as
//! the other.

use std::collections::HashMap;

use glam::DVec3;

use crate::geom::{collinear3d, triangulate_3d};
use crate::mesh::{Polygon, PolygonSoup};

use super::report::{HoleLoop, OpenReason};

/// What filling did: loops filled and left open. Added triangles are
/// appended to the soup; `next_to` is a polygon index of the soup as given.
pub(crate) struct Filled {
    pub filled: Vec<HoleLoop>,
    pub left_open: Vec<(HoleLoop, OpenReason)>,
}

/// Fills every hole of at most `max_edges` edges (all when `None`).
pub(crate) fn fill(soup: &mut PolygonSoup, max_edges: Option<usize>) -> Filled {
    let loops = boundary_loops(soup);
    let mut filled = Vec::new();
    let mut left_open = Vec::new();
    for (cycle, next_to) in loops {
        let mut hole = HoleLoop {
            edges: cycle.len(),
            triangles: 0,
            next_to,
        };
        if let Some(limit) = max_edges.filter(|&l| cycle.len() > l) {
            left_open.push((hole, OpenReason::LargerThanLimit(limit)));
            continue;
        }
        // The fill runs the loop backwards.
        let corners: Vec<usize> = cycle.iter().rev().copied().collect();
        let ring: Vec<DVec3> = corners.iter().map(|&v| soup.positions[v]).collect();
        if collinear(&ring) {
            // Its edges lie on one line (a crack at a T-junction): nothing
            // to fill; the arrangement joins its sides.
            filled.push(hole);
            continue;
        }
        match triangulate_3d(&ring, &[]) {
            Ok(triangles) => {
                hole.triangles = triangles.len();
                for t in triangles {
                    soup.polygons
                        .push(Polygon::new(t.iter().map(|&k| corners[k])));
                }
                filled.push(hole);
            }
            Err(_) => left_open.push((hole, OpenReason::NotTriangulable)),
        }
    }
    Filled { filled, left_open }
}

/// Whether every point lies on the line through the first two.
fn collinear(ring: &[DVec3]) -> bool {
    ring[2..].iter().all(|&c| collinear3d(ring[0], ring[1], c))
}

/// The soup's holes: cycles of unpartnered edge uses, each as the vertices
/// it visits in the direction the polygons run it, with a polygon on its
/// rim; in a fixed order.
pub(crate) fn boundary_loops(soup: &PolygonSoup) -> Vec<(Vec<usize>, usize)> {
    // Net uses of each directed edge: (u, v) run minus (v, u) run.
    let mut net: HashMap<(usize, usize), (i64, usize)> = HashMap::new();
    for (p, polygon) in soup.polygons.iter().enumerate() {
        let n = polygon.vertices.len();
        for k in 0..n {
            let (u, v) = (polygon.vertices[k], polygon.vertices[(k + 1) % n]);
            let (key, step) = if u < v { ((u, v), 1) } else { ((v, u), -1) };
            let entry = net.entry(key).or_insert((0, p));
            entry.0 += step;
        }
    }
    // Open half-edges, leaving each vertex (sorted for a fixed order).
    let mut open: Vec<(usize, usize, usize)> = Vec::new();
    for (&(u, v), &(count, p)) in &net {
        let (from, to) = if count > 0 { (u, v) } else { (v, u) };
        for _ in 0..count.unsigned_abs() {
            open.push((from, to, p));
        }
    }
    open.sort_unstable();
    let mut leaving: HashMap<usize, Vec<(usize, usize)>> = HashMap::new();
    for &(from, to, p) in open.iter().rev() {
        leaving.entry(from).or_default().push((to, p));
    }
    let mut loops = Vec::new();
    for &(start, _, _) in &open {
        while leaving.get(&start).is_some_and(|l| !l.is_empty()) {
            // A closed trail from `start` (every vertex is left as often as
            // it is reached, so the walk can end only there), cut into
            // simple cycles wherever a vertex repeats.
            let mut stack: Vec<(usize, usize)> = vec![(start, usize::MAX)];
            let mut at = start;
            while let Some((to, p)) = leaving.get_mut(&at).and_then(Vec::pop) {
                if let Some(k) = stack.iter().position(|&(v, _)| v == to) {
                    let mut cycle = stack.split_off(k + 1);
                    cycle.push((to, p));
                    let vertices: Vec<usize> = std::iter::once(to)
                        .chain(cycle[..cycle.len() - 1].iter().map(|&(v, _)| v))
                        .collect();
                    loops.push((vertices, p));
                } else {
                    stack.push((to, p));
                }
                at = to;
                if to == start && stack.len() == 1 {
                    break;
                }
            }
        }
    }
    loops
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cube_without_its_top_gets_two_triangles_and_closes() {
        let positions: Vec<DVec3> = (0..8)
            .map(|i| DVec3::new((i & 1) as f64, ((i >> 1) & 1) as f64, ((i >> 2) & 1) as f64))
            .collect();
        let mut soup = PolygonSoup::new(
            positions,
            [
                vec![0, 2, 3, 1],
                vec![0, 1, 5, 4],
                vec![1, 3, 7, 5],
                vec![3, 2, 6, 7],
                vec![2, 0, 4, 6],
            ],
        );
        let filled = fill(&mut soup, None);
        assert_eq!(filled.filled.len(), 1);
        assert_eq!(filled.filled[0].edges, 4);
        assert_eq!(filled.filled[0].triangles, 2);
        assert!(boundary_loops(&soup).is_empty());
        let mut small = soup.clone();
        small.polygons.truncate(5);
        let limited = fill(&mut small, Some(3));
        assert_eq!(limited.left_open.len(), 1);
    }
}
