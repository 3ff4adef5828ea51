//! The octree: cells the boundary meets are split down to the depth asked
//! for; every other cell is `In` or `Out`. Written once over a
//! [`CellTarget`]: a solid (below) or a CSG tree
//! ([`Octree::classify_csg`]).
//!
//! # How the cells of a solid are labelled
//!
//! 1. The root is the smallest cube of power-of-two side whose corner is a
//!    multiple of the finest cell side and which holds the solid's box, so
//!    that every cell corner is an exact `f64` and every cell volume a power
//!    of two.
//! 2. A cell is `On` exactly when the solid's boundary meets the closed
//!    cell: its faces, triangulated exactly (`Solid::try_triangulate_face`,
//!    rings included), are
//!    fetched by a box query on the shared BVH and tested by
//!    [`box_meets_triangle`](crate::geom::box_meets_triangle). `On` cells above the finest depth are split;
//!    cells the boundary does not meet are leaves.
//! 3. Two leaves that share a face and are both not `On` lie in one region
//!    without boundary, so they have the same label. Leaves are joined
//!    across shared faces (union–find; a leaf looks for its neighbour at
//!    its own depth and above, so every adjacency is found from its finer
//!    side), and one point of each region — the centre of its first cell,
//!    rounded, still inside that cell — is classified exactly. A region
//!    costs one query, not one per cell.
//!
//! A CSG tree labels each cell itself ([`Csg::cell_verdict`]): `In` or
//! `Out` when every leaf whose side matters is decided on the cell, else
//! refined; what a cell learnt of a leaf is handed down to its sub-cells.
//!
//! # The volume interval
//!
//! `In` cells lie inside the solid and `On` cells hold all of its
//! boundary, so the solid's volume lies in `[V_in, V_in + V_on]`. Cell
//! volumes are powers of two: the totals are counted exactly in units of
//! the finest cell and rounded down and up only past 2^53 units, so the
//! interval is certified.

use std::cell::RefCell;

use rayon::prelude::*;
use rustc_hash::FxHashMap;

use glam::DVec3;
use thiserror::Error;

use super::label::{Cell, Label};
use super::target::{CellTarget, CsgTarget, Judgement, SolidTarget};
use super::walk::{Pending, Task};
use crate::csg::{Csg, LeafTileError, Stats};
use crate::disjoint_sets::DisjointSets;
use crate::geom::{Aabb, Readable};
use crate::mesh::{FaceId, Solid};
use crate::query::{Accel, BoundaryTiles};

/// The deepest octree [`Octree::classify`] builds: `2^16` cells along a
/// side, far past what memory holds for a surface of any size.
pub const MAX_DEPTH: u32 = 16;

/// The deepest octree whose dense array [`Octree::dense`] writes:
/// `2^9 = 512` cells along a side, 128 MiB.
pub const MAX_DENSE_DEPTH: u32 = 9;

/// Down to this depth a solid's octree is walked on one thread; the
/// subtrees below it (up to 8³ of them) are refined in parallel.
const PARALLEL_DEPTH: u32 = 3;

/// How many leaves of each label one depth holds.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct LevelCounts {
    /// `In` leaves.
    pub inside: u64,
    /// `Out` leaves.
    pub outside: u64,
    /// `On` leaves.
    pub on: u64,
}

/// Why cells cannot be made.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum CellsError {
    /// A depth beyond [`MAX_DEPTH`] (or, for the dense array, beyond
    /// [`MAX_DENSE_DEPTH`]).
    #[error("depth {depth} is beyond the limit of {limit}")]
    TooDeep {
        /// The depth asked for.
        depth: u32,
        /// The limit.
        limit: u32,
    },
    /// In and out need a closed surface.
    #[error("the solid is not closed ({0} edges have one face): in and out are undefined")]
    NotClosed(usize),
    /// A solid without faces.
    #[error("the solid has no faces")]
    Empty,
    /// A face that is not a simple planar polygon cannot be tiled exactly.
    #[error("face {face:?} cannot be triangulated: {message}")]
    Face {
        /// The face.
        face: FaceId,
        /// Why.
        message: String,
    },
    /// A leaf of a CSG tree whose faces cannot be tiled exactly.
    #[error(transparent)]
    Leaf(#[from] LeafTileError),
    /// A CSG tree whose solid is unbounded (a half-space not cut down to a
    /// bounded piece).
    #[error("the solid is unbounded (its bounds reach infinity): nothing to lay cells over")]
    Unbounded,
    /// A CSG tree whose bounds hold nothing (an intersection of disjoint
    /// boxes).
    #[error("the solid is empty (its bounds hold nothing)")]
    EmptyBounds,
    /// The `In` cells' outer faces could not be made manifold within the
    /// repair's bounds (see [`Octree::in_shell`]).
    #[error("the In cells' faces cannot be made a manifold solid: {message}")]
    Repair {
        /// Why.
        message: String,
    },
    /// The certified volume interval cannot be held in `f64`: the finest
    /// cell's volume `2^exponent` times the cell counts overflows, or
    /// underflows below the normal range (where it would be rounded).
    #[error(
        "the certified volume interval cannot be held in f64: {low_cells} to {high_cells} finest cells of volume 2^{exponent} each {}",
        if *.exponent > 0 { "overflow" } else { "underflow" }
    )]
    VolumeOutOfRange {
        /// The binary exponent of the finest cell's volume.
        exponent: i32,
        /// The lower end of the interval, in finest cells.
        low_cells: u128,
        /// The upper end of the interval, in finest cells.
        high_cells: u128,
    },
    /// The solid's box is too large for cell corners to be exact.
    #[error("the solid's box (size {}) is too large or too far out for exact cell corners", Readable(*.size))]
    OutOfRange {
        /// The longest side of the solid's box.
        size: f64,
    },
}

/// An octree over a solid with every leaf labelled.
///
/// # Invariants
///
/// - `leaves` tile the root cube; `On` leaves are all at depth `depth`.
/// - `counts[d]` counts the leaves at depth `d` by label.
#[derive(Clone, Debug)]
pub struct Octree {
    origin: DVec3,
    side: f64,
    depth: u32,
    leaves: Vec<Cell>,
    counts: Vec<LevelCounts>,
    regions: usize,
}

impl Octree {
    /// Labels the cells of an octree of depth `depth` over `solid`.
    ///
    /// # Errors
    ///
    /// [`CellsError::TooDeep`], [`CellsError::Empty`],
    /// [`CellsError::NotClosed`], [`CellsError::Face`] for a face that is
    /// not a simple planar polygon, [`CellsError::OutOfRange`] for a box
    /// whose cell corners would not be exact.
    pub fn classify(solid: &Solid, depth: u32) -> Result<Octree, CellsError> {
        if depth > MAX_DEPTH {
            return Err(CellsError::TooDeep {
                depth,
                limit: MAX_DEPTH,
            });
        }
        if solid.face_count() == 0 {
            return Err(CellsError::Empty);
        }
        let accel = Accel::new(solid);
        if !accel.is_closed() {
            let open = solid
                .edges()
                .filter(|(_, e)| e.right_face.is_none())
                .count();
            return Err(CellsError::NotClosed(open));
        }
        let (origin, side) = root_cube(&solid.bounding_box(), depth)?;
        let tiles = BoundaryTiles::try_new(solid).map_err(|e| CellsError::Face {
            face: e.face,
            message: e.source.to_string(),
        })?;
        Ok(Octree::build_parallel(
            &SolidTarget { accel, tiles },
            origin,
            side,
            depth,
        ))
    }

    /// Labels the cells of an octree of depth `depth` over the solid of a
    /// CSG tree (see [`Csg::cell_verdict`]).
    ///
    /// A cell is `On` when the boundary of a leaf whose side could change
    /// the tree's answer may meet it: exactly when it meets for flat leaves
    /// (half-spaces, boxes, polyhedra, moved boxes and polyhedra),
    /// conservatively for spheres and cylinders, so `On` cells hold the whole
    /// boundary of the result and perhaps a little more. A cell inside or
    /// outside every leaf that matters gets the tree's label at once, and
    /// what a cell learns of a leaf holds for its sub-cells. The tree's
    /// work is added to `stats` (leaf box tests, point classifications,
    /// culled subtrees, skipped right operands).
    ///
    /// # Errors
    ///
    /// [`CellsError::TooDeep`], [`CellsError::Leaf`] for a polyhedral leaf
    /// whose faces cannot be tiled, [`CellsError::Unbounded`],
    /// [`CellsError::EmptyBounds`], [`CellsError::OutOfRange`].
    pub fn classify_csg(csg: &Csg, depth: u32, stats: &mut Stats) -> Result<Octree, CellsError> {
        if depth > MAX_DEPTH {
            return Err(CellsError::TooDeep {
                depth,
                limit: MAX_DEPTH,
            });
        }
        csg.prepare_cells()?;
        let bounds = csg.bounds();
        if bounds.is_empty() {
            return Err(CellsError::EmptyBounds);
        }
        if !(bounds.min.is_finite() && bounds.max.is_finite()) {
            return Err(CellsError::Unbounded);
        }
        // Every primitive's bounds hold it (rounded ones are rounded
        // outward), so the root cube holds the solid.
        let (origin, side) = root_cube(&bounds, depth)?;
        let target = CsgTarget {
            csg,
            stats: RefCell::new(Stats::default()),
        };
        let tree = Octree::build(&target, origin, side, depth);
        *stats += target.stats.into_inner();
        Ok(tree)
    }

    /// An unlabelled tree over the root cube.
    fn empty(origin: DVec3, side: f64, depth: u32) -> Octree {
        Octree {
            origin,
            side,
            depth,
            leaves: Vec::new(),
            counts: vec![LevelCounts::default(); depth as usize + 1],
            regions: 0,
        }
    }

    /// Refines the cells the target's boundary may meet, labels the rest,
    /// and counts.
    fn build<T: CellTarget>(target: &T, origin: DVec3, side: f64, depth: u32) -> Octree {
        let mut tree = Octree::empty(origin, side, depth);
        let root = Pending {
            depth: 0,
            at: [0; 3],
            known: target.root_known(),
        };
        let (leaves, free) = tree.descend(target, root);
        tree.leaves = leaves;
        tree.finish(target, &free);
        tree
    }

    /// [`Octree::build`] with the subtrees below [`PARALLEL_DEPTH`] refined
    /// on all threads. The leaves come out in the same order as from the
    /// sequential build: the subtrees are those the sequential walk would
    /// visit one after the other, and their leaves are joined in that
    /// order.
    fn build_parallel<T>(target: &T, origin: DVec3, side: f64, depth: u32) -> Octree
    where
        T: CellTarget + Sync,
        T::Known: Send,
    {
        let mut tree = Octree::empty(origin, side, depth);
        // The walk of the sequential build down to PARALLEL_DEPTH: cells
        // decided on the way become leaves, in order, and the cells reached
        // at that depth become subtrees.
        let mut tasks: Vec<Task<T::Known>> = Vec::new();
        let mut stack = vec![Pending {
            depth: 0,
            at: [0; 3],
            known: target.root_known(),
        }];
        while let Some(mut cell) = stack.pop() {
            if cell.depth == PARALLEL_DEPTH.min(depth) {
                tasks.push(Task::Subtree(cell));
                continue;
            }
            let [x, y, z] = cell.at;
            let bounds = tree.cell_box(cell.depth, x, y, z);
            match target.judge(&bounds, &mut cell.known) {
                Judgement::Meets => stack.extend(cell.children(
                    target,
                    &tree.child_boxes(&cell),
                    cell.depth + 1 == depth,
                )),
                judgement => tasks.push(Task::Leaf {
                    cell: cell.leaf(judgement),
                    free: judgement == Judgement::Free,
                }),
            }
        }
        let parts: Vec<(Vec<Cell>, Vec<usize>)> = tasks
            .into_par_iter()
            .map(|task| match task {
                Task::Leaf { cell, free } => (vec![cell], if free { vec![0] } else { Vec::new() }),
                Task::Subtree(cell) => tree.descend(target, cell),
            })
            .collect();
        let mut free = Vec::new();
        for (leaves, part_free) in parts {
            let offset = tree.leaves.len();
            free.extend(part_free.into_iter().map(|i| i + offset));
            tree.leaves.extend(leaves);
        }
        tree.finish(target, &free);
        tree
    }

    /// The leaves below `start` in the sequential walk's order (the last
    /// child first), and the indices of the `Free` ones among them, whose
    /// label is `Out` until their region is labelled.
    fn descend<T: CellTarget>(
        &self,
        target: &T,
        start: Pending<T::Known>,
    ) -> (Vec<Cell>, Vec<usize>) {
        let mut leaves = Vec::new();
        let mut free = Vec::new();
        let mut stack = vec![start];
        while let Some(mut cell) = stack.pop() {
            let [x, y, z] = cell.at;
            let bounds = self.cell_box(cell.depth, x, y, z);
            let judgement = target.judge(&bounds, &mut cell.known);
            if judgement == Judgement::Meets && cell.depth < self.depth {
                stack.extend(cell.children(
                    target,
                    &self.child_boxes(&cell),
                    cell.depth + 1 == self.depth,
                ));
                continue;
            }
            if judgement == Judgement::Free {
                free.push(leaves.len());
            }
            leaves.push(cell.leaf(judgement));
        }
        (leaves, free)
    }

    /// Labels the free regions and counts the leaves.
    fn finish<T: CellTarget>(&mut self, target: &T, free: &[usize]) {
        if !free.is_empty() {
            self.label_regions(free, target);
        }
        for c in &self.leaves {
            let counts = &mut self.counts[c.depth as usize];
            match c.label {
                Label::In => counts.inside += 1,
                Label::Out => counts.outside += 1,
                Label::On => counts.on += 1,
            }
        }
    }

    /// Joins face-adjacent undecided leaves and labels each region by one
    /// exact point classification.
    fn label_regions<T: CellTarget>(&mut self, undecided: &[usize], target: &T) {
        let index: FxHashMap<(u32, u32, u32, u32), usize> = self
            .leaves
            .iter()
            .enumerate()
            .map(|(i, c)| ((c.depth, c.x, c.y, c.z), i))
            .collect();
        let mut sets = DisjointSets::new(self.leaves.len());
        for &i in undecided {
            let c = self.leaves[i];
            let n = 1u32 << c.depth;
            for (axis, step) in [(0, -1i64), (0, 1), (1, -1), (1, 1), (2, -1), (2, 1)] {
                let mut at = [i64::from(c.x), i64::from(c.y), i64::from(c.z)];
                at[axis] += step;
                if at[axis] < 0 || at[axis] >= i64::from(n) {
                    continue;
                }
                // The neighbour at this depth, or the coarser leaf holding it.
                let mut d = c.depth;
                let mut at = at.map(|v| v as u32);
                loop {
                    if let Some(&j) = index.get(&(d, at[0], at[1], at[2])) {
                        if self.leaves[j].label != Label::On {
                            sets.union(i, j);
                        }
                        break;
                    }
                    if d == 0 {
                        break;
                    }
                    d -= 1;
                    at = at.map(|v| v / 2);
                }
            }
        }
        let mut region_label: FxHashMap<usize, Label> = FxHashMap::default();
        for &i in undecided {
            let root = sets.find(i);
            let label = *region_label.entry(root).or_insert_with(|| {
                let c = self.leaves[root];
                let b = self.cell_box(c.depth, c.x, c.y, c.z);
                let centre = (b.min + (b.max - b.min) * 0.5).clamp(b.min, b.max);
                target.classify(centre)
            });
            self.leaves[i].label = label;
        }
        self.regions = region_label.len();
    }

    /// The closed boxes of the eight children of `cell`, child `k` at
    /// offset `(k & 1, k >> 1 & 1, k >> 2)`.
    fn child_boxes<K>(&self, cell: &Pending<K>) -> [Aabb; 8] {
        let [x, y, z] = cell.at.map(|v| 2 * v);
        std::array::from_fn(|k| {
            let k = k as u32;
            self.cell_box(cell.depth + 1, x + (k & 1), y + (k >> 1 & 1), z + (k >> 2))
        })
    }

    /// The closed box of cell `(x, y, z)` at depth `d`: exact corners.
    #[must_use]
    pub fn cell_box(&self, d: u32, x: u32, y: u32, z: u32) -> Aabb {
        let s = self.side / f64::from(1u32 << d);
        let lo = self.origin + DVec3::new(f64::from(x), f64::from(y), f64::from(z)) * s;
        Aabb {
            min: lo,
            max: lo + DVec3::splat(s),
        }
    }

    /// The leaves.
    #[must_use]
    pub fn leaves(&self) -> &[Cell] {
        &self.leaves
    }

    /// Leaves per depth and label (index: depth).
    #[must_use]
    pub fn counts(&self) -> &[LevelCounts] {
        &self.counts
    }

    /// The depth of the finest cells.
    #[must_use]
    pub fn depth(&self) -> u32 {
        self.depth
    }

    /// The root cube: its smallest corner and its side.
    #[must_use]
    pub fn root(&self) -> (DVec3, f64) {
        (self.origin, self.side)
    }

    /// How many regions of `In` and `Out` leaves were labelled: the number
    /// of point classifications made.
    #[must_use]
    pub fn regions(&self) -> usize {
        self.regions
    }

    /// The certified volume interval `[V_in, V_in + V_on]`: finite, and
    /// holding the solid's exact volume.
    ///
    /// # Errors
    ///
    /// [`CellsError::VolumeOutOfRange`] when an end of the interval does
    /// not fit in `f64` as a normal number (a box of side 1e300 overflows,
    /// a ball of radius 1e-300 underflows): no interval is claimed then.
    pub fn try_volume_bounds(&self) -> Result<(f64, f64), CellsError> {
        // Sums in units of the finest cell (a cell at depth d is 8^(depth − d)
        // of them): integers, exact. Converted to f64 rounding down and up,
        // then scaled by the finest cell's volume, a power of two: exact
        // unless the product leaves the normal range, which is refused.
        let (mut inside, mut on) = (0u128, 0u128);
        for (d, c) in self.counts.iter().enumerate() {
            let units = 1u128 << (3 * (self.depth as usize - d));
            inside += u128::from(c.inside) * units;
            on += u128::from(c.on) * units;
        }
        // The root's side is a power of two (`root_cube`), and so is the
        // finest side.
        let finest_side = self.side / f64::from(1u32 << self.depth);
        let exponent = 3 * finest_side.log2().round() as i32;
        let refused = CellsError::VolumeOutOfRange {
            exponent,
            low_cells: inside,
            high_cells: inside + on,
        };
        // The steps of the product move monotonically from `cells` (an
        // integer) to the result, so a normal result was never rounded.
        let scaled = |cells: f64| {
            let v = times_power_of_two(cells, exponent);
            (cells == 0.0 || v.is_normal()).then_some(v)
        };
        match (scaled(round_down(inside)), scaled(round_up(inside + on))) {
            (Some(low), Some(high)) => Ok((low, high)),
            _ => Err(refused),
        }
    }

    /// The dense array of the finest cells, `n³` bytes for `n = 2^depth`,
    /// index `(x · n + y) · n + z`: 0 `Out`, 1 `On`, 2 `In`.
    ///
    /// # Errors
    ///
    /// [`CellsError::TooDeep`] beyond [`MAX_DENSE_DEPTH`].
    pub fn dense(&self) -> Result<Vec<u8>, CellsError> {
        if self.depth > MAX_DENSE_DEPTH {
            return Err(CellsError::TooDeep {
                depth: self.depth,
                limit: MAX_DENSE_DEPTH,
            });
        }
        let n = 1usize << self.depth;
        let mut out = vec![0u8; n * n * n];
        for c in &self.leaves {
            let value = match c.label {
                Label::Out => continue,
                Label::On => 1,
                Label::In => 2,
            };
            let k = (self.depth - c.depth) as usize;
            let span = 1usize << k;
            let (x0, y0, z0) = (
                c.x as usize * span,
                c.y as usize * span,
                c.z as usize * span,
            );
            for x in x0..x0 + span {
                for y in y0..y0 + span {
                    let row = (x * n + y) * n;
                    out[row + z0..row + z0 + span].fill(value);
                }
            }
        }
        Ok(out)
    }
}

/// `x · 2^k`, exact whenever the result is a normal number.
fn times_power_of_two(mut x: f64, mut k: i32) -> f64 {
    while k != 0 {
        let step = k.clamp(-1000, 1000);
        x *= 2f64.powi(step);
        k -= step;
    }
    x
}

/// `n` as an `f64` no larger than `n`.
fn round_down(n: u128) -> f64 {
    let x = n as f64;
    if x as u128 > n { x.next_down() } else { x }
}

/// `n` as an `f64` no smaller than `n`.
fn round_up(n: u128) -> f64 {
    let x = n as f64;
    if (x as u128) < n { x.next_up() } else { x }
}

/// The root cube: side a power of two holding the box, corner a multiple
/// of the finest side (so that every cell corner is exact).
fn root_cube(bounds: &Aabb, depth: u32) -> Result<(DVec3, f64), CellsError> {
    let extent = bounds.size().max_element();
    let out_of_range = || CellsError::OutOfRange { size: extent };
    if !(extent.is_finite() && bounds.min.is_finite()) {
        return Err(out_of_range());
    }
    let mut side = if extent > 0.0 {
        2f64.powi(extent.log2().ceil() as i32)
    } else {
        1.0
    };
    for _ in 0..64 {
        // The corner is aligned to half the root's side at least, so that
        // a box straddling a multiple of the side still fits at depth 0.
        let finest = side / f64::from(1u32 << depth.max(1));
        let origin = (bounds.min / finest).floor() * finest;
        if !(origin.is_finite() && finest > 0.0 && finest.is_normal()) {
            return Err(out_of_range());
        }
        if (origin + DVec3::splat(side)).cmpge(bounds.max).all() {
            // Corners exact: every coordinate a multiple of `finest` below
            // 2^53 of them.
            let cells = ((origin.abs() + DVec3::splat(side)) / finest).max_element();
            if cells >= 2f64.powi(53) {
                return Err(out_of_range());
            }
            return Ok((origin, side));
        }
        side *= 2.0;
    }
    Err(out_of_range())
}

#[cfg(test)]
#[path = "octree_tests.rs"]
mod tests;
