//! Times first-hit ray casting on one thread (a profiling aid for the
//! walks in `query/ray_stream.rs`):
//!
//! ```sh
//! cargo run --release -p wingedge-bench --bin ray_probe -- DIR NAME [REPS]
//! ```
//!
//! reads `DIR/NAME.obj` and `DIR/NAME.rays.f64` (the peer harness's inputs,
//! `benches/peers/`), builds the accel, casts the rays as one batch `REPS`
//! times (default 5) and prints the best time per ray, with the nodes and
//! triangles a ray visits. With `REPS` 1 it suits instruction counting
//! (`valgrind --tool=callgrind`); with `REPS` 0 it times the accel build.
//! Compare two builds by alternating their runs: this machine's speed
//! drifts within minutes, so only runs close in time compare.

// Shared with the peer drivers; this one reads inputs only.
#[allow(dead_code)]
#[path = "../peers_io.rs"]
mod peers_io;

use std::time::Instant;

use glam::DVec3;
use peers_io::{Result, read_f64s};
use wingedge::geom::Ray;
use wingedge::io::read_obj;
use wingedge::mesh::Solid;
use wingedge::query::Accel;

fn run() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [dir, name, rest @ ..] = args.as_slice() else {
        return Err("usage: ray_probe DIR NAME [REPS]".into());
    };
    let reps: usize = match rest.first() {
        Some(r) => r.parse().map_err(|e| format!("REPS {r}: {e}"))?,
        None => 5,
    };
    let dir = std::path::Path::new(dir);
    let obj = dir.join(format!("{name}.obj"));
    let soup = read_obj(&obj)?;
    let solid = Solid::try_from_soup(&soup).map_err(|e| format!("{}: {e}", obj.display()))?;
    let pool = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let accel = pool.install(|| Accel::new(&solid));
    if reps == 0 {
        let mut best = f64::INFINITY;
        for _ in 0..5 {
            let t = Instant::now();
            std::hint::black_box(pool.install(|| Accel::new(&solid)));
            best = best.min(t.elapsed().as_secs_f64());
        }
        let stats = accel.stats();
        println!(
            "{name}: accel build best {:.1} ms on one thread ({} triangles, {} nodes, {:.1} MB)",
            best * 1e3,
            stats.triangles,
            stats.bvh_nodes,
            stats.memory_bytes as f64 / 1e6
        );
        return Ok(());
    }
    let rays: Vec<Ray> = read_f64s(&dir.join(format!("{name}.rays.f64")), 6)?
        .chunks_exact(6)
        .map(|c| Ray::new(DVec3::new(c[0], c[1], c[2]), DVec3::new(c[3], c[4], c[5])))
        .collect();
    let (mut best, mut hits) = (f64::INFINITY, 0);
    for _ in 0..reps {
        let t = Instant::now();
        let answers = pool.install(|| accel.first_hit_batch(&rays))?;
        best = best.min(t.elapsed().as_secs_f64());
        hits = answers.iter().filter(|h| h.is_some()).count();
    }
    let (mut nodes, mut triangles, mut exact) = (0, 0, 0);
    let sample = &rays[..rays.len().min(10_000)];
    for ray in sample {
        let (_, s) = accel.first_hit_traced(ray)?;
        (nodes, triangles, exact) = (
            nodes + s.nodes,
            triangles + s.triangles,
            exact + s.exact_tests,
        );
    }
    let per = |n: u64| n as f64 / sample.len().max(1) as f64;
    println!(
        "{name}: batch best {:.1} ns/ray on one thread ({hits} hits of {}); \
         per ray {:.1} nodes, {:.1} triangles, {:.1} exact tests",
        best * 1e9 / rays.len().max(1) as f64,
        rays.len(),
        per(nodes),
        per(triangles),
        per(exact)
    );
    Ok(())
}

fn main() {
    if let Err(e) = run() {
        eprintln!("ray_probe: {e}");
        std::process::exit(2);
    }
}
