//! Validity rule 4, first half: an edge with only one face borders a hole.

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every edge used by exactly one face.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    ctx.edges
        .iter()
        .enumerate()
        .filter(|(e, _)| ctx.uses(*e).len() == 1)
        .map(|(e, edge)| {
            let face = ctx.uses(e)[0].face();
            Violation {
                rule: Rule::EdgeInOneFace,
                message: format!(
                    "edge {}–{} has only one face, {}: it borders a hole",
                    edge.low(),
                    edge.high(),
                    ctx.face_name(face)
                ),
                line: ctx.face_line(face),
                lines: ctx.face_line(face).into_iter().collect(),
                vertices: vec![edge.low(), edge.high()],
                faces: vec![face],
                value: None,
            }
        })
        .collect()
}
