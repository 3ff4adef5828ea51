//! `wingedge render SCENE -o out.png [--size WxH]`.

use std::path::Path;
use std::process::ExitCode;

use wingedge::io::ImportOptions;
use wingedge::render::{RenderOptions, render};
use wingedge::scene::Scene;

use crate::output::Outcome;
use crate::progress::Progress;

/// Parses `WxH`.
pub fn parse_size(s: &str) -> Result<(u32, u32), String> {
    let parsed = s
        .split_once(['x', 'X'])
        .and_then(|(w, h)| Some((w.parse::<u32>().ok()?, h.parse::<u32>().ok()?)));
    match parsed {
        Some((w, h)) if w > 0 && h > 0 && u64::from(w) * u64::from(h) <= 100_000_000 => Ok((w, h)),
        _ => Err(format!(
            "size \"{s}\" is not WIDTHxHEIGHT with positive numbers (at most 100 megapixels)"
        )),
    }
}

/// Renders `scene` to `out`; leaves may also resolve inside
/// `allowed.allowed_roots`.
pub fn run(
    scene: &Path,
    out: &Path,
    size: (u32, u32),
    show_stats: bool,
    allowed: &ImportOptions,
) -> Outcome {
    let scene_data = Scene::from_file_with(scene, allowed).map_err(|e| e.to_string())?;
    let options = RenderOptions {
        width: size.0,
        height: size.1,
        ..RenderOptions::default()
    };
    let progress = Progress::new("render");
    let started = std::time::Instant::now();
    let (image, stats) = render(&scene_data, &options, &|f| progress.update(f));
    progress.finish();
    image.write_png(out).map_err(|e| e.to_string())?;
    eprintln!(
        "{}: {}x{} in {:.2} s",
        out.display(),
        size.0,
        size.1,
        started.elapsed().as_secs_f64()
    );
    if show_stats {
        eprintln!("{stats}");
    }
    Ok(ExitCode::SUCCESS)
}
