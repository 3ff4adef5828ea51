//! Marching cubes on the three-blob field (`fixtures/fields/three_blobs.json`),
//! printed as a table: per resolution, the triangles, the time to sample
//! the field and to march the grid, the volume's error against a fine
//! reference, and whether the solid validates.
//!
//! The reference volume is the Richardson extrapolation of the resolutions
//! 160 and 320 (the march's volume error is second order in the cell size:
//! `V_ref = V₃₂₀ + (V₃₂₀ − V₁₆₀) / 3`).
//!
//! `cargo run --release -p wingedge-bench --bin marching_cubes_bench` (about a minute on
//! two cores; `RAYON_NUM_THREADS=1` for one).
//!
//! With `--goal [RESOLUTION] [--whole]` it prints one JSON line instead,
//! for `benches/peers/marching_cubes_peer.py`: the best of three
//! `try_mesh` runs at the resolution (default 256) — sampling and marching
//! by blocks, the way the library meshes — its counters, whether the solid
//! validates, and the peak resident memory of this process; `--whole`
//! times the whole-grid sampler and march instead.

use std::path::Path;
use std::time::Instant;

use wingedge::field::marching::{march_grid, solid_of};
use wingedge::field::{Field, MarchingOptions, SampleGrid, load_json, try_mesh};
use wingedge::validate::{Options, validate_soup};

#[path = "../peers_io.rs"]
#[allow(dead_code)]
mod peers_io;

fn volume_at(field: &dyn Field, resolution: usize) -> f64 {
    let (grid, _) = SampleGrid::try_sample(field, resolution).expect("a grid");
    let (soup, _) = march_grid(&grid, &MarchingOptions::default());
    solid_of(&soup).expect("a solid").volume()
}

/// One JSON line: the best of three meshings at `resolution`, by blocks
/// (the library's way) or over the whole grid.
fn goal(field: &dyn Field, resolution: usize, whole: bool) {
    let options = MarchingOptions {
        resolution,
        ..MarchingOptions::default()
    };
    let mut best = f64::INFINITY;
    let mut last = None;
    for _ in 0..3 {
        drop(last.take());
        let t = Instant::now();
        let soup = if whole {
            let (grid, _) = SampleGrid::try_sample(field, resolution).expect("a grid");
            march_grid(&grid, &options).0
        } else {
            try_mesh(field, &options).expect("a mesh").soup
        };
        best = best.min(t.elapsed().as_secs_f64());
        last = Some(soup);
    }
    let peak = peers_io::peak_rss_mib().unwrap_or(f64::NAN);
    let soup = last.expect("a run");
    let meshed = try_mesh(field, &options).expect("a mesh");
    let report = validate_soup(&soup, None, &Options::default()).expect("a report");
    let volume = solid_of(&soup).expect("a solid").volume();
    let [nx, ny, nz] = meshed.dims;
    println!(
        r#"{{"method": "{}", "resolution": {resolution}, "grid": [{nx}, {ny}, {nz}], "threads": {}, "seconds": {best:.4}, "triangles": {}, "volume": {volume}, "samples": {}, "whole_grid_samples": {}, "blocks": {}, "blocks_marched": {}, "valid": {}, "peak_rss_mib": {peak:.1}}}"#,
        if whole { "whole grid" } else { "blocks" },
        rayon::current_num_threads(),
        soup.polygons.len(),
        if whole {
            nx * ny * nz
        } else {
            meshed.field.samples as usize
        },
        nx * ny * nz,
        meshed.march.blocks,
        meshed.march.blocks_marched,
        report.validity == wingedge::validate::Validity::ValidSolid,
    );
}

fn main() {
    let doc = load_json(Path::new("fixtures/fields/three_blobs.json")).expect("the fixture");
    let field = doc.field.as_ref();
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--goal") {
        let resolution = args.get(1).and_then(|r| r.parse().ok()).unwrap_or(256);
        goal(field, resolution, args.iter().any(|a| a == "--whole"));
        return;
    }
    let coarse = volume_at(field, 160);
    let fine = volume_at(field, 320);
    let reference = fine + (fine - coarse) / 3.0;
    println!(
        "three-blob field, {} sources; {} threads; reference volume {reference:.6} (Richardson of 160 and 320: {coarse:.6}, {fine:.6})\n",
        doc.sources,
        rayon::current_num_threads()
    );
    println!(
        "| resolution | grid | triangles | sample (s) | march (s) | volume | relative error | validate (s) | valid |"
    );
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---|");
    for resolution in [32, 64, 128, 256] {
        let t = Instant::now();
        let (grid, stats) = SampleGrid::try_sample(field, resolution).expect("a grid");
        let sample = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let (soup, march) = march_grid(&grid, &MarchingOptions::default());
        let marching = t.elapsed().as_secs_f64();
        let solid = solid_of(&soup).expect("a solid");
        let t = Instant::now();
        let report = validate_soup(&soup, None, &Options::default()).expect("a report");
        let validating = t.elapsed().as_secs_f64();
        let volume = solid.volume();
        let [nx, ny, nz] = grid.dims();
        println!(
            "| {resolution} | {nx}×{ny}×{nz} | {} | {sample:.3} | {marching:.3} | {volume:.6} | {:.2e} | {validating:.2} | {} |",
            march.triangles,
            (volume - reference).abs() / reference,
            report.validity.describe(),
        );
        if resolution == 256 {
            println!(
                "\nat 256: {} samples, {:.2} source evaluations per sample of {} sources",
                stats.samples,
                stats.source_evaluations as f64 / stats.samples as f64,
                doc.sources
            );
        }
    }
}
