//! Accuracy against time for octree cells and marching cubes, against
//! exact volumes.
//!
//! ```text
//! cargo run --release -p wingedge-bench --bin cells_fields_accuracy
//! cargo run --release -p wingedge-bench --bin cells_fields_accuracy -- --mesh MODEL.obj --mesh-volume V --csv OUT.csv
//! ```
//!
//! - **Cells** (`Octree::classify_csg`, `Octree::classify`): per depth, the
//!   certified interval `[V_in, V_in + V_on]`, its width `V_on` relative to
//!   the exact volume, whether it holds the exact volume, the time and the
//!   peak memory. Targets: the drilled cube scene (`8 − 3π/2 + √2`), a
//!   sphere scene (`4π/3`), and a closed mesh with a reference volume given
//!   on the command line (default: the genus-1 torus fixture, volume 8;
//!   `benches/peers/cells_fields_plot.py` passes manifold3d's volume of a
//!   real model).
//! - **Marching cubes** (`field::try_mesh`): per resolution, the volume's
//!   relative error against the exact volume of a sphere field (one
//!   soft-object source of radius 2: `F = ½` on the unit sphere, volume
//!   `4π/3`), the time and the peak memory.
//!
//! Each row runs in a child process (this program with `--row ...`), so its
//! peak resident memory (`VmHWM`, Linux) is its own; times are the best of
//! three runs in that process. `RAYON_NUM_THREADS` sets the threads
//! (marching cubes and a solid's octree use them; a scene's octree is built
//! on one). The marching-cubes peak memory includes building the solid
//! whose volume is measured.

use std::f64::consts::PI;
use std::fmt::Write as _;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

use wingedge::cells::Octree;
use wingedge::csg::Stats;
use wingedge::field::{Blobs, Falloff, MarchingOptions, Source, try_mesh};
use wingedge::glam::DVec3;
use wingedge::io::read_obj;
use wingedge::mesh::{PolygonSoup, Solid};
use wingedge::scene::Scene;

#[path = "../peers_io.rs"]
#[allow(dead_code)]
mod peers_io;

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

const SPHERE_SCENE: &str = r#"{"root": {"sphere": {"center": [0.1, 0.2, 0.3], "radius": 1}}}"#;

/// The best time of three runs of `f`, and its last result.
fn best_of_3<T>(mut f: impl FnMut() -> Result<T>) -> Result<(f64, T)> {
    let mut best = f64::INFINITY;
    let mut out = None;
    for _ in 0..3 {
        drop(out.take());
        let t = Instant::now();
        let r = f()?;
        best = best.min(t.elapsed().as_secs_f64());
        out = Some(r);
    }
    Ok((best, out.ok_or("no run")?))
}

/// One row, in this process: prints `seconds low high leaves_or_triangles
/// peak_mib` (for marching cubes `low = high =` the mesh's volume).
fn row(args: &[String]) -> Result<()> {
    let kind = args.first().ok_or("--row KIND ...")?;
    let target = args.get(1).ok_or("--row KIND TARGET N")?;
    let n: u32 = args.get(2).ok_or("--row KIND TARGET N")?.parse()?;
    let (seconds, low, high, count) = match kind.as_str() {
        "scene" => {
            let scene = if target == "sphere" {
                Scene::from_json(SPHERE_SCENE, "sphere", Path::new("."))?
            } else {
                Scene::from_file(Path::new(target))?
            };
            let (t, tree) =
                best_of_3(|| Ok(Octree::classify_csg(&scene.csg, n, &mut Stats::default())?))?;
            let (low, high) = tree.try_volume_bounds().unwrap();
            (t, low, high, tree.leaves().len())
        }
        "mesh" => {
            let soup: PolygonSoup = read_obj(Path::new(target))?;
            let solid = Solid::try_from_soup(&soup)?;
            let (t, tree) = best_of_3(|| Ok(Octree::classify(&solid, n)?))?;
            let (low, high) = tree.try_volume_bounds().unwrap();
            (t, low, high, tree.leaves().len())
        }
        "field" => {
            let field = Blobs::try_new(
                vec![Source::try_unit(DVec3::new(0.1, 0.2, 0.3), 2.0)?],
                Falloff::SoftObject,
            )?;
            let options = MarchingOptions {
                resolution: n as usize,
                ..MarchingOptions::default()
            };
            let (t, meshed) = best_of_3(|| Ok(try_mesh(&field, &options)?))?;
            let solid = Solid::try_from_soup(&meshed.soup)?;
            let v = solid.volume();
            (t, v, v, meshed.soup.polygons.len())
        }
        other => return Err(format!("unknown row kind {other}").into()),
    };
    let peak = peers_io::peak_rss_mib().unwrap_or(f64::NAN);
    println!("{seconds} {low} {high} {count} {peak}");
    Ok(())
}

/// Runs one row in a child process.
fn child(kind: &str, target: &str, n: u32) -> Result<[f64; 5]> {
    let out = Command::new(std::env::current_exe()?)
        .args(["--row", kind, target, &n.to_string()])
        .output()?;
    if !out.status.success() {
        return Err(format!(
            "{kind} {target} {n}: {}",
            String::from_utf8_lossy(&out.stderr)
        )
        .into());
    }
    let text = String::from_utf8(out.stdout)?;
    let values: Vec<f64> = text
        .split_whitespace()
        .map(str::parse)
        .collect::<std::result::Result<_, _>>()?;
    values
        .try_into()
        .map_err(|v: Vec<f64>| format!("{kind} {target} {n}: {v:?}").into())
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("--row") {
        return row(&args[1..]);
    }
    let value_of = |flag: &str| {
        args.iter()
            .position(|a| a == flag)
            .and_then(|i| args.get(i + 1))
            .cloned()
    };
    let mesh = value_of("--mesh").unwrap_or_else(|| "fixtures/valid/torus_genus1.obj".into());
    let mesh_volume: f64 = match value_of("--mesh-volume") {
        Some(v) => v.parse()?,
        None if mesh == "fixtures/valid/torus_genus1.obj" => 8.0,
        None => return Err("--mesh needs --mesh-volume (the reference volume)".into()),
    };
    let mesh_name = Path::new(&mesh)
        .file_stem()
        .map_or(mesh.clone(), |s| s.to_string_lossy().into_owned());
    let mut csv =
        String::from("kind,target,n,seconds,peak_mib,low,high,exact,relative,holds,count\n");
    let threads = rayon::current_num_threads();
    println!(
        "cells: certified interval against the exact volume ({threads} threads available: a solid's octree uses them, a scene's is built on one)\n"
    );
    println!(
        "| target (exact volume) | depth | interval | width / volume | holds | leaves | time (s) | peak memory (MiB) |"
    );
    println!("|---|---:|---|---:|---|---:|---:|---:|");
    let targets: [(&str, &str, String, f64, std::ops::RangeInclusive<u32>); 3] = [
        (
            "scene",
            "fixtures/scenes/drilled_cube.json",
            "drilled cube (8 − 3π/2 + √2)".to_string(),
            8.0 - 1.5 * PI + 2f64.sqrt(),
            3..=9,
        ),
        (
            "scene",
            "sphere",
            "sphere scene (4π/3)".to_string(),
            4.0 / 3.0 * PI,
            3..=9,
        ),
        (
            "mesh",
            &mesh,
            format!("{mesh_name} ({mesh_volume})"),
            mesh_volume,
            3..=9,
        ),
    ];
    for (kind, target, name, exact, depths) in &targets {
        for depth in depths.clone() {
            let [seconds, low, high, leaves, peak] = child(kind, target, depth)?;
            let holds = low <= *exact && *exact <= high;
            let width = (high - low) / exact;
            println!(
                "| {name} | {depth} | [{low:.6}, {high:.6}] | {width:.3e} | {} | {leaves} | {seconds:.4} | {peak:.0} |",
                if holds { "yes" } else { "NO" }
            );
            let label = if *kind == "mesh" {
                mesh_name.as_str()
            } else {
                target
            };
            writeln!(
                csv,
                "cells,{label},{depth},{seconds},{peak},{low},{high},{exact},{width},{holds},{leaves}"
            )?;
        }
    }
    let exact = 4.0 / 3.0 * PI;
    println!(
        "\nmarching cubes: a sphere field (one source of radius 2, F = ½ on the unit sphere, exact volume 4π/3), {threads} threads\n"
    );
    println!("| resolution | triangles | volume | relative error | time (s) | peak memory (MiB) |");
    println!("|---:|---:|---:|---:|---:|---:|");
    for resolution in [8u32, 16, 32, 64, 128, 256] {
        let [seconds, volume, _, triangles, peak] = child("field", "sphere", resolution)?;
        let error = (volume - exact).abs() / exact;
        println!(
            "| {resolution} | {triangles} | {volume:.6} | {error:.2e} | {seconds:.4} | {peak:.0} |"
        );
        writeln!(
            csv,
            "marching,sphere field,{resolution},{seconds},{peak},{volume},{volume},{exact},{error},,{triangles}"
        )?;
    }
    if let Some(path) = value_of("--csv") {
        std::fs::write(&path, csv)?;
        println!("\nwrote {path}");
    }
    Ok(())
}
