//! A tree evaluated by its structure: several booleans where that is
//! exact, one pass over the leaves where it is not.
//!
//! One pass over all leaves ([`combine`] with the tree's expression) cuts
//! every leaf by every other leaf it meets, so its cost follows the pairs
//! of leaves; a tree evaluated node by node costs what each node's result
//! holds, but rounds each intermediate result to `f64`, and a rounded
//! intermediate cut again would move the final result off the exact one.
//! This walk takes the node-by-node route only where no rounding happens:
//!
//! - a node whose two sides are each a leaf or an exact intermediate, all
//!   *axis-aligned* (every face in a plane `x`, `y` or `z` = constant, so
//!   that every point a boolean makes has coordinates of the operands'
//!   own), is evaluated on its own; its result is kept as an operand for
//!   the nodes above only if it is *exact* ([`OutputWork::is_exact`]:
//!   every point representable in `f64` as it is, nothing fixed), so that
//!   cutting it again is cutting the exact set. Axis-aligned trees (a
//!   Menger sponge, boxes on a grid) stay exact all the way up. Sides with
//!   other faces are not tried: their crossings are almost never `f64`
//!   points, and a try that is not exact is work the root does again;
//! - otherwise the node is left *pending*: its expression over its
//!   operands (leaves and exact intermediates) goes up unevaluated, and
//!   every node above it is pending too, so the root evaluates all pending
//!   operands in one exact pass, as before. A node evaluated on its own
//!   whose result was not exact is work spent once per such node (on
//!   disjoint subtrees, so at most the one pass over those subtrees); at
//!   the root that result is the answer and nothing is repeated;
//! - sides whose boxes do not share interior points need no cutting: a
//!   difference keeps its left side, an intersection is empty, before any
//!   boolean (boxes hold their sides' points, so this is exact).
//!
//! Every result is proven by the boolean that made it; the final one is
//! the tree's.
//!
//! [`OutputWork::is_exact`]: crate::boolean::OutputWork::is_exact

use std::sync::Mutex;

use crate::SetOp;
use crate::boolean::{BooleanError, BooleanOptions, BooleanStats, Expression, combine};
use crate::geom::Aabb;
use crate::mesh::{FaceId, Solid};
use crate::validate::Report;

use super::tree::{Csg, NodeIndex, NodeKind};

/// A face of an operand traced to the leaf it lies in: the leaf's slot
/// among the made leaves and the face of the leaf's polyhedron.
pub(super) type Source = (usize, FaceId);

/// How the walk went: the booleans it ran and what became of them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct StructureWork {
    /// Booleans run (each node evaluated on its own, and the root's pass).
    pub booleans: usize,
    /// Of those below the root, the results that were exact and were cut
    /// again as operands.
    pub exact: usize,
    /// Of those below the root, the results that were not exact and were
    /// set aside for the root's pass over the leaves.
    pub set_aside: usize,
    /// Operator nodes decided by their boxes alone (a difference whose
    /// sides do not meet, an intersection whose sides do not).
    pub by_boxes: usize,
    /// The operands of the root's boolean (1 when the whole tree was
    /// evaluated node by node).
    pub root_operands: usize,
}

/// The tree's result: its solid (faces' `source_index` into `sources`),
/// the validator's report, and the summed work.
pub(super) struct Outcome {
    pub solid: Solid,
    pub report: Report,
    pub sources: Vec<Source>,
    pub stats: BooleanStats,
    pub work: StructureWork,
}

/// Why the root's boolean failed, and the leaf slot of each of its
/// operands (`None` for an intermediate result).
pub(super) struct Failure {
    pub source: BooleanError,
    pub slots: Vec<Option<usize>>,
}

/// A subtree evaluated exactly.
struct Exact {
    solid: Solid,
    /// Whether every face lies in a plane `x`, `y` or `z` = constant.
    aligned: bool,
    report: Report,
    sources: Vec<Source>,
}

/// An operand of a boolean: a leaf's polyhedron, or an exact result.
enum Operand {
    Leaf(usize),
    Done(Box<Exact>),
}

/// What a subtree became.
enum Part {
    /// Nothing (an intersection of sides that do not meet).
    Empty,
    /// An expression over leaves and exact results: one operand when the
    /// subtree was evaluated exactly (or is a leaf), several when it is a
    /// union of sides whose boxes do not meet (left for later: those need
    /// no cutting against each other, and one boolean over all of them
    /// costs what they hold), or when the subtree is `pending`.
    Group {
        expression: Expression,
        operands: Vec<Operand>,
        /// Whether evaluating the group was tried and was not exact (or
        /// a side was pending): every node above is left to the root.
        pending: bool,
        /// The result of the one attempt made at this very node (used if
        /// this node is the root).
        attempt: Option<Box<Exact>>,
    },
}

impl Part {
    fn of(operand: Operand) -> Part {
        Part::Group {
            expression: Expression::Operand(0),
            operands: vec![operand],
            pending: false,
            attempt: None,
        }
    }
}

/// The walk's shared state.
struct Walk<'a> {
    csg: &'a Csg,
    leaves: &'a [Solid],
    /// The slot of each leaf (by `LeafId`).
    slot: Vec<usize>,
    /// The exact box of each leaf's polyhedron.
    boxes: Vec<Aabb>,
    /// Whether each leaf's polyhedron is axis-aligned.
    aligned: Vec<bool>,
    stats: Mutex<(BooleanStats, StructureWork)>,
}

/// Evaluates `csg` whose leaves were made into `leaves` (in the order of
/// `ids`, slot by slot) by its structure (see the module documentation).
///
/// # Errors
///
/// The root boolean's error, with the leaf of each of its operands.
pub(super) fn evaluate(
    csg: &Csg,
    leaves: &[Solid],
    ids: &[super::tree::LeafId],
) -> Result<Outcome, Failure> {
    let mut slot = vec![usize::MAX; csg.leaves.len()];
    for (k, id) in ids.iter().enumerate() {
        slot[id.0 as usize] = k;
    }
    let walk = Walk {
        csg,
        leaves,
        slot,
        boxes: leaves.iter().map(bounds).collect(),
        aligned: leaves.iter().map(axis_aligned).collect(),
        stats: Mutex::new((BooleanStats::default(), StructureWork::default())),
    };
    let (part, _) = walk.node(csg.root);
    let exact = walk.finish(part)?;
    let (stats, work) = walk.stats.into_inner().unwrap_or_else(|e| e.into_inner());
    Ok(Outcome {
        solid: exact.solid,
        report: exact.report,
        sources: exact.sources,
        stats,
        work,
    })
}

/// The exact box of a solid's vertices (empty for the empty solid).
fn bounds(solid: &Solid) -> Aabb {
    Aabb::from_points(solid.vertices().map(|(_, v)| v.position))
}

/// The axes `k` along which all of a face's corners share coordinate `k`
/// (bit `k`; exactly compared): a face in the plane `x = c` has bit 0.
fn face_axes(solid: &Solid, face: FaceId) -> u8 {
    let mut corners = solid
        .face_loops(face)
        .flat_map(|l| solid.loop_vertices(l))
        .map(|v| solid.position(v));
    let Some(first) = corners.next() else {
        return 0;
    };
    let mut same = [true; 3];
    for p in corners {
        for (k, s) in same.iter_mut().enumerate() {
            *s &= p[k] == first[k];
        }
    }
    (0..3).filter(|&k| same[k]).fold(0, |m, k| m | 1 << k)
}

/// Whether every face of `solid` lies in a plane `x`, `y` or `z` =
/// constant.
fn axis_aligned(solid: &Solid) -> bool {
    solid.faces().all(|(f, _)| face_axes(solid, f) != 0)
}

/// Whether a boolean's result of axis-aligned operands is, as rounded,
/// exactly the exact result: every face axis-aligned, and every vertex on
/// faces of at least two axes.
///
/// Why this suffices: each face of the exact result lies in a plane
/// `x = c` of an operand, `c` an `f64`, and rounding is per coordinate, so
/// every rounded point of the face keeps `x = c` exactly. A vertex on faces
/// of all three axes is thus exact; one on faces of two axes only (`x = c`
/// and `y = d`) is no corner of the solid but a point of the line where
/// they meet, and it lies on that line exactly whatever its rounded `z`
/// (the proof that followed has checked the order of the points along it).
/// A vertex only on faces of one axis (between coplanar faces kept apart)
/// could have moved within the plane: then the result is not taken as
/// exact.
fn pinned(solid: &Solid) -> bool {
    let mut axes: slotmap::SecondaryMap<crate::mesh::VertexId, u8> =
        slotmap::SecondaryMap::with_capacity(solid.vertex_count());
    for (f, _) in solid.faces() {
        let mask = face_axes(solid, f);
        if mask == 0 {
            return false;
        }
        for l in solid.face_loops(f) {
            for v in solid.loop_vertices(l) {
                match axes.get_mut(v) {
                    Some(m) => *m |= mask,
                    None => {
                        axes.insert(v, mask);
                    }
                }
            }
        }
    }
    axes.values().all(|m| m.count_ones() >= 2)
}

/// Whether two boxes share no interior point (either empty, or apart or
/// touching along some axis).
fn interiors_apart(a: &Aabb, b: &Aabb) -> bool {
    a.is_empty() || b.is_empty() || (0..3).any(|k| a.max[k] <= b.min[k] || b.max[k] <= a.min[k])
}

/// The options of every boolean of the walk: the leaves were proven
/// valid, and so is every intermediate result.
fn options() -> BooleanOptions {
    BooleanOptions {
        check_operands: false,
        ..BooleanOptions::default()
    }
}

impl Walk<'_> {
    fn aligned(&self, operand: &Operand) -> bool {
        match operand {
            Operand::Leaf(slot) => self.aligned[*slot],
            Operand::Done(exact) => exact.aligned,
        }
    }

    fn solid<'s>(&'s self, operand: &'s Operand) -> &'s Solid {
        match operand {
            Operand::Leaf(slot) => &self.leaves[*slot],
            Operand::Done(exact) => &exact.solid,
        }
    }

    /// The part the subtree at `index` becomes, and a box that holds it.
    fn node(&self, index: NodeIndex) -> (Part, Aabb) {
        let (op, left, right) = match self.csg.nodes[index].kind {
            NodeKind::Leaf(id) => {
                let slot = self.slot[id.0 as usize];
                return (Part::of(Operand::Leaf(slot)), self.boxes[slot]);
            }
            NodeKind::Op { op, left, right } => match op {
                SetOp::ReverseDifference => (SetOp::Difference, right, left),
                _ => (op, left, right),
            },
        };
        let ((a, a_box), (b, b_box)) = rayon::join(|| self.node(left), || self.node(right));
        let apart = interiors_apart(&a_box, &b_box);
        match (op, a, b) {
            // An empty part's box is empty.
            (SetOp::Union, Part::Empty, other) | (SetOp::Union, other, Part::Empty) => {
                (other, a_box.union(b_box))
            }
            (SetOp::Intersection, Part::Empty, _)
            | (SetOp::Intersection, _, Part::Empty)
            // A difference (the only operator left).
            | (_, Part::Empty, _) => (Part::Empty, Aabb::EMPTY),
            (_, a, Part::Empty) => (a, a_box),
            (SetOp::Intersection, _, _) if apart => {
                self.tally(|w| w.by_boxes += 1);
                (Part::Empty, Aabb::EMPTY)
            }
            (SetOp::Difference | SetOp::ReverseDifference, a, _) if apart => {
                self.tally(|w| w.by_boxes += 1);
                (a, a_box)
            }
            (
                op,
                Part::Group {
                    expression: left,
                    mut operands,
                    pending: left_pending,
                    ..
                },
                Part::Group {
                    expression: right,
                    operands: more,
                    pending: right_pending,
                    ..
                },
            ) => {
                let n = operands.len();
                operands.extend(more);
                let expression = Expression::of(op, left, right.renumbered(&|k| k + n));
                let held = match op {
                    SetOp::Union => a_box.union(b_box),
                    SetOp::Intersection => a_box.intersection(b_box),
                    _ => a_box,
                };
                let aligned = operands.iter().all(|o| self.aligned(o));
                let part = if left_pending || right_pending || !aligned || (op == SetOp::Union && apart) {
                    Part::Group {
                        expression,
                        operands,
                        pending: left_pending || right_pending || !aligned,
                        attempt: None,
                    }
                } else {
                    self.evaluate_group(expression, operands)
                };
                (part, held)
            }
        }
    }

    /// One boolean over a group of leaves and exact results: kept as an
    /// operand if exact, else set aside (pending), its result kept for the
    /// case that this is the root.
    fn evaluate_group(&self, expression: Expression, operands: Vec<Operand>) -> Part {
        match self.run(&expression, &operands).ok() {
            Some((exact, true)) => {
                self.tally(|w| w.exact += 1);
                Part::of(Operand::Done(Box::new(exact)))
            }
            attempt => {
                self.tally(|w| w.set_aside += 1);
                Part::Group {
                    expression,
                    operands,
                    pending: true,
                    attempt: attempt.map(|(e, _)| Box::new(e)),
                }
            }
        }
    }

    /// Runs one boolean; returns its result, traced to the leaves, and
    /// whether it is exact.
    fn run(
        &self,
        expression: &Expression,
        operands: &[Operand],
    ) -> Result<(Exact, bool), BooleanError> {
        let solids: Vec<&Solid> = operands.iter().map(|o| self.solid(o)).collect();
        let result = combine(&solids, expression, options());
        let result = match result {
            Ok(r) => r,
            Err(e) => {
                self.tally(|w| w.booleans += 1);
                return Err(e);
            }
        };
        let aligned = operands.iter().all(|o| self.aligned(o));
        let output = &result.stats.output;
        let exact =
            output.is_exact() || (aligned && !output.fixed_anything() && pinned(&result.solid));
        {
            let mut guard = self.stats.lock().unwrap_or_else(|e| e.into_inner());
            guard.0 += &result.stats;
            guard.1.booleans += 1;
        }
        let sources = result
            .origins
            .iter()
            .map(|origin| match &operands[origin.operand] {
                Operand::Leaf(slot) => (*slot, origin.face),
                Operand::Done(done) => {
                    let index = done
                        .solid
                        .face(origin.face)
                        .attributes
                        .source_index
                        .unwrap_or_default();
                    done.sources[index]
                }
            })
            .collect();
        Ok((
            Exact {
                solid: result.solid,
                aligned,
                report: result.report,
                sources,
            },
            exact,
        ))
    }

    /// The root's result.
    fn finish(&self, part: Part) -> Result<Exact, Failure> {
        let (expression, operands) = match part {
            Part::Empty => (None, Vec::new()),
            Part::Group {
                attempt: Some(exact),
                ..
            } => return Ok(*exact),
            Part::Group {
                expression,
                mut operands,
                ..
            } => {
                if let (Expression::Operand(_), [Operand::Done(_)]) =
                    (&expression, operands.as_slice())
                    && let Some(Operand::Done(exact)) = operands.pop()
                {
                    return Ok(*exact);
                }
                (Some(expression), operands)
            }
        };
        self.tally(|w| w.root_operands = operands.len());
        let Some(expression) = expression else {
            let solid = Solid::default();
            let report = crate::boolean::prove(&solid).map_err(|source| Failure {
                source,
                slots: Vec::new(),
            })?;
            return Ok(Exact {
                solid,
                aligned: true,
                report,
                sources: Vec::new(),
            });
        };
        self.run(&expression, &operands)
            .map(|(exact, _)| exact)
            .map_err(|source| Failure {
                source,
                slots: operands
                    .iter()
                    .map(|o| match o {
                        Operand::Leaf(slot) => Some(*slot),
                        Operand::Done(_) => None,
                    })
                    .collect(),
            })
    }

    fn tally(&self, f: impl FnOnce(&mut StructureWork)) {
        let mut guard = self.stats.lock().unwrap_or_else(|e| e.into_inner());
        f(&mut guard.1);
    }
}
