//! The validation benchmark: import, build and fully validate one OBJ file
//! (what `wingedge validate` does), print each stage and the peak memory.
//!
//! ```text
//! cargo run --release --example validate_bench -- MESH.obj [REPEATS]
//! ```
//!
//! `benches/peers_validate.py` runs this example and trimesh load +
//! manifold3d construction of the same file alternately, in one run, and
//! prints the ratio.

use std::path::PathBuf;
use std::time::Instant;

use wingedge::io::{ObjOptions, import_obj};
use wingedge::validate::{Options, validate_and_build};

/// Import seconds, total seconds and the stages of the best run.
type Best = (f64, f64, Vec<(&'static str, f64)>);

fn peak_rss_mib() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kib: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kib / 1024.0)
}

fn main() {
    let mut args = std::env::args().skip(1);
    let Some(path) = args.next().map(PathBuf::from) else {
        eprintln!("usage: validate_bench MESH.obj [REPEATS]");
        std::process::exit(2);
    };
    let repeats: usize = args.next().and_then(|r| r.parse().ok()).unwrap_or(3);
    let mut best: Option<Best> = None;
    let mut summary = String::new();
    for _ in 0..repeats {
        let t0 = Instant::now();
        let import = match import_obj(&path, &ObjOptions::default()) {
            Ok(i) => i,
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(2);
            }
        };
        let t1 = Instant::now();
        let (report, solid) = match validate_and_build(&import, &Options::default()) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(2);
            }
        };
        let t2 = Instant::now();
        let (import_s, total_s) = ((t1 - t0).as_secs_f64(), (t2 - t0).as_secs_f64());
        if best.as_ref().is_none_or(|b| total_s < b.1) {
            let stages = import
                .stage_seconds
                .iter()
                .chain(&report.stage_seconds)
                .copied()
                .collect();
            best = Some((import_s, total_s, stages));
        }
        summary = format!(
            "faces {}  verdict {:?}  violations {}  solid built {}",
            report.faces,
            report.validity,
            report.violations.len(),
            solid.is_some()
        );
    }
    let Some((import_s, total_s, stages)) = best else {
        return;
    };
    println!("{}: {summary}", path.display());
    println!("| stage (best of {repeats}) | s |");
    println!("|---|---:|");
    for (name, t) in stages {
        println!("| {name} | {t:.3} |");
    }
    println!("| import (tobj ∥ line pass, weld) | {import_s:.3} |");
    println!("| import + full validate | {total_s:.3} |");
    println!("peak RSS {:.0} MiB", peak_rss_mib().unwrap_or(f64::NAN));
}
