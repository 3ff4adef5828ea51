//! `wingedge classify MESH.obj POINTS`: inside / outside / boundary per point.

use std::fmt::Write as _;
use std::path::Path;
use std::process::ExitCode;

use glam::DVec3;
use wingedge::query::Method;

use crate::input::{load_mesh, parse_lines, read_source};

pub fn run(mesh: &Path, points: &str, method: Method) -> ExitCode {
    match classify(mesh, points, method) {
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

fn classify(mesh: &Path, source: &str, method: Method) -> Result<String, String> {
    let text = read_source(source)?;
    let lines = parse_lines::<3>(source, &text)?;
    let (_, accel) = load_mesh(mesh)?;
    let points: Vec<DVec3> = lines.iter().map(|(_, p)| DVec3::from_array(*p)).collect();
    let classes = accel
        .classify_batch(&points, method)
        .map_err(|e| format!("{}: {e}", mesh.display()))?;
    let mut out = String::with_capacity(classes.len() * 8);
    for c in classes {
        let _ = writeln!(out, "{}", c.as_word());
    }
    Ok(out)
}
