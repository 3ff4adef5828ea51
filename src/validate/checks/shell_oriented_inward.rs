//! A closed shell whose faces point into the material.
//!
//! An outer shell must enclose positive signed volume; a cavity (a closed
//! shell inside one other shell, as in a hollow ball) must enclose negative
//! volume; an island inside a cavity positive again, and so on. The sign of
//! each shell's volume is exact ([`volume_sign`](super::super::exact::volume_sign)),
//! and nesting is decided by exact winding numbers.

use super::super::report::{Rule, ShellSummary, Violation};
use super::super::solid_view::ShellGeometry;
use crate::geom::Sign;

/// Every closed shell whose exact volume sign disagrees with its nesting
/// depth. Shells whose depth could not be decided (they touch another shell)
/// are judged as outer shells only if they are not inside anything.
pub(crate) fn check(shells: &[ShellGeometry], summaries: &[ShellSummary]) -> Vec<Violation> {
    shells
        .iter()
        .zip(summaries)
        .enumerate()
        .filter(|(_, (g, s))| s.closed && g.volume_sign != Sign::Zero)
        .filter_map(|(index, (g, s))| {
            let depth = s.depth?;
            let expected = if depth % 2 == 0 {
                Sign::Positive
            } else {
                Sign::Negative
            };
            if g.volume_sign == expected {
                return None;
            }
            let message = if depth % 2 == 0 {
                format!(
                    "shell {index} ({} faces, starting at {}) is oriented inward: its faces point into the solid (signed volume {:.6e})",
                    s.faces, g.first_face_name, s.volume
                )
            } else {
                format!(
                    "shell {index} ({} faces, starting at {}) is a cavity inside shell {} but is oriented like an outer shell: its faces point into the material (signed volume {:.6e})",
                    s.faces,
                    g.first_face_name,
                    s.parent.map_or_else(|| "?".to_string(), |p| p.to_string()),
                    s.volume
                )
            };
            Some(Violation {
                rule: Rule::ShellOrientedInward,
                message,
                line: s.first_line,
                lines: s.first_line.into_iter().collect(),
                vertices: Vec::new(),
                faces: vec![g.first_face],
                value: Some(s.volume),
            })
        })
        .collect()
}
