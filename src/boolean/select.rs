//! Stage 5: the operator's rule — which labelled pieces bound the result,
//! and which are turned over.

use super::Operation;
use super::classify::Label;
use super::operand::Operand;

/// Whether a piece of operand `side` with `label` bounds the result of
/// `operation`, and if so whether it is turned over (`Some(true)`).
///
/// Coplanar pieces are kept once: where both operands' surfaces coincide
/// with the same orientation the first operand's piece stands for both (in
/// a union or intersection); with opposite orientations the two solids
/// touch from opposite sides and the surface is inside a union and outside
/// an intersection, so neither piece stays. A difference `a − b` is
/// `a ∩ ¬b`: `b`'s pieces inside `a` are kept turned over, and a coplanar
/// pair counts as the same orientation when the normals are opposite.
#[must_use]
pub(crate) fn keep(operation: Operation, side: Operand, label: Label) -> Option<bool> {
    use Label::{Inside, OnOpposite, OnSame, Outside};
    use Operation::{Difference, Intersection, Union};
    match (operation, side, label) {
        (Union, Operand::First, Outside | OnSame) => Some(false),
        (Union, Operand::Second, Outside) => Some(false),
        (Intersection, Operand::First, Inside | OnSame) => Some(false),
        (Intersection, Operand::Second, Inside) => Some(false),
        (Difference, Operand::First, Outside | OnOpposite) => Some(false),
        (Difference, Operand::Second, Inside) => Some(true),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every combination, written out as a table of the regularized set
    /// operations.
    #[test]
    fn the_rule_is_the_regularized_set_operation() {
        use Label::*;
        use Operation::*;
        let cases = [
            (
                Union,
                [Some(false), None, Some(false), None],
                [Some(false), None, None, None],
            ),
            (
                Intersection,
                [None, Some(false), Some(false), None],
                [None, Some(false), None, None],
            ),
            (
                Difference,
                [Some(false), None, None, Some(false)],
                [None, Some(true), None, None],
            ),
        ];
        for (op, first, second) in cases {
            for (k, label) in [Outside, Inside, OnSame, OnOpposite]
                .into_iter()
                .enumerate()
            {
                assert_eq!(
                    keep(op, Operand::First, label),
                    first[k],
                    "{op:?} first {label:?}"
                );
                assert_eq!(
                    keep(op, Operand::Second, label),
                    second[k],
                    "{op:?} second {label:?}"
                );
            }
        }
    }
}
