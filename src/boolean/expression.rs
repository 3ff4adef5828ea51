//! A set expression over several operands: what [`combine`](super::combine)
//! evaluates in one pass, so that a whole CSG tree's constructed points
//! stay exact from the leaves to the result.

use crate::SetOp;

/// A regularized set expression over operands named by their index in the
/// operands' list.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Expression {
    /// The operand with this index.
    Operand(usize),
    /// `left ∪ right`.
    Union(Box<Expression>, Box<Expression>),
    /// `left ∩ right`.
    Intersection(Box<Expression>, Box<Expression>),
    /// `left − right`.
    Difference(Box<Expression>, Box<Expression>),
}

impl Expression {
    /// `left operation right`.
    #[must_use]
    pub fn of(operation: SetOp, left: Expression, right: Expression) -> Expression {
        let (left, right) = (Box::new(left), Box::new(right));
        match operation {
            SetOp::Union => Expression::Union(left, right),
            SetOp::Intersection => Expression::Intersection(left, right),
            SetOp::Difference => Expression::Difference(left, right),
            SetOp::ReverseDifference => Expression::Difference(right, left),
        }
    }

    /// The operands the expression names, each once, in increasing order.
    #[must_use]
    pub fn operands(&self) -> Vec<usize> {
        let mut found = Vec::new();
        self.visit(&mut |k| found.push(k));
        found.sort_unstable();
        found.dedup();
        found
    }

    fn visit(&self, f: &mut impl FnMut(usize)) {
        match self {
            Expression::Operand(k) => f(*k),
            Expression::Union(l, r)
            | Expression::Intersection(l, r)
            | Expression::Difference(l, r) => {
                l.visit(f);
                r.visit(f);
            }
        }
    }

    /// Whether a point is in the expression's set, given whether it is in
    /// each operand (`member(k)`); `member` is asked only for the operands
    /// that decide (a union whose left side holds the point does not ask
    /// about its right side).
    ///
    /// # Errors
    ///
    /// The first error `member` returns.
    pub fn contains<E>(
        &self,
        member: &mut impl FnMut(usize) -> Result<bool, E>,
    ) -> Result<bool, E> {
        Ok(match self {
            Expression::Operand(k) => member(*k)?,
            Expression::Union(l, r) => l.contains(member)? || r.contains(member)?,
            Expression::Intersection(l, r) => l.contains(member)? && r.contains(member)?,
            Expression::Difference(l, r) => l.contains(member)? && !r.contains(member)?,
        })
    }

    /// The same expression over operands renamed by `rename`.
    #[must_use]
    pub(crate) fn renumbered(&self, rename: &impl Fn(usize) -> usize) -> Expression {
        let both = |l: &Expression, r: &Expression| {
            (
                Box::new(l.renumbered(rename)),
                Box::new(r.renumbered(rename)),
            )
        };
        match self {
            Expression::Operand(k) => Expression::Operand(rename(*k)),
            Expression::Union(l, r) => {
                let (l, r) = both(l, r);
                Expression::Union(l, r)
            }
            Expression::Intersection(l, r) => {
                let (l, r) = both(l, r);
                Expression::Intersection(l, r)
            }
            Expression::Difference(l, r) => {
                let (l, r) = both(l, r);
                Expression::Difference(l, r)
            }
        }
    }

    /// The expression with the operands for which `empty(k)` holds
    /// replaced by the empty set and simplified: `None` when the whole
    /// expression is empty.
    #[must_use]
    pub fn without_empty(&self, empty: &impl Fn(usize) -> bool) -> Option<Expression> {
        match self {
            Expression::Operand(k) => (!empty(*k)).then(|| self.clone()),
            Expression::Union(l, r) => match (l.without_empty(empty), r.without_empty(empty)) {
                (Some(l), Some(r)) => Some(Expression::Union(Box::new(l), Box::new(r))),
                (one, None) | (None, one) => one,
            },
            Expression::Intersection(l, r) => {
                let (l, r) = (l.without_empty(empty)?, r.without_empty(empty)?);
                Some(Expression::Intersection(Box::new(l), Box::new(r)))
            }
            Expression::Difference(l, r) => {
                let l = l.without_empty(empty)?;
                Some(match r.without_empty(empty) {
                    Some(r) => Expression::Difference(Box::new(l), Box::new(r)),
                    None => l,
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn op(k: usize) -> Expression {
        Expression::Operand(k)
    }

    /// `(0 ∪ 1) − (2 ∩ 3)` on every membership of four operands, against
    /// the formula written out.
    #[test]
    fn contains_is_the_set_formula() {
        let e = Expression::of(
            SetOp::Difference,
            Expression::of(SetOp::Union, op(0), op(1)),
            Expression::of(SetOp::Intersection, op(2), op(3)),
        );
        assert_eq!(e.operands(), vec![0, 1, 2, 3]);
        for bits in 0..16u32 {
            let inside = |k: usize| bits & (1 << k) != 0;
            let expected = (inside(0) || inside(1)) && !(inside(2) && inside(3));
            let mut asked = Vec::new();
            let got = e
                .contains(&mut |k| {
                    asked.push(k);
                    Ok::<bool, ()>(inside(k))
                })
                .unwrap();
            assert_eq!(got, expected, "memberships {bits:04b}");
            // A point in neither 0 nor 1 is decided without 2 and 3.
            if !inside(0) && !inside(1) {
                assert_eq!(asked, vec![0, 1]);
            }
        }
    }

    /// Empty operands drop out as the empty set would.
    #[test]
    fn empty_operands_simplify_away() {
        let e = Expression::of(
            SetOp::Difference,
            Expression::of(SetOp::Union, op(0), op(1)),
            Expression::of(SetOp::Intersection, op(2), op(3)),
        );
        assert_eq!(
            e.without_empty(&|k| k == 1 || k == 3),
            Some(op(0)),
            "(0 ∪ ∅) − (2 ∩ ∅) = 0"
        );
        assert_eq!(e.without_empty(&|k| k <= 1), None);
        assert_eq!(
            e.without_empty(&|k| k == 0),
            Some(Expression::of(
                SetOp::Difference,
                op(1),
                Expression::of(SetOp::Intersection, op(2), op(3))
            ))
        );
    }
}
