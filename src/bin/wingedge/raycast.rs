//! `wingedge raycast MESH.obj RAYS`: per ray, where its origin is and the
//! parameters of its crossings with the boundary.

use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;

use glam::DVec3;
use wingedge::geom::Ray;

use crate::input::{load_mesh, parse_lines, read_source};

pub fn run(mesh: &Path, rays: &str) -> ExitCode {
    match raycast(mesh, rays) {
        Ok(out) => {
            print!("{out}");
            ExitCode::SUCCESS
        }
        Err(message) => {
            eprintln!("error: {message}");
            ExitCode::from(2)
        }
    }
}

fn raycast(mesh: &Path, source: &str) -> Result<String, String> {
    let text = read_source(source)?;
    let lines = parse_lines::<6>(source, &text)?;
    let mut rays = Vec::with_capacity(lines.len());
    for (line, v) in &lines {
        let ray = Ray::new(DVec3::new(v[0], v[1], v[2]), DVec3::new(v[3], v[4], v[5]));
        if !ray.is_valid() {
            return Err(format!("{source}:{line}: the direction is zero"));
        }
        rays.push(ray);
    }
    let (_, accel) = load_mesh(mesh)?;
    let answers = accel
        .ray_crossings_batch(&rays)
        .map_err(|e| format!("{}: {e}", mesh.display()))?;
    let mut out = String::with_capacity(answers.len() * 24);
    for a in answers {
        out.push_str(a.origin.as_word());
        for h in &a.hits {
            let _ = write!(out, " {:?}", h.t);
        }
        out.push('\n');
    }
    Ok(out)
}
