//! Validity rule 2: every vertex appears in at least three face lists.

use rayon::prelude::*;

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every referenced vertex on fewer than three distinct faces.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    (0..ctx.soup.positions.len())
        .into_par_iter()
        .filter(|&v| ctx.referenced[v])
        .filter_map(|v| {
            let mut faces: Vec<usize> = ctx.vertex_faces(v).iter().map(|&f| f as usize).collect();
            faces.dedup();
            let count = faces.len();
            (count < 3).then(|| Violation {
                rule: Rule::VertexInFewerThanThreeFaces,
                message: format!(
                    "{} lies on {count} face{}; a vertex needs at least 3",
                    ctx.vertex_name(v),
                    if count == 1 { "" } else { "s" }
                ),
                line: ctx.vertex_line(v),
                lines: ctx.vertex_line(v).into_iter().collect(),
                vertices: vec![v],
                faces,
                value: Some(count as f64),
            })
        })
        .collect()
}
