//! The acceleration structure shared by every query on one solid: a thin
//! owner of the shared BVH, the fan triangles in its order, their leaf
//! packets, and the lazily built point grid and convexity verdict.

pub(super) mod cell_gaps;
pub(super) mod convexity;
pub(super) mod fan;
pub(super) mod point_grid;
pub(super) mod ray_leaves;
pub(super) mod ray_stream;
pub(super) mod tri_packet;
pub(super) mod triangle_records;
pub(super) mod triangles_holding;

use std::time::{Duration, Instant};

use glam::DVec3;
use rayon::prelude::*;

use crate::geom::Aabb;
use crate::mesh::{FaceId, Solid};
use crate::spatial::Bvh;
use crate::spatial::raw::huge_pages::HugeVec;

use self::cell_gaps::CellGaps;
pub use self::convexity::NotConvex;
use self::convexity::check_convexity;
use self::fan::fan_triangles;
use self::point_grid::{YzGrid, build_grid};
use self::tri_packet::TriPacket;
use self::triangle_records::{YzTri, yz_tri};

/// How the accel was built: its size and the time it took.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AccelStats {
    /// Fan triangles (one per face corner beyond the second).
    pub triangles: usize,
    /// BVH nodes.
    pub bvh_nodes: usize,
    /// Grid cells (`ny × nz`); 0 until the grid is built (by the first
    /// point query, or [`Accel::build_point_grid`]).
    pub grid_cells: usize,
    /// Triangle references held by the grid's cells (0 until it is built).
    pub grid_entries: usize,
    /// Heap bytes held by the accel (with the grid once it is built).
    pub memory_bytes: usize,
    /// Wall time of [`Accel::new`] (triangles and BVH).
    pub build_time: Duration,
    /// Wall time of building the point grid (zero until it is built).
    pub grid_build_time: Duration,
}

/// The acceleration structure of one solid, built once and shared by every
/// query (it is `Send + Sync`; batch queries split work over rayon's pool).
///
/// Only the work a caller's queries need is done: [`Accel::new`] builds the
/// fan triangles and the BVH (all that rays need); the `yz` grid of point
/// classification is built by the first point query, and the convexity
/// verdict of [`Method::Normals`](super::Method::Normals) by the first
/// query that needs it (each once, thread-safe).
///
/// # Invariants
///
/// - `tris` (in BVH leaf order) is the fan triangulation of every face with at least three
///   vertices, `(v₀, vₖ, vₖ₊₁)` for `k = 1 .. n − 2` in the face's winding,
///   with `v₀` the face's lexicographically smallest corner `(x, y, z)`,
///   holding the exact input coordinates; `tri_face[i]` is its face.
/// - `bvh` is built over the triangles' exact boxes, and `tris` is in its
///   item order: leaf `k` of `bvh` holds the triangles `bvh.leaf(k)`, so
///   culling by its boxes never loses a triangle a ray touches.
/// - `packets[k]` holds the triangles of leaf `k` (`first .. first + count`
///   of `tris`, in order); a packet only ever drops a triangle the exact
///   line provably misses.
/// - Every triangle whose projected `yz` box contains a point `(y, z)` is
///   listed in the grid cell of `(y, z)` (cell indices are monotone in the
///   coordinates).
/// - `boundary_edges` counts the edges whose uses by the faces do not
///   cancel (a solid's edges with one face; for a soup, see
///   [`SoupWinding::open_edges`](super::SoupWinding::open_edges)). When it
///   is 0 the triangles form a closed, consistently oriented cycle, and the
///   signed count of a ray's crossings is the winding number.
#[derive(Clone, Debug)]
pub struct Accel {
    pub(in crate::query) tris: HugeVec<YzTri>,
    pub(in crate::query) tri_face: HugeVec<FaceId>,
    /// The shared BVH over the triangles, in `tris` order.
    pub(in crate::query) bvh: Bvh,
    /// One per BVH leaf, the leaf's triangles in `f32` for the rays' miss
    /// filter; the leaf numbers of `bvh` index it.
    pub(in crate::query) packets: HugeVec<TriPacket>,
    grid: std::sync::OnceLock<(YzGrid, CellGaps, Duration)>,
    pub(in crate::query) bounds: Aabb,
    pub(in crate::query) boundary_edges: usize,
    pub(in crate::query) convexity: std::sync::OnceLock<Result<(), NotConvex>>,
    pub(in crate::query) stats: AccelStats,
}

impl Accel {
    /// Builds the accel of `solid`: fan triangles and BVH (the `yz` grid of
    /// point queries and the convexity verdict of the normals method are
    /// computed on first use).
    ///
    /// Never fails: an open solid gets an accel too (the winding number is
    /// defined for it; parity and crossings then return
    /// [`QueryError::NotClosed`](super::QueryError::NotClosed)). A solid with
    /// no faces gives an empty accel for which every point is outside.
    #[must_use]
    pub fn new(solid: &Solid) -> Accel {
        let start = Instant::now();
        let boundary_edges = solid.boundary_edges().count();
        let (fan, fan_face) = fan_triangles(solid);
        Accel::from_triangles(fan, fan_face, boundary_edges, start)
    }

    /// The accel of the triangles `fan`, `fan_face[i]` the face of
    /// `fan[i]`, on a surface with `boundary_edges` edges whose uses do not
    /// cancel (0: a closed surface, on which parity and the exact crossing
    /// count answer); `start` is when the build began, for
    /// [`AccelStats::build_time`].
    pub(in crate::query) fn from_triangles(
        fan: Vec<[DVec3; 3]>,
        fan_face: Vec<FaceId>,
        boundary_edges: usize,
        start: Instant,
    ) -> Accel {
        let (bvh, order) = Bvh::build_by(fan.len(), |i| Aabb::from_points(fan[i]));
        let bounds = bvh.bounds();
        let tris = HugeVec::from_par_iter(order.par_iter().map(|&i| yz_tri(&fan[i as usize])));
        // The fan in face order is not needed again: its memory goes back
        // before the packets take theirs.
        drop(fan);
        // The packets are made on all cores: their memory is fresh huge
        // pages, whose first touch is at times slow.
        let scale = bvh.frame().scale;
        let packets =
            HugeVec::from_par_iter((0..bvh.leaf_count() as u32).into_par_iter().map(|k| {
                let leaf = bvh.leaf(k).unwrap_or_default();
                TriPacket::new(&tris, leaf.first, leaf.count, scale)
            }));
        let tri_face = HugeVec::from_par_iter(order.par_iter().map(|&i| fan_face[i as usize]));
        drop(fan_face);
        // What rays read at random, on huge pages where offered.
        tris.collapse();
        tri_face.collapse();
        bvh.collapse_into_huge_pages();
        packets.collapse();
        let memory_bytes = tris.memory_bytes()
            + tri_face.memory_bytes()
            + bvh.memory_bytes()
            + packets.memory_bytes();
        let stats = AccelStats {
            triangles: tris.len(),
            bvh_nodes: bvh.node_count(),
            grid_cells: 0,
            grid_entries: 0,
            memory_bytes,
            build_time: Duration::ZERO,
            grid_build_time: Duration::ZERO,
        };
        let mut accel = Accel {
            tris,
            tri_face,
            bvh,
            packets,
            grid: std::sync::OnceLock::new(),
            bounds,
            boundary_edges,
            convexity: std::sync::OnceLock::new(),
            stats,
        };
        accel.stats.build_time = start.elapsed();
        accel
    }

    /// Size and build time (the grid's part once it is built).
    #[must_use]
    pub fn stats(&self) -> AccelStats {
        let mut stats = self.stats;
        if let Some((grid, gaps, time)) = self.grid.get() {
            stats.grid_cells = grid.ny * grid.nz;
            stats.grid_entries = grid.entries();
            stats.memory_bytes += grid.memory_bytes() + gaps.memory_bytes();
            stats.grid_build_time = *time;
        }
        stats
    }

    /// Builds the `yz` grid of point classification now, if no point query
    /// has yet (they build it on first use); for callers who want the cost
    /// up front, or measured apart.
    pub fn build_point_grid(&self) {
        let _ = self.grid();
    }

    /// The `yz` grid, built on first use.
    pub(in crate::query) fn grid(&self) -> &YzGrid {
        self.grid_and_gaps().0
    }

    /// The `yz` grid and, on a closed surface, its cells' gaps along `x`
    /// (none on an open one, where a gap's parity would not hold across
    /// its column), built on first use.
    pub(in crate::query) fn grid_and_gaps(&self) -> (&YzGrid, &CellGaps) {
        let (grid, gaps, _) = self.grid.get_or_init(|| {
            let start = Instant::now();
            let grid = build_grid(&self.tris, self.bounds);
            let gaps = if self.is_closed() {
                CellGaps::find(&grid, &self.tris)
            } else {
                CellGaps::default()
            };
            (grid, gaps, start.elapsed())
        });
        (grid, gaps)
    }

    /// The bounding box of the solid's vertices.
    #[must_use]
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Whether the surface is closed (every edge has two faces).
    #[must_use]
    pub fn is_closed(&self) -> bool {
        self.boundary_edges == 0
    }

    /// `Ok` when the solid is convex (decided exactly, see [`NotConvex`]),
    /// else why not. Computed on first use (`O(n log n)` in the triangles)
    /// and cached.
    ///
    /// # Errors
    ///
    /// The first reason found in triangle order; see [`NotConvex`].
    pub fn convexity(&self) -> Result<(), NotConvex> {
        *self
            .convexity
            .get_or_init(|| check_convexity(&self.tris, &self.tri_face, self.boundary_edges))
    }

    pub(in crate::query) fn require_closed(&self) -> Result<(), super::QueryError> {
        if self.boundary_edges == 0 {
            Ok(())
        } else {
            Err(super::QueryError::NotClosed {
                boundary_edges: self.boundary_edges,
            })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

    #[test]
    fn accel_of_platonic_solids() {
        for solid in [
            builders::tetrahedron(),
            builders::cube(),
            builders::octahedron(),
            builders::icosahedron(),
        ] {
            let accel = Accel::new(&solid);
            assert!(accel.is_closed());
            assert_eq!(accel.convexity(), Ok(()));
            assert_eq!(accel.stats().grid_entries, 0, "the grid is built lazily");
            accel.build_point_grid();
            let s = accel.stats();
            assert!(s.triangles >= solid.face_count());
            assert!(s.grid_entries >= s.triangles);
        }
        let l = Accel::new(&builders::l_prism());
        assert!(l.convexity().is_err());
    }

    #[test]
    fn an_empty_solid_has_an_empty_accel() {
        let accel = Accel::new(&Solid::default());
        assert_eq!(accel.stats().triangles, 0);
        assert_eq!(
            accel.classify(DVec3::new(0.5, 0.5, 0.5)),
            Ok(super::super::Containment::Outside)
        );
        let ray = crate::geom::Ray::new(DVec3::ZERO, DVec3::X);
        assert_eq!(accel.first_hit(&ray), Ok(None));
        assert!(accel.ray_crossings(&ray).unwrap().hits.is_empty());
        assert_eq!(accel.winding_number(DVec3::ZERO), Ok(0.0));
    }
}
