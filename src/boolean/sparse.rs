//! An expression evaluated where only a few operands are not known to be
//! outside: a patch meets the boxes of a handful of operands, and every
//! other operand is outside it. Each node keeps the least and the greatest
//! operand under it and its value when all of those are outside, so a
//! subtree naming no operand of the few is answered in one step. On the
//! balanced trees of an n-ary union, a patch's decision then costs
//! `O(few · log n)`, not `O(n)`.

use super::expression::Expression;

/// A node of a [`SparseExpression`].
#[derive(Clone, Copy, Debug)]
enum Kind {
    Operand(usize),
    Union(u32, u32),
    Intersection(u32, u32),
    Difference(u32, u32),
}

#[derive(Clone, Copy, Debug)]
struct Node {
    kind: Kind,
    /// The least and the greatest operand under the node.
    lo: usize,
    hi: usize,
    /// The node's value when every operand under it is outside.
    when_outside: bool,
}

/// An [`Expression`] flattened for sparse evaluation.
///
/// # Invariants
///
/// Children come before their parent in `nodes`; the root is the last.
#[derive(Clone, Debug)]
pub(crate) struct SparseExpression {
    nodes: Vec<Node>,
}

impl SparseExpression {
    /// The flattened `expression`.
    pub fn new(expression: &Expression) -> SparseExpression {
        let mut nodes = Vec::new();
        push(expression, &mut nodes);
        SparseExpression { nodes }
    }

    /// Whether a point is in the expression's set, where `member(k)` says
    /// whether it is in operand `k` for every `k` in `few` (sorted,
    /// increasing) and every other operand is outside. `member` is asked
    /// only for operands in `few`, and only where they decide.
    ///
    /// # Errors
    ///
    /// The first error `member` returns.
    pub fn contains<E>(
        &self,
        few: &[usize],
        member: &mut impl FnMut(usize) -> Result<bool, E>,
    ) -> Result<bool, E> {
        self.at(self.nodes.len() - 1, few, member)
    }

    fn at<E>(
        &self,
        index: usize,
        few: &[usize],
        member: &mut impl FnMut(usize) -> Result<bool, E>,
    ) -> Result<bool, E> {
        let node = self.nodes[index];
        // The first of `few` at or after `lo`: none up to `hi`, and the
        // subtree is all outside.
        let first = few.partition_point(|&k| k < node.lo);
        if few.get(first).is_none_or(|&k| k > node.hi) {
            return Ok(node.when_outside);
        }
        let mut side = |i: u32| self.at(i as usize, few, member);
        Ok(match node.kind {
            Kind::Operand(k) => member(k)?,
            Kind::Union(l, r) => side(l)? || side(r)?,
            Kind::Intersection(l, r) => side(l)? && side(r)?,
            Kind::Difference(l, r) => side(l)? && !side(r)?,
        })
    }
}

/// Pushes `expression`'s nodes, children first; returns the index of its
/// root.
fn push(expression: &Expression, nodes: &mut Vec<Node>) -> u32 {
    let node = match expression {
        Expression::Operand(k) => Node {
            kind: Kind::Operand(*k),
            lo: *k,
            hi: *k,
            when_outside: false,
        },
        Expression::Union(l, r) | Expression::Intersection(l, r) | Expression::Difference(l, r) => {
            let (l, r) = (push(l, nodes), push(r, nodes));
            let (a, b) = (nodes[l as usize], nodes[r as usize]);
            let (kind, when_outside) = match expression {
                Expression::Union(..) => (Kind::Union(l, r), a.when_outside || b.when_outside),
                Expression::Intersection(..) => {
                    (Kind::Intersection(l, r), a.when_outside && b.when_outside)
                }
                _ => (Kind::Difference(l, r), a.when_outside && !b.when_outside),
            };
            Node {
                kind,
                lo: a.lo.min(b.lo),
                hi: a.hi.max(b.hi),
                when_outside,
            }
        }
    };
    nodes.push(node);
    (nodes.len() - 1) as u32
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::SetOp;

    fn op(k: usize) -> Expression {
        Expression::Operand(k)
    }

    /// On every membership of five operands and every set of operands
    /// that may be inside, the sparse answer is the full expression's with
    /// the others outside, and only operands of the few are asked.
    #[test]
    fn sparse_evaluation_is_full_evaluation_with_the_rest_outside() {
        // (0 ∪ 1) − ((2 ∩ 3) ∪ 4), and one that names 0 twice.
        let expressions = [
            Expression::of(
                SetOp::Difference,
                Expression::of(SetOp::Union, op(0), op(1)),
                Expression::of(
                    SetOp::Union,
                    Expression::of(SetOp::Intersection, op(2), op(3)),
                    op(4),
                ),
            ),
            Expression::of(
                SetOp::Intersection,
                Expression::of(SetOp::Difference, op(3), op(0)),
                Expression::of(
                    SetOp::Union,
                    op(0),
                    Expression::of(SetOp::Union, op(1), op(4)),
                ),
            ),
        ];
        for e in &expressions {
            let sparse = SparseExpression::new(e);
            for few_bits in 0..32u32 {
                let few: Vec<usize> = (0..5).filter(|k| few_bits & (1 << k) != 0).collect();
                for bits in 0..32u32 {
                    let inside = |k: usize| few.contains(&k) && bits & (1 << k) != 0;
                    let expected = e.contains(&mut |k| Ok::<bool, ()>(inside(k))).unwrap();
                    let got = sparse
                        .contains(&few, &mut |k| {
                            assert!(few.contains(&k), "asked about {k}, not in {few:?}");
                            Ok::<bool, ()>(inside(k))
                        })
                        .unwrap();
                    assert_eq!(got, expected, "few {few:?}, memberships {bits:05b}");
                }
            }
        }
    }
}
