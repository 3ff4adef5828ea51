//! `wingedge mesh SCENE.json` for a CSG scene (a document with `"root"`):
//! marching cubes over the scene's indicator, each grid node classified
//! exactly (inside or on the boundary: 1, outside: 0), so not one cell of
//! the grid is wrong; the surface crosses each cut cell edge at its middle
//! and lies within half a cell of the exact boundary. Fields inside the
//! scene are classified as every command classifies them.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use glam::DVec3;
use wingedge::csg::{Csg, Stats};
use wingedge::field::{Field, FieldError, FieldStats, MarchingOptions, Placement, try_mesh};
use wingedge::geom::Aabb;
use wingedge::query::Containment;
use wingedge::scene::Scene;

use crate::output::{Out, Outcome, measure};

/// A CSG tree as a field: 1 on the closed solid, 0 elsewhere.
struct Indicator<'a> {
    csg: &'a Csg,
    /// The tree's bounds grown by a margin, so that `F < ½` holds strictly
    /// outside the box and on its faces.
    bounds: Aabb,
}

impl Field for Indicator<'_> {
    fn value_counted(&self, p: DVec3, stats: &mut FieldStats) -> f64 {
        stats.samples += 1;
        match self.csg.classify_point(p, &mut Stats::default()) {
            Containment::Outside => 0.0,
            Containment::Inside | Containment::OnBoundary => 1.0,
        }
    }

    fn bounds(&self) -> Aabb {
        self.bounds
    }
}

/// Whether `path` holds a scene rather than a field document: a JSON
/// object with a `"root"` key. Only the top-level keys are kept (the
/// values are skipped, not built), and the read stops at the JSON limit,
/// so the look costs no more memory than the document's text.
pub fn is_scene(path: &Path) -> bool {
    let Ok(bytes) = wingedge::io::read_input_at_most(path, wingedge::io::MAX_JSON_BYTES) else {
        return false;
    };
    serde_json::from_slice::<std::collections::BTreeMap<String, serde::de::IgnoredAny>>(&bytes)
        .is_ok_and(|doc| doc.contains_key("root"))
}

/// Meshes the scene at `path` on a grid of `resolution` cells along its
/// longest side and writes the validated solid to `output`. Exit codes as
/// for field documents.
pub fn run(path: &Path, output: &Path, resolution: Option<usize>) -> Outcome {
    let name = path.display();
    let scene = Scene::from_path(path).map_err(|e| e.to_string())?;
    let bounds = scene.csg.bounds();
    let options = MarchingOptions {
        resolution: resolution.unwrap_or(super::mesh::DEFAULT_RESOLUTION),
        placement: Placement::Midpoint,
        ..MarchingOptions::default()
    };
    let start = Instant::now();
    let meshed = if bounds.is_empty() {
        Err(FieldError::Empty)
    } else {
        // A margin of a thousandth of the box (and at least the spacing of
        // f64 there) keeps the box's faces outside the solid.
        let margin = DVec3::splat(
            (bounds.size().max_element() * 1e-3)
                .max(bounds.min.abs().max(bounds.max.abs()).max_element() * f64::EPSILON * 4.0),
        );
        let field = Indicator {
            csg: &scene.csg,
            bounds: Aabb {
                min: bounds.min - margin,
                max: bounds.max + margin,
            },
        };
        try_mesh(&field, &options)
    };
    let meshed = match meshed {
        Ok(m) if !m.soup.polygons.is_empty() => m,
        Ok(_) | Err(FieldError::Empty) => {
            let mut out = Out::new();
            out.write(format!(
                "{name}: empty: no grid node is in the solid (resolution {}); nothing written\n",
                options.resolution
            ))?;
            out.finish()?;
            return Ok(ExitCode::from(1));
        }
        Err(e) => return Err(format!("{name}: {e}")),
    };
    let meshing = start.elapsed().as_secs_f64();
    let (solid, report) = super::mesh::prove_and_write(&meshed.soup, &name.to_string(), output)?;
    let [nx, ny, nz] = meshed.dims;
    let genus = report
        .genus
        .map_or_else(|| "-".to_string(), |g| g.to_string());
    let mut out = Out::new();
    out.write(format!(
        "{name}: scene of {} leaves, grid {nx}×{ny}×{nz} (cell {}), nodes classified exactly, midpoint placement\n  \
         triangles {}  vertices {}  shells {}  genus {genus}  volume {}\n  \
         {}  (meshed in {meshing:.3} s)\n  wrote {}\n",
        scene.csg.leaves().len(),
        measure(meshed.cell, 6),
        meshed.march.triangles,
        meshed.march.vertices,
        report.shells,
        measure(solid.volume(), 6),
        report.validity.describe(),
        output.display(),
    ))?;
    out.finish()?;
    Ok(ExitCode::SUCCESS)
}
