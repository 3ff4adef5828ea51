//! `wingedge render SCENE -o out.png [--size WxH]`.

use std::path::Path;
use std::process::ExitCode;

use wingedge::csg::Scene;
use wingedge::render::{RenderOptions, render};

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

pub fn run(scene: &Path, out: &Path, size: (u32, u32), show_stats: bool) -> ExitCode {
    let scene_data = match Scene::from_file(scene) {
        Ok(s) => s,
        Err(e) => return crate::fail(&e.to_string()),
    };
    let options = RenderOptions {
        width: size.0,
        height: size.1,
        ..RenderOptions::default()
    };
    let progress = Progress::new("render");
    let started = std::time::Instant::now();
    let (image, stats) = render(&scene_data, &options, &|f| progress.update(f));
    progress.finish();
    if let Err(e) = image.write_png(out) {
        return crate::fail(&e.to_string());
    }
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
    ExitCode::SUCCESS
}
