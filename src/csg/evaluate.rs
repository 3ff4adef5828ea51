//! Boundary evaluation of a whole tree: every leaf made a polyhedron,
//! then one exact boolean per operator node, bottom up.
//!
//! Each boolean's result is a validated solid with `f64` vertices, and the
//! next boolean takes it as its operand: the constructed points of one
//! operator are rounded (and the rounded solid proven valid) before the
//! operator above uses them.

use std::time::Instant;

use thiserror::Error;

use super::tessellate::DEFAULT_TOLERANCE;
use super::tree::{Csg, NodeIndex, NodeKind};
use super::{CsgOp, TessellateError};
use crate::boolean::{BooleanError, BooleanOptions, BooleanStats, Operation, boolean};
use crate::mesh::Solid;
use crate::validate::Report;

/// How a tree is evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EvaluateOptions {
    /// The chord tolerance of curved leaves, a fraction of each primitive's
    /// radius ([`DEFAULT_TOLERANCE`] by default).
    pub tolerance: f64,
}

impl Default for EvaluateOptions {
    fn default() -> EvaluateOptions {
        EvaluateOptions {
            tolerance: DEFAULT_TOLERANCE,
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
    /// A boolean failed.
    #[error("{operation:?} of {left} and {right}: {source}")]
    Boolean {
        /// The operation.
        operation: Operation,
        /// The labels of the left operand's leaves.
        left: String,
        /// The labels of the right operand's leaves.
        right: String,
        /// Why.
        source: BooleanError,
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
    /// The number of booleans evaluated.
    pub booleans: usize,
}

struct Partial {
    solid: Solid,
    report: Report,
    labels: String,
}

/// Evaluates `csg` to a valid solid.
///
/// # Errors
///
/// [`EvaluateError`] naming the leaf or the operands where it failed.
pub fn evaluate(csg: &Csg, options: &EvaluateOptions) -> Result<Evaluated, EvaluateError> {
    let mut work = Work::default();
    let clip = csg.bounds();
    let root = node(csg, csg.root, options, &clip, &mut work)?;
    Ok(Evaluated {
        solid: root.solid,
        report: root.report,
        stats: work.stats,
        tessellate_seconds: work.tessellate_seconds,
        booleans: work.booleans,
    })
}

/// The work counted while evaluating.
#[derive(Default)]
struct Work {
    stats: BooleanStats,
    tessellate_seconds: f64,
    booleans: usize,
}

fn node(
    csg: &Csg,
    index: NodeIndex,
    options: &EvaluateOptions,
    clip: &crate::geom::Aabb,
    out: &mut Work,
) -> Result<Partial, EvaluateError> {
    match csg.nodes[index].kind {
        NodeKind::Leaf(id) => {
            let leaf = &csg.leaves[id.0 as usize];
            let clock = Instant::now();
            let solid = leaf
                .primitive
                .tessellate(options.tolerance, clip)
                .map_err(|source| EvaluateError::Leaf {
                    label: leaf.label.clone(),
                    source,
                })?;
            out.tessellate_seconds += clock.elapsed().as_secs_f64();
            let report =
                crate::boolean::prove(&solid).map_err(|source| EvaluateError::InvalidLeaf {
                    label: leaf.label.clone(),
                    source,
                })?;
            Ok(Partial {
                solid,
                report,
                labels: leaf.label.clone(),
            })
        }
        NodeKind::Op { op, left, right } => {
            let (l, r) = (
                node(csg, left, options, clip, out)?,
                node(csg, right, options, clip, out)?,
            );
            let (a, b, operation) = match op {
                CsgOp::Union => (l, r, Operation::Union),
                CsgOp::Intersection => (l, r, Operation::Intersection),
                CsgOp::Difference => (l, r, Operation::Difference),
                CsgOp::ReverseDifference => (r, l, Operation::Difference),
            };
            // Leaves were proven valid above and every result is.
            let options = BooleanOptions {
                check_operands: false,
                ..BooleanOptions::default()
            };
            let result = boolean(&a.solid, &b.solid, operation, options).map_err(|source| {
                EvaluateError::Boolean {
                    operation,
                    left: a.labels.clone(),
                    right: b.labels.clone(),
                    source,
                }
            })?;
            out.booleans += 1;
            out.stats += &result.stats;
            Ok(Partial {
                solid: result.solid,
                report: result.report,
                labels: format!("({} {} {})", a.labels, symbol(operation), b.labels),
            })
        }
    }
}

fn symbol(operation: Operation) -> &'static str {
    match operation {
        Operation::Union => "∪",
        Operation::Intersection => "∩",
        Operation::Difference => "−",
    }
}
