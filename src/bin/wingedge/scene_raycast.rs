//! `wingedge raycast SCENE.json RAYS`: the in/out spans of each ray through a
//! CSG scene.

use std::fmt::Write as _;
use std::io::Write;
use std::path::Path;
use std::process::ExitCode;

use glam::DVec3;
use wingedge::csg::Stats;
use wingedge::geom::Ray;

use crate::input::{parse_lines, read_source};
use crate::target;

pub fn run(target: &Path, rays: &str, show_stats: bool) -> ExitCode {
    let scene = match target::load(target) {
        Ok(s) => s,
        Err(e) => return crate::fail(&e),
    };
    let rows = match read_source(rays).and_then(|text| parse_lines::<6>(rays, &text)) {
        Ok(r) => r,
        Err(e) => return crate::fail(&e),
    };
    let mut stats = Stats::default();
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    for (line, r) in &rows {
        let ray = Ray::new(DVec3::new(r[0], r[1], r[2]), DVec3::new(r[3], r[4], r[5]));
        if !ray.is_valid() {
            return crate::fail(&format!("{rays}:{line}: the direction is zero"));
        }
        let spans = scene.csg.spans(&ray, &mut stats);
        let mut line = String::from(if spans.origin_inside {
            "inside"
        } else {
            "outside"
        });
        for (a, b) in spans.intervals() {
            let _ = write!(line, " [{a}, {b}]");
        }
        if writeln!(out, "{line}").is_err() {
            return ExitCode::from(2);
        }
    }
    let _ = out.flush();
    if show_stats {
        eprintln!("{stats}");
    }
    ExitCode::SUCCESS
}
