//! The regularized set operators every layer combines solids with: exact
//! booleans ([`boolean`](crate::boolean)), ray-cast CSG ([`csg`](crate::csg))
//! and field CSG ([`field`](crate::field)).

/// A set operator on two operands `A` and `B` (Requicha 1980; Roth 1982
/// lists all four, `B − A` being `A − B` with the operands swapped).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum SetOp {
    /// `A ∪ B`.
    Union,
    /// `A ∩ B`.
    Intersection,
    /// `A − B`.
    Difference,
    /// `B − A`.
    ReverseDifference,
}

impl SetOp {
    /// Whether a point is in the result, given whether it is in `A` and in
    /// `B`: `A OR B`, `A AND B`, `A AND NOT B`, `NOT A AND B`.
    #[must_use]
    pub fn contains(self, in_a: bool, in_b: bool) -> bool {
        match self {
            SetOp::Union => in_a || in_b,
            SetOp::Intersection => in_a && in_b,
            SetOp::Difference => in_a && !in_b,
            SetOp::ReverseDifference => !in_a && in_b,
        }
    }

    /// The same operator with its operands swapped (`A − B` ↔ `B − A`).
    #[must_use]
    pub fn swapped(self) -> SetOp {
        match self {
            SetOp::Difference => SetOp::ReverseDifference,
            SetOp::ReverseDifference => SetOp::Difference,
            op => op,
        }
    }

    /// The operator's name in scene files, field documents and messages.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            SetOp::Union => "union",
            SetOp::Intersection => "intersection",
            SetOp::Difference => "difference",
            SetOp::ReverseDifference => "reverse difference",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ALL: [SetOp; 4] = [
        SetOp::Union,
        SetOp::Intersection,
        SetOp::Difference,
        SetOp::ReverseDifference,
    ];

    /// Membership by the truth table, and swapping the operands of each
    /// operator answers as the swapped operator does.
    #[test]
    fn membership_and_swapping() {
        let table = [
            (SetOp::Union, [false, true, true, true]),
            (SetOp::Intersection, [false, false, false, true]),
            (SetOp::Difference, [false, true, false, false]),
            (SetOp::ReverseDifference, [false, false, true, false]),
        ];
        for (op, want) in table {
            let got = [(false, false), (true, false), (false, true), (true, true)]
                .map(|(a, b)| op.contains(a, b));
            assert_eq!(got, want, "{}", op.name());
        }
        for op in ALL {
            for (a, b) in [(false, false), (true, false), (false, true), (true, true)] {
                assert_eq!(op.swapped().contains(b, a), op.contains(a, b));
            }
            assert_eq!(op.swapped().swapped(), op);
        }
    }
}
