//! wingedge's side of the peer comparison (`benches/peers/run.py` runs it).
//!
//! ```text
//! cargo run --release -p wingedge-bench --bin peers_wingedge -- queries DIR NAME[@SET]...
//! cargo run --release -p wingedge-bench --bin peers_wingedge -- validate FILE.obj [REPEATS]
//! ```
//!
//! **queries**: for each `NAME`, reads `DIR/NAME.obj` and builds the
//! winged-edge solid (timed as `load_s`), builds the [`Accel`] (best of 3,
//! `accel_s`), then reads `DIR/NAME.points.f64` (N × 3 little-endian `f64`)
//! and `DIR/NAME.rays.f64` (N × 6: origin, direction) — reading is not timed —
//! and times [`Accel::classify_batch`] (parity) and [`Accel::first_hit_batch`],
//! best of 3 each (one when a call takes over 5 s), on the global rayon pool (`RAYON_NUM_THREADS` sets its
//! size). Answers go to `DIR/NAME.wingedge.points.u8` (0 outside, 1 inside,
//! 2 on the boundary), `DIR/NAME.wingedge.rays.f64` (first-hit `t`, `inf`
//! for a miss) and `DIR/NAME.wingedge.hitface.u32` (per ray `2 · face +
//! exit`, `face` the index in the solid's face order, `u32::MAX` for a miss:
//! the exact decisions, for comparing two builds file to file); one JSON line
//! per mesh goes to stdout (`accel_bytes`: the accel's heap bytes after the
//! queries, the point grid included; `grid_s`: the grid's build, part of
//! the first point query).
//!
//! `NAME@SET` asks one of the harder query sets of `inputs.py` instead:
//! the mesh is still `DIR/NAME.obj`, the queries are
//! `DIR/NAME.SET.points.f64` and `DIR/NAME.SET.rays.f64` — whichever of the
//! two exists; a set holds points or rays — and the answers go to
//! `DIR/NAME.SET.wingedge.*`.
//!
//! **validate**: what `wingedge validate` does — import (tobj and the line
//! pass, welding), build the winged-edge solid, every check (the exact
//! self-intersection check included) — best of `REPEATS` (default 1), then
//! one JSON line with the times, the verdict, the counts, genus, volume and
//! this process's peak resident memory. Run it in a fresh process per
//! measurement when the memory matters.
//!
//! Profiling aids (queries): `WINGEDGE_ONLY=points|rays|build` restricts the
//! work (`build`: ten accel builds, no answers written); `WINGEDGE_CPU=1`
//! prints the wall and whole-process CPU time of each measurement to stderr
//! (CPU seconds are what other jobs on a shared machine inflate least);
//! `WINGEDGE_TRACE=1` prints the mean BVH nodes and triangles a first-hit ray
//! visits, and how many of those triangles the `f32` filter left to the
//! exact test (over the first 100,000 rays); `WINGEDGE_RUNS=N` times each
//! query batch `N` times (3 by default) and keeps the best.
//! Run with `RAYON_NUM_THREADS=1` for single-thread rates.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde_json::json;
use wingedge::geom::Ray;
use wingedge::glam::DVec3;
use wingedge::io::{ObjOptions, import_obj, read_obj};
use wingedge::mesh::{FaceId, Solid};
use wingedge::query::{Accel, Containment, Method, Transition};
use wingedge::validate::{Options, validate_and_build};

#[path = "../peers_io.rs"]
mod peers_io;

use peers_io::{Result, peak_rss_mib, read_f64s, write_answers};

const USAGE: &str =
    "usage: peers_wingedge queries DIR NAME... | peers_wingedge validate FILE.obj [REPEATS]";

/// CPU time of the whole process (every thread), seconds.
fn process_cpu() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime only writes into the timespec we own.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

/// A call slower than this is not repeated (as the Python peers do).
const REPEAT_BELOW_S: f64 = 5.0;

/// Best wall time of `runs` calls (at least one; one if a call takes over
/// [`REPEAT_BELOW_S`]) and the last result.
fn best_of<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let (mut best, mut best_cpu, mut out) = (f64::INFINITY, f64::INFINITY, None);
    for _ in 0..runs.max(1) {
        if out.is_some() && best > REPEAT_BELOW_S {
            break;
        }
        let (t, c) = (Instant::now(), process_cpu());
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        best_cpu = best_cpu.min(process_cpu() - c);
        out = Some(std::hint::black_box(r));
    }
    if std::env::var_os("WINGEDGE_CPU").is_some() {
        eprintln!("    wall {best:.4} s, process cpu {best_cpu:.4} s");
    }
    (best, out.expect("runs.max(1) >= 1"))
}

/// Reads `N × width` `f64`s from `path`, or `None` when a query set has no such file.
fn read_optional(path: &Path, width: usize, in_set: bool) -> Result<Option<Vec<f64>>> {
    if in_set && !path.exists() {
        return Ok(None);
    }
    read_f64s(path, width).map(Some)
}

fn queries(dir: &Path, request: &str) -> Result<()> {
    // `NAME@SET`: the mesh NAME, the query files and answers of NAME.SET.
    let (name, stem, in_set) = match request.split_once('@') {
        Some((name, set)) => (name, format!("{name}.{set}"), true),
        None => (request, request.to_owned(), false),
    };
    let only = std::env::var("WINGEDGE_ONLY").unwrap_or_default();
    let repeats = std::env::var("WINGEDGE_RUNS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3);
    let runs = |what: &str| {
        if only.is_empty() || only == what {
            repeats
        } else {
            0
        }
    };
    let obj = dir.join(format!("{name}.obj"));
    let t = Instant::now();
    let soup = read_obj(&obj)?;
    let solid = Solid::try_from_soup(&soup).map_err(|e| format!("{}: {e}", obj.display()))?;
    let load_s = t.elapsed().as_secs_f64();
    let (accel_s, accel) = best_of(3, || Accel::new(&solid));
    if only == "build" {
        for _ in 0..10 {
            std::hint::black_box(Accel::new(&solid));
        }
        return Ok(());
    }
    let points: Vec<DVec3> = read_optional(&dir.join(format!("{stem}.points.f64")), 3, in_set)?
        .unwrap_or_default()
        .chunks_exact(3)
        .map(|c| DVec3::new(c[0], c[1], c[2]))
        .collect();
    let rays: Vec<Ray> = read_optional(&dir.join(format!("{stem}.rays.f64")), 6, in_set)?
        .unwrap_or_default()
        .chunks_exact(6)
        .map(|c| Ray::new(DVec3::new(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5])))
        .collect();
    let (points_s, classes) = if runs("points") > 0 && !points.is_empty() {
        let (s, c) = best_of(runs("points"), || {
            accel.classify_batch(&points, Method::Parity)
        });
        (s, c?)
    } else {
        (f64::NAN, Vec::new())
    };
    if std::env::var_os("WINGEDGE_TRACE").is_some() {
        let sample = &rays[..rays.len().min(100_000)];
        let (mut nodes, mut triangles, mut exact) = (0u64, 0u64, 0u64);
        for ray in sample {
            let (_, s) = accel.first_hit_traced(ray)?;
            nodes += s.nodes;
            triangles += s.triangles;
            exact += s.exact_tests;
        }
        let k = sample.len().max(1) as f64;
        eprintln!(
            "    {name}: per first-hit ray {:.1} nodes, {:.1} triangles, {:.1} of them tested exactly",
            nodes as f64 / k,
            triangles as f64 / k,
            exact as f64 / k
        );
    }
    let (rays_s, hits) = if runs("rays") > 0 && !rays.is_empty() {
        let (s, h) = best_of(runs("rays"), || accel.first_hit_batch(&rays));
        (s, h?)
    } else {
        (f64::NAN, Vec::new())
    };
    if !classes.is_empty() {
        let codes = classes
            .iter()
            .map(|c| match c {
                Containment::Outside => 0,
                Containment::Inside => 1,
                Containment::OnBoundary => 2,
            })
            .collect();
        write_answers(&dir.join(format!("{stem}.wingedge.points.u8")), codes)?;
    }
    if !hits.is_empty() {
        let ts = hits
            .iter()
            .flat_map(|h| h.map_or(f64::INFINITY, |c| c.t).to_le_bytes())
            .collect();
        write_answers(&dir.join(format!("{stem}.wingedge.rays.f64")), ts)?;
        let face_index: HashMap<FaceId, u32> = solid
            .faces()
            .enumerate()
            .map(|(k, (id, _))| (id, k as u32))
            .collect();
        let faces = hits
            .iter()
            .flat_map(|h| {
                h.map_or(u32::MAX, |c| {
                    2 * face_index[&c.face] + u32::from(c.transition == Transition::Exit)
                })
                .to_le_bytes()
            })
            .collect();
        write_answers(&dir.join(format!("{stem}.wingedge.hitface.u32")), faces)?;
    }
    let count = |want: Containment| classes.iter().filter(|&&c| c == want).count();
    // After the queries, so that the point grid (built by the first point
    // query) is counted.
    let stats = accel.stats();
    println!(
        "{}",
        json!({
            "mesh": name,
            "set": in_set.then(|| &stem[name.len() + 1..]),
            "threads": rayon::current_num_threads(),
            "triangles": stats.triangles,
            "load_s": load_s,
            "accel_s": accel_s,
            "accel_bytes": stats.memory_bytes,
            "grid_s": stats.grid_build_time.as_secs_f64(),
            "points": points.len(),
            "points_s": points_s,
            "inside": count(Containment::Inside),
            "boundary": count(Containment::OnBoundary),
            "rays": rays.len(),
            "rays_s": rays_s,
            "hits": hits.iter().filter(|h| h.is_some()).count(),
        })
    );
    Ok(())
}

fn validate(path: &Path, repeats: usize) -> Result<()> {
    let mut best: Option<(f64, f64)> = None;
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let t0 = Instant::now();
        let import = import_obj(path, &ObjOptions::default())?;
        let import_s = t0.elapsed().as_secs_f64();
        let (report, solid) = validate_and_build(&import, &Options::default())
            .map_err(|e| format!("{}: {e}", path.display()))?;
        let total_s = t0.elapsed().as_secs_f64();
        if best.is_none_or(|(_, b)| total_s < b) {
            best = Some((import_s, total_s));
        }
        last = Some((report, solid.is_some()));
    }
    let (Some((import_s, total_s)), Some((report, built))) = (best, last) else {
        return Ok(());
    };
    println!(
        "{}",
        json!({
            "file": path.display().to_string(),
            "seconds": total_s,
            "import_s": import_s,
            "rss_mib": peak_rss_mib(),
            "valid": report.is_valid(),
            "validity": report.validity,
            "verdict": report.validity.describe(),
            "vertices": report.vertices,
            "edges": report.edges,
            "faces": report.faces,
            "genus": report.genus,
            "volume": report.volume,
            "violations": report.violations.len(),
            "solid_built": built,
        })
    );
    Ok(())
}

fn run(args: &[String]) -> Result<()> {
    match args {
        [mode, dir, names @ ..] if mode == "queries" && !names.is_empty() => {
            let dir = PathBuf::from(dir);
            names.iter().try_for_each(|name| queries(&dir, name))
        }
        [mode, file] if mode == "validate" => validate(Path::new(file), 1),
        [mode, file, repeats] if mode == "validate" => {
            let repeats = repeats
                .parse()
                .map_err(|e| format!("REPEATS {repeats:?}: {e}"))?;
            validate(Path::new(file), repeats)
        }
        _ => Err(USAGE.into()),
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let Err(e) = run(&args) {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}
