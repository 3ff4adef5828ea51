//! `wingedge info`: counts and measures of one solid.

use std::path::PathBuf;
use std::process::ExitCode;

use wingedge::io::{Format, ImportOptions, import, write_obj};
use wingedge::mesh::{Solid, builders};

use wingedge::geom::ReadableVec;

use crate::output::{Out, Outcome, measure};

pub fn run(
    file: Option<PathBuf>,
    builtin: Option<String>,
    write: Option<PathBuf>,
    format: Option<Format>,
) -> Outcome {
    let (name, solid) = match (file, builtin) {
        (_, Some(name)) => match builders::by_name(&name) {
            Some(solid) => (name, solid),
            None => {
                return Err(format!(
                    "unknown built-in solid '{name}'; choose one of: {}",
                    builders::NAMES.join(", ")
                ));
            }
        },
        (Some(path), None) => {
            let options = ImportOptions {
                format,
                ..ImportOptions::default()
            };
            let soup = import(&path, &options).map_err(|e| e.to_string())?.soup;
            let solid =
                Solid::try_from_soup(&soup).map_err(|e| format!("{}: {e}", path.display()))?;
            (path.display().to_string(), solid)
        }
        (None, None) => return Err("give an OBJ file or --builtin NAME".into()),
    };
    // Each measure once: a million-face solid takes a while for each.
    let (volume, area) = (solid.volume(), solid.surface_area());
    let mut out = Out::new();
    out.write(describe(&name, &solid, volume, area))?;
    out.finish()?;
    if let Some(path) = write {
        write_obj(&solid, &path).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    if !(volume.is_finite() && area.is_finite()) {
        eprintln!(
            "warning: {name}: the volume or area overflows f64 (the coordinates are too large to multiply)"
        );
        return Ok(ExitCode::from(1));
    }
    Ok(ExitCode::SUCCESS)
}

fn describe(name: &str, solid: &Solid, volume: f64, area: f64) -> String {
    let bounds = solid.bounding_box();
    let shells = solid.shells();
    let mut out = format!(
        "{name}\n  vertices {}  edges {}  faces {}  euler characteristic {}\n  closed {}  shells {}  rings {}\n",
        solid.vertex_count(),
        solid.edge_count(),
        solid.face_count(),
        solid.euler_characteristic(),
        solid.is_closed(),
        shells.len(),
        solid.ring_count(),
    );
    for (i, shell) in shells.iter().enumerate() {
        let genus = shell
            .genus()
            .map_or_else(|| "-".to_string(), |g| g.to_string());
        out += &format!(
            "    shell {i}: faces {}  edges {}  vertices {}  rings {}  boundary edges {}  χ {}  genus {genus}  volume {}\n",
            shell.faces.len(),
            shell.edge_count,
            shell.vertex_count,
            shell.ring_count,
            shell.boundary_edge_count,
            shell.euler_characteristic,
            measure(shell.signed_volume, 10),
        );
    }
    let centroid = solid.centroid().map_or_else(
        || "-".to_string(),
        |c| {
            format!(
                "({}, {}, {})",
                measure(c.x, 10),
                measure(c.y, 10),
                measure(c.z, 10)
            )
        },
    );
    out += &format!(
        "  volume {}  surface area {}\n  centroid {centroid}\n  bounding box {} .. {}\n",
        measure(volume, 10),
        measure(area, 10),
        ReadableVec(bounds.min),
        ReadableVec(bounds.max),
    );
    out
}
