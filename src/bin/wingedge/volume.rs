//! `wingedge volume TARGET [--spacing H]`: the volume of a mesh or a scene.

use std::path::Path;
use std::process::ExitCode;

use wingedge::io::ImportOptions;
use wingedge::scene::Scene;

use crate::output::{Out, Outcome};
use crate::progress::Progress;

/// Grid cells across the longest side of the bounds when no spacing is given.
const DEFAULT_CELLS: f64 = 400.0;

pub fn run(
    target: &Path,
    spacing: Option<f64>,
    integrate: bool,
    show_stats: bool,
    options: &ImportOptions,
) -> Outcome {
    let scene = Scene::from_path_with(target, options).map_err(|e| e.to_string())?;
    let bounds = scene.csg.bounds();
    let spacing = spacing.unwrap_or_else(|| {
        let s = bounds.size();
        s.x.max(s.y).max(s.z) / DEFAULT_CELLS
    });
    // A lone polyhedron or analytic solid has a closed form: print it.
    let single = scene.csg.single_leaf();
    let exact = single.and_then(|l| l.primitive.exact_volume());
    let mut out = Out::new();
    if let (Some(leaf), Some(v), false) = (single, exact, integrate) {
        if !v.is_finite() {
            return Err(format!(
                "{}: the volume of {} overflows f64 (the coordinates are too large to multiply)",
                target.display(),
                leaf.label
            ));
        }
        out.write(format_args!("{v}\n"))?;
        out.finish()?;
        eprintln!(
            "closed-form volume of the single {} (--integrate to cast rays)",
            leaf.label
        );
        return Ok(ExitCode::SUCCESS);
    }
    let progress = Progress::new("volume");
    let estimate = scene
        .csg
        .try_volume_with_progress(spacing, |f| progress.update(f));
    progress.finish();
    match estimate {
        Ok(v) => {
            let volume = exact.unwrap_or(v.volume);
            if !volume.is_finite() {
                return Err(format!(
                    "{}: the volume overflows f64 (the coordinates are too large to multiply)",
                    target.display()
                ));
            }
            out.write(format_args!("{volume}\n"))?;
            out.finish()?;
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
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => Err(format!("{}: {e}", target.display())),
    }
}
