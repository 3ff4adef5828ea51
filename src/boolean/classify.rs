//! Stage 4: which pieces bound the result — membership classification.
//!
//! Pieces of one operand that share an edge not on an intersection segment
//! form a patch, and a patch lies wholly inside, outside or on the other
//! operand (its interior never meets the other's surface except where it is
//! coplanar with it). So one decision per patch suffices: a piece inside a
//! coplanar triangle of the other operand is *on* it (with the same or the
//! opposite orientation); otherwise the first patch corner off the other
//! surface is classified by an exact `+x` ray from it; a patch with no
//! such corner (every corner constructed or on the other surface) casts an
//! exact `+x` ray from a piece's centroid, an implicit point, against the
//! other operand's triangles.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use smallvec::SmallVec;

use glam::DVec3;

use crate::compressed_rows::compressed_rows;
use crate::disjoint_sets::DisjointSets;
use crate::geom::implicit::{
    Centroid, HasHomogeneous, ImplicitPoint, XRayCrossing, enclosing_box, orient2d_projected,
    x_ray_crossing,
};
use crate::geom::{Aabb, Sign};

use super::BooleanError;
use super::intersect::projection;
use super::nearby::Nearby;
use super::operand::Prepared;
use super::points::{PointTable, PointView};
use super::select::{Label, covered, keep};
use super::sparse::SparseExpression;

/// A piece of an operand's triangle.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Piece {
    /// Canonical point indices, wound like the triangle.
    pub corners: [u32; 3],
    /// The operand triangle it is part of.
    pub triangle: u32,
}

/// A coplanar triangle of another operand (by operand slot and triangle),
/// and whether it faces the same way.
pub(crate) type Partner = (usize, u32, bool);

/// What every piece of operand `mine` becomes in the result of
/// `expression`: `None` when it does not bound it, `Some(flip)` when it
/// does (turned over when `flip`). Pieces are grouped into patches across
/// unconstrained edges; each patch is labelled against the other operands
/// only as far as the expression asks ([`keep`]), and only against those
/// whose boxes meet it (`nearby`: the others are outside it).
#[allow(clippy::too_many_arguments)]
pub(crate) fn keep_pieces(
    table: &PointTable,
    operands: &[Prepared],
    nearby: &Nearby,
    mine: usize,
    pieces: &[Piece],
    constrained: &HashSet<(u32, u32)>,
    partners: &HashMap<u32, Vec<Partner>>,
    expression: &SparseExpression,
) -> Result<Vec<Option<bool>>, BooleanError> {
    let (start, by_root) = patch_rows(pieces, constrained);
    let mut decisions = vec![None; pieces.len()];
    for root in 0..pieces.len() {
        let members = &by_root[start[root]..start[root + 1]];
        if members.is_empty() {
            continue;
        }
        let patch = Patch {
            table,
            operands,
            nearby,
            mine,
            pieces,
            members,
            partners,
        };
        let decision = patch.decide(expression)?;
        for &m in members {
            decisions[m as usize] = decision;
        }
    }
    Ok(decisions)
}

/// The patches of `pieces` ([`patches_of`]) as compressed rows: row
/// `root` holds the pieces of the patch whose root is `root`, in piece
/// order; every other row is empty.
pub(super) fn patch_rows(
    pieces: &[Piece],
    constrained: &HashSet<(u32, u32)>,
) -> (Vec<usize>, Vec<u32>) {
    let mut sets = patches_of(pieces, constrained);
    let roots: Vec<usize> = (0..pieces.len()).map(|i| sets.find(i)).collect();
    compressed_rows(
        pieces.len(),
        roots.iter().enumerate().map(|(i, &r)| (r, i as u32)),
    )
}

/// The pieces joined across their edges that are not on a segment in
/// `constrained`, as disjoint sets. The uses of an edge are paired in the
/// order of the pieces (first with second, third with fourth: sheets that
/// touch along an edge), found by bucketing each edge by its smaller end,
/// not by hashing every edge. The buckets are over the pieces' own points
/// (numbered in the order of their canonical indices), so an operand costs
/// what its pieces hold, not the points of all operands.
pub(super) fn patches_of(pieces: &[Piece], constrained: &HashSet<(u32, u32)>) -> DisjointSets {
    let mut points: Vec<u32> = pieces.iter().flat_map(|p| p.corners).collect();
    points.sort_unstable();
    points.dedup();
    let local = |c: u32| points.binary_search(&c).unwrap_or_default();
    // (other end, piece) by smaller end, each bucket in piece order.
    let (start, mut uses) = compressed_rows(
        points.len(),
        pieces.iter().enumerate().flat_map(|(i, piece)| {
            (0..3).map(move |k| {
                let (u, v) = (piece.corners[k], piece.corners[(k + 1) % 3]);
                (local(u.min(v)), (u.max(v), i as u32))
            })
        }),
    );
    let mut sets = DisjointSets::new(pieces.len());
    for (lo_local, &lo) in points.iter().enumerate() {
        let bucket = &mut uses[start[lo_local]..start[lo_local + 1]];
        // Stable: the uses of one edge stay in piece order.
        bucket.sort_by_key(|&(hi, _)| hi);
        for run in bucket.chunk_by(|a, b| a.0 == b.0) {
            if constrained.contains(&(lo, run[0].0)) {
                continue;
            }
            for pair in run.chunks_exact(2) {
                sets.union(pair[0].1 as usize, pair[1].1 as usize);
            }
        }
    }
    sets
}

/// One patch of an operand's pieces, with what labelling it needs.
struct Patch<'p> {
    table: &'p PointTable,
    operands: &'p [Prepared<'p>],
    nearby: &'p Nearby,
    /// The slot of the patch's operand in `operands`.
    mine: usize,
    pieces: &'p [Piece],
    members: &'p [u32],
    partners: &'p HashMap<u32, Vec<Partner>>,
}

impl Patch<'_> {
    /// The patch's fate in the result (see [`keep_pieces`]).
    fn decide(&self, expression: &SparseExpression) -> Result<Option<bool>, BooleanError> {
        let mine = self.mine;
        // The operands on whose surface a piece lies (coplanar partners).
        let mut coplanar: SmallVec<[usize; 4]> = self
            .members
            .iter()
            .filter_map(|&m| self.partners.get(&self.pieces[m as usize].triangle))
            .flatten()
            .map(|&(k, _, _)| k)
            .collect();
        coplanar.sort_unstable();
        coplanar.dedup();
        // The few operands that may not be outside the patch: its own, the
        // coplanar ones, and those whose boxes meet its first piece's box
        // (for any other, `label` would answer `Outside` from the boxes).
        let mut few: SmallVec<[usize; 8]> = SmallVec::new();
        few.push(mine);
        few.extend(coplanar.iter().copied());
        self.nearby
            .overlapping(&self.first_piece_box(), |k| few.push(k));
        few.sort_unstable();
        few.dedup();
        let mut known: SmallVec<[Option<Label>; 8]> = smallvec::smallvec![None; few.len()];
        let mut label = |k: usize| -> Result<Label, BooleanError> {
            let Ok(at) = few.binary_search(&k) else {
                return Ok(Label::Outside);
            };
            if let Some(l) = known[at] {
                return Ok(l);
            }
            let l = self.label(k, &self.operands[k])?;
            known[at] = Some(l);
            Ok(l)
        };
        // On the surface of an operand that comes first: its patch stands
        // for this one.
        for &k in coplanar.iter().filter(|&&k| k < mine) {
            if covered(mine, k, label(k)?) {
                return Ok(None);
            }
        }
        keep(expression, &few, mine, &mut label)
    }

    /// The box of the patch's first piece (its corners' enclosing boxes).
    fn first_piece_box(&self) -> Aabb {
        let first = self.pieces[self.members[0] as usize];
        let mut piece_box = Aabb::EMPTY;
        for c in first.corners {
            piece_box = piece_box.union(enclosing_box(&self.table.get(c)));
        }
        piece_box
    }

    /// Where the patch lies against operand `k` (`other`).
    fn label(&self, k: usize, other: &Prepared) -> Result<Label, BooleanError> {
        let (table, pieces, members) = (self.table, self.pieces, self.members);
        // On the other surface?
        let on_partner = |m: &u32| {
            self.partners
                .get(&pieces[*m as usize].triangle)
                .is_some_and(|list| list.iter().any(|&(o, _, _)| o == k))
        };
        if let Some(&m) = members.iter().find(|m| on_partner(m)) {
            let piece = pieces[m as usize];
            let centroid = Centroid(piece.corners.map(|c| table.get(c)));
            for &(o, t, same) in &self.partners[&piece.triangle] {
                if o == k && strictly_inside(&centroid, other.corners(t)) {
                    return Ok(if same {
                        Label::OnSame
                    } else {
                        Label::OnOpposite
                    });
                }
            }
        }
        // Off the other operand's box: outside (the patch does not cross
        // its surface, so one piece's box decides).
        let first = pieces[members[0] as usize];
        if self
            .first_piece_box()
            .intersection(other.bvh.bounds())
            .is_empty()
        {
            return Ok(Label::Outside);
        }
        // A corner off the other surface.
        for &m in members {
            for c in pieces[m as usize].corners {
                let Some(p) = table.explicit(c) else {
                    continue;
                };
                match ray_parity(&ImplicitPoint::Explicit(p), other) {
                    Some(true) => return Ok(Label::Inside),
                    Some(false) => return Ok(Label::Outside),
                    None => {}
                }
            }
        }
        // A ray from an implicit centroid.
        let centroid = Centroid(first.corners.map(|c| table.get(c)));
        match ray_parity(&centroid, other) {
            Some(true) => Ok(Label::Inside),
            Some(false) => Ok(Label::Outside),
            None => Err(BooleanError::Inconsistent(format!(
                "a piece of operand {} has its centroid on the surface of operand {}",
                self.operands[self.mine].index, other.index
            ))),
        }
    }
}

/// Whether `p` (in the plane of `tri`) is strictly inside `tri`.
fn strictly_inside(p: &Centroid<PointView>, tri: [DVec3; 3]) -> bool {
    let (axis, facing) = projection(&tri);
    if facing == Sign::Zero {
        return false;
    }
    let corners = tri.map(ImplicitPoint::Explicit);
    (0..3).all(|k| orient2d_projected(&corners[k], &corners[(k + 1) % 3], p, axis) == facing)
}

/// The parity of the `+x` ray from `p` through `other`'s triangles
/// (`true`: inside), or `None` when `p` lies on one.
fn ray_parity(p: &impl HasHomogeneous, other: &Prepared) -> Option<bool> {
    let mut query = enclosing_box(p);
    query.max.x = other.bvh.bounds().max.x.max(query.max.x);
    let mut crossings = 0usize;
    let mut on_surface = false;
    other.triangles_overlapping(&query, |t| match x_ray_crossing(p, other.corners(t)) {
        XRayCrossing::Crosses => crossings += 1,
        XRayCrossing::Contains => on_surface = true,
        XRayCrossing::Misses => {}
    });
    (!on_surface).then_some(crossings % 2 == 1)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn patches_pair_an_edge_s_uses_in_piece_order_and_stop_at_segments() {
        let piece = |corners: [u32; 3]| Piece {
            corners,
            triangle: 0,
        };
        // Four pieces on edge 0–1 (two sheets touching along it), and a
        // fifth joined to the first across edge 1–2.
        let pieces = [
            piece([0, 1, 2]),
            piece([1, 0, 3]),
            piece([0, 1, 4]),
            piece([1, 0, 5]),
            piece([2, 1, 6]),
        ];
        let mut sets = patches_of(&pieces, &HashSet::default());
        let root: Vec<usize> = (0..5).map(|i| sets.find(i)).collect();
        assert_eq!(root[0], root[1]);
        assert_eq!(root[2], root[3]);
        assert_ne!(root[0], root[2]);
        assert_eq!(root[0], root[4]);
        // Edge 0–1 on a segment: only the join across 1–2 is left.
        let constrained: HashSet<(u32, u32)> = [(0, 1)].into_iter().collect();
        let mut sets = patches_of(&pieces, &constrained);
        let root: Vec<usize> = (0..5).map(|i| sets.find(i)).collect();
        assert_eq!(root[0], root[4]);
        for (i, j) in [(0, 1), (1, 2), (2, 3), (0, 2)] {
            assert_ne!(root[i], root[j], "{i} {j}");
        }
    }
}
