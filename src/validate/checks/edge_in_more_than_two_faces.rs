//! Validity rule 4, second half: an edge with three or more faces is
//! non-manifold.

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every edge used by three or more faces.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    ctx.edges
        .iter()
        .enumerate()
        .filter(|(e, _)| ctx.uses(*e).len() >= 3)
        .map(|(e, edge)| {
            let faces: Vec<usize> = ctx.uses(e).iter().map(|u| u.face()).collect();
            let lines: Vec<usize> = faces.iter().filter_map(|&f| ctx.face_line(f)).collect();
            Violation {
                rule: Rule::EdgeInMoreThanTwoFaces,
                message: format!(
                    "edge {}–{} has {} faces {} (lines {}); a manifold edge has 2",
                    edge.low(),
                    edge.high(),
                    faces.len(),
                    super::preview(&faces),
                    super::preview(&lines)
                ),
                line: lines.first().copied(),
                lines,
                vertices: vec![edge.low(), edge.high()],
                faces,
                value: None,
            }
        })
        .collect()
}
