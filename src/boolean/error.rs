//! What can stop a boolean.

use thiserror::Error;

use crate::mesh::FaceId;

/// Why a boolean produced no solid.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum BooleanError {
    /// An operand is not a valid closed solid; `report` lists the located
    /// defects the validator found.
    #[error(
        "operand {operand} is not a valid solid ({validity}): {report}; resolve_operands (csg --resolve) takes it by its winding number instead"
    )]
    InvalidOperand {
        /// Which operand, by its index (0 is the first).
        operand: usize,
        /// The validator's verdict in words.
        validity: String,
        /// The first defects, with their faces.
        report: String,
    },
    /// A face of an operand could not be triangulated.
    #[error("face {face:?} of operand {operand} cannot be triangulated: {reason}")]
    Face {
        /// Which operand, by its index (0 is the first).
        operand: usize,
        /// The face.
        face: FaceId,
        /// The triangulator's reason.
        reason: String,
    },
    /// The set expression names an operand that is not in the list.
    #[error("the expression names operand {operand}, but there are only {count} operands")]
    UnknownOperand {
        /// The index named.
        operand: usize,
        /// How many operands were given.
        count: usize,
    },
    /// The operands touch in more pairs of triangles than the boolean's
    /// limit allows (the memory it would take).
    #[error(
        "the operands' surfaces meet in {contacts} pairs of triangles, more than the limit of {limit}"
    )]
    TooLarge {
        /// Pairs of touching triangles found.
        contacts: usize,
        /// The limit ([`BooleanOptions::max_contacts`](super::BooleanOptions::max_contacts)).
        limit: usize,
    },
    /// The exact decisions disagreed with each other — a defect of
    /// wingedge, reported instead of returning a broken solid.
    #[error("inconsistent intersection (a wingedge defect, please report it): {0}")]
    Inconsistent(String),
    /// The pieces chosen for the result could not be assembled into a
    /// winged-edge solid (a non-manifold result, such as two solids that
    /// touch only along an edge, or rounding that broke the surface).
    #[error("the result cannot be built as a winged-edge solid: {reason}")]
    NotBuilt {
        /// Why, and where in world coordinates (and by operand).
        reason: String,
        /// The operands (by index) whose faces meet where it failed, if
        /// known.
        operands: Vec<usize>,
    },
    /// The result after rounding to `f64` failed validation; `report`
    /// locates the defects.
    #[error("the rounded result is not a valid solid ({validity}): {report}")]
    InvalidResult {
        /// The validator's verdict in words.
        validity: String,
        /// The broken rules with their counts, and where in world
        /// coordinates (and by operand) the defects are.
        report: String,
        /// The operands (by index) whose faces hold the defects.
        operands: Vec<usize>,
    },
}

impl BooleanError {
    /// A failure to build or prove the result, located nowhere.
    pub(crate) fn not_built(reason: impl Into<String>) -> BooleanError {
        BooleanError::NotBuilt {
            reason: reason.into(),
            operands: Vec::new(),
        }
    }

    /// The operands (by index) an error is about: the one refused, or
    /// those whose faces hold the result's defects; empty when none is
    /// known.
    #[must_use]
    pub fn operands(&self) -> Vec<usize> {
        match self {
            BooleanError::InvalidOperand { operand, .. } | BooleanError::Face { operand, .. } => {
                vec![*operand]
            }
            BooleanError::NotBuilt { operands, .. }
            | BooleanError::InvalidResult { operands, .. } => operands.clone(),
            _ => Vec::new(),
        }
    }
}
