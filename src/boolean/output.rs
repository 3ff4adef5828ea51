//! Stage 8: the result written and proven, in rounds until what would be
//! written is valid.
//!
//! Every decision before this stage was exact; here the result's points
//! are rounded to `f64`, its pieces built into a winged-edge solid, and
//! coplanar neighbours merged into polygon faces. Rounding can break what
//! the exact result had — two points a few units in the last place apart
//! become one, a sliver folds, a merged face touches itself along a slit
//! or is no longer flat enough — so the stage proves exactly what would be
//! written (the polygons of [`written_soup`], validated as `wingedge
//! validate` reads the file) and, where the proof finds a defect, changes
//! the output locally and tries again:
//!
//! - a merged face with a defect is split back into its pieces around the
//!   vertices the defect names (or wholly, when it names none): a polygon
//!   face is a convenience, its triangles are always flat;
//! - a defect among pieces that are not merged is a feature smaller than
//!   `f64` can hold: the shortest edge of each piece involved is collapsed
//!   (a constructed point moved onto its neighbour; operand vertices never
//!   move), as snap rounding does (Hobby 1999; Halperin and Packer 2002).
//!
//! Each round changes only what the proof found, and what it found is
//! proven again with the rest. A result the rounds cannot make valid is an
//! error naming the operands and where in space the defect is — never a
//! file that fails its own validator.

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};

use glam::DVec3;
use slotmap::SecondaryMap;

use crate::disjoint_sets::DisjointSets;
use crate::geom::{Plane, Tolerance};
use crate::io::written_soup;
use crate::mesh::{FaceId, PolygonSoup, Solid};
use crate::validate::{Options, Report, Rule, validate_soup, validate_soup_near_changed};

use super::assemble::{Fixes, KeptPiece, Rounded, soup_of};
use super::failure::{invalid, not_built};
use super::merge::{PieceSource, merge_faces};
use super::operand::{FaceOrigin, Prepared};
use super::points::PointTable;
use super::{BooleanError, OutputWork};

/// How many times the output may be changed and proven again.
const MAX_ROUNDS: usize = 24;

/// A built result: the solid, its faces' origins, the validator's report
/// on what is written, and the seconds the proofs took.
pub(crate) type Built = (Solid, Vec<FaceOrigin>, Report, f64, OutputWork);

/// Builds, merges and proves the kept pieces, in rounds (see the module
/// documentation). Returns the solid (faces' `source_index` into the
/// returned origins), the origins, the report on what is written and the
/// seconds the proofs took.
pub(crate) fn build_and_prove(
    table: &PointTable,
    pieces: &[KeptPiece],
    operands: &[Prepared],
) -> Result<Built, BooleanError> {
    let rounded = Rounded::new(table, pieces);
    let mut fixes = Fixes::new(&rounded);
    let mut proof_seconds = 0.0;
    let mut failure = None;
    for round in 1..=MAX_ROUNDS {
        let (soup, sources, slots) = soup_of(&rounded, &fixes, pieces, operands);
        if soup.polygons.is_empty() {
            let solid = Solid::default();
            let report = prove(&solid)?;
            return Ok((
                solid,
                Vec::new(),
                report,
                proof_seconds,
                work(&fixes, &rounded, round),
            ));
        }
        let at = Round {
            rounded: &rounded,
            soup: &soup,
            sources: &sources,
            slots: &slots,
        };
        let mut solid = match Solid::try_from_touching_soup(&soup) {
            Ok(solid) => solid,
            Err(e) => {
                let (polygons, ends) = match &e {
                    crate::mesh::BuildError::NonManifoldEdge {
                        polygons, vertices, ..
                    } => (polygons.clone(), Some(*vertices)),
                    crate::mesh::BuildError::InconsistentOrientation { polygons, .. } => {
                        (polygons.to_vec(), None)
                    }
                    _ => (Vec::new(), None),
                };
                failure = Some(not_built(&e, &polygons, &soup, |p| {
                    sources.get(p).map(|s| s.origin.operand)
                }));
                let pairs: Vec<(usize, usize)> = polygons
                    .iter()
                    .enumerate()
                    .flat_map(|(k, &s)| polygons[k + 1..].iter().map(move |&t| (s, t)))
                    .collect();
                // Two sheets along a slit whose copies of the edge share
                // both ends: a vertex in the middle is theirs to split.
                let slit = ends.is_some_and(|[p, q]| {
                    polygons.len() == 4 && split_touching_edge(&mut fixes, &at, p, q)
                });
                if slit
                    || drop_thin_shells(&mut fixes, &at, &soup, &polygons, &|p| Some(vec![p]))
                    || fix_pieces(&mut fixes, &at, &polygons, &pairs)
                {
                    continue;
                }
                break;
            }
        };
        let (changed, merged) = merge_faces(&mut solid, &sources, &fixes.blocked, &fixes.joined);
        let clock = std::time::Instant::now();
        let (written, faces) = written_soup(&solid);
        let changed_polygons: Vec<bool> = faces.iter().map(|f| changed.contains(f)).collect();
        let report = validate_soup_near_changed(&written, &changed_polygons)
            .map_err(|e| BooleanError::not_built(e.to_string()))?;
        proof_seconds += clock.elapsed().as_secs_f64();
        if report.is_valid() {
            let (origins, renumbered) = origins_of(&solid, &sources);
            for (f, index) in renumbered {
                let mut attributes = solid.face(f).attributes.clone();
                attributes.source_index = Some(index);
                solid.set_face_attributes(f, attributes);
            }
            return Ok((
                solid,
                origins,
                report,
                proof_seconds,
                work(&fixes, &rounded, round),
            ));
        }
        failure = Some(invalid(&report, &written, |polygon| {
            let face = faces.get(polygon)?;
            let index = solid.get_face(*face)?.attributes.source_index?;
            Some(sources.get(index)?.origin.operand)
        }));
        let proven = Proven {
            solid: &solid,
            written: &written,
            faces: &faces,
            merged: &merged,
        };
        if !learn(&mut fixes, &at, &report, &proven) {
            break;
        }
    }
    Err(failure.unwrap_or_else(|| BooleanError::not_built("the output did not settle")))
}

/// The output's work after `round` rounds: the fixes made, and the
/// constructed points written rounded.
fn work(fixes: &Fixes, rounded: &Rounded, round: usize) -> OutputWork {
    let mut work = fixes.work(round);
    work.rounded_points = rounded.exact.iter().filter(|&&exact| !exact).count();
    work
}

/// One round's soup of pieces, as the solid was built from it.
struct Round<'r> {
    rounded: &'r Rounded,
    soup: &'r PolygonSoup,
    sources: &'r [PieceSource],
    /// The slot of each soup vertex.
    slots: &'r [usize],
}

/// One round's output, as the proof saw it.
struct Proven<'r> {
    solid: &'r Solid,
    written: &'r PolygonSoup,
    /// The face of each written polygon.
    faces: &'r [FaceId],
    /// Pairs of soup polygons whose faces merged.
    merged: &'r [(usize, usize)],
}

/// Learns from the proof's defects: blocks merges of the pieces around a
/// merged face's defect; splits an edge that two sheets touch along
/// between two vertices of their own (a slit inside a face); fixes the
/// pieces with a defect of their own ([`fix_pieces`]). Returns whether
/// anything changed.
fn learn(fixes: &mut Fixes, at: &Round, report: &Report, proven: &Proven) -> bool {
    // The soup polygons of each merged face (by source index of a member).
    let mut groups = DisjointSets::new(at.soup.polygons.len());
    for &(a, b) in proven.merged {
        groups.union(a, b);
    }
    let group_of: Vec<usize> = (0..at.soup.polygons.len())
        .map(|i| groups.find(i))
        .collect();
    let mut members: HashMap<usize, Vec<usize>> = HashMap::default();
    for (i, &g) in group_of.iter().enumerate() {
        members.entry(g).or_default().push(i);
    }
    // Soup vertex by position, to name the pieces at a written vertex.
    let key = |p: DVec3| (p + DVec3::ZERO).to_array().map(f64::to_bits);
    let vertex_at: HashMap<[u64; 3], usize> = at
        .soup
        .positions
        .iter()
        .enumerate()
        .map(|(v, &p)| (key(p), v))
        .collect();
    let soup_vertex = |w: usize| vertex_at.get(&key(proven.written.positions[w])).copied();
    // The soup pieces of the (merged) face a written polygon is.
    let pieces_of_polygon = |p: usize| -> Option<Vec<usize>> {
        let face = proven.faces.get(p)?;
        let source = proven.solid.face(*face).attributes.source_index?;
        Some(members[&group_of[source]].clone())
    };
    // The written polygons the defects name.
    let named: Vec<usize> = report
        .violations
        .iter()
        .flat_map(|v| v.faces.iter().copied())
        .collect();
    // A shell turned inside out is a sliver between near-coincident
    // sheets that rounding flipped: dropped first, if thinner than f64
    // can hold, before any fix moves points around it.
    let inward: Vec<usize> = report
        .violations
        .iter()
        .filter(|v| v.rule == Rule::ShellOrientedInward)
        .flat_map(|v| v.faces.iter().copied())
        .collect();
    if !inward.is_empty()
        && drop_thin_shells(fixes, at, proven.written, &inward, &pieces_of_polygon)
    {
        return true;
    }
    let mut learnt = false;
    let mut to_fix: Vec<usize> = Vec::new();
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for violation in &report.violations {
        let mut pieces_of_faces: Vec<usize> = Vec::new();
        let mut merged_face = false;
        for &p in &violation.faces {
            let Some(&face) = proven.faces.get(p) else {
                continue;
            };
            let Some(source) = proven.solid.face(face).attributes.source_index else {
                continue;
            };
            let group = &members[&group_of[source]];
            merged_face |= group.len() > 1;
            pieces_of_faces.extend(group);
        }
        let at_vertices: HashSet<usize> = violation
            .vertices
            .iter()
            .filter_map(|&v| soup_vertex(v))
            .collect();
        if violation.rule == Rule::EdgeInMoreThanTwoFaces
            && let [p, q] = at_vertices.iter().copied().collect::<Vec<_>>()[..]
            && split_touching_edge(fixes, at, p, q)
        {
            learnt = true;
            continue;
        }
        let vertex_rule = matches!(
            violation.rule,
            Rule::VertexInFewerThanThreeEdges
                | Rule::VertexInFewerThanThreeFaces
                | Rule::NonManifoldVertex
        );
        if merged_face || vertex_rule {
            // Split the merged face back: around the named vertices for a
            // vertex's defect, wholly for a face's.
            let candidates: Vec<usize> = if vertex_rule && !at_vertices.is_empty() {
                (0..at.soup.polygons.len())
                    .filter(|&i| {
                        at.soup.polygons[i]
                            .vertices
                            .iter()
                            .any(|v| at_vertices.contains(v))
                    })
                    .collect()
            } else {
                pieces_of_faces.clone()
            };
            let mut blocked_any = false;
            for i in candidates {
                blocked_any |= fixes.blocked.insert(at.sources[i].piece);
            }
            if blocked_any {
                learnt = true;
                continue;
            }
        }
        // Nothing merged to split: the pieces themselves are at fault.
        if let [f, g] = violation.faces[..] {
            let piece_of = |p: usize| {
                let face = proven.faces.get(p)?;
                proven.solid.face(*face).attributes.source_index
            };
            if let (Some(s), Some(t)) = (piece_of(f), piece_of(g)) {
                if violation.rule == Rule::SelfIntersection
                    && flat_together(proven.written, f, g)
                    && fixes.joined.insert((
                        at.sources[s].piece.min(at.sources[t].piece),
                        at.sources[s].piece.max(at.sources[t].piece),
                    ))
                {
                    learnt = true;
                    continue;
                }
                pairs.push((s, t));
            }
        }
        to_fix.extend(pieces_of_faces);
    }
    to_fix.sort_unstable();
    to_fix.dedup();
    // Sheets that rounding made cross, with nothing merged to split: a
    // shell thinner than `f64` can hold is left out whole before any of
    // its points is moved (moving them folds its neighbours in turn).
    if !learnt && drop_thin_shells(fixes, at, proven.written, &named, &pieces_of_polygon) {
        return true;
    }
    learnt |= fix_pieces(fixes, at, &to_fix, &pairs);
    if !learnt {
        // A defect between two pieces may be a sliver beside them that
        // rounding flattened (a vertex on the line of a neighbour's edge):
        // their neighbours around each vertex may hold what to fix.
        let corners: HashSet<usize> = to_fix
            .iter()
            .flat_map(|&i| at.soup.polygons[i].vertices.iter().copied())
            .collect();
        let around: Vec<usize> = (0..at.soup.polygons.len())
            .filter(|&i| {
                at.soup.polygons[i]
                    .vertices
                    .iter()
                    .any(|v| corners.contains(v))
            })
            .collect();
        learnt |= fix_pieces(fixes, at, &around, &[]);
    }
    if !learnt {
        learnt |= drop_thin_shells(fixes, at, proven.written, &named, &pieces_of_polygon);
    }
    learnt
}

/// Leaves out every shell of `written` (the written result, or the soup of
/// pieces when it could not be built) that a defect names (`named`
/// polygons) and that is thinner than `f64` can hold (its volume below its area times
/// the largest reach of a fix): a sliver between two near-coincident
/// sheets whose faces rounding made cross or turn inside out. Its exact
/// volume is below what the result's coordinates can express. Returns
/// whether any was left out.
fn drop_thin_shells(
    fixes: &mut Fixes,
    at: &Round,
    written: &PolygonSoup,
    named: &[usize],
    pieces_of: &dyn Fn(usize) -> Option<Vec<usize>>,
) -> bool {
    let n = written.polygons.len();
    // Shells: written polygons joined across the edges they share.
    let mut shells = DisjointSets::new(n);
    let mut by_edge: HashMap<(usize, usize), usize> = HashMap::default();
    for (f, polygon) in written.polygons.iter().enumerate() {
        let v = &polygon.vertices;
        for k in 0..v.len() {
            let (a, b) = (v[k], v[(k + 1) % v.len()]);
            if let Some(&g) = by_edge.get(&(a.min(b), a.max(b))) {
                shells.union(f, g);
            } else {
                by_edge.insert((a.min(b), a.max(b)), f);
            }
        }
    }
    let shell_of: Vec<usize> = (0..n).map(|f| shells.find(f)).collect();
    let named: HashSet<usize> = named
        .iter()
        .filter_map(|&f| shell_of.get(f).copied())
        .collect();
    let ulp = |x: f64| (x.next_up() - x).max(f64::MIN_POSITIVE);
    let (lo, hi) = at.soup.positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let largest = lo.abs().max(hi.abs()).max_element();
    let thickness = (MIN_REACH_ULPS * ulp(largest)).max((hi - lo).length() * MAX_REACH_OF_SIZE);
    let mut learnt = false;
    for shell in named {
        let faces: Vec<usize> = (0..n).filter(|&f| shell_of[f] == shell).collect();
        let origin = written.positions[written.polygons[faces[0]].vertices[0]];
        let (mut volume, mut area) = (0.0, 0.0);
        for &f in &faces {
            let v = &written.polygons[f].vertices;
            for k in 1..v.len().saturating_sub(1) {
                let [a, b, c] = [v[0], v[k], v[k + 1]].map(|i| written.positions[i] - origin);
                volume += a.dot(b.cross(c)) / 6.0;
                area += (b - a).cross(c - a).length() / 2.0;
            }
        }
        if volume.abs() > area * thickness {
            continue;
        }
        for &f in &faces {
            for i in pieces_of(f).unwrap_or_default() {
                learnt |= fixes.dropped.insert(at.sources[i].piece);
            }
        }
    }
    learnt
}

/// Whether written polygons `f` and `g` share an edge and, together, are
/// flat within half the validator's planarity tolerance: two pieces of
/// near-coplanar sheets that one polygon face can replace.
fn flat_together(written: &PolygonSoup, f: usize, g: usize) -> bool {
    let (pf, pg) = (&written.polygons[f].vertices, &written.polygons[g].vertices);
    let shared = pf.iter().filter(|v| pg.contains(v)).count();
    if shared < 2 {
        return false;
    }
    let (lo, hi) = written.positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let limit = 0.5 * Tolerance::default().planarity_limit((hi - lo).length());
    let points: Vec<DVec3> = pf
        .iter()
        .chain(pg.iter().filter(|v| !pf.contains(v)))
        .map(|&v| written.positions[v])
        .collect();
    Plane::try_fit_newell(&points).is_ok_and(|fit| fit.max_deviation <= limit)
}

/// An edge between soup vertices `p` and `q` used by four faces: two
/// sheets touching along it (a slit inside a face) whose copies of the
/// edge end at the same two vertices, which a file names the same edge.
/// Splitting it at its midpoint gives each sheet a vertex of its own
/// there. Returns whether the split is new (and the edge long enough).
fn split_touching_edge(fixes: &mut Fixes, at: &Round, p: usize, q: usize) -> bool {
    let (a, b) = (at.slots[p], at.slots[q]);
    // Once per edge: the halves of a split edge that still touch along
    // their length are sheets that cross there, for the other fixes.
    if fixes.is_made(a) || fixes.is_made(b) || !fixes.try_slit(a, b) {
        return false;
    }
    let (pa, pb) = (at.soup.positions[p], at.soup.positions[q]);
    let middle = pa + (pb - pa) * 0.5;
    if middle == pa || middle == pb {
        return false;
    }
    let m = fixes.make_point(middle);
    fixes.split(a, b, m)
}

/// The most a fix may move a point, as a fraction of the result's size
/// (2^-28, 4e-9), except that a few units in the last place are always
/// allowed ([`MIN_REACH_ULPS`]) where `f64` is coarser than that.
const MAX_REACH_OF_SIZE: f64 = 1.0 / (1u64 << 28) as f64;

/// The reach in units in the last place that every fix may take, however
/// small the result.
const MIN_REACH_ULPS: f64 = 64.0;

/// The most units in the last place (of the point's largest coordinate) a
/// fix may move a point by: 2^24, a relative 4e-9. Features this small
/// only need collapsing where sheets meet at an angle so small that `f64`
/// cannot keep them apart (copies turned by 1e-11 rad); most fixes move a
/// point by a few units.
const MAX_REACH_ULPS: f64 = 16_777_216.0;

/// Fixes the pieces (soup triangles) a defect names, by the smallest
/// change that removes a feature too small for `f64`: an edge of a piece
/// collapsed, a vertex too close to the opposite edge put on it (the edge
/// split there, so the piece flattens and its neighbour across the edge
/// bends through the vertex), or, for two pieces that meet (`pairs`), their
/// closest vertices collapsed (sheets closer than `f64` can keep apart).
/// Points the result shares with an operand move only when nothing else
/// helps. The reach grows from a few units in the last place until
/// something can be fixed (see [`MAX_REACH_ULPS`]). Returns whether
/// anything changed.
fn fix_pieces(fixes: &mut Fixes, at: &Round, pieces: &[usize], pairs: &[(usize, usize)]) -> bool {
    let ulp = |p: DVec3| {
        let m = p.abs().max_element();
        (m.next_up() - m).max(f64::MIN_POSITIVE)
    };
    // A fix never moves a point by more than a small fraction of the
    // result's size, however coarse `f64` is where it sits.
    let (lo, hi) = at.soup.positions.iter().fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), &p| (lo.min(p), hi.max(p)),
    );
    let cap = (hi - lo).length() * MAX_REACH_OF_SIZE;
    let corners = |i: usize| -> Option<[usize; 3]> {
        let [a, b, c] = at.soup.polygons.get(i)?.vertices[..] else {
            return None;
        };
        Some([a, b, c])
    };
    for move_exact in [false, true] {
        let mut reach = 4.0;
        while reach <= MAX_REACH_ULPS {
            let within = |u: f64| (reach * u).min((MIN_REACH_ULPS * u).max(cap));
            let movable = |v: usize| move_exact || !fixes.exact(at.rounded, at.slots[v]);
            let mut collapses: Vec<(usize, usize)> = Vec::new();
            let mut splits: Vec<(usize, usize, usize)> = Vec::new();
            for v in pieces.iter().filter_map(|&i| corners(i)) {
                let p = v.map(|k| at.soup.positions[k]);
                // Every edge within reach with a point that may move.
                let before = collapses.len();
                for k in 0..3 {
                    let (a, b) = (k, (k + 1) % 3);
                    let length = (p[a] - p[b]).length();
                    if (movable(v[a]) || movable(v[b]))
                        && length <= within(ulp(p[a]).max(ulp(p[b])))
                    {
                        collapses.push((v[a], v[b]));
                    }
                }
                if collapses.len() > before {
                    continue;
                }
                // A vertex within reach of the opposite edge.
                let near = (0..3)
                    .filter(|&k| movable(v[k]))
                    .map(|k| {
                        let (a, b) = (p[(k + 1) % 3], p[(k + 2) % 3]);
                        (k, distance_to_segment(p[k], a, b))
                    })
                    .filter(|&(k, d)| d <= within(ulp(p[k])))
                    .min_by(|x, y| x.1.total_cmp(&y.1));
                if let Some((k, _)) = near {
                    splits.push((v[(k + 1) % 3], v[(k + 2) % 3], v[k]));
                }
            }
            for (s, t) in pairs
                .iter()
                .filter_map(|&(s, t)| Some((corners(s)?, corners(t)?)))
            {
                // The closest two distinct vertices, one of each.
                let closest = s
                    .iter()
                    .flat_map(|&a| t.iter().map(move |&b| (a, b)))
                    .filter(|&(a, b)| a != b && (movable(a) || movable(b)))
                    .map(|(a, b)| {
                        let (pa, pb) = (at.soup.positions[a], at.soup.positions[b]);
                        ((pa - pb).length(), a, b, ulp(pa).max(ulp(pb)))
                    })
                    .filter(|&(d, _, _, u)| d <= within(u))
                    .min_by(|x, y| x.0.total_cmp(&y.0));
                if let Some((_, a, b, _)) = closest {
                    collapses.push((a, b));
                }
            }
            let mut learnt = false;
            for (a, b) in collapses {
                learnt |= fixes.collapse(at.rounded, at.slots[a], at.slots[b], move_exact);
            }
            for (a, b, at_vertex) in splits {
                learnt |= fixes.split(at.slots[a], at.slots[b], at.slots[at_vertex]);
            }
            if learnt {
                return true;
            }
            reach *= 4.0;
        }
    }
    false
}

/// The distance from `p` to the segment `a b` (a rounded measure, used
/// only to choose which feature is too small, never for a sign).
fn distance_to_segment(p: DVec3, a: DVec3, b: DVec3) -> f64 {
    let d = b - a;
    let length = d.length_squared();
    if length == 0.0 {
        return (p - a).length();
    }
    let t = ((p - a).dot(d) / length).clamp(0.0, 1.0);
    (p - (a + d * t)).length()
}

/// Each operand face the result's faces came from, once, in the order of
/// the faces; and for each face with a source, its index in that list.
fn origins_of(solid: &Solid, sources: &[PieceSource]) -> (Vec<FaceOrigin>, Vec<(FaceId, usize)>) {
    let mut origins = Vec::new();
    // Per operand, the index of each of its faces in `origins`.
    let operands = sources.iter().map(|s| s.origin.operand + 1).max();
    let mut origin_index: Vec<SecondaryMap<FaceId, usize>> =
        vec![SecondaryMap::new(); operands.unwrap_or(0)];
    let mut renumbered = Vec::with_capacity(solid.face_count());
    for (f, face) in solid.faces() {
        let Some(i) = face.attributes.source_index else {
            continue;
        };
        let origin = sources[i].origin;
        let known = &mut origin_index[origin.operand];
        let index = match known.get(origin.face) {
            Some(&index) => index,
            None => {
                origins.push(origin);
                known.insert(origin.face, origins.len() - 1);
                origins.len() - 1
            }
        };
        renumbered.push((f, index));
    }
    (origins, renumbered)
}

/// Validates `solid` as it would be written ([`written_soup`]): every rule,
/// the exact self-intersection check included; the empty solid is valid.
///
/// # Errors
///
/// [`BooleanError::InvalidResult`] with the located defects.
pub(crate) fn prove(solid: &Solid) -> Result<Report, BooleanError> {
    let (written, _) = written_soup(solid);
    let report = validate_soup(&written, None, &Options::default())
        .map_err(|e| BooleanError::not_built(e.to_string()))?;
    if report.is_valid() {
        Ok(report)
    } else {
        Err(invalid(&report, &written, |_| None))
    }
}
