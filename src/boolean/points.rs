//! The points of a boolean: every vertex of both operands and every point
//! the intersection made, with one canonical index per distinct position
//! (decided by exact comparison, so a point found twice by different
//! constructions — an edge through a face next to a vertex, a corner on
//! the other solid — is one vertex of the result).

use std::cmp::Ordering;

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::implicit::{
    Arithmetic, HasHomogeneous, Homogeneous, ImplicitPoint, Interval, compare_axis, compare_points,
};

/// A point with its interval coordinates kept (the filter of every
/// predicate on it).
#[derive(Clone, Debug)]
pub(crate) struct CachedPoint {
    pub point: ImplicitPoint,
    filter: Homogeneous<Interval>,
}

impl CachedPoint {
    pub fn new(point: ImplicitPoint) -> CachedPoint {
        CachedPoint {
            filter: point.homogeneous(),
            point,
        }
    }
}

impl HasHomogeneous for CachedPoint {
    fn homogeneous<T: Arithmetic>(&self) -> Homogeneous<T> {
        self.point.homogeneous()
    }

    fn filter(&self) -> Homogeneous<Interval> {
        self.filter.clone()
    }
}

/// All points of a boolean by raw index, and the canonical index of each.
///
/// # Invariants
///
/// `canonical[i] == canonical[j]` exactly when points `i` and `j` are the
/// same position; `canonical[i]` is the smallest raw index of that
/// position, so an operand vertex stays its own canonical point.
pub(crate) struct PointTable {
    pub points: Vec<CachedPoint>,
    pub canonical: Vec<u32>,
}

impl PointTable {
    /// Indexes `points` and finds which are the same position.
    pub fn new(points: Vec<ImplicitPoint>) -> PointTable {
        let points: Vec<CachedPoint> = points.into_par_iter().map(CachedPoint::new).collect();
        let mut by_position: Vec<u32> = (0..points.len() as u32).collect();
        by_position.par_sort_by(|&i, &j| {
            exact_order(&points[i as usize], &points[j as usize]).then(i.cmp(&j))
        });
        let mut canonical = vec![0u32; points.len()];
        let mut run_start = 0;
        for k in 0..by_position.len() {
            if k > 0
                && exact_order(
                    &points[by_position[k - 1] as usize],
                    &points[by_position[k] as usize],
                ) != Ordering::Equal
            {
                run_start = k;
            }
            // Runs are sorted by raw index, so the run's first is smallest.
            canonical[by_position[k] as usize] = by_position[run_start];
        }
        PointTable { points, canonical }
    }

    /// The point with raw index `i`.
    #[must_use]
    pub fn get(&self, i: u32) -> &CachedPoint {
        &self.points[i as usize]
    }

    /// The explicit position of point `i`, if it has one.
    #[must_use]
    pub fn explicit(&self, i: u32) -> Option<DVec3> {
        self.points[i as usize].point.explicit()
    }
}

fn exact_order(a: &CachedPoint, b: &CachedPoint) -> Ordering {
    if let (Some(_), Some(_)) = (a.point.explicit(), b.point.explicit()) {
        return compare_points(&a.point, &b.point);
    }
    (0..3)
        .map(|axis| compare_axis(a, b, axis))
        .find(|o| o.is_ne())
        .unwrap_or(Ordering::Equal)
}
