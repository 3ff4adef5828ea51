//! Stage 3: each triangle cut along its intersection segments — a
//! constrained triangulation of its corners and the points found on it, in
//! the projection that keeps the triangle non-degenerate, with every sign
//! decided exactly on the (implicit) points.
//!
//! Points are inserted one by one (a point inside a triangle splits it in
//! three, a point on an edge splits the two triangles of that edge); each
//! segment is then recovered by flipping the edges that cross it (Sloan's
//! procedure; the segments of one boolean never cross each other, they
//! meet only at their ends). Sub-triangles keep the triangle's winding.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use crate::geom::implicit::{
    HasHomogeneous, compare_axis, enclosing_box, kept_axes, orient2d_projected, times,
};
use crate::geom::{Aabb, Sign};

use super::points::PointTable;

/// Why a triangle could not be cut: an inconsistency that exact predicates
/// should make impossible, reported rather than hidden.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct SplitError(pub String);

/// A triangle cut into pieces.
#[derive(Clone, Debug, Default)]
pub(crate) struct Split {
    /// The pieces, as canonical point indices, wound like the triangle.
    pub triangles: Vec<[u32; 3]>,
    /// The pieces' edges that lie on a segment (unordered pairs, smaller
    /// index first).
    pub constrained: Vec<(u32, u32)>,
}

/// # Invariants
///
/// `edges` maps every directed edge `(t[k], t[k + 1])` of every triangle
/// `t` to that triangle's index, and nothing else; `vertices` holds every
/// corner once.
struct Triangulation<'t> {
    table: &'t PointTable,
    axis: u8,
    facing: Sign,
    vertices: Vec<u32>,
    present: HashSet<u32>,
    /// A box surely holding each vertex: pairs whose boxes are apart need
    /// no exact test.
    boxes: HashMap<u32, Aabb>,
    triangles: Vec<[u32; 3]>,
    edges: HashMap<(u32, u32), usize>,
    constrained: HashSet<(u32, u32)>,
    /// Where the last change happened: the walk to the next point starts
    /// there.
    last: usize,
    /// The state of the walk's coin (a fixed-seed xorshift: the walk is
    /// deterministic).
    coin: u64,
}

/// Cuts the triangle with canonical corners `corners` (a non-degenerate
/// triangle, `axis` a projection that keeps it so) at `points` and along
/// `segments` (canonical indices).
pub(crate) fn split_triangle(
    table: &PointTable,
    corners: [u32; 3],
    axis: u8,
    points: &[u32],
    segments: &[(u32, u32)],
) -> Result<Split, SplitError> {
    let mut t = Triangulation {
        table,
        axis,
        facing: Sign::Positive,
        vertices: corners.to_vec(),
        present: corners.iter().copied().collect(),
        boxes: corners
            .iter()
            .chain(points)
            .map(|&p| (p, enclosing_box(&table.get(p))))
            .collect(),
        triangles: Vec::new(),
        edges: HashMap::default(),
        constrained: HashSet::default(),
        last: 0,
        coin: 0x9E37_79B9_7F4A_7C15,
    };
    t.push(corners);
    t.facing = t.orient(corners[0], corners[1], corners[2]);
    if t.facing == Sign::Zero {
        return Err(SplitError(format!("triangle {corners:?} has zero area")));
    }
    // Nearby points one after another, so each walk is short.
    let (u, v) = kept_axes(axis);
    let mut order: Vec<(f64, f64, u32)> = points
        .iter()
        .map(|&p| {
            let h = table.get(p).filter();
            let w = h.w.mid();
            (h.xyz[u].mid() / w, h.xyz[v].mid() / w, p)
        })
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    for (_, _, p) in order {
        if !t.present.contains(&p) {
            t.insert_point(p)?;
        }
    }
    for &(u, v) in segments {
        t.insert_segment(u, v, 0)?;
    }
    let mut constrained: Vec<(u32, u32)> = t.constrained.into_iter().collect();
    constrained.sort_unstable();
    Ok(Split {
        triangles: t.triangles,
        constrained,
    })
}

fn key(u: u32, v: u32) -> (u32, u32) {
    (u.min(v), u.max(v))
}

impl Triangulation<'_> {
    /// Orientation in the projection, positive for the triangle's own
    /// winding.
    fn orient(&self, a: u32, b: u32, c: u32) -> Sign {
        let t = self.table;
        if t.collinear_by_construction(a, b, c) {
            return Sign::Zero;
        }
        let s = orient2d_projected(&t.get(a), &t.get(b), &t.get(c), self.axis);
        times(s, self.facing)
    }

    /// A box surely holding vertex `p` (every vertex has one).
    fn box_of(&self, p: u32) -> Aabb {
        self.boxes.get(&p).copied().unwrap_or(Aabb {
            min: glam::DVec3::NEG_INFINITY,
            max: glam::DVec3::INFINITY,
        })
    }

    /// Replaces triangle `ti` by `tri`, keeping the edge map.
    fn set(&mut self, ti: usize, tri: [u32; 3]) {
        let old = self.triangles[ti];
        for k in 0..3 {
            let edge = (old[k], old[(k + 1) % 3]);
            // Another triangle may have taken the edge over already.
            if self.edges.get(&edge) == Some(&ti) {
                self.edges.remove(&edge);
            }
        }
        self.triangles[ti] = tri;
        for k in 0..3 {
            self.edges.insert((tri[k], tri[(k + 1) % 3]), ti);
        }
        self.last = ti;
    }

    /// Adds triangle `tri`.
    fn push(&mut self, tri: [u32; 3]) {
        self.triangles.push(tri);
        let ti = self.triangles.len() - 1;
        for k in 0..3 {
            self.edges.insert((tri[k], tri[(k + 1) % 3]), ti);
        }
    }

    /// The triangle holding `p` (on its boundary included): a walk from
    /// the last change towards `p`, crossing an edge that has `p` strictly
    /// on its far side (chosen by a coin among two, so the walk cannot
    /// cycle), and a scan of all triangles if the walk leaves the
    /// triangle or runs long.
    fn locate(&mut self, p: u32) -> Option<(usize, [Sign; 3])> {
        let mut ti = self.last.min(self.triangles.len() - 1);
        for _ in 0..4 * self.triangles.len() + 16 {
            let [a, b, c] = self.triangles[ti];
            let s = [
                self.orient(b, c, p),
                self.orient(c, a, p),
                self.orient(a, b, p),
            ];
            let away: smallvec::SmallVec<[usize; 3]> =
                (0..3).filter(|&k| s[k] == Sign::Negative).collect();
            if away.is_empty() {
                return Some((ti, s));
            }
            self.coin ^= self.coin << 13;
            self.coin ^= self.coin >> 7;
            self.coin ^= self.coin << 17;
            let k = away[(self.coin % away.len() as u64) as usize];
            let t = self.triangles[ti];
            // The edge opposite corner k, crossed to the other side.
            let (x, y) = (t[(k + 1) % 3], t[(k + 2) % 3]);
            match self.across(y, x) {
                Some((next, _)) => ti = next,
                None => break,
            }
        }
        (0..self.triangles.len()).find_map(|ti| {
            let [a, b, c] = self.triangles[ti];
            let s = [
                self.orient(b, c, p),
                self.orient(c, a, p),
                self.orient(a, b, p),
            ];
            (!s.contains(&Sign::Negative)).then_some((ti, s))
        })
    }

    fn insert_point(&mut self, p: u32) -> Result<(), SplitError> {
        let Some((ti, s)) = self.locate(p) else {
            return Err(SplitError(format!(
                "point {p} lies outside the triangle it cuts"
            )));
        };
        let [a, b, c] = self.triangles[ti];
        let zeros: smallvec::SmallVec<[usize; 3]> =
            (0..3).filter(|&k| s[k] == Sign::Zero).collect();
        match zeros[..] {
            [] => {
                self.set(ti, [a, b, p]);
                self.push([b, c, p]);
                self.push([c, a, p]);
            }
            [k] => {
                // On the edge opposite corner k.
                let t = self.triangles[ti];
                let (o, x, y) = (t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
                let neighbour = self.across(y, x);
                self.set(ti, [o, x, p]);
                self.push([o, p, y]);
                if let Some((tj, m)) = neighbour {
                    self.set(tj, [m, y, p]);
                    self.push([m, p, x]);
                }
                if self.constrained.remove(&key(x, y)) {
                    self.constrained.insert(key(x, p));
                    self.constrained.insert(key(p, y));
                }
            }
            _ => {
                return Err(SplitError(format!(
                    "point {p} coincides with a corner of a piece but has its own index"
                )));
            }
        }
        self.vertices.push(p);
        self.present.insert(p);
        Ok(())
    }

    /// The triangle holding the directed edge `from → to`, and its third
    /// corner.
    fn across(&self, from: u32, to: u32) -> Option<(usize, u32)> {
        let &ti = self.edges.get(&(from, to))?;
        let t = self.triangles[ti];
        (0..3).find_map(|k| (t[k] == from).then_some((ti, t[(k + 2) % 3])))
    }

    fn has_edge(&self, u: u32, v: u32) -> bool {
        self.across(u, v).is_some() || self.across(v, u).is_some()
    }

    /// Whether `w`, on the line of `u v`, lies strictly between them.
    fn strictly_between(&self, u: u32, v: u32, w: u32) -> bool {
        let t = self.table;
        let (a, b) = kept_axes(self.axis);
        [a, b].iter().any(|&axis| {
            let (lo, hi) = match compare_axis(&t.get(u), &t.get(v), axis) {
                std::cmp::Ordering::Less => (u, v),
                std::cmp::Ordering::Greater => (v, u),
                std::cmp::Ordering::Equal => return false,
            };
            compare_axis(&t.get(lo), &t.get(w), axis).is_lt()
                && compare_axis(&t.get(w), &t.get(hi), axis).is_lt()
        })
    }

    fn crosses(&self, u: u32, v: u32, x: u32, y: u32) -> bool {
        let proper = |p: Sign, q: Sign| p != Sign::Zero && q != Sign::Zero && p != q;
        proper(self.orient(u, v, x), self.orient(u, v, y))
            && proper(self.orient(x, y, u), self.orient(x, y, v))
    }

    fn insert_segment(&mut self, u: u32, v: u32, depth: usize) -> Result<(), SplitError> {
        if u == v {
            return Ok(());
        }
        if depth > self.vertices.len() {
            return Err(SplitError(format!(
                "segment {u}–{v} could not be recovered"
            )));
        }
        if self.has_edge(u, v) {
            self.constrained.insert(key(u, v));
            return Ok(());
        }
        let reach = self.box_of(u).union(self.box_of(v));
        let on_segment = self.vertices.iter().copied().find(|&w| {
            w != u
                && w != v
                && !self.box_of(w).intersection(reach).is_empty()
                && self.orient(u, v, w) == Sign::Zero
                && self.strictly_between(u, v, w)
        });
        if let Some(w) = on_segment {
            self.insert_segment(u, w, depth + 1)?;
            return self.insert_segment(w, v, depth + 1);
        }
        // Sloan's queue: every edge crossing the segment; a crossing edge
        // whose quadrilateral is convex is flipped, the others wait, and a
        // new diagonal that still crosses queues again.
        let mut queue: std::collections::VecDeque<(u32, u32)> = std::collections::VecDeque::new();
        for t in &self.triangles {
            for k in 0..3 {
                let (x, y) = (t[k], t[(k + 1) % 3]);
                if x < y
                    && !self
                        .box_of(x)
                        .union(self.box_of(y))
                        .intersection(reach)
                        .is_empty()
                    && self.crosses(u, v, x, y)
                {
                    queue.push_back((x, y));
                }
            }
        }
        let mut budget = 64 + 16 * queue.len() * queue.len();
        while let Some((x, y)) = queue.pop_front() {
            if budget == 0 {
                break;
            }
            budget -= 1;
            if self.constrained.contains(&key(x, y)) {
                return Err(SplitError(format!(
                    "segment {u}–{v} crosses segment {x}–{y}"
                )));
            }
            let (Some((ti, a)), Some((tj, b))) = (self.across(x, y), self.across(y, x)) else {
                return Err(SplitError(format!("segment {u}–{v} leaves the triangle")));
            };
            // The quadrilateral x, b, y, a is convex when a b crosses x y;
            // then the diagonal can be flipped.
            if self.crosses(a, b, x, y) {
                self.set(ti, [x, b, a]);
                self.set(tj, [b, y, a]);
                if self.crosses(u, v, a, b) {
                    queue.push_back((a, b));
                }
            } else {
                queue.push_back((x, y));
            }
        }
        if self.has_edge(u, v) {
            self.constrained.insert(key(u, v));
            return Ok(());
        }
        Err(SplitError(format!(
            "segment {u}–{v} could not be recovered"
        )))
    }
}
