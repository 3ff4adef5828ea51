//! Two faces with the same vertex cycle, in either orientation.

use super::super::context::Context;
use super::super::report::{Rule, Violation};

/// Every later copy of a face, named together with the first copy. Later
/// copies are left out of the edge and vertex counts of the other rules.
pub(crate) fn check(ctx: &Context) -> Vec<Violation> {
    (0..ctx.face_count())
        .filter_map(|f| ctx.duplicate_of[f].map(|first| (first as usize, f)))
        .map(|(first, f)| {
            let same = same_direction(ctx.corners(first), ctx.corners(f));
            let lines: Vec<usize> = [first, f]
                .iter()
                .filter_map(|&g| ctx.face_line(g))
                .collect();
            Violation {
                rule: Rule::DuplicateFace,
                message: format!(
                    "{} repeats {} ({})",
                    ctx.face_name(f),
                    ctx.face_name(first),
                    if same {
                        "same orientation"
                    } else {
                        "opposite orientation"
                    }
                ),
                line: ctx.face_line(f),
                lines,
                vertices: ctx.corners(f).to_vec(),
                faces: vec![f, first],
                value: None,
            }
        })
        .collect()
}

/// Whether two equal cycles run the same way.
fn same_direction(a: &[usize], b: &[usize]) -> bool {
    let k = a.len();
    let Some(shift) = b.iter().position(|&v| v == a[0]) else {
        return true;
    };
    (0..k).all(|i| a[i] == b[(shift + i) % k])
}
