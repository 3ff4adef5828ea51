//! `wingedge info`: counts and measures of one solid.

use std::path::PathBuf;
use std::process::ExitCode;

use wingedge::io::{read_obj, write_obj};
use wingedge::mesh::{Solid, builders};

use crate::output::{Out, Outcome};

pub fn run(file: Option<PathBuf>, builtin: Option<String>, write: Option<PathBuf>) -> Outcome {
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
            let soup = read_obj(&path).map_err(|e| e.to_string())?;
            let solid =
                Solid::try_from_soup(&soup).map_err(|e| format!("{}: {e}", path.display()))?;
            (path.display().to_string(), solid)
        }
        (None, None) => return Err("give an OBJ file or --builtin NAME".into()),
    };
    let mut out = Out::new();
    out.write(describe(&name, &solid))?;
    out.finish()?;
    if let Some(path) = write {
        write_obj(&solid, &path).map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
    }
    Ok(ExitCode::SUCCESS)
}

fn describe(name: &str, solid: &Solid) -> String {
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
            "    shell {i}: faces {}  edges {}  vertices {}  rings {}  boundary edges {}  χ {}  genus {genus}  volume {:.10}\n",
            shell.faces.len(),
            shell.edge_count,
            shell.vertex_count,
            shell.ring_count,
            shell.boundary_edge_count,
            shell.euler_characteristic,
            shell.signed_volume,
        );
    }
    let centroid = solid.centroid().map_or_else(
        || "-".to_string(),
        |c| format!("({:.10}, {:.10}, {:.10})", c.x, c.y, c.z),
    );
    out += &format!(
        "  volume {:.10}  surface area {:.10}\n  centroid {centroid}\n  bounding box ({}, {}, {}) .. ({}, {}, {})\n",
        solid.volume(),
        solid.surface_area(),
        bounds.min.x,
        bounds.min.y,
        bounds.min.z,
        bounds.max.x,
        bounds.max.y,
        bounds.max.z,
    );
    out
}
