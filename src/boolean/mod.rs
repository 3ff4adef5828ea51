//! Boundary evaluation: exact booleans of polyhedral solids that produce a
//! valid winged-edge solid.
//!
//! The boundaries of `a` and `b` are cut where they meet, and membership
//! classification decides which cut pieces bound the result (Requicha and
//! Voelcker's boundary evaluation; the seeds' §9.5). The stages, one file
//! each, in the order they run:
//!
//! 1. `operand`: each face triangulated exactly, a BVH over the triangles;
//!    operands that are not valid closed solids are refused first.
//! 2. `intersect`: the BVH pair walk hands over triangle pairs whose boxes
//!    meet; each pair's contact (points and segments, or a coplanar overlap)
//!    is decided with exact predicates, new points kept implicit.
//! 3. `points`: every point once, by exact comparison.
//! 4. `split`: each cut triangle triangulated along its segments.
//! 5. `classify`: pieces grouped into patches, one exact membership
//!    decision per patch.
//! 6. `select`: the operator's rule.
//! 7. `assemble`: points rounded to `f64` (constructed points a few units
//!    in the last place from another snapped onto it), the solid built.
//! 8. `merge`: coplanar neighbours merged back into polygon faces (with
//!    rings) by Euler operators; then the result is proven valid by the
//!    validator (closed, oriented, no self-intersection).
//!
//! No sign is decided on a rounded constructed point: implicit points
//! ([`ImplicitPoint`]) carry their
//! definitions until the output is written.

mod assemble;
mod classify;
mod error;
mod intersect;
mod merge;
mod operand;
mod points;
mod select;
mod split;

use rustc_hash::{FxHashMap as HashMap, FxHashSet as HashSet};
use std::time::Instant;

use rayon::prelude::*;

use crate::geom::implicit::ImplicitPoint;
use crate::mesh::Solid;
use crate::validate::Report;

pub use error::BooleanError;
pub use operand::{FaceOrigin, Operand};

use classify::{Partner, Piece};
use intersect::{Contact, PointRef, Tri};
use operand::Prepared;
use points::PointTable;

/// A regularized set operation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Operation {
    /// `a ∪ b`.
    Union,
    /// `a ∩ b`.
    Intersection,
    /// `a − b`.
    Difference,
}

/// Where a boolean spent its time, in seconds, and how much work it found.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BooleanStats {
    /// Checking both operands with the validator.
    pub check_seconds: f64,
    /// Triangulating the operands and building their BVHs and classifiers.
    pub prepare_seconds: f64,
    /// The pair walk and the exact contact of each candidate pair.
    pub intersect_seconds: f64,
    /// Merging equal points.
    pub points_seconds: f64,
    /// Cutting triangles along their segments.
    pub split_seconds: f64,
    /// Patches and membership.
    pub classify_seconds: f64,
    /// Rounding, snapping, building the result and merging its faces.
    pub output_seconds: f64,
    /// Proving the result valid with the validator.
    pub proof_seconds: f64,
    /// Pairs of triangles that meet.
    pub contacts: usize,
    /// Points made by the intersection (before merging equal ones).
    pub new_points: usize,
    /// Triangles that were cut.
    pub cut_triangles: usize,
}

impl BooleanStats {
    /// The time of each stage, in pipeline order, named as in reports
    /// (`check`, `prepare`, `intersect`, `points`, `split`, `classify`,
    /// `output`, `proof`).
    #[must_use]
    pub fn stages(&self) -> [(&'static str, f64); 8] {
        [
            ("check", self.check_seconds),
            ("prepare", self.prepare_seconds),
            ("intersect", self.intersect_seconds),
            ("points", self.points_seconds),
            ("split", self.split_seconds),
            ("classify", self.classify_seconds),
            ("output", self.output_seconds),
            ("proof", self.proof_seconds),
        ]
    }

    /// The stages' times as `name 0.123, …`, in pipeline order.
    #[must_use]
    pub fn stages_text(&self) -> String {
        self.stages()
            .iter()
            .map(|(name, seconds)| format!("{name} {seconds:.3}"))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

impl std::ops::AddAssign<&BooleanStats> for BooleanStats {
    /// Sums the time and work of several booleans (a tree's).
    fn add_assign(&mut self, one: &BooleanStats) {
        self.check_seconds += one.check_seconds;
        self.prepare_seconds += one.prepare_seconds;
        self.intersect_seconds += one.intersect_seconds;
        self.points_seconds += one.points_seconds;
        self.split_seconds += one.split_seconds;
        self.classify_seconds += one.classify_seconds;
        self.output_seconds += one.output_seconds;
        self.proof_seconds += one.proof_seconds;
        self.contacts += one.contacts;
        self.new_points += one.new_points;
        self.cut_triangles += one.cut_triangles;
    }
}

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
    /// be valid (the output of an earlier boolean, a builder's solid).
    pub check_operands: bool,
    /// The most pairs of touching triangles a boolean takes on: each costs
    /// a few hundred bytes through the later stages, so the default
    /// ([`MAX_CONTACTS`]) keeps a boolean within a few gigabytes and refuses
    /// beyond it instead of running out of memory.
    pub max_contacts: usize,
}

/// The default limit on touching triangle pairs: 10 million.
pub const MAX_CONTACTS: usize = 10_000_000;

impl Default for BooleanOptions {
    fn default() -> BooleanOptions {
        BooleanOptions {
            check_operands: true,
            max_contacts: MAX_CONTACTS,
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
        boolean(self, other, Operation::Union, BooleanOptions::default())
    }

    /// `self ∩ other`, exact; see [`boolean`].
    ///
    /// # Errors
    ///
    /// As for [`boolean`].
    pub fn intersection(&self, other: &Solid) -> Result<Boolean, BooleanError> {
        boolean(
            self,
            other,
            Operation::Intersection,
            BooleanOptions::default(),
        )
    }

    /// `self − other`, exact; see [`boolean`].
    ///
    /// # Errors
    ///
    /// As for [`boolean`].
    pub fn difference(&self, other: &Solid) -> Result<Boolean, BooleanError> {
        boolean(
            self,
            other,
            Operation::Difference,
            BooleanOptions::default(),
        )
    }
}

/// The regularized boolean `a op b` of two closed solids, as a valid
/// winged-edge solid.
///
/// # Errors
///
/// [`BooleanError::InvalidOperand`] when an operand is not a valid closed
/// solid (with the validator's located defects);
/// [`BooleanError::NotBuilt`] when the result is not a 2-manifold (solids
/// touching only along an edge or at a vertex);
/// [`BooleanError::InvalidResult`] when rounding the result's constructed
/// points to `f64` broke it (located); [`BooleanError::Inconsistent`]
/// never, unless wingedge has a defect.
pub fn boolean(
    a: &Solid,
    b: &Solid,
    operation: Operation,
    options: BooleanOptions,
) -> Result<Boolean, BooleanError> {
    let mut stats = BooleanStats::default();
    let clock = Instant::now();
    if options.check_operands {
        check_operand(a, Operand::First)?;
        check_operand(b, Operand::Second)?;
    }
    stats.check_seconds = clock.elapsed().as_secs_f64();
    if a.face_count() == 0 || b.face_count() == 0 {
        return with_empty_operand(a, b, operation, stats);
    }

    let clock = Instant::now();
    let (first, second) = rayon::join(
        || Prepared::new(a, Operand::First),
        || Prepared::new(b, Operand::Second),
    );
    let (first, second) = (first?, second?);
    stats.prepare_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let offset = first.positions.len() as u32;
    let contacts = contacts(&first, &second, offset);
    stats.contacts = contacts.len();
    if contacts.len() > options.max_contacts {
        return Err(BooleanError::TooLarge {
            contacts: contacts.len(),
            limit: options.max_contacts,
        });
    }
    stats.intersect_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let vertices: Vec<glam::DVec3> = first
        .positions
        .iter()
        .chain(&second.positions)
        .copied()
        .collect();
    let base = vertices.len();
    let mut made: Vec<ImplicitPoint> = Vec::new();
    let mut cuts: [HashMap<u32, Cuts>; 2] = [HashMap::default(), HashMap::default()];
    let mut partners: [HashMap<u32, Vec<Partner>>; 2] = [HashMap::default(), HashMap::default()];
    let mut candidates: Vec<u32> = Vec::new();
    for (ta, tb, contact) in &contacts {
        let ids: Vec<u32> = contact
            .points
            .iter()
            .map(|r| match r {
                PointRef::Vertex(i) => *i,
                PointRef::New(p) => {
                    made.push(*p);
                    (base + made.len() - 1) as u32
                }
            })
            .collect();
        candidates.extend(&ids);
        candidates.extend(&contact.touched);
        for (side, t, segments) in [
            (0, *ta, &contact.first_cuts),
            (1, *tb, &contact.second_cuts),
        ] {
            let entry = cuts[side].entry(t).or_default();
            entry.points.extend(&ids);
            entry.segments.extend(
                segments
                    .iter()
                    .map(|&(i, j)| (ids[i as usize], ids[j as usize])),
            );
        }
        if let Some(same) = contact.coplanar_same {
            partners[0].entry(*ta).or_default().push((*tb, same));
            partners[1].entry(*tb).or_default().push((*ta, same));
        }
    }
    stats.new_points = made.len();
    let table = PointTable::new(vertices, made, candidates);
    stats.points_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    stats.cut_triangles = cuts[0].len() + cuts[1].len();
    let (pieces_a, constrained_a) = pieces(&table, &first, 0, &cuts[0])?;
    let (pieces_b, constrained_b) = pieces(&table, &second, offset, &cuts[1])?;
    let constrained: HashSet<(u32, u32)> = constrained_a.into_iter().chain(constrained_b).collect();
    stats.split_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let (labels_a, labels_b) = rayon::join(
        || {
            classify::label_pieces(
                &table,
                &first,
                &pieces_a,
                &constrained,
                &partners[0],
                &second,
            )
        },
        || {
            classify::label_pieces(
                &table,
                &second,
                &pieces_b,
                &constrained,
                &partners[1],
                &first,
            )
        },
    );
    let (labels_a, labels_b) = (labels_a?, labels_b?);
    stats.classify_seconds = clock.elapsed().as_secs_f64();

    let clock = Instant::now();
    let mut kept = Vec::new();
    for (operand, pieces, labels) in [
        (&first, &pieces_a, &labels_a),
        (&second, &pieces_b, &labels_b),
    ] {
        for (piece, &label) in pieces.iter().zip(labels.iter()) {
            if let Some(flip) = select::keep(operation, operand.side, label) {
                let [x, y, z] = piece.corners;
                let [p, q, r] = operand.corners(piece.triangle);
                kept.push(assemble::KeptPiece {
                    corners: if flip { [x, z, y] } else { [x, y, z] },
                    side: operand.side,
                    face: operand.faces[piece.triangle as usize],
                    plane: if flip { [p, r, q] } else { [p, q, r] },
                });
            }
        }
    }
    let (soup, sources) = assemble::soup_of(&table, &kept, [&first, &second]);
    let (solid, origins, report, proof_seconds) = assemble::build_and_prove(&soup, &sources)?;
    stats.proof_seconds = proof_seconds;
    stats.output_seconds = clock.elapsed().as_secs_f64() - proof_seconds;
    Ok(Boolean {
        solid,
        origins,
        report,
        stats,
    })
}

/// An operand's pieces and the edges of them that lie on segments.
type Pieces = (Vec<Piece>, Vec<(u32, u32)>);

/// A boolean with an empty operand: one operand or nothing, as it is.
fn with_empty_operand(
    a: &Solid,
    b: &Solid,
    operation: Operation,
    stats: BooleanStats,
) -> Result<Boolean, BooleanError> {
    let chosen = match operation {
        Operation::Union if a.face_count() == 0 => Some((b, Operand::Second)),
        Operation::Union | Operation::Difference if b.face_count() == 0 => {
            Some((a, Operand::First))
        }
        _ => None,
    };
    let Some((source, side)) = chosen else {
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
        origins.push(FaceOrigin { side, face: f });
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
struct Cuts {
    points: Vec<u32>,
    segments: Vec<(u32, u32)>,
}

/// Refuses an operand that is not a valid closed solid.
fn check_operand(solid: &Solid, side: Operand) -> Result<(), BooleanError> {
    prove(solid).map(|_| ()).map_err(|e| match e {
        BooleanError::InvalidResult { validity, report } => BooleanError::InvalidOperand {
            side,
            validity,
            report,
        },
        other => other,
    })
}

/// Validates `solid` with every rule (the exact self-intersection check
/// included) on the exact triangulations of its faces, and its rings by
/// their own checks; an empty solid (no faces) is valid.
///
/// # Errors
///
/// [`BooleanError::InvalidResult`] with the located defects.
pub fn prove(solid: &Solid) -> Result<Report, BooleanError> {
    assemble::prove(solid)
}

/// Every pair of triangles that meet, with its contact, in an order fixed
/// by the two BVHs.
fn contacts(first: &Prepared, second: &Prepared, offset: u32) -> Vec<(u32, u32, Contact)> {
    let tri = |operand: &Prepared, t: u32, base: u32| Tri {
        corners: operand.corners(t),
        ids: operand.triangles[t as usize].map(|i| i + base),
    };
    first.bvh.par_leaf_pairs(&second.bvh, |la, lb, found| {
        let (Some(items_a), Some(items_b)) = (first.bvh.leaf(la), second.bvh.leaf(lb)) else {
            return;
        };
        for pa in items_a.range() {
            let ta = first.order[pa];
            let box_a = first.bounds[ta as usize];
            for pb in items_b.range() {
                let tb = second.order[pb];
                if box_a.intersection(second.bounds[tb as usize]).is_empty() {
                    continue;
                }
                if let Some(contact) =
                    intersect::contact(&tri(first, ta, 0), &tri(second, tb, offset))
                {
                    found.push((ta, tb, contact));
                }
            }
        }
    })
}

/// The pieces of every triangle of `operand`: whole triangles where
/// nothing cuts them, split ones elsewhere; and the constrained edges.
fn pieces(
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
                .map(|&(i, j)| (canonical(i), canonical(j)))
                .filter(|(i, j)| i != j)
                .collect();
            let (axis, _) = intersect::projection(&operand.corners(t));
            let split =
                split::split_triangle(table, corners, axis, &points, &segments).map_err(|e| {
                    BooleanError::Inconsistent(format!(
                        "cutting triangle {t} of the {:?} operand: {}",
                        operand.side, e.0
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
