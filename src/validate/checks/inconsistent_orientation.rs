//! Two faces that run a shared edge in the same direction disagree on which
//! side is outside.

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every edge with exactly two faces that both run it the same way. (Edges
/// with three or more faces are non-manifold and reported as such.)
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    ctx.edges
        .iter()
        .enumerate()
        .filter_map(|(e, edge)| match ctx.uses(e) {
            [a, b] if a.forward == b.forward => {
                let (from, to) = if a.forward {
                    (edge.low(), edge.high())
                } else {
                    (edge.high(), edge.low())
                };
                let lines: Vec<usize> = [a.face(), b.face()]
                    .iter()
                    .filter_map(|&f| ctx.face_line(f))
                    .collect();
                Some(Violation {
                    rule: Rule::InconsistentOrientation,
                    message: format!(
                        "{} and {} both run edge {from}→{to}: their orientations disagree",
                        ctx.face_name(a.face()),
                        ctx.face_name(b.face())
                    ),
                    line: lines.first().copied(),
                    lines,
                    vertices: vec![from, to],
                    faces: vec![a.face(), b.face()],
                    value: None,
                })
            }
            _ => None,
        })
        .collect()
}
