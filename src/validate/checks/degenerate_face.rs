//! A face with zero area or that is not simple: all vertices collinear, two
//! vertices at one position, one vertex visited twice (not in a row: that is
//! an edge from a vertex to itself), or two edges that meet (a bow tie).

use rayon::prelude::*;

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every face with at least three distinct vertices and edges that is
/// degenerate. Collinearity and coincidence are decided exactly.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    (0..ctx.face_count())
        .into_par_iter()
        .filter(|&f| ctx.degenerate[f])
        .filter_map(|f| {
            let why = ctx.degeneracy(f)?;
            Some(Violation {
                rule: Rule::DegenerateFace,
                message: format!("{} is degenerate: it {why}", ctx.face_name(f)),
                line: ctx.face_line(f),
                lines: ctx.face_line(f).into_iter().collect(),
                vertices: ctx.corners(f).to_vec(),
                faces: vec![f],
                value: None,
            })
        })
        .collect()
}
