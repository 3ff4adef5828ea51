//! How the evaluation of a CSG tree scales with its leaves, by its
//! structure (`csg::evaluate`'s default) and in one pass over all leaves
//! (`EvaluateOptions { by_structure: false }`, `wingedge csg --one-pass`),
//! on three families:
//!
//! - `turned`: `n` cubes of side 2 about the origin, the `i`-th turned by
//!   `i · 90°/n` about `z`, unioned: they share their top and bottom
//!   planes, and the result is one prism of `4n` sides;
//! - `sponge`: the Menger sponge of depth `d` on a cube of side `3^d`
//!   (integer coordinates), the cube minus the union of its tunnels;
//! - `spheres`: `n` disjoint spheres of radius 1 on a grid, unioned.
//!
//! ```text
//! cargo build --release -p wingedge-bench --bin tree_scaling
//! target/release/tree_scaling [--limit SECONDS] [--family turned|sponge|spheres]
//! ```
//!
//! Each row is one evaluation in this process (wall time; booleans on all
//! cores), with the result's faces and whether both ways give the same
//! volume and genus. The slope is that of log time against log size
//! between a row and the one before (size: `n`, or the sponge's result
//! faces). After a run longer than `--limit` seconds (default 60) a way
//! skips the larger sizes of its family ("—").

use std::time::Instant;

use glam::{DAffine3, DVec3};
use wingedge::csg::{AxisBox, Csg, CsgExpr, EvaluateOptions, Evaluated, Sphere, evaluate};

type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

/// `n` turned cubes sharing their top and bottom planes.
fn turned(n: usize) -> Result<CsgExpr> {
    let cube = AxisBox::try_new(DVec3::splat(-1.0), DVec3::splat(1.0))?;
    let leaves = (0..n)
        .map(|i| {
            let angle = (i as f64) * std::f64::consts::FRAC_PI_2 / n as f64;
            CsgExpr::leaf(cube).transformed(DAffine3::from_rotation_z(angle))
        })
        .collect();
    Ok(CsgExpr::Union(leaves))
}

/// The Menger sponge of depth `depth` on a cube of side `3^depth`.
fn sponge(depth: u32) -> Result<CsgExpr> {
    let side = 3f64.powi(depth as i32);
    let mut tunnels = Vec::new();
    for level in 1..=depth {
        let n = 3i64.pow(level);
        let s = side / n as f64;
        for a in (1..n).step_by(3) {
            for b in (1..n).step_by(3) {
                let (lo_a, hi_a) = (a as f64 * s, (a + 1) as f64 * s);
                let (lo_b, hi_b) = (b as f64 * s, (b + 1) as f64 * s);
                for axis in 0..3 {
                    let mut min = [lo_a, lo_b, -1.0];
                    let mut max = [hi_a, hi_b, side + 1.0];
                    min.rotate_right(axis);
                    max.rotate_right(axis);
                    tunnels.push(CsgExpr::leaf(AxisBox::try_new(
                        DVec3::from(min),
                        DVec3::from(max),
                    )?));
                }
            }
        }
    }
    let cube = AxisBox::try_new(DVec3::ZERO, DVec3::splat(side))?;
    Ok(CsgExpr::leaf(cube).difference(CsgExpr::Union(tunnels)))
}

/// `n` disjoint unit spheres on a grid of spacing 3.
fn spheres(n: usize) -> Result<CsgExpr> {
    let side = (1..).find(|s: &usize| s * s * s >= n).unwrap_or(1);
    let leaves = (0..n)
        .map(|i| {
            let at = DVec3::new(
                (i % side) as f64,
                (i / side % side) as f64,
                (i / (side * side)) as f64,
            ) * 3.0;
            Ok(CsgExpr::leaf(Sphere::try_new(at, 1.0)?))
        })
        .collect::<Result<Vec<_>>>()?;
    Ok(CsgExpr::Union(leaves))
}

/// One evaluation: seconds and the result.
fn run(expr: CsgExpr, by_structure: bool) -> Result<(f64, Evaluated)> {
    let csg = Csg::try_new(expr)?;
    let options = EvaluateOptions {
        by_structure,
        ..EvaluateOptions::default()
    };
    let clock = Instant::now();
    let evaluated = evaluate(&csg, &options)?;
    Ok((clock.elapsed().as_secs_f64(), evaluated))
}

fn main() -> Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let limit: f64 = args
        .iter()
        .position(|a| a == "--limit")
        .and_then(|i| args.get(i + 1))
        .map_or(Ok(60.0), |s| s.parse())?;
    let only = args
        .iter()
        .position(|a| a == "--family")
        .and_then(|i| args.get(i + 1))
        .cloned();
    println!(
        "| family | n | leaves | result faces | one pass, ms | slope | by structure, ms | slope | speed-up | booleans (exact) | same volume and genus |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---|");
    type Maker = fn(usize) -> Result<CsgExpr>;
    let families: [(&str, Vec<usize>, Maker, usize); 3] = [
        ("turned", vec![4, 8, 16, 32, 64, 128, 256], turned, 1),
        ("sponge", vec![1, 2, 3, 4], |d| sponge(d as u32), 0),
        ("spheres", vec![8, 27, 64, 216, 512, 1000], spheres, 1),
    ];
    for (family, sizes, make, leaves_per) in families {
        if only.as_deref().is_some_and(|o| o != family) {
            continue;
        }
        let mut stopped = [false; 2];
        let mut last: [Option<(f64, f64)>; 2] = [None; 2];
        for n in sizes {
            let leaves = if leaves_per == 0 {
                (1..=n as u32).map(|l| 3 * 9usize.pow(l - 1)).sum::<usize>() + 1
            } else {
                n * leaves_per
            };
            let mut cells = Vec::new();
            let mut results: Vec<Option<Evaluated>> = Vec::new();
            let mut times = [None; 2];
            for (k, by_structure) in [false, true].into_iter().enumerate() {
                if stopped[k] {
                    results.push(None);
                    continue;
                }
                let (seconds, evaluated) = run(make(n)?, by_structure)?;
                stopped[k] = seconds > limit;
                times[k] = Some(seconds);
                results.push(Some(evaluated));
            }
            let faces = results
                .iter()
                .flatten()
                .map(|e| e.solid.face_count())
                .next()
                .unwrap_or(0);
            let size = if leaves_per == 0 {
                faces as f64
            } else {
                n as f64
            };
            for k in 0..2 {
                match times[k] {
                    Some(t) => {
                        cells.push(format!("{:.0}", t * 1e3));
                        cells.push(match last[k] {
                            Some((s0, t0)) if size > s0 => {
                                format!("{:.2}", (t / t0).ln() / (size / s0).ln())
                            }
                            _ => "—".to_string(),
                        });
                        last[k] = Some((size, t));
                    }
                    None => {
                        cells.push("—".to_string());
                        cells.push("—".to_string());
                    }
                }
            }
            let speedup = match times {
                [Some(a), Some(b)] => format!("{:.1}×", a / b),
                _ => "—".to_string(),
            };
            let structured = results[1].as_ref();
            let booleans = structured.map_or("—".to_string(), |e| {
                format!("{} ({})", e.structure.booleans, e.structure.exact)
            });
            let same = match (&results[0], &results[1]) {
                (Some(a), Some(b)) => {
                    let same = a.solid.volume() == b.solid.volume()
                        && a.report.genus == b.report.genus
                        && a.report.is_valid()
                        && b.report.is_valid();
                    if same {
                        "yes".to_string()
                    } else {
                        format!(
                            "no: {} / {}, genus {:?} / {:?}",
                            a.solid.volume(),
                            b.solid.volume(),
                            a.report.genus,
                            b.report.genus
                        )
                    }
                }
                _ => "—".to_string(),
            };
            println!(
                "| {family} | {n} | {leaves} | {faces} | {} | {} | {} | {} | {speedup} | {booleans} | {same} |",
                cells[0], cells[1], cells[2], cells[3]
            );
        }
    }
    Ok(())
}
