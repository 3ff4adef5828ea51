//! Validity rule 5: every face has at least three vertices.

use super::super::context::{Context, Shape};
use super::super::report::{Rule, Violation};

/// Every face with fewer than three distinct vertices (the reader already
/// refuses faces with fewer than three corners, so these repeat vertices:
/// `f 1 2 1 2`).
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    (0..ctx.face_count())
        .filter(|&f| ctx.shape[f] == Shape::TooFewVertices)
        .map(|f| {
            let mut vertices = ctx.corners(f).to_vec();
            vertices.sort_unstable();
            vertices.dedup();
            Violation {
                rule: Rule::FaceWithFewerThanThreeVertices,
                message: format!(
                    "{} has only {} distinct vertices {:?}; a face needs at least 3",
                    ctx.face_name(f),
                    vertices.len(),
                    vertices
                ),
                line: ctx.face_line(f),
                lines: ctx.face_line(f).into_iter().collect(),
                value: Some(vertices.len() as f64),
                vertices,
                faces: vec![f],
            }
        })
        .collect()
}
