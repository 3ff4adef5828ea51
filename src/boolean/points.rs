//! The points of a boolean: every vertex of both operands and every point
//! the intersection made, with one canonical index per distinct position
//! (decided by exact comparison, so a point found twice by different
//! constructions — an edge through a face next to a vertex, a corner on
//! the other solid — is one vertex of the result).

use std::cmp::Ordering;

use std::sync::OnceLock;

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::dyadic::Dyadic;
use crate::geom::implicit::{
    Arithmetic, HasHomogeneous, Homogeneous, ImplicitPoint, Interval, compare_axis, compare_points,
};

/// A constructed point with its interval coordinates kept (the filter of
/// every predicate on it).
#[derive(Clone, Debug)]
pub(crate) struct CachedPoint {
    pub point: ImplicitPoint,
    filter: Homogeneous<Interval>,
    /// The exact coordinates, computed the first time a predicate needs
    /// them (degenerate configurations ask again and again).
    exact: OnceLock<Homogeneous<Dyadic>>,
}

impl CachedPoint {
    pub fn new(point: ImplicitPoint) -> CachedPoint {
        CachedPoint {
            filter: point.homogeneous(),
            point,
            exact: OnceLock::new(),
        }
    }
}

/// A point of the table: an input vertex or a constructed point.
#[derive(Clone, Copy, Debug)]
pub(crate) enum PointView<'t> {
    /// An operand vertex.
    Vertex(DVec3),
    /// A point the intersection made.
    Made(&'t CachedPoint),
}

impl PointView<'_> {
    /// The explicit coordinates, if the point has them.
    #[must_use]
    pub fn explicit(&self) -> Option<DVec3> {
        match self {
            PointView::Vertex(v) => Some(*v),
            PointView::Made(c) => c.point.explicit(),
        }
    }
}

impl HasHomogeneous for PointView<'_> {
    fn homogeneous<T: Arithmetic>(&self) -> Homogeneous<T> {
        match self {
            PointView::Vertex(v) => ImplicitPoint::Explicit(*v).homogeneous(),
            PointView::Made(c) => c.point.homogeneous(),
        }
    }

    fn filter(&self) -> Homogeneous<Interval> {
        match self {
            PointView::Vertex(v) => ImplicitPoint::Explicit(*v).homogeneous(),
            PointView::Made(c) => c.filter.clone(),
        }
    }

    fn exact(&self) -> Homogeneous<Dyadic> {
        match self {
            PointView::Vertex(v) => ImplicitPoint::Explicit(*v).homogeneous(),
            PointView::Made(c) => c.exact.get_or_init(|| c.point.homogeneous()).clone(),
        }
    }

    fn known_coordinate(&self, axis: usize) -> Option<f64> {
        match self {
            PointView::Vertex(v) => Some(v[axis]),
            PointView::Made(c) => c.point.known_coordinate(axis),
        }
    }

    fn double_double_safe(&self) -> bool {
        match self {
            PointView::Vertex(v) => ImplicitPoint::Explicit(*v).double_double_safe(),
            PointView::Made(c) => c.point.double_double_safe(),
        }
    }
}

/// All points of a boolean by raw index — first the operands' vertices,
/// then the constructed points — and the canonical index of each.
///
/// # Invariants
///
/// `canonical[i] == canonical[j]` exactly when points `i` and `j` are the
/// same position; `canonical[i]` is the smallest raw index of that
/// position, so an operand vertex stays its own canonical point.
pub(crate) struct PointTable {
    vertices: Vec<DVec3>,
    made: Vec<CachedPoint>,
    pub canonical: Vec<u32>,
}

impl PointTable {
    /// Indexes the points and finds which of `candidates` are the same
    /// position; every other point is its own (the caller guarantees that
    /// only candidates can coincide: every point the intersection found or
    /// touched).
    pub fn new(
        vertices: Vec<DVec3>,
        made: Vec<ImplicitPoint>,
        mut candidates: Vec<u32>,
    ) -> PointTable {
        let made: Vec<CachedPoint> = made.into_par_iter().map(CachedPoint::new).collect();
        let count = vertices.len() + made.len();
        let mut table = PointTable {
            vertices,
            made,
            canonical: (0..count as u32).collect(),
        };
        candidates.sort_unstable();
        candidates.dedup();
        let mut by_position = candidates;
        by_position
            .par_sort_by(|&i, &j| compare_positions(&table.get(i), &table.get(j)).then(i.cmp(&j)));
        let mut run_start = 0;
        for k in 0..by_position.len() {
            if k > 0
                && compare_positions(&table.get(by_position[k - 1]), &table.get(by_position[k]))
                    != Ordering::Equal
            {
                run_start = k;
            }
            // Runs are sorted by raw index, so the run's first is smallest.
            table.canonical[by_position[k] as usize] = by_position[run_start];
        }
        table
    }

    /// The point with raw index `i`.
    #[must_use]
    pub fn get(&self, i: u32) -> PointView<'_> {
        let i = i as usize;
        match self.vertices.get(i) {
            Some(&v) => PointView::Vertex(v),
            None => PointView::Made(&self.made[i - self.vertices.len()]),
        }
    }

    /// Whether points `a`, `b`, `c` lie on one line by construction: a
    /// point made on an input segment (where the segment meets a plane,
    /// or another segment) and points that are that segment's ends or
    /// made on the same segment; or two of them one point (one index, one
    /// canonical point, or one construction). Then every orientation of
    /// the three is zero, which the filter can never certify; this answers
    /// without arithmetic. `false` says nothing.
    #[must_use]
    pub fn collinear_by_construction(&self, a: u32, b: u32, c: u32) -> bool {
        let points = [a, b, c].map(|i| self.get(i));
        let one_point = |i: usize, j: usize| {
            let (x, y) = ([a, b, c][i], [a, b, c][j]);
            self.canonical[x as usize] == self.canonical[y as usize]
                || match (&points[i], &points[j]) {
                    (PointView::Made(p), PointView::Made(q)) => {
                        same_construction(&p.point, &q.point)
                    }
                    (PointView::Vertex(v), PointView::Vertex(w)) => v == w,
                    _ => false,
                }
        };
        if one_point(0, 1) || one_point(1, 2) || one_point(0, 2) {
            return true;
        }
        let segment_of = |p: &PointView| match p {
            PointView::Made(made) => match made.point {
                ImplicitPoint::EdgePlane { p, q, .. } | ImplicitPoint::EdgeEdge { p, q, .. } => {
                    Some((p, q))
                }
                _ => None,
            },
            PointView::Vertex(_) => None,
        };
        let on = |point: &PointView, (p, q): (DVec3, DVec3)| match point {
            PointView::Vertex(v) => *v == p || *v == q,
            PointView::Made(_) => {
                segment_of(point).is_some_and(|(r, s)| (r == p && s == q) || (r == q && s == p))
            }
        };
        points
            .iter()
            .filter_map(segment_of)
            .any(|line| points.iter().all(|point| on(point, line)))
    }

    /// The explicit position of point `i`, if it has one.
    #[must_use]
    pub fn explicit(&self, i: u32) -> Option<DVec3> {
        self.get(i).explicit()
    }
}

/// The exact lexicographic order of two points' positions (`Equal`
/// exactly when they are one position).
pub(crate) fn compare_positions(a: &PointView, b: &PointView) -> Ordering {
    if let (Some(x), Some(y)) = (a.explicit(), b.explicit()) {
        return compare_points(&ImplicitPoint::Explicit(x), &ImplicitPoint::Explicit(y));
    }
    // The same construction twice (an edge shared by two triangles meets
    // a face once for each): equal without arithmetic, where the filter
    // could never tell and the exact stage would be asked.
    if let (PointView::Made(x), PointView::Made(y)) = (a, b)
        && same_construction(&x.point, &y.point)
    {
        return Ordering::Equal;
    }
    (0..3)
        .map(|axis| compare_axis(a, b, axis))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}

/// Whether two definitions make the same point by construction: equal, or
/// equal once each segment is read from its other end.
fn same_construction(a: &ImplicitPoint, b: &ImplicitPoint) -> bool {
    let same_segment =
        |(p, q): (DVec3, DVec3), (r, s): (DVec3, DVec3)| (p == r && q == s) || (p == s && q == r);
    match (a, b) {
        (
            ImplicitPoint::EdgePlane { p, q, plane },
            ImplicitPoint::EdgePlane {
                p: r,
                q: s,
                plane: other,
            },
        ) => plane == other && same_segment((*p, *q), (*r, *s)),
        (
            ImplicitPoint::EdgeEdge {
                p,
                q,
                r,
                s,
                drop_axis,
            },
            ImplicitPoint::EdgeEdge {
                p: p2,
                q: q2,
                r: r2,
                s: s2,
                drop_axis: axis2,
            },
        ) => {
            drop_axis == axis2
                && same_segment((*p, *q), (*p2, *q2))
                && same_segment((*r, *s), (*r2, *s2))
        }
        _ => a == b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_construction_made_twice_is_one_point_without_exact_arithmetic() {
        let plane = [
            DVec3::new(0.1, 0.0, 0.3),
            DVec3::new(1.0, 0.2, 0.35),
            DVec3::new(0.0, 1.0, 0.25),
        ];
        let (p, q) = (DVec3::new(0.3, 0.3, -1.0), DVec3::new(0.35, 0.2, 1.0));
        let made = vec![
            ImplicitPoint::EdgePlane { p, q, plane },
            // The same edge read from its other end (the neighbouring
            // triangle's half-edge).
            ImplicitPoint::EdgePlane { p: q, q: p, plane },
            // Another point of the same plane.
            ImplicitPoint::EdgePlane {
                p,
                q: DVec3::new(0.5, 0.3, 1.0),
                plane,
            },
        ];
        let table = PointTable::new(vec![DVec3::ZERO], made, vec![1, 2, 3]);
        assert_eq!(table.canonical, [0, 1, 1, 3]);
        // Neither the filter nor the exact stage was needed to tell.
        assert!(table.made.iter().all(|c| c.exact.get().is_none()));
        assert!(same_construction(
            &ImplicitPoint::EdgeEdge {
                p,
                q,
                r: plane[0],
                s: plane[1],
                drop_axis: 2
            },
            &ImplicitPoint::EdgeEdge {
                p: q,
                q: p,
                r: plane[1],
                s: plane[0],
                drop_axis: 2
            },
        ));
        assert!(!same_construction(
            &ImplicitPoint::EdgeEdge {
                p,
                q,
                r: plane[0],
                s: plane[1],
                drop_axis: 2
            },
            &ImplicitPoint::EdgeEdge {
                p: plane[0],
                q: plane[1],
                r: p,
                s: q,
                drop_axis: 2
            },
        ));
    }
}
