//! What can stop a boolean.

use thiserror::Error;

use crate::mesh::FaceId;

/// Why a boolean produced no solid.
#[derive(Clone, Debug, Error, PartialEq)]
pub enum BooleanError {
    /// An operand is not a valid closed solid; `report` lists the located
    /// defects the validator found.
    #[error("operand {operand} is not a valid solid ({validity}): {report}")]
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
    #[error("the result cannot be built as a winged-edge solid: {0}")]
    NotBuilt(String),
    /// The result after rounding to `f64` failed validation; `report`
    /// locates the defects.
    #[error("the rounded result is not a valid solid ({validity}): {report}")]
    InvalidResult {
        /// The validator's verdict in words.
        validity: String,
        /// The first defects, with their faces.
        report: String,
    },
}
