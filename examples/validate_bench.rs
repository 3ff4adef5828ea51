//! The validation benchmark: import, build and fully validate one large OBJ
//! file, stage by stage, and print a table (peak memory included).
//!
//! ```text
//! cargo run --release --example validate_bench -- MESH.obj [REPEATS]
//! ```
//!
//! Compare with `benches/peers_validate.py` (trimesh load + manifold3d
//! construction of the same file), which runs this example too so that both
//! are measured in one run.

use std::path::PathBuf;
use std::time::Instant;

use wingedge::io::{ObjOptions, import_obj};
use wingedge::mesh::Solid;
use wingedge::validate::{Options, validate_import};

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
    let mut best = [f64::INFINITY; 5];
    let mut summary = String::new();
    let mut stages = String::new();
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
        let no_si = Options {
            self_intersection: false,
            ..Options::default()
        };
        let _ = validate_import(&import, &no_si).expect("validates");
        let t2 = Instant::now();
        let report = validate_import(&import, &Options::default()).expect("validates");
        stages = import
            .stage_seconds
            .iter()
            .chain(&report.stage_seconds)
            .map(|(n, t)| format!("{n}: {t:.3}"))
            .collect::<Vec<_>>()
            .join("; ");
        let t3 = Instant::now();
        let solid = Solid::try_from_soup(&import.soup);
        let t4 = Instant::now();
        let times = [
            (t1 - t0).as_secs_f64(),
            (t2 - t1).as_secs_f64(),
            (t3 - t2).as_secs_f64(),
            (t4 - t3).as_secs_f64(),
            ((t1 - t0) + (t3 - t2)).as_secs_f64(),
        ];
        for (b, t) in best.iter_mut().zip(times) {
            *b = b.min(t);
        }
        summary = format!(
            "faces {}  verdict {:?}  violations {}  solid built {}",
            report.faces,
            report.validity,
            report.violations.len(),
            solid.is_ok()
        );
    }
    println!("{}: {summary}", path.display());
    println!("last run's stages: {stages}");
    println!("| stage | best of {repeats} (s) |");
    println!("|---|---:|");
    for (name, t) in [
        "import (tobj + line pass + weld)",
        "validate without self-intersection (incl. solid build)",
        "validate, full",
        "Solid::try_from_soup alone",
        "import + full validate",
    ]
    .iter()
    .zip(best)
    {
        println!("| {name} | {t:.3} |");
    }
    println!("peak RSS {:.0} MiB", peak_rss_mib().unwrap_or(f64::NAN));
}
