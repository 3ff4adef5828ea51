//! Roth's four-state machine (Roth 1982) that combines two children's ray
//! answers.
//!
//! Input: `(INOUT_A, t_A1 < t_A2 < …)` and `(INOUT_B, t_B1 < …)`; output
//! `(INOUT_C, t_C1 < …)` for `C = A ∪ B`, `A ∩ B`, `A − B` or `B − A`. The
//! start state comes from `INOUT_A` and `INOUT_B`; the smallest head of the
//! two lists is taken, crossing A toggles "in A", crossing B toggles "in B",
//! and the `t` is kept exactly when the change enters or leaves the
//! operator's state X. Equal `t` at the heads of both lists (coincident or
//! touching faces) are taken **together**: both toggles are applied at once
//! and the `t` is kept only if the combined change enters or leaves X, so
//! two boxes sharing a face leave no zero-length span and no phantom
//! boundary. Equal `t` repeated within one list toggle once per copy.

use crate::SetOp;
use std::cmp::Ordering;

use glam::DVec3;

use super::{LeafId, SurfaceId};

/// A boundary crossing of a (sub)tree along a ray: where, and on which
/// surface of which leaf.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hit {
    /// The ray parameter, `t > 0` (rounded).
    pub t: f64,
    /// A bound on the rounding of `t` (the exact parameter is within
    /// `t ± spread`); 0 when the leaf gives none (curved surfaces).
    pub spread: f32,
    /// The leaf whose surface is crossed.
    pub leaf: LeafId,
    /// Which surface of that leaf.
    pub surface: SurfaceId,
}

/// Where a point of the ray is relative to the two children.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum MergeState {
    /// In neither A nor B.
    InNeither,
    /// In A only.
    InJustA,
    /// In B only.
    InJustB,
    /// In both A and B.
    InBoth,
}

impl MergeState {
    /// The start state "in the obvious way" from `INOUT_A` and `INOUT_B`.
    #[must_use]
    pub fn from_flags(in_a: bool, in_b: bool) -> MergeState {
        match (in_a, in_b) {
            (false, false) => MergeState::InNeither,
            (true, false) => MergeState::InJustA,
            (false, true) => MergeState::InJustB,
            (true, true) => MergeState::InBoth,
        }
    }

    /// `(in A, in B)`.
    #[must_use]
    pub fn flags(self) -> (bool, bool) {
        match self {
            MergeState::InNeither => (false, false),
            MergeState::InJustA => (true, false),
            MergeState::InJustB => (false, true),
            MergeState::InBoth => (true, true),
        }
    }

    /// The state after crossing A's boundary (`cross_a`) and/or B's.
    #[must_use]
    pub fn step(self, cross_a: bool, cross_b: bool) -> MergeState {
        let (a, b) = self.flags();
        MergeState::from_flags(a ^ cross_a, b ^ cross_b)
    }
}

impl MergeState {
    /// Roth's state X of an operator: entering or leaving it keeps the `t`.
    #[must_use]
    pub fn kept_by(op: SetOp) -> MergeState {
        match op {
            SetOp::Union => MergeState::InNeither,
            SetOp::Intersection => MergeState::InBoth,
            SetOp::Difference => MergeState::InJustA,
            SetOp::ReverseDifference => MergeState::InJustB,
        }
    }
}

/// Runs the state machine: appends `C`'s crossings to `out` and returns
/// `INOUT_C`, with hits ordered (and equal) by their rounded `t`.
///
/// `limit` stops the merge once `out` holds that many crossings of `C`
/// (a first-hit query needs one); the returned `INOUT_C` is correct either
/// way. Returns whether the merge was stopped early as the second value.
pub fn merge(
    op: SetOp,
    a: (bool, &[Hit]),
    b: (bool, &[Hit]),
    out: &mut Vec<Hit>,
    limit: Option<usize>,
) -> (bool, bool) {
    merge_by(op, a, b, out, limit, |x, y| x.t.total_cmp(&y.t))
}

/// [`merge`] with the order of two hits given by `order` (the tree's
/// traversal orders hits of different leaves exactly where their rounded
/// `t` cannot tell): hits that compare `Equal` are taken together.
pub fn merge_by(
    op: SetOp,
    (in_a, a): (bool, &[Hit]),
    (in_b, b): (bool, &[Hit]),
    out: &mut Vec<Hit>,
    limit: Option<usize>,
    mut order: impl FnMut(&Hit, &Hit) -> Ordering,
) -> (bool, bool) {
    let x = MergeState::kept_by(op);
    let start = MergeState::from_flags(in_a, in_b);
    debug_assert_eq!(op.contains(in_a, in_b), inside(op, start));
    let mut state = start;
    let (mut i, mut j) = (0, 0);
    let mut kept = 0;
    while i < a.len() || j < b.len() {
        if limit.is_some_and(|l| kept >= l) {
            return (op.contains(in_a, in_b), true);
        }
        let (from_a, from_b) = match (a.get(i), b.get(j)) {
            (Some(ha), Some(hb)) => match order(ha, hb) {
                Ordering::Less => (true, false),
                Ordering::Greater => (false, true),
                Ordering::Equal => (true, true),
            },
            (Some(_), None) => (true, false),
            (None, Some(_)) => (false, true),
            (None, None) => break,
        };
        // Take every copy of the head's t from both lists together.
        let head = if from_a { a[i] } else { b[j] };
        let (first_a, first_b) = (i, j);
        if from_a {
            i += 1;
            while a.get(i).is_some_and(|h| order(h, &head) == Ordering::Equal) {
                i += 1;
            }
        }
        if from_b {
            j += 1;
            while b.get(j).is_some_and(|h| order(h, &head) == Ordering::Equal) {
                j += 1;
            }
        }
        let cross_a = (i - first_a) % 2 == 1;
        let cross_b = (j - first_b) % 2 == 1;
        let next = state.step(cross_a, cross_b);
        if (state == x) != (next == x) {
            // Report the surface whose crossing changed the answer: A's when
            // A toggled, B's otherwise.
            let hit = if cross_a { a[i - 1] } else { b[j - 1] };
            out.push(hit);
            kept += 1;
        }
        state = next;
    }
    (op.contains(in_a, in_b), false)
}

/// Whether the state lies inside `C`: in X for ∩ and −, outside X for ∪.
fn inside(op: SetOp, state: MergeState) -> bool {
    let (a, b) = state.flags();
    op.contains(a, b)
}

/// The outward normal of the combined solid seen along a ray: the leaf's
/// normal turned so that it opposes the ray where the ray enters `C` and
/// follows it where the ray leaves. This is how a hit on B's surface in
/// `A − B` gets its normal flipped without any bookkeeping.
#[must_use]
pub fn oriented_normal(leaf_normal: DVec3, direction: DVec3, entering: bool) -> DVec3 {
    let along = leaf_normal.dot(direction) > 0.0;
    if along == entering {
        -leaf_normal
    } else {
        leaf_normal
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn hits(ts: &[f64], leaf: u32) -> Vec<Hit> {
        ts.iter()
            .map(|&t| Hit {
                t,
                spread: 0.0,
                leaf: LeafId(leaf),
                surface: 0,
            })
            .collect()
    }

    fn run(op: SetOp, a: (bool, &[f64]), b: (bool, &[f64])) -> (bool, Vec<f64>) {
        let (ha, hb) = (hits(a.1, 0), hits(b.1, 1));
        let mut out = Vec::new();
        let (inout, stopped) = merge(op, (a.0, &ha), (b.0, &hb), &mut out, None);
        assert!(!stopped);
        (inout, out.iter().map(|h| h.t).collect())
    }

    const ALL: [SetOp; 4] = [
        SetOp::Union,
        SetOp::Intersection,
        SetOp::Difference,
        SetOp::ReverseDifference,
    ];

    #[test]
    fn roths_table_of_state_x_and_inout_c() {
        use MergeState::*;
        let x: Vec<_> = ALL.iter().map(|&op| MergeState::kept_by(op)).collect();
        assert_eq!(x, [InNeither, InBoth, InJustA, InJustB]);
        // INOUT_C for (INOUT_A, INOUT_B) = FF, TF, FT, TT.
        let table = [
            (SetOp::Union, [false, true, true, true]),
            (SetOp::Intersection, [false, false, false, true]),
            (SetOp::Difference, [false, true, false, false]),
            (SetOp::ReverseDifference, [false, false, true, false]),
        ];
        for (op, expected) in table {
            let got: Vec<bool> = [(false, false), (true, false), (false, true), (true, true)]
                .iter()
                .map(|&(a, b)| op.contains(a, b))
                .collect();
            assert_eq!(got, expected, "{op:?}");
            // The state machine's own answer agrees with the table.
            for (k, &(a, b)) in [(false, false), (true, false), (false, true), (true, true)]
                .iter()
                .enumerate()
            {
                assert_eq!(run(op, (a, &[]), (b, &[])).0, expected[k]);
            }
        }
    }

    /// A = [1, 4] ∪ [6, 8] along the ray (origin outside), B = [3, 7].
    /// Worked by hand on a diagram of the two span lists.
    #[test]
    fn hand_worked_lists_from_outside() {
        let a = (false, &[1.0, 4.0, 6.0, 8.0][..]);
        let b = (false, &[3.0, 7.0][..]);
        assert_eq!(run(SetOp::Union, a, b), (false, vec![1.0, 8.0]));
        assert_eq!(
            run(SetOp::Intersection, a, b),
            (false, vec![3.0, 4.0, 6.0, 7.0])
        );
        assert_eq!(
            run(SetOp::Difference, a, b),
            (false, vec![1.0, 3.0, 7.0, 8.0])
        );
        assert_eq!(run(SetOp::ReverseDifference, a, b), (false, vec![4.0, 6.0]));
    }

    /// `((INOUT_A, INOUT_B), [(INOUT_C, t_C list) for ∪, ∩, A − B, B − A])`.
    type StartCase = ((bool, bool), [(bool, &'static [f64]); 4]);

    /// Every start state: A's origin inside or not, B's inside or not.
    /// A = (0, 2] ∪ [5, 9] when inside (crossings 2, 5, 9) or [2, 5] ∪ [9, ∞)
    /// when outside; B = (0, 4] ∪ [8, ∞) when inside (crossings 4, 8) or
    /// [4, 8] when outside.
    #[test]
    fn hand_worked_lists_for_every_start_state() {
        let a_ts = &[2.0, 5.0, 9.0][..];
        let b_ts = &[4.0, 8.0][..];
        #[rustfmt::skip]
        let expected: [StartCase; 4] = [
            // A = [2,5] ∪ [9,∞), B = [4,8]
            ((false, false), [
                (false, &[2.0, 8.0, 9.0]),        // ∪ = [2,8] ∪ [9,∞)
                (false, &[4.0, 5.0]),             // ∩ = [4,5]
                (false, &[2.0, 4.0, 9.0]),        // A−B = [2,4] ∪ [9,∞)
                (false, &[5.0, 8.0]),             // B−A = [5,8]
            ]),
            // A = (0,2] ∪ [5,9], B = [4,8]
            ((true, false), [
                (true, &[2.0, 4.0, 9.0]),         // ∪ = (0,2] ∪ [4,9]
                (false, &[5.0, 8.0]),             // ∩ = [5,8]
                (true, &[2.0, 8.0, 9.0]),         // A−B = (0,2] ∪ [8,9]
                (false, &[4.0, 5.0]),             // B−A = [4,5]
            ]),
            // A = [2,5] ∪ [9,∞), B = (0,4] ∪ [8,∞)
            ((false, true), [
                (true, &[5.0, 8.0]),              // ∪ = (0,5] ∪ [8,∞)
                (false, &[2.0, 4.0, 9.0]),        // ∩ = [2,4] ∪ [9,∞)
                (false, &[4.0, 5.0]),             // A−B = [4,5]
                (true, &[2.0, 8.0, 9.0]),         // B−A = (0,2] ∪ [8,9]
            ]),
            // A = (0,2] ∪ [5,9], B = (0,4] ∪ [8,∞)
            ((true, true), [
                (true, &[4.0, 5.0]),              // ∪ = (0,4] ∪ [5,∞)
                (true, &[2.0, 8.0, 9.0]),         // ∩ = (0,2] ∪ [8,9]
                (false, &[5.0, 8.0]),             // A−B = [5,8]
                (false, &[2.0, 4.0, 9.0]),        // B−A = [2,4] ∪ [9,∞)
            ]),
        ];
        for ((in_a, in_b), per_op) in expected {
            for (op, (inout, ts)) in ALL.into_iter().zip(per_op) {
                let got = run(op, (in_a, a_ts), (in_b, b_ts));
                assert_eq!(got, (inout, ts.to_vec()), "{op:?} from ({in_a}, {in_b})");
            }
        }
    }

    #[test]
    fn equal_t_from_both_sides_are_taken_together() {
        // Touching boxes along the ray: A = [1, 2], B = [2, 3].
        let a = (false, &[1.0, 2.0][..]);
        let b = (false, &[2.0, 3.0][..]);
        assert_eq!(run(SetOp::Union, a, b), (false, vec![1.0, 3.0]));
        assert_eq!(run(SetOp::Intersection, a, b), (false, vec![]));
        assert_eq!(run(SetOp::Difference, a, b), (false, vec![1.0, 2.0]));
        // Coincident spans: A = B = [1, 2].
        let b = (false, &[1.0, 2.0][..]);
        assert_eq!(run(SetOp::Union, a, b), (false, vec![1.0, 2.0]));
        assert_eq!(run(SetOp::Intersection, a, b), (false, vec![1.0, 2.0]));
        assert_eq!(run(SetOp::Difference, a, b), (false, vec![]));
        assert_eq!(run(SetOp::ReverseDifference, a, b), (false, vec![]));
        // B flush with A's far face: A = [1, 3], B = [2, 3]; A − B = [1, 2].
        let a = (false, &[1.0, 3.0][..]);
        let b = (false, &[2.0, 3.0][..]);
        assert_eq!(run(SetOp::Difference, a, b), (false, vec![1.0, 2.0]));
        assert_eq!(run(SetOp::Union, a, b), (false, vec![1.0, 3.0]));
    }

    #[test]
    fn swapping_children_turns_a_minus_b_into_b_minus_a() {
        let a = (true, &[0.5, 1.0, 2.5, 4.0][..]);
        let b = (false, &[1.0, 3.0][..]);
        for op in ALL {
            assert_eq!(run(op, a, b), run(op.swapped(), b, a), "{op:?}");
        }
    }

    #[test]
    fn a_first_hit_merge_stops_after_one_crossing() {
        let ha = hits(&[1.0, 4.0, 6.0, 8.0], 0);
        let hb = hits(&[3.0, 7.0], 1);
        let mut out = Vec::new();
        let (inout, stopped) = merge(SetOp::Union, (false, &ha), (false, &hb), &mut out, Some(1));
        assert!(stopped && !inout);
        assert_eq!(out.len(), 1);
        assert_eq!(out[0].t, 1.0);
    }

    #[test]
    fn normals_turn_with_entering_and_leaving() {
        let d = DVec3::X;
        assert_eq!(oriented_normal(DVec3::X, d, true), -DVec3::X);
        assert_eq!(oriented_normal(-DVec3::X, d, true), -DVec3::X);
        assert_eq!(oriented_normal(-DVec3::X, d, false), DVec3::X);
    }
}
