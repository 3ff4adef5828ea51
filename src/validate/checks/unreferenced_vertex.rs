//! A vertex that no face uses.

use rayon::prelude::*;

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every vertex no face refers to.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    (0..ctx.soup.positions.len())
        .into_par_iter()
        .filter(|&v| !ctx.referenced[v])
        .map(|v| Violation {
            rule: Rule::UnreferencedVertex,
            message: format!("{} is used by no face", ctx.vertex_name(v)),
            line: ctx.vertex_line(v),
            lines: ctx.vertex_line(v).into_iter().collect(),
            vertices: vec![v],
            faces: Vec::new(),
            value: None,
        })
        .collect()
}
