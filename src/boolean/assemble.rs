//! Stage 7: the kept pieces made into a soup of `f64` triangles — implicit
//! points rounded to the nearest `f64` only now, after every decision was
//! made on their exact definitions — with the collapses the output stage
//! asked for applied.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use glam::DVec3;

use crate::compressed_rows::compressed_rows;
use crate::geom::implicit::rounded_point;
use crate::geom::triangulate_3d;
use rayon::prelude::*;
use smallvec::SmallVec;

use crate::mesh::{FaceId, Polygon, PolygonSoup};

use super::merge::PieceSource;
use super::operand::{FaceOrigin, Prepared};
use super::points::PointTable;

/// A piece that bounds the result, wound as it faces out of the result.
#[derive(Clone, Copy, Debug)]
pub(crate) struct KeptPiece {
    pub corners: [u32; 3],
    /// The operand's slot in the operands' list.
    pub operand: usize,
    pub face: FaceId,
    /// The operand triangle the piece lies in, wound as the piece.
    pub plane: [DVec3; 3],
    /// Whether the piece is less than its whole operand triangle (cut, or
    /// with points of another operand on it).
    pub changed: bool,
    /// Whether the piece is the only one of its operand face: the face is
    /// one triangle and the piece all of it.
    pub alone: bool,
}

/// Every point the kept pieces use, rounded once: the correctly rounded
/// `f64` of each constructed point, and whether it is an operand vertex
/// (or otherwise exact), which a collapse never moves.
pub(crate) struct Rounded {
    /// The canonical points used, in order of first use.
    used: Vec<u32>,
    /// The slot in `used` of each canonical point (`u32::MAX`: unused).
    slot: Vec<u32>,
    /// The position of each used point.
    pub position: Vec<DVec3>,
    /// Whether each used point is exact as written (never moved).
    pub exact: Vec<bool>,
}

impl Rounded {
    /// Rounds every point the pieces use.
    pub(crate) fn new(table: &PointTable, pieces: &[KeptPiece]) -> Rounded {
        let mut slot = vec![u32::MAX; table.canonical.len()];
        let mut used: Vec<u32> = Vec::new();
        for piece in pieces {
            for &c in &piece.corners {
                if slot[c as usize] == u32::MAX {
                    slot[c as usize] = used.len() as u32;
                    used.push(c);
                }
            }
        }
        let (position, exact) = used
            .par_iter()
            .map(|&c| match table.get(c).explicit() {
                Some(p) => (p, true),
                None => (rounded_point(&table.get(c)), false),
            })
            .unzip();
        Rounded {
            used,
            slot,
            position,
            exact,
        }
    }

    /// The slot of canonical point `c` (used by some piece).
    pub(crate) fn slot_of(&self, c: u32) -> usize {
        self.slot[c as usize] as usize
    }

    /// How many points are used.
    pub(crate) fn len(&self) -> usize {
        self.used.len()
    }
}

/// What the output stage changed in the rounded result, round by round
/// (see `output`): pieces kept apart from their neighbours, points
/// collapsed onto others, and edges split at a point near them. Points are
/// named by their slot in [`Rounded`]; points the fixes made (a midpoint)
/// get slots after those.
pub(crate) struct Fixes {
    /// Pieces (by index) that merge with no neighbour.
    pub blocked: HashSet<usize>,
    /// Pieces (by index) left out: shells thinner than `f64` can hold.
    pub dropped: HashSet<usize>,
    /// Pairs of pieces (smaller index first) that merge although they lie
    /// in two planes: near-coplanar sheets folded by rounding.
    pub joined: HashSet<(usize, usize)>,
    /// The slot each slot was collapsed onto (itself when not).
    onto: Vec<usize>,
    /// Edges split at a point: `(a, b, at)`, by slots.
    splits: Vec<(usize, usize, usize)>,
    /// The positions of the points the fixes made.
    made: Vec<DVec3>,
    /// Edges tried as slits (by collapsed slots, smaller first).
    slits: HashSet<(usize, usize)>,
    /// How many points [`Rounded`] holds.
    rounded: usize,
}

impl Fixes {
    /// No fix yet, for the points of `rounded`.
    pub(crate) fn new(rounded: &Rounded) -> Fixes {
        Fixes {
            blocked: HashSet::default(),
            dropped: HashSet::default(),
            joined: HashSet::default(),
            onto: (0..rounded.len()).collect(),
            splits: Vec::new(),
            made: Vec::new(),
            slits: HashSet::default(),
            rounded: rounded.len(),
        }
    }

    /// The slot `s` ends on after every collapse.
    pub(crate) fn collapsed(&self, mut s: usize) -> usize {
        while self.onto[s] != s {
            s = self.onto[s];
        }
        s
    }

    /// The position of slot `s`.
    pub(crate) fn position(&self, rounded: &Rounded, s: usize) -> DVec3 {
        if s < self.rounded {
            rounded.position[s]
        } else {
            self.made[s - self.rounded]
        }
    }

    /// Whether slot `s` is exact as written: an operand vertex or a point
    /// that rounds to itself, which a collapse never moves.
    pub(crate) fn exact(&self, rounded: &Rounded, s: usize) -> bool {
        s < self.rounded && rounded.exact[s]
    }

    /// Collapses the points of slots `a` and `b` into one, keeping an
    /// exact point where it is. Returns whether anything changed: not when
    /// both are exact, unless `move_exact` (then the smaller slot stays).
    pub(crate) fn collapse(
        &mut self,
        rounded: &Rounded,
        a: usize,
        b: usize,
        move_exact: bool,
    ) -> bool {
        let (a, b) = (self.collapsed(a), self.collapsed(b));
        if a == b {
            return false;
        }
        match (self.exact(rounded, a), self.exact(rounded, b)) {
            (true, true) if !move_exact => return false,
            (true, true) => self.onto[a.max(b)] = a.min(b),
            (true, false) => self.onto[b] = a,
            (false, true) => self.onto[a] = b,
            (false, false) => self.onto[a.max(b)] = a.min(b),
        }
        true
    }

    /// Splits the edge between slots `a` and `b` at slot `at`. Returns
    /// whether this is new.
    pub(crate) fn split(&mut self, a: usize, b: usize, at: usize) -> bool {
        let (a, b, at) = (self.collapsed(a), self.collapsed(b), self.collapsed(at));
        let key = (a.min(b), a.max(b), at);
        if a == b || at == a || at == b || self.splits.contains(&key) {
            return false;
        }
        self.splits.push(key);
        true
    }

    /// What the fixes so far amount to, after `rounds` rounds.
    pub(crate) fn work(&self, rounds: usize) -> super::OutputWork {
        super::OutputWork {
            rounds,
            collapsed_points: (0..self.onto.len()).filter(|&s| self.onto[s] != s).count(),
            split_edges: self.splits.len(),
            unmerged_pieces: self.blocked.len(),
            joined_pairs: self.joined.len(),
            dropped_pieces: self.dropped.len(),
            welded_vertices: 0,
            rounded_points: 0,
        }
    }

    /// Whether `slot` (collapsed) is a point a fix made.
    pub(crate) fn is_made(&self, slot: usize) -> bool {
        self.collapsed(slot) >= self.rounded
    }

    /// Marks the edge between slots `a` and `b` as split for a slit;
    /// returns whether it was not marked before (each edge is tried once:
    /// an edge that is a diagonal of a piece's polygon has no split).
    pub(crate) fn try_slit(&mut self, a: usize, b: usize) -> bool {
        let (a, b) = (self.collapsed(a), self.collapsed(b));
        self.slits.insert((a.min(b), a.max(b)))
    }

    /// A new point at `position` (a slot of its own).
    pub(crate) fn make_point(&mut self, position: DVec3) -> usize {
        self.made.push(position);
        self.onto.push(self.onto.len());
        self.onto.len() - 1
    }

    /// The split points of each edge, by collapsed slots.
    fn split_points(&self) -> HashMap<(usize, usize), Vec<usize>> {
        let mut points: HashMap<(usize, usize), Vec<usize>> = HashMap::default();
        for &(a, b, at) in &self.splits {
            let (a, b, at) = (self.collapsed(a), self.collapsed(b), self.collapsed(at));
            if a != b && at != a && at != b {
                let list = points.entry((a.min(b), a.max(b))).or_default();
                if !list.contains(&at) {
                    list.push(at);
                }
            }
        }
        points
    }
}

/// The soup of the kept pieces with the fixes applied: each point once —
/// points that round to one `f64` position are one vertex — and each piece
/// a triangle with its source, or, where an edge of it was split, the
/// triangles of the polygon its corners and split points make. A piece
/// whose corners became one is dropped, and so is a pair of triangles that
/// became one triangle wound both ways. Returns also the slot of each soup
/// vertex.
pub(crate) fn soup_of(
    rounded: &Rounded,
    fixes: &Fixes,
    pieces: &[KeptPiece],
    operands: &[Prepared],
) -> (PolygonSoup, Vec<PieceSource>, Vec<usize>) {
    let splits = fixes.split_points();
    // Each piece's polygon of slots: its collapsed corners with the split
    // points of its edges between them, in order along each edge.
    let polygons: Vec<(usize, SmallVec<[usize; 3]>)> = pieces
        .par_iter()
        .enumerate()
        .filter(|(i, _)| !fixes.dropped.contains(i))
        .map(|(i, piece)| {
            let corners = piece.corners.map(|c| fixes.collapsed(rounded.slot_of(c)));
            let mut polygon: SmallVec<[usize; 3]> = SmallVec::new();
            for k in 0..3 {
                let (a, b) = (corners[k], corners[(k + 1) % 3]);
                polygon.push(a);
                if let Some(on) = splits.get(&(a.min(b), a.max(b))) {
                    let (pa, pb) = (fixes.position(rounded, a), fixes.position(rounded, b));
                    let mut along: Vec<(f64, usize)> = on
                        .iter()
                        .map(|&s| ((fixes.position(rounded, s) - pa).dot(pb - pa), s))
                        .collect();
                    along.sort_by(|x, y| x.0.total_cmp(&y.0));
                    polygon.extend(along.into_iter().map(|(_, s)| s));
                }
            }
            (i, without_spikes(polygon))
        })
        .collect();
    // Each slot's vertex: the first slot at its position.
    let key = |p: DVec3| (p + DVec3::ZERO).to_array().map(f64::to_bits);
    let mut vertex_of: HashMap<usize, usize> = HashMap::default();
    let mut at: HashMap<[u64; 3], usize> = HashMap::default();
    let mut positions: Vec<DVec3> = Vec::new();
    let mut slots: Vec<usize> = Vec::new();
    for (_, polygon) in &polygons {
        for &s in polygon {
            if vertex_of.contains_key(&s) {
                continue;
            }
            let p = fixes.position(rounded, s);
            let v = *at.entry(key(p)).or_insert_with(|| {
                positions.push(p);
                slots.push(s);
                positions.len() - 1
            });
            vertex_of.insert(s, v);
        }
    }
    // The triangles: a piece as it is, or its polygon triangulated.
    let triangles: Vec<(usize, [usize; 3])> = polygons
        .par_iter()
        .flat_map_iter(|(i, polygon)| {
            let vertices: SmallVec<[usize; 3]> =
                without_spikes(polygon.iter().map(|s| vertex_of[s]).collect());
            let out: SmallVec<[(usize, [usize; 3]); 2]> = match vertices.len() {
                0..=2 => SmallVec::new(),
                3 => smallvec::smallvec![(*i, [vertices[0], vertices[1], vertices[2]])],
                _ => {
                    let points: Vec<DVec3> = vertices.iter().map(|&v| positions[v]).collect();
                    match triangulate_3d(&points, &[]) {
                        Ok(ts) => ts
                            .into_iter()
                            .map(|t| (*i, t.map(|k| vertices[k])))
                            .collect(),
                        // Not simple once rounded: a fan, which the proof
                        // will judge.
                        Err(_) => (1..vertices.len() - 1)
                            .map(|k| (*i, [vertices[0], vertices[k], vertices[k + 1]]))
                            .collect(),
                    }
                }
            };
            out
        })
        .collect();
    let corners: Vec<Option<[usize; 3]>> = triangles
        .iter()
        .map(|&(_, c)| (c[0] != c[1] && c[1] != c[2] && c[2] != c[0]).then_some(c))
        .collect();
    let alive = kept_after_mirror_cancel(&corners, positions.len());
    let (polygons, sources): (Vec<Polygon>, Vec<PieceSource>) = triangles
        .par_iter()
        .zip(&corners)
        .zip(&alive)
        .filter_map(|((&(i, _), c), &alive)| Some((i, (*c).filter(|_| alive)?)))
        .map(|(i, c)| {
            let piece = &pieces[i];
            let operand = &operands[piece.operand];
            let mut polygon = Polygon::new(c);
            if let Some(solid) = operand.solid {
                let face = solid.face(piece.face);
                polygon.attributes.group = face.attributes.group.clone();
                polygon.attributes.material = face.attributes.material.clone();
            }
            let whole = c.iter().all(|v| {
                piece
                    .corners
                    .iter()
                    .any(|&k| slots[*v] == fixes.collapsed(rounded.slot_of(k)))
            });
            let source = PieceSource {
                piece: i,
                origin: FaceOrigin {
                    operand: operand.index,
                    face: piece.face,
                },
                plane: piece.plane,
                changed: piece.changed || !whole,
                alone: piece.alone && whole,
            };
            (polygon, source)
        })
        .unzip();
    (
        PolygonSoup {
            positions,
            polygons,
        },
        sources,
        slots,
    )
}

/// The polygon without what a collapse or a split point made flat:
/// consecutive repeats, and spikes (`… u, w, u …`, a corner that goes out
/// and comes straight back).
fn without_spikes(mut polygon: SmallVec<[usize; 3]>) -> SmallVec<[usize; 3]> {
    loop {
        let n = polygon.len();
        if n < 3 {
            return if n == 0 { polygon } else { SmallVec::new() };
        }
        let repeat = (0..n).find(|&k| polygon[k] == polygon[(k + 1) % n]);
        if let Some(k) = repeat {
            polygon.remove(k);
            continue;
        }
        let spike = (0..n).find(|&k| polygon[k] == polygon[(k + 2) % n]);
        match spike {
            Some(k) => {
                // Remove the tip and one copy of its base.
                let tip = (k + 1) % n;
                let base = (k + 2) % n;
                let (first, second) = (tip.max(base), tip.min(base));
                polygon.remove(first);
                polygon.remove(second);
            }
            None => return polygon,
        }
    }
}

/// Whether each piece is kept: not collapsed (`None`), and not cancelled
/// with an earlier one — a sliver pair collapsed by the snap, the same
/// triangle wound both ways. In piece order, as each piece meets the
/// latest kept piece with its mirror image's corners; only pieces that
/// share their corners with another can meet a mirror image.
fn kept_after_mirror_cancel(corners: &[Option<[usize; 3]>], point_count: usize) -> Vec<bool> {
    let mut alive: Vec<bool> = corners.iter().map(Option::is_some).collect();
    let twins = with_twin_corners(corners, point_count);
    let mut seen: HashMap<[usize; 3], usize> =
        HashMap::with_capacity_and_hasher(twins.len(), Default::default());
    for &i in &twins {
        let Some(c) = &corners[i] else {
            continue;
        };
        let mirror = rotated_to_smallest([c[0], c[2], c[1]]);
        if let Some(&other) = seen.get(&mirror)
            && alive[other]
        {
            alive[other] = false;
            alive[i] = false;
            continue;
        }
        seen.insert(rotated_to_smallest(*c), i);
    }
    alive
}

/// The pieces (in piece order) that share their set of three corners with
/// another piece: the only ones that can cancel with a mirror image,
/// since a triangle and its mirror image have the same corners. Pieces
/// are grouped by their smallest corner (one counting pass, no hashing),
/// and each group of a few pieces is compared pairwise.
fn with_twin_corners(corners: &[Option<[usize; 3]>], point_count: usize) -> Vec<usize> {
    let sorted: Vec<Option<[usize; 3]>> = corners
        .par_iter()
        .map(|c| {
            c.map(|mut c| {
                c.sort_unstable();
                c
            })
        })
        .collect();
    let (offsets, by_smallest) = compressed_rows(
        point_count,
        sorted
            .iter()
            .enumerate()
            .filter_map(|(i, c)| c.map(|c| (c[0], i))),
    );
    let mut twins: Vec<usize> = offsets
        .par_windows(2)
        .flat_map_iter(|range| {
            let group = &by_smallest[range[0]..range[1]];
            group
                .iter()
                .copied()
                .filter(|&i| group.iter().any(|&j| j != i && sorted[j] == sorted[i]))
                .collect::<Vec<_>>()
        })
        .collect();
    twins.par_sort_unstable();
    twins
}

/// The triangle's corners in the same cyclic order, smallest first: equal
/// for two triangles exactly when they are one triangle wound one way.
fn rotated_to_smallest(mut corners: [usize; 3]) -> [usize; 3] {
    let first = (0..3).min_by_key(|&k| corners[k]).unwrap_or(0);
    corners.rotate_left(first);
    corners
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_with_twin_corners_are_those_sharing_all_three() {
        let corners = vec![
            Some([0, 1, 2]),
            Some([3, 4, 5]),
            Some([2, 1, 0]), // the mirror image of piece 0
            None,            // collapsed by the snap
            Some([1, 2, 3]), // shares two corners with piece 0 only
            Some([5, 3, 4]), // piece 1 turned: same corners, same winding
            Some([0, 2, 6]),
        ];
        assert_eq!(with_twin_corners(&corners, 7), vec![0, 1, 2, 5]);
    }

    #[test]
    fn a_mirror_pair_cancels_and_a_third_copy_stays() {
        // Soup indices after the snap: three copies of one triangle, the
        // second wound the other way; the first two cancel, the third
        // meets no kept mirror image and stays. Piece 3 collapsed; piece 4
        // and 5 are one triangle wound one way (no cancel).
        let corners = [
            Some([0, 1, 2]),
            Some([0, 2, 1]),
            Some([1, 2, 0]),
            None,
            Some([3, 4, 5]),
            Some([4, 5, 3]),
        ];
        assert_eq!(
            kept_after_mirror_cancel(&corners, 6),
            vec![false, false, true, false, true, true]
        );
    }
}
