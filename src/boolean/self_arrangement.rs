//! One soup cut by itself: the boolean's stages on a single operand whose
//! triangles may cross, overlap and nest, labelled by the winding number
//! (Zhou, Grinspun, Zorin and Jacobson, *Mesh arrangements for solid
//! geometry*, 2016).
//!
//! The soup's polygons are triangulated exactly into one operand;
//! `self_pairs` hands over the pairs of its triangles that meet (pairs
//! that share an edge and lie on either side of it meet only along it and
//! are skipped); `intersect`, `crossings` (segments of different
//! triangles crossing inside a third), `points` and `split` then arrange it
//! exactly as they arrange two operands. Each patch of pieces separates two
//! cells of space whose winding numbers are read off one exact ray from an
//! implicit point inside a piece: the patch bounds the result where the
//! winding number is positive on exactly one side, wound to face the side
//! where it is not. Pieces covered by several coplanar triangles are kept
//! once, from the triangle of the smallest index. The kept pieces go through
//! the boolean's `assemble`, `merge` and `output` stages, so the result is
//! proven valid like every boolean's.
//!
//! The winding number is an integer, the same along every ray, only when
//! the soup is closed: every edge run as often one way as the other. The
//! caller ensures it ([`arrange_soup`] refuses otherwise).

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::time::Instant;

use glam::DVec3;
use slotmap::SlotMap;

use crate::geom::dyadic::Dyadic;
use crate::geom::implicit::{
    Arithmetic, Centroid, HasHomogeneous, Homogeneous, ImplicitPoint, Interval, XRayCrossing,
    enclosing_box, x_ray_crossing,
};
use crate::geom::{Sign, collinear3d, projected_orientation, triangulate_3d};
use crate::mesh::{FaceId, PolygonSoup, Solid};
use crate::validate::Report;

use super::assemble::KeptPiece;
use super::classify::{Piece, patch_rows};
use super::crossings::{Line, Segment};
use super::intersect::Carrier;
use super::operand::Prepared;
use super::points::PointTable;
use super::self_pairs::self_contacts;
use super::{BooleanError, BooleanStats, Cuts, cross_segments, output, pieces};

/// A soup arranged against itself and reduced to the boundary of the
/// region where its winding number is positive.
#[derive(Clone, Debug)]
pub struct SelfArrangement {
    /// The result, proven valid (possibly empty: the soup encloses
    /// nothing).
    pub solid: Solid,
    /// For each face of `solid` (by its `attributes.source_index`), the
    /// soup polygon it is part of.
    pub polygons: Vec<usize>,
    /// The validator's report on `solid`.
    pub report: Report,
    /// Pairs of soup polygons whose triangles cross or overlap (not
    /// counting neighbours that only share an edge or a corner), each once,
    /// smaller index first, sorted.
    pub crossing_polygons: Vec<(usize, usize)>,
    /// Time and work, as a boolean's.
    pub stats: BooleanStats,
}

/// Arranges the closed soup `soup` against itself and keeps the boundary
/// of `{p : w(p) > ½}`, `w` the soup's winding number (an integer off the
/// surface: the soup is closed).
///
/// # Errors
///
/// [`BooleanError::Inconsistent`] when an edge is run more often one way
/// than the other (the winding number would depend on the ray) or a
/// polygon cannot be triangulated; [`BooleanError::TooLarge`] beyond
/// `max_contacts` touching pairs; the output stage's errors when rounding
/// the result to `f64` broke it.
pub fn arrange_soup(
    soup: &PolygonSoup,
    max_contacts: usize,
) -> Result<SelfArrangement, BooleanError> {
    let mut stats = BooleanStats::default();
    let clock = Instant::now();
    let mut keys: SlotMap<FaceId, usize> = SlotMap::with_key();
    let prepared = prepare(soup, &mut keys)?;
    let polygon_of: HashMap<FaceId, usize> = keys.iter().map(|(k, &i)| (k, i)).collect();
    if prepared.triangles.is_empty() {
        return empty(stats);
    }
    stats.prepare_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let found = self_contacts(&prepared);
    stats.contacts = found.len();
    if stats.contacts > max_contacts {
        return Err(BooleanError::TooLarge {
            contacts: stats.contacts,
            limit: max_contacts,
        });
    }
    let mut crossing_polygons: Vec<(usize, usize)> = found
        .iter()
        .map(|&(a, b, _)| {
            let (p, q) = (
                polygon_of[&prepared.faces[a as usize]],
                polygon_of[&prepared.faces[b as usize]],
            );
            (p.min(q), p.max(q))
        })
        .filter(|(p, q)| p != q)
        .collect();
    crossing_polygons.sort_unstable();
    crossing_polygons.dedup();
    stats.intersect_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let vertices = prepared.positions.clone();
    let base = vertices.len();
    let mut made: Vec<ImplicitPoint> = Vec::new();
    let mut cuts: Vec<HashMap<u32, Cuts>> = vec![HashMap::default()];
    let mut candidates: Vec<u32> = Vec::new();
    for (ta, tb, contact) in &found {
        let ids = contact.point_ids(base, &mut made);
        candidates.extend(&ids);
        candidates.extend(&contact.touched);
        let corners = [prepared.corners(*ta), prepared.corners(*tb)];
        for (t, other, list, other_corners) in [
            (*ta, *tb, &contact.first_cuts, corners[1]),
            (*tb, *ta, &contact.second_cuts, corners[0]),
        ] {
            let entry = cuts[0].entry(t).or_default();
            entry.points.extend(&ids);
            entry
                .segments
                .extend(list.iter().map(|&(from, to, along)| Segment {
                    ends: (ids[from as usize], ids[to as usize]),
                    // Segments of different triangles may cross inside a
                    // third: each triangle counts as an operand of its own.
                    operand: other as usize,
                    line: match along {
                        Carrier::PlanesMeet => Line::Meets(other_corners),
                        Carrier::OtherEdge(k) => Line::Through(
                            other_corners[k as usize],
                            other_corners[(k as usize + 1) % 3],
                        ),
                    },
                }));
        }
    }
    drop(found);
    stats.segment_crossings = cross_segments(
        std::slice::from_ref(&prepared),
        &vertices,
        &mut made,
        &mut cuts,
        &mut candidates,
    );
    stats.new_points = made.len();
    let table = PointTable::new(vertices, made, candidates);
    stats.points_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    stats.cut_triangles = cuts[0].len();
    let (all_pieces, constrained) = pieces(&table, &prepared, 0, &cuts[0])?;
    let mut constrained: HashSet<(u32, u32)> = constrained.into_iter().collect();
    constrained.extend(branching_edges(&all_pieces));
    stats.split_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let decisions = decide(&table, &prepared, &all_pieces, &constrained)?;
    stats.classify_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let kept: Vec<KeptPiece> = all_pieces
        .iter()
        .zip(&decisions)
        .filter_map(|(piece, decision)| {
            let flip = (*decision)?;
            let [x, y, z] = piece.corners;
            let [p, q, r] = prepared.corners(piece.triangle);
            let mut own =
                prepared.triangles[piece.triangle as usize].map(|i| table.canonical[i as usize]);
            own.sort_unstable();
            let mut corners = piece.corners;
            corners.sort_unstable();
            let changed = corners != own;
            Some(KeptPiece {
                corners: if flip { [x, z, y] } else { [x, y, z] },
                operand: 0,
                face: prepared.faces[piece.triangle as usize],
                plane: if flip { [p, r, q] } else { [p, q, r] },
                changed,
                alone: !changed && prepared.face_is_one_triangle(piece.triangle),
            })
        })
        .collect();
    let (solid, origins, report, proof_seconds, work) =
        output::build_and_prove(&table, &kept, std::slice::from_ref(&prepared))?;
    stats.proof_seconds = proof_seconds;
    stats.output = work;
    stats.output_seconds = clock.elapsed().as_secs_f64() - proof_seconds;
    Ok(SelfArrangement {
        solid,
        polygons: origins.iter().map(|o| polygon_of[&o.face]).collect(),
        report,
        crossing_polygons,
        stats,
    })
}

/// An operand that is not a valid solid, as the solid of the region where
/// its winding number is positive.
///
/// # Errors
///
/// [`BooleanError::InvalidOperand`] when it is open (its winding number
/// would depend on the ray); those of [`arrange_soup`].
pub(crate) fn resolve_operand(
    solid: &Solid,
    operand: usize,
    max_contacts: usize,
) -> Result<Solid, BooleanError> {
    let soup = solid.to_soup();
    let open = unbalanced_edges(&soup);
    if open > 0 {
        return Err(BooleanError::InvalidOperand {
            operand,
            validity: "open".into(),
            report: format!(
                "{open} edges are run more often one way than the other, so its winding number is not defined; fill its holes first (wingedge repair)"
            ),
        });
    }
    Ok(arrange_soup(&soup, max_contacts)?.solid)
}

/// How many edges of `soup` are run more often one way than the other.
fn unbalanced_edges(soup: &PolygonSoup) -> usize {
    let mut net: HashMap<(usize, usize), i64> = HashMap::default();
    for polygon in &soup.polygons {
        let n = polygon.vertices.len();
        for k in 0..n {
            let (u, v) = (polygon.vertices[k], polygon.vertices[(k + 1) % n]);
            *net.entry((u.min(v), u.max(v))).or_default() += if u < v { 1 } else { -1 };
        }
    }
    net.values().filter(|&&c| c != 0).count()
}

/// The empty result.
fn empty(stats: BooleanStats) -> Result<SelfArrangement, BooleanError> {
    let solid = Solid::default();
    Ok(SelfArrangement {
        report: output::prove(&solid)?,
        solid,
        polygons: Vec::new(),
        crossing_polygons: Vec::new(),
        stats,
    })
}

/// The soup as one operand: every polygon triangulated exactly (a polygon
/// of zero area gives no triangle), each triangle's face a key minted in
/// `keys` for its polygon.
fn prepare<'s>(
    soup: &PolygonSoup,
    keys: &mut SlotMap<FaceId, usize>,
) -> Result<Prepared<'s>, BooleanError> {
    let positions = soup.positions.clone();
    let mut triangles = Vec::with_capacity(soup.polygons.len());
    let mut faces = Vec::with_capacity(soup.polygons.len());
    let mut ring: Vec<DVec3> = Vec::new();
    for (index, polygon) in soup.polygons.iter().enumerate() {
        let face = keys.insert(index);
        let corners = &polygon.vertices;
        if corners.iter().any(|&v| v >= positions.len()) {
            return Err(BooleanError::Inconsistent(format!(
                "polygon {index} names a vertex past the soup's {}",
                positions.len()
            )));
        }
        let local: Vec<[usize; 3]> = if corners.len() == 3 {
            vec![[0, 1, 2]]
        } else {
            ring.clear();
            ring.extend(corners.iter().map(|&v| positions[v]));
            triangulate_3d(&ring, &[]).map_err(|e| {
                BooleanError::Inconsistent(format!("polygon {index} cannot be triangulated: {e}"))
            })?
        };
        for t in local {
            let t = t.map(|k| corners[k] as u32);
            let [a, b, c] = t.map(|i| positions[i as usize]);
            if !collinear3d(a, b, c) {
                triangles.push(t);
                faces.push(face);
            }
        }
    }
    Ok(Prepared::from_tables(None, 0, positions, triangles, faces))
}

/// The edges of pieces that patches must not be joined across although no
/// segment lies on them: those of more or fewer than two uses (where
/// coplanar pieces or several sheets meet) and those whose two uses run
/// the same way; as `(smaller, larger)` canonical point indices.
fn branching_edges(pieces: &[Piece]) -> Vec<(u32, u32)> {
    let mut uses: Vec<(u32, u32, bool)> = pieces
        .iter()
        .flat_map(|piece| {
            (0..3).map(move |k| {
                let (u, v) = (piece.corners[k], piece.corners[(k + 1) % 3]);
                (u.min(v), u.max(v), u < v)
            })
        })
        .collect();
    uses.sort_unstable();
    uses.chunk_by(|a, b| (a.0, a.1) == (b.0, b.1))
        .filter(|run| run.len() != 2 || run[0].2 == run[1].2)
        .map(|run| (run[0].0, run[0].1))
        .collect()
}

/// Each piece's fate: `None` when it does not bound `{w > ½}`, `Some(flip)`
/// when it does (turned over when `flip`); one decision per patch.
fn decide(
    table: &PointTable,
    operand: &Prepared,
    pieces: &[Piece],
    constrained: &HashSet<(u32, u32)>,
) -> Result<Vec<Option<bool>>, BooleanError> {
    use rayon::prelude::*;
    let (start, by_root) = patch_rows(pieces, constrained);
    let patch_decisions: Vec<(usize, Option<bool>)> = (0..pieces.len())
        .into_par_iter()
        .filter(|&root| start[root] < start[root + 1])
        .map(|root| {
            let first = pieces[by_root[start[root]] as usize];
            winding_sides(table, operand, first).map(|sides| (root, sides))
        })
        .collect::<Result<_, _>>()?;
    let mut decisions = vec![None; pieces.len()];
    for (root, decision) in patch_decisions {
        for &m in &by_root[start[root]..start[root + 1]] {
            decisions[m as usize] = decision;
        }
    }
    Ok(decisions)
}

/// The fate of the patch of `piece` (see [`decide`]): the winding numbers
/// just behind and just in front of the piece, counted along an exact ray
/// from its centroid along an axis its plane is not parallel to; `None`
/// also when a coplanar triangle of smaller index covers the piece (that
/// triangle's piece stands for it).
fn winding_sides(
    table: &PointTable,
    operand: &Prepared,
    piece: Piece,
) -> Result<Option<bool>, BooleanError> {
    let own = operand.corners(piece.triangle);
    let Some(axis) = (0..3u8).find(|&a| projected_orientation(own, a) != Sign::Zero) else {
        return Err(BooleanError::Inconsistent(format!(
            "triangle {} has zero area",
            piece.triangle
        )));
    };
    let own_facing = projected_orientation(own, axis);
    let centroid = Centroid(piece.corners.map(|c| table.get(c)));
    let turned = Turned {
        point: &centroid,
        axis,
    };
    let mut query = enclosing_box(&centroid);
    let a = axis as usize;
    query.max[a] = operand.bvh.bounds().max[a].max(query.max[a]);
    let mut crossings = 0i64;
    let mut on: i64 = 0;
    let mut covered_by_smaller = false;
    operand.triangles_overlapping(&query, |t| {
        let corners = operand.corners(t);
        let facing = projected_orientation(corners, axis);
        match x_ray_crossing(&turned, corners.map(|p| turn(p, axis))) {
            XRayCrossing::Crosses => crossings += sign_value(facing),
            XRayCrossing::Contains => {
                on += sign_value(facing);
                // A coplanar triangle (every triangle through the centroid
                // is one) of smaller index.
                covered_by_smaller |= t < piece.triangle;
            }
            XRayCrossing::Misses => {}
        }
    });
    if covered_by_smaller {
        return Ok(None);
    }
    // From the side a `+axis` ray does not cross the piece's plane, the
    // count is the crossings alone; from the other side it also crosses
    // every triangle containing the piece.
    let (in_front, behind) = if own_facing == Sign::Positive {
        (crossings, crossings + on)
    } else {
        (crossings + on, crossings)
    };
    Ok(match (behind > 0, in_front > 0) {
        (true, false) => Some(false),
        (false, true) => Some(true),
        _ => None,
    })
}

/// `+1`, `0` or `−1`.
fn sign_value(s: Sign) -> i64 {
    match s {
        Sign::Positive => 1,
        Sign::Zero => 0,
        Sign::Negative => -1,
    }
}

/// `p` with its axes turned cyclically so that `axis` comes first (an
/// exact, orientation-preserving relabelling).
fn turn(p: DVec3, axis: u8) -> DVec3 {
    let a = axis as usize;
    DVec3::new(p[a], p[(a + 1) % 3], p[(a + 2) % 3])
}

/// A point seen with its axes turned as [`turn`] turns them.
struct Turned<'p, P> {
    point: &'p P,
    axis: u8,
}

impl<P: HasHomogeneous> Turned<'_, P> {
    fn reorder<T>(&self, h: Homogeneous<T>) -> Homogeneous<T> {
        let [x, y, z] = h.xyz;
        let xyz = match self.axis {
            0 => [x, y, z],
            1 => [y, z, x],
            _ => [z, x, y],
        };
        Homogeneous { xyz, w: h.w }
    }
}

impl<P: HasHomogeneous> HasHomogeneous for Turned<'_, P> {
    fn homogeneous<T: Arithmetic>(&self) -> Homogeneous<T> {
        self.reorder(self.point.homogeneous())
    }

    fn filter(&self) -> Homogeneous<Interval> {
        self.reorder(self.point.filter())
    }

    fn exact(&self) -> Homogeneous<Dyadic> {
        self.reorder(self.point.exact())
    }

    fn double_double_safe(&self) -> bool {
        self.point.double_double_safe()
    }

    fn known_coordinate(&self, axis: usize) -> Option<f64> {
        self.point.known_coordinate((axis + self.axis as usize) % 3)
    }
}
