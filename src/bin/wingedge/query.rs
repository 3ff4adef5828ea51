//! `wingedge classify TARGET POINTS` and `wingedge raycast TARGET RAYS`:
//! the same commands for a mesh and for a scene, through one
//! [`Target`].

use std::path::Path;

use glam::DVec3;
use wingedge::csg::Stats;
use wingedge::geom::Ray;
use wingedge::io::ImportOptions;
use wingedge::query::Method;
use wingedge::scene::Target;

use crate::input::{parse_lines, read_source};
use crate::output::{Out, Outcome};

/// Prints `inside`, `outside` or `boundary` per point of `source`, in
/// order.
pub fn classify(
    target: &Path,
    source: &str,
    method: Method,
    show_stats: bool,
    options: &ImportOptions,
) -> Outcome {
    let text = read_source(source)?;
    let points: Vec<DVec3> = parse_lines::<3>(source, &text)?
        .iter()
        .map(|(_, p)| DVec3::from_array(*p))
        .collect();
    let target = Target::try_load_with(target, options).map_err(|e| e.to_string())?;
    let mut stats = Stats::default();
    let classes =
        target
            .classify(&points, method, &mut stats)
            .map_err(|e| match target.build_refusal() {
                // Parity or normals on a mesh that is no solid: the build error,
                // and what does answer such a mesh.
                Some(_) => format!("{e} (--method winding answers a mesh that is no solid)"),
                None => e.to_string(),
            })?;
    if let Some(refused) = target.build_refusal() {
        // Only the winding method answers a mesh that is no solid.
        eprintln!(
            "note: {}: parity is undefined for this mesh, which is not a solid ({refused}); \
             answered by the generalized winding number of its triangles",
            target.file().display()
        );
    }
    let mut out = Out::new();
    for c in classes {
        if !out.write(format_args!("{}\n", c.as_word()))? {
            break;
        }
    }
    out.finish()?;
    finish(&target, show_stats, &stats)
}

/// Prints one line per ray of `source` (see [`wingedge::scene::RayAnswer`]).
pub fn raycast(target: &Path, source: &str, show_stats: bool, options: &ImportOptions) -> Outcome {
    let text = read_source(source)?;
    let mut rays = Vec::new();
    for (line, v) in parse_lines::<6>(source, &text)? {
        let ray = Ray::new(DVec3::new(v[0], v[1], v[2]), DVec3::new(v[3], v[4], v[5]));
        if !ray.is_valid() {
            return Err(format!("{source}:{line}: the direction is zero"));
        }
        rays.push(ray);
    }
    let target = Target::try_load_with(target, options).map_err(|e| e.to_string())?;
    let mut stats = Stats::default();
    let answers = target.rays(&rays, &mut stats).map_err(|e| e.to_string())?;
    let mut out = Out::new();
    for a in answers {
        if !out.write(format_args!("{a}\n"))? {
            break;
        }
    }
    out.finish()?;
    finish(&target, show_stats, &stats)
}

/// Prints a scene's work counters when asked (a mesh has none).
fn finish(target: &Target, show_stats: bool, stats: &Stats) -> Outcome {
    if show_stats && target.scene().is_some() {
        eprintln!("{stats}");
    }
    Ok(std::process::ExitCode::SUCCESS)
}
