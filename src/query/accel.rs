//! The acceleration structure shared by every query on one solid.

use std::time::{Duration, Instant};

use glam::{DVec2, DVec3};
use rayon::prelude::*;
use thiserror::Error;

use crate::geom::polygon::{Axis, Projection};
use crate::geom::{Aabb, Sign, orient2d, orient3d};
use crate::mesh::{FaceId, Solid};

use super::bvh_build::build_bvh;
use super::huge_pages::{HugeVec, collapse_into_huge_pages};
use super::tri_packet::TriPacket;

/// Why a solid is not convex (the normals method refuses it).
///
/// Decided exactly on the fan triangles: every edge of the triangulation
/// (face edges and fan diagonals) must be shared with one triangle running it
/// the other way, whose third corner is not strictly above the first
/// triangle's plane and, when exactly in it, lies across the edge (no fold).
/// A closed connected surface that is convex at every edge bounds a convex
/// body.
#[derive(Clone, Copy, Debug, Error, PartialEq)]
pub enum NotConvex {
    /// The surface has holes (an edge of a triangle has no partner running it
    /// the other way).
    #[error("the surface is not closed")]
    NotClosed,
    /// The surface has more than one connected shell.
    #[error("the surface has {count} shells")]
    Shells {
        /// How many shells.
        count: usize,
    },
    /// Across an edge of face `face`, the neighbouring corner `point` lies
    /// strictly outside the face's plane: a reflex edge (or a face whose
    /// corners are not exactly coplanar, bent outward).
    #[error("the corner {point} lies strictly outside the plane of face {face:?}")]
    ReflexEdge {
        /// The face.
        face: FaceId,
        /// The offending corner.
        point: DVec3,
    },
    /// Two coplanar triangles of face `face` fold over each other across an
    /// edge: the face has a reflex corner.
    #[error("face {face:?} folds over itself near {point} (a reflex corner)")]
    ReflexCorner {
        /// The face.
        face: FaceId,
        /// The offending corner.
        point: DVec3,
    },
}

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

/// One fan triangle as the queries need it: its exact corners split by
/// coordinate and the sign of its `yz` projection (80 bytes). Stored in BVH
/// leaf order; the grid and the BVH both index this one array.
#[derive(Clone, Copy, Debug, Default)]
#[repr(C)]
pub(super) struct YzTri {
    /// `x` of the three corners.
    pub x: [f64; 3],
    /// `y` of the three corners.
    pub y: [f64; 3],
    /// `z` of the three corners.
    pub z: [f64; 3],
    /// `orient2d` of the projected corners: the sign of the normal's `x`.
    pub sigma: i8,
}

impl YzTri {
    /// The corners as points.
    #[inline]
    pub fn corners(&self) -> [DVec3; 3] {
        [0, 1, 2].map(|k| DVec3::new(self.x[k], self.y[k], self.z[k]))
    }

    fn max_x(&self) -> f64 {
        self.x[0].max(self.x[1]).max(self.x[2])
    }

    fn min_x(&self) -> f64 {
        self.x[0].min(self.x[1]).min(self.x[2])
    }
}

/// A uniform grid over the `yz` projection of the solid's bounding box; each
/// cell lists the triangles whose projected bounding box overlaps it, by
/// ascending lower bound of `x`, and a bound on their `x` extents: so the
/// triangles a `−x` ray from a point can meet are a prefix of the cell's list
/// and those a `+x` ray can meet are within a suffix.
///
/// # Invariants
///
/// - Cell `c` owns `entries[cell_start[c] .. cell_start[c + 1]]`, sorted by
///   ascending [`GridEntry::x`], ties by record.
/// - `extent[c] ≥ max x − entry.x` for every triangle listed in cell `c`
///   (exactly, not only as rounded), so a triangle whose largest `x` is at
///   least `x` has `entry.x ≥ x − extent[c]`.
#[derive(Clone, Debug)]
pub(super) struct YzGrid {
    pub y0: f64,
    pub z0: f64,
    pub y1: f64,
    pub z1: f64,
    pub inv_hy: f64,
    pub inv_hz: f64,
    pub ny: usize,
    pub nz: usize,
    pub cell_start: Vec<u32>,
    pub entries: HugeVec<GridEntry>,
    pub extent: Vec<f32>,
}

/// One triangle listed in a grid cell: its `yz` record and its smallest `x`
/// rounded down to `f32` (8 bytes).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct GridEntry {
    /// A lower bound on the triangle's smallest `x`.
    pub x: f32,
    /// Index into the accel's triangles.
    pub record: u32,
}

impl YzGrid {
    /// The cell column of `y` (monotone in `y`, clamped).
    #[inline]
    pub fn col(&self, y: f64) -> usize {
        (((y - self.y0) * self.inv_hy) as usize).min(self.ny - 1)
    }

    /// The cell row of `z` (monotone in `z`, clamped).
    #[inline]
    pub fn row(&self, z: f64) -> usize {
        (((z - self.z0) * self.inv_hz) as usize).min(self.nz - 1)
    }

    /// The index of the cell holding `(y, z)`.
    #[inline]
    pub fn cell_index(&self, y: f64, z: f64) -> usize {
        self.row(z) * self.ny + self.col(y)
    }

    /// The triangles of cell `c` (an index from [`YzGrid::cell_index`]) and
    /// the bound on their `x` extents (see [`YzGrid`]).
    #[inline]
    pub fn cell_at(&self, c: usize) -> (&[GridEntry], f32) {
        let range = self.cell_start[c] as usize..self.cell_start[c + 1] as usize;
        (&self.entries[range], self.extent[c])
    }

    /// The number of cells, `ny · nz`.
    #[inline]
    pub fn cell_count(&self) -> usize {
        self.ny * self.nz
    }

    /// Triangle references held by the cells.
    pub fn entries(&self) -> usize {
        self.entries.len()
    }

    /// Heap bytes.
    pub fn memory_bytes(&self) -> usize {
        (self.cell_start.capacity() + self.extent.capacity()) * std::mem::size_of::<u32>()
            + self.entries.memory_bytes()
    }
}

/// A node of the binary BVH (before collapsing to [`Node8`]) with
/// conservatively rounded `f32` bounds in the accel's [`BoxFrame`] (32 bytes).
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Node {
    pub min: [f32; 3],
    pub max: [f32; 3],
    /// Leaf: first triangle; inner node: index of the second child (the
    /// first child follows the node).
    pub first: u32,
    /// Leaf: number of triangles (> 0); inner node: 0.
    pub count: u32,
}

/// Slots of a [`Node8`].
pub(super) const WIDTH: usize = 8;

/// The bit of [`Node8::child`] that marks a leaf slot (the rest is the index
/// of its [`TriPacket`]).
pub(super) const LEAF: u32 = 1 << 31;

/// A BVH node as traversed: the boxes of up to eight children in four cache
/// lines, so that deciding where to descend touches only the parent. Made by
/// collapsing the binary SAH tree: the tree is a third as deep, so a ray
/// waits for a third as many dependent node loads, and opens fewer nodes
/// (on sphere_80k 6.3 per ray instead of 9.5 with four slots). The eight
/// slab tests run side by side (see `node_open`). Boxes are in the accel's
/// [`BoxFrame`].
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(super) struct Node8 {
    /// The children's boxes by bound then axis then child: `bounds[a]` the
    /// lower bounds along axis `a` (rounded down), `bounds[3 + a]` the upper
    /// ones (rounded up), so that all children are tested in one pass. An
    /// empty slot has lower `+∞` and upper `−∞` (never entered).
    pub bounds: [[f32; WIDTH]; 6],
    /// Per child: [`LEAF`] plus the index of a leaf's [`TriPacket`], or the
    /// index of an inner node; `u32::MAX` for an empty slot.
    pub child: [u32; WIDTH],
    /// Per octant of ray directions (bit `a` set when the direction runs
    /// down axis `a`), the slots in the order the AVX-512 and AVX2 openers
    /// push them: nibble `k` (bits `4k .. 4k + 4`) holds the `k`-th slot in
    /// its low three bits, farthest first along the octant's diagonal (by
    /// the projection of the boxes' centres), and bit 3 set for an empty
    /// slot (never pushed, wherever it stands).
    ///
    /// # Invariants
    ///
    /// The low three bits of each entry's nibbles are a permutation of the
    /// slots, whatever the boxes (infinite or NaN centres included): a slot
    /// missing from the order would never be visited.
    pub order: [u32; WIDTH],
}

impl Node8 {
    pub(super) const EMPTY: Node8 = Node8 {
        bounds: [
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        child: [u32::MAX; WIDTH],
        order: [0xFEDC_BA98; WIDTH],
    };

    /// Fills [`Node8::order`] from the slots' boxes.
    pub(super) fn order_children(&mut self) {
        // Twice each box's centre; empty slots come first (their flag
        // keeps them from ever being pushed).
        let centre: [[f64; 3]; WIDTH] = std::array::from_fn(|k| {
            std::array::from_fn(|a| f64::from(self.bounds[a][k]) + f64::from(self.bounds[3 + a][k]))
        });
        let empty: [bool; WIDTH] = std::array::from_fn(|k| self.child[k] == u32::MAX);
        let flag = |slot: usize| slot as u32 | if empty[slot] { 8 } else { 0 };
        // The opposite octant (every sign flipped) takes the reverse order.
        for octant in 0..WIDTH / 2 {
            let along: [f64; WIDTH] = std::array::from_fn(|k| {
                if empty[k] {
                    return f64::INFINITY;
                }
                (0..3)
                    .map(|a| {
                        if octant >> a & 1 == 1 {
                            -centre[k][a]
                        } else {
                            centre[k][a]
                        }
                    })
                    .sum()
            });
            // Each slot's place by descending projection (ties by slot),
            // counted rather than sorted (a sort's comparisons are not
            // predictable, and this runs for every node). `total_cmp` is a
            // total order, NaN included, so the places are a permutation.
            let (mut forward, mut backward) = (0, 0);
            for k in 0..WIDTH {
                let place = (0..WIDTH)
                    .filter(|&j| match along[j].total_cmp(&along[k]) {
                        std::cmp::Ordering::Greater => true,
                        std::cmp::Ordering::Equal => j < k,
                        std::cmp::Ordering::Less => false,
                    })
                    .count();
                forward |= flag(k) << (4 * place);
                backward |= flag(k) << (4 * (WIDTH - 1 - place));
            }
            self.order[octant] = forward;
            self.order[WIDTH - 1 - octant] = backward;
        }
    }

    fn set(&mut self, k: usize, n: &Node, child: u32) {
        for a in 0..3 {
            self.bounds[a][k] = n.min[a];
            self.bounds[3 + a][k] = n.max[a];
        }
        self.child[k] = child;
    }
}

/// The coordinates the BVH's `f32` boxes are stored in: `(p − centre) ·
/// scale`, with `centre` the middle of the solid's bounding box and `scale`
/// the power of two that brings its largest half-extent into `[½, 1)`.
///
/// Relative to the centre, `f32` boxes stay as tight as the solid is small,
/// wherever it is (a solid 1e8 from the origin culls as well as one at the
/// origin); the power-of-two scale keeps `f32` far from overflow and
/// underflow for solids of any size (1e-12 or 1e12) and is exact.
///
/// # Invariants
///
/// Every stored bound is the exact real `(x − centre) · scale` rounded
/// outward: [`BoxFrame::lower`] never exceeds it, [`BoxFrame::upper`] is
/// never below it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct BoxFrame {
    /// The middle of the solid's bounding box (any point would be correct).
    pub centre: DVec3,
    /// A power of two.
    pub scale: f64,
}

impl BoxFrame {
    /// The frame of a solid with bounding box `bounds`.
    pub(super) fn of(bounds: &Aabb) -> BoxFrame {
        if bounds.is_empty() {
            return BoxFrame {
                centre: DVec3::ZERO,
                scale: 1.0,
            };
        }
        let centre = bounds.center();
        let half = (bounds.max - centre).max(centre - bounds.min).max_element();
        // 2^-e with 2^(e-1) <= half < 2^e; 1 for a single point.
        let scale = if half > 0.0 && half.is_finite() {
            let e = half.log2().floor() as i32 + 1;
            2f64.powi(-e.clamp(-1000, 1000))
        } else {
            1.0
        };
        BoxFrame { centre, scale }
    }

    /// `(x − centre[axis]) · scale`, rounded to `f64`: within half an
    /// `f64` ulp of the exact value (the scaling by a power of two is exact
    /// unless the result is subnormal, where it errs by at most 2⁻¹⁰⁷⁵).
    #[inline]
    pub fn in_frame(&self, x: f64, axis: usize) -> f64 {
        (x - self.centre[axis]) * self.scale
    }

    /// An `f32` at most the exact `(x − centre[axis]) · scale`: the rounded
    /// value stepped one `f64` ulp down (covering its rounding), then rounded
    /// down to `f32`.
    pub fn lower(&self, x: f64, axis: usize) -> f32 {
        f32_down(f64_below(self.in_frame(x, axis)))
    }

    /// An `f32` at least the exact `(x − centre[axis]) · scale`.
    pub fn upper(&self, x: f64, axis: usize) -> f32 {
        f32_up(f64_above(self.in_frame(x, axis)))
    }
}

/// Turns the binary BVH (one box per node) into [`Node8`]s, root first:
/// each binary inner node becomes a node whose slots hold up to eight of its
/// descendants (the inner descendant with the largest box opened first),
/// and each leaf a [`TriPacket`] of its triangles (`tris` in leaf order,
/// in the frame of scale `scale`). Also returns the depth of the new tree
/// (nodes on its longest path from the root).
///
/// The nodes are made in one pass, which numbers the leaves as it meets
/// them; the packets are then made on all cores, in that order. (Their
/// memory is fresh huge pages, whose first touch is costly at times on
/// this project's virtual machines: made in the serial pass, sphere_80k's
/// nodes and packets took 3–5 ms in most processes and 13–29 ms in a third
/// of them, 2026-11-22 00:40 UTC; with the packets made on two threads,
/// 2–4 ms in 12 processes out of 12 a few minutes later, when the slow
/// first touches had not come back for the serial pass either.)
fn to_node8(
    nodes: &[Node],
    tris: &[YzTri],
    scale: f64,
) -> (HugeVec<Node8>, HugeVec<TriPacket>, usize) {
    let leaves = nodes.iter().filter(|n| n.count > 0).count();
    // Each node but a leaf root's is made from its own binary inner node.
    let mut out = HugeVec::with_capacity((nodes.len() - leaves).max(1));
    out.push(Node8::EMPTY);
    let mut c = Collapse {
        nodes,
        out,
        leaves: Vec::with_capacity(leaves),
    };
    let has_triangles = nodes
        .first()
        .is_some_and(|n| n.count > 0 || nodes.len() > 1);
    let depth = if !has_triangles {
        1
    } else if nodes[0].count > 0 {
        let leaf = c.leaf(0);
        c.out[0].set(0, &nodes[0], leaf);
        1
    } else {
        c.fill(0, 0)
    };
    let packets = HugeVec::from_par_iter(c.leaves.par_iter().map(|&j| {
        let n = &nodes[j];
        TriPacket::new(tris, n.first, n.count, scale)
    }));
    let mut out = c.out;
    out.par_iter_mut().for_each(Node8::order_children);
    (out, packets, depth)
}

/// The state of [`to_node8`]'s pass over the binary tree.
struct Collapse<'a> {
    nodes: &'a [Node],
    out: HugeVec<Node8>,
    /// The binary leaves met so far, by packet index.
    leaves: Vec<usize>,
}

impl Collapse<'_> {
    /// Numbers binary leaf `j` as the next packet; returns its slot entry.
    fn leaf(&mut self, j: usize) -> u32 {
        self.leaves.push(j);
        (self.leaves.len() - 1) as u32 | LEAF
    }

    /// Fills `out[at]` from the binary inner node `i`, appending the nodes
    /// of its inner descendants and the packets of its leaves; returns the
    /// depth of the subtree at `out[at]`.
    fn fill(&mut self, i: usize, at: usize) -> usize {
        let nodes = self.nodes;
        let area = |n: &Node| {
            let s = [0, 1, 2].map(|a| f64::from(n.max[a]) - f64::from(n.min[a]));
            s[0] * s[1] + s[1] * s[2] + s[2] * s[0]
        };
        let mut slots: smallvec::SmallVec<[usize; WIDTH]> =
            smallvec::smallvec![i + 1, nodes[i].first as usize];
        while slots.len() < WIDTH {
            let open = (0..slots.len())
                .filter(|&k| nodes[slots[k]].count == 0)
                .max_by(|&p, &q| area(&nodes[slots[p]]).total_cmp(&area(&nodes[slots[q]])));
            let Some(k) = open else { break };
            let j = slots[k];
            slots[k] = j + 1;
            slots.insert(k + 1, nodes[j].first as usize);
        }
        let mut depth = 1;
        for (k, &j) in slots.iter().enumerate() {
            let n = &nodes[j];
            if n.count > 0 {
                let leaf = self.leaf(j);
                self.out[at].set(k, n, leaf);
            } else {
                let child = self.out.len();
                self.out.push(Node8::EMPTY);
                self.out[at].set(k, n, child as u32);
                depth = depth.max(1 + self.fill(j, child));
            }
        }
        depth
    }
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
/// - The BVH's `f32` node boxes, in `frame` (see `BoxFrame`), contain
///   their triangles' exact boxes (bounds rounded outward), so culling never
///   loses a triangle a ray touches.
/// - Every leaf slot of a node holds `LEAF` plus the index of the
///   `TriPacket` of its triangles (`first .. first + count` of `tris`, in
///   order); a packet only ever drops a triangle the exact line provably
///   misses.
/// - `stack_len` is at least `(WIDTH − 1) · depth + WIDTH` for the depth of
///   `nodes`.
/// - Every triangle whose projected `yz` box contains a point `(y, z)` is
///   listed in the grid cell of `(y, z)` (cell indices are monotone in the
///   coordinates).
#[derive(Clone, Debug)]
pub struct Accel {
    pub(super) tris: HugeVec<YzTri>,
    pub(super) tri_face: HugeVec<FaceId>,
    pub(super) nodes: HugeVec<Node8>,
    /// One per BVH leaf, the leaf's triangles in `f32` for the rays' miss
    /// filter; leaves of `nodes` index it.
    pub(super) packets: HugeVec<TriPacket>,
    pub(super) frame: BoxFrame,
    /// A length of traversal stack that never overflows: the stack holds
    /// at most `WIDTH − 1` deferred children per level above the node being
    /// opened, which then pushes at most `WIDTH` more.
    pub(super) stack_len: usize,
    grid: std::sync::OnceLock<(YzGrid, Duration)>,
    pub(super) bounds: Aabb,
    pub(super) boundary_edges: usize,
    pub(super) convexity: std::sync::OnceLock<Result<(), NotConvex>>,
    pub(super) stats: AccelStats,
}

/// Grid cells per triangle.
const CELLS_PER_TRIANGLE: f64 = 1.0;
/// The largest ratio of the grid's cell counts along `y` and `z`: a mesh
/// that is flat in one of them still gets a grid of sensible shape. A layout
/// choice, not a tolerance: it decides no answer.
const MAX_GRID_ASPECT: f64 = 1e6;

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
        let (tris, tri_face) = fan_triangles(solid);
        let (binary, order, frame, bounds) = build_bvh(&tris);
        let tris = HugeVec::from_par_iter(order.par_iter().map(|&i| yz_tri(&tris[i as usize])));
        let (nodes, packets, depth) = to_node8(&binary, &tris, frame.scale);
        drop(binary);
        let tri_face = HugeVec::from_par_iter(order.par_iter().map(|&i| tri_face[i as usize]));
        // What rays read at random, on huge pages where offered.
        tris.collapse();
        tri_face.collapse();
        nodes.collapse();
        packets.collapse();
        let memory_bytes = tris.memory_bytes()
            + tri_face.memory_bytes()
            + nodes.memory_bytes()
            + packets.memory_bytes();
        let stats = AccelStats {
            triangles: tris.len(),
            bvh_nodes: nodes.len(),
            grid_cells: 0,
            grid_entries: 0,
            memory_bytes,
            build_time: Duration::ZERO,
            grid_build_time: Duration::ZERO,
        };
        let mut accel = Accel {
            tris,
            tri_face,
            nodes,
            packets,
            frame,
            stack_len: (WIDTH - 1) * depth + WIDTH,
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
        if let Some((grid, time)) = self.grid.get() {
            stats.grid_cells = grid.ny * grid.nz;
            stats.grid_entries = grid.entries();
            stats.memory_bytes += grid.memory_bytes();
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
    pub(super) fn grid(&self) -> &YzGrid {
        &self
            .grid
            .get_or_init(|| {
                let start = Instant::now();
                let grid = build_grid(&self.tris, self.bounds);
                (grid, start.elapsed())
            })
            .0
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

    pub(super) fn require_closed(&self) -> Result<(), super::QueryError> {
        if self.boundary_edges == 0 {
            Ok(())
        } else {
            Err(super::QueryError::NotClosed {
                boundary_edges: self.boundary_edges,
            })
        }
    }
}

/// The fan triangles of every face (apex at [`fan_apex`]) and their faces,
/// in face order.
fn fan_triangles(solid: &Solid) -> (Vec<[DVec3; 3]>, Vec<FaceId>) {
    let ids: Vec<FaceId> = solid.faces().map(|(id, _)| id).collect();
    // Each run of faces makes its triangles into two flat arrays, which are
    // then appended in order (a copy of a few large blocks, not one small
    // vector per face).
    let parts: Vec<(Vec<[DVec3; 3]>, Vec<FaceId>)> = ids
        .par_chunks(FAN_CHUNK)
        .map(|run| {
            let (mut tris, mut faces) =
                (Vec::with_capacity(run.len()), Vec::with_capacity(run.len()));
            let mut corners: Vec<DVec3> = Vec::with_capacity(8);
            for &id in run {
                if solid.face_ring_count(id) > 0 {
                    push_face_with_rings(solid, id, &mut tris, &mut faces);
                    continue;
                }
                corners.clear();
                for v in solid.face_vertices(id) {
                    corners.push(solid.position(v));
                }
                // Canonical fan apex: the triangulation of a face whose
                // corners are not exactly coplanar must not depend on where
                // its vertex list starts.
                let apex = fan_apex(&corners);
                corners.rotate_left(apex);
                for k in 1..corners.len().saturating_sub(1) {
                    tris.push([corners[0], corners[k], corners[k + 1]]);
                    faces.push(id);
                }
            }
            (tris, faces)
        })
        .collect();
    let count: usize = parts.iter().map(|(t, _)| t.len()).sum();
    let (mut tris, mut tri_face) = (Vec::with_capacity(count), Vec::with_capacity(count));
    for (t, f) in &parts {
        tris.extend_from_slice(t);
        tri_face.extend_from_slice(f);
    }
    (tris, tri_face)
}

/// The triangles of a face with rings (a fan cannot cover it): its exact
/// constrained triangulation ([`Solid::try_triangulate_face`]). Loops that
/// do not bound a valid face (validation reports them) are fanned one by
/// one instead: the fans of a ring, wound against the outer loop, cover the
/// hole a second time, so every line still crosses the face an odd number
/// of times exactly where it crosses the face's region.
fn push_face_with_rings(
    solid: &Solid,
    face: FaceId,
    tris: &mut Vec<[DVec3; 3]>,
    faces: &mut Vec<FaceId>,
) {
    let at = |v| solid.position(v);
    match solid.try_triangulate_face(face) {
        Ok(triangles) => {
            for t in triangles {
                tris.push(t.map(at));
                faces.push(face);
            }
        }
        Err(_) => {
            for l in solid.face_loops(face) {
                let corners: Vec<DVec3> = solid.loop_vertices(l).map(at).collect();
                for k in 1..corners.len().saturating_sub(1) {
                    tris.push([corners[0], corners[k], corners[k + 1]]);
                    faces.push(face);
                }
            }
        }
    }
}

/// Faces per unit of parallel work in [`fan_triangles`].
const FAN_CHUNK: usize = 4096;

/// The index of the lexicographically smallest point `(x, y, z)`: the apex
/// of a face's fan triangulation. Preserved by translations and positive
/// scalings, independent of where the vertex list starts.
fn fan_apex(corners: &[DVec3]) -> usize {
    (0..corners.len())
        .min_by(|&i, &j| {
            let (p, q) = (corners[i], corners[j]);
            p.x.total_cmp(&q.x)
                .then(p.y.total_cmp(&q.y))
                .then(p.z.total_cmp(&q.z))
        })
        .unwrap_or(0)
}

fn yz_tri(t: &[DVec3; 3]) -> YzTri {
    let p = |v: DVec3| DVec2::new(v.y, v.z);
    YzTri {
        x: [t[0].x, t[1].x, t[2].x],
        y: [t[0].y, t[1].y, t[2].y],
        z: [t[0].z, t[1].z, t[2].z],
        sigma: orient2d(p(t[0]), p(t[1]), p(t[2])).as_i32() as i8,
    }
}

fn build_grid(yz: &[YzTri], bounds: Aabb) -> YzGrid {
    let (y0, z0, y1, z1) = if bounds.is_empty() {
        (0.0, 0.0, 1.0, 1.0)
    } else {
        (bounds.min.y, bounds.min.z, bounds.max.y, bounds.max.z)
    };
    let (wy, wz) = (
        (y1 - y0).max(f64::MIN_POSITIVE),
        (z1 - z0).max(f64::MIN_POSITIVE),
    );
    let cells = (yz.len() as f64 * CELLS_PER_TRIANGLE).clamp(1.0, 64.0e6);
    let aspect = (wy / wz).clamp(1.0 / MAX_GRID_ASPECT, MAX_GRID_ASPECT);
    // At most 2¹⁴ cells either way (so a cell index fits `u16`).
    let ny = ((cells * aspect).sqrt().round() as usize).clamp(1, 1 << 14);
    let nz = ((cells / ny as f64).round() as usize).clamp(1, 1 << 14);
    let mut grid = YzGrid {
        y0,
        z0,
        y1,
        z1,
        inv_hy: ny as f64 / wy,
        inv_hz: nz as f64 / wz,
        ny,
        nz,
        cell_start: vec![0; ny * nz + 1],
        entries: HugeVec::with_capacity(0),
        extent: vec![0.0; ny * nz],
    };
    // Each triangle's cells: columns `c0..=c1`, rows `r0..=r1` (its
    // projected box mapped by the monotone `col` and `row`).
    let spans: Vec<[u16; 4]> = yz
        .par_iter()
        .with_min_len(4096)
        .map(|t| {
            let ymin = t.y[0].min(t.y[1]).min(t.y[2]);
            let ymax = t.y[0].max(t.y[1]).max(t.y[2]);
            let zmin = t.z[0].min(t.z[1]).min(t.z[2]);
            let zmax = t.z[0].max(t.z[1]).max(t.z[2]);
            [
                grid.col(ymin),
                grid.col(ymax),
                grid.row(zmin),
                grid.row(zmax),
            ]
            .map(|k| k as u16)
        })
        .collect();
    // Rows are split into bands; a band's cells are a contiguous range (row
    // major), so each band counts, fills and sorts its own part in parallel.
    let bands = (4 * rayon::current_num_threads()).clamp(1, nz);
    let band_rows = |b: usize| (b * nz / bands, (b + 1) * nz / bands);
    let rows_of = |span: &[u16; 4], (lo, hi): (usize, usize)| {
        usize::from(span[2]).max(lo)..(usize::from(span[3]) + 1).min(hi)
    };
    {
        let mut counts: Vec<&mut [u32]> = Vec::with_capacity(bands);
        let mut rest: &mut [u32] = &mut grid.cell_start[1..];
        for b in 0..bands {
            let (lo, hi) = band_rows(b);
            let (head, tail) = std::mem::take(&mut rest).split_at_mut((hi - lo) * ny);
            counts.push(head);
            rest = tail;
        }
        counts.into_par_iter().enumerate().for_each(|(b, count)| {
            let (lo, hi) = band_rows(b);
            for span in &spans {
                for r in rows_of(span, (lo, hi)) {
                    for c in usize::from(span[0])..=usize::from(span[1]) {
                        count[(r - lo) * ny + c] += 1;
                    }
                }
            }
        });
    }
    for i in 0..ny * nz {
        grid.cell_start[i + 1] += grid.cell_start[i];
    }
    let total = grid.cell_start[ny * nz] as usize;
    // Initialised in parallel: for a large mesh this is mostly page faults
    // (fewer of them on huge pages, which the point queries' random reads
    // want too).
    let mut entries = HugeVec::from_par_iter(
        (0..total)
            .into_par_iter()
            .with_min_len(1 << 16)
            .map(|_| GridEntry::default()),
    );
    let mut parts = Vec::with_capacity(bands);
    let mut rest: &mut [GridEntry] = &mut entries;
    let mut extent_rest: &mut [f32] = &mut grid.extent;
    for b in 0..bands {
        let (lo, hi) = band_rows(b);
        let len = (grid.cell_start[hi * ny] - grid.cell_start[lo * ny]) as usize;
        let (head, tail) = std::mem::take(&mut rest).split_at_mut(len);
        let (extent_head, extent_tail) =
            std::mem::take(&mut extent_rest).split_at_mut((hi - lo) * ny);
        parts.push((head, extent_head));
        rest = tail;
        extent_rest = extent_tail;
    }
    let cell_start = &grid.cell_start;
    parts
        .into_par_iter()
        .enumerate()
        .for_each(|(b, (part, extent))| {
            let (lo, hi) = band_rows(b);
            let base = cell_start[lo * ny];
            let mut fill: Vec<u32> = cell_start[lo * ny..hi * ny]
                .iter()
                .map(|&s| s - base)
                .collect();
            for (i, (t, span)) in yz.iter().zip(&spans).enumerate() {
                let rows = rows_of(span, (lo, hi));
                if rows.is_empty() {
                    continue;
                }
                let min_x = f32_down(t.min_x());
                // At least `max x − min_x` exactly: the rounded difference
                // is within half an ulp of it, the next `f64` above it is not
                // below it, and rounding up to `f32` keeps that.
                let reach = f32_up(f64_above(t.max_x() - f64::from(min_x)));
                for r in rows {
                    for c in usize::from(span[0])..=usize::from(span[1]) {
                        let cell = (r - lo) * ny + c;
                        part[fill[cell] as usize] = GridEntry {
                            x: min_x,
                            record: i as u32,
                        };
                        fill[cell] += 1;
                        extent[cell] = extent[cell].max(reach);
                    }
                }
            }
            // Each cell's list by ascending `x`: filled in record order, so a
            // stable sort breaks ties by record.
            for cell in lo * ny..hi * ny {
                let s = (cell_start[cell] - base) as usize;
                let e = (cell_start[cell + 1] - base) as usize;
                sort_by_x(&mut part[s..e]);
            }
        });
    entries.collapse();
    collapse_into_huge_pages(&grid.cell_start);
    collapse_into_huge_pages(&grid.extent);
    grid.entries = entries;
    grid
}

/// Stable insertion sort of a cell's entries by ascending [`GridEntry::x`]:
/// cells hold a handful of entries, for which this is the fastest sort. The
/// bounds are never NaN (rounded from finite coordinates).
fn sort_by_x(entries: &mut [GridEntry]) {
    for i in 1..entries.len() {
        let e = entries[i];
        let mut j = i;
        while j > 0 && e.x < entries[j - 1].x {
            entries[j] = entries[j - 1];
            j -= 1;
        }
        entries[j] = e;
    }
}

// ---------------------------------------------------------------------------
// BVH: binned SAH over triangle boxes.

/// The largest `f32` not above `x` (`x` itself when representable; `−∞`
/// below the `f32` range only for `x = −∞`).
pub(super) fn f32_down(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) > x { f32_below(f) } else { f }
}

/// The next `f32` below `f` (`f` itself for `−∞` and NaN; below `±0` the
/// smallest negative subnormal). `f32::next_down` is newer than the crate's
/// minimum Rust.
pub(super) fn f32_below(f: f32) -> f32 {
    if f.is_nan() || f == f32::NEG_INFINITY {
        return f;
    }
    if f == 0.0 {
        return -f32::from_bits(1);
    }
    let bits = f.to_bits();
    f32::from_bits(if f > 0.0 { bits - 1 } else { bits + 1 })
}

/// The next `f64` below `x` (as [`f32_below`]).
pub(super) fn f64_below(x: f64) -> f64 {
    if x.is_nan() || x == f64::NEG_INFINITY {
        return x;
    }
    if x == 0.0 {
        return -f64::from_bits(1);
    }
    let bits = x.to_bits();
    f64::from_bits(if x > 0.0 { bits - 1 } else { bits + 1 })
}

/// The next `f64` above `x`.
pub(super) fn f64_above(x: f64) -> f64 {
    -f64_below(-x)
}

/// The smallest `f32` not below `x`.
pub(super) fn f32_up(x: f64) -> f32 {
    let f = x as f32;
    if f64::from(f) < x { -f32_below(-f) } else { f }
}

// ---------------------------------------------------------------------------
// Convexity, decided exactly on the fan triangles.

/// The exact convexity test on the fan triangles; see [`NotConvex`].
fn check_convexity(
    tris: &[YzTri],
    tri_face: &[FaceId],
    boundary_edges: usize,
) -> Result<(), NotConvex> {
    if boundary_edges > 0 {
        return Err(NotConvex::NotClosed);
    }
    let key = |p: DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
    // Every directed edge (by exact corner coordinates) with its triangle and
    // the triangle's third corner; sorted so that partners can be found.
    let mut edges: Vec<([u64; 3], [u64; 3], u32, u8)> = tris
        .par_iter()
        .enumerate()
        .flat_map_iter(|(i, t)| {
            let c = t.corners();
            (0..3).map(move |k| {
                (
                    key(c[k]),
                    key(c[(k + 1) % 3]),
                    i as u32,
                    ((k + 2) % 3) as u8,
                )
            })
        })
        .collect();
    edges.par_sort_unstable();
    let partner = |from: [u64; 3], to: [u64; 3]| {
        edges
            .binary_search_by(|e| (e.0, e.1).cmp(&(from, to)))
            .ok()
            .map(|j| edges[j])
    };
    // Local test at every edge, in parallel; the first failure in edge order
    // is reported.
    let local = edges.par_iter().find_map_first(|&(from, to, t, _)| {
        let Some((_, _, u, opposite)) = partner(to, from) else {
            return Some(NotConvex::NotClosed);
        };
        let [a, b, c] = tris[t as usize].corners();
        let d = tris[u as usize].corners()[opposite as usize];
        let face = tri_face[t as usize];
        match orient3d(a, b, c, d) {
            Sign::Positive => Some(NotConvex::ReflexEdge { face, point: d }),
            Sign::Negative => None,
            Sign::Zero => {
                // Coplanar neighbours must lie across the shared edge.
                let (p, q) = (from, to);
                let [pp, qq] = [p, q].map(|k| {
                    DVec3::new(
                        f64::from_bits(k[0]),
                        f64::from_bits(k[1]),
                        f64::from_bits(k[2]),
                    )
                });
                let r = [a, b, c]
                    .into_iter()
                    .find(|&v| key(v) != p && key(v) != q)
                    .unwrap_or(a);
                folded(pp, qq, r, d).then_some(NotConvex::ReflexCorner { face, point: d })
            }
        }
    });
    if let Some(reason) = local {
        return Err(reason);
    }
    let shells = count_shells(tris.len(), &edges);
    if shells != 1 {
        return Err(NotConvex::Shells { count: shells });
    }
    Ok(())
}

/// Whether `r` and `s`, coplanar with the edge `p q`, lie strictly on the
/// same side of it (decided in an axis plane where `p, q, r` do not
/// collapse). Degenerate triangles never fold.
fn folded(p: DVec3, q: DVec3, r: DVec3, s: DVec3) -> bool {
    for axis in [Axis::X, Axis::Y, Axis::Z] {
        let proj = Projection {
            axis,
            flipped: false,
        };
        let [pp, qq, rr, ss] = [p, q, r, s].map(|v| proj.apply(v));
        let side_r = orient2d(pp, qq, rr);
        if side_r != Sign::Zero {
            return orient2d(pp, qq, ss) == side_r;
        }
    }
    false
}

/// The number of edge-connected components of the triangles, from the
/// sorted directed edges (union–find).
fn count_shells(n: usize, edges: &[([u64; 3], [u64; 3], u32, u8)]) -> usize {
    let mut parent: Vec<u32> = (0..n as u32).collect();
    fn root(parent: &mut [u32], mut i: u32) -> u32 {
        while parent[i as usize] != i {
            let grand = parent[parent[i as usize] as usize];
            parent[i as usize] = grand;
            i = grand;
        }
        i
    }
    for &(from, to, t, _) in edges {
        if let Ok(j) = edges.binary_search_by(|e| (e.0, e.1).cmp(&(to, from))) {
            let (a, b) = (root(&mut parent, t), root(&mut parent, edges[j].2));
            if a != b {
                parent[a as usize] = b;
            }
        }
    }
    (0..n as u32).filter(|&i| root(&mut parent, i) == i).count()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::builders;

    #[test]
    fn f32_bounds_round_outward() {
        for x in [0.1, -0.1, 1e12 + 0.3, -1e-12, 1e-50, -1e-50, 0.0, 3.0] {
            assert!(f64::from(f32_down(x)) <= x, "{x}");
            assert!(f64::from(f32_up(x)) >= x, "{x}");
        }
    }

    #[test]
    fn frame_bounds_round_outward() {
        // Far from the origin, a tiny solid: `x − centre` is exact here, so
        // the bounds must bracket it, and tightly (f32 relative to the
        // solid's size, not to its distance from the origin).
        let bounds = Aabb::from_points([DVec3::splat(1e8), DVec3::splat(1e8 + 1.0)]);
        let frame = BoxFrame::of(&bounds);
        assert_eq!(frame.scale, 1.0);
        for x in [1e8, 1e8 + 1.0, 1e8 + 2f64.powi(-26), 1e8 + 0.75] {
            let exact = (x - frame.centre.x) * frame.scale;
            let (lo, hi) = (frame.lower(x, 0), frame.upper(x, 0));
            assert!(f64::from(lo) <= exact && exact <= f64::from(hi), "{x}");
            assert!(f64::from(hi) - f64::from(lo) < 1e-6, "{x}: {lo} {hi}");
        }
        // Huge and tiny solids keep the frame's coordinates near 1.
        for size in [1e-300, 1e-12, 1e12, 1e300] {
            let b = Aabb::from_points([DVec3::ZERO, DVec3::splat(size)]);
            let f = BoxFrame::of(&b);
            let top = f.upper(size, 1);
            assert!((0.5..=1.0).contains(&top), "{size}: {top}");
        }
    }

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
