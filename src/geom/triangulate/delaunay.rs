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

use std::collections::HashMap;

use glam::DVec2;

use super::super::{Sign, incircle, orient2d};

/// Above this many triangles, directed edges are found through a hash map;
/// below, a linear scan is cheaper (most faces are small).
const LINEAR_SCAN_MAX: usize = 16;

/// Which triangle lies left of a directed edge.
struct Owners {
    /// `None` for small triangulations, scanned linearly.
    map: Option<HashMap<(usize, usize), usize>>,
}

impl Owners {
    fn new(triangles: &[[usize; 3]]) -> Owners {
        let map = (triangles.len() > LINEAR_SCAN_MAX).then(|| {
            let mut map = HashMap::with_capacity(3 * triangles.len());
            for (t, tri) in triangles.iter().enumerate() {
                for k in 0..3 {
                    map.insert((tri[k], tri[(k + 1) % 3]), t);
                }
            }
            map
        });
        Owners { map }
    }

    fn get(&self, triangles: &[[usize; 3]], a: usize, b: usize) -> Option<usize> {
        match &self.map {
            Some(map) => map.get(&(a, b)).copied(),
            None => triangles
                .iter()
                .position(|t| (0..3).any(|k| t[k] == a && t[(k + 1) % 3] == b)),
        }
    }

    /// Records triangle `t`'s new corners `tri`, replacing the edge `a → b`
    /// it no longer has.
    fn set(&mut self, t: usize, tri: [usize; 3], gone: (usize, usize)) {
        if let Some(map) = &mut self.map {
            map.remove(&gone);
            for k in 0..3 {
                map.insert((tri[k], tri[(k + 1) % 3]), t);
            }
        }
    }
}

/// Flips the non-loop edges of `triangles` (counter-clockwise, indexing
/// `points`) until every one is locally Delaunay. Loop `r` is the index
/// range `rings[r]` (in either direction).
pub(super) fn make_delaunay(
    points: &[DVec2],
    rings: &[std::ops::Range<usize>],
    triangles: &mut [[usize; 3]],
) {
    // Consecutive indices of one ring, or its first and last.
    let on_loop = |a: usize, b: usize| {
        let (lo, hi) = (a.min(b), a.max(b));
        rings.iter().any(|r| {
            r.contains(&lo)
                && r.contains(&hi)
                && (hi == lo + 1 || (lo == r.start && hi + 1 == r.end))
        })
    };
    let mut owners = Owners::new(triangles);
    let mut stack: Vec<(usize, usize)> = triangles
        .iter()
        .flat_map(|tri| (0..3).map(move |k| (tri[k], tri[(k + 1) % 3])))
        .filter(|&(a, b)| a < b && !on_loop(a, b))
        .collect();
    let third = |tri: [usize; 3], a: usize, b: usize| {
        tri.into_iter().find(|&x| x != a && x != b).unwrap_or(a)
    };
    while let Some((p, q)) = stack.pop() {
        let (Some(t1), Some(t2)) = (owners.get(triangles, p, q), owners.get(triangles, q, p))
        else {
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
        triangles[t1] = [p, s, r];
        triangles[t2] = [s, q, r];
        owners.set(t1, triangles[t1], (p, q));
        owners.set(t2, triangles[t2], (q, p));
        for (a, b) in [(p, s), (s, q), (q, r), (r, p)] {
            if !on_loop(a, b) {
                stack.push((a, b));
            }
        }
    }
}
