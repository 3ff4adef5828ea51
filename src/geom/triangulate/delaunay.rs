//! Lawson's flips (1977) on the edges that are not loop edges, until each
//! is locally Delaunay by the exact [`incircle`]: the result is the
//! constrained Delaunay triangulation of the loops.
//!
//! An edge `pq` between triangles `pqr` and `qps` (both counter-clockwise)
//! is flipped to `rs` when `s` lies strictly inside the circle through `p`,
//! `q`, `r`. Then the quadrilateral `psqr` is strictly convex, so both new
//! triangles are counter-clockwise, and every flip raises the triangulation
//! strictly in the lifting to the paraboloid, so the flips end. Cocircular
//! points (a zero sign) are left as they are.

use std::collections::{HashMap, HashSet};

use glam::DVec2;

use super::super::{Sign, incircle, orient2d};

/// Flips the non-loop edges of `triangles` (counter-clockwise, indexing
/// `points`) until every one is locally Delaunay.
pub(super) fn make_delaunay(points: &[DVec2], loops: &[Vec<usize>], triangles: &mut [[usize; 3]]) {
    let undirected = |a: usize, b: usize| (a.min(b), a.max(b));
    let constrained: HashSet<(usize, usize)> = loops
        .iter()
        .flat_map(|l| (0..l.len()).map(move |k| undirected(l[k], l[(k + 1) % l.len()])))
        .collect();
    // Directed edge -> the triangle on its left.
    let mut owner: HashMap<(usize, usize), usize> = HashMap::with_capacity(3 * triangles.len());
    for (t, tri) in triangles.iter().enumerate() {
        for k in 0..3 {
            owner.insert((tri[k], tri[(k + 1) % 3]), t);
        }
    }
    let mut stack: Vec<(usize, usize)> = triangles
        .iter()
        .flat_map(|tri| (0..3).map(move |k| (tri[k], tri[(k + 1) % 3])))
        .filter(|&(a, b)| a < b && !constrained.contains(&(a, b)))
        .collect();
    let third = |tri: [usize; 3], a: usize, b: usize| {
        tri.into_iter().find(|&x| x != a && x != b).unwrap_or(a)
    };
    while let Some((p, q)) = stack.pop() {
        let (Some(&t1), Some(&t2)) = (owner.get(&(p, q)), owner.get(&(q, p))) else {
            continue;
        };
        let r = third(triangles[t1], p, q);
        let s = third(triangles[t2], p, q);
        let at = |i: usize| points[i];
        if incircle(at(p), at(q), at(r), at(s)) != Sign::Positive {
            continue;
        }
        if orient2d(at(p), at(s), at(r)) != Sign::Positive
            || orient2d(at(s), at(q), at(r)) != Sign::Positive
        {
            debug_assert!(false, "a non-Delaunay edge with a non-convex quadrilateral");
            continue;
        }
        owner.remove(&(p, q));
        owner.remove(&(q, p));
        triangles[t1] = [p, s, r];
        triangles[t2] = [s, q, r];
        for (t, tri) in [(t1, triangles[t1]), (t2, triangles[t2])] {
            for k in 0..3 {
                owner.insert((tri[k], tri[(k + 1) % 3]), t);
            }
        }
        for (a, b) in [(p, s), (s, q), (q, r), (r, p)] {
            if !constrained.contains(&undirected(a, b)) {
                stack.push((a, b));
            }
        }
    }
}
