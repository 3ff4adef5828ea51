//! Validity rule 3: every edge appears in exactly two vertex lists, that is,
//! joins two distinct vertices.

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every edge from a vertex to itself: a face that lists one vertex twice in
/// a row (`f 1 2 2 3`). The face is otherwise judged with the repeat removed.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    ctx.loop_edges
        .iter()
        .map(|&(face, v)| Violation {
            rule: Rule::EdgeWithoutTwoDistinctVertices,
            message: format!(
                "{} has an edge from vertex {v} to itself (the vertex is listed twice in a row)",
                ctx.face_name(face)
            ),
            line: ctx.face_line(face),
            lines: ctx.face_line(face).into_iter().collect(),
            vertices: vec![v, v],
            faces: vec![face],
            value: None,
        })
        .collect()
}
