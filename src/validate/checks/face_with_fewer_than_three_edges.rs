//! Validity rule 6: every face has at least three edges.

use super::super::context::{Context, Shape};
use super::super::report::{Rule, Violation};

/// Every face with three or more distinct vertices but fewer than three
/// distinct edges (it walks back along itself: `f 1 2 3 2`).
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    (0..ctx.face_count())
        .filter(|&f| ctx.shape[f] == Shape::TooFewEdges)
        .map(|f| Violation {
            rule: Rule::FaceWithFewerThanThreeEdges,
            message: format!(
                "{} walks back along itself: its corners {} use fewer than 3 distinct edges",
                ctx.face_name(f),
                super::preview(ctx.corners(f))
            ),
            line: ctx.face_line(f),
            lines: ctx.face_line(f).into_iter().collect(),
            vertices: ctx.corners(f).to_vec(),
            faces: vec![f],
            value: None,
        })
        .collect()
}
