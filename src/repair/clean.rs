//! Stage 1: the soup cleaned — bit-identical positions merged into one
//! vertex, and polygons dropped that bound nothing: fewer than three
//! distinct corners, a corner visited twice, zero area, a repeat of an
//! earlier polygon, or a polygon and its reverse (which cancel).

use std::collections::HashMap;

use glam::DVec3;
use smallvec::SmallVec;

use crate::mesh::{Polygon, PolygonSoup};

use super::RepairError;
use super::report::{DropReason, DroppedPolygon};
use crate::geom::collinear3d;

/// The cleaned soup: its polygons, each with its index in the input.
pub(crate) struct Cleaned {
    pub soup: PolygonSoup,
    /// The input polygon of each polygon of `soup`.
    pub origin: Vec<usize>,
    /// How many input vertices were merged into others.
    pub welded: usize,
    pub dropped: Vec<DroppedPolygon>,
}

/// Cleans `soup` (see the module's documentation); unreferenced vertices
/// are left out of the result.
///
/// # Errors
///
/// [`RepairError::IndexOutOfRange`] for a corner past the positions,
/// [`RepairError::NonFinitePosition`] for a NaN or infinite coordinate of
/// a vertex a polygon uses.
pub(crate) fn clean(soup: &PolygonSoup) -> Result<Cleaned, RepairError> {
    // One vertex per position (−0 and +0 are one position).
    let key = |p: DVec3| (p + DVec3::ZERO).to_array().map(f64::to_bits);
    let mut first_at: HashMap<[u64; 3], usize> = HashMap::new();
    let merged_into: Vec<usize> = soup
        .positions
        .iter()
        .enumerate()
        .map(|(i, &p)| *first_at.entry(key(p)).or_insert(i))
        .collect();
    let mut dropped = Vec::new();
    let mut kept: Vec<(usize, SmallVec<[usize; 4]>)> = Vec::new();
    // Surviving polygons by their sorted corners.
    let mut by_corners: HashMap<SmallVec<[usize; 4]>, Vec<usize>> = HashMap::new();
    let mut cancelled: Vec<bool> = Vec::new();
    for (index, polygon) in soup.polygons.iter().enumerate() {
        let mut corners: SmallVec<[usize; 4]> = SmallVec::new();
        for &v in &polygon.vertices {
            let Some(&p) = soup.positions.get(v) else {
                return Err(RepairError::IndexOutOfRange {
                    polygon: index,
                    vertex: v,
                    count: soup.positions.len(),
                });
            };
            if !p.is_finite() {
                return Err(RepairError::NonFinitePosition {
                    polygon: index,
                    vertex: v,
                });
            }
            let v = merged_into[v];
            if corners.last() != Some(&v) {
                corners.push(v);
            }
        }
        while corners.len() > 1 && corners.first() == corners.last() {
            corners.pop();
        }
        let reason = if corners.len() < 3 {
            Some(DropReason::FewerThanThreeCorners)
        } else if has_repeat(&corners) {
            Some(DropReason::VisitsACornerTwice)
        } else if zero_area(&corners, &soup.positions) {
            Some(DropReason::ZeroArea)
        } else {
            None
        };
        if let Some(reason) = reason {
            dropped.push(DroppedPolygon {
                polygon: index,
                reason,
            });
            continue;
        }
        let mut sorted = corners.clone();
        sorted.sort_unstable();
        let same = by_corners.entry(sorted).or_default();
        let slot = kept.len();
        let mut fate = None;
        for &other in same.iter() {
            if cancelled[other] {
                continue;
            }
            if cyclic_equal(&kept[other].1, &corners) {
                fate = Some(DropReason::Repeats(kept[other].0));
                break;
            }
            let mut reversed = corners.clone();
            reversed.reverse();
            if cyclic_equal(&kept[other].1, &reversed) {
                cancelled[other] = true;
                dropped.push(DroppedPolygon {
                    polygon: kept[other].0,
                    reason: DropReason::CancelsReverse(index),
                });
                fate = Some(DropReason::CancelsReverse(kept[other].0));
                break;
            }
        }
        if let Some(reason) = fate {
            dropped.push(DroppedPolygon {
                polygon: index,
                reason,
            });
            continue;
        }
        same.push(slot);
        kept.push((index, corners));
        cancelled.push(false);
    }
    dropped.sort_by_key(|d| d.polygon);
    // Compact: only the vertices the kept polygons use, in input order.
    let mut new_index = vec![usize::MAX; soup.positions.len()];
    let mut used: Vec<usize> = kept
        .iter()
        .zip(&cancelled)
        .filter(|(_, c)| !**c)
        .flat_map(|((_, corners), _)| corners.iter().copied())
        .collect();
    used.sort_unstable();
    used.dedup();
    let positions: Vec<DVec3> = used
        .iter()
        .enumerate()
        .map(|(k, &v)| {
            new_index[v] = k;
            soup.positions[v]
        })
        .collect();
    let mut polygons = Vec::with_capacity(kept.len());
    let mut origin = Vec::with_capacity(kept.len());
    for ((index, corners), c) in kept.into_iter().zip(cancelled) {
        if c {
            continue;
        }
        polygons.push(Polygon {
            vertices: corners.iter().map(|&v| new_index[v]).collect(),
            attributes: soup.polygons[index].attributes.clone(),
        });
        origin.push(index);
    }
    let welded = merged_into
        .iter()
        .enumerate()
        .filter(|&(i, &m)| i != m)
        .count();
    Ok(Cleaned {
        soup: PolygonSoup {
            positions,
            polygons,
        },
        origin,
        welded,
        dropped,
    })
}

/// Whether a corner appears twice.
fn has_repeat(corners: &[usize]) -> bool {
    let mut sorted: SmallVec<[usize; 8]> = corners.iter().copied().collect();
    sorted.sort_unstable();
    sorted.windows(2).any(|w| w[0] == w[1])
}

/// Whether every corner lies on the line through the first two, exactly.
fn zero_area(corners: &[usize], positions: &[DVec3]) -> bool {
    let (a, b) = (positions[corners[0]], positions[corners[1]]);
    corners[2..]
        .iter()
        .all(|&c| collinear3d(a, b, positions[c]))
}

/// Whether `a` is `b` turned cyclically.
fn cyclic_equal(a: &[usize], b: &[usize]) -> bool {
    a.len() == b.len()
        && (0..a.len()).any(|shift| (0..a.len()).all(|k| a[(k + shift) % a.len()] == b[k]))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeats_reverses_and_zero_area_are_dropped_and_positions_merged() {
        let positions = vec![
            DVec3::new(0.0, 0.0, 0.0),
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(0.0, 1.0, 0.0),
            DVec3::new(2.0, 0.0, 0.0),
            DVec3::new(-0.0, 0.0, 0.0),
        ];
        let soup = PolygonSoup::new(
            positions,
            [
                vec![0, 1, 2],
                vec![1, 2, 0],
                vec![4, 1, 3],
                vec![0, 2, 3],
                vec![3, 2, 0],
                vec![0, 1, 1],
            ],
        );
        let cleaned = clean(&soup).unwrap();
        assert_eq!(cleaned.welded, 1);
        assert_eq!(cleaned.origin, vec![0]);
        let reasons: Vec<(usize, DropReason)> = cleaned
            .dropped
            .iter()
            .map(|d| (d.polygon, d.reason))
            .collect();
        assert_eq!(
            reasons,
            vec![
                (1, DropReason::Repeats(0)),
                (2, DropReason::ZeroArea),
                (3, DropReason::CancelsReverse(4)),
                (4, DropReason::CancelsReverse(3)),
                (5, DropReason::FewerThanThreeCorners),
            ]
        );
        assert_eq!(cleaned.soup.positions.len(), 3);
    }
}
