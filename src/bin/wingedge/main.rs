//! The `wingedge` command line.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand};

mod info;
mod validate;

/// wingedge: a B-rep polyhedron kernel on the winged-edge structure.
#[derive(Debug, Parser)]
#[command(version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Print counts and measures of a solid read from an OBJ file or built in.
    Info {
        /// The OBJ file to read.
        #[arg(required_unless_present = "builtin", conflicts_with = "builtin")]
        file: Option<PathBuf>,
        /// A built-in solid: tetrahedron, cube, octahedron, dodecahedron,
        /// icosahedron or prism.
        #[arg(long)]
        builtin: Option<String>,
        /// Also write the solid as OBJ to this path.
        #[arg(long, value_name = "OUT.obj")]
        write: Option<PathBuf>,
    },
    /// Validate OBJ files: a graded verdict per file and every defect with
    /// its OBJ line. Exit code 0 when every file is a valid closed solid, 1
    /// when any has defects, 2 when any cannot be read.
    Validate {
        /// The OBJ files.
        #[arg(required = true)]
        files: Vec<PathBuf>,
        /// Print one JSON array (one object per file) instead of text.
        #[arg(long)]
        json: bool,
        /// Weld vertices closer than TOL × the bounding-box diagonal (only
        /// where that closes open edges). Default: bit-identical positions.
        #[arg(long, value_name = "TOL", conflicts_with = "no_weld")]
        weld: Option<f64>,
        /// Merge no vertices at all.
        #[arg(long)]
        no_weld: bool,
        /// Planarity tolerance as a fraction of the bounding-box diagonal
        /// (default 1e-6).
        #[arg(long, value_name = "TOL")]
        planarity: Option<f64>,
        /// How many instances of each broken rule to print (text output).
        #[arg(long, default_value_t = 3)]
        show: usize,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Info {
            file,
            builtin,
            write,
        } => info::run(file, builtin, write),
        Command::Validate {
            files,
            json,
            weld,
            no_weld,
            planarity,
            show,
        } => validate::run(validate::Args {
            files,
            json,
            weld,
            no_weld,
            planarity,
            show,
        }),
    }
}
