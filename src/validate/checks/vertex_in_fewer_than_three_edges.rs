//! Validity rule 1: every vertex appears in at least three edge lists.

use rayon::prelude::*;

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every referenced vertex with fewer than three edges. (Unreferenced
/// vertices are reported by [`Rule::UnreferencedVertex`] instead.)
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    (0..ctx.soup.positions.len())
        .into_par_iter()
        .filter(|&v| ctx.referenced[v])
        .filter_map(|v| {
            let count = ctx.vertex_edges(v).len();
            (count < 3).then(|| Violation {
                rule: Rule::VertexInFewerThanThreeEdges,
                message: format!(
                    "{} lies on {count} edge{}; a vertex needs at least 3",
                    ctx.vertex_name(v),
                    if count == 1 { "" } else { "s" }
                ),
                line: ctx.vertex_line(v),
                lines: ctx.vertex_line(v).into_iter().collect(),
                vertices: vec![v],
                faces: Vec::new(),
                value: Some(count as f64),
            })
        })
        .collect()
}
