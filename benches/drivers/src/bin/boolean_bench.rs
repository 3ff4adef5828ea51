//! wingedge's side of the boolean benchmark (`benches/peers/booleans.py`
//! runs it, one process per measurement, and reads its peak memory).
//!
//! ```text
//! cargo run --release -p wingedge-bench --bin boolean_bench -- A.obj B.obj [REPEATS] [OUT.obj]
//! ```
//!
//! Reads both OBJ files (default weld) and builds their winged-edge solids,
//! proves both valid once (untimed: the operands of a benchmark pair are
//! known to be closed solids, as the peers assume), then runs the exact
//! difference `A − B` with the operand check off `REPEATS` times (default 1)
//! on the global rayon pool (`RAYON_NUM_THREADS` sets its size). Only the
//! boolean is timed, not the reading. The result's own proof of validity
//! is part of the boolean and so of the time; the stage split shows it
//! apart (`proof`).
//!
//! Prints one JSON line: the best time, the stage split of the best run,
//! the work counters, the result's counts and verdict, and this process's
//! peak resident memory up to the end of the runs (reading included). With
//! `OUT.obj`, writes the result there afterwards.

use std::path::Path;
use std::time::Instant;
use wingedge::SetOp;

use serde_json::json;
use wingedge::boolean::{BooleanOptions, boolean, prove};
use wingedge::io::{read_obj, write_obj};
use wingedge::mesh::Solid;

#[path = "../peers_io.rs"]
#[allow(dead_code)]
mod peers_io;

use peers_io::{Result, peak_rss_mib};

const USAGE: &str = "usage: boolean_bench A.obj B.obj [REPEATS] [OUT.obj]";

fn main() {
    if let Err(e) = run() {
        eprintln!("boolean_bench: {e}");
        std::process::exit(1);
    }
}

fn run() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(a_path), Some(b_path)) = (args.first(), args.get(1)) else {
        return Err(USAGE.into());
    };
    let repeats: usize = match args.get(2) {
        Some(s) => s.parse().map_err(|_| format!("REPEATS {s:?}: {USAGE}"))?,
        None => 1,
    };
    let out = args.get(3).map(Path::new);

    let a = load(Path::new(a_path))?;
    let b = load(Path::new(b_path))?;
    prove(&a).map_err(|e| format!("{a_path}: {e}"))?;
    prove(&b).map_err(|e| format!("{b_path}: {e}"))?;

    let options = BooleanOptions {
        check_operands: false,
        ..BooleanOptions::default()
    };
    let mut best = None;
    for _ in 0..repeats.max(1) {
        let clock = Instant::now();
        let result = boolean(&a, &b, SetOp::Difference, options)?;
        let seconds = clock.elapsed().as_secs_f64();
        if best.as_ref().is_none_or(|(s, _)| seconds < *s) {
            best = Some((seconds, result));
        }
    }
    let Some((seconds, result)) = best else {
        return Err("no run".into());
    };
    let peak = peak_rss_mib();
    if let Some(path) = out {
        write_obj(&result.solid, path).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let s = &result.stats;
    let line = json!({
        "tool": "wingedge",
        "seconds": seconds,
        "repeats": repeats.max(1),
        "threads": rayon::current_num_threads(),
        "stages": s
            .stages()
            .iter()
            .map(|&(name, seconds)| (name.to_string(), json!(seconds)))
            .collect::<serde_json::Map<_, _>>(),
        "contacts": s.contacts,
        "new_points": s.new_points,
        "cut_triangles": s.cut_triangles,
        "operand_triangles": [triangles(&a), triangles(&b)],
        "vertices": result.solid.vertex_count(),
        "faces": result.solid.face_count(),
        "valid": result.report.is_valid(),
        "volume": result.solid.volume(),
        "peak_rss_mib": peak,
    });
    println!("{line}");
    Ok(())
}

/// Reads an OBJ file into a winged-edge solid.
fn load(path: &Path) -> Result<Solid> {
    let soup = read_obj(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Solid::try_from_soup(&soup).map_err(|e| format!("{}: {e}", path.display()).into())
}

/// Triangles of a solid once every face is triangulated: a face with `n`
/// corners over all its loops and `k` loops gives `n + 2 (k − 1) − 2`.
fn triangles(solid: &Solid) -> usize {
    solid
        .faces()
        .map(|(face, _)| {
            let loops = solid.face_loops(face).count();
            let corners: usize = solid
                .face_loops(face)
                .map(|l| solid.loop_vertices(l).count())
                .sum();
            (corners + 2 * loops).saturating_sub(4)
        })
        .sum()
}
