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
    /// The point's definition.
    #[must_use]
    pub fn definition(&self) -> ImplicitPoint {
        match self {
            PointView::Vertex(v) => ImplicitPoint::Explicit(*v),
            PointView::Made(c) => c.point.clone(),
        }
    }

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
        by_position.par_sort_by(|&i, &j| exact_order(&table.get(i), &table.get(j)).then(i.cmp(&j)));
        let mut run_start = 0;
        for k in 0..by_position.len() {
            if k > 0
                && exact_order(&table.get(by_position[k - 1]), &table.get(by_position[k]))
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

    /// The explicit position of point `i`, if it has one.
    #[must_use]
    pub fn explicit(&self, i: u32) -> Option<DVec3> {
        self.get(i).explicit()
    }
}

fn exact_order(a: &PointView, b: &PointView) -> Ordering {
    if let (Some(x), Some(y)) = (a.explicit(), b.explicit()) {
        return compare_points(&ImplicitPoint::Explicit(x), &ImplicitPoint::Explicit(y));
    }
    (0..3)
        .map(|axis| compare_axis(a, b, axis))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}
