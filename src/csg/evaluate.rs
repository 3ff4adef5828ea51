//! Boundary evaluation of a whole tree: every leaf made a polyhedron
//! (proven a valid solid), then the tree evaluated by its structure
//! ([`structure`](super::structure): node by node where every intermediate
//! result is exact in `f64`, sides whose boxes do not meet never cut
//! against each other), and whatever is left in one exact pass
//! ([`combine`]): every remaining leaf's surface is cut by every other's
//! and no constructed point is rounded until the result is written, so
//! chained operators are as exact as one.

use crate::SetOp;
use std::time::Instant;

use thiserror::Error;

use super::TessellateError;
use super::structure::{self, Source, StructureWork};
use super::tessellate::DEFAULT_TOLERANCE;
use super::tree::{Csg, LeafId, NodeIndex, NodeKind};
use crate::boolean::{BooleanError, BooleanOptions, BooleanStats, Expression, combine};
use crate::mesh::Solid;
use crate::validate::Report;

/// How a tree is evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EvaluateOptions {
    /// The chord tolerance of curved leaves, a fraction of each primitive's
    /// radius ([`DEFAULT_TOLERANCE`] by default).
    pub tolerance: f64,
    /// Evaluate by the tree's structure (on by default): node by node
    /// where that is exact, one pass for the rest. Off: the whole tree in
    /// one pass over all leaves (the same set; for comparison).
    pub by_structure: bool,
}

impl Default for EvaluateOptions {
    fn default() -> EvaluateOptions {
        EvaluateOptions {
            tolerance: DEFAULT_TOLERANCE,
            by_structure: true,
        }
    }
}

/// Why a tree could not be evaluated.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum EvaluateError {
    /// A leaf has no polyhedral boundary, or its tessellation failed.
    #[error("leaf {label}: {source}")]
    Leaf {
        /// The leaf's label (the JSON path for scene files).
        label: String,
        /// Why.
        source: TessellateError,
    },
    /// A leaf's polyhedron is not a valid solid (a mesh leaf with defects).
    #[error("leaf {label}: {source}")]
    InvalidLeaf {
        /// The leaf's label.
        label: String,
        /// The validator's located report.
        source: BooleanError,
    },
    /// The booleans failed: the result could not be made a valid solid.
    #[error("{tree}: {source}{}", operand_key(leaves))]
    Boolean {
        /// The tree as a formula of its leaves' labels (its first 160
        /// characters).
        tree: String,
        /// Why.
        source: BooleanError,
        /// The leaves the error's operands are (`source` names operands by
        /// index), each as `(operand, label)`: in a scene, the JSON path.
        leaves: Vec<(usize, String)>,
    },
}

/// A tree evaluated to one solid.
#[derive(Clone, Debug)]
pub struct Evaluated {
    /// The solid (empty when the tree is).
    pub solid: Solid,
    /// The validator's report on it.
    pub report: Report,
    /// The booleans' time and work, summed over the tree.
    pub stats: BooleanStats,
    /// Seconds spent making leaves into polyhedra.
    pub tessellate_seconds: f64,
    /// The number of operators in the tree.
    pub booleans: usize,
    /// How the tree's structure was used (all zero for one pass).
    pub structure: StructureWork,
    /// For each face of `solid` (by its `attributes.source_index`), the
    /// leaf and the face of the leaf's polyhedron it is part of.
    pub origins: Vec<LeafFace>,
}

/// Where a face of an evaluated tree comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct LeafFace {
    /// The leaf.
    pub leaf: LeafId,
    /// The face's index in the faces of the leaf's polyhedron, in their
    /// order (for a mesh leaf, the mesh's face order; for a primitive, its
    /// tessellation's).
    pub face: usize,
}

/// Evaluates `csg` to a valid solid.
///
/// # Errors
///
/// [`EvaluateError`] naming the leaf where a leaf failed, or the tree
/// where the booleans did.
pub fn evaluate(csg: &Csg, options: &EvaluateOptions) -> Result<Evaluated, EvaluateError> {
    let mut leaves = Leaves::default();
    let clip = csg.bounds();
    let (expression, tree) = node(csg, csg.root, &mut leaves);
    leaves.make(csg, options, &clip)?;
    let (solid, report, sources, stats, structure) = if options.by_structure {
        let outcome = structure::evaluate(csg, &leaves.solids, &leaves.ids).map_err(|failure| {
            let named = failure
                .source
                .operands()
                .into_iter()
                .filter_map(|k| {
                    let slot = (*failure.slots.get(k)?)?;
                    let id = leaves.ids.get(slot)?;
                    Some((k, csg.leaves[id.0 as usize].label.clone()))
                })
                .collect();
            EvaluateError::Boolean {
                tree: shortened(&tree),
                source: failure.source,
                leaves: named,
            }
        })?;
        (
            outcome.solid,
            outcome.report,
            outcome.sources,
            outcome.stats,
            outcome.work,
        )
    } else {
        one_pass(csg, &leaves, &expression, &tree)?
    };
    // Each operand's faces numbered in their order, for the operands that
    // faces of the result come from.
    let mut numbering: Vec<Option<rustc_hash::FxHashMap<crate::mesh::FaceId, usize>>> =
        vec![None; leaves.solids.len()];
    let origins = sources
        .iter()
        .map(|&(slot, face)| {
            let faces = numbering[slot].get_or_insert_with(|| {
                leaves.solids[slot]
                    .faces()
                    .enumerate()
                    .map(|(i, (f, _))| (f, i))
                    .collect()
            });
            LeafFace {
                leaf: leaves.ids[slot],
                face: faces[&face],
            }
        })
        .collect();
    Ok(Evaluated {
        solid,
        report,
        stats,
        tessellate_seconds: leaves.tessellate_seconds,
        booleans: leaves.operators,
        structure,
        origins,
    })
}

/// The solid, its report, each face's leaf face, the booleans' work.
type Result5 = (Solid, Report, Vec<Source>, BooleanStats, StructureWork);

/// The whole tree's expression over all leaves in one pass.
fn one_pass(
    csg: &Csg,
    leaves: &Leaves,
    expression: &Expression,
    tree: &str,
) -> Result<Result5, EvaluateError> {
    let operands: Vec<&Solid> = leaves.solids.iter().collect();
    // Every leaf was proven valid.
    let boolean_options = BooleanOptions {
        check_operands: false,
        ..BooleanOptions::default()
    };
    let result = combine(&operands, expression, boolean_options).map_err(|source| {
        let named = source
            .operands()
            .into_iter()
            .filter_map(|k| {
                let id = leaves.ids.get(k)?;
                Some((k, csg.leaves[id.0 as usize].label.clone()))
            })
            .collect();
        EvaluateError::Boolean {
            tree: shortened(tree),
            source,
            leaves: named,
        }
    })?;
    let sources = result
        .origins
        .iter()
        .map(|origin| (origin.operand, origin.face))
        .collect();
    Ok((
        result.solid,
        result.report,
        sources,
        result.stats,
        StructureWork::default(),
    ))
}

/// The leaves of the tree, in the order the expression names them, and
/// their polyhedra once made.
#[derive(Default)]
struct Leaves {
    solids: Vec<Solid>,
    /// The leaf of each solid.
    ids: Vec<LeafId>,
    tessellate_seconds: f64,
    operators: usize,
}

impl Leaves {
    /// Makes every leaf a polyhedron and proves it valid, on all cores
    /// (each leaf on its own: a union of many small leaves costs what they
    /// hold, not a hand-over between threads per leaf). The error is the
    /// first leaf's in the expression's order, whatever the threads.
    fn make(
        &mut self,
        csg: &Csg,
        options: &EvaluateOptions,
        clip: &crate::geom::Aabb,
    ) -> Result<(), EvaluateError> {
        use rayon::prelude::*;
        let made: Vec<Result<(Solid, f64), EvaluateError>> = self
            .ids
            .par_iter()
            .map(|&id| {
                let leaf = &csg.leaves[id.0 as usize];
                let clock = Instant::now();
                let solid =
                    leaf.primitive
                        .tessellate(options.tolerance, clip)
                        .map_err(|source| EvaluateError::Leaf {
                            label: leaf.label.clone(),
                            source,
                        })?;
                let seconds = clock.elapsed().as_secs_f64();
                crate::boolean::prove(&solid).map_err(|source| EvaluateError::InvalidLeaf {
                    label: leaf.label.clone(),
                    source,
                })?;
                Ok((solid, seconds))
            })
            .collect();
        self.solids.reserve(made.len());
        for result in made {
            let (solid, seconds) = result?;
            self.solids.push(solid);
            self.tessellate_seconds += seconds;
        }
        Ok(())
    }
}

/// The expression of the subtree at `index` over the leaves it adds to
/// `out` (named, not yet made), and its formula in leaf labels.
fn node(csg: &Csg, index: NodeIndex, out: &mut Leaves) -> (Expression, String) {
    match csg.nodes[index].kind {
        NodeKind::Leaf(id) => {
            out.ids.push(id);
            let leaf = &csg.leaves[id.0 as usize];
            (Expression::Operand(out.ids.len() - 1), leaf.label.clone())
        }
        NodeKind::Op { op, left, right } => {
            let (l, r) = (node(csg, left, out), node(csg, right, out));
            let (a, b, operation) = match op {
                SetOp::Union => (l, r, SetOp::Union),
                SetOp::Intersection => (l, r, SetOp::Intersection),
                SetOp::Difference => (l, r, SetOp::Difference),
                SetOp::ReverseDifference => (r, l, SetOp::Difference),
            };
            out.operators += 1;
            // Only the formula's start is ever quoted ([`shortened`]): cut
            // past it at every node, so a tree of n leaves does not build
            // strings of n labels log n times.
            let mut formula = format!("({} {} {})", a.1, symbol(operation), b.1);
            if let Some((end, _)) = formula.char_indices().nth(FORMULA_CHARS + 1) {
                formula.truncate(end);
            }
            (Expression::of(operation, a.0, b.0), formula)
        }
    }
}

/// ` (operand 0 is leaf root.union[0], operand 1 is leaf …)`: which leaves
/// an error's operand numbers are.
fn operand_key(leaves: &[(usize, String)]) -> String {
    if leaves.is_empty() {
        return String::new();
    }
    let named: Vec<String> = leaves
        .iter()
        .map(|(k, label)| format!("operand {k} is leaf {label}"))
        .collect();
    format!(" ({})", named.join(", "))
}

/// A tree's formula cut to its first [`FORMULA_CHARS`] characters, so an
/// error about a large scene stays readable.
fn shortened(formula: &str) -> String {
    match formula.char_indices().nth(FORMULA_CHARS) {
        Some((end, _)) => format!("{}…", &formula[..end]),
        None => formula.to_string(),
    }
}

/// How much of a tree's formula an error quotes.
const FORMULA_CHARS: usize = 160;

fn symbol(operation: SetOp) -> &'static str {
    match operation {
        SetOp::Union => "∪",
        SetOp::Intersection => "∩",
        SetOp::Difference | SetOp::ReverseDifference => "−",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_error_says_which_leaf_each_operand_is() {
        assert_eq!(operand_key(&[]), "");
        let key = operand_key(&[
            (0, "root.union[0]".into()),
            (2, "root.union[1].difference[1]".into()),
        ]);
        assert_eq!(
            key,
            " (operand 0 is leaf root.union[0], operand 2 is leaf root.union[1].difference[1])"
        );
    }
}
