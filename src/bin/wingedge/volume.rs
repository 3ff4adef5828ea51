//! `wingedge volume TARGET [--spacing H]`: the volume of a mesh or a scene.

use std::path::Path;
use std::process::ExitCode;

use crate::progress::Progress;
use crate::target;

/// Grid cells across the longest side of the bounds when no spacing is given.
const DEFAULT_CELLS: f64 = 400.0;

pub fn run(target: &Path, spacing: Option<f64>, integrate: bool, show_stats: bool) -> ExitCode {
    let scene = match target::load(target) {
        Ok(s) => s,
        Err(e) => return crate::fail(&e),
    };
    let bounds = scene.csg.bounds();
    let spacing = spacing.unwrap_or_else(|| {
        let s = bounds.size();
        s.x.max(s.y).max(s.z) / DEFAULT_CELLS
    });
    // A lone polyhedron or analytic solid has a closed form: print it.
    let exact = scene
        .csg
        .single_leaf()
        .and_then(|l| l.primitive.exact_volume());
    if let (Some(v), false) = (exact, integrate) {
        println!("{v}");
        eprintln!(
            "closed-form volume of the single {} (--integrate to cast rays)",
            scene.csg.leaves()[0].label
        );
        return ExitCode::SUCCESS;
    }
    let progress = Progress::new("volume");
    let estimate = scene
        .csg
        .try_volume_with_progress(spacing, |f| progress.update(f));
    progress.finish();
    match estimate {
        Ok(v) => {
            println!("{}", exact.unwrap_or(v.volume));
            eprintln!(
                "ray integration: {} with spacing {} ({} rays){}",
                v.volume,
                v.spacing,
                v.rays,
                exact.map_or(String::new(), |e| format!("; closed form {e}"))
            );
            if show_stats {
                eprintln!("{}", v.stats);
            }
            ExitCode::SUCCESS
        }
        Err(e) => crate::fail(&format!("{}: {e}", target.display())),
    }
}
