//! `wingedge volume TARGET [--spacing H]`: the volume of a mesh or a scene.

use std::path::Path;
use std::process::ExitCode;

use wingedge::geom::Readable;
use wingedge::io::ImportOptions;
use wingedge::scene::Scene;

use crate::output::{Out, Outcome};
use crate::progress::Progress;

pub fn run(
    target: &Path,
    spacing: Option<f64>,
    integrate: bool,
    show_stats: bool,
    options: &ImportOptions,
) -> Outcome {
    // A bad spacing is the argument's fault: named before the scene is read.
    if let Some(h) = spacing
        && !(h.is_finite() && h > 0.0)
    {
        return Err(format!(
            "--spacing: {}",
            wingedge::csg::VolumeError::BadSpacing { spacing: h }
        ));
    }
    let scene = Scene::from_path_with(target, options).map_err(|e| e.to_string())?;
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
        // Every leaf has a positive volume: 0 is one too small for f64.
        if v == 0.0 {
            return Err(format!(
                "{}: the volume of {} underflows f64 (the solid is too small to measure)",
                target.display(),
                leaf.label
            ));
        }
        out.write(format_args!("{}\n", Readable(v)))?;
        out.finish()?;
        eprintln!(
            "closed-form volume of the single {} (--integrate to cast rays)",
            leaf.label
        );
        return Ok(ExitCode::SUCCESS);
    }
    let progress = Progress::new("volume");
    let estimate = match spacing {
        Some(h) => scene
            .csg
            .try_volume_with_progress(h, |f| progress.update(f)),
        None => scene
            .csg
            .try_default_volume_with_progress(|f| progress.update(f)),
    };
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
            out.write(format_args!("{}\n", Readable(volume)))?;
            out.finish()?;
            eprintln!(
                "ray integration: {} with spacing {} ({} rays){}",
                Readable(v.volume),
                Readable(v.spacing),
                v.rays,
                exact.map_or(String::new(), |e| format!("; closed form {}", Readable(e)))
            );
            if let Some(u) = v.unresolved {
                let label = scene
                    .csg
                    .leaf(u.narrowest)
                    .map_or("a leaf", |l| l.label.as_str());
                eprintln!(
                    "warning: {} leaf(s) narrower than a grid cell may be missed: {label} is {} wide along {} (cells of {}); give a smaller --spacing",
                    u.count,
                    Readable(u.width),
                    ["x", "y"][u.axis],
                    Readable(v.spacing)
                );
            }
            if show_stats {
                eprintln!("{}", v.stats);
            }
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => Err(format!("{}: {e}", target.display())),
    }
}
