//! The outer faces of the `In` cells as a valid closed solid whose volume
//! lies in the certified interval `[V_in, V_in + V_on]`.
//!
//! # The surface
//!
//! Every face between an `In` cell and a cell that is not `In` is a face
//! of an `On` cell at the finest depth (an `In` cell never touches an
//! `Out` cell: the boundary would meet both), so the surface is made of
//! finest-cell squares. Coplanar squares are not merged: one quad per
//! finest face.
//!
//! # Contacts along an edge or at a corner
//!
//! Two `In` cells that share only an edge (the other two cells around it
//! not `In`), or only a corner, would make a non-manifold edge or vertex;
//! and so would two cells that are not `In` touching only along an edge or
//! at a corner of the `In` set. These are exactly the critical
//! configurations of digital topology: a set of cubes without them is
//! *well-composed*, and its boundary is a 2-manifold (Latecki 1997). They
//! are removed on a grid of sub-cells, [`SUBDIVISION`] to a cell side:
//!
//! 1. Each critical configuration is resolved by filling sub-cells next to
//!    it: one of the two empty sub-cells of an edge's diagonal pair, the
//!    two sub-cells that join two opposite corners by faces, or one of two
//!    opposite empty corners. Every fill is checked again around the
//!    filled sub-cell until no critical configuration is left (fills only
//!    add, so this ends).
//! 2. The filled sub-cells stay: every cell around a contact that is not
//!    `In` is `On` (an `In` cell and an `Out` cell never share even a
//!    corner, since the boundary would pass through it), so what is added
//!    lies in `On` cells and the solid's volume, `V_in` plus the filled
//!    sub-cells, stays within `[V_in, V_in + V_on]`. The solid has no
//!    hidden parts: its shells are those of the `In` set (keeping `V_in`
//!    exactly would mean carving the added volume out again as internal
//!    cavities, extra shells no reader of the OBJ expects).
//!
//! All corners are multiples of the sub-cell side from the root corner:
//! exact `f64`, so the solid's volume is [`InShell::volume`] exactly where
//! the sums of its divergence-theorem terms are exact, and to rounding
//! otherwise.
//! Faces made of sub-cells meet whole squares along their edges: the whole
//! squares get the sub-cell corners that lie on their edges as extra
//! (collinear) vertices, so every edge has exactly two faces.

use std::collections::{HashMap, HashSet};

use glam::DVec3;

use super::label::Label;
use super::octree::{CellsError, Octree};
use crate::mesh::{Polygon, PolygonSoup};

/// Sub-cells along a cell side in the repair grid.
pub const SUBDIVISION: i64 = 4;

/// The largest number of sub-cells a repair may fill per `On` cell before
/// it is refused (fills stay next to contacts; this bounds a runaway).
const MAX_FILLS_PER_ON_CELL: usize = 64;

/// A point of the sub-cell lattice (sub-cell `v` spans `[v, v + 1]`).
type Lattice = [i64; 3];

/// The `In` cells' outer faces and what the repair did.
#[derive(Clone, Debug)]
pub struct InShell {
    /// The faces: quads (with extra collinear corners where sub-cell faces
    /// meet them) oriented outward.
    pub soup: PolygonSoup,
    /// Sub-cells filled to remove contacts along edges and at corners.
    pub filled: usize,
    /// The volume the faces bound: `V_in` plus the filled sub-cells (each
    /// `1 / SUBDIVISION³` of a finest cell), within `[V_in, V_in + V_on]`.
    pub volume: f64,
}

/// The labels of the finest cells and the sub-cells the repair changed.
struct SubGrid<'a> {
    tree: &'a Octree,
    index: HashMap<(u32, u32, u32, u32), Label>,
    filled: HashSet<Lattice>,
    /// Finest cells that hold filled sub-cells.
    touched: HashSet<Lattice>,
}

impl SubGrid<'_> {
    /// The label of the finest cell `c` (`Out` beyond the root).
    fn label(&self, c: Lattice) -> Label {
        let n = 1i64 << self.tree.depth();
        if c.iter().any(|&v| v < 0 || v >= n) {
            return Label::Out;
        }
        let mut at = c.map(|v| v as u32);
        for d in (0..=self.tree.depth()).rev() {
            if let Some(&label) = self.index.get(&(d, at[0], at[1], at[2])) {
                return label;
            }
            at = at.map(|v| v / 2);
        }
        Label::Out
    }

    fn cell_of(v: Lattice) -> Lattice {
        v.map(|k| k.div_euclid(SUBDIVISION))
    }

    /// Whether sub-cell `v` is in the solid.
    fn full(&self, v: Lattice) -> bool {
        if self.filled.contains(&v) {
            return true;
        }
        self.label(Self::cell_of(v)) == Label::In
    }

    /// The eight sub-cells around lattice point `p`, octant `o` (bit `k`
    /// set: the side of larger coordinate `k`).
    fn octants(&self, p: Lattice) -> [bool; 8] {
        std::array::from_fn(|o| self.full(octant(p, o)))
    }

    /// The sub-cells to fill that remove a critical configuration at `p`,
    /// if there is one.
    fn repair_at(&self, p: Lattice) -> Option<Vec<Lattice>> {
        let fill = critical(self.octants(p))?;
        Some(fill.into_iter().map(|o| octant(p, o)).collect())
    }
}

/// The octants to fill that remove a critical configuration among the
/// eight cubes around a point (`full[o]`, octant `o` as in [`octant`]), if
/// there is one: a diagonal pair around one of the six edges from the
/// point, or two opposite corners alone (full or empty).
fn critical(full: [bool; 8]) -> Option<Vec<usize>> {
    // An edge from the point along ±axis: its four cubes.
    for axis in 0..3 {
        for side in 0..2 {
            let (b, c) = ((axis + 1) % 3, (axis + 2) % 3);
            let o = |i: usize, j: usize| (side << axis) | (i << b) | (j << c);
            let (o00, o01, o10, o11) = (o(0, 0), o(0, 1), o(1, 0), o(1, 1));
            if full[o00] == full[o11] && full[o01] == full[o10] && full[o00] != full[o01] {
                let empty = if full[o00] { o01 } else { o00 };
                return Some(vec![empty]);
            }
        }
    }
    let count = full.iter().filter(|&&f| f).count();
    for o in 0..8 {
        let opposite = 7 - o;
        if count == 2 && full[o] && full[opposite] {
            // Join them by faces: o → o^1 → o^3 → opposite.
            return Some(vec![o ^ 1, o ^ 3]);
        }
        if count == 6 && !full[o] && !full[opposite] {
            return Some(vec![o]);
        }
    }
    None
}

/// The sub-cell in octant `o` of lattice point `p`.
fn octant(p: Lattice, o: usize) -> Lattice {
    std::array::from_fn(|k| p[k] - 1 + ((o >> k) & 1) as i64)
}

/// The eight corners of finest cell `c`, in lattice units.
fn corners(c: Lattice) -> impl Iterator<Item = Lattice> {
    (0..8).map(move |o| std::array::from_fn(|k| (c[k] + ((o >> k) & 1) as i64) * SUBDIVISION))
}

impl Octree {
    /// The outer faces of the `In` cells as a closed, oriented, manifold
    /// surface whose volume lies in `[V_in, V_in + V_on]` (see the module
    /// documentation of `in_shell` for how contacts along edges and at
    /// corners are removed).
    ///
    /// # Errors
    ///
    /// [`CellsError::Repair`] if removing the contacts would fill more than
    /// a bounded number of sub-cells; [`CellsError::VolumeOutOfRange`] as
    /// [`Octree::try_volume_bounds`].
    pub fn in_shell(&self) -> Result<InShell, CellsError> {
        let mut grid = SubGrid {
            tree: self,
            index: self
                .leaves()
                .iter()
                .map(|c| ((c.depth, c.x, c.y, c.z), c.label))
                .collect(),
            filled: HashSet::new(),
            touched: HashSet::new(),
        };
        let finest = self.depth();
        let on: Vec<Lattice> = self
            .leaves()
            .iter()
            .filter(|c| c.label == Label::On && c.depth == finest)
            .map(|c| [i64::from(c.x), i64::from(c.y), i64::from(c.z)])
            .collect();
        self.fill_contacts(&mut grid, &on)?;
        let soup = self.faces(&grid, &on);
        let (_, side) = self.root();
        let finest_side = side / f64::from(1u32 << finest.min(31));
        let sub_cell = (finest_side / SUBDIVISION as f64).powi(3);
        Ok(InShell {
            soup,
            filled: grid.filled.len(),
            volume: self.try_volume_bounds()?.0 + grid.filled.len() as f64 * sub_cell,
        })
    }

    /// Fills sub-cells until no critical configuration is left.
    fn fill_contacts(&self, grid: &mut SubGrid<'_>, on: &[Lattice]) -> Result<(), CellsError> {
        // Before any fill, critical configurations can only sit on the
        // edges of finest cells, and one sits on an edge's inner lattice
        // points exactly when it sits on the edge: check the corners of
        // `On` cells at the cell level, then the edges found at sub-cell
        // level.
        let mut work: Vec<Lattice> = Vec::new();
        let mut seen: HashSet<Lattice> = HashSet::new();
        for &c in on {
            for p in corners(c) {
                let at_cells: [bool; 8] = std::array::from_fn(|o| {
                    grid.label(octant(p.map(|v| v / SUBDIVISION), o)) == Label::In
                });
                if critical(at_cells).is_some() && seen.insert(p) {
                    work.push(p);
                    for axis in 0..3 {
                        for step in 1..SUBDIVISION {
                            for sign in [-1, 1] {
                                let mut q = p;
                                q[axis] += sign * step;
                                work.push(q);
                            }
                        }
                    }
                }
            }
        }
        let limit = MAX_FILLS_PER_ON_CELL * on.len().max(1);
        while let Some(p) = work.pop() {
            let Some(fill) = grid.repair_at(p) else {
                continue;
            };
            for v in fill {
                grid.filled.insert(v);
                grid.touched.insert(SubGrid::cell_of(v));
                work.extend((0..8).map(|o| std::array::from_fn(|k| v[k] + ((o >> k) & 1) as i64)));
            }
            if grid.filled.len() > limit {
                return Err(CellsError::Repair {
                    message: format!("more than {limit} sub-cells needed to remove contacts"),
                });
            }
            // Check p again: it may hold a second configuration.
            work.push(p);
        }
        Ok(())
    }

    /// The faces between full and empty sub-cells, whole squares where a
    /// finest face is uniform.
    fn faces(&self, grid: &SubGrid<'_>, on: &[Lattice]) -> PolygonSoup {
        let mut scan: Vec<Lattice> = on.to_vec();
        scan.extend(grid.touched.iter().copied());
        scan.sort_unstable();
        scan.dedup();
        let scanned: HashSet<Lattice> = scan.iter().copied().collect();
        let mut quads: Vec<[Lattice; 4]> = Vec::new();
        let s = SUBDIVISION;
        for &c in &scan {
            let uniform = !grid.touched.contains(&c);
            // Faces with the six neighbours, each once.
            for axis in 0..3 {
                for sign in [-1i64, 1] {
                    let mut n = c;
                    n[axis] += sign;
                    if scanned.contains(&n) && n < c {
                        continue;
                    }
                    // The face plane, in lattice units.
                    let plane = (c[axis] + i64::from(sign > 0)) * s;
                    let (b, d) = ((axis + 1) % 3, (axis + 2) % 3);
                    if uniform && !grid.touched.contains(&n) {
                        let (fc, fn_) = (grid.label(c) == Label::In, grid.label(n) == Label::In);
                        if fc != fn_ {
                            let low_full = if sign > 0 { fc } else { fn_ };
                            quads.push(square(axis, plane, c[b] * s, c[d] * s, s, low_full));
                        }
                        continue;
                    }
                    let mut subs = Vec::new();
                    for i in 0..s {
                        for j in 0..s {
                            let mut low: Lattice = [0; 3];
                            low[axis] = plane - 1;
                            low[b] = c[b] * s + i;
                            low[d] = c[d] * s + j;
                            let mut high = low;
                            high[axis] = plane;
                            let (fl, fh) = (grid.full(low), grid.full(high));
                            if fl != fh {
                                subs.push(square(axis, plane, low[b], low[d], 1, fl));
                            }
                        }
                    }
                    quads.extend(subs);
                }
            }
            if !uniform {
                // Faces between the cell's own sub-cells.
                for axis in 0..3 {
                    let (b, d) = ((axis + 1) % 3, (axis + 2) % 3);
                    for k in 1..s {
                        let plane = c[axis] * s + k;
                        for i in 0..s {
                            for j in 0..s {
                                let mut low: Lattice = [0; 3];
                                low[axis] = plane - 1;
                                low[b] = c[b] * s + i;
                                low[d] = c[d] * s + j;
                                let mut high = low;
                                high[axis] = plane;
                                let (fl, fh) = (grid.full(low), grid.full(high));
                                if fl != fh {
                                    quads.push(square(axis, plane, low[b], low[d], 1, fl));
                                }
                            }
                        }
                    }
                }
            }
        }
        self.soup_of(&quads)
    }

    /// Numbers the lattice points, adds the collinear corners where sub-cell
    /// faces meet a whole square's edge, and places the points.
    fn soup_of(&self, quads: &[[Lattice; 4]]) -> PolygonSoup {
        let mut index: HashMap<Lattice, usize> = HashMap::new();
        let mut lattice: Vec<Lattice> = Vec::new();
        for q in quads {
            for &p in q {
                index.entry(p).or_insert_with(|| {
                    lattice.push(p);
                    lattice.len() - 1
                });
            }
        }
        let polygons: Vec<Polygon> = quads
            .iter()
            .map(|q| {
                let mut ring = Vec::with_capacity(4);
                for k in 0..4 {
                    let (a, b) = (q[k], q[(k + 1) % 4]);
                    ring.push(index[&a]);
                    let steps = (0..3).map(|i| (b[i] - a[i]).abs()).sum::<i64>();
                    for t in 1..steps {
                        let p: Lattice = std::array::from_fn(|i| a[i] + (b[i] - a[i]).signum() * t);
                        if let Some(&v) = index.get(&p) {
                            ring.push(v);
                        }
                    }
                }
                Polygon::new(ring)
            })
            .collect();
        let (origin, side) = self.root();
        let step = side / f64::from(1u32 << self.depth()) / SUBDIVISION as f64;
        let positions = lattice
            .iter()
            .map(|p| origin + DVec3::new(p[0] as f64, p[1] as f64, p[2] as f64) * step)
            .collect();
        PolygonSoup {
            positions,
            polygons,
        }
    }
}

/// The square of side `len` in the plane `x_axis = plane` with smallest
/// corner `(u, v)` in the two other axes (in cyclic order), counter-
/// clockwise seen from the empty side: from `+axis` when the full side is
/// the lower one.
fn square(axis: usize, plane: i64, u: i64, v: i64, len: i64, low_full: bool) -> [Lattice; 4] {
    let (b, d) = ((axis + 1) % 3, (axis + 2) % 3);
    let at = |du: i64, dv: i64| {
        let mut p = [0; 3];
        p[axis] = plane;
        p[b] = u + du;
        p[d] = v + dv;
        p
    };
    let ring = [at(0, 0), at(len, 0), at(len, len), at(0, len)];
    if low_full {
        ring
    } else {
        [ring[0], ring[3], ring[2], ring[1]]
    }
}
