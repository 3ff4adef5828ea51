//! Boundary evaluation: exact booleans of polyhedral solids that produce a
//! valid winged-edge solid.
//!
//! The boundaries of `a` and `b` are cut where they meet, and membership
//! classification decides which cut pieces bound the result (Requicha and
//! Voelcker's boundary evaluation, 1985). The stages, one file
//! each, in the order they run:
//!
//! 0. `operand`: each face triangulated exactly, a BVH over the triangles;
//!    operands that are not valid closed solids are refused first.
//! 1. `contacts`: the BVH pair walk hands over triangle pairs whose boxes
//!    meet;
//! 2. `intersect`: each pair's contact (points and segments, or a coplanar
//!    overlap) is decided with exact predicates, new points kept implicit;
//!    2b. `crossings` (three or more operands): segments of different
//!    operands crossing inside a triangle; then `points`: every point
//!    once, by exact comparison.
//! 3. `split`: each cut triangle triangulated along its segments.
//! 4. `classify`: pieces grouped into patches, one exact membership
//!    decision per patch;
//! 5. `select`: the operator's rule.
//! 6. the kept pieces, wound to face out of the result (in `combine`).
//! 7. `assemble`: points rounded to `f64`, the soup of kept pieces with
//!    the output's fixes applied; `merge`: the solid built and coplanar
//!    neighbours merged back into polygon faces (with rings) by Euler
//!    operators.
//! 8. `output`: what would be written proven valid by the validator
//!    (closed, oriented, no self-intersection, planar faces), in rounds
//!    that fix what rounding broke; `weld` is its last resort; `failure`
//!    says what could not be fixed.
//!
//! No sign is decided on a rounded constructed point: implicit points
//! ([`ImplicitPoint`]) carry their
//! definitions until the output is written.

mod apart;
mod assemble;
mod classify;
mod contacts;
mod crossings;
mod error;
mod expression;
mod failure;
mod intersect;
mod merge;
mod nearby;
mod operand;
mod output;
mod points;
mod select;
mod self_arrangement;
mod self_pairs;
mod sparse;
mod split;
mod stats;
mod weld;

use crate::SetOp;
use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::time::Instant;

use rayon::prelude::*;

use crate::geom::implicit::ImplicitPoint;
use crate::mesh::Solid;
use crate::validate::Report;

pub use error::BooleanError;
pub use expression::Expression;
pub use operand::FaceOrigin;
pub use self_arrangement::{SelfArrangement, arrange_soup};
pub use stats::{BooleanStats, OutputWork};

use classify::{Partner, Piece};
use crossings::{Line, Segment};
use intersect::Carrier;
use nearby::Nearby;
use operand::Prepared;
use points::PointTable;
use sparse::SparseExpression;

/// The result of a boolean: a valid solid, where each face came from, and
/// the validator's report on it.
#[derive(Clone, Debug)]
pub struct Boolean {
    /// The result (possibly empty: no faces).
    pub solid: Solid,
    /// For each face of `solid` (by its `attributes.source_index`), the
    /// operand face it is part of.
    pub origins: Vec<FaceOrigin>,
    /// The validator's report on the result.
    pub report: Report,
    /// Time and work.
    pub stats: BooleanStats,
}

/// What a boolean checks before it starts.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BooleanOptions {
    /// Validate both operands (closed, oriented, no self-intersection)
    /// before any work; on by default. Turn off only for operands known to
    /// be valid (the output of an earlier boolean, a builder's solid): the
    /// proof of the result relies on it, testing for self-intersection
    /// only the faces the boolean changed.
    pub check_operands: bool,
    /// The most pairs of touching triangles a boolean takes on: each costs
    /// a few hundred bytes through the later stages, so the default
    /// ([`MAX_CONTACTS`]) keeps a boolean within a few gigabytes and refuses
    /// beyond it instead of running out of memory.
    pub max_contacts: usize,
    /// Take an operand that is not a valid solid (self-intersecting,
    /// overlapping or nested shells, turned inside out) by its winding
    /// number instead of refusing it: a point is in the operand when its
    /// winding number is positive. The operand is first arranged against
    /// itself ([`arrange_soup`]); it must still be closed (every edge run
    /// as often one way as the other: holes are `repair`'s to fill). The
    /// result's [`FaceOrigin`]s then name faces of that arranged operand.
    /// Off by default.
    pub resolve_operands: bool,
}

/// The default limit on touching triangle pairs: 10 million.
pub const MAX_CONTACTS: usize = 10_000_000;

impl Default for BooleanOptions {
    fn default() -> BooleanOptions {
        BooleanOptions {
            check_operands: true,
            max_contacts: MAX_CONTACTS,
            resolve_operands: false,
        }
    }
}

impl Solid {
    /// `self ∪ other`, exact; see [`boolean`].
    ///
    /// # Errors
    ///
    /// As for [`boolean`].
    pub fn union(&self, other: &Solid) -> Result<Boolean, BooleanError> {
        boolean(self, other, SetOp::Union, BooleanOptions::default())
    }

    /// `self ∩ other`, exact; see [`boolean`].
    ///
    /// # Errors
    ///
    /// As for [`boolean`].
    pub fn intersection(&self, other: &Solid) -> Result<Boolean, BooleanError> {
        boolean(self, other, SetOp::Intersection, BooleanOptions::default())
    }

    /// `self − other`, exact; see [`boolean`].
    ///
    /// # Errors
    ///
    /// As for [`boolean`].
    pub fn difference(&self, other: &Solid) -> Result<Boolean, BooleanError> {
        boolean(self, other, SetOp::Difference, BooleanOptions::default())
    }
}

/// The regularized boolean `a op b` of two closed solids, as a valid
/// winged-edge solid: [`combine`] with the expression `0 op 1`.
///
/// # Errors
///
/// As for [`combine`].
pub fn boolean(
    a: &Solid,
    b: &Solid,
    operation: SetOp,
    options: BooleanOptions,
) -> Result<Boolean, BooleanError> {
    let expression = Expression::of(operation, Expression::Operand(0), Expression::Operand(1));
    combine(&[a, b], &expression, options)
}

/// The regularized set `expression` of closed solids (`operands`, named
/// in the expression by index), evaluated in one pass as a valid
/// winged-edge solid: every operand's surface is cut by every other's, and
/// every point made — an edge through a face, two coplanar edges crossing,
/// three faces meeting — stays implicit until the result is written, so a
/// whole CSG tree is as exact as one boolean.
///
/// # Errors
///
/// [`BooleanError::UnknownOperand`] when the expression names an index
/// past the list; [`BooleanError::InvalidOperand`] when an operand is not
/// a valid closed solid (with the validator's located defects);
/// [`BooleanError::NotBuilt`] when the result is not a 2-manifold (solids
/// touching only along an edge or at a vertex);
/// [`BooleanError::InvalidResult`] when rounding the result's constructed
/// points to `f64` broke it (located); [`BooleanError::Inconsistent`]
/// never, unless wingedge has a defect.
pub fn combine(
    operands: &[&Solid],
    expression: &Expression,
    options: BooleanOptions,
) -> Result<Boolean, BooleanError> {
    let first = combine_once(operands, expression, options);
    let Err(BooleanError::InvalidResult { .. } | BooleanError::NotBuilt { .. }) = &first else {
        return first;
    };
    // Rounding broke the result: the operands are moved where they lie
    // closer together than `f64` can keep apart (`weld::retried`), proven
    // valid, and evaluated again.
    let named = expression.operands();
    let solids: Vec<&Solid> = named.iter().map(|&k| operands[k]).collect();
    let again = BooleanOptions {
        check_operands: false,
        ..options
    };
    let attempt = |moved_solids: &[Solid], moved: usize| {
        if moved_solids.iter().any(|s| check_operand(s, 0).is_err()) {
            return None;
        }
        let mut all: Vec<&Solid> = operands.to_vec();
        for (&k, s) in named.iter().zip(moved_solids) {
            all[k] = s;
        }
        let mut result = combine_once(&all, expression, again).ok()?;
        result.stats.output.welded_vertices = moved;
        Some(result)
    };
    weld::retried(&solids, attempt).map_or(first, Ok)
}

/// [`combine`] once, on the operands as given.
fn combine_once(
    operands: &[&Solid],
    expression: &Expression,
    options: BooleanOptions,
) -> Result<Boolean, BooleanError> {
    let mut stats = BooleanStats::default();
    let named = expression.operands();
    if let Some(&operand) = named.iter().find(|&&k| k >= operands.len()) {
        return Err(BooleanError::UnknownOperand {
            operand,
            count: operands.len(),
        });
    }
    let clock = Instant::now();
    let mut resolved: Vec<Option<Solid>> = vec![None; operands.len()];
    if options.check_operands {
        let checks: Vec<Result<(), BooleanError>> = named
            .par_iter()
            .map(|&k| check_operand(operands[k], k))
            .collect();
        for (&k, check) in named.iter().zip(checks) {
            match check {
                Err(BooleanError::InvalidOperand { .. }) if options.resolve_operands => {
                    resolved[k] = Some(self_arrangement::resolve_operand(
                        operands[k],
                        k,
                        options.max_contacts,
                    )?);
                }
                other => other?,
            }
        }
    }
    let operands: Vec<&Solid> = operands
        .iter()
        .zip(&resolved)
        .map(|(&o, r)| r.as_ref().unwrap_or(o))
        .collect();
    let operands = operands.as_slice();
    stats.check_seconds = clock.elapsed().as_secs_f64();
    let Some(expression) = expression.without_empty(&|k| operands[k].face_count() == 0) else {
        return as_is(None, stats);
    };
    if let Expression::Operand(k) = expression {
        return as_is(Some((operands[k], k)), stats);
    }
    let named = expression.operands();
    let expression = expression.renumbered(&|k| named.binary_search(&k).unwrap_or(0));

    let clock = Instant::now();
    let prepared: Vec<Prepared> = named
        .par_iter()
        .map(|&k| Prepared::new(operands[k], k))
        .collect::<Result<_, _>>()?;
    let mut offsets = Vec::with_capacity(prepared.len());
    let mut base = 0u32;
    for p in &prepared {
        offsets.push(base);
        base += p.positions.len() as u32;
    }
    stats.prepare_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let mut all_contacts = Vec::new();
    // Only operands whose boxes meet can touch: pairs from an index of the
    // boxes, in the order of the all-pairs loop.
    let nearby = Nearby::new(prepared.iter().map(|p| p.bvh.bounds()).collect());
    for (i, j) in nearby.meeting_pairs() {
        let (a, b) = (&prepared[i], &prepared[j]);
        let found = contacts::contacts(a, b, offsets[i], offsets[j]);
        stats.contacts += found.len();
        if stats.contacts > options.max_contacts {
            return Err(BooleanError::TooLarge {
                contacts: stats.contacts,
                limit: options.max_contacts,
            });
        }
        all_contacts.push((i, j, found));
    }
    stats.intersect_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let vertices: Vec<glam::DVec3> = prepared
        .iter()
        .flat_map(|p| p.positions.iter().copied())
        .collect();
    let base = vertices.len();
    let mut made: Vec<ImplicitPoint> = Vec::new();
    let mut cuts: Vec<HashMap<u32, Cuts>> = vec![HashMap::default(); prepared.len()];
    let mut partners: Vec<HashMap<u32, Vec<Partner>>> = vec![HashMap::default(); prepared.len()];
    let mut candidates: Vec<u32> = Vec::new();
    for (i, j, found) in &all_contacts {
        for (ta, tb, contact) in found {
            let ids = contact.point_ids(base, &mut made);
            candidates.extend(&ids);
            candidates.extend(&contact.touched);
            let corners = [prepared[*i].corners(*ta), prepared[*j].corners(*tb)];
            for (mine, other, t, list, other_corners) in [
                (*i, *j, *ta, &contact.first_cuts, corners[1]),
                (*j, *i, *tb, &contact.second_cuts, corners[0]),
            ] {
                let entry = cuts[mine].entry(t).or_default();
                entry.points.extend(&ids);
                entry
                    .segments
                    .extend(list.iter().map(|&(from, to, along)| Segment {
                        ends: (ids[from as usize], ids[to as usize]),
                        operand: other,
                        line: match along {
                            Carrier::PlanesMeet => Line::Meets(other_corners),
                            Carrier::OtherEdge(k) => Line::Through(
                                other_corners[k as usize],
                                other_corners[(k as usize + 1) % 3],
                            ),
                        },
                    }));
            }
            if let Some(same) = contact.coplanar_same {
                partners[*i].entry(*ta).or_default().push((*j, *tb, same));
                partners[*j].entry(*tb).or_default().push((*i, *ta, same));
            }
        }
    }
    drop(all_contacts);
    if prepared.len() > 2 {
        stats.segment_crossings =
            cross_segments(&prepared, &vertices, &mut made, &mut cuts, &mut candidates);
    }
    stats.new_points = made.len();
    let table = PointTable::new(vertices, made, candidates);
    stats.points_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    stats.cut_triangles = cuts.iter().map(HashMap::len).sum();
    let mut all_pieces = Vec::with_capacity(prepared.len());
    let mut constrained: HashSet<(u32, u32)> = HashSet::default();
    // Operands side by side on all cores (a union of many small operands
    // would otherwise hand each one's few triangles between threads).
    let split: Vec<Result<Pieces, BooleanError>> = prepared
        .par_iter()
        .enumerate()
        .map(|(slot, operand)| pieces(&table, operand, offsets[slot], &cuts[slot]))
        .collect();
    for result in split {
        let (p, c) = result?;
        all_pieces.push(p);
        constrained.extend(c);
    }
    stats.split_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let sparse = SparseExpression::new(&expression);
    let decisions: Vec<Vec<Option<bool>>> = (0..prepared.len())
        .into_par_iter()
        .map(|slot| {
            classify::keep_pieces(
                &table,
                &prepared,
                &nearby,
                slot,
                &all_pieces[slot],
                &constrained,
                &partners[slot],
                &sparse,
            )
        })
        .collect::<Result<_, _>>()?;
    stats.classify_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let kept_by_operand: Vec<Vec<assemble::KeptPiece>> = prepared
        .par_iter()
        .enumerate()
        .map(|(slot, operand)| {
            all_pieces[slot]
                .iter()
                .zip(&decisions[slot])
                .filter_map(|(piece, decision)| {
                    let flip = (*decision)?;
                    let [x, y, z] = piece.corners;
                    let [p, q, r] = operand.corners(piece.triangle);
                    let mut own = operand.triangles[piece.triangle as usize]
                        .map(|i| table.canonical[(i + offsets[slot]) as usize]);
                    own.sort_unstable();
                    let mut corners = piece.corners;
                    corners.sort_unstable();
                    let changed = corners != own;
                    Some(assemble::KeptPiece {
                        corners: if flip { [x, z, y] } else { [x, y, z] },
                        operand: slot,
                        face: operand.faces[piece.triangle as usize],
                        plane: if flip { [p, r, q] } else { [p, q, r] },
                        changed,
                        alone: !changed && operand.face_is_one_triangle(piece.triangle),
                    })
                })
                .collect()
        })
        .collect();
    let kept: Vec<assemble::KeptPiece> = kept_by_operand.into_iter().flatten().collect();
    let (solid, origins, report, proof_seconds, work) =
        output::build_and_prove(&table, &kept, &prepared)?;
    stats.proof_seconds = proof_seconds;
    stats.output = work;
    stats.output_seconds = clock.elapsed().as_secs_f64() - proof_seconds;
    Ok(Boolean {
        solid,
        origins,
        report,
        stats,
    })
}

/// An operand's pieces and the edges of them that lie on segments.
pub(super) type Pieces = (Vec<Piece>, Vec<(u32, u32)>);

/// The result when it is empty (`None`) or one operand as it is.
fn as_is(chosen: Option<(&Solid, usize)>, stats: BooleanStats) -> Result<Boolean, BooleanError> {
    let Some((source, operand)) = chosen else {
        return Ok(Boolean {
            report: prove(&Solid::default())?,
            solid: Solid::default(),
            origins: Vec::new(),
            stats,
        });
    };
    let mut solid = source.clone();
    let faces: Vec<_> = solid.faces().map(|(f, _)| f).collect();
    let mut origins = Vec::with_capacity(faces.len());
    for f in faces {
        origins.push(FaceOrigin { operand, face: f });
        let mut attributes = solid.face(f).attributes.clone();
        attributes.source_index = Some(origins.len() - 1);
        solid.set_face_attributes(f, attributes);
    }
    Ok(Boolean {
        report: prove(&solid)?,
        solid,
        origins,
        stats,
    })
}

/// The points and segments found on one triangle (raw point indices).
#[derive(Clone, Debug, Default)]
pub(super) struct Cuts {
    pub points: Vec<u32>,
    pub segments: Vec<Segment>,
}

/// With three or more operands: the crossings of segments of different
/// operands inside each triangle, added to its points (and to the points
/// that may coincide with others). Returns how many were made.
pub(super) fn cross_segments(
    prepared: &[Prepared],
    vertices: &[glam::DVec3],
    made: &mut Vec<ImplicitPoint>,
    cuts: &mut [HashMap<u32, Cuts>],
    candidates: &mut Vec<u32>,
) -> usize {
    let base = vertices.len();
    let point = |i: u32| match vertices.get(i as usize) {
        Some(&v) => ImplicitPoint::Explicit(v),
        None => made[i as usize - base].clone(),
    };
    let mut found: Vec<(usize, u32, Vec<ImplicitPoint>)> = Vec::new();
    for (slot, operand) in prepared.iter().enumerate() {
        let mut triangles: Vec<(&u32, &Cuts)> = cuts[slot]
            .iter()
            .filter(|(_, cut)| {
                cut.segments
                    .iter()
                    .any(|s| s.operand != cut.segments[0].operand)
            })
            .collect();
        if triangles.is_empty() {
            continue;
        }
        triangles.sort_unstable_by_key(|(t, _)| **t);
        found.extend(
            triangles
                .par_iter()
                .map(|&(&t, cut)| {
                    let plane = operand.corners(t);
                    let (axis, _) = intersect::projection(&plane);
                    (
                        slot,
                        t,
                        crossings::crossings(plane, axis, &cut.segments, point),
                    )
                })
                .filter(|(_, _, points)| !points.is_empty())
                .collect::<Vec<_>>(),
        );
    }
    let mut count = 0;
    for (slot, t, points) in found {
        let Some(cut) = cuts[slot].get_mut(&t) else {
            continue;
        };
        for p in points {
            made.push(p);
            let id = (base + made.len() - 1) as u32;
            cut.points.push(id);
            candidates.push(id);
            count += 1;
        }
    }
    count
}

/// Refuses an operand that is not a valid closed solid.
fn check_operand(solid: &Solid, operand: usize) -> Result<(), BooleanError> {
    prove(solid).map(|_| ()).map_err(|e| match e {
        BooleanError::InvalidResult {
            validity, report, ..
        } => BooleanError::InvalidOperand {
            operand,
            validity,
            report,
        },
        other => other,
    })
}

/// Validates `solid` as it would be written ([`to_obj_string`]: polygons,
/// and faces with rings as their exact triangulations) with every rule,
/// the exact self-intersection check included; the empty solid is valid.
///
/// [`to_obj_string`]: crate::io::to_obj_string
///
/// # Errors
///
/// [`BooleanError::InvalidResult`] with the located defects.
pub fn prove(solid: &Solid) -> Result<Report, BooleanError> {
    output::prove(solid)
}

/// The pieces of every triangle of `operand`: whole triangles where
/// nothing cuts them, split ones elsewhere; and the constrained edges.
pub(super) fn pieces(
    table: &PointTable,
    operand: &Prepared,
    base: u32,
    cuts: &HashMap<u32, Cuts>,
) -> Result<Pieces, BooleanError> {
    let canonical = |i: u32| table.canonical[i as usize];
    let results: Vec<Result<Pieces, BooleanError>> = (0..operand.triangles.len() as u32)
        .into_par_iter()
        .map(|t| {
            let corners = operand.triangles[t as usize].map(|i| canonical(i + base));
            let Some(cut) = cuts.get(&t) else {
                return Ok((
                    vec![Piece {
                        corners,
                        triangle: t,
                    }],
                    Vec::new(),
                ));
            };
            let mut points: Vec<u32> = cut.points.iter().map(|&i| canonical(i)).collect();
            points.sort_unstable();
            points.dedup();
            let segments: Vec<(u32, u32)> = cut
                .segments
                .iter()
                .map(|s| (canonical(s.ends.0), canonical(s.ends.1)))
                .filter(|(i, j)| i != j)
                .collect();
            let (axis, _) = intersect::projection(&operand.corners(t));
            let split =
                split::split_triangle(table, corners, axis, &points, &segments).map_err(|e| {
                    BooleanError::Inconsistent(format!(
                        "cutting triangle {t} of operand {}: {}",
                        operand.index, e.0
                    ))
                })?;
            let pieces = split
                .triangles
                .into_iter()
                .map(|corners| Piece {
                    corners,
                    triangle: t,
                })
                .collect();
            Ok((pieces, split.constrained))
        })
        .collect();
    let mut all = Vec::new();
    let mut constrained = Vec::new();
    for r in results {
        let (p, c) = r?;
        all.extend(p);
        constrained.extend(c);
    }
    Ok((all, constrained))
}
