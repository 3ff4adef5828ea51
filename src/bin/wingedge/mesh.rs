//! `wingedge mesh`: a field document meshed by marching cubes into a
//! validated solid, written as OBJ.

use std::path::Path;
use std::process::ExitCode;
use std::time::Instant;

use wingedge::field::{FieldError, MarchingOptions, Placement, load_json, marching, try_mesh};
use wingedge::io::write_obj;
use wingedge::validate::{Options, Validity, validate_soup};

use crate::output::{Out, Outcome, measure};

/// Builds the marched `soup`, proves it valid and writes it to `output`
/// (atomically); what is written is what was proven: a surface the
/// validator rejects is refused, never written. `name` names the input in
/// messages.
pub fn prove_and_write(
    soup: &wingedge::mesh::PolygonSoup,
    name: &str,
    output: &Path,
) -> Result<(wingedge::mesh::Solid, wingedge::validate::Report), String> {
    let solid = marching::solid_of(soup).map_err(|e| format!("{name}: {e}"))?;
    let report =
        validate_soup(soup, None, &Options::default()).map_err(|e| format!("{name}: {e}"))?;
    if report.validity != Validity::ValidSolid {
        let first = report.violations.first().map_or_else(String::new, |v| {
            format!("; first: {}: {}", v.rule.name(), v.message)
        });
        return Err(format!(
            "{name}: the meshed surface is not a valid solid ({}{first}); {} not written",
            report.validity.describe(),
            output.display()
        ));
    }
    write_obj(&solid, output).map_err(|e| format!("{}: cannot write: {e}", output.display()))?;
    Ok((solid, report))
}

/// The resolution when neither the command nor the document gives one.
pub const DEFAULT_RESOLUTION: usize = 64;

/// Meshes `field` and writes the solid to `output`. Exit 0 for a valid
/// solid, 1 for an empty field (nothing written); 2 for a document or grid
/// it refuses, or (never expected) a surface the validator rejects:
/// nothing is written then either, and an existing file stays as it was.
pub fn run(
    field: &Path,
    output: &Path,
    resolution: Option<usize>,
    midpoints: bool,
    stats: bool,
) -> Outcome {
    // Field-document errors name the file, as every other message does.
    let doc = load_json(field).map_err(|e| {
        let text = e.to_string();
        let name = field.display().to_string();
        if text.starts_with(&name) {
            text
        } else {
            format!("{name}: {text}")
        }
    })?;
    let options = MarchingOptions {
        resolution: resolution.or(doc.resolution).unwrap_or(DEFAULT_RESOLUTION),
        placement: if midpoints {
            Placement::Midpoint
        } else {
            Placement::Interpolated
        },
        ..MarchingOptions::default()
    };
    let name = field.display();
    let start = Instant::now();
    let meshed = match try_mesh(doc.field.as_ref(), &options) {
        Ok(m) if !m.soup.polygons.is_empty() => m,
        Ok(_) | Err(FieldError::Empty) => {
            let mut out = Out::new();
            out.write(format!(
                "{name}: empty: the field is below 1/2 at every sample (resolution {}); nothing written\n",
                options.resolution
            ))?;
            out.finish()?;
            return Ok(ExitCode::from(1));
        }
        Err(e) => return Err(format!("{name}: {e}")),
    };
    let meshing = start.elapsed().as_secs_f64();
    let (solid, report) = prove_and_write(&meshed.soup, &name.to_string(), output)?;
    let [nx, ny, nz] = meshed.dims;
    let genus = report
        .genus
        .map_or_else(|| "-".to_string(), |g| g.to_string());
    let mut out = Out::new();
    out.write(format!(
        "{name}: {} sources, grid {nx}×{ny}×{nz} (cell {}), {} placement\n  \
         triangles {}  vertices {}  shells {}  genus {genus}  volume {}\n  \
         {}  (meshed in {meshing:.3} s)\n  wrote {}\n",
        doc.sources,
        measure(meshed.cell, 6),
        if midpoints {
            "midpoint"
        } else {
            "interpolated"
        },
        meshed.march.triangles,
        meshed.march.vertices,
        report.shells,
        measure(solid.volume(), 6),
        report.validity.describe(),
        output.display(),
    ))?;
    out.finish()?;
    if stats {
        let f = meshed.field;
        eprintln!(
            "field: {f}; per sample: {:.2} candidates, {:.2} source evaluations of {} sources\n\
             march: {} of {} blocks sampled and marched ({} cells), {} cells cut by the surface",
            f.candidates as f64 / f.samples.max(1) as f64,
            f.source_evaluations as f64 / f.samples.max(1) as f64,
            doc.sources,
            meshed.march.blocks_marched,
            meshed.march.blocks,
            meshed.march.cells,
            meshed.march.surface_cells,
        );
    }
    Ok(ExitCode::SUCCESS)
}
