//! What a failed output says: no ids of a result that is never written,
//! but each broken rule with its count, where the defects are in world
//! coordinates, and the operands whose faces they are in.

use glam::DVec3;

use super::BooleanError;
use crate::mesh::PolygonSoup;
use crate::validate::Report;

/// The failure of a result the validator refused, said without ids of a
/// result that is never written: each broken rule with its count, the box
/// in world coordinates that holds the defects, and the operands whose
/// faces they are in (`operand_of` a written polygon).
pub(super) fn invalid(
    report: &Report,
    written: &PolygonSoup,
    operand_of: impl Fn(usize) -> Option<usize>,
) -> BooleanError {
    let polygons: Vec<usize> = report
        .violations
        .iter()
        .flat_map(|v| v.faces.iter().copied())
        .collect();
    let mut points: Vec<DVec3> = report
        .violations
        .iter()
        .flat_map(|v| v.vertices.iter())
        .filter_map(|&i| written.positions.get(i).copied())
        .collect();
    points.extend(
        polygons
            .iter()
            .filter_map(|&f| written.polygons.get(f))
            .flat_map(|p| p.vertices.iter())
            .filter_map(|&i| written.positions.get(i).copied()),
    );
    let operands = sorted(polygons.iter().filter_map(|&f| operand_of(f)).collect());
    BooleanError::InvalidResult {
        validity: report.validity.describe().to_string(),
        report: format!("{}{}", rule_counts(report), whereabouts(&points, &operands)),
        operands,
    }
}

/// `rule × count, …` of a report's violations (and why it was not built).
fn rule_counts(report: &Report) -> String {
    let mut counts: Vec<(&str, usize)> = Vec::new();
    for v in &report.violations {
        match counts.iter_mut().find(|(name, _)| *name == v.rule.name()) {
            Some((_, n)) => *n += 1,
            None => counts.push((v.rule.name(), 1)),
        }
    }
    let mut text: Vec<String> = counts
        .iter()
        .map(|(name, n)| format!("{name} × {n}"))
        .collect();
    if let Some(reason) = &report.not_built {
        text.push(reason.clone());
    }
    text.join(", ")
}

/// `; at (lo) … (hi), in faces of operands i and j`: where defects are, in
/// world coordinates and by operand.
fn whereabouts(points: &[DVec3], operands: &[usize]) -> String {
    let mut text = String::new();
    if let Some(first) = points.first() {
        let (lo, hi) = points
            .iter()
            .fold((*first, *first), |(lo, hi), &p| (lo.min(p), hi.max(p)));
        text.push_str(&format!(
            "; at {} … {}",
            crate::geom::ReadableVec(lo),
            crate::geom::ReadableVec(hi)
        ));
    }
    if !operands.is_empty() {
        let names: Vec<String> = operands.iter().map(usize::to_string).collect();
        text.push_str(&format!(
            ", in faces from operand{} {}",
            if operands.len() == 1 { "" } else { "s" },
            names.join(" and ")
        ));
    }
    text
}

/// Why a round's soup could not be built, located: the kind of defect,
/// where it is in world coordinates and which operands' faces meet there
/// (the soup's own numbers name nothing the caller ever sees).
pub(super) fn not_built(
    error: &crate::mesh::BuildError,
    polygons: &[usize],
    soup: &PolygonSoup,
    operand_of: impl Fn(usize) -> Option<usize>,
) -> BooleanError {
    let kind = match error {
        crate::mesh::BuildError::NonManifoldEdge { polygons, .. } => {
            format!("an edge used by {} faces", polygons.len())
        }
        crate::mesh::BuildError::InconsistentOrientation { .. } => {
            "two faces running an edge the same way".to_string()
        }
        other => other.to_string(),
    };
    let points: Vec<DVec3> = polygons
        .iter()
        .filter_map(|&p| soup.polygons.get(p))
        .flat_map(|p| p.vertices.iter().map(|&v| soup.positions[v]))
        .collect();
    let operands = sorted(polygons.iter().filter_map(|&p| operand_of(p)).collect());
    BooleanError::NotBuilt {
        reason: format!("{kind}{}", whereabouts(&points, &operands)),
        operands,
    }
}

/// `operands` sorted, each once.
fn sorted(mut operands: Vec<usize>) -> Vec<usize> {
    operands.sort_unstable();
    operands.dedup();
    operands
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::validate::{Options, validate_soup};

    /// A refused result is described by rule, place and operand, never by
    /// the face numbers of a soup nobody sees.
    #[test]
    fn a_refused_result_is_said_by_rule_place_and_operand() {
        // A quadrilateral bent out of its plane, closed by triangles.
        let mut soup = PolygonSoup::default();
        for p in [
            [0.0, 0.0, 0.0],
            [4.0, 0.0, 0.0],
            [4.0, 4.0, 1.0],
            [0.0, 4.0, 0.0],
            [2.0, 2.0, -3.0],
        ] {
            soup.positions.push(DVec3::from(p));
        }
        for vertices in [
            vec![0, 3, 2, 1],
            vec![0, 1, 4],
            vec![1, 2, 4],
            vec![2, 3, 4],
            vec![3, 0, 4],
        ] {
            soup.polygons.push(crate::mesh::Polygon {
                vertices: vertices.into_iter().collect(),
                attributes: Default::default(),
            });
        }
        let report = validate_soup(&soup, None, &Options::default()).unwrap();
        assert!(!report.is_valid());
        let e = invalid(&report, &soup, |p| Some(p % 2));
        let text = e.to_string();
        assert!(text.contains("non_planar_face × 1"), "{text}");
        assert!(text.contains("at (0, 0, 0) … (4, 4, 1)"), "{text}");
        assert!(text.contains("in faces from operand 0"), "{text}");
        assert!(!text.contains("face 0"), "{text}");
    }
}
