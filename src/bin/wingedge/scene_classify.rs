//! `wingedge classify SCENE.json POINTS`: inside, outside or boundary per
//! point, against a CSG scene (the same output as for a mesh).

use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

use glam::DVec3;
use wingedge::csg::Stats;

use crate::input::{parse_lines, read_source};
use crate::target;

pub fn run(target: &Path, points: &str, show_stats: bool) -> ExitCode {
    let scene = match target::load(target) {
        Ok(s) => s,
        Err(e) => return crate::fail(&e),
    };
    let rows = match read_source(points).and_then(|text| parse_lines::<3>(points, &text)) {
        Ok(r) => r,
        Err(e) => return crate::fail(&e),
    };
    let mut stats = Stats::default();
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    for (_, p) in rows {
        let class = scene
            .csg
            .classify_point(DVec3::new(p[0], p[1], p[2]), &mut stats);
        if writeln!(out, "{}", class.as_word()).is_err() {
            return ExitCode::from(2);
        }
    }
    let _ = out.flush();
    if show_stats {
        eprintln!("{stats}");
    }
    ExitCode::SUCCESS
}
