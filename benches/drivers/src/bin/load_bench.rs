//! Loading one mesh file, as the format speed table of docs/formats.md
//! measures it (`benches/peers/formats.py` runs it as a whole process).
//!
//! ```text
//! cargo run --release -p wingedge-bench --bin load_bench -- load FILE
//! cargo run --release -p wingedge-bench --bin load_bench -- solid FILE
//! ```
//!
//! **load**: [`io::import`] with the default options, what every command
//! that reads a mesh does first: the file read whole, parsed (every face
//! located), checked (finite coordinates, indices in range) and welded
//! (bit-identical positions merged where that closes open edges); prints
//! the soup's vertex and face counts and the corners welded.
//!
//! **solid**: the same, then [`Solid::try_from_soup`], the winged-edge
//! solid with all its adjacency; prints its vertex, edge and face counts.
//!
//! With `WINGEDGE_STAGES=1` the wall seconds of each stage go to stderr.

use std::path::PathBuf;
use std::process::ExitCode;
use std::time::Instant;

use wingedge::io::{self, ImportOptions};
use wingedge::mesh::Solid;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [mode, file] = args.as_slice() else {
        eprintln!("usage: load_bench load|solid FILE");
        return ExitCode::from(2);
    };
    let path = PathBuf::from(file);
    let stages = std::env::var_os("WINGEDGE_STAGES").is_some();
    let start = Instant::now();
    let import = match io::import(&path, &ImportOptions::default()) {
        Ok(import) => import,
        Err(e) => {
            eprintln!("{e}");
            return ExitCode::from(2);
        }
    };
    if stages {
        for (stage, seconds) in &import.stage_seconds {
            eprintln!("{stage:>8} {seconds:.3} s");
        }
    }
    let soup = &import.soup;
    match mode.as_str() {
        "load" => println!(
            "vertices {}  faces {}  welded {}",
            soup.positions.len(),
            soup.polygons.len(),
            import.weld.merged
        ),
        "solid" => {
            let built = Instant::now();
            let solid = match Solid::try_from_soup(soup) {
                Ok(solid) => solid,
                Err(e) => {
                    eprintln!("{}: {e}", path.display());
                    return ExitCode::from(1);
                }
            };
            if stages {
                eprintln!("{:>8} {:.3} s", "solid", built.elapsed().as_secs_f64());
            }
            println!(
                "vertices {}  edges {}  faces {}",
                solid.vertex_count(),
                solid.edge_count(),
                solid.face_count()
            );
        }
        other => {
            eprintln!("unknown mode `{other}`: load or solid");
            return ExitCode::from(2);
        }
    }
    if stages {
        eprintln!("{:>8} {:.3} s", "total", start.elapsed().as_secs_f64());
    }
    ExitCode::SUCCESS
}
