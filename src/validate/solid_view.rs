//! The solid-level part of validation: build the winged-edge solid from the
//! faces that passed the soup checks, then measure its shells and decide
//! their nesting.

use glam::DVec3;

use super::context::Context;
use super::exact::{volume_sign, winding_number};
use super::report::ShellSummary;
use crate::geom::{Aabb, Sign};
use crate::mesh::{Polygon, PolygonSoup, Solid};

/// What the orientation check needs to know about a shell besides its
/// summary.
pub(crate) struct ShellGeometry {
    /// The exact sign of the shell's signed volume.
    pub volume_sign: Sign,
    /// The shell's first face (soup numbering).
    pub first_face: usize,
    /// "face 3 (line 17)".
    pub first_face_name: String,
}

/// The solid and its shells, or why it could not be built.
pub(crate) struct SolidView {
    pub shells: Vec<ShellSummary>,
    pub geometry: Vec<ShellGeometry>,
    pub volume: Option<f64>,
    pub genus: Option<i64>,
}

/// How many vertices of a shell are tried when deciding whether it lies
/// inside another (a vertex on the other shell's surface is inconclusive).
const NESTING_PROBES: usize = 16;

/// Builds the solid from the faces that count in the topology (repeats in a
/// row collapsed, duplicates and non-polygons left out).
///
/// # Errors
///
/// The build error, as text, when the faces do not form a winged-edge solid.
pub(crate) fn build(ctx: &Context) -> Result<SolidView, String> {
    let mut original = Vec::new();
    let soup = PolygonSoup {
        positions: ctx.soup.positions.clone(),
        polygons: (0..ctx.face_count())
            .filter(|&f| ctx.in_topology[f])
            .map(|f| {
                original.push(f);
                Polygon {
                    vertices: ctx.corners(f).iter().copied().collect(),
                    attributes: ctx.soup.polygons[f].attributes.clone(),
                }
            })
            .collect(),
    };
    let solid = Solid::try_from_soup(&soup).map_err(|e| e.to_string())?;
    let face_of = |id| {
        let built = solid.face(id).attributes.source_index.unwrap_or_default();
        original[built]
    };
    let mut shells = Vec::new();
    let mut geometry = Vec::new();
    let mut triangles_of = Vec::new();
    let mut boxes = Vec::new();
    for shell in solid.shells() {
        let mut triangles: Vec<[DVec3; 3]> = Vec::new();
        let mut area = 0.0;
        for &f in &shell.faces {
            let points: Vec<DVec3> = solid.face_vertices(f).map(|v| solid.position(v)).collect();
            for i in 1..points.len() - 1 {
                triangles.push([points[0], points[i], points[i + 1]]);
            }
            area += solid.face_area(f);
        }
        let first = face_of(shell.faces[0]);
        boxes.push(Aabb::from_points(triangles.iter().flatten().copied()));
        geometry.push(ShellGeometry {
            volume_sign: volume_sign(&triangles),
            first_face: first,
            first_face_name: ctx.face_name(first),
        });
        shells.push(ShellSummary {
            faces: shell.faces.len(),
            vertices: shell.vertex_count,
            edges: shell.edge_count,
            boundary_edges: shell.boundary_edge_count,
            euler_characteristic: shell.euler_characteristic,
            genus: shell.genus(),
            volume: shell.signed_volume,
            area,
            closed: shell.is_closed(),
            depth: None,
            parent: None,
            first_line: ctx.face_line(first),
        });
        triangles_of.push(triangles);
    }
    nest(&mut shells, &triangles_of, &boxes);
    let all_closed = shells.iter().all(|s| s.closed);
    let volume = all_closed.then(|| shells.iter().map(|s| s.volume).sum());
    let genus = if all_closed {
        shells.iter().map(|s| s.genus).sum::<Option<i64>>()
    } else {
        None
    };
    Ok(SolidView {
        shells,
        geometry,
        volume,
        genus,
    })
}

/// Depth and parent of each closed shell: how many closed shells contain it,
/// by exact winding numbers at its vertices.
fn nest(shells: &mut [ShellSummary], triangles: &[Vec<[DVec3; 3]>], boxes: &[Aabb]) {
    let closed: Vec<usize> = (0..shells.len()).filter(|&i| shells[i].closed).collect();
    for &a in &closed {
        let probes: Vec<DVec3> = triangles[a]
            .iter()
            .flatten()
            .step_by(3)
            .take(NESTING_PROBES)
            .copied()
            .collect();
        let mut depth = Some(0);
        let mut parent: Option<(usize, f64)> = None;
        for &b in &closed {
            if a == b {
                continue;
            }
            let inside = probes
                .iter()
                .filter(|&&p| boxes[b].contains(p))
                .find_map(|&p| winding_number(&triangles[b], p));
            let any_in_box = probes.iter().any(|&p| boxes[b].contains(p));
            match inside {
                Some(w) if w != 0 => {
                    depth = depth.map(|d| d + 1);
                    let size = boxes[b].volume();
                    if parent.is_none_or(|(_, s)| size < s) {
                        parent = Some((b, size));
                    }
                }
                None if any_in_box => depth = None,
                _ => {}
            }
        }
        shells[a].depth = depth;
        shells[a].parent = parent.map(|(b, _)| b);
    }
}
