//! Stage 5: the expression's rule — which labelled patches bound the
//! result, and which are turned over.
//!
//! A patch of operand `i` separates the inside of `i` (behind it) from the
//! outside (in front). It bounds the result exactly when the expression
//! holds on one side and not on the other: evaluated once with `i`'s
//! membership true and once false, every other operand's membership being
//! its label (inside, outside; on its surface with the same orientation:
//! like `i`; with the opposite: unlike `i`). Kept facing out of the result:
//! as it is when the result is behind it, turned over when in front.
//!
//! Where several operands' surfaces coincide, their patches are the same
//! piece of the result, and the one of the smallest operand index stands
//! for all (its decision is theirs: a coincident patch with the same
//! orientation sees the same two sides, one with the opposite orientation
//! sees them swapped and turns over accordingly).

use super::BooleanError;
use super::sparse::SparseExpression;

/// Where a patch lies against the other operand.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Label {
    /// Strictly inside.
    Inside,
    /// Strictly outside.
    Outside,
    /// On its surface, both normals pointing the same way.
    OnSame,
    /// On its surface, the normals opposite.
    OnOpposite,
}

/// Whether a patch of operand `own` bounds the result of `expression`, and
/// if so whether it is turned over (`Some(true)`); `label(k)` is the
/// patch's label against operand `k ≠ own`, asked only where it decides
/// and only for `k` in `few` (sorted, holding `own`): every other operand
/// is known to be outside the patch.
///
/// # Errors
///
/// The first error `label` returns.
pub(crate) fn keep(
    expression: &SparseExpression,
    few: &[usize],
    own: usize,
    label: &mut impl FnMut(usize) -> Result<Label, BooleanError>,
) -> Result<Option<bool>, BooleanError> {
    let mut side = |inside_own: bool| {
        expression.contains(few, &mut |k| {
            if k == own {
                return Ok(inside_own);
            }
            Ok(match label(k)? {
                Label::Inside => true,
                Label::Outside => false,
                Label::OnSame => inside_own,
                Label::OnOpposite => !inside_own,
            })
        })
    };
    let behind = side(true)?;
    let in_front = side(false)?;
    Ok(match (behind, in_front) {
        (true, false) => Some(false),
        (false, true) => Some(true),
        _ => None,
    })
}

/// Whether a patch with `label` against operand `other` is that operand's
/// to keep rather than its own (`own`): it lies on `other`'s surface and
/// `other` comes first.
#[must_use]
pub(crate) fn covered(own: usize, other: usize, label: Label) -> bool {
    other < own && matches!(label, Label::OnSame | Label::OnOpposite)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SetOp;
    use crate::boolean::expression::Expression;

    /// With two operands the rule is the table of the regularized set
    /// operations, written out.
    #[test]
    fn with_two_operands_the_rule_is_the_regularized_set_operation() {
        use crate::SetOp::*;
        use Label::*;
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
            let e = SparseExpression::new(&Expression::of(
                op,
                Expression::Operand(0),
                Expression::Operand(1),
            ));
            for (k, label) in [Outside, Inside, OnSame, OnOpposite]
                .into_iter()
                .enumerate()
            {
                for (own, expected) in [(0, first[k]), (1, second[k])] {
                    let other = 1 - own;
                    let got = if covered(own, other, label) {
                        None
                    } else {
                        keep(&e, &[0, 1], own, &mut |_| Ok(label)).unwrap()
                    };
                    assert_eq!(got, expected, "{op:?} operand {own} {label:?}");
                }
            }
        }
    }

    /// `a − (b ∪ c)`: a patch of `b` inside `a` and outside `c` bounds the
    /// result turned over; inside `c` it is hidden.
    #[test]
    fn a_patch_bounds_the_result_where_the_expression_changes_across_it() {
        let e = SparseExpression::new(&Expression::of(
            SetOp::Difference,
            Expression::Operand(0),
            Expression::of(SetOp::Union, Expression::Operand(1), Expression::Operand(2)),
        ));
        let labels = |inside_c: bool| {
            move |k: usize| {
                Ok(match k {
                    0 => Label::Inside,
                    _ if inside_c => Label::Inside,
                    _ => Label::Outside,
                })
            }
        };
        let all = [0, 1, 2];
        assert_eq!(keep(&e, &all, 1, &mut labels(false)).unwrap(), Some(true));
        assert_eq!(keep(&e, &all, 1, &mut labels(true)).unwrap(), None);
        // Only 0 and 1 near the patch: 2 is outside.
        assert_eq!(keep(&e, &[0, 1], 1, &mut labels(true)).unwrap(), Some(true));
    }
}
