//! A face whose vertices do not lie in one plane (four or more points need
//! not be coplanar), beyond the planarity tolerance.

use glam::DVec3;

use rayon::prelude::*;

use super::super::context::{Context, Shape};
use super::super::report::{Rule, Violation};
use crate::geom::Plane;

/// Every face of four or more vertices (not degenerate) whose largest vertex
/// distance from its Newell plane exceeds `tolerance.planarity × diagonal`.
/// The deviation is reported as the violation's value.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    let limit = ctx.tolerance.planarity_limit(ctx.diagonal);
    (0..ctx.face_count())
        .into_par_iter()
        .filter(|&f| ctx.shape[f] == Shape::Polygon && ctx.corners(f).len() > 3)
        .filter(|&f| !ctx.degenerate[f])
        .filter_map(|f| {
            let points: Vec<DVec3> = ctx.corners(f).iter().map(|&v| ctx.position(v)).collect();
            let fit = Plane::try_fit_newell(&points).ok()?;
            (fit.max_deviation > limit).then(|| Violation {
                rule: Rule::NonPlanarFace,
                message: format!(
                    "{} is not planar: a vertex lies {:.3e} from its plane, more than the tolerance {:.3e}",
                    ctx.face_name(f),
                    fit.max_deviation,
                    limit
                ),
                line: ctx.face_line(f),
                lines: ctx.face_line(f).into_iter().collect(),
                vertices: ctx.corners(f).to_vec(),
                faces: vec![f],
                value: Some(fit.max_deviation),
            })
        })
        .collect()
}
