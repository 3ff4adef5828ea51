//! The faces around a vertex must form a single fan; two cones sharing a tip
//! do not, nor two holes touching at a corner.

use rayon::prelude::*;

use super::super::context::Context;
use super::super::report::{Rule, Violation};
use crate::disjoint_sets::DisjointSets;

/// Every vertex whose faces fall into more than one group when faces are
/// joined through the edges they share at the vertex.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    (0..ctx.soup.positions.len())
        .into_par_iter()
        .filter_map(|v| {
            let mut faces: Vec<usize> = ctx.vertex_faces(v).iter().map(|&f| f as usize).collect();
            faces.dedup();
            if faces.len() < 2 {
                return None;
            }
            let mut fans = DisjointSets::new(faces.len());
            for &e in ctx.vertex_edges(v) {
                let uses = ctx.uses(e as usize);
                let slot = |f: usize| faces.binary_search(&f).ok();
                if let Some(first) = uses.first().and_then(|u| slot(u.face())) {
                    for u in &uses[1..] {
                        if let Some(other) = slot(u.face()) {
                            fans.union(first, other);
                        }
                    }
                }
            }
            let fan_count = (0..faces.len()).filter(|&i| fans.find(i) == i).count();
            // A fan is open when one of its edges at the vertex has only
            // one face: a hole passes the vertex there.
            let mut open: Vec<usize> = Vec::new();
            for &e in ctx.vertex_edges(v) {
                if let [only] = ctx.uses(e as usize)
                    && let Ok(i) = faces.binary_search(&only.face())
                {
                    open.push(fans.find(i));
                }
            }
            open.sort_unstable();
            open.dedup();
            let holes = if open.len() > 1 {
                format!("; {} of them border holes, which touch there", open.len())
            } else {
                String::new()
            };
            (fan_count > 1).then(|| Violation {
                rule: Rule::NonManifoldVertex,
                message: format!(
                    "{} is a pinch point: its {} faces form {fan_count} separate fans{holes}",
                    ctx.vertex_name(v),
                    faces.len()
                ),
                line: ctx.vertex_line(v),
                lines: ctx.vertex_line(v).into_iter().collect(),
                vertices: vec![v],
                faces,
                value: Some(fan_count as f64),
            })
        })
        .collect()
}
