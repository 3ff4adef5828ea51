//! Prints a throughput table for point classification and first-hit ray
//! casting on the shared peer meshes, and writes wingedge's answers next to
//! the peers' so that `examples/peers_query.py` can compare them.
//!
//! ```text
//! python3 ../shared/peers/make_meshes.py          # in a writable copy
//! cargo run --release --example query_table -- /tmp/peers/meshes sphere_80k torus_knot sphere_1m
//! ```
//!
//! For each mesh: OBJ read + winged-edge build (reported, not part of the
//! accel), [`Accel::new`] (best of 3; triangles and BVH — the `yz` grid of
//! point queries is built by the first classification and its build time
//! reported with its size), then 1M points (`<name>.points.f64`)
//! classified by parity and 1M rays (`<name>.rays.f64`) cast for their first
//! hit, each best of 3 on 1 and on 2 threads. Answers are written to
//! `<name>.in.wingedge.u8` (1 inside, 0 outside, 2 boundary) and
//! `<name>.hit.wingedge.f64` (first-hit `t`, `inf` for a miss), and
//! `<name>.hitface.wingedge.u32` (per ray: `2 · face + exit`, where `face`
//! counts the solid's faces in iteration order and `exit` is 1 for a
//! [`Transition::Exit`]; `u32::MAX` for a miss) so that two builds' exact
//! decisions can be compared file to file.
//!
//! Profiling aids: `WINGEDGE_ONLY=points|rays|build` restricts the work
//! (`build`: ten accel builds, no table row); `WINGEDGE_CPU=1` prints wall
//! and process CPU time of each measurement to stderr;
//! `WINGEDGE_TRACE=1` prints the mean BVH nodes and triangles a first-hit
//! ray visits (over the first 100,000 rays) to stderr.

use std::path::{Path, PathBuf};
use std::time::Instant;

use glam::DVec3;
use wingedge::geom::Ray;
use wingedge::io::read_obj;
use wingedge::mesh::Solid;
use wingedge::query::{Accel, Containment, Method, Transition};

fn read_f64(path: &Path) -> Vec<f64> {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    bytes
        .chunks_exact(8)
        .map(|c| f64::from_le_bytes(c.try_into().unwrap_or([0; 8])))
        .collect()
}

/// CPU time of the whole process (all threads), seconds (for profiling
/// under load, when wall time mostly measures the other jobs).
fn process_cpu() -> f64 {
    let mut ts = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: clock_gettime writes into the timespec we own.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut ts) };
    ts.tv_sec as f64 + ts.tv_nsec as f64 * 1e-9
}

fn best_of<T>(runs: usize, mut f: impl FnMut() -> T) -> (f64, T) {
    let mut best = f64::INFINITY;
    let mut best_cpu = f64::INFINITY;
    let mut out = None;
    for _ in 0..runs.max(1) {
        let t = Instant::now();
        let c = process_cpu();
        let r = f();
        best = best.min(t.elapsed().as_secs_f64());
        best_cpu = best_cpu.min(process_cpu() - c);
        out = Some(r);
    }
    if std::env::var("WINGEDGE_CPU").is_ok() {
        eprintln!("    wall {best:.4} s, process cpu {best_cpu:.4} s");
    }
    (best, out.expect("at least one run"))
}

fn main() {
    let mut args = std::env::args().skip(1);
    let dir = PathBuf::from(args.next().unwrap_or_else(|| "/tmp/q/peers/meshes".into()));
    let mut names: Vec<String> = args.collect();
    if names.is_empty() {
        names = vec!["sphere_80k".into(), "torus_knot".into(), "sphere_1m".into()];
    }
    let pool1 = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("pool");
    let pool2 = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .expect("pool");
    println!(
        "| mesh | tris | OBJ read + solid build s | accel build s | accel MB | grid cells / entries (grid build s) | classify 1 thr M/s | classify 2 thr M/s | inside frac | boundary | first hit 1 thr M/s | first hit 2 thr M/s | hit frac |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for name in names {
        let obj = dir.join(format!("{name}.obj"));
        let t = Instant::now();
        let soup = read_obj(&obj).unwrap_or_else(|e| panic!("{e}"));
        let solid = Solid::try_from_soup(&soup).unwrap_or_else(|e| panic!("{e}"));
        let load = t.elapsed().as_secs_f64();
        let (build, accel) = best_of(3, || Accel::new(&solid));
        let p = read_f64(&dir.join(format!("{name}.points.f64")));
        let points: Vec<DVec3> = p
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect();
        let r = read_f64(&dir.join(format!("{name}.rays.f64")));
        let rays: Vec<Ray> = r
            .chunks_exact(6)
            .map(|c| Ray::new(DVec3::new(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5])))
            .collect();
        let classify = || {
            accel
                .classify_batch(&points, Method::Parity)
                .expect("closed mesh, finite points")
        };
        // WINGEDGE_ONLY=points|rays restricts the run (for profiling).
        let only = std::env::var("WINGEDGE_ONLY").unwrap_or_default();
        let runs = |what: &str| {
            if only.is_empty() || only == what {
                3
            } else {
                0
            }
        };
        if only == "build" {
            for _ in 0..10 {
                std::hint::black_box(Accel::new(&solid));
            }
            continue;
        }
        let (c1, _) = pool1.install(|| best_of(runs("points"), classify));
        let (c2, classes) = pool2.install(|| best_of(runs("points"), classify));
        if std::env::var("WINGEDGE_TRACE").is_ok() {
            let sample = &rays[..rays.len().min(100_000)];
            let (nodes, triangles) = sample.iter().fold((0u64, 0u64), |(n, t), r| {
                let (_, s) = accel.first_hit_traced(r).expect("valid rays");
                (n + s.nodes, t + s.triangles)
            });
            let k = sample.len().max(1) as f64;
            eprintln!(
                "    {name}: per first-hit ray {:.1} nodes, {:.1} triangles",
                nodes as f64 / k,
                triangles as f64 / k
            );
        }
        let cast = || accel.first_hit_batch(&rays).expect("valid rays");
        let (r1, _) = pool1.install(|| best_of(runs("rays"), cast));
        let (r2, hits) = pool2.install(|| best_of(runs("rays"), cast));
        let inside = classes
            .iter()
            .filter(|&&c| c == Containment::Inside)
            .count();
        let boundary = classes
            .iter()
            .filter(|&&c| c == Containment::OnBoundary)
            .count();
        let hit = hits.iter().filter(|h| h.is_some()).count();
        // After the point queries: with the grid they built.
        let stats = accel.stats();
        let n = points.len() as f64;
        let m = rays.len() as f64;
        println!(
            "| {name} | {} | {load:.3} | {build:.4} | {:.1} | {} / {} ({:.4}) | {:.2} | {:.2} | {:.6} | {boundary} | {:.2} | {:.2} | {:.4} |",
            stats.triangles,
            stats.memory_bytes as f64 / 1e6,
            stats.grid_cells,
            stats.grid_entries,
            stats.grid_build_time.as_secs_f64(),
            n / c1 / 1e6,
            n / c2 / 1e6,
            inside as f64 / n,
            m / r1 / 1e6,
            m / r2 / 1e6,
            hit as f64 / m,
        );
        let codes: Vec<u8> = classes
            .iter()
            .map(|c| match c {
                Containment::Outside => 0,
                Containment::Inside => 1,
                Containment::OnBoundary => 2,
            })
            .collect();
        let _ = std::fs::write(dir.join(format!("{name}.in.wingedge.u8")), codes);
        let ts: Vec<u8> = hits
            .iter()
            .flat_map(|h| h.map_or(f64::INFINITY, |c| c.t).to_le_bytes())
            .collect();
        let _ = std::fs::write(dir.join(format!("{name}.hit.wingedge.f64")), ts);
        let face_index: std::collections::HashMap<_, u32> = solid
            .faces()
            .enumerate()
            .map(|(k, (id, _))| (id, k as u32))
            .collect();
        let faces: Vec<u8> = hits
            .iter()
            .flat_map(|h| {
                h.map_or(u32::MAX, |c| {
                    2 * face_index[&c.face] + u32::from(c.transition == Transition::Exit)
                })
                .to_le_bytes()
            })
            .collect();
        let _ = std::fs::write(dir.join(format!("{name}.hitface.wingedge.u32")), faces);
    }
}
